// Lucerna: the per-path integrator body shared by the CPU and CUDA backends: unidirectional path
// tracing with next-event estimation and BSDF sampling combined by MIS (power heuristic), as
// pbrt-v4's PathIntegrator, plus the regularized explicit technique at specular vertices
// (integrators/regularization.h). Backends supply a Tracer with
//     bool Intersect(const Ray &, HitRecord *) const;   bool Occluded(const Ray &) const;
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"
#include "lucerna/camera/camera.h"
#include "lucerna/camera/filter.h"
#include "lucerna/geometry/shapes.h"
#include "lucerna/integrators/regularization.h"
#include "lucerna/lights/lights.h"
#include "lucerna/materials/bsdf.h"
#include "lucerna/sampling/sampler.h"

namespace lu {

// Which unbiased techniques estimate direct light (tests compare them; renders use MIS).
enum class LightStrategy : uint8_t { MIS, NEEOnly, BSDFOnly };

struct PathSettings {
    int maxDepth = 5;
    LightStrategy strategy = LightStrategy::MIS;
    RegularizationParams reg;
};

// Counters of one path (summed by the backend).
struct PathStats {
    uint64_t rays = 0;               // camera + extension + shadow rays
    uint64_t shadowRays = 0;
    uint64_t regConnections = 0;     // regularized connections that contributed
    Float regEnergy = 0;             // luminance-like sum (average over wavelengths) they carried
    Float totalEnergy = 0;           // same for the whole path
};

// Shadow ray from p (offset along n towards the light) to the point pLight (or to infinity along wi).
LU_INLINE Ray SpawnShadowRay(const Vec3f &p, const Vec3f &n, const Vec3f &wi, Float distance, const Vec3f &pLight) {
    Ray r;
    r.o = OffsetRayOrigin(p, n, wi);
    if (distance == Infinity) {
        r.d = wi;
        r.tMax = Infinity;
    } else {
        Vec3f target = pLight;
        r.d = target - r.o;
        r.tMax = 1 - 1e-4f;   // the light surface itself is excluded
    }
    return r;
}

LU_INLINE LightSampleContext MakeLightContext(const SurfaceInteraction &si) {
    LightSampleContext ctx;
    ctx.p = si.p;
    ctx.n = si.n;
    ctx.ns = si.ns;
    return ctx;
}

// Next-event estimation with MIS at a non-specular vertex (pbrt-v4 PathIntegrator::SampleLd).
template <typename Tracer>
LU_HD SampledSpectrum SampleLd(const SurfaceInteraction &si, const BSDF &bsdf, const SampledWavelengths &lambda,
                               Sampler &sampler, const SceneView &scene, const Tracer &tracer, PathStats &st,
                               LightStrategy strategy = LightStrategy::MIS) {
    Float uLight = sampler.Get1D();
    Vec2f u2 = sampler.Get2D();
    Float pmf = 0;
    uint32_t li = SampleLight(scene, uLight, &pmf);
    if (li == NoIndex || pmf == 0) return SampledSpectrum(0);
    const Light &light = scene.lights[li];
    LightLiSample ls;
    if (!SampleLi(light, scene, MakeLightContext(si), u2, lambda, &ls) || ls.pdf == 0 || ls.L.IsBlack())
        return SampledSpectrum(0);
    SampledSpectrum f = bsdf.f(si.wo, ls.wi) * AbsDot(ls.wi, si.ns);
    if (f.IsBlack()) return SampledSpectrum(0);
    Ray shadow = SpawnShadowRay(si.p, si.n, ls.wi, ls.distance, ls.pLight);
    ++st.rays; ++st.shadowRays;
    if (tracer.Occluded(shadow)) return SampledSpectrum(0);
    Float pL = pmf * ls.pdf;
    if (ls.isDelta || strategy == LightStrategy::NEEOnly) return f * ls.L / pL;
    Float pB = bsdf.PDF(si.wo, ls.wi);
    return f * ls.L * (PowerHeuristic(pL, pB) / pL);
}

// The regularized explicit technique at a specular vertex: one light sample, tested against the
// cone of every Dirac lobe. Returns the MIS-weighted contribution (without the path throughput).
// A light that no lobe's cone can reach is not sampled (same random numbers consumed, same result).
template <typename Tracer>
LU_HD SampledSpectrum SampleRegularized(const SurfaceInteraction &si, const BSDF &bsdf, const SampledWavelengths &lambda,
                                        Sampler &sampler, const SceneView &scene, const Tracer &tracer,
                                        const RegularizationParams &rp, PathStats &st) {
    Float uLight = sampler.Get1D();
    Vec2f u2 = sampler.Get2D();
    Float pmf = 0;
    uint32_t li = SampleLight(scene, uLight, &pmf);
    if (li == NoIndex || pmf == 0) return SampledSpectrum(0);
    const Light &light = scene.lights[li];
    SpecularLobe lobes[2];
    int n = bsdf.SpecularLobes(si.wo, lobes);
    if (light.boundRadius >= 0) {
        bool reachable = false;
        for (int i = 0; i < n; ++i)
            reachable |= RegularizedConeMayReach(si.p, lobes[i].wi, light.boundCenter, light.boundRadius, rp.radius);
        if (!reachable) return SampledSpectrum(0);
    }
    LightLiSample ls;
    if (!SampleLi(light, scene, MakeLightContext(si), u2, lambda, &ls) || ls.pdf == 0 || ls.L.IsBlack())
        return SampledSpectrum(0);
    Float oneMinusCos = RegularizedOneMinusCos(rp, ls.distance);
    Float pImplW = ConePdfW(oneMinusCos);
    SampledSpectrum sum(0);
    for (int i = 0; i < n; ++i) {
        if (OneMinusCosBetween(lobes[i].wi, ls.wi) >= oneMinusCos) continue;
        sum += lobes[i].weight;
    }
    if (sum.IsBlack()) return SampledSpectrum(0);
    Ray shadow = SpawnShadowRay(si.p, si.n, ls.wi, ls.distance, ls.pLight);
    ++st.rays; ++st.shadowRays;
    if (tracer.Occluded(shadow)) return SampledSpectrum(0);
    Float pExplW = ls.isDelta ? Infinity : pmf * ls.pdf;
    Float w = RegularizedExplicitWeight(pImplW, pExplW);
    // f_reg |cos| / p = weight * phi / pdf; for delta lights the "pdf" is the pmf alone.
    Float pSample = pmf * ls.pdf;
    SampledSpectrum c = sum * ls.L * (w * pImplW / pSample);
    ++st.regConnections;
    return c;
}

// MIS weight of an emitter hit by BSDF sampling after a non-specular vertex.
LU_INLINE Float ImplicitWeight(LightStrategy s, Float pB, Float pL) {
    if (s == LightStrategy::NEEOnly) return 0;
    if (s == LightStrategy::BSDFOnly) return 1;
    return PowerHeuristic(pB, pL);
}

// Radiance along a camera ray (pbrt-v4 PathIntegrator::Li with regularization).
template <typename Tracer>
LU_HD SampledSpectrum Li(Ray ray, SampledWavelengths &lambda, Sampler &sampler, const SceneView &scene,
                         const Tracer &tracer, const PathSettings &ps, PathStats &st, int *terminalDepth = nullptr) {
    SampledSpectrum L(0), beta(1);
    int depth = 0;
    Float pB = 1, etaScale = 1;
    bool specularBounce = false;
    bool regularizedPrev = false;   // previous vertex was specular and regularized
    SurfaceInteraction prev;
    for (int guard = 0; guard < 1024; ++guard) {
        HitRecord hit;
        ++st.rays;
        bool found = tracer.Intersect(ray, &hit);
        if (!found) {
            for (uint32_t k = 0; k < scene.infiniteLights.size; ++k) {
                uint32_t li = scene.infiniteLights[k];
                const Light &light = scene.lights[li];
                SampledSpectrum Le = InfiniteLightLe(light, scene, Normalize(ray.d), lambda);
                if (Le.IsBlack()) continue;
                if (depth == 0 || (specularBounce && !regularizedPrev)) {
                    L += beta * Le;
                } else {
                    Vec3f wi = Normalize(ray.d);
                    Float pL = LightPMF(scene, li) * PDF_Li(light, scene, MakeLightContext(prev), wi, prev.p + wi, -wi);
                    Float w = specularBounce ? RegularizedImplicitWeight(ConePdfW(RegularizedOneMinusCos(ps.reg, Infinity)), pL)
                                             : ImplicitWeight(ps.strategy, pB, pL);
                    L += beta * Le * w;
                }
            }
            break;
        }
        SurfaceInteraction si = ComputeInteraction(scene, hit, ray);
        if (si.areaLight != NoIndex) {
            const Light &light = scene.lights[si.areaLight];
            SampledSpectrum Le = AreaLightL(light, scene, si.p, si.n, si.uv, si.wo, lambda);
            if (!Le.IsBlack()) {
                if (depth == 0 || (specularBounce && !regularizedPrev)) {
                    L += beta * Le;
                } else {
                    Vec3f wi = -si.wo;
                    Float pL = LightPMF(scene, si.areaLight) * PDF_Li(light, scene, MakeLightContext(prev), wi, si.p, si.n);
                    Float w;
                    if (specularBounce) {
                        Float d = Distance(prev.p, si.p);
                        w = RegularizedImplicitWeight(ConePdfW(RegularizedOneMinusCos(ps.reg, d)), pL);
                    } else {
                        w = ImplicitWeight(ps.strategy, pB, pL);
                    }
                    L += beta * Le * w;
                }
            }
        }
        BSDF bsdf;
        if (si.material == NoIndex || !MakeBSDF(scene.materials[si.material], si, lambda, scene, &bsdf)) {
            // Interface: continue the ray past the surface, same depth (pbrt-v4 SkipIntersection).
            ray.o = OffsetRayOrigin(si.p, si.n, ray.d);
            continue;
        }
        if (depth++ == ps.maxDepth) break;
        bool specular = bsdf.IsSpecular();
        regularizedPrev = false;
        if (!specular && ps.strategy != LightStrategy::BSDFOnly) {
            SampledSpectrum Ld = SampleLd(si, bsdf, lambda, sampler, scene, tracer, st, ps.strategy);
            L += beta * Ld;
        } else if (ps.reg.enabled) {
            SampledSpectrum Lr = beta * SampleRegularized(si, bsdf, lambda, sampler, scene, tracer, ps.reg, st);
            st.regEnergy += Lr.Average();
            L += Lr;
            regularizedPrev = true;
        }
        Float uc = sampler.Get1D();
        Vec2f u2 = sampler.Get2D();
        BSDFSample bs;
        if (!bsdf.Sample_f(si.wo, uc, u2, &bs) || bs.pdf == 0 || bs.f.IsBlack()) break;
        beta *= bs.f * (AbsDot(bs.wi, si.ns) / bs.pdf);
        pB = bs.pdfIsProportional ? bsdf.PDF(si.wo, bs.wi) : bs.pdf;
        specularBounce = bs.IsSpecular();
        if (!specularBounce) regularizedPrev = false;
        if (bs.IsTransmission()) etaScale *= Sqr(bs.eta);
        prev = si;
        ray.o = OffsetRayOrigin(si.p, si.n, bs.wi);
        ray.d = bs.wi;
        ray.tMax = Infinity;
        // Russian roulette (pbrt-v4): after the first bounce, when the throughput is small.
        SampledSpectrum rrBeta = beta * etaScale;
        if (rrBeta.MaxValue() < 1 && depth > 1) {
            Float q = Max(Float(0), 1 - rrBeta.MaxValue());
            if (sampler.Get1D() < q) break;
            beta /= 1 - q;
        }
        if (!beta.IsFinite()) break;
    }
    if (terminalDepth) *terminalDepth = depth;
    st.totalEnergy += L.Average();
    return L;
}

// One camera sample of pixel (px, py) at sample index `sampleIndex` (pbrt-v4's order of sampler
// dimensions: wavelengths, filter, lens, then the path).
struct CameraSampleResult {
    SampledSpectrum L;
    SampledWavelengths lambda;
    Float filterWeight = 0;
    int depth = 0;
};

template <typename Tracer>
LU_HD CameraSampleResult RenderSample(int px, int py, uint32_t sampleIndex, Sampler &sampler, const SceneView &scene,
                                      const Tracer &tracer, const PathSettings &ps, PathStats &st) {
    CameraSampleResult r;
    sampler.StartPixelSample(px, py, int(sampleIndex), 0);
    Float lu = sampler.Get1D();
    r.lambda = SampledWavelengths::SampleVisible(lu);
    FilterSample fs = SampleFilter(scene.filter, scene, sampler.GetPixel2D());
    Vec2f pFilm(px + 0.5f + fs.p.x, py + 0.5f + fs.p.y);
    (void)sampler.Get1D();  // time (unused; keeps pbrt-v4's dimension order)
    Vec2f uLens = sampler.Get2D();
    Ray ray;
    r.filterWeight = fs.weight;
    if (!GenerateRay(scene.camera, pFilm, uLens, &ray)) {
        r.L = SampledSpectrum(0);
        return r;
    }
    r.L = Li(ray, r.lambda, sampler, scene, tracer, ps, st, &r.depth);
    return r;
}

}  // namespace lu
