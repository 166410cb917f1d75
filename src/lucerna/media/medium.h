// Lucerna: participating media (host and device), after pbrt-v4's media.h: the scattering
// properties at a point (homogeneous, uniform grid, RGB grid, procedural cloud), the majorants
// along a ray (one segment, or a 3D DDA over the 16^3 majorant grid) and SampleTmaj, which samples tentative
// collisions against those majorants (Woodcock / delta tracking). Grids are plain arrays in
// SceneView::mediumData; the phase function is Henyey-Greenstein (materials/scattering.h).
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/materials/noise.h"
#include "lucerna/materials/scattering.h"
#include "lucerna/sampling/rng.h"
#include "lucerna/sampling/warp.h"

namespace lu {

// ---- Grids (pbrt-v4's SampledGrid) ----

// Sample (x, y, z) of a float grid; 0 outside.
LU_INLINE Float GridValue(const SceneView &s, const MediumGrid &g, int x, int y, int z) {
    if (x < 0 || y < 0 || z < 0 || x >= int(g.nx) || y >= int(g.ny) || z >= int(g.nz)) return 0;
    return s.mediumData[uint32_t(g.offset + (uint64_t(z) * g.ny + uint64_t(y)) * g.nx + uint64_t(x))];
}

// Trilinear lookup at p in [0,1]^3 of the bounds (samples at cell centers).
LU_INLINE Float LookupGrid(const SceneView &s, const MediumGrid &g, Vec3f p) {
    Float px = p.x * g.nx - 0.5f, py = p.y * g.ny - 0.5f, pz = p.z * g.nz - 0.5f;
    int ix = int(std::floor(px)), iy = int(std::floor(py)), iz = int(std::floor(pz));
    Float dx = px - ix, dy = py - iy, dz = pz - iz;
    auto v = [&](int a, int b, int c) { return GridValue(s, g, ix + a, iy + b, iz + c); };
    Float d00 = Lerp(dx, v(0, 0, 0), v(1, 0, 0)), d10 = Lerp(dx, v(0, 1, 0), v(1, 1, 0));
    Float d01 = Lerp(dx, v(0, 0, 1), v(1, 0, 1)), d11 = Lerp(dx, v(0, 1, 1), v(1, 1, 1));
    return Lerp(dz, Lerp(dy, d00, d10), Lerp(dy, d01, d11));
}

// The spectrum of sample (x, y, z) of a spectrum grid at the path's wavelengths; 0 outside.
LU_INLINE SampledSpectrum GridSpectrum(const SceneView &s, const MediumGrid &g, int x, int y, int z,
                                       const SampledWavelengths &lambda) {
    if (x < 0 || y < 0 || z < 0 || x >= int(g.nx) || y >= int(g.ny) || z >= int(g.nz)) return SampledSpectrum(0);
    const Float *c = s.mediumData.ptr + g.offset + ((uint64_t(z) * g.ny + uint64_t(y)) * g.nx + uint64_t(x)) * 4;
    Spectrum sp;
    sp.kind = g.kind;
    sp.c[0] = c[0];
    sp.c[1] = c[1];
    sp.c[2] = c[2];
    sp.scale = c[3];
    sp.table = IlluminantTable(s, g.colorSpace);
    return SampleSpectrum(sp, lambda, s.spectra);
}

// Trilinear interpolation of the sampled spectra (pbrt-v4's SampledGrid::Lookup with a convert).
LU_INLINE SampledSpectrum LookupGridSpectrum(const SceneView &s, const MediumGrid &g, Vec3f p,
                                             const SampledWavelengths &lambda) {
    Float px = p.x * g.nx - 0.5f, py = p.y * g.ny - 0.5f, pz = p.z * g.nz - 0.5f;
    int ix = int(std::floor(px)), iy = int(std::floor(py)), iz = int(std::floor(pz));
    Float dx = px - ix, dy = py - iy, dz = pz - iz;
    auto v = [&](int a, int b, int c) { return GridSpectrum(s, g, ix + a, iy + b, iz + c, lambda); };
    auto lerp = [](Float t, const SampledSpectrum &a, const SampledSpectrum &b) { return a * (1 - t) + b * t; };
    SampledSpectrum d00 = lerp(dx, v(0, 0, 0), v(1, 0, 0)), d10 = lerp(dx, v(0, 1, 0), v(1, 1, 0));
    SampledSpectrum d01 = lerp(dx, v(0, 0, 1), v(1, 0, 1)), d11 = lerp(dx, v(0, 1, 1), v(1, 1, 1));
    return lerp(dz, lerp(dy, d00, d10), lerp(dy, d01, d11));
}

// pbrt-v4's BlackbodySpectrum: Planck's law normalized to 1 at its peak (Wien's law).
LU_INLINE Float NormalizedBlackbody(Float lambdaNm, Float T) {
    Float lambdaMax = Float(2.8977721e-3 / double(T) * 1e9);
    Float peak = BlackbodyRadiance(lambdaMax, T);
    return peak > 0 ? BlackbodyRadiance(lambdaNm, T) / peak : 0;
}

// ---- pbrt-v4's procedural cloud ----

// pbrt-v4's DNoise: the forward-difference gradient of Noise with step 0.01.
LU_INLINE Vec3f NoiseGradientFD(const Vec3f &p) {
    const Float delta = 0.01f;
    Float n = Noise(p);
    return Vec3f(Noise(p + Vec3f(delta, 0, 0)) - n, Noise(p + Vec3f(0, delta, 0)) - n,
                 Noise(p + Vec3f(0, 0, delta)) - n) / delta;
}

// pbrt-v4's CloudMedium::Density at medium-space point p, in [0, 1]: five octaves of noise at
// frequency * p (its lookup point perturbed by two octaves of the noise gradient, scaled by the
// wispiness), thinning with height y and dense below y = 0.5.
LU_INLINE Float CloudDensity(const Medium &m, const Vec3f &p) {
    Vec3f pp = p * m.frequency;
    if (m.wispiness > 0) {
        Float vOmega = 0.05f * m.wispiness, vLambda = 10;
        for (int i = 0; i < 2; ++i) {
            pp += NoiseGradientFD(pp * vLambda) * vOmega;
            vOmega *= 0.5f;
            vLambda *= 1.99f;
        }
    }
    Float d = 0, omega = 0.5f, lambda = 1;
    for (int i = 0; i < 5; ++i) {
        d += omega * Noise(pp * lambda);
        omega *= 0.5f;
        lambda *= 1.99f;
    }
    d = Clamp((1 - p.y) * 4.5f * m.cloudDensity * d, Float(0), Float(1));
    d += 2 * Max(Float(0), 0.5f - p.y);
    return Clamp(d, Float(0), Float(1));
}

// ---- Scattering properties at a point ----

struct MediumProperties {
    SampledSpectrum sigmaA, sigmaS, Le;
};

// Medium-space point p as [0,1]^3 of the medium's bounds.
LU_INLINE Vec3f BoundsOffset(const Bounds3f &b, const Vec3f &p) {
    Vec3f d = b.pMax - b.pMin;
    return Vec3f((p.x - b.pMin.x) / d.x, (p.y - b.pMin.y) / d.y, (p.z - b.pMin.z) / d.z);
}

// sigma_a, sigma_s and emitted radiance of medium m at render-space point p (pbrt-v4's
// Medium::SamplePoint).
LU_INLINE MediumProperties SampleMediumPoint(const SceneView &s, const Medium &m, const Vec3f &p,
                                             const SampledWavelengths &lambda) {
    MediumProperties mp;
    mp.Le = SampledSpectrum(0);
    switch (m.kind) {
    case MediumKind::Homogeneous:
        mp.sigmaA = SampleSpectrum(m.sigmaA, lambda, s.spectra) * m.sigmaScale;
        mp.sigmaS = SampleSpectrum(m.sigmaS, lambda, s.spectra) * m.sigmaScale;
        if (m.emissive) mp.Le = SampleSpectrum(m.Le, lambda, s.spectra) * m.LeScale;
        return mp;
    case MediumKind::UniformGrid: {
        Vec3f pg = BoundsOffset(m.bounds, m.renderFromMedium.Inverted().ApplyPoint(p));
        Float d = LookupGrid(s, m.density, pg);
        mp.sigmaA = SampleSpectrum(m.sigmaA, lambda, s.spectra) * (m.sigmaScale * d);
        mp.sigmaS = SampleSpectrum(m.sigmaS, lambda, s.spectra) * (m.sigmaScale * d);
        if (m.emissive) {
            Float scale = m.LeGrid.nx > 0 ? LookupGrid(s, m.LeGrid, pg) : m.LeScale;   // nanovdb: constant
            if (scale > 0) {
                if (m.temperature.nx > 0) {
                    Float T = (LookupGrid(s, m.temperature, pg) - m.temperatureOffset) * m.temperatureScale;
                    if (T > 100)
                        for (int i = 0; i < NSpectrumSamples; ++i) mp.Le[i] = scale * NormalizedBlackbody(lambda.lambda[i], T);
                } else {
                    mp.Le = SampleSpectrum(m.Le, lambda, s.spectra) * scale;
                }
            }
        }
        return mp;
    }
    case MediumKind::RGBGrid: {
        Vec3f pg = BoundsOffset(m.bounds, m.renderFromMedium.Inverted().ApplyPoint(p));
        mp.sigmaA = (m.density.nx > 0 ? LookupGridSpectrum(s, m.density, pg, lambda) : SampledSpectrum(1)) * m.sigmaScale;
        mp.sigmaS = (m.density2.nx > 0 ? LookupGridSpectrum(s, m.density2, pg, lambda) : SampledSpectrum(1)) * m.sigmaScale;
        if (m.emissive) mp.Le = LookupGridSpectrum(s, m.LeGrid, pg, lambda) * m.LeScale;
        return mp;
    }
    case MediumKind::Cloud: {
        Float d = CloudDensity(m, m.renderFromMedium.Inverted().ApplyPoint(p));
        mp.sigmaA = SampleSpectrum(m.sigmaA, lambda, s.spectra) * (m.sigmaScale * d);
        mp.sigmaS = SampleSpectrum(m.sigmaS, lambda, s.spectra) * (m.sigmaScale * d);
        return mp;
    }
    }
    mp.sigmaA = mp.sigmaS = SampledSpectrum(0);
    return mp;
}

// ---- Majorants along a ray ----

struct MajorantSegment {
    Float tMin = 0, tMax = 0;
    SampledSpectrum sigmaMaj;
};

// The majorant segments of a ray through a medium, in order (pbrt-v4's HomogeneousMajorantIterator
// and DDAMajorantIterator): one segment for a homogeneous medium, the voxels of the majorant grid
// the ray crosses otherwise.
struct MajorantIterator {
    Float tMin = Infinity, tMax = -Infinity;
    SampledSpectrum sigmaT;               // per unit majorant value
    const MediumGrid *grid = nullptr;     // nullptr: one segment with sigma_maj = sigmaT
    Float nextCrossingT[3], deltaT[3];
    int step[3], voxelLimit[3], voxel[3];

