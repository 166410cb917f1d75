// Lucerna: the RGB color spaces of pbrt-v4's ColorSpace directive, as indices shared by host and
// device code (an image texture, an image light or a grid medium records the space its RGB is in;
// SceneView holds one Jakob-Hanika table and one illuminant per space). Host data: spectra/color_spaces.h.
#pragma once

#include <cstdint>

namespace lu {

// pbrt-v4's RGBColorSpace::sRGB, DCI_P3, Rec2020, ACES2065_1 (util/colorspace.cpp).
enum class ColorSpaceId : uint8_t { SRGB = 0, DCI_P3 = 1, Rec2020 = 2, ACES2065_1 = 3 };
constexpr uint32_t NumColorSpaces = 4;

}  // namespace lu
