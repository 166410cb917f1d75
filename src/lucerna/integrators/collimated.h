// Lucerna: the implicit technique for collimated beams (lights/collimated.h): a ray that crosses a
// beam's disc from its front, within the pass's cone around the beam direction, collects the
// regularized radiance E K / cos, MIS-weighted against the explicit technique (SampleBeamLi in
// next-event estimation, a mixture of cone and disc-area sampling). The discs are not geometry:
// rays pass through them.
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

}  // namespace lu