    LU_HD bool Next(const SceneView &s, MajorantSegment *seg) {
        if (!(tMin < tMax)) return false;
        if (!grid) {
            seg->tMin = tMin;
            seg->tMax = tMax;
            seg->sigmaMaj = sigmaT;
            tMin = tMax;
            return true;
        }
        // The axis whose voxel boundary comes first, and the exit point of the voxel.
        int bits = ((nextCrossingT[0] < nextCrossingT[1]) << 2) + ((nextCrossingT[0] < nextCrossingT[2]) << 1) +
                   ((nextCrossingT[1] < nextCrossingT[2]));
        const int cmpToAxis[8] = {2, 1, 2, 1, 2, 2, 0, 0};
        int axis = cmpToAxis[bits];
        Float tExit = Min(tMax, nextCrossingT[axis]);
        seg->tMin = tMin;
        seg->tMax = tExit;
        seg->sigmaMaj = sigmaT * GridValue(s, *grid, voxel[0], voxel[1], voxel[2]);
        tMin = tExit;
        if (nextCrossingT[axis] > tMax) tMin = tMax;
        voxel[axis] += step[axis];
        if (voxel[axis] == voxelLimit[axis]) tMin = tMax;
        nextCrossingT[axis] += deltaT[axis];
        return true;
    }
};

// Parametric range [t0, t1] of ray (o, d) inside box b within [0, tMax]; false if none.
LU_INLINE bool IntersectBounds(const Bounds3f &b, const Vec3f &o, const Vec3f &d, Float tMax, Float *t0, Float *t1) {
    Float a = 0, e = tMax;
    for (int i = 0; i < 3; ++i) {
        Float inv = 1 / d[i];
        Float tNear = (b.pMin[i] - o[i]) * inv, tFar = (b.pMax[i] - o[i]) * inv;
        if (tNear > tFar) Swap(tNear, tFar);
        tFar *= 1 + 2 * 3 * 0x1p-24f;   // pbrt-v4's gamma(3) robustness
        a = tNear > a ? tNear : a;
        e = tFar < e ? tFar : e;
        if (a > e) return false;
    }
    *t0 = a;
    *t1 = e;
    return true;
}

// The majorants of medium m along ray (unit render-space direction) for t in [0, tMax]: the
// homogeneous sigma_t over [0, tMax]; the cloud's sigma_t (its density is at most 1) over its
// bounds, one segment as pbrt-v4; the grids' majorant voxels over their bounds.
LU_INLINE MajorantIterator MediumMajorants(const SceneView &s, const Medium &m, const Ray &ray, Float tMax,
                                           const SampledWavelengths &lambda) {
    MajorantIterator it;
    if (m.kind == MediumKind::Homogeneous) {
        it.tMin = 0;
        it.tMax = tMax;
        it.sigmaT = (SampleSpectrum(m.sigmaA, lambda, s.spectra) + SampleSpectrum(m.sigmaS, lambda, s.spectra)) * m.sigmaScale;
        return it;
    }
    // Medium space keeps the ray parameter t (the direction is not renormalized).
    const Transform mediumFromRender = m.renderFromMedium.Inverted();
    Vec3f o = mediumFromRender.ApplyPoint(ray.o), d = mediumFromRender.ApplyVector(ray.d);
    Float t0, t1;
    if (!IntersectBounds(m.bounds, o, d, tMax, &t0, &t1)) return it;
    it.tMin = t0;
    it.tMax = t1;
    if (m.kind == MediumKind::Cloud) {
        it.sigmaT = (SampleSpectrum(m.sigmaA, lambda, s.spectra) + SampleSpectrum(m.sigmaS, lambda, s.spectra)) * m.sigmaScale;
        return it;
    }
    it.sigmaT = m.kind == MediumKind::RGBGrid
                    ? SampledSpectrum(1)
                    : (SampleSpectrum(m.sigmaA, lambda, s.spectra) + SampleSpectrum(m.sigmaS, lambda, s.spectra)) * m.sigmaScale;
    it.grid = &m.majorant;
    // 3D DDA over the majorant grid, in [0,1]^3 of the bounds.
    Vec3f diag = m.bounds.pMax - m.bounds.pMin;
    Vec3f og = BoundsOffset(m.bounds, o);
    Vec3f dg(d.x / diag.x, d.y / diag.y, d.z / diag.z);
    Vec3f pg = og + dg * t0;
    const int res[3] = {int(m.majorant.nx), int(m.majorant.ny), int(m.majorant.nz)};
    for (int a = 0; a < 3; ++a) {
        it.voxel[a] = Clamp(int(pg[a] * res[a]), 0, res[a] - 1);
        Float da = dg[a] == 0 ? Float(0) : dg[a];   // -0 -> +0
        it.deltaT[a] = 1 / (std::abs(da) * res[a]);
        if (da >= 0) {
            Float next = Float(it.voxel[a] + 1) / res[a];
            it.nextCrossingT[a] = t0 + (next - pg[a]) / da;
            it.step[a] = 1;
            it.voxelLimit[a] = res[a];
        } else {
            Float next = Float(it.voxel[a]) / res[a];
            it.nextCrossingT[a] = t0 + (next - pg[a]) / da;
            it.step[a] = -1;
            it.voxelLimit[a] = -1;
        }
    }
    return it;
}

// Samples tentative collisions along ray (unit direction) in medium m up to tMax against the
// majorants, pbrt-v4's SampleT_maj: for each, callback(p, MediumProperties, sigmaMaj, Tmaj) with
// Tmaj the majorant transmittance since the previous one (or the ray origin); the callback
// returns false to stop. Returns the majorant transmittance from the last collision to tMax
// (1 when the callback stopped the walk). u is the first uniform sample, rng gives the others.
template <typename F>
LU_HD SampledSpectrum SampleTmaj(const SceneView &s, const Medium &m, const Ray &ray, Float tMax, Float u, RNG &rng,
                                 const SampledWavelengths &lambda, F callback) {
    MajorantIterator it = MediumMajorants(s, m, ray, tMax, lambda);
    SampledSpectrum Tmaj(1);
    MajorantSegment seg;
    while (it.Next(s, &seg)) {
        if (seg.sigmaMaj[0] == 0) {
            Float dt = seg.tMax - seg.tMin;
            if (dt == Infinity) dt = FLT_MAX;
            Tmaj *= Exp(seg.sigmaMaj * -dt);
            continue;
        }
        Float t0 = seg.tMin;
        while (true) {
            Float t = t0 + SampleExponential(u, seg.sigmaMaj[0]);
            u = rng.Uniform<Float>();
            if (t < seg.tMax) {
                Tmaj *= Exp(seg.sigmaMaj * -(t - t0));
                Vec3f p = ray(t);
                MediumProperties mp = SampleMediumPoint(s, m, p, lambda);
                if (!callback(p, mp, seg.sigmaMaj, Tmaj)) return SampledSpectrum(1);
                Tmaj = SampledSpectrum(1);
                t0 = t;
            } else {
                Float dt = seg.tMax - t0;
                if (dt == Infinity) dt = FLT_MAX;
                Tmaj *= Exp(seg.sigmaMaj * -dt);
                break;
            }
        }
    }
    return Tmaj;
}

// The medium a ray leaving a surface of `shape` along w enters (n: the oriented geometric
// normal), pbrt-v4's Interaction::GetMedium; `current` when the shape is no medium transition.
LU_INLINE uint32_t MediumAfter(const Shape &shape, const Vec3f &n, const Vec3f &w, uint32_t current) {
    if (!shape.mediumTransition) return current;
    return Dot(w, n) > 0 ? shape.outsideMedium : shape.insideMedium;
}

}  // namespace lu
