// Lucerna: pixel reconstruction filters (box, gaussian, triangle, mitchell, Lanczos sinc) with
// filter importance sampling, after pbrt-v4's filters.h/.cpp and FilterSampler: box and triangle
// are sampled exactly (weight 1); gaussian, mitchell and sinc through a 32-cells-per-unit-radius
// table of |f| (a Distribution2D) with weight f/pdf, negative in the negative lobes.
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/sampling/distribution.h"
#include "lucerna/sampling/warp.h"

namespace lu {

// ---- Filter functions (p in pixels, relative to the pixel center) ----

LU_INLINE Float Gaussian1D(Float x, Float sigma) {
    return 1 / std::sqrt(2 * Pi * sigma * sigma) * std::exp(-(x * x) / (2 * sigma * sigma));
}

// Integral of the normal density N(mu, sigma) over [x0, x1].
LU_INLINE Float GaussianIntegral(Float x0, Float x1, Float mu, Float sigma) {
    Float sigmaRoot2 = sigma * 1.414213562373095f;
    return 0.5f * (std::erf((mu - x0) / sigmaRoot2) - std::erf((mu - x1) / sigmaRoot2));
}

// Mitchell-Netravali cubic on [-2, 2].
LU_INLINE Float Mitchell1D(Float x, Float B, Float C) {
    x = std::abs(x);
    if (x <= 1)
        return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) * (1.f / 6.f);
    if (x <= 2)
        return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x + (8 * B + 24 * C)) *
               (1.f / 6.f);
    return 0;
}

// sin(pi x) / (pi x), 1 at 0.
LU_INLINE Float Sinc(Float x) {
    Float px = Pi * x;
    if (1 - px * px == 1) return 1;
    return std::sin(px) / px;
}

// pbrt-v4's WindowedSinc: the sinc times the Lanczos window sinc(x / tau), cut at |x| > radius.
LU_INLINE Float WindowedSinc(Float x, Float radius, Float tau) {
    if (std::abs(x) > radius) return 0;
    return Sinc(x) * Sinc(x / tau);
}

// Integral of WindowedSinc over [-radius, radius]: composite Simpson over 512 intervals (the
// integrand is smooth on the support; the error is below 1e-7 for radius <= 16, tau >= 1).
LU_INLINE Float WindowedSincIntegral(Float radius, Float tau) {
    const int n = 512;
    double h = 2.0 * double(radius) / n, sum = 0;
    for (int i = 0; i <= n; ++i) {
        Float x = Float(-double(radius) + i * h);
        double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        sum += w * double(WindowedSinc(x, radius, tau));
    }
    return Float(sum * h / 3);
}

// The (unnormalized) filter value at offset p; 0 outside [-radius, radius].
LU_INLINE Float EvalFilter(const FilterData &f, Vec2f p) {
    switch (f.kind) {
    case FilterKind::Box: return (std::abs(p.x) <= f.radiusX && std::abs(p.y) <= f.radiusY) ? 1 : 0;
    case FilterKind::Gaussian:
        return Max<Float>(0, Gaussian1D(p.x, f.sigma) - Gaussian1D(f.radiusX, f.sigma)) *
               Max<Float>(0, Gaussian1D(p.y, f.sigma) - Gaussian1D(f.radiusY, f.sigma));
    case FilterKind::Triangle:
        return Max<Float>(0, f.radiusX - std::abs(p.x)) * Max<Float>(0, f.radiusY - std::abs(p.y));
    case FilterKind::Mitchell:
        return Mitchell1D(2 * p.x / f.radiusX, f.B, f.C) * Mitchell1D(2 * p.y / f.radiusY, f.B, f.C);
    case FilterKind::LanczosSinc: return WindowedSinc(p.x, f.radiusX, f.tau) * WindowedSinc(p.y, f.radiusY, f.tau);
    }
    return 0;
}

