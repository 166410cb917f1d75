// Lucerna: the BSDF at a surface point (tagged union of the BxDFs + shading frame) and MakeBSDF,
// which evaluates a material's textures (host and device). Follows pbrt-v4's bsdf.h and the
// materials' GetBxDF; adds SpecularLobes, the Dirac lobes the regularized connection needs.
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"
#include "lucerna/materials/bxdfs.h"
#include "lucerna/materials/texture.h"

namespace lu {

// One ideal (Dirac) lobe at a specular vertex: the BSDF contains weight * delta(wi - dir) / |cos wi|
// (wi in render space). weight: Fresnel R for reflection; T (divided by eta^2 in Radiance mode)
// for transmission; the complex Fresnel for a conductor; the slab R/T for a thin dielectric.
// eta: relative index across a transmission (1 for reflection). pdf: the probability that
// Sample_f picks this lobe (R / (R + T) or T / (R + T) for dielectrics, 1 for a conductor).
struct SpecularLobe {
    Vec3f wi;
    SampledSpectrum weight;
    uint8_t flags = 0;
    Float eta = 1;
    Float pdf = 1;
};

enum class BxDFKind : uint8_t { None, Diffuse, Conductor, Dielectric, ThinDielectric, CoatedDiffuse };

struct BSDF {
    BxDFKind kind = BxDFKind::None;
    Frame shadingFrame;   // z = shading normal, x along the shading dpdu
    union {
        DiffuseBxDF diffuse;
        ConductorBxDF conductor;
        DielectricBxDF dielectric;
        ThinDielectricBxDF thinDielectric;
        CoatedDiffuseBxDF coatedDiffuse;
    };

    LU_HD BSDF() : diffuse() {}

    LU_HD Vec3f RenderToLocal(const Vec3f &v) const { return shadingFrame.ToLocal(v); }
    LU_HD Vec3f LocalToRender(const Vec3f &v) const { return shadingFrame.FromLocal(v); }

    // ---- Dispatch over the BxDF kinds (local frame) ----
    LU_HD uint8_t Flags() const {
        switch (kind) {
        case BxDFKind::Diffuse: return diffuse.Flags();
        case BxDFKind::Conductor: return conductor.Flags();
        case BxDFKind::Dielectric: return dielectric.Flags();
        case BxDFKind::ThinDielectric: return thinDielectric.Flags();
        case BxDFKind::CoatedDiffuse: return coatedDiffuse.Flags();
        default: return BxDF_Unset;
        }
    }
    LU_HD SampledSpectrum fLocal(Vec3f wo, Vec3f wi, TransportMode mode) const {
        switch (kind) {
        case BxDFKind::Diffuse: return diffuse.f(wo, wi, mode);
        case BxDFKind::Conductor: return conductor.f(wo, wi, mode);
        case BxDFKind::Dielectric: return dielectric.f(wo, wi, mode);
        case BxDFKind::ThinDielectric: return thinDielectric.f(wo, wi, mode);
        case BxDFKind::CoatedDiffuse: return coatedDiffuse.f(wo, wi, mode);
        default: return SampledSpectrum(0);
        }
    }
    LU_HD bool Sample_fLocal(Vec3f wo, Float uc, Vec2f u, TransportMode mode, uint8_t sampleFlags, BSDFSample *bs) const {
        switch (kind) {
        case BxDFKind::Diffuse: return diffuse.Sample_f(wo, uc, u, mode, sampleFlags, bs);
        case BxDFKind::Conductor: return conductor.Sample_f(wo, uc, u, mode, sampleFlags, bs);
        case BxDFKind::Dielectric: return dielectric.Sample_f(wo, uc, u, mode, sampleFlags, bs);
        case BxDFKind::ThinDielectric: return thinDielectric.Sample_f(wo, uc, u, mode, sampleFlags, bs);
        case BxDFKind::CoatedDiffuse: return coatedDiffuse.Sample_f(wo, uc, u, mode, sampleFlags, bs);
        default: return false;
        }
    }
    LU_HD Float PDFLocal(Vec3f wo, Vec3f wi, TransportMode mode, uint8_t sampleFlags) const {
        switch (kind) {
        case BxDFKind::Diffuse: return diffuse.PDF(wo, wi, mode, sampleFlags);
        case BxDFKind::Conductor: return conductor.PDF(wo, wi, mode, sampleFlags);
        case BxDFKind::Dielectric: return dielectric.PDF(wo, wi, mode, sampleFlags);
        case BxDFKind::ThinDielectric: return thinDielectric.PDF(wo, wi, mode, sampleFlags);
        case BxDFKind::CoatedDiffuse: return coatedDiffuse.PDF(wo, wi, mode, sampleFlags);
        default: return 0;
        }
    }

