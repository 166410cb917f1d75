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
    return ps.beamSegments && ps.reg.enabled && scene.collimatedLights > 0 && scene.media.size > 0 &&
           ps.strategy != LightStrategy::BSDFOnly;
}

// The last link of both beam techniques in media: the medium point xp (in `medium`), reached along
// the unit direction d, scatters the beam sample ls towards -d: sigma_s(xp) p(-d, ls.wi)
// T(xp, y) L_r / pdf_a. *sL: the beam shadow ray's per-wavelength probabilities. Black when xp
// does not scatter or the beam is hidden.
template <typename Tracer>
LU_HD SampledSpectrum BeamInScatter(const LightLiSample &ls, Vec3f xp, uint32_t medium, Vec3f d,
                                    const SampledWavelengths &lambda, const SceneView &scene, const Tracer &tracer,
                                    PathStats &st, SampledSpectrum *sL) {
    const Medium &m = scene.media[medium];
    SampledSpectrum f = PhaseScatter{m.g}.f(-d, ls.wi);
    if (f.IsBlack()) return f;
    MediumProperties mp = SampleMediumPoint(scene, m, xp, lambda);
    if (mp.sigmaS.IsBlack()) return mp.sigmaS;
    Ray toBeam = SpawnShadowRay(xp, Vec3f(0, 0, 0), ls.wi, ls.distance, ls.pLight);
    ShadowTransmittance tr;
    ++st.rays; ++st.shadowRays;
    if (!TraceTransmittance(scene, tracer, toBeam, medium, lambda, st, &tr)) return SampledSpectrum(0);
    *sL = tr.sL;
    return mp.sigmaS * f * tr.T * ls.L / ls.pdf;
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
        // The transmittance o -> x (this medium), then x's scattering of the beam.
        ShadowTransmittance trSeg;
        RNG rng(Hash(ctx.p.x, ctx.p.y, ctx.p.z), Hash(ru.d.x, ru.d.y, ru.d.z));
        if (!RayTransmittance(scene, medium, ru, t, lambda, rng, &trSeg)) continue;
        SampledSpectrum sL;
        SampledSpectrum in = BeamInScatter(ls, ctx.p, medium, ru.d, lambda, scene, tracer, st, &sL);
        if (in.IsBlack()) continue;
        SampledSpectrum q = r.u * trSeg.sL * sL;
        L += trSeg.T * in * (WavelengthWeight(q, 1, q, 0, lambda) / pdfT);
    }
    return L;
}

// ---- The beam's scattered light seen from a vertex (media) ----
// At a non-specular vertex x (surface or medium) the paths x -> x' -> beam with x' a medium point
// in the beam's region are sampled from x: x' on the beam, its distance along the axis s
// equiangular as seen from x (density D / ((theta_b - theta_a)(D^2 + (s - s_x)^2)) on [0, L], D
// the distance of x from the axis, at least R), uniform across the disc of radius R + s tan sigma
// (outside it nothing sees the regularized beam), shadow rays x -> x' and x' -> beam (SampleBeamLi):
//     f(x) T(x, x') sigma_s(x') p(x') T(x', y) L_r / (pdf_V |x' - x|^2 pdf_a).
// These paths have three techniques: this one, the beam-segment technique on the segment that
// leaves x, and free flight on it. Inside the region free flight gives the beam up (see above),
// and the segment technique runs only on segments that leave the camera or a Dirac lobe (where
// nothing can connect); from a non-specular vertex this one takes them all. A random direction
// from x meets a 2 cm beam in a small solid angle: the light the beam scatters into the haze
// around it, onto the walls and back into the beam would otherwise be speckle.
template <typename Scatter, typename Tracer>
LU_HD SampledSpectrum BeamScatterLd(const LightSampleContext &ctx, Vec3f wo, const Scatter &sc, const VertexMedia &vm,
                                    const SampledWavelengths &lambda, Sampler &sampler, const SceneView &scene,
                                    const Tracer &tracer, const PathSettings &ps, PathStats &st) {
    SampledSpectrum L(0);
    Float omc = BeamOneMinusCos(ps.reg);
    Float cosS = 1 - omc, sinS = SafeSqrt(omc * (2 - omc));
    if (!(omc > 0) || !(cosS > 0)) return L;
    Float tanS = sinS / cosS;
    SampledSpectrum prefix = vm.r ? vm.r->u : SampledSpectrum(1);
    for (uint32_t li = 0; li < scene.lights.size; ++li) {
        const Light &l = scene.lights[li];
        if (l.kind != LightKind::Collimated) continue;
        Float u1 = sampler.Get1D();
        Vec2f u2 = sampler.Get2D(), u3 = sampler.Get2D();
        // The axial distance, equiangular from x.
        Vec3f q = ctx.p - l.position;
        Float sx = Dot(q, l.direction), reach = BeamReach(l);
        Float D = Max(Length(q - l.direction * sx), l.beamRadius);
        Float ta = std::atan2(-sx, D), tb = std::atan2(reach - sx, D);
        if (!(tb > ta)) continue;
        Float s = sx + D * std::tan(ta + u1 * (tb - ta));
        if (!(s > 0 && s < reach)) continue;
        Float pdfS = D / ((tb - ta) * (Sqr(D) + Sqr(s - sx)));
        // Across the blurred beam.
        Float Rl = l.beamRadius + s * tanS;
        Vec2f dxy = SampleUniformDiskConcentric(u2) * Rl;
        Frame f = Frame::FromZ(l.direction);
        Vec3f xp = l.position + l.direction * s + f.FromLocal(Vec3f(dxy.x, dxy.y, 0));
        if (!InBeamRegion(l, xp, BeamRegionRadius(l, omc))) continue;   // free flight's
        Float pdfV = pdfS / (Pi * Sqr(Rl));
        Vec3f d = xp - ctx.p;
        Float dist2 = LengthSquared(d);
        if (!(dist2 > 0) || !(pdfV > 0)) continue;
        Vec3f wi = d / std::sqrt(dist2);
        SampledSpectrum fx = sc.f(wo, wi);
        if (fx.IsBlack()) continue;
        // x' must see the beam.
        LightSampleContext cp;
        cp.p = xp;
        LightLiSample ls;
        if (!SampleBeamLi(l, scene, cp, u3, omc, lambda, &ls)) continue;
        Ray toX = SpawnShadowRay(ctx.p, ctx.n, wi, std::sqrt(dist2), xp);
        ShadowTransmittance tr1;
        uint32_t mp = NoIndex;
        ++st.rays; ++st.shadowRays;
        if (!TraceTransmittance(scene, tracer, toX, vm.Toward(wi), lambda, st, &tr1, &mp) || mp == NoIndex) continue;
        SampledSpectrum sL;
        SampledSpectrum in = BeamInScatter(ls, xp, mp, wi, lambda, scene, tracer, st, &sL);
        if (in.IsBlack()) continue;
        SampledSpectrum qw = prefix * tr1.sL * sL;
        L += fx * tr1.T * in * (WavelengthWeight(qw, 1, qw, 0, lambda) / (pdfV * dist2));
    }
    return L;
}

}  // namespace lu
