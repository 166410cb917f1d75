// Lucerna: RGB -> sigmoid-polynomial spectrum lookup (Jakob & Hanika 2019), shared by host and
// device. Follows pbrt-v4's RGBToSpectrumTable::operator() and RGBAlbedo/RGBUnbounded/
// RGBIlluminantSpectrum; the table comes from SRGBToSpectrumTable() or SceneView::rgbToSpec*.
#pragma once

#include "lucerna/spectrum/spectrum.h"

namespace lu {

// Sigmoid coefficients c (value = s(c0 l^2 + c1 l + c2), l in nm) for rgb in [0,1]^3, by
// trilinear interpolation of the table coeffs[maxc][z][y][x][3] (res >= 2, zNodes increasing).
LU_INLINE void RGBToSigmoidCoeffs(const Float *coeffs, const Float *zNodes, uint32_t resU, Float r, Float g,
                                  Float b, Float c[3]) {
    const Float rgb[3] = {r, g, b};
    c[0] = c[1] = 0;
    // Uniform rgb: an exactly constant spectrum (s^-1 of the value; +-inf at 1 and 0).
    if (r == g && g == b) {
        c[2] = (r - 0.5f) / std::sqrt(r * (1 - r));
        return;
    }
    const int res = int(resU);
    int maxc = (r > g) ? ((r > b) ? 0 : 2) : ((g > b) ? 1 : 2);
    Float z = rgb[maxc];
    Float x = rgb[(maxc + 1) % 3] * (res - 1) / z;
    Float y = rgb[(maxc + 2) % 3] * (res - 1) / z;
    int xi = Min(int(x), res - 2), yi = Min(int(y), res - 2);
    // zi: the last node with zNodes[zi] < z, clamped to [0, res - 2] (pbrt-v4's FindInterval).
    int first = 1, size = res - 2;
    while (size > 0) {
        int half = size >> 1, middle = first + half;
        bool pred = zNodes[middle] < z;
        first = pred ? middle + 1 : first;
        size = pred ? size - (half + 1) : half;
    }
    int zi = Clamp(first - 1, 0, res - 2);
    Float dx = x - xi, dy = y - yi, dz = (z - zNodes[zi]) / (zNodes[zi + 1] - zNodes[zi]);
    auto co = [&](int ddx, int ddy, int ddz, int i) {
        return coeffs[3 * (((size_t(maxc) * res + (zi + ddz)) * res + (yi + ddy)) * res + (xi + ddx)) + i];
    };
    for (int i = 0; i < 3; ++i)
        c[i] = Lerp(dz, Lerp(dy, Lerp(dx, co(0, 0, 0, i), co(1, 0, 0, i)), Lerp(dx, co(0, 1, 0, i), co(1, 1, 0, i))),
                    Lerp(dy, Lerp(dx, co(0, 0, 1, i), co(1, 0, 1, i)), Lerp(dx, co(0, 1, 1, i), co(1, 1, 1, i))));
}

// pbrt-v4 RGBAlbedoSpectrum: a reflectance in [0,1]; rgb is clamped to [0,1] first.
LU_INLINE Spectrum RGBAlbedoSpectrum(const Float *coeffs, const Float *zNodes, uint32_t res, Float r, Float g,
                                     Float b) {
    Spectrum s;
    s.kind = SpectrumKind::RGBAlbedo;
    s.scale = 1;
    RGBToSigmoidCoeffs(coeffs, zNodes, res, Clamp(r, Float(0), Float(1)), Clamp(g, Float(0), Float(1)),
                       Clamp(b, Float(0), Float(1)), s.c);
    return s;
}

// pbrt-v4 RGBUnboundedSpectrum: scale = 2 max(rgb), coefficients of rgb / scale (negative
// components clamped to 0, as RGBColorSpace::ToRGBCoeffs does).
LU_INLINE Spectrum RGBUnboundedSpectrum(const Float *coeffs, const Float *zNodes, uint32_t res, Float r, Float g,
                                        Float b) {
    Spectrum s;
    s.kind = SpectrumKind::RGBUnbounded;
    Float m = Max(r, Max(g, b));
    s.scale = 2 * m;
    if (s.scale > 0)
        RGBToSigmoidCoeffs(coeffs, zNodes, res, Max(Float(0), r / s.scale), Max(Float(0), g / s.scale),
                           Max(Float(0), b / s.scale), s.c);
    else
        RGBToSigmoidCoeffs(coeffs, zNodes, res, 0, 0, 0, s.c);
    return s;
}

// pbrt-v4 RGBIlluminantSpectrum: the unbounded spectrum times the color space illuminant
// (illuminantTable: index of its 1 nm table in SpectrumTables, TableD65 for sRGB).
LU_INLINE Spectrum RGBIlluminantSpectrum(const Float *coeffs, const Float *zNodes, uint32_t res, Float r, Float g,
                                         Float b, uint32_t illuminantTable) {
    Spectrum s = RGBUnboundedSpectrum(coeffs, zNodes, res, r, g, b);
    s.kind = SpectrumKind::RGBIlluminant;
    s.table = illuminantTable;
    return s;
}

}  // namespace lu
