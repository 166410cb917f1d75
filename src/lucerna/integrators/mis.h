// Lucerna: multiple importance sampling of the path integrator in one place: the weight of each
// technique for a path it sampled, and the light pick the explicit techniques share (Veach 1997,
// ch. 9; the regularized pair after Bogolepov et al., see docs/regularization.md). PDFs are named
// by measure: pdfW is solid angle at the vertex that connects, pdfA area at the light point; the
// two pdfs given to one weight always share a measure.
#pragma once

#include "lucerna/integrators/regularization.h"
#include "lucerna/lights/collimated.h"
#include "lucerna/lights/lights.h"
#include "lucerna/sampling/mis.h"

namespace lu {

// Which unbiased techniques estimate direct light (tests compare them; renders use MIS).
enum class LightStrategy : uint8_t { MIS, NEEOnly, BSDFOnly };

// ---- Weights ----

// Next-event estimation at a non-specular vertex against BSDF sampling of the same direction.
// Delta lights have no BSDF-sampling partner (the caller skips the weight: it is 1).
LU_INLINE Float LightSampleWeight(Float pdfLightW, Float pdfBsdfW) { return PowerHeuristic(pdfLightW, pdfBsdfW); }

// BSDF sampling that hit an emitter after a non-specular vertex, against next-event estimation.
LU_INLINE Float BSDFHitWeight(LightStrategy s, Float pdfBsdfW, Float pdfLightW) {
    if (s == LightStrategy::NEEOnly) return 0;
    if (s == LightStrategy::BSDFOnly) return 1;
    return PowerHeuristic(pdfBsdfW, pdfLightW);
}

// The regularized connection at a specular vertex (explicit, biased) against the implicit
// technique, BSDF sampling of the Dirac lobe that hits the emitter, whose pdf for the comparison
// is the cone kernel's: pdfConeW = ConePdfW(...) (the ratio of the two pdfs is the same in area
// measure at the light point: both convert with cos theta_z / d^2). Delta lights have no implicit
// technique: pdfLightW = Infinity gives the connection weight 1 and the hit weight 0.
LU_INLINE Float RegularizedConnectionWeight(Float pdfConeW, Float pdfLightW) {
    if (pdfLightW == Infinity) return 1;
    Float a = Sqr(pdfLightW), b = Sqr(pdfConeW);
    if (b == Infinity) return 0;
    return a + b > 0 ? a / (a + b) : 0;
}
LU_INLINE Float RegularizedHitWeight(Float pdfConeW, Float pdfLightW) {
    if (pdfLightW == Infinity) return 0;
    Float a = Sqr(pdfConeW), b = Sqr(pdfLightW);
    if (a == Infinity) return 1;
    return a + b > 0 ? a / (a + b) : 1;
}

// Manifold NEE (explicit, unbiased) against BSDF sampling of the same refractive chain, both in
// area measure at the light point: pdfA is the technique's own, pdfOtherA the other's.
LU_INLINE Float MneeWeight(Float pdfA, Float pdfOtherA) { return PowerHeuristic(pdfA, pdfOtherA); }
// ---- Through media: the wavelengths as techniques (pbrt-v4's VolPathIntegrator) ----

// pbrt-v4's rescaled path probabilities r_u, r_l: per wavelength, the probability density of the
// path so far relative to the one it was sampled with at the hero wavelength (lambda[0]), under
// unidirectional sampling (u) and, for its last segment, under the explicit technique of the
// vertex it left (l: light sampling, whose transmittance is estimated by ratio tracking). Chromatic
// media make them differ between wavelengths, null collisions between u and l. Paths that never
// entered a medium keep them 1 and are weighted by the scalar functions above.
// lChain is l for the whole refractive chain since the last non-specular vertex x0 (surface or
// medium): manifold NEE from x0 estimates the transmittance of every segment of the chain, not
// only of the last one (reset to u at non-specular vertices only).
struct WavelengthPdfs {
    SampledSpectrum u = SampledSpectrum(1), l = SampledSpectrum(1), lChain = SampledSpectrum(1);
};

// The wavelength part of the weight of technique t for a path it sampled at the hero wavelength,
// against technique o: pT = rT * pdfT and pO = rO * pdfO per wavelength (pdfO = 0: no second
// technique; pdfT = Infinity: a delta light, no second technique). The balance heuristic over the
// wavelengths (a one-sample choice: Veach 1997, 9.2.4), to be multiplied by the technique weight
// at the hero wavelength; these products add up to 1 over all techniques and wavelengths. 1 once
// the secondary wavelengths are terminated (only the hero remains).
LU_INLINE Float WavelengthWeight(const SampledSpectrum &rT, Float pdfT, const SampledSpectrum &rO, Float pdfO,
                                 const SampledWavelengths &lambda) {
    if (lambda.SecondaryTerminated()) return 1;
    SampledSpectrum q = (pdfO > 0 && pdfT != Infinity) ? rT * pdfT + rO * pdfO : rT;
    Float avg = q.Average();
    return avg > 0 ? q[0] / avg : 0;
}

// ---- The light pick of the explicit techniques ----

struct LightPick {
    uint32_t light = NoIndex;
    Float pmf = 0;
};

// Chooses a light (power light sampler); light == NoIndex when the scene has none.
LU_INLINE LightPick PickLight(const SceneView &scene, Float u) {
    LightPick pick;
    pick.light = SampleLight(scene, u, &pick.pmf);
    return pick;
}

// Whether the explicit techniques use pbrt-v4's MIS-aware light sampling (allowIncompletePDF):
// a uniform infinite light is then left to BSDF sampling alone, an image light is sampled where
// it exceeds its average. Only when BSDF sampling is their MIS partner; the same flag on both
// sides of every weight (light samples and emitter hits).
LU_INLINE bool AllowIncompletePDF(LightStrategy s) { return s == LightStrategy::MIS; }

// A point on the picked light seen from ctx: false when the light gives nothing there.
// pdfLightW of the sample = pick.pmf * ls->pdf (ls->pdf is the light's own solid-angle pdf).
// beamOneMinusCos: the pass's cone for collimated beams (BeamOneMinusCos; 0: they give nothing).
LU_INLINE bool SampleLightPoint(const SceneView &scene, const Light &light, const LightSampleContext &ctx, Vec2f u,
                                const SampledWavelengths &lambda, bool allowIncompletePDF, LightLiSample *ls,
                                Float beamOneMinusCos = 0) {
    if (light.kind == LightKind::Collimated) return SampleBeamLi(light, scene, ctx, u, beamOneMinusCos, lambda, ls);
    return SampleLi(light, scene, ctx, u, lambda, ls, allowIncompletePDF) && ls->pdf != 0 && !ls->L.IsBlack();
}

// The light sampler's solid-angle pdf at ctx for emitter `li` seen along wi at pLight (normal nLight).
LU_INLINE Float LightPdfW(const SceneView &scene, uint32_t li, const LightSampleContext &ctx, Vec3f wi, Vec3f pLight,
                          Vec3f nLight, bool allowIncompletePDF) {
    return LightPMF(scene, li) * PDF_Li(scene.lights[li], scene, ctx, wi, pLight, nLight, allowIncompletePDF);
}

}  // namespace lu
