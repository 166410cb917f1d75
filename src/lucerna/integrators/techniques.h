// Lucerna: the sampling techniques of the path integrator, one function each (after Tungsten's
// TraceBase): next-event estimation at non-specular vertices, the regularized connection at
// specular vertices, BSDF sampling of the next direction, and the weight of an emitter that BSDF
// sampling hits. Their MIS weights come from integrators/mis.h. A new technique goes here: its
// function, its call in SampleDirect, and its pdf in EmitterHitWeight. A vertex is a surface
// point (its BSDF) or a medium scattering point (its phase function); the media a shadow ray
// crosses are estimated by integrators/volume.h.
// Backends supply a Tracer with  bool Intersect(const Ray &, HitRecord *) const;  bool Occluded(const Ray &) const;
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/integrators/mis.h"
#include "lucerna/integrators/mnee.h"
#include "lucerna/integrators/stats.h"
#include "lucerna/integrators/volume.h"
#include "lucerna/materials/bsdf.h"
#include "lucerna/sampling/sampler.h"

namespace lu {

// What the per-path code needs of the settings in one pass (host: render/settings.h).
struct PathSettings {
    int maxDepth = 5;
    LightStrategy strategy = LightStrategy::MIS;
    RegularizationParams reg;   // this pass's kernel
    bool mnee = false;          // manifold NEE through refractive chains (integrators/mnee.h)
    Float mneeMaxSolidAngle = 0.01f;   // ... to area lights subtending less than this (sr) from the chain's start
    bool beamSegments = false;  // collimated beams in media: the beam-segment technique (integrators/collimated.h)
    bool nearSpecular = false;  // near-specular microfacet lobes widened for delta lights (NearSpecularBsdf)
};

// MNEE applies in this scene: the setting is on and some material can refract or pass light.
// In scenes with media too: the chains carry the transmittance of the media they cross
// (MneeChainTransmittance), and medium vertices start chains as surface vertices do.
LU_INLINE bool UsesMnee(const PathSettings &ps, const SceneView &scene) { return ps.mnee && scene.transmitters > 0; }

// MNEE's selectivity: whether MNEE is a technique for chains from x0 to `light`. Always for point
// and spot lights (the only technique besides the regularized one). For an area light under MIS
// only when its bounding sphere subtends less than maxSolidAngle (sr) from x0: a larger light,
// seen through the chain, is found often enough by BSDF sampling (its hit probability is about the
// solid angle times the BSDF's density), and a solve at every blocked shadow ray and at every hit
// after a refractive chain costs more than it saves (smallvcm bs_c, a 50 cm ceiling light over a
// glass ball: MNEE made samples 1.7x as expensive and their variance 8% lower). A function of
// (x0, light) alone, so SampleMnee, MneeReproducesHit and SampleRegularized agree on it; under the
// NEE-only strategy always (nothing else samples these paths without bias there).
LU_INLINE bool MneeTargetsLight(LightStrategy strategy, Float maxSolidAngle, const Light &light, Vec3f x0) {
    if (light.kind != LightKind::DiffuseArea || strategy != LightStrategy::MIS || light.boundRadius < 0) return true;
    Float d2 = DistanceSquared(x0, light.boundCenter), r2 = Sqr(light.boundRadius);
    if (!(r2 < d2)) return false;   // inside the bounding sphere
    Float s2 = r2 / d2;             // 2 pi (1 - cos theta) with sin^2 theta = r^2 / d^2, without cancellation
    return 2 * Pi * s2 / (1 + std::sqrt(1 - s2)) < maxSolidAngle;
}
LU_INLINE bool MneeTargetsLight(const PathSettings &ps, const Light &light, Vec3f x0) {
    return MneeTargetsLight(ps.strategy, ps.mneeMaxSolidAngle, light, x0);
}

// What MNEE may do at a non-specular vertex: add at most `vertices` chain vertices (0: MNEE off),
// to the lights MneeTargetsLight admits.
struct MneeBudget {
    int vertices = 0;
    Float maxSolidAngle = Infinity;
};
// At the vertex of index depth on the path: the vertices maxdepth leaves.
LU_INLINE MneeBudget MneeAt(const PathSettings &ps, const SceneView &scene, int depth) {
    MneeBudget b;
    if (UsesMnee(ps, scene)) {
        b.vertices = ps.maxDepth - depth;
        b.maxSolidAngle = ps.mneeMaxSolidAngle;
    }
    return b;
}

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

// ---- Vertices: what scatters there, and which media they touch ----

// The scattering function at a surface vertex: the BSDF times |cos| at the shading normal.
struct SurfaceScatter {
    const BSDF &bsdf;
    Vec3f ns;
    const BSDF *deltaBsdf = nullptr;   // the BSDF delta lights see, when not bsdf (NearSpecularBsdf)
    LU_HD SampledSpectrum f(Vec3f wo, Vec3f wi) const { return bsdf.f(wo, wi) * AbsDot(wi, ns); }
    LU_HD SampledSpectrum fDelta(Vec3f wo, Vec3f wi) const { return (deltaBsdf ? *deltaBsdf : bsdf).f(wo, wi) * AbsDot(wi, ns); }
    LU_HD Float PDF(Vec3f wo, Vec3f wi) const { return bsdf.PDF(wo, wi); }
};

// The scattering function at a medium vertex: the Henyey-Greenstein phase function (sigma_s is
// in the path throughput), which its sampling reproduces exactly.
struct PhaseScatter {
    Float g = 0;
    LU_HD SampledSpectrum f(Vec3f wo, Vec3f wi) const { return SampledSpectrum(HenyeyGreenstein(Dot(wo, wi), g)); }
    LU_HD SampledSpectrum fDelta(Vec3f wo, Vec3f wi) const { return f(wo, wi); }
    LU_HD Float PDF(Vec3f wo, Vec3f wi) const { return HenyeyGreenstein(Dot(wo, wi), g); }
};

// The media at a vertex: the medium the path arrived in, the interface of a surface vertex, and
// the path's per-wavelength probabilities (nullptr: the path has not entered a medium).
struct VertexMedia {
    uint32_t medium = NoIndex;
    const Shape *shape = nullptr;   // surface vertices
    Vec3f n;                        // surface vertices: the oriented geometric normal
    const WavelengthPdfs *r = nullptr;
    // The medium a ray leaving the vertex along w starts in.
    LU_HD uint32_t Toward(const Vec3f &w) const { return shape ? MediumAfter(*shape, n, w, medium) : medium; }
};

// The visibility of a light sample: one occlusion query in scenes without media or interfaces,
// else the transmittance through them (TraceTransmittance). *tr stays 1 when nothing was crossed.
template <typename Tracer>
LU_HD bool ShadowRayVisible(const SceneView &scene, const Tracer &tracer, const Ray &shadow, const VertexMedia &vm,
                            const Vec3f &wi, const SampledWavelengths &lambda, PathStats &st, ShadowTransmittance *tr) {
    ++st.rays; ++st.shadowRays;
    if (!scene.walkInterfaces) return !tracer.Occluded(shadow);
    return TraceTransmittance(scene, tracer, shadow, vm.Toward(wi), lambda, st, tr);
}

// The per-wavelength probabilities of a light sample's path under the explicit technique (*rL)
// and under the implicit one (*rU), from the path's and the shadow ray's (pbrt-v4's SampleLd);
// false when neither the path nor the shadow ray went through a medium (scalar weights apply).
LU_INLINE bool LightSamplePdfs(const VertexMedia &vm, const ShadowTransmittance &tr, SampledSpectrum *rL,
                               SampledSpectrum *rU) {
    if (!vm.r && !tr.throughMedium) return false;
    SampledSpectrum prefix = vm.r ? vm.r->u : SampledSpectrum(1);
    *rL = prefix * tr.sL;
    *rU = prefix * tr.sU;
    return true;
}

// ---- Manifold next-event estimation (integrators/mnee.h) ----

// The transmittance of the media along a solved chain x0 -> x1 ... xk -> y, estimated per
// segment as a shadow ray's (SegmentTransmittance: ratio tracking, exact in homogeneous media),
// starting in `medium`: the pass-through surfaces on a segment and the chain's refractions change
// the medium as their interfaces say (pbrt-v4's MediumInterface). False when the estimate is 0
// or a segment crosses more surfaces than the chain's walk allows.
template <typename Tracer>
LU_HD bool MneeChainTransmittance(const SceneView &scene, const Tracer &tracer, const MneeChain &ch, uint32_t medium,
                                  const SampledWavelengths &lambda, PathStats &st, ShadowTransmittance *tr) {
    RNG rng(Hash(ch.x0.x, ch.x0.y, ch.x0.z), Hash(ch.y.x, ch.y.y, ch.y.z));
    Vec3f from = ch.x0, nFrom = ch.n0;
    for (int i = 0; i <= ch.k; ++i) {
        Vec3f to = i == ch.k ? ch.y : ch.v[i].p;
        Ray ray;
        ray.o = OffsetRayOrigin(from, nFrom, to - from);
        ray.d = to - ray.o;
        ray.tMax = 1 - 1e-4f;   // up to the vertex (or the light point), not its surface
        bool reached = false;
        for (int crossing = 0; crossing <= MaxMneeSurfaces && !reached; ++crossing) {
            HitRecord hit;
            ++st.rays;
            bool found = tracer.Intersect(ray, &hit);
            if (medium != NoIndex && !RayTransmittance(scene, medium, ray, found ? hit.t : ray.tMax, lambda, rng, tr))
                return false;
            if (!found) {
                reached = true;
                break;
            }
            SurfaceInteraction si = ComputeInteraction(scene, hit, ray);   // a pass-through surface
            medium = MediumAfter(scene.shapes[hit.shape], si.n, ray.d, medium);
            ray.o = OffsetRayOrigin(si.p, si.n, to - si.p);
            ray.d = to - ray.o;
            ray.tMax = 1 - 1e-4f;
        }
        if (!reached) return false;
        if (i < ch.k) {   // refracted at vertex i into the medium on its other side
            const MneeVertex &v = ch.v[i];
            medium = MediumAfter(scene.shapes[v.shape], v.ng, MneeNext(ch, i) - v.p, medium);
            from = v.p;
            nFrom = v.ng;
        }
    }
    return true;
}

// The light sample ls of NEE at the non-specular vertex ctx (a surface, or a medium point: ctx.n
// zero), whose straight shadow ray is blocked: the refractive chain to the same light point,
// when the blockers are smooth dielectrics and Newton's method finds it, through the media of vm
// (budget: the vertices maxdepth leaves for the chain, so that MNEE adds the paths BSDF sampling
// would find, no longer ones). Weighted against BSDF (phase) sampling of the same chain (area
// lights; the power heuristic in area measure at the light point, and over the wavelengths once
// the path is in media, with the chain's own per-wavelength probabilities: WavelengthPdfs::lChain
// on the other side); the only technique for point and spot lights. The regularized connection
// leaves these paths to MNEE (see SampleRegularized).
template <typename Tracer, typename Scatter>
LU_HD SampledSpectrum SampleMnee(const LightSampleContext &ctx, Vec3f wo, const Scatter &sc, const VertexMedia &vm,
                                 const LightPick &pick, const Light &light, const LightLiSample &ls,
                                 const SampledWavelengths &lambda, const SceneView &scene, const Tracer &tracer,
                                 LightStrategy strategy, MneeBudget budget, PathStats &st) {
    if (ls.distance == Infinity) return SampledSpectrum(0);   // distant and infinite lights: no light point
    bool delta = ls.isDelta;
    if (!delta && light.kind != LightKind::DiffuseArea) return SampledSpectrum(0);
    if (!MneeTargetsLight(strategy, budget.maxSolidAngle, light, ctx.p)) return SampledSpectrum(0);
    MneeChain ch;
    MneeThroughput tp;
    if (!FindMneeChain(scene, tracer, ctx.p, ctx.n, ls.pLight, ls.nLight, lambda, &ch, &tp)) return SampledSpectrum(0);
    if (ch.k + tp.passThrough > budget.vertices) return SampledSpectrum(0);   // longer than maxdepth allows
    Vec3f w0 = Normalize((ch.k ? ch.v[0].p : ch.y) - ctx.p);
    Vec3f wy = Normalize((ch.k ? ch.v[ch.k - 1].p : ctx.p) - ch.y);   // from the light towards the chain
    SampledSpectrum f = sc.f(wo, w0);
    if (f.IsBlack()) return SampledSpectrum(0);
    ShadowTransmittance tr;
    if (scene.walkInterfaces && !MneeChainTransmittance(scene, tracer, ch, vm.Toward(w0), lambda, st, &tr))
        return SampledSpectrum(0);
    SampledSpectrum rL, rU;
    bool spectral = LightSamplePdfs(vm, tr, &rL, &rU);
    f *= tr.T;
    bool surface = LengthSquared(ctx.n) > 0;
    SampledSpectrum c;
    if (delta) {   // E = I |d omega_y / dA_x0| per unit area of the surface at x0 (in a medium: of
                   // the plane normal to the arriving light, w0)
        if (!surface) ch.n0 = w0;
        Float cosG = surface ? AbsDot(w0, ctx.n) : 1, G = MneeGeometry(ch, false);
        if (!(cosG > 0) || !(G > 0)) return SampledSpectrum(0);
        Float w = spectral ? WavelengthWeight(rL, 1, rU, 0, lambda) : 1;
        c = f * tp.weight * PointLightIntensity(light, scene, wy, lambda) * (G * w / (cosG * pick.pmf));
    } else {
        Float G = MneeGeometry(ch, true);
        Float pdfLightA = pick.pmf * ls.pdf * AbsDot(ls.nLight, ls.wi) / Sqr(ls.distance);
        if (!(pdfLightA > 0) || !(G > 0)) return SampledSpectrum(0);
        Float pdfBsdfA = strategy == LightStrategy::MIS ? sc.PDF(wo, w0) * tp.lobePdf * G : 0;
        Float w = 1;
        if (spectral)
            w = (pdfBsdfA > 0 ? MneeWeight(pdfLightA, rU[0] * pdfBsdfA) : 1) *
                WavelengthWeight(rL, pdfLightA, rU, pdfBsdfA, lambda);
        else if (strategy == LightStrategy::MIS)
            w = MneeWeight(pdfLightA, pdfBsdfA);
        c = f * tp.weight * AreaLightL(light, scene, ch.y, ch.nY, ls.uvLight, wy, lambda) * (G * w / pdfLightA);
    }
    if (!c.IsBlack()) ++st.mneeConnections;
    return c;
}

// ---- Next-event estimation (pbrt-v4 PathIntegrator::SampleLd and VolPathIntegrator::SampleLd) ----

// One light sample at a non-specular vertex (ctx, outgoing direction wo, scattering function sc:
// SurfaceScatter or PhaseScatter), MIS-weighted against sampling sc, through the media in vm;
// through a blocking refractive chain by MNEE as mnee allows (default: none).
template <typename Tracer, typename Scatter>
LU_HD SampledSpectrum SampleLd(const LightSampleContext &ctx, Vec3f wo, const Scatter &sc, const VertexMedia &vm,
                               const SampledWavelengths &lambda, Sampler &sampler, const SceneView &scene,
                               const Tracer &tracer, PathStats &st, LightStrategy strategy = LightStrategy::MIS,
                               MneeBudget mnee = {}, Float beamOneMinusCos = 0, bool beamRegions = false) {
    Float uLight = sampler.Get1D();
    Vec2f u2 = sampler.Get2D();
    LightPick pick = PickLight(scene, uLight);
    if (pick.light == NoIndex || pick.pmf == 0) return SampledSpectrum(0);
    const Light &light = scene.lights[pick.light];
    // A medium vertex inside a beam's region leaves that beam to the beam-segment technique
    // (integrators/collimated.h).
    if (beamRegions && light.kind == LightKind::Collimated &&
        InBeamRegion(light, ctx.p, BeamRegionRadius(light, beamOneMinusCos)))
        return SampledSpectrum(0);
    LightLiSample ls;
    if (!SampleLightPoint(scene, light, ctx, u2, lambda, AllowIncompletePDF(strategy), &ls, beamOneMinusCos))
        return SampledSpectrum(0);
    SampledSpectrum f = ls.isDelta ? sc.fDelta(wo, ls.wi) : sc.f(wo, ls.wi);
    if (f.IsBlack()) return SampledSpectrum(0);
    Ray shadow = SpawnShadowRay(ctx.p, ctx.n, ls.wi, ls.distance, ls.pLight);
    ShadowTransmittance tr;
    if (!ShadowRayVisible(scene, tracer, shadow, vm, ls.wi, lambda, st, &tr))
        return mnee.vertices > 0 ? SampleMnee(ctx, wo, sc, vm, pick, light, ls, lambda, scene, tracer, strategy, mnee, st)
                              : SampledSpectrum(0);
    Float pdfLightW = pick.pmf * ls.pdf;
    SampledSpectrum rL, rU;
    if (!LightSamplePdfs(vm, tr, &rL, &rU)) {
        if (ls.isDelta || strategy == LightStrategy::NEEOnly) return f * ls.L / pdfLightW;
        Float pdfBsdfW = sc.PDF(wo, ls.wi);
        return f * ls.L * (LightSampleWeight(pdfLightW, pdfBsdfW) / pdfLightW);
    }
    f *= tr.T;
    if (ls.isDelta || strategy == LightStrategy::NEEOnly)
        return f * ls.L * (WavelengthWeight(rL, pdfLightW, rU, 0, lambda) / pdfLightW);
    Float pdfBsdfW = sc.PDF(wo, ls.wi);
    Float w = LightSampleWeight(pdfLightW, rU[0] * pdfBsdfW) * WavelengthWeight(rL, pdfLightW, rU, pdfBsdfW, lambda);
    return f * ls.L * (w / pdfLightW);
}

// NEE at a surface vertex.
template <typename Tracer>
LU_HD SampledSpectrum SampleLd(const SurfaceInteraction &si, const BSDF &bsdf, const VertexMedia &vm,
                               const SampledWavelengths &lambda, Sampler &sampler, const SceneView &scene,
                               const Tracer &tracer, PathStats &st, LightStrategy strategy = LightStrategy::MIS,
                               MneeBudget mnee = {}, Float beamOneMinusCos = 0, const BSDF *deltaBsdf = nullptr) {
    return SampleLd(MakeLightContext(si), si.wo, SurfaceScatter{bsdf, si.ns, deltaBsdf}, vm, lambda, sampler, scene,
                    tracer, st, strategy, mnee, beamOneMinusCos);
}

// ---- The vertex record for MIS ----

// The vertex a BSDF-sampled ray left from, as the emitter it hits needs it for MIS.
struct ScatterVertex {
    LightSampleContext ctx;
    Float pdfBsdfW = 1;        // pdf of the sampled direction (proportional samples: the BSDF's PDF)
    bool camera = true;        // the ray is a camera ray: nothing else can sample what it hits
    bool specular = false;     // the sampled lobe is a Dirac lobe
    bool regularized = false;  // ... and the regularized connection to area/infinite lights ran there,
    Float candidatePmf = 0;    // ... choosing among lights whose LightPMFs sum to this
    bool allSpecular = true;   // every vertex of the path so far (from the camera) sampled a Dirac lobe
    bool beamRegions = false;  // a medium vertex where the beam-segment technique takes the beams'
                               // light inside their regions (integrators/collimated.h)
    // MNEE: the chain of smooth transmissions since the last non-specular vertex x0, where NEE ran.
    int8_t chainVertices = -1;      // refractive vertices since x0; -1: no such chain (no x0 yet, a
                                    // reflection or another lobe since, or more than MaxMneeVertices)
    uint32_t chainHash = 0;         // their surfaces in order (MneeShapeHash)
    Vec3f chainFirst;               // the first of them
    LightSampleContext chainStart;  // x0
    Float chainBsdfPdfW = 0;        // BSDF sampling's pdf of the direction leaving x0
    Float chainLobePdf = 1;         // product of the lobe selection probabilities since x0
    // The regularized kernel's footprint (RegularizationAtVertex): the path's length from the
    // camera to this vertex, and to the last non-specular vertex up to it (-1: none yet).
    Float pathLength = 0;
    Float receiverT = -1;
};

// The regularized kernel at a specular vertex whose path has length T from the camera, after the
// non-specular vertex at length receiverT (-1: none). A footprint kernel when the pass has one.
LU_INLINE RegularizationParams VertexRegularization(const PathSettings &ps, const SceneView &scene, Float receiverT, Float T) {
    return RegularizationAtVertex(ps.reg, scene.camera.pixelWidth, scene.camera.pixelSpread, receiverT, T);
}
// ... at the specular vertex v was recorded at (the emitter-hit side of the MIS).
LU_INLINE RegularizationParams VertexRegularization(const PathSettings &ps, const SceneView &scene, const ScatterVertex &v) {
    return VertexRegularization(ps, scene, v.receiverT, v.pathLength);
}

// Whether MNEE from the chain start of `in` to light point y (normal nY) finds the chain of the
// path that continues through specular vertex si along a transmission (refractive: a dielectric,
// else a pass-through thin sheet), up to tol at the first refractive vertex.
template <typename Tracer>
LU_HD bool MneeCoversPath(const ScatterVertex &in, const SurfaceInteraction &si, bool refractive, Vec3f y, Vec3f nY,
                          Float tol, const SampledWavelengths &lambda, const SceneView &scene, const Tracer &tracer,
                          MneeChain *ch) {
    if (in.chainVertices < 0) return false;
    int k = in.chainVertices + (refractive ? 1 : 0);
    if (k > MaxMneeVertices) return false;
    uint32_t hash = refractive ? MneeShapeHash(in.chainHash, si.shape) : in.chainHash;
    Vec3f first = in.chainVertices > 0 ? in.chainFirst : si.p;
    MneeThroughput tp;
    return FindMneeChain(scene, tracer, in.chainStart.p, in.chainStart.n, y, nY, lambda, ch, &tp) &&
           MneeChainMatches(*ch, k, hash, first, tol);
}

// ---- The regularized connection (integrators/regularization.h) ----

// Light selection at a specular vertex p with Dirac lobes `lobes`: only the lights the technique
// may connect to, in proportion to their power (LightPMF): eligible ones (deltaOnly: point, spot
// and distant lights; no uniform infinite light when allowIncompletePDF leaves it to BSDF
// sampling) that some lobe's cone can reach (conservative test on the light's bounding sphere;
// lights without bounds always). The emitter-hit weight uses the same pmf: LightPMF / total.
LU_INLINE bool RegularizedCandidate(const SceneView &scene, uint32_t li, Vec3f p, const SpecularLobe *lobes, int n,
                                    const RegularizationParams &rp, const RegularizationParams &passRp, bool deltaOnly,
                                    bool allowIncompletePDF) {
    const Light &light = scene.lights[li];
    // A collimated beam is a candidate after a non-specular vertex only (the regularized beam
    // connection, two kernels: SampleRegularized); from the camera through Dirac lobes the
    // implicit technique alone reaches it (BeamHitWeight: weight 1).
    if (light.kind == LightKind::Collimated && deltaOnly) return false;
    if (deltaOnly && !IsDeltaLight(light)) return false;
    if (allowIncompletePDF && light.kind == LightKind::UniformInfinite) return false;
    if (light.boundRadius < 0) return true;
    for (int i = 0; i < n; ++i)
        if (light.kind == LightKind::Collimated
                ? RegularizedConeMayReach(p, lobes[i].wi, light.boundCenter, light.boundRadius, passRp.radius)
                : RegularizedConeMayReach(p, lobes[i].wi, light.boundCenter, light.boundRadius, rp.radius,
                                          rp.radiusPerDistance))
            return true;
    return false;
}
// The total pmf of the candidates (0: none).
LU_INLINE Float RegularizedCandidatePmf(const SceneView &scene, Vec3f p, const SpecularLobe *lobes, int n,
                                        const RegularizationParams &rp, const RegularizationParams &passRp,
                                        bool deltaOnly, bool allowIncompletePDF) {
    Float total = 0;
    for (uint32_t li = 0; li < scene.lights.size; ++li)
        if (RegularizedCandidate(scene, li, p, lobes, n, rp, passRp, deltaOnly, allowIncompletePDF))
            total += LightPMF(scene, li);
    return total;
}
// Picks a candidate with probability LightPMF / total (u in [0, 1)).
LU_INLINE LightPick PickRegularizedCandidate(const SceneView &scene, Vec3f p, const SpecularLobe *lobes, int n,
                                             const RegularizationParams &rp, const RegularizationParams &passRp,
                                             bool deltaOnly, bool allowIncompletePDF, Float total, Float u) {
    LightPick pick;
    Float target = u * total, run = 0;
    for (uint32_t li = 0; li < scene.lights.size; ++li) {
        if (!RegularizedCandidate(scene, li, p, lobes, n, rp, passRp, deltaOnly, allowIncompletePDF)) continue;
        Float pmf = LightPMF(scene, li);
        if (pmf <= 0) continue;
        pick.light = li;
        pick.pmf = pmf / total;
        run += pmf;
        if (target < run) break;
    }
    return pick;
}

// One light sample at a specular vertex among the candidates (total pmf candidatePmf > 0), tested
// against the cone of every Dirac lobe; each lobe it falls in is weighted against the implicit
// technique that picks that lobe (with the lobe's probability: lobe-aware MIS) and hits the light.
// With MNEE on (mnee.vertices > 0; in: the record of the path so far), a transmission lobe whose
// path MNEE would have found from the chain's start to the same light point, a light MNEE targets
// from there (MneeTargetsLight), is left to MNEE (weight 0 here).
template <typename Tracer>
LU_HD SampledSpectrum SampleRegularized(const SurfaceInteraction &si, const BSDF &bsdf, const SpecularLobe *lobes,
                                        int n, Float candidatePmf, bool deltaOnly, const ScatterVertex &in,
                                        MneeBudget mnee, const VertexMedia &vm, const SampledWavelengths &lambda,
                                        Sampler &sampler, const SceneView &scene, const Tracer &tracer,
                                        const RegularizationParams &rp, const RegularizationParams &passRp,
                                        LightStrategy strategy, PathStats &st) {
    Float uLight = sampler.Get1D();
    Vec2f u2 = sampler.Get2D();
    bool allowIncomplete = AllowIncompletePDF(strategy);
    LightPick pick = PickRegularizedCandidate(scene, si.p, lobes, n, rp, passRp, deltaOnly, allowIncomplete,
                                              candidatePmf, uLight);
    if (pick.light == NoIndex || pick.pmf == 0) return SampledSpectrum(0);
    const Light &light = scene.lights[pick.light];
    LightLiSample ls;
    if (!SampleLightPoint(scene, light, MakeLightContext(si), u2, lambda, allowIncomplete, &ls, BeamOneMinusCos(passRp)))
        return SampledSpectrum(0);
    // rp: this vertex's kernel (RegularizationAtVertex); a collimated beam keeps the pass's (BeamHitWeight).
    Float oneMinusCos = RegularizedOneMinusCos(light.kind == LightKind::Collimated ? passRp : rp, ls.distance);
    Float pdfConeW = ConePdfW(oneMinusCos);
    Float pdfLightW = ls.isDelta ? Infinity : pick.pmf * ls.pdf;
    // f_reg |cos| / p = weight * phi / pdf per lobe; for delta lights the "pdf" is the pmf alone.
    SampledSpectrum sum(0);
    bool inCone[2] = {false, false};
    int covered = -1;   // MNEE's verdict on the transmission lobe, computed once when needed
    for (int i = 0; i < n; ++i) {
        if (OneMinusCosBetween(lobes[i].wi, ls.wi) >= oneMinusCos) continue;
        if (mnee.vertices > 0 && (lobes[i].flags & BxDF_Transmission) && ls.distance != Infinity &&
            (ls.isDelta || light.kind == LightKind::DiffuseArea) &&
            MneeTargetsLight(strategy, mnee.maxSolidAngle, light, in.chainStart.p)) {
            if (covered < 0) {
                MneeChain ch;
                Float tol = 4 * (rp.radius + rp.radiusPerDistance * ls.distance) + 1e-3f * Distance(in.chainStart.p, si.p);
                covered = MneeCoversPath(in, si, bsdf.kind == BxDFKind::Dielectric, ls.pLight, ls.nLight, tol, lambda,
                                         scene, tracer, &ch) ? 1 : 0;
            }
            if (covered) continue;
        }
        inCone[i] = true;
        sum += lobes[i].weight * RegularizedConnectionWeight(lobes[i].pdf * pdfConeW, pdfLightW);
    }
    if (sum.IsBlack()) return SampledSpectrum(0);
    Ray shadow = SpawnShadowRay(si.p, si.n, ls.wi, ls.distance, ls.pLight);
    ShadowTransmittance tr;
    if (!ShadowRayVisible(scene, tracer, shadow, vm, ls.wi, lambda, st, &tr)) return SampledSpectrum(0);
    SampledSpectrum rL, rU;
    if (LightSamplePdfs(vm, tr, &rL, &rU)) {
        // Through media: the lobes' weights from the per-wavelength probabilities, and the
        // transmittance of the connection.
        sum = SampledSpectrum(0);
        for (int i = 0; i < n; ++i) {
            if (!inCone[i]) continue;
            Float pdfImplicitW = lobes[i].pdf * pdfConeW;
            sum += lobes[i].weight * (RegularizedConnectionWeight(rU[0] * pdfImplicitW, pdfLightW) *
                                      WavelengthWeight(rL, pdfLightW, rU, pdfImplicitW, lambda));
        }
        sum *= tr.T;
    }
    Float pSample = pick.pmf * ls.pdf;
    SampledSpectrum c = sum * ls.L * (pdfConeW / pSample);
    ++st.regConnections;
    return c;
}

// ---- The explicit techniques at one vertex ----

// Direct light at vertex si by every explicit technique that applies there: NEE at non-specular
// vertices, the regularized connection at specular ones (when the pass regularizes). `in` is the
// vertex the path came from; `out` (the record of this vertex for the next emitter hit) learns
// whether the regularized connection could have sampled area and infinite lights, and among which.
// Returns which technique ran: None when none applies (no random numbers are then consumed).
// depth: the vertex's index on the path (1 = first hit), for the length MNEE may add.
enum class DirectTechnique : uint8_t { None, LightSample, Regularized };

// Near-specular regularization: a rough conductor or dielectric narrower than kNearSpecularAlpha
// (or a layered BSDF whose coat or conductor base is such a lobe), at a vertex after a
// non-specular one (in: the record of the path so far; pathLength: this vertex's), is evaluated for
// delta lights with alpha raised to tan(sigma / 2) (at most kNearSpecularAlpha), sigma the
// half-angle of the regularized kernel a Dirac vertex here would use (RegularizedAngle: the
// footprint kernel's blur of at most K N^-lambda pixels at the last non-specular vertex, or
// sigma_N): a mirror lobe then spreads about as far as that cone. Delta lights are the one case
// nothing else samples: NEE evaluates a narrow lobe in a direction fixed by the earlier vertices,
// so its variance grows like 1 / alpha^2, and no other technique shares these paths, so no MIS
// weight changes. sigma falls as N^-lambda: from the pass where tan(sigma / 2) <= alpha on, the
// surface's own BSDF is used (consistent, and unbiased from then on). Camera paths through Dirac
// vertices only (glints) keep their narrow lobes: the pixel integral samples them.
// A smooth coat over a non-Dirac base (coated diffuse, varnish) is the Dirac lobe of a BSDF that is
// not Dirac as a whole: its reflection of a delta light is sampled by nothing (NEE sees the base,
// the BSDF-sampled mirror ray never hits a point light), as for a mirror, so it is widened the
// same way at every vertex, after Dirac-only camera paths too (as the regularized connection keeps
// delta lights there); the kernel shrinks to the Dirac lobe as the mirror's does.
// Nothing of this runs in scenes without delta lights. Writes the widened BSDF to *out and
// returns true where it applies.
LU_INLINE bool NearSpecularBsdf(const PathSettings &ps, const SceneView &scene, const BSDF &bsdf, const ScatterVertex &in,
                                Float pathLength, BSDF *out) {
    if (!ps.nearSpecular || !ps.reg.enabled || scene.deltaLights == 0) return false;
    BSDF::NearSpecularKind kind = bsdf.NearSpecular();
    if (kind == BSDF::NearSpecularKind::None || (in.allSpecular && kind != BSDF::NearSpecularKind::DiracCoat))
        return false;
    *out = bsdf;
    Float sigma = RegularizedAngle(VertexRegularization(ps, scene, in.receiverT, pathLength));
    return out->Roughen(Min(std::tan(Min(sigma, Float(1)) / 2), kNearSpecularAlpha), in.allSpecular);
}
template <typename Tracer>
LU_HD DirectTechnique SampleDirect(const SurfaceInteraction &si, const BSDF &bsdf, bool specular, const ScatterVertex &in,
                                   int depth, const VertexMedia &vm, const SampledWavelengths &lambda,
                                   Sampler &sampler, const SceneView &scene, const Tracer &tracer,
                                   const PathSettings &ps, PathStats &st, SampledSpectrum *Ld, ScatterVertex *out) {
    out->regularized = false;
    if (!specular && ps.strategy != LightStrategy::BSDFOnly) {
        BSDF wide;
        bool widened = NearSpecularBsdf(ps, scene, bsdf, in, out->pathLength, &wide);
        *Ld = SampleLd(si, bsdf, vm, lambda, sampler, scene, tracer, st, ps.strategy,
                       MneeAt(ps, scene, depth), BeamOneMinusCos(ps.reg), widened ? &wide : nullptr);
        return DirectTechnique::LightSample;
    }
    if (!ps.reg.enabled) return DirectTechnique::None;
    SpecularLobe lobes[2];
    int n = bsdf.SpecularLobes(si.wo, lobes);
    // Selectivity: after Dirac vertices only (from the camera) the pixel integral samples the paths
    // to area and infinite lights without bias; only delta lights need the technique there.
    bool deltaOnly = in.allSpecular;
    RegularizationParams rp = VertexRegularization(ps, scene, in.receiverT, out->pathLength);
    Float total = RegularizedCandidatePmf(scene, si.p, lobes, n, rp, ps.reg, deltaOnly, AllowIncompletePDF(ps.strategy));
    if (!(total > 0)) return DirectTechnique::None;
    // MNEE's verdict there concerns the chain from its start: on wherever the scene uses MNEE.
    MneeBudget mnee = MneeAt(ps, scene, 0);
    *Ld = SampleRegularized(si, bsdf, lobes, n, total, deltaOnly, in, mnee, vm, lambda, sampler, scene,
                            tracer, rp, ps.reg, ps.strategy, st);
    out->regularized = !deltaOnly;
    out->candidatePmf = total;
    return DirectTechnique::Regularized;
}

// ---- BSDF sampling, and the emitters it hits ----

// Whether area light li, hit at pLight after a refractive chain from a non-specular vertex, is a
// path MNEE from that vertex reproduces (it re-runs MNEE's deterministic solve). Then *pdfChainA
// is BSDF (phase) sampling's pdf of the chain and *pdfMneeA MNEE's, both in area measure at
// pLight. With the NEE-only strategy the answer is yes without a solve (the hit's weight is 0).
template <typename Tracer>
LU_HD bool MneeReproducesHit(const ScatterVertex &v, const SceneView &scene, uint32_t li, Vec3f pLight, Vec3f nLight,
                             bool atInfinity, const PathSettings &ps, const SampledWavelengths &lambda,
                             const Tracer &tracer, Float *pdfChainA, Float *pdfMneeA) {
    if (!v.specular || v.chainVertices < 0 || atInfinity || !UsesMnee(ps, scene) ||
        ps.strategy == LightStrategy::BSDFOnly || scene.lights[li].kind != LightKind::DiffuseArea ||
        !MneeTargetsLight(ps, scene.lights[li], v.chainStart.p))
        return false;
    if (ps.strategy == LightStrategy::NEEOnly) return true;
    MneeChain ch;
    MneeThroughput tp;
    Float tol = 1e-3f * Distance(v.chainStart.p, v.chainVertices > 0 ? v.chainFirst : pLight) + 1e-6f;
    if (!FindMneeChain(scene, tracer, v.chainStart.p, v.chainStart.n, pLight, nLight, lambda, &ch, &tp) ||
        !MneeChainMatches(ch, v.chainVertices, v.chainHash, v.chainFirst, tol))
        return false;
    Vec3f ws = pLight - v.chainStart.p;
    Float d = Length(ws);
    ws = ws / d;
    *pdfMneeA = LightPdfW(scene, li, v.chainStart, ws, pLight, nLight, AllowIncompletePDF(ps.strategy)) *
                AbsDot(nLight, ws) / Sqr(d);
    *pdfChainA = v.chainBsdfPdfW * v.chainLobePdf * MneeGeometry(ch, true);
    return true;
}


// EmitterHitWeight for a path that went through media: the technique weights at the hero
// wavelength from the per-wavelength probabilities (r.u[0] == 1), times the wavelength weight.
// After a refractive chain that MNEE from its start reproduces, MNEE is the partner technique, with
// the chain's per-wavelength probabilities r.lChain (SampleMnee's weight on the other side).
template <typename Tracer>
LU_HD Float EmitterHitWeightInMedia(const ScatterVertex &v, const SceneView &scene, uint32_t li, Vec3f wi,
                                    Vec3f pLight, Vec3f nLight, bool atInfinity, const PathSettings &ps,
                                    const WavelengthPdfs &r, const SampledWavelengths &lambda, const Tracer &tracer) {
    Float pdfMneeA, pdfChainA;
    if (MneeReproducesHit(v, scene, li, pLight, nLight, atInfinity, ps, lambda, tracer, &pdfChainA, &pdfMneeA)) {
        if (ps.strategy == LightStrategy::NEEOnly) return 0;
        return MneeWeight(pdfChainA, r.lChain[0] * pdfMneeA) * WavelengthWeight(r.u, pdfChainA, r.lChain, pdfMneeA, lambda);
    }
    if (v.camera || (v.specular && !v.regularized)) return WavelengthWeight(r.u, 1, r.l, 0, lambda);
    Float pdfLightW = LightPdfW(scene, li, v.ctx, wi, pLight, nLight, AllowIncompletePDF(ps.strategy));
    if (v.specular) {
        pdfLightW /= v.candidatePmf;   // the connection chose among candidates only
        Float d = atInfinity ? Infinity : Distance(v.ctx.p, pLight);
        Float pdfConeW = v.pdfBsdfW * ConePdfW(RegularizedOneMinusCos(VertexRegularization(ps, scene, v), d));   // lobe-aware
        return RegularizedHitWeight(pdfConeW, r.l[0] * pdfLightW) * WavelengthWeight(r.u, pdfConeW, r.l, pdfLightW, lambda);
    }
    if (ps.strategy == LightStrategy::NEEOnly) return 0;
    if (ps.strategy == LightStrategy::BSDFOnly) return WavelengthWeight(r.u, 1, r.l, 0, lambda);
    return BSDFHitWeight(ps.strategy, v.pdfBsdfW, r.l[0] * pdfLightW) *
           WavelengthWeight(r.u, v.pdfBsdfW, r.l, pdfLightW, lambda);
}

// MIS weight of emitter `li` hit along wi at pLight (normal nLight) from vertex v, against the
// explicit technique that could have sampled it there. Infinite lights: pLight = v.ctx.p + wi,
// nLight = -wi, atInfinity = true. r: the path's per-wavelength probabilities when it went
// through a medium (nullptr: scalar weights). After a chain of smooth transmissions from a non-specular
// vertex, MNEE is that technique where it finds this very chain to pLight (it re-runs MNEE's
// deterministic solve: the partner of SampleMnee's weight); elsewhere the regularized connection.
template <typename Tracer>
LU_HD Float EmitterHitWeight(const ScatterVertex &v, const SceneView &scene, uint32_t li, Vec3f wi, Vec3f pLight,
                             Vec3f nLight, bool atInfinity, const PathSettings &ps, const WavelengthPdfs *r,
                             const SampledWavelengths &lambda, const Tracer &tracer) {
    if (r) return EmitterHitWeightInMedia(v, scene, li, wi, pLight, nLight, atInfinity, ps, *r, lambda, tracer);
    if (v.camera) return 1;
    Float pdfMneeA, pdfChainA;
    if (MneeReproducesHit(v, scene, li, pLight, nLight, atInfinity, ps, lambda, tracer, &pdfChainA, &pdfMneeA))
        return ps.strategy == LightStrategy::NEEOnly ? 0 : MneeWeight(pdfChainA, pdfMneeA);
    if (v.specular && !v.regularized) return 1;
    Float pdfLightW = LightPdfW(scene, li, v.ctx, wi, pLight, nLight, AllowIncompletePDF(ps.strategy));
    if (v.specular) {   // lobe-aware: the implicit technique picked this Dirac lobe with probability pdfBsdfW
        pdfLightW /= v.candidatePmf;   // the connection chose among candidates only
        Float d = atInfinity ? Infinity : Distance(v.ctx.p, pLight);
        return RegularizedHitWeight(v.pdfBsdfW * ConePdfW(RegularizedOneMinusCos(VertexRegularization(ps, scene, v), d)),
                                    pdfLightW);
    }
    return BSDFHitWeight(ps.strategy, v.pdfBsdfW, pdfLightW);
}

// Samples the BSDF at si for the next direction: updates the throughput beta, the radiance scale
// for Russian roulette, the record v of this vertex and the ray. False when the path ends.
// v holds the vertex's record from SampleDirect (regularized, candidatePmf) and is completed here.
LU_INLINE bool SampleBSDFDirection(const SurfaceInteraction &si, const BSDF &bsdf, Sampler &sampler,
                                   SampledSpectrum &beta, Float &etaScale, ScatterVertex &v, Ray &ray) {
    Float uc = sampler.Get1D();
    Vec2f u2 = sampler.Get2D();
    BSDFSample bs;
    if (!bsdf.Sample_f(si.wo, uc, u2, &bs) || bs.pdf == 0 || bs.f.IsBlack()) return false;
    beta *= bs.f * (AbsDot(bs.wi, si.ns) / bs.pdf);
    v.pdfBsdfW = bs.pdfIsProportional ? bsdf.PDF(si.wo, bs.wi) : bs.pdf;
    v.camera = false;
    v.beamRegions = false;
    v.specular = bs.IsSpecular();
    if (!bsdf.IsSpecular()) {   // NEE (and MNEE) ran here: a chain may start
        v.chainVertices = v.specular ? -1 : 0;
        v.chainHash = 0;
        v.chainStart = MakeLightContext(si);
        v.chainBsdfPdfW = v.pdfBsdfW;
        v.chainLobePdf = 1;
    } else if (v.chainVertices >= 0) {
        bool refracts = bs.IsTransmission() && bsdf.kind == BxDFKind::Dielectric;
        bool passes = bs.IsTransmission() && bsdf.kind == BxDFKind::ThinDielectric;
        if (refracts && v.chainVertices < MaxMneeVertices) {
            if (v.chainVertices == 0) v.chainFirst = si.p;
            ++v.chainVertices;
            v.chainHash = MneeShapeHash(v.chainHash, si.shape);
            v.chainLobePdf *= bs.pdf;
        } else if (passes) {
            v.chainLobePdf *= bs.pdf;
        } else {
            v.chainVertices = -1;
        }
    }
    v.allSpecular = v.allSpecular && v.specular;
    if (!v.specular) v.receiverT = v.pathLength;   // where a later regularized kernel's blur lands
    v.regularized = v.specular && v.regularized;
    v.ctx = MakeLightContext(si);
    if (bs.IsTransmission()) etaScale *= Sqr(bs.eta);
    ray.o = OffsetRayOrigin(si.p, si.n, bs.wi);
    ray.d = bs.wi;
    ray.tMax = Infinity;
    return true;
}

}  // namespace lu
