// Lucerna: the measured BRDF of Dupuy & Jakob 2018 ("An Adaptive Parameterization for Efficient
// Material Acquisition and Rendering"), host and device: pbrt-v4's PiecewiseLinear2D warps
// (util/sampling.h) over tables in SceneView::measuredData, and MeasuredBxDF (bxdfs.h/.cpp, with
// pbrt-v4 PR #215: f and PDF parameterized by wo, as Sample_f).
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/materials/bxdfs.h"

namespace lu {

// ---- PiecewiseLinear2D (pbrt-v4's util/sampling.h, Dimension = table.nParams) ----

// Where a point of the parameter grid falls: the first slice of its cell and the linear weights
// (w[2d], w[2d + 1]) of the cell's two vertices along parameter d (clamped outside the grid).
struct PLParamCell {
    uint32_t sliceOffset = 0;
    Float w[6] = {1, 0, 1, 0, 1, 0};
};

LU_INLINE PLParamCell PLFindParams(const PiecewiseLinear2DTable &t, const Float *data, const Float *param) {
    PLParamCell c;
    for (uint32_t d = 0; d < t.nParams; ++d) {
        uint32_t n = t.paramSize[d];
        if (n == 1) continue;
        const Float *v = data + t.paramValues[d];
        // pbrt-v4's FindInterval: the last vertex <= param, within [0, n - 2].
        uint32_t lo = 0, hi = n - 1;
        while (hi - lo > 1) {
            uint32_t mid = (lo + hi) / 2;
            if (v[mid] <= param[d]) lo = mid;
            else hi = mid;
        }
        Float p0 = v[lo], p1 = v[lo + 1];
        c.w[2 * d + 1] = Clamp((param[d] - p0) / (p1 - p0), Float(0), Float(1));
        c.w[2 * d] = 1 - c.w[2 * d + 1];
        c.sliceOffset += t.paramStride[d] * lo;
    }
    return c;
}

// The value at index i of a slice (sliceSize entries per slice), interpolated over the 2^nParams
// slices of the parameter cell (base already offset to the cell's first slice).
LU_INLINE Float PLLookup(const PiecewiseLinear2DTable &t, const Float *base, uint32_t i, uint32_t sliceSize,
                         const PLParamCell &c) {
    Float r = 0;
    for (uint32_t corner = 0; corner < (1u << t.nParams); ++corner) {
        Float w = 1;
        uint32_t idx = i;
        for (uint32_t d = 0; d < t.nParams; ++d) {
            uint32_t bit = (corner >> d) & 1;
            w *= c.w[2 * d + bit];
            idx += bit * t.paramStride[d] * sliceSize;
        }
        if (w != 0) r += w * base[idx];
    }
    return r;
}

struct PLSample {
    Vec2f p;
    Float pdf = 0;
};

// The bilinear density at pos in [0,1]^2 (pbrt-v4's PiecewiseLinear2D::Evaluate).
LU_INLINE Float PLEvaluate(const PiecewiseLinear2DTable &t, const Float *data, Vec2f pos, const Float *param) {
    PLParamCell c = PLFindParams(t, data, param);
    Float sx = pos.x * Float(t.nx - 1), sy = pos.y * Float(t.ny - 1);
    int ix = Min(int(sx), int(t.nx) - 2), iy = Min(int(sy), int(t.ny) - 2);
    ix = Max(ix, 0);
    iy = Max(iy, 0);
    Float w1x = sx - Float(ix), w1y = sy - Float(iy), w0x = 1 - w1x, w0y = 1 - w1y;
    uint32_t size = t.nx * t.ny;
    uint32_t index = uint32_t(ix) + uint32_t(iy) * t.nx + c.sliceOffset * size;
    const Float *d = data + t.data;
    Float v00 = PLLookup(t, d, index, size, c), v10 = PLLookup(t, d + 1, index, size, c);
    Float v01 = PLLookup(t, d + t.nx, index, size, c), v11 = PLLookup(t, d + t.nx + 1, index, size, c);
    return (w0y * (w0x * v00 + w1x * v10) + w1y * (w0x * v01 + w1x * v11)) * Float((t.nx - 1) * (t.ny - 1));
}

// The t in [0,1] where a density linear from c0 to c1 holds the mass x: the root of
// c0 t + (c1 - c0) t^2 / 2 = x. pbrt-v4 writes it (c0 - sqrt(c0^2 - 2x(c0 - c1))) / (c0 - c1),
// which cancels catastrophically when c0 and c1 are close (0.5% pdf errors against PLInvertTable
// were measured); 2x / (c0 + sqrt(...)) is the same root without the cancellation, and also the
// constant case.
LU_INLINE Float PLInvertLinear(Float x, Float c0, Float c1) {
    Float denom = c0 + SafeSqrt(c0 * c0 - 2 * x * (c0 - c1));
    return denom > 0 ? 2 * x / denom : 0;   // a patch without mass (a zero slice): rejected by its pdf
}

// Warps u in [0,1)^2 to the table's density by the marginal (rows, y) then conditional
// (columns, x) inversion; returns the point and its density (pbrt-v4's Sample).
LU_INLINE PLSample PLSampleTable(const PiecewiseLinear2DTable &t, const Float *data, Vec2f u, const Float *param) {
    u.x = Clamp(u.x, 1 - OneMinusEpsilon, OneMinusEpsilon);
    u.y = Clamp(u.y, 1 - OneMinusEpsilon, OneMinusEpsilon);
    PLParamCell c = PLFindParams(t, data, param);
    const Float *marginal = data + t.marginalCdf, *conditional = data + t.conditionalCdf, *d = data + t.data;
    uint32_t size = t.nx * t.ny;

    // ---- The row, from the marginal cdf ----
    uint32_t mOffset = c.sliceOffset * t.ny;
    uint32_t lo = 0, hi = t.ny - 1;
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (PLLookup(t, marginal, mOffset + mid, t.ny, c) < u.y) lo = mid;
        else hi = mid;
    }
    uint32_t row = lo;
    u.y -= PLLookup(t, marginal, mOffset + row, t.ny, c);
    uint32_t offset = row * t.nx + c.sliceOffset * size;
    Float r0 = PLLookup(t, conditional, offset + t.nx - 1, size, c);
    Float r1 = PLLookup(t, conditional, offset + 2 * t.nx - 1, size, c);
    u.y = PLInvertLinear(u.y, r0, r1);

