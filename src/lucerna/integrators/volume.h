// Lucerna: the path integrator in participating media (host and device), after pbrt-v4's
// VolPathIntegrator: delta tracking of a path segment against the majorants (absorption, real and
// null collisions, emission), and the transmittance of a shadow ray through interfaces and media
// (ratio tracking; exact for homogeneous media). Both keep pbrt-v4's rescaled per-wavelength path
// probabilities (WavelengthPdfs, integrators/mis.h) for the spectral MIS of chromatic media.
#pragma once

#include "lucerna/geometry/shapes.h"
#include "lucerna/integrators/mis.h"
#include "lucerna/integrators/stats.h"
#include "lucerna/media/medium.h"
#include "lucerna/sampling/sampler.h"

namespace lu {

// ---- A path segment through a medium (delta tracking) ----

enum class MediumEvent : uint8_t { Passed, Scattered, Terminated };

// Samples the segment [0, tMax] of `ray` (any direction length; tMax in its units) in medium
// `medium`, pbrt-v4's "Sample the participating medium": adds the medium's emission at every
// tentative collision to L (weighted over the wavelengths), and returns Scattered with the real
// scattering point in *pScatter, Terminated (absorbed, or the depth limit at a real collision), or
// Passed (no real collision: beta and r then carry the transmittance to tMax). beta and r.u are
// updated for the collisions sampled; r.l (and r.lChain) with the probabilities of the light technique's
// transmittance estimate (TraceTransmittance): ratio tracking, or 1 for a homogeneous medium,
// whose transmittance it computes exactly. Consumes three sampler dimensions.
LU_HD inline MediumEvent SampleMediumSegment(const SceneView &scene, uint32_t medium, const Ray &ray, Float tMax,
                                             const SampledWavelengths &lambda, Sampler &sampler, int depth, int maxDepth,
                                             SampledSpectrum &beta, WavelengthPdfs &r, SampledSpectrum &L, Vec3f *pScatter) {
    const Medium &m = scene.media[medium];
    Float len = Length(ray.d);
    Ray ru;
    ru.o = ray.o;
    ru.d = ray.d / len;
    tMax *= len;
    uint64_t h0 = Hash(sampler.Get1D()), h1 = Hash(sampler.Get1D());
    RNG rng(h0, h1);
    Float u = sampler.Get1D();
    MediumEvent event = MediumEvent::Passed;
    SampledSpectrum Tmaj = SampleTmaj(scene, m, ru, tMax, u, rng, lambda,
        [&](Vec3f p, const MediumProperties &mp, const SampledSpectrum &sigmaMaj, const SampledSpectrum &Tm) {
            // Emission at the collision (absorption sampled with probability 1 for it).
            if (depth < maxDepth && !mp.Le.IsBlack()) {
                Float pdf = sigmaMaj[0] * Tm[0];
                SampledSpectrum betap = beta * Tm / pdf, rE = r.u * sigmaMaj * Tm / pdf;
                if (!rE.IsBlack()) L += betap * mp.sigmaA * mp.Le * WavelengthWeight(rE, 1, rE, 0, lambda);
            }
            Float pAbsorb = mp.sigmaA[0] / sigmaMaj[0], pScat = mp.sigmaS[0] / sigmaMaj[0];
            Float um = rng.Uniform<Float>();
            if (um < pAbsorb) {
                event = MediumEvent::Terminated;
                return false;
            }
            if (um < pAbsorb + pScat) {
                if (depth >= maxDepth) {
                    event = MediumEvent::Terminated;
                    return false;
                }
                Float pdf = Tm[0] * mp.sigmaS[0];
                beta *= Tm * mp.sigmaS / pdf;
                r.u *= Tm * mp.sigmaS / pdf;
                event = (!beta.IsBlack() && !r.u.IsBlack()) ? MediumEvent::Scattered : MediumEvent::Terminated;
                *pScatter = p;
                return false;
            }
            // Null collision.
            SampledSpectrum sigmaN = ClampZero(sigmaMaj - mp.sigmaA - mp.sigmaS);
            Float pdf = Tm[0] * sigmaN[0];
            if (pdf == 0) {
                event = MediumEvent::Terminated;
                return false;
            }
            beta *= Tm * sigmaN / pdf;
            r.u *= Tm * sigmaN / pdf;
            r.l *= Tm * sigmaMaj / pdf;
            r.lChain *= Tm * sigmaMaj / pdf;
            return !beta.IsBlack() && !r.u.IsBlack();
        });
    if (event != MediumEvent::Passed) return event;
    if (!(Tmaj[0] > 0) || beta.IsBlack() || r.u.IsBlack()) return MediumEvent::Terminated;
    beta *= Tmaj / Tmaj[0];
    r.u *= Tmaj / Tmaj[0];
    if (m.kind == MediumKind::Homogeneous) {
        r.l /= Tmaj[0];
        r.lChain /= Tmaj[0];
    } else {
        r.l *= Tmaj / Tmaj[0];
        r.lChain *= Tmaj / Tmaj[0];
    }
    return MediumEvent::Passed;
}

// ---- Shadow rays through interfaces and media ----

// The transmittance estimate of a shadow ray, relative to the probability of the light
// technique's own samples at the hero wavelength, and the per-wavelength probabilities of the
// segment under the light technique (sL, sL[0] == 1) and under unidirectional sampling (sU).
struct ShadowTransmittance {
    SampledSpectrum T = SampledSpectrum(1), sU = SampledSpectrum(1), sL = SampledSpectrum(1);
    bool throughMedium = false;
};

// Ratio tracking over [0, tMax] of a unit-direction ray in medium m (pbrt-v4's SampleLd), or the
// exact transmittance of a homogeneous medium (residual ratio tracking with the medium itself as
// control: no collisions to sample).
LU_HD inline void SegmentTransmittance(const SceneView &scene, const Medium &m, const Ray &ray, Float tMax,
                                       const SampledWavelengths &lambda, RNG &rng, ShadowTransmittance *tr) {
    if (m.kind == MediumKind::Homogeneous) {
        SampledSpectrum sigmaT =
            (SampleSpectrum(m.sigmaA, lambda, scene.spectra) + SampleSpectrum(m.sigmaS, lambda, scene.spectra)) * m.sigmaScale;
        SampledSpectrum Tr = Exp(sigmaT * -tMax);
        tr->T *= Tr;
        tr->sU *= Tr;
        return;
    }
    SampledSpectrum &T = tr->T, &sU = tr->sU, &sL = tr->sL;
    Float u = rng.Uniform<Float>();
    SampledSpectrum Tmaj = SampleTmaj(scene, m, ray, tMax, u, rng, lambda,
        [&](Vec3f, const MediumProperties &mp, const SampledSpectrum &sigmaMaj, const SampledSpectrum &Tm) {
            SampledSpectrum sigmaN = ClampZero(sigmaMaj - mp.sigmaA - mp.sigmaS);
            Float pdf = Tm[0] * sigmaMaj[0];
            T *= Tm * sigmaN / pdf;
            sL *= Tm * sigmaMaj / pdf;
            sU *= Tm * sigmaN / pdf;
            // Russian roulette on strongly attenuated estimates (pbrt-v4: below 0.05, q = 0.75).
            SampledSpectrum Tr = T / (sL + sU).Average();
            if (Tr.MaxValue() < 0.05f) {
                if (rng.Uniform<Float>() < 0.75f) T = SampledSpectrum(0);
                else T /= 0.25f;
            }
            return !T.IsBlack();
        });
    if (T.IsBlack() || !(Tmaj[0] > 0)) {
        T = SampledSpectrum(0);
        return;
    }
    T *= Tmaj / Tmaj[0];
    sL *= Tmaj / Tmaj[0];
    sU *= Tmaj / Tmaj[0];
}

// SegmentTransmittance of medium `medium` over ray parameters [0, t] of `ray` (any direction
// length), marking tr as through a medium. False when the estimate is 0.
LU_HD inline bool RayTransmittance(const SceneView &scene, uint32_t medium, const Ray &ray, Float t,
                                   const SampledWavelengths &lambda, RNG &rng, ShadowTransmittance *tr) {
    tr->throughMedium = true;
    Float len = Length(ray.d);
    Ray ru;
    ru.o = ray.o;
    ru.d = ray.d / len;
    SegmentTransmittance(scene, scene.media[medium], ru, t * len, lambda, rng, tr);
    return !tr->T.IsBlack();
}

// The transmittance along shadow ray `ray` (from SpawnShadowRay: towards the point ray.o + ray.d
// up to ray.tMax, or along a unit direction to infinity) that starts in `medium`: interface
// surfaces (no material) are crossed, changing the medium as pbrt-v4's MediumInterface says; any
// other surface blocks it. False when blocked or the estimate is 0. *endMedium (if given): the
// medium at the ray's end.
template <typename Tracer>
LU_HD bool TraceTransmittance(const SceneView &scene, const Tracer &tracer, Ray ray, uint32_t medium,
                              const SampledWavelengths &lambda, PathStats &st, ShadowTransmittance *tr,
                              uint32_t *endMedium = nullptr) {
    const bool toPoint = ray.tMax != Infinity;
    const Vec3f target = ray.o + ray.d;
    RNG rng(Hash(ray.o.x, ray.o.y, ray.o.z), Hash(ray.d.x, ray.d.y, ray.d.z));
    for (int crossing = 0; crossing < 256; ++crossing) {
        HitRecord hit;
        bool found = tracer.Intersect(ray, &hit);
        if (found && scene.shapes[hit.shape].material != NoIndex) return false;
        if (medium != NoIndex && !RayTransmittance(scene, medium, ray, found ? hit.t : ray.tMax, lambda, rng, tr))
            return false;
        if (!found) {
            if (endMedium) *endMedium = medium;
            return true;
        }
        // Cross the interface.
        SurfaceInteraction si = ComputeInteraction(scene, hit, ray);
        medium = MediumAfter(scene.shapes[hit.shape], si.n, ray.d, medium);
        ray.o = OffsetRayOrigin(si.p, si.n, ray.d);
        if (toPoint) {
            ray.d = target - ray.o;
            ray.tMax = 1 - 1e-4f;
        }
        ++st.rays;
    }
    return false;
}

}  // namespace lu
