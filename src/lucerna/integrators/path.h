// Lucerna: the per-path integrator body shared by the CPU and CUDA backends: unidirectional path
// tracing with next-event estimation and BSDF sampling combined by MIS (power heuristic), as
// pbrt-v4's PathIntegrator, plus the regularized connection at specular vertices; the techniques
// are in integrators/techniques.h, their weights in integrators/mis.h. RenderPixelSample is what a
// backend runs per pixel and pass.
#pragma once

#include "lucerna/camera/camera.h"
#include "lucerna/film/film_sample.h"
#include "lucerna/geometry/shapes.h"
#include "lucerna/integrators/techniques.h"

namespace lu {

// Radiance along a camera ray (pbrt-v4 PathIntegrator::Li with the regularized technique).
template <typename Tracer>
LU_HD SampledSpectrum Li(Ray ray, SampledWavelengths &lambda, Sampler &sampler, const SceneView &scene,
                         const Tracer &tracer, const PathSettings &ps, PathStats &st, int *terminalDepth = nullptr) {
    SampledSpectrum L(0), beta(1);
    int depth = 0;
    Float etaScale = 1;
    ScatterVertex prev;   // the vertex the current ray left from (camera at first)
    for (int guard = 0; guard < 1024; ++guard) {
        HitRecord hit;
        ++st.rays;
        bool found = tracer.Intersect(ray, &hit);
        // ---- Emitters the ray reaches ----
        if (!found) {
            for (uint32_t k = 0; k < scene.infiniteLights.size; ++k) {
                uint32_t li = scene.infiniteLights[k];
                SampledSpectrum Le = InfiniteLightLe(scene.lights[li], scene, Normalize(ray.d), lambda);
                if (Le.IsBlack()) continue;
                Vec3f wi = Normalize(ray.d);
                L += beta * Le * EmitterHitWeight(prev, scene, li, wi, prev.ctx.p + wi, -wi, true, ps);
            }
            break;
        }
        SurfaceInteraction si = ComputeInteraction(scene, hit, ray);
        if (si.areaLight != NoIndex) {
            SampledSpectrum Le = AreaLightL(scene.lights[si.areaLight], scene, si.p, si.n, si.uv, si.wo, lambda);
            if (!Le.IsBlack()) L += beta * Le * EmitterHitWeight(prev, scene, si.areaLight, -si.wo, si.p, si.n, false, ps);
        }
        BSDF bsdf;
        if (si.material == NoIndex || !MakeBSDF(scene.materials[si.material], si, lambda, scene, &bsdf)) {
            // Interface: continue the ray past the surface, same depth (pbrt-v4 SkipIntersection).
            ray.o = OffsetRayOrigin(si.p, si.n, ray.d);
            continue;
        }
        if (depth++ == ps.maxDepth) break;
        // ---- Explicit techniques at this vertex ----
        bool specular = bsdf.IsSpecular();
        ScatterVertex here = prev;   // becomes this vertex's record (SampleDirect, SampleBSDFDirection)
        SampledSpectrum Ld;
        DirectTechnique t = SampleDirect(si, bsdf, specular, prev, lambda, sampler, scene, tracer, ps, st, &Ld, &here);
        if (t != DirectTechnique::None) {
            SampledSpectrum c = beta * Ld;
            if (t == DirectTechnique::Regularized) st.regEnergy += c.Average();
            L += c;
        }
        // ---- BSDF sampling ----
        if (!SampleBSDFDirection(si, bsdf, sampler, beta, etaScale, here, ray)) break;
        prev = here;
        // Russian roulette (pbrt-v4): after the first bounce, when the throughput is small.
        SampledSpectrum rrBeta = beta * etaScale;
        if (rrBeta.MaxValue() < 1 && depth > 1) {
            Float q = Max(Float(0), 1 - rrBeta.MaxValue());
            if (sampler.Get1D() < q) break;
            beta /= 1 - q;
        }
        if (!beta.IsFinite()) {   // a NaN or Inf from a material or light: reject the sample, do not hide it
            st.invalid = true;
            break;
        }
    }
    if (terminalDepth) *terminalDepth = depth;
    st.totalEnergy += L.Average();
    return L;
}

// One camera sample of pixel (px, py) at sample index `sampleIndex`, in pbrt-v4's order of
// sampler dimensions: wavelengths, then GetCameraSample (filter, time, lens), then the path.
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
    r.lambda = SampledWavelengths::SampleVisible(sampler.Get1D());
    CameraSample cs = GetCameraSample(sampler, px, py, scene.filter, scene);
    r.filterWeight = cs.filterWeight;
    Ray ray;
    if (!GenerateRay(scene.camera, cs.pFilm, cs.pLens, &ray)) {
        r.L = SampledSpectrum(0);
        return r;
    }
    r.L = Li(ray, r.lambda, sampler, scene, tracer, ps, st, &r.depth);
    return r;
}

// What a backend runs for pixel (x, y) in pass `pass`: one camera sample into its pass-buffer
// pixel xyzw (4 floats), counted in c. `base` is the render's sampler (each call starts its own
// pixel sample from a copy).
template <typename Tracer>
LU_HD void RenderPixelSample(int x, int y, uint32_t pass, const Sampler &base, const SceneView &scene,
                             const Tracer &tracer, const PathSettings &ps, float *xyzw, PassCounters &c) {
    Sampler sampler = base;
    PathStats st;
    CameraSampleResult cs = RenderSample(x, y, pass, sampler, scene, tracer, ps, st);
    c.Add(st);
    if (!WriteFilmSample(cs.L, cs.lambda, cs.filterWeight, scene, xyzw) || st.invalid) {
        xyzw[0] = xyzw[1] = xyzw[2] = xyzw[3] = 0;
        c.Reject(RejectedSampleKey(x, y, scene.film.width, cs.depth));
    }
}

}  // namespace lu