    // ---- Render-space interface (pbrt-v4's BSDF) ----

    // BSDF value for directions in render space (both pointing away from the surface); 0 when wo
    // is exactly in the tangent plane. Dirac lobes evaluate to 0.
    LU_HD SampledSpectrum f(Vec3f woRender, Vec3f wiRender, TransportMode mode = TransportMode::Radiance) const {
        if (kind == BxDFKind::Diffuse) {   // reads only the local z components: two dots, not six
            Float woz = Dot(woRender, shadingFrame.z);
            if (woz == 0) return SampledSpectrum(0);
            return diffuse.f(Vec3f(0, 0, woz), Vec3f(0, 0, Dot(wiRender, shadingFrame.z)), mode);
        }
        Vec3f wi = RenderToLocal(wiRender), wo = RenderToLocal(woRender);
        if (wo.z == 0) return SampledSpectrum(0);
        return fLocal(wo, wi, mode);
    }

    // Samples wi (render space) given uc (lobe choice) and u; false if no sample (bs untouched or
    // partially written). A returned sample has f nonzero, pdf > 0 and wi off the tangent plane.
    LU_HD bool Sample_f(Vec3f woRender, Float uc, Vec2f u, BSDFSample *bs, TransportMode mode = TransportMode::Radiance,
                        uint8_t sampleFlags = BxDF_SampleAll) const {
        // Diffuse sampling reads only wo.z (the side of the surface).
        Vec3f wo = kind == BxDFKind::Diffuse ? Vec3f(0, 0, Dot(woRender, shadingFrame.z)) : RenderToLocal(woRender);
        if (wo.z == 0 || !(Flags() & sampleFlags)) return false;
        if (!Sample_fLocal(wo, uc, u, mode, sampleFlags, bs)) return false;
        if (!bs->f || !(bs->pdf > 0) || bs->wi.z == 0) return false;
        bs->wi = LocalToRender(bs->wi);
        return true;
    }

    // pdfW of Sample_f choosing wiRender (0 for Dirac lobes). For layered BSDFs a stochastic estimate.
    LU_HD Float PDF(Vec3f woRender, Vec3f wiRender, TransportMode mode = TransportMode::Radiance,
                    uint8_t sampleFlags = BxDF_SampleAll) const {
        if (kind == BxDFKind::Diffuse) {   // reads only the local z components
            Float woz = Dot(woRender, shadingFrame.z);
            if (woz == 0) return 0;
            return diffuse.PDF(Vec3f(0, 0, woz), Vec3f(0, 0, Dot(wiRender, shadingFrame.z)), mode, sampleFlags);
        }
        Vec3f wo = RenderToLocal(woRender), wi = RenderToLocal(wiRender);
        if (wo.z == 0) return 0;
        return PDFLocal(wo, wi, mode, sampleFlags);
    }

    // True when every lobe is a Dirac: smooth conductor, smooth or index-matched dielectric,
    // thin dielectric (and a coated diffuse with a smooth coat over a black base, no medium).
    LU_HD bool IsSpecular() const {
        if (kind == BxDFKind::Dielectric && dielectric.IsDirac()) return true;
        uint8_t fl = Flags();
        return lu::IsSpecular(fl) && !IsNonSpecular(fl);
    }
    LU_HD explicit operator bool() const { return kind != BxDFKind::None; }