    // ---- The column, from the conditional cdf interpolated at that height ----
    u.x *= (1 - u.y) * r0 + u.y * r1;
    auto conditionalAt = [&](uint32_t i) {
        Float v0 = PLLookup(t, conditional, offset + i, size, c);
        Float v1 = PLLookup(t, conditional + t.nx, offset + i, size, c);
        return (1 - u.y) * v0 + u.y * v1;
    };
    lo = 0;
    hi = t.nx - 1;
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (conditionalAt(mid) < u.x) lo = mid;
        else hi = mid;
    }
    uint32_t col = lo;
    u.x -= conditionalAt(col);
    offset += col;
    Float v00 = PLLookup(t, d, offset, size, c), v10 = PLLookup(t, d + 1, offset, size, c);
    Float v01 = PLLookup(t, d + t.nx, offset, size, c), v11 = PLLookup(t, d + t.nx + 1, offset, size, c);
    Float c0 = (1 - u.y) * v00 + u.y * v01, c1 = (1 - u.y) * v10 + u.y * v11;
    u.x = PLInvertLinear(u.x, c0, c1);

    PLSample s;
    s.p = Vec2f((Float(col) + u.x) / Float(t.nx - 1), (Float(row) + u.y) / Float(t.ny - 1));
    s.pdf = ((1 - u.x) * c0 + u.x * c1) * Float((t.nx - 1) * (t.ny - 1));
    return s;
}

// The inverse of PLSampleTable: the uniform point that warps to p, and the density at p.
LU_INLINE PLSample PLInvertTable(const PiecewiseLinear2DTable &t, const Float *data, Vec2f p, const Float *param) {
    PLParamCell c = PLFindParams(t, data, param);
    const Float *marginal = data + t.marginalCdf, *conditional = data + t.conditionalCdf, *d = data + t.data;
    uint32_t size = t.nx * t.ny;
    Float sx = p.x * Float(t.nx - 1), sy = p.y * Float(t.ny - 1);
    int ix = Max(Min(int(sx), int(t.nx) - 2), 0), iy = Max(Min(int(sy), int(t.ny) - 2), 0);
    sx -= Float(ix);
    sy -= Float(iy);
    uint32_t offset = uint32_t(ix) + uint32_t(iy) * t.nx + c.sliceOffset * size;

    // ---- x: the mass left of sx in the patch, plus the conditional cdf, over the row's mass ----
    Float v00 = PLLookup(t, d, offset, size, c), v10 = PLLookup(t, d + 1, offset, size, c);
    Float v01 = PLLookup(t, d + t.nx, offset, size, c), v11 = PLLookup(t, d + t.nx + 1, offset, size, c);
    Float c0 = (1 - sy) * v00 + sy * v01, c1 = (1 - sy) * v10 + sy * v11;
    Float pdf = (1 - sx) * c0 + sx * c1;
    Float x = sx * (c0 + 0.5f * sx * (c1 - c0));
    x += (1 - sy) * PLLookup(t, conditional, offset, size, c) + sy * PLLookup(t, conditional + t.nx, offset, size, c);
    uint32_t rowOffset = uint32_t(iy) * t.nx + c.sliceOffset * size;
    Float r0 = PLLookup(t, conditional, rowOffset + t.nx - 1, size, c);
    Float r1 = PLLookup(t, conditional, rowOffset + 2 * t.nx - 1, size, c);
    Float rowMass = (1 - sy) * r0 + sy * r1;
    x = rowMass > 0 ? x / rowMass : 0;

    // ---- y: the marginal mass below sy ----
    Float y = sy * (r0 + 0.5f * sy * (r1 - r0));
    y += PLLookup(t, marginal, uint32_t(iy) + c.sliceOffset * t.ny, t.ny, c);

    PLSample s;
    s.p = Vec2f(x, y);
    s.pdf = pdf * Float((t.nx - 1) * (t.ny - 1));
    return s;
}