// Integral of the filter over its support (pbrt-v4's Filter::Integral).
LU_INLINE Float FilterIntegral(const FilterData &f) {
    switch (f.kind) {
    case FilterKind::Box: return 2 * f.radiusX * 2 * f.radiusY;
    case FilterKind::Gaussian:
        return (GaussianIntegral(-f.radiusX, f.radiusX, 0, f.sigma) - 2 * f.radiusX * Gaussian1D(f.radiusX, f.sigma)) *
               (GaussianIntegral(-f.radiusY, f.radiusY, 0, f.sigma) - 2 * f.radiusY * Gaussian1D(f.radiusY, f.sigma));
    case FilterKind::Triangle: return Sqr(f.radiusX) * Sqr(f.radiusY);
    case FilterKind::Mitchell: return f.radiusX * f.radiusY / 4;
    case FilterKind::LanczosSinc: return WindowedSincIntegral(f.radiusX, f.tau) * WindowedSincIntegral(f.radiusY, f.tau);
    }
    return 0;
}

// ---- Sampling ----

struct FilterSample {
    Vec2f p;       // offset from the pixel center, in pixels
    Float weight;  // f(p) / pdf(p) (pbrt-v4: f at the table cell / pdf), may be negative
};

// pbrt-v4's SampleTent: a sample of the tent max(0, r - |x|) on [-r, r].
LU_INLINE Float SampleTent(Float u, Float r) {
    if (u < 0.5f) {
        Float up = Min(u * 2, OneMinusEpsilon);
        return -r + r * SampleLinear(up, 0, 1);
    }
    Float up = Min((u - 0.5f) * 2, OneMinusEpsilon);
    return r * SampleLinear(up, 1, 0);
}

// Number of table cells per axis (pbrt-v4's FilterSampler: int(32 * radius)).
LU_INLINE int FilterTableSize(Float radius) { return int(32 * radius); }

// The tabulated (signed) filter value of cell (ix, iy): f at the cell center.
LU_INLINE Float FilterTableValue(const FilterData &f, int ix, int iy, int nx, int ny) {
    Vec2f p(Lerp((ix + 0.5f) / nx, -f.radiusX, f.radiusX), Lerp((iy + 0.5f) / ny, -f.radiusY, f.radiusY));
    return EvalFilter(f, p);
}

// Samples an offset p from u in [0,1)^2 proportionally to |f| (box, triangle exactly; gaussian,
// mitchell, sinc from the table in scene.distributions2D[f.distribution]). Without a table (none
// built, or a radius under 1/32 pixel) p is uniform over the support with weight f(p) * area.
LU_INLINE FilterSample SampleFilter(const FilterData &f, const SceneView &scene, Vec2f u) {
    switch (f.kind) {
    case FilterKind::Box:
        return {Vec2f(Lerp(u.x, -f.radiusX, f.radiusX), Lerp(u.y, -f.radiusY, f.radiusY)), Float(1)};
    case FilterKind::Triangle: return {Vec2f(SampleTent(u.x, f.radiusX), SampleTent(u.y, f.radiusY)), Float(1)};
    default: break;
    }
    if (f.distribution == NoIndex || f.distribution >= scene.distributions2D.size) {
        Vec2f p(Lerp(u.x, -f.radiusX, f.radiusX), Lerp(u.y, -f.radiusY, f.radiusY));
        return {p, EvalFilter(f, p) * (4 * f.radiusX * f.radiusY)};
    }
    const Distribution2D &d = scene.distributions2D[f.distribution];
    uint32_t row, col;
    Float y01 = SampleCdfTable(MarginalCdf(scene, d), nullptr, d.ny, 0, u.y, nullptr, &row);
    Float x01 = SampleCdfTable(ConditionalCdf(scene, d, row), nullptr, d.nx, 0, u.x, nullptr, &col);
    Float absF = Func2D(scene, d)[uint64_t(row) * d.nx + col];
    Vec2f p(Lerp(x01, -f.radiusX, f.radiusX), Lerp(y01, -f.radiusY, f.radiusY));
    if (!(absF > 0) || !(d.integral > 0)) return {p, Float(0)};
    // pdf over the filter domain: (|f| / integral over [0,1]^2) / area.
    Float pdf = absF / (d.integral * (4 * f.radiusX * f.radiusY));
    Float fCell = FilterTableValue(f, int(col), int(row), int(d.nx), int(d.ny));
    return {p, fCell / pdf};
}

}  // namespace lu
