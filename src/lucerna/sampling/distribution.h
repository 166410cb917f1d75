// Lucerna: piecewise-constant 1D/2D distributions over tables in SceneView::distData (host and
// device), with sampling, pdf and inversion; after pbrt-v4's PiecewiseConstant1D/2D (sampling.h).
// Host builders at the end append the tables to a std::vector<Float>.
#pragma once

#include "lucerna/core/scene_data.h"

namespace lu {

// Piecewise-constant distribution of n bins over [min, max]. Tables in distData from `offset`:
// cdf (n+1, cdf[0] = 0, cdf[n] = 1), then the absolute function values (n).
struct Distribution1D {
    uint32_t n = 0;
    uint64_t offset = 0;
    Float integral = 0;   // integral of |f| over [min, max]
    Float min = 0, max = 1;
};

// ---- Table helpers (raw pointers, shared by 1D, 2D and the light CDF) ----

// Largest i in [0, n-1] with cdf[i] <= u (cdf has n+1 entries), as pbrt-v4's FindInterval.
// Bins of zero width are skipped.
LU_INLINE uint32_t FindCdfInterval(const Float *cdf, uint32_t n, Float u) {
    if (n <= 1) return 0;
    // Binary search for the first index in [1, n] whose cdf exceeds u.
    uint32_t lo = 1, len = n;  // search in [1, n] (n entries)
    while (len > 0) {
        uint32_t half = len >> 1, mid = lo + half;
        if (cdf[mid] <= u) { lo = mid + 1; len -= half + 1; }
        else len = half;
    }
    // lo is the first index with cdf[lo] > u (or n + 1); the interval is lo - 1.
    uint32_t i = lo - 1;
    return i > n - 1 ? n - 1 : i;
}

// Samples a bin and the continuous offset within it; returns x in [0,1) over the n bins.
// *pdf = func[o] / funcInt (0 if the integral is 0); func may be null when pdf is.
LU_INLINE Float SampleCdfTable(const Float *cdf, const Float *func, uint32_t n, Float funcInt, Float u,
                               Float *pdf, uint32_t *offset) {
    uint32_t o = FindCdfInterval(cdf, n, u);
    if (offset) *offset = o;
    Float du = u - cdf[o];
    Float w = cdf[o + 1] - cdf[o];
    if (w > 0) du /= w;
    if (pdf) *pdf = funcInt > 0 ? func[o] / funcInt : 0;
    Float x = (Float(o) + du) / Float(n);
    return x < OneMinusEpsilon ? x : OneMinusEpsilon;
}

// ---- 1D ----

LU_INLINE const Float *CdfOf(const SceneView &s, const Distribution1D &d) { return s.distData.ptr + d.offset; }
LU_INLINE const Float *FuncOf(const SceneView &s, const Distribution1D &d) { return s.distData.ptr + d.offset + d.n + 1; }

// Continuous sample in [min, max); *pdf is the density w.r.t. x.
LU_INLINE Float SampleDistribution1D(const SceneView &s, const Distribution1D &d, Float u, Float *pdf,
                                     uint32_t *offset = nullptr) {
    Float x = SampleCdfTable(CdfOf(s, d), FuncOf(s, d), d.n, d.integral, u, pdf, offset);
    return Lerp(x, d.min, d.max);
}

LU_INLINE Float Distribution1DPDF(const SceneView &s, const Distribution1D &d, Float x) {
    if (!(x >= d.min && x <= d.max) || d.integral <= 0) return 0;
    Float c = (x - d.min) / (d.max - d.min) * Float(d.n);
    uint32_t o = uint32_t(Clamp(int(c), 0, int(d.n) - 1));
    return FuncOf(s, d)[o] / d.integral;
}

// Discrete sampling of bin i with probability (cdf[i+1] - cdf[i]).
LU_INLINE uint32_t SampleDiscrete1D(const SceneView &s, const Distribution1D &d, Float u, Float *pmf) {
    const Float *cdf = CdfOf(s, d);
    uint32_t o = FindCdfInterval(cdf, d.n, u);
    if (pmf) *pmf = cdf[o + 1] - cdf[o];
    return o;
}

// The u that SampleDistribution1D maps to x; returns false outside [min, max].
LU_INLINE bool InvertDistribution1D(const SceneView &s, const Distribution1D &d, Float x, Float *u) {
    if (!(x >= d.min && x <= d.max)) return false;
    const Float *cdf = CdfOf(s, d);
    Float c = (x - d.min) / (d.max - d.min) * Float(d.n);
    int o = Clamp(int(c), 0, int(d.n) - 1);
    *u = Lerp(c - Float(o), cdf[o], cdf[o + 1]);
    return true;
}

// ---- 2D (domain [0,1]^2; rows are v = y, columns u = x) ----
// Tables: marginal cdf over rows (ny+1), conditional cdfs per row (ny * (nx+1)), func (nx * ny).

LU_INLINE const Float *MarginalCdf(const SceneView &s, const Distribution2D &d) { return s.distData.ptr + d.offset; }
LU_INLINE const Float *ConditionalCdf(const SceneView &s, const Distribution2D &d, uint32_t row) {
    return s.distData.ptr + d.offset + (d.ny + 1) + uint64_t(row) * (d.nx + 1);
}
LU_INLINE const Float *Func2D(const SceneView &s, const Distribution2D &d) {
    return s.distData.ptr + d.offset + (d.ny + 1) + uint64_t(d.ny) * (d.nx + 1);
}

// Samples (u, v) in [0,1)^2 with density *pdf = f(u, v) / integral (pbrt-v4's marginal x
// conditional product). *pdf is 0 when the distribution is all zero.
LU_INLINE Vec2f SampleDistribution2D(const SceneView &s, const Distribution2D &d, Vec2f u, Float *pdf) {
    uint32_t row;
    Float v = SampleCdfTable(MarginalCdf(s, d), nullptr, d.ny, 0, u.y, nullptr, &row);
    uint32_t col;
    Float x = SampleCdfTable(ConditionalCdf(s, d, row), nullptr, d.nx, 0, u.x, nullptr, &col);
    if (pdf) *pdf = d.integral > 0 ? Func2D(s, d)[uint64_t(row) * d.nx + col] / d.integral : 0;
    return {x, v};
}

LU_INLINE Float Distribution2DPDF(const SceneView &s, const Distribution2D &d, Vec2f p) {
    if (d.integral <= 0) return 0;
    int iu = Clamp(int(p.x * Float(d.nx)), 0, int(d.nx) - 1);
    int iv = Clamp(int(p.y * Float(d.ny)), 0, int(d.ny) - 1);
    return Func2D(s, d)[uint64_t(iv) * d.nx + iu] / d.integral;
}

// The sample u that SampleDistribution2D maps to p; false outside [0,1]^2.
LU_INLINE bool InvertDistribution2D(const SceneView &s, const Distribution2D &d, Vec2f p, Vec2f *u) {
    if (!(p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1)) return false;
    const Float *mc = MarginalCdf(s, d);
    Float cv = p.y * Float(d.ny);
    int iv = Clamp(int(cv), 0, int(d.ny) - 1);
    Float uy = Lerp(cv - Float(iv), mc[iv], mc[iv + 1]);
    const Float *cc = ConditionalCdf(s, d, uint32_t(iv));
    Float cu = p.x * Float(d.nx);
    int iu = Clamp(int(cu), 0, int(d.nx) - 1);
    Float ux = Lerp(cu - Float(iu), cc[iu], cc[iu + 1]);
    *u = Vec2f(ux, uy);
    return true;
}

}  // namespace lu
