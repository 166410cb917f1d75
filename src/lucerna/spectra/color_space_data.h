// Lucerna: the chromaticities and illuminants of pbrt-v4's four RGB color spaces
// (RGBColorSpace::Init in util/colorspace.cpp); header-only so that the build-time table
// generator (tools/rgb2spec_gen.cpp) uses the same numbers as the renderer (host only).
#pragma once

#include <cstring>

#include "lucerna/spectrum/color_space.h"

namespace lu::data {

struct ColorSpaceDefinition {
    const char *name;        // as written in ColorSpace "name" (lower case, as pbrt-v4's GetNamed)
    double r[2], g[2], b[2]; // xy chromaticities of the primaries
    const char *illuminant;  // named spectrum of the white (its XYZ sets the white point)
};

// Indexed by ColorSpaceId.
constexpr ColorSpaceDefinition ColorSpaces[NumColorSpaces] = {
    {"srgb", {0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, "stdillum-D65"},          // ITU-R BT.709
    {"dci-p3", {0.68, 0.32}, {0.265, 0.690}, {0.15, 0.06}, "stdillum-D65"},      // P3-D65 (display)
    {"rec2020", {0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}, "stdillum-D65"}, // ITU-R BT.2020
    {"aces2065-1", {0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.077}, "illum-acesD60"},  // ACES AP0
};

// The index of a color space name, or -1.
inline int ColorSpaceIndex(const char *name) {
    for (int i = 0; i < int(NumColorSpaces); ++i)
        if (std::strcmp(name, ColorSpaces[i].name) == 0) return i;
    return -1;
}

}  // namespace lu::data