// ---- MeasuredBxDF (pbrt-v4's bxdfs.h / bxdfs.cpp) ----

// The format's unit-square coordinates of a direction: u = sqrt(2 theta / pi) (denser samples
// near the normal) and (phi + pi) / (2 pi).
LU_INLINE Float MeasuredTheta2u(Float theta) { return std::sqrt(theta * (2 / Pi)); }
LU_INLINE Float MeasuredPhi2u(Float phi) { return (phi + Pi) / (2 * Pi); }
LU_INLINE Float MeasuredU2theta(Float u) { return Sqr(u) * (Pi / 2); }
LU_INLINE Float MeasuredU2phi(Float u) { return (2 * u - 1) * Pi; }
// theta of a unit vector; atan2 keeps its precision near the pole, where acos(z) loses it (the
// half vector of a sampled reflection maps back to u_theta ~ 1e-3 off by acos at theta ~ 0.4
// degrees, a 0.5% pdf error in the u_theta^3 density there).
LU_INLINE Float MeasuredTheta(Vec3f w) { return std::atan2(std::sqrt(Sqr(w.x) + Sqr(w.y)), w.z); }

// Reflection only, on the side of wo (both directions in the same hemisphere, mirrored to +z).
// f = spectra(R^-1(wm)) D(wm) / (4 sigma(wo) |cos wi|), where R^-1 is the vndf warp's inverse
// given wo; Sample_f warps u by the luminance table, then the vndf, and reflects wo about wm.
struct MeasuredBxDF {
    const MeasuredBRDFData *brdf = nullptr;   // in scene.materials
    const Float *data = nullptr;              // scene.measuredData
    Float lambda[NSpectrumSamples];           // the path's wavelengths (nm)

    MeasuredBxDF() = default;
    LU_HD MeasuredBxDF(const MeasuredBRDFData *brdf, const Float *data, const SampledWavelengths &wl)
        : brdf(brdf), data(data) {
        for (int i = 0; i < NSpectrumSamples; ++i) lambda[i] = wl.lambda[i];
    }

    LU_HD uint8_t Flags() const { return BxDF_GlossyReflection; }

    // The reflectance spectrum at `sample` of the vndf's sample space, given wo's angles.
    LU_HD SampledSpectrum Spectra(Vec2f sample, Float phi_o, Float theta_o) const {
        SampledSpectrum fr;
        for (int i = 0; i < NSpectrumSamples; ++i) {
            Float params[3] = {phi_o, theta_o, lambda[i]};
            fr[i] = Max(Float(0), PLEvaluate(brdf->spectra, data, sample, params));
        }
        return fr;
    }

    // wm's unit-square coordinates (phi relative to wo's for isotropic data), wrapped into [0,1).
    LU_HD Vec2f WmToUnit(Vec3f wm, Float phi_o) const {
        Float theta_m = MeasuredTheta(wm), phi_m = std::atan2(wm.y, wm.x);
        Vec2f u(MeasuredTheta2u(theta_m), MeasuredPhi2u(brdf->isotropic ? phi_m - phi_o : phi_m));
        u.y = u.y - std::floor(u.y);
        return u;
    }

