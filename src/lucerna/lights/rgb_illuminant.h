// Lucerna: RGB illuminant texels -> Spectrum (RGBIlluminant kind) through the Jakob-Hanika table
// in SceneView (host and device), as pbrt-v4's RGBIlluminantSpectrum(colorSpace, ClampZero(rgb)).
#pragma once

#include "lucerna/core/scene_data.h"

namespace lu {

// Sigmoid-polynomial coefficients for an RGB in [0,1]^3 by trilinear lookup in the table
// (pbrt-v4's RGBToSpectrumTable::operator()).
LU_INLINE void RGBToSigmoidCoeffs(const SceneView &s, const Float rgb[3], Float c[3]) {
    c[0] = c[1] = 0;
    if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) {
        // Gray: a constant sigmoid with value rgb[0].
        Float v = rgb[0];
        c[2] = (v <= 0) ? -Infinity : (v >= 1 ? Infinity : (v - 0.5f) / std::sqrt(v * (1 - v)));
        return;
    }
    int res = int(s.rgbToSpecRes);
    if (res < 2) { c[2] = 0; return; }
    int maxc = (rgb[0] > rgb[1]) ? ((rgb[0] > rgb[2]) ? 0 : 2) : ((rgb[1] > rgb[2]) ? 1 : 2);
    Float z = rgb[maxc];
    Float x = rgb[(maxc + 1) % 3] * Float(res - 1) / z;
    Float y = rgb[(maxc + 2) % 3] * Float(res - 1) / z;
    int xi = Min(int(x), res - 2), yi = Min(int(y), res - 2);
    const Float *zn = s.rgbToSpecZNodes.ptr;
    int zi = 0;  // largest i in [0, res-2] with zNodes[i] < z
    {
        int lo = 1, len = res - 2;
        while (len > 0) {
            int half = len >> 1, mid = lo + half;
            if (zn[mid] < z) { lo = mid + 1; len -= half + 1; }
            else len = half;
        }
        zi = Clamp(lo - 1, 0, res - 2);
    }
    Float dx = x - Float(xi), dy = y - Float(yi), dz = (z - zn[zi]) / (zn[zi + 1] - zn[zi]);
    const Float *tab = s.rgbToSpecCoeffs.ptr;
    auto co = [&](int ix, int iy, int iz, int i) {
        return tab[((((size_t(maxc) * res + (zi + iz)) * res + (yi + iy)) * res + (xi + ix)) * 3) + i];
    };
    for (int i = 0; i < 3; ++i)
        c[i] = Lerp(dz, Lerp(dy, Lerp(dx, co(0, 0, 0, i), co(1, 0, 0, i)), Lerp(dx, co(0, 1, 0, i), co(1, 1, 0, i))),
                    Lerp(dy, Lerp(dx, co(0, 0, 1, i), co(1, 0, 1, i)), Lerp(dx, co(0, 1, 1, i), co(1, 1, 1, i))));
}

// The illuminant spectrum of a linear RGB (negative components clamped to 0): scale = 2 max,
// sigmoid coefficients of rgb / scale, times the color space illuminant (SceneView::illuminantTable).
LU_INLINE Spectrum RGBIlluminantSpectrum(const SceneView &s, const Float rgbIn[3]) {
    Float rgb[3] = {Max(rgbIn[0], Float(0)), Max(rgbIn[1], Float(0)), Max(rgbIn[2], Float(0))};
    Spectrum sp;
    sp.kind = SpectrumKind::RGBIlluminant;
    sp.table = s.illuminantTable;
    Float m = Max(rgb[0], Max(rgb[1], rgb[2]));
    sp.scale = 2 * m;
    if (sp.scale == 0) return sp;  // black
    Float n[3] = {rgb[0] / sp.scale, rgb[1] / sp.scale, rgb[2] / sp.scale};
    RGBToSigmoidCoeffs(s, n, sp.c);
    return sp;
}

}  // namespace lu
