// Lucerna: the per-path integrator body shared by the CPU and CUDA backends: unidirectional path
// tracing with next-event estimation and BSDF sampling combined by MIS (power heuristic), as
// pbrt-v4's PathIntegrator, plus the regularized connection at specular vertices; the techniques
// are in integrators/techniques.h, their weights in integrators/mis.h. RenderPixelSample is what a
// backend runs per pixel and pass.
#pragma once

#include "lucerna/camera/camera.h"
#include "lucerna/film/film_sample.h"
#include "lucerna/geometry/shapes.h"
#include "lucerna/integrators/collimated.h"
#include "lucerna/integrators/techniques.h"
#include "lucerna/integrators/volume.h"

namespace lu {

// The phase-function sampling of a medium vertex at p (wo towards the previous vertex): the next
// ray and the record of this vertex; the phase function samples itself exactly (beta unchanged).
LU_INLINE void SamplePhaseDirection(const Vec3f &p, const Vec3f &wo, Float g, bool beamRegions, Sampler &sampler,
                                    ScatterVertex &v, Ray &ray) {
    Float pdf;
    Vec3f wi = SampleHenyeyGreenstein(wo, g, sampler.Get2D(), &pdf);
    v.ctx = LightSampleContext();
    v.ctx.p = p;
    v.pdfBsdfW = pdf;
    v.camera = v.specular = v.regularized = v.allSpecular = false;
    v.beamRegions = beamRegions;
    // NEE (and MNEE) ran here: a refractive chain may start (as at a non-specular surface).
    v.chainVertices = 0;
    v.chainHash = 0;
    v.chainStart = v.ctx;
    v.chainBsdfPdfW = pdf;
    v.chainLobePdf = 1;
    ray.o = p;
    ray.d = wi;
    ray.tMax = Infinity;
}

// Radiance along a camera ray (pbrt-v4 PathIntegrator::Li with the regularized technique; in
// media pbrt-v4's VolPathIntegrator::Li: delta tracking, medium vertices with NEE and phase
// sampling, and the wavelengths weighted as techniques once the path has entered a medium).
template <typename Tracer>
LU_HD SampledSpectrum Li(Ray ray, SampledWavelengths &lambda, Sampler &sampler, const SceneView &scene,
                         const Tracer &tracer, const PathSettings &ps, PathStats &st, int *terminalDepth = nullptr) {
    SampledSpectrum L(0), beta(1);
    int depth = 0;
    Float etaScale = 1;
    ScatterVertex prev;   // the vertex the current ray left from (camera at first)
    uint32_t medium = scene.camera.medium;   // the medium the current ray travels in
    WavelengthPdfs r;                        // used once the path has entered a medium
    bool inMedia = false;
    const bool beamSegments = UsesBeamSegments(ps, scene);   // the beam techniques in media
    uint32_t crossedBeam = NoIndex;          // the collimated light's disc the ray was continued through
    Vec3f lastVertex = ray.o;                // the path's last vertex (the camera at first), for its length
    for (int guard = 0; guard < 1024; ++guard) {
        HitRecord hit;
        ++st.rays;
        bool found = tracer.Intersect(ray, &hit);
        // A collimated beam's disc before the hit (regularized passes only: otherwise it gives nothing).
        Float tEnd = found ? hit.t : Infinity;
        Vec3f yBeam;
        uint32_t beam = NoIndex;
        if (scene.collimatedLights > 0 && ps.reg.enabled)
            beam = NearestBeamCrossing(scene, ray, tEnd, crossedBeam, &tEnd, &yBeam);
        // ---- The medium along the ray ----
        if (medium != NoIndex) {
            inMedia = true;
            // The beams' light scattered along this segment where it crosses their regions, when
            // the segment leaves the camera or a Dirac lobe (else BeamScatterLd at its origin).
            if (beamSegments && depth < ps.maxDepth && (prev.camera || prev.specular)) {
                SampledSpectrum c = beta * BeamSegmentsLi(ray, tEnd, medium, r, lambda, sampler, scene, tracer, ps, st);
                NoteBadValue(st, c, RejectCause::Medium, medium, depth);
                L += c;
            }
            Vec3f pScatter;
            MediumEvent ev = SampleMediumSegment(scene, medium, ray, tEnd, lambda, sampler, depth,
                                                 ps.maxDepth, beta, r, L, &pScatter);
            NoteBadValue(st, L, RejectCause::Medium, medium, depth);
            if (ev == MediumEvent::Terminated) break;
            if (ev == MediumEvent::Scattered) {
                ++depth;
                Vec3f wo = -Normalize(ray.d);
                Float g = scene.media[medium].g;
                LightSampleContext ctx;
                ctx.p = pScatter;
                VertexMedia vm;
                vm.medium = medium;
                vm.r = &r;
                if (ps.strategy != LightStrategy::BSDFOnly) {
                    SampledSpectrum c = beta * SampleLd(ctx, wo, PhaseScatter{g}, vm, lambda, sampler, scene, tracer, st,
                                                        ps.strategy, MneeAt(ps, scene, depth),
                                                        BeamOneMinusCos(ps.reg), beamSegments);
                    NoteBadValue(st, c, RejectCause::Medium, medium, depth);
                    L += c;
                }
                if (beamSegments && depth < ps.maxDepth) {
                    SampledSpectrum c = beta * BeamScatterLd(ctx, wo, PhaseScatter{g}, vm, lambda, sampler, scene, tracer, ps, st);
                    NoteBadValue(st, c, RejectCause::Medium, medium, depth);
                    L += c;
                }
                Float T = prev.pathLength + Distance(lastVertex, pScatter);
                SamplePhaseDirection(pScatter, wo, g, beamSegments, sampler, prev, ray);
                prev.pathLength = prev.receiverT = T;   // a non-specular vertex
                lastVertex = pScatter;
                crossedBeam = NoIndex;
                r.l = r.lChain = r.u;
                if (!beta.IsFinite()) {
                    NoteBadValue(st, beta, RejectCause::Medium, medium, depth);
                    st.invalid = true;
                    break;
                }
                continue;
            }
        }
        const WavelengthPdfs *rPath = inMedia ? &r : nullptr;
        if (beam != NoIndex) {   // the beam's regularized radiance; the ray goes on through the disc
            SampledSpectrum c = beta * BeamHitLe(prev, scene, beam, ray, yBeam, ps, rPath, lambda);
            NoteBadValue(st, c, RejectCause::Emission, beam, depth);
            L += c;
            ray.o = yBeam;
            crossedBeam = beam;
            continue;
        }
        // ---- Emitters the ray reaches ----
        if (!found) {
            for (uint32_t k = 0; k < scene.infiniteLights.size; ++k) {
                uint32_t li = scene.infiniteLights[k];
                SampledSpectrum Le = InfiniteLightLe(scene.lights[li], scene, Normalize(ray.d), lambda);
                if (Le.IsBlack()) continue;
                Vec3f wi = Normalize(ray.d);
                SampledSpectrum c = beta * Le * EmitterHitWeight(prev, scene, li, wi, prev.ctx.p + wi, -wi, true, ps, rPath, lambda, tracer);
                NoteBadValue(st, c, RejectCause::Emission, li, depth);
                L += c;
            }
            break;
        }
        SurfaceInteraction si = ComputeInteraction(scene, hit, ray);
        if (si.areaLight != NoIndex && !AreaLightAlphaMasked(scene.lights[si.areaLight], scene, si.p, si.uv)) {
            SampledSpectrum Le = AreaLightL(scene.lights[si.areaLight], scene, si.p, si.n, si.uv, si.wo, lambda);
            if (!Le.IsBlack()) {
                SampledSpectrum c = beta * Le * EmitterHitWeight(prev, scene, si.areaLight, -si.wo, si.p, si.n, false, ps, rPath, lambda, tracer);
                NoteBadValue(st, c, RejectCause::Emission, si.areaLight, depth);
                L += c;
            }
        }
        const Shape &shape = scene.shapes[si.shape];
        BSDF bsdf;
        if (si.material == NoIndex || !MakeBSDF(scene.materials[si.material], si, lambda, scene, &bsdf)) {
            // Interface: continue the ray past the surface, same depth (pbrt-v4 SkipIntersection).
            if (scene.walkInterfaces) medium = MediumAfter(shape, si.n, ray.d, medium);
            ray.o = OffsetRayOrigin(si.p, si.n, ray.d);
            continue;
        }
        // A normal map moves the shading normal (pbrt-v4's SetShadingGeometry); without one this
        // is the same vector.
        si.ns = bsdf.shadingFrame.z;
        if (depth++ == ps.maxDepth) break;
        // ---- Explicit techniques at this vertex ----
        bool specular = bsdf.IsSpecular();
        ScatterVertex here = prev;   // becomes this vertex's record (SampleDirect, SampleBSDFDirection)
        here.pathLength = prev.pathLength + Distance(lastVertex, si.p);
        VertexMedia vm;
        vm.medium = medium;
        vm.shape = &shape;
        vm.n = si.n;
        vm.r = rPath;
        SampledSpectrum Ld;
        DirectTechnique t = SampleDirect(si, bsdf, specular, prev, depth, vm, lambda, sampler, scene, tracer, ps, st, &Ld, &here);
        if (t != DirectTechnique::None) {
            SampledSpectrum c = beta * Ld;
            if (t == DirectTechnique::Regularized) st.regEnergy += c.Average();
            NoteBadValue(st, c, RejectCause::Direct, si.material, depth);
            L += c;
        }
        if (!specular && beamSegments && depth < ps.maxDepth) {
            SampledSpectrum c = beta * BeamScatterLd(MakeLightContext(si), si.wo, SurfaceScatter{bsdf, si.ns}, vm, lambda,
                                                     sampler, scene, tracer, ps, st);
            NoteBadValue(st, c, RejectCause::Direct, si.material, depth);
            L += c;
        }
        // ---- BSDF sampling ----
        if (!SampleBSDFDirection(si, bsdf, sampler, beta, etaScale, here, ray)) break;
        prev = here;
        lastVertex = si.p;
        crossedBeam = NoIndex;
        if (scene.walkInterfaces) {
            medium = MediumAfter(shape, si.n, ray.d, medium);
            r.l = r.u;
            if (!specular) r.lChain = r.u;   // a chain for MNEE starts here (it continues through Dirac vertices)
        }
        // Russian roulette (pbrt-v4): after the first bounce, when the throughput is small.
        SampledSpectrum rrBeta = beta * etaScale;
        if (inMedia) rrBeta /= r.u.Average();
        if (rrBeta.MaxValue() < 1 && depth > 1) {
            Float q = Max(Float(0), 1 - rrBeta.MaxValue());
            if (sampler.Get1D() < q) break;
            beta /= 1 - q;
        }
        if (!beta.IsFinite()) {   // a NaN or Inf from a material: reject the sample, do not hide it
            NoteBadValue(st, beta, RejectCause::Scatter, si.material, depth);
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
    Float uLambda = sampler.Get1D();
    r.lambda = SampledWavelengths::SampleVisible(scene.film.disableWavelengthJitter ? Float(0.5) : uLambda);
    CameraSample cs = GetCameraSample(sampler, px, py, scene.filter, scene);
    r.filterWeight = cs.filterWeight;
    Ray ray;
    Float cameraWeight;
    if (!GenerateRay(scene.camera, cs.pFilm, cs.pLens, &ray, &cameraWeight)) {
        r.L = SampledSpectrum(0);   // vignetted or degenerate: a zero sample that still counts
        return r;
    }
    r.L = Li(ray, r.lambda, sampler, scene, tracer, ps, st, &r.depth);
    if (cameraWeight != 1) r.L *= cameraWeight;   // pbrt-v4: L = cameraRay->weight * Li (1 but for lens systems)
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
        if (st.cause == RejectCause::None) {   // fine on the way, not at the film
            st.cause = RejectCause::Film;
            st.causeDepth = cs.depth;
            if (!FindBadValue(cs.L, &st.badValue)) st.badValue = BadValue::Infinite;   // XYZ overflow or filter weight
        }
        c.Reject(RejectedSampleKey(x, y, scene.film.width, st.causeDepth, st.cause, st.badValue, st.causeEntity));
    }
}

}  // namespace lu
