// Lucerna: RGB illuminant texels -> Spectrum through the scene's Jakob-Hanika table (host and
// device), as pbrt-v4's RGBIlluminantSpectrum(colorSpace, ClampZero(rgb)); a thin wrapper of
// spectrum/rgb_to_spectrum.h over the SceneView fields.
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/spectrum/rgb_to_spectrum.h"

namespace lu {

// rgb in color space cs (a ColorSpaceId; sRGB by default). Negative components are clamped to 0;
// black gives a zero-scale spectrum.
LU_INLINE Spectrum RGBIlluminantSpectrum(const SceneView &s, const Float rgb[3], uint32_t cs = 0) {
    return RGBIlluminantSpectrum(RGBToSpecCoeffs(s, cs), s.rgbToSpecZNodes.ptr, s.rgbToSpecRes, Max(rgb[0], Float(0)),
                                 Max(rgb[1], Float(0)), Max(rgb[2], Float(0)), IlluminantTable(s, cs));
}

}  // namespace lu