    // Directional albedo estimate (pbrt-v4's BSDF::rho): mean of f |cos| / pdf over n samples.
    LU_HD SampledSpectrum rho(Vec3f woRender, const Float *uc, const Vec2f *u2, int n) const {
        SampledSpectrum r(0);
        if (n <= 0) return r;
        for (int i = 0; i < n; ++i) {
            BSDFSample bs;
            if (Sample_f(woRender, uc[i], u2[i], &bs)) r += bs.f * (AbsDot(bs.wi, shadingFrame.z) / bs.pdf);
        }
        return r / Float(n);
    }

    // The Dirac lobes for outgoing direction woRender; returns their number (0..2). A coated
    // diffuse with a smooth coat reports its coat reflection (the rest of it is not Dirac).
    LU_HD int SpecularLobes(Vec3f woRender, SpecularLobe lobes[2], TransportMode mode = TransportMode::Radiance) const {
        Vec3f wo = RenderToLocal(woRender);
        if (wo.z == 0) return 0;
        int n = 0;
        auto add = [&](Vec3f wiLocal, const SampledSpectrum &w, uint8_t flags, Float eta, Float pdf) {
            if (!w || wiLocal.z == 0) return;
            lobes[n].wi = LocalToRender(wiLocal);
            lobes[n].weight = w;
            lobes[n].flags = flags;
            lobes[n].eta = eta;
            lobes[n].pdf = pdf;
            ++n;
        };
        Vec3f wr(-wo.x, -wo.y, wo.z);
        switch (kind) {
        case BxDFKind::Conductor:
            if (conductor.mfDistrib.EffectivelySmooth())
                add(wr, FrComplex(AbsCosTheta(wo), conductor.eta, conductor.k), BxDF_SpecularReflection, 1, 1);
            break;
        case BxDFKind::Dielectric:
        case BxDFKind::CoatedDiffuse: {
            const DielectricBxDF &d = (kind == BxDFKind::Dielectric) ? dielectric : coatedDiffuse.top;
            if (!d.IsDirac()) break;
            Float cosO = CosTheta(wo);
            if (kind == BxDFKind::CoatedDiffuse) cosO = AbsCosTheta(wo);   // two-sided coat
            Float R = FrDielectric(cosO, d.eta), T = 1 - R;
            // Sample_f picks reflection with R / (R + T); a coated diffuse samples its coat the same way.
            add(wr, SampledSpectrum(R), BxDF_SpecularReflection, 1, R / (R + T));
            if (kind == BxDFKind::Dielectric) {
                Vec3f wt;
                Float etap;
                if (T > 0 && Refract(wo, Vec3f(0, 0, 1), d.eta, &etap, &wt)) {
                    Float w = T;
                    if (mode == TransportMode::Radiance) w /= Sqr(etap);
                    add(wt, SampledSpectrum(w), BxDF_SpecularTransmission, etap, T / (R + T));
                }
            }
            break;
        }
        case BxDFKind::ThinDielectric: {
            Float R, T;
            thinDielectric.RT(AbsCosTheta(wo), &R, &T);
            add(wr, SampledSpectrum(R), BxDF_SpecularReflection, 1, R / (R + T));
            add(-wo, SampledSpectrum(T), BxDF_SpecularTransmission, 1, T / (R + T));
            break;
        }
        default: break;
        }
        return n;
    }
};

// ---- Materials (pbrt-v4's materials.h GetBxDF) ----

LU_INLINE SampledSpectrum ClampSpectrum(const SampledSpectrum &s, Float lo, Float hi) {
    SampledSpectrum r;
    for (int i = 0; i < NSpectrumSamples; ++i) r[i] = Clamp(s[i], lo, hi);
    return r;
}

LU_INLINE TrowbridgeReitzDistribution MakeDistribution(const Material &m, const TextureEvalContext &ctx,
                                                       const SceneView &scene) {
    Float uRough = EvalFloatTexture(m.uRoughness, ctx, scene);
    Float vRough = EvalFloatTexture(m.vRoughness, ctx, scene);
    if (m.remapRoughness) {
        uRough = TrowbridgeReitzDistribution::RoughnessToAlpha(uRough);
        vRough = TrowbridgeReitzDistribution::RoughnessToAlpha(vRough);
    }
    return TrowbridgeReitzDistribution(uRough, vRough);
}

// Relative index of refraction at the hero wavelength; a non-constant (dispersive) eta keeps
// only the hero wavelength. 0 is treated as 1, as pbrt-v4 does.
LU_INLINE Float SampleEta(const Spectrum &eta, SampledWavelengths &lambda, const SceneView &scene) {
    Float e = EvalSpectrum(eta, lambda.lambda[0], scene.spectra);
    if (!eta.IsConstant()) lambda.TerminateSecondary();
    if (e == 0) e = 1;
    return e;
}

// Evaluates the textures of material m at si and builds the BSDF in si's shading frame
// (z = si.ns, x along si.dpdu). Returns false for interface materials (no surface).
// May call lambda.TerminateSecondary() (dispersive dielectrics).
LU_INLINE bool MakeBSDF(const Material &m, const SurfaceInteraction &si, SampledWavelengths &lambda,
                        const SceneView &scene, BSDF *bsdf) {
    if (m.kind == MaterialKind::Interface) return false;
    TextureEvalContext ctx;
    ctx.p = si.p;
    ctx.n = si.n;
    ctx.uv = si.uv;
    bsdf->shadingFrame = Frame::FromXZ(si.dpdu, si.ns);
    switch (m.kind) {
    case MaterialKind::Diffuse: {
        SampledSpectrum r = ClampSpectrum(EvalSpectrumTexture(m.reflectance, ctx, lambda, scene), 0, 1);
        bsdf->kind = BxDFKind::Diffuse;
        bsdf->diffuse = DiffuseBxDF(r);
        return true;
    }
    case MaterialKind::Conductor: {
        TrowbridgeReitzDistribution distrib = MakeDistribution(m, ctx, scene);
        SampledSpectrum etas, ks;
        if (!m.useReflectance) {
            etas = EvalSpectrumTexture(m.conductorEta, ctx, lambda, scene);
            ks = EvalSpectrumTexture(m.conductorK, ctx, lambda, scene);
        } else {
            // pbrt-v4: a reflectance r becomes eta = 1, k = 2 sqrt(r) / sqrt(1 - r) (normal-incidence F = r).
            SampledSpectrum r = ClampSpectrum(EvalSpectrumTexture(m.reflectance, ctx, lambda, scene), 0, .9999f);
            etas = SampledSpectrum(1);
            ks = Sqrt(r) * 2 / Sqrt(ClampZero(SampledSpectrum(1) - r));
        }
        bsdf->kind = BxDFKind::Conductor;
        bsdf->conductor = ConductorBxDF(distrib, etas, ks);
        return true;
    }
    case MaterialKind::Dielectric: {
        Float eta = SampleEta(m.eta, lambda, scene);
        bsdf->kind = BxDFKind::Dielectric;
        bsdf->dielectric = DielectricBxDF(eta, MakeDistribution(m, ctx, scene));
        return true;
    }
    case MaterialKind::ThinDielectric: {
        Float eta = SampleEta(m.eta, lambda, scene);
        bsdf->kind = BxDFKind::ThinDielectric;
        bsdf->thinDielectric = ThinDielectricBxDF(eta);
        return true;
    }
    case MaterialKind::CoatedDiffuse: {
        SampledSpectrum r = ClampSpectrum(EvalSpectrumTexture(m.reflectance, ctx, lambda, scene), 0, 1);
        TrowbridgeReitzDistribution distrib = MakeDistribution(m, ctx, scene);
        Float thick = EvalFloatTexture(m.thickness, ctx, scene);
        Float eta = SampleEta(m.eta, lambda, scene);
        SampledSpectrum a = ClampSpectrum(EvalSpectrumTexture(m.albedo, ctx, lambda, scene), 0, 1);
        Float gg = Clamp(EvalFloatTexture(m.g, ctx, scene), Float(-1), Float(1));
        bsdf->kind = BxDFKind::CoatedDiffuse;
        bsdf->coatedDiffuse = CoatedDiffuseBxDF(DielectricBxDF(eta, distrib), DiffuseBxDF(r), thick, a, gg,
                                                m.maxDepth, m.nSamples);
        return true;
    }
    default: return false;
    }
}

}  // namespace lu