    LU_HD SampledSpectrum f(Vec3f wo, Vec3f wi, TransportMode) const {
        if (!SameHemisphere(wo, wi)) return SampledSpectrum(0);
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
        }
        Vec3f wm = wi + wo;
        if (LengthSquared(wm) == 0 || wi.z == 0) return SampledSpectrum(0);
        wm = Normalize(wm);
        Float theta_o = MeasuredTheta(wo), phi_o = std::atan2(wo.y, wo.x);
        Vec2f u_wo(MeasuredTheta2u(theta_o), MeasuredPhi2u(phi_o));
        Vec2f u_wm = WmToUnit(wm, phi_o);
        Float params[2] = {phi_o, theta_o};
        PLSample ui = PLInvertTable(brdf->vndf, data, u_wm, params);
        SampledSpectrum fr = Spectra(ui.p, phi_o, theta_o);
        Float sigma = PLEvaluate(brdf->sigma, data, u_wo, params);
        if (!(sigma > 0)) return SampledSpectrum(0);
        return fr * (PLEvaluate(brdf->ndf, data, u_wm, params) / (4 * sigma * AbsCosTheta(wi)));
    }

    // The density of wi from the unit square: d(omega_m) = 2 pi^2 u_theta sin(theta_m) du and the
    // reflection's 4 (wo . wm) (pbrt-v4's jacobian, floored at 1e-6 as there).
    LU_HD static Float Jacobian(Vec3f wo, Vec3f wm, Float u_theta, Float sinTheta_m) {
        return 4 * Dot(wo, wm) * Max(2 * Sqr(Pi) * u_theta * sinTheta_m, Float(1e-6f));
    }

    LU_HD bool Sample_f(Vec3f wo, Float, Vec2f u, TransportMode, uint8_t sampleFlags, BSDFSample *bs) const {
        if (!(sampleFlags & BxDF_SampleReflection)) return false;
        bool flipWi = false;
        if (wo.z <= 0) {
            wo = -wo;
            flipWi = true;
        }
        Float theta_o = MeasuredTheta(wo), phi_o = std::atan2(wo.y, wo.x);
        Float params[2] = {phi_o, theta_o};
        PLSample s = PLSampleTable(brdf->luminance, data, Vec2f(u.y, u.x), params);
        Vec2f sample = s.p;
        Float lumPDF = s.pdf;
        s = PLSampleTable(brdf->vndf, data, sample, params);
        Vec2f u_wm = s.p;
        Float vndfPDF = s.pdf;
        Float phi_m = MeasuredU2phi(u_wm.y), theta_m = MeasuredU2theta(u_wm.x);
        if (brdf->isotropic) phi_m += phi_o;
        Float sinTheta_m = std::sin(theta_m), cosTheta_m = std::cos(theta_m);
        Vec3f wm = SphericalDirection(sinTheta_m, cosTheta_m, phi_m);
        Vec3f wi = Reflect(wo, wm);
        if (wi.z <= 0) return false;
        SampledSpectrum fr = Spectra(sample, phi_o, theta_o);
        Vec2f u_wo(MeasuredTheta2u(theta_o), MeasuredPhi2u(phi_o));
        Float sigma = PLEvaluate(brdf->sigma, data, u_wo, params);
        if (!(sigma > 0)) return false;
        fr *= PLEvaluate(brdf->ndf, data, u_wm, params) / (4 * sigma * AbsCosTheta(wi));
        Float pdf = vndfPDF * lumPDF / Jacobian(wo, wm, u_wm.x, sinTheta_m);
        if (!(pdf > 0)) return false;
        if (flipWi) wi = -wi;
        *bs = MakeBSDFSample(fr, wi, pdf, BxDF_GlossyReflection);
        return true;
    }

    LU_HD Float PDF(Vec3f wo, Vec3f wi, TransportMode, uint8_t sampleFlags) const {
        if (!(sampleFlags & BxDF_SampleReflection)) return 0;
        if (!SameHemisphere(wo, wi)) return 0;
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
        }
        Vec3f wm = wi + wo;
        if (LengthSquared(wm) == 0) return 0;
        wm = Normalize(wm);
        Float theta_o = MeasuredTheta(wo), phi_o = std::atan2(wo.y, wo.x);
        Vec2f u_wm = WmToUnit(wm, phi_o);
        Float params[2] = {phi_o, theta_o};
        PLSample ui = PLInvertTable(brdf->vndf, data, u_wm, params);
        Float lumPDF = PLEvaluate(brdf->luminance, data, ui.p, params);
        Float sinTheta_m = std::sqrt(Sqr(wm.x) + Sqr(wm.y));
        return ui.pdf * lumPDF / Jacobian(wo, wm, u_wm.x, sinTheta_m);
    }
};

}  // namespace lu
