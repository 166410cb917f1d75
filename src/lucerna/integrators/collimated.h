// Lucerna: the implicit technique for collimated beams (lights/collimated.h): a ray that crosses a
// beam's disc from its front, within the pass's cone around the beam direction, collects the
// regularized radiance E K / cos, MIS-weighted against the explicit technique (SampleBeamLi in
// next-event estimation, a mixture of cone and disc-area sampling). The discs are not geometry:
// rays pass through them. In media, the beam-segment technique: a distance sampled uniformly
// where a ray segment crosses a beam's region, connected to the beam.
#pragma once

#include "lucerna/integrators/techniques.h"
#include "lucerna/lights/collimated.h"

namespace lu {

// The nearest collimated light whose disc the ray crosses from the front in (0, tMax), other than
// `skip` (the disc the ray was just continued through); NoIndex when none. *t, *y: where.
LU_INLINE uint32_t NearestBeamCrossing(const SceneView &scene, const Ray &ray, Float tMax, uint32_t skip, Float *t,
                                       Vec3f *y) {
    uint32_t found = NoIndex;
    for (uint32_t li = 0; li < scene.lights.size; ++li) {
        const Light &l = scene.lights[li];
        if (l.kind != LightKind::Collimated || li == skip) continue;
        Float tt;
        Vec3f yy;
        if (BeamDiscCrossing(l, ray.o, ray.d, 0, tMax, &tt, &yy)) {
            tMax = tt;
            *t = tt;
            *y = yy;
            found = li;
        }
    }
    return found;
}

// MIS weight of the beam `li` reached along wi (unit) from vertex v, crossing its disc at y at
// distance t, against next-event estimation at v, which samples the same direction with pdfW =
// LightPMF * the mixture of its two techniques (BeamMixturePdfW; both in solid angle at v). No
// explicit technique reaches the beam from the camera or through a Dirac lobe: weight 1 there.
// r: the path's per-wavelength probabilities when it went through a medium (as EmitterHitWeight).
LU_INLINE Float BeamHitWeight(const ScatterVertex &v, const SceneView &scene, uint32_t li, Vec3f wi, Vec3f y, Float t,
                              const PathSettings &ps, const WavelengthPdfs *r, const SampledWavelengths &lambda) {
    if (v.camera || (v.specular && !v.regularized)) return r ? WavelengthWeight(r->u, 1, r->l, 0, lambda) : 1;
    // A medium vertex inside the beam's region: the beam-segment technique estimates its light.
    if (v.beamRegions && InBeamRegion(scene.lights[li], v.ctx.p, BeamRegionRadius(scene.lights[li], BeamOneMinusCos(ps.reg))))
        return 0;
    Float pdfLightW = LightPMF(scene, li) * BeamMixturePdfW(scene.lights[li], y, t, -wi, BeamOneMinusCos(ps.reg));
    if (v.specular) {
        // After a Dirac lobe where the regularized connection ran (a non-specular vertex came
        // before): its partner is the connection to this beam, lobe-aware as for area lights
        // (EmitterHitWeight), the light picked among the connection's candidates.
        pdfLightW /= v.candidatePmf;
        Float pdfConeW = v.pdfBsdfW * ConePdfW(RegularizedOneMinusCos(ps.reg, t));
        if (!r) return RegularizedHitWeight(pdfConeW, pdfLightW);
        return RegularizedHitWeight(pdfConeW, r->l[0] * pdfLightW) * WavelengthWeight(r->u, pdfConeW, r->l, pdfLightW, lambda);
    }
    if (ps.strategy == LightStrategy::BSDFOnly) return r ? WavelengthWeight(r->u, 1, r->l, 0, lambda) : 1;
    if (ps.strategy == LightStrategy::NEEOnly) return 0;
    if (!r) return BSDFHitWeight(ps.strategy, v.pdfBsdfW, pdfLightW);
    return BSDFHitWeight(ps.strategy, v.pdfBsdfW, r->l[0] * pdfLightW) *
           WavelengthWeight(r->u, v.pdfBsdfW, r->l, pdfLightW, lambda);
}

// The weighted regularized radiance the ray from v collects where it crosses beam li at y.
LU_INLINE SampledSpectrum BeamHitLe(const ScatterVertex &v, const SceneView &scene, uint32_t li, const Ray &ray, Vec3f y,
                                    const PathSettings &ps, const WavelengthPdfs *r, const SampledWavelengths &lambda) {
    Vec3f wi = Normalize(ray.d);
    SampledSpectrum Le = BeamRadiance(scene.lights[li], scene, y, -wi, BeamOneMinusCos(ps.reg), lambda);
    if (Le.IsBlack()) return Le;
    // The distance from the vertex (the ray may start where it crossed another beam).
    return Le * BeamHitWeight(v, scene, li, wi, y, Distance(v.ctx.p, y), ps, r, lambda);
}

// ---- The beam-segment technique (media) ----
// The beams' light scattered once at the medium points of a ray segment x(t) = o + t d,
// 0 < t < tEnd, in one medium: for each beam whose region (lights/collimated.h) the segment
// crosses in (t0, t1), a distance t uniform in it (pdf 1 / (t1 - t0)) and next-event estimation
// from x(t) to that beam (SampleBeamLi, weight 1):
//     T(o, x) sigma_s(x) p(-d, wi) T(x, y) L_r(y, -wi) / (pdf_t pdf_a).
// Free-flight vertices inside a beam's region give that beam up (weight 0 on both of their
// techniques, in SampleLd and BeamHitWeight); outside it they keep it. The region is a function of
// the point alone, so the two partition the medium points, and every path through a medium point
// to a beam is estimated once. A free-flight vertex hits a beam of 2 cm with a probability of
// about sigma_s x 4 cm, 1% in a light haze; the segment technique connects every camera ray that
// crosses it. Off with --beam-segments false and with --light-strategy bsdf. Spectral MIS: the positions are sampled the same way at every wavelength, the
// transmittance estimates (ratio tracking in heterogeneous media) as a shadow ray's.
LU_INLINE bool UsesBeamSegments(const PathSettings &ps, const SceneView &scene) {
    return ps.beamSegments && ps.reg.enabled && scene.collimatedLights > 0 && ps.strategy != LightStrategy::BSDFOnly;
}

// The technique's radiance for `ray` (any direction length) in `medium` up to ray parameter tEnd,
// to be multiplied by the path throughput at the ray's origin (depth: the path's depth there; the
// scattering vertex would be depth + 1). r: the path's per-wavelength probabilities.
template <typename Tracer>
LU_HD SampledSpectrum BeamSegmentsLi(const Ray &ray, Float tEnd, uint32_t medium, const WavelengthPdfs &r,
                                     const SampledWavelengths &lambda, Sampler &sampler, const SceneView &scene,
                                     const Tracer &tracer, const PathSettings &ps, PathStats &st) {
    SampledSpectrum L(0);
    Float len = Length(ray.d);
    if (!(len > 0)) return L;
    Ray ru;
    ru.o = ray.o;
    ru.d = ray.d / len;
    Float tMax = tEnd * len;
    Float omc = BeamOneMinusCos(ps.reg);
    const Medium &m = scene.media[medium];
    PhaseScatter phase{m.g};
    VertexMedia vm;
    vm.medium = medium;
    vm.r = &r;
    for (uint32_t li = 0; li < scene.lights.size; ++li) {
        const Light &l = scene.lights[li];
        if (l.kind != LightKind::Collimated) continue;
        Float t0, t1;
        if (!BeamRegionInterval(l, ru.o, ru.d, tMax, BeamRegionRadius(l, omc), &t0, &t1)) continue;
        Float ut = sampler.Get1D();
        Vec2f u2 = sampler.Get2D();
        Float t = Min(t1, t0 + ut * (t1 - t0)), pdfT = 1 / (t1 - t0);
        if (!(pdfT > 0) || !(pdfT < Infinity)) continue;
        LightSampleContext ctx;
        ctx.p = ru.o + ru.d * t;
        LightLiSample ls;
        if (!SampleBeamLi(l, scene, ctx, u2, omc, lambda, &ls)) continue;
        SampledSpectrum f = phase.f(-ru.d, ls.wi);
        if (f.IsBlack()) continue;
        // The transmittance o -> x (this medium), the scattering coefficient at x, then x -> y.
        ShadowTransmittance trSeg;
        RNG rng(Hash(ctx.p.x, ctx.p.y, ctx.p.z), Hash(ru.d.x, ru.d.y, ru.d.z));
        if (!RayTransmittance(scene, medium, ru, t, lambda, rng, &trSeg)) continue;
        MediumProperties mp = SampleMediumPoint(scene, m, ctx.p, lambda);
        if (mp.sigmaS.IsBlack()) continue;
        Ray shadow = SpawnShadowRay(ctx.p, ctx.n, ls.wi, ls.distance, ls.pLight);
        ShadowTransmittance tr;
        if (!ShadowRayVisible(scene, tracer, shadow, vm, ls.wi, lambda, st, &tr)) continue;
        SampledSpectrum q = r.u * trSeg.sL * tr.sL;
        L += trSeg.T * mp.sigmaS * f * tr.T * ls.L * (WavelengthWeight(q, 1, q, 0, lambda) / (pdfT * ls.pdf));
    }
    return L;
}

}  // namespace lu
