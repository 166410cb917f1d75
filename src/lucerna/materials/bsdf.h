// Lucerna: the BSDF at a surface point (tagged union of the BxDFs + shading frame) and MakeBSDF,
// which evaluates a material's textures (host and device). Follows pbrt-v4's bsdf.h and the
// materials' GetBxDF; adds SpecularLobes, the Dirac lobes the regularized connection needs.
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"
#include "lucerna/geometry/shapes.h"
#include "lucerna/materials/bxdfs.h"
#include "lucerna/materials/measured.h"
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

enum class BxDFKind : uint8_t {
    None, Diffuse, Conductor, Dielectric, ThinDielectric, CoatedDiffuse, CoatedConductor, DiffuseTransmission, Hair, Measured
};

// Microfacet lobes narrower than this (alpha, both axes) are near-specular: regpath may widen them
// for delta lights (BSDF::Roughen), never beyond it.
constexpr Float kNearSpecularAlpha = 0.1f;

struct BSDF {
    BxDFKind kind = BxDFKind::None;
    Frame shadingFrame;   // z = shading normal, x along the shading dpdu
    union {
        DiffuseBxDF diffuse;
        ConductorBxDF conductor;
        DielectricBxDF dielectric;
        ThinDielectricBxDF thinDielectric;
        CoatedDiffuseBxDF coatedDiffuse;
        CoatedConductorBxDF coatedConductor;
        DiffuseTransmissionBxDF diffuseTransmission;
        HairBxDF hair;
        MeasuredBxDF measured;
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
        case BxDFKind::CoatedConductor: return coatedConductor.Flags();
        case BxDFKind::DiffuseTransmission: return diffuseTransmission.Flags();
        case BxDFKind::Hair: return hair.Flags();
        case BxDFKind::Measured: return measured.Flags();
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
        case BxDFKind::CoatedConductor: return coatedConductor.f(wo, wi, mode);
        case BxDFKind::DiffuseTransmission: return diffuseTransmission.f(wo, wi, mode);
        case BxDFKind::Hair: return hair.f(wo, wi, mode);
        case BxDFKind::Measured: return measured.f(wo, wi, mode);
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
        case BxDFKind::CoatedConductor: return coatedConductor.Sample_f(wo, uc, u, mode, sampleFlags, bs);
        case BxDFKind::DiffuseTransmission: return diffuseTransmission.Sample_f(wo, uc, u, mode, sampleFlags, bs);
        case BxDFKind::Hair: return hair.Sample_f(wo, uc, u, mode, sampleFlags, bs);
        case BxDFKind::Measured: return measured.Sample_f(wo, uc, u, mode, sampleFlags, bs);
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
        case BxDFKind::CoatedConductor: return coatedConductor.PDF(wo, wi, mode, sampleFlags);
        case BxDFKind::DiffuseTransmission: return diffuseTransmission.PDF(wo, wi, mode, sampleFlags);
        case BxDFKind::Hair: return hair.PDF(wo, wi, mode, sampleFlags);
        case BxDFKind::Measured: return measured.PDF(wo, wi, mode, sampleFlags);
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

    // Near-specular regularization (integrators/techniques.h, NearSpecularBsdf). Narrow: a rough
    // conductor or dielectric (not index-matched) narrower than kNearSpecularAlpha on both axes and
    // not a Dirac lobe, or a layered BSDF whose coat (not index-matched) or whose conductor base is
    // such a lobe. DiracCoat: a coated diffuse or coated conductor with a smooth coat that is not
    // Dirac as a whole (IsSpecular false): NEE sees its non-Dirac part only, so a delta light's
    // reflection in the coat is sampled by no technique at all. None: everything else (Dirac BSDFs,
    // which the regularized connection handles, rougher lobes, diffuse, hair, measured).
    enum class NearSpecularKind : uint8_t { None, Narrow, DiracCoat };
    LU_HD static bool NarrowLobe(const TrowbridgeReitzDistribution &d) {
        return !d.EffectivelySmooth() && Max(d.alphaX, d.alphaY) < kNearSpecularAlpha;
    }
    LU_HD NearSpecularKind NearSpecular() const {
        switch (kind) {
        case BxDFKind::Conductor:
            return NarrowLobe(conductor.mfDistrib) ? NearSpecularKind::Narrow : NearSpecularKind::None;
        case BxDFKind::Dielectric:
            return dielectric.eta != 1 && NarrowLobe(dielectric.mfDistrib) ? NearSpecularKind::Narrow
                                                                         : NearSpecularKind::None;
        case BxDFKind::CoatedDiffuse:
        case BxDFKind::CoatedConductor: {
            const DielectricBxDF &top = kind == BxDFKind::CoatedDiffuse ? coatedDiffuse.top : coatedConductor.top;
            if (top.eta != 1 && top.mfDistrib.EffectivelySmooth() && !IsSpecular()) return NearSpecularKind::DiracCoat;
            if (top.eta != 1 && NarrowLobe(top.mfDistrib)) return NearSpecularKind::Narrow;
            if (kind == BxDFKind::CoatedConductor && NarrowLobe(coatedConductor.bottom.mfDistrib))
                return NearSpecularKind::Narrow;
            return NearSpecularKind::None;
        }
        default: return NearSpecularKind::None;
        }
    }
    LU_HD bool IsNearSpecular() const { return NearSpecular() != NearSpecularKind::None; }
    // Widens the lobes NearSpecular reports to alpha >= alphaMin (each axis): Dirac coats always,
    // narrow lobes unless diracCoatOnly. Returns false, changing nothing that matters, when no lobe
    // widens (already that rough, or alphaMin too small to make a Dirac coat a lobe).
    LU_HD bool Roughen(Float alphaMin, bool diracCoatOnly = false) {
        NearSpecularKind k = NearSpecular();
        if (k == NearSpecularKind::None || (diracCoatOnly && k != NearSpecularKind::DiracCoat)) return false;
        auto widen = [alphaMin](TrowbridgeReitzDistribution &d) {
            if (!(alphaMin > Min(d.alphaX, d.alphaY))) return false;
            TrowbridgeReitzDistribution w = d;
            w.alphaX = Max(w.alphaX, alphaMin);
            w.alphaY = Max(w.alphaY, alphaMin);
            if (w.EffectivelySmooth()) return false;   // still a Dirac lobe
            d = w;
            return true;
        };
        switch (kind) {
        case BxDFKind::Conductor: return widen(conductor.mfDistrib);
        case BxDFKind::Dielectric: return widen(dielectric.mfDistrib);
        case BxDFKind::CoatedDiffuse:
        case BxDFKind::CoatedConductor: {
            DielectricBxDF &top = kind == BxDFKind::CoatedDiffuse ? coatedDiffuse.top : coatedConductor.top;
            bool changed = false;
            if (top.eta != 1 && (top.mfDistrib.EffectivelySmooth() ? k == NearSpecularKind::DiracCoat
                                                                   : !diracCoatOnly && NarrowLobe(top.mfDistrib)))
                changed = widen(top.mfDistrib);
            if (kind == BxDFKind::CoatedConductor && !diracCoatOnly && NarrowLobe(coatedConductor.bottom.mfDistrib))
                changed = widen(coatedConductor.bottom.mfDistrib) || changed;
            return changed;
        }
        default: return false;
        }
    }

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
    // diffuse or coated conductor with a smooth coat reports its coat reflection only (the light
    // that enters the coat is not reported, even over a smooth conductor).
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
        case BxDFKind::CoatedDiffuse:
        case BxDFKind::CoatedConductor: {
            const DielectricBxDF &d = kind == BxDFKind::Dielectric      ? dielectric
                                      : kind == BxDFKind::CoatedDiffuse ? coatedDiffuse.top
                                                                        : coatedConductor.top;
            if (!d.IsDirac()) break;
            Float cosO = CosTheta(wo);
            if (kind != BxDFKind::Dielectric) cosO = AbsCosTheta(wo);   // two-sided coat
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
// A material's textured eta (etaTexture) is evaluated at ctx and is the same at every wavelength.
LU_INLINE Float SampleEta(const Spectrum &eta, SampledWavelengths &lambda, const SceneView &scene) {
    Float e = EvalSpectrum(eta, lambda.lambda[0], scene.spectra);
    if (!eta.IsConstant()) lambda.TerminateSecondary();
    if (e == 0) e = 1;
    return e;
}
LU_INLINE Float SampleEta(const Material &m, const TextureEvalContext &ctx, SampledWavelengths &lambda,
                          const SceneView &scene) {
    if (m.etaTexture == NoIndex) return SampleEta(m.eta, lambda, scene);
    Float e = EvalFloatTexture(scene.floatTextures[m.etaTexture], ctx, scene);
    return e == 0 ? 1 : e;
}

// Complex index of a conductor (conductor, coatedconductor's base): eta/k textures, or pbrt-v4's
// reflectance r -> eta = 1, k = 2 sqrt(r) / sqrt(1 - r) (normal-incidence Fresnel = r).
LU_INLINE void ConductorEtaK(const Material &m, const TextureEvalContext &ctx, const SampledWavelengths &lambda,
                             const SceneView &scene, SampledSpectrum *eta, SampledSpectrum *k) {
    if (!m.useReflectance) {
        *eta = EvalSpectrumTexture(m.conductorEta, ctx, lambda, scene);
        *k = EvalSpectrumTexture(m.conductorK, ctx, lambda, scene);
    } else {
        SampledSpectrum r = ClampSpectrum(EvalSpectrumTexture(m.reflectance, ctx, lambda, scene), 0, .9999f);
        *eta = SampledSpectrum(1);
        *k = Sqrt(r) * 2 / Sqrt(ClampZero(SampledSpectrum(1) - r));
    }
}

// pbrt-v4's MixMaterial::ChooseMaterial, repeated while the choice is itself a mix: amount <= 0
// picks the first material, >= 1 the second, otherwise the second where a hash of (p, wo) and
// the two children, uniform in [0,1), is <= amount. Deterministic: the same point seen along the
// same direction always scatters with the same material (shadow rays and MIS see the same BSDF).
LU_INLINE const Material &ResolveMixMaterial(const Material &m, const SurfaceInteraction &si, const SceneView &scene) {
    const Material *cur = &m;
    while (cur->kind == MaterialKind::Mix) {
        TextureEvalContext ctx;
        ctx.p = si.p;
        ctx.n = si.n;
        ctx.uv = si.uv;
        Float amount = EvalFloatTexture(cur->amount, ctx, scene);
        uint32_t m0 = cur->mixMaterials[0], m1 = cur->mixMaterials[1];
        uint32_t pick;
        if (amount <= 0) pick = m0;
        else if (amount >= 1) pick = m1;
        else pick = amount < HashFloat(si.p, si.wo, m0, m1) ? m0 : m1;
        cur = &scene.materials[pick];
    }
    return *cur;
}

// pbrt-v4's NormalMap: the tangent-space normal 2 rgb - 1 of the map at (u, 1 - v) (repeat
// wrap), in the shading frame f, becomes the shading normal (on n's side), with the shading
// tangent made orthogonal to it (Gram-Schmidt). Computed in f's local coordinates, so that a flat
// map ((0.5, 0.5, 1) everywhere: local normal exactly (0, 0, 1)) returns f bit for bit. The
// bilinear lookup is written as nested lerps, exact where the four texels are equal.
LU_INLINE Float NormalMapChannel(const ImageData &img, const SceneView &scene, Vec2f st, int c) {
    Float x = st.x * img.width - 0.5f, y = st.y * img.height - 0.5f;
    Float fx = std::floor(x), fy = std::floor(y);
    int xi = int(fx), yi = int(fy);
    Float dx = x - fx, dy = y - fy;
    Float v00 = ImageTexel(img, scene, xi, yi, c), v10 = ImageTexel(img, scene, xi + 1, yi, c);
    Float v01 = ImageTexel(img, scene, xi, yi + 1, c), v11 = ImageTexel(img, scene, xi + 1, yi + 1, c);
    Float top = v00 + dx * (v10 - v00), bottom = v01 + dx * (v11 - v01);
    return top + dy * (bottom - top);
}
LU_INLINE Frame NormalMappedFrame(const Frame &f, const ImageData &img, const SceneView &scene, Vec2f uv, Vec3f n) {
    Vec2f st(uv.x, 1 - uv.y);
    Vec3f nl(2 * NormalMapChannel(img, scene, st, 0) - 1, 2 * NormalMapChannel(img, scene, st, 1) - 1,
             2 * NormalMapChannel(img, scene, st, 2) - 1);
    if (!(LengthSquared(nl) > 0)) return f;   // a black texel has no direction: keep the frame
    nl = Normalize(nl);
    Frame r;
    r.z = f.FromLocal(nl);
    if (Dot(r.z, n) < 0) r.z = -r.z;          // pbrt-v4: the shading normal faces n's side
    Vec3f xl = Vec3f(1, 0, 0) - nl * nl.x;    // the tangent (1, 0, 0) orthogonal to the new normal
    if (!(LengthSquared(xl) > 1e-12f)) return Frame::FromZ(r.z);
    r.x = f.FromLocal(Normalize(xl));
    r.y = Cross(r.z, r.x);
    return r;
}

// pbrt-v4's BumpMap: the surface displaced by the texture D along the shading normal,
// p' = p + D ns, has tangents dp'/du = dpdu + dD/du ns + D dndu (and in v); dD/du by forward
// differences of du = dv = 0.0005 (pbrt-v4's step without ray differentials, which Lucerna has
// not). Its normal dp'/du x dp'/dv, on n's side, and the tangent dp'/du make the frame. A
// degenerate displaced frame keeps f.
LU_INLINE Frame BumpMappedFrame(const Frame &f, const FloatTexture &disp, const SurfaceInteraction &si,
                                const SceneView &scene) {
    constexpr Float du = .0005f, dv = .0005f;
    ShadingDerivatives sd = ComputeShadingDerivatives(scene, si);
    TextureEvalContext ctx;
    ctx.p = si.p;
    ctx.n = si.n;
    ctx.uv = si.uv;
    Float displace = EvalFloatTexture(disp, ctx, scene);
    TextureEvalContext shifted = ctx;
    shifted.p = si.p + sd.dpdu * du;
    shifted.uv = Vec2f(si.uv.x + du, si.uv.y);
    Float uDisplace = EvalFloatTexture(disp, shifted, scene);
    shifted.p = si.p + sd.dpdv * dv;
    shifted.uv = Vec2f(si.uv.x, si.uv.y + dv);
    Float vDisplace = EvalFloatTexture(disp, shifted, scene);
    Vec3f dpdu = sd.dpdu + si.ns * ((uDisplace - displace) / du) + sd.dndu * displace;
    Vec3f dpdv = sd.dpdv + si.ns * ((vDisplace - displace) / dv) + sd.dndv * displace;
    Vec3f ns = Cross(dpdu, dpdv);
    Float l2 = LengthSquared(ns);
    if (!(l2 > 0) || !(l2 < Infinity)) return f;
    ns = ns / std::sqrt(l2);
    if (Dot(ns, si.n) < 0) ns = -ns;    // pbrt-v4's SetShadingGeometry: FaceForward(ns, n)
    return Frame::FromXZ(dpdu, ns);
}

// pbrt-v4's HairMaterial::GetBxDF: the roughnesses clamped to [0.01, 1], the absorption from
// sigma_a (clamped at 0), from a colour in [0, 1] (SigmaAFromReflectance) or from the melanin
// concentrations (clamped at 0; their RGB absorption as an unbounded sRGB spectrum), and the
// fiber offset h = -1 + 2 v from the hit's uv.
LU_INLINE HairBxDF MakeHairBxDF(const Material &m, const TextureEvalContext &ctx, Vec2f uv,
                                const SampledWavelengths &lambda, const SceneView &scene) {
    Float bm = Max(Float(1e-2), Min(Float(1), EvalFloatTexture(m.betaM, ctx, scene)));
    Float bn = Max(Float(1e-2), Min(Float(1), EvalFloatTexture(m.betaN, ctx, scene)));
    Float a = EvalFloatTexture(m.hairAlpha, ctx, scene);
    Float e = EvalFloatTexture(m.hairEta, ctx, scene);
    SampledSpectrum sig_a;
    if (m.hairColor == HairColor::SigmaA) {
        sig_a = ClampZero(EvalSpectrumTexture(m.hairSigmaA, ctx, lambda, scene));
    } else if (m.hairColor == HairColor::Reflectance) {
        SampledSpectrum c = ClampSpectrum(EvalSpectrumTexture(m.reflectance, ctx, lambda, scene), 0, 1);
        sig_a = HairBxDF::SigmaAFromReflectance(c, bn);
    } else {
        Float ce = Max(Float(0), EvalFloatTexture(m.eumelanin, ctx, scene));
        Float cp = Max(Float(0), EvalFloatTexture(m.pheomelanin, ctx, scene));
        Float rgb[3];
        HairBxDF::SigmaAFromConcentrationRGB(ce, cp, rgb);
        sig_a = RGBToSampledSpectrum(rgb, true, lambda, scene, uint32_t(ColorSpaceId::SRGB));
    }
    Float h = -1 + 2 * uv.y;
    return HairBxDF(h, e, sig_a, bm, bn, a);
}

// Evaluates the textures of material m at si and builds the BSDF in si's shading frame (z =
// si.ns, x along si.dpdu; with a normal map, NormalMappedFrame of it, else with a displacement
// texture BumpMappedFrame). Returns false for
// interface materials (no surface). A mix material is first resolved to the material it picks at
// si (ResolveMixMaterial). May call lambda.TerminateSecondary() (dispersive dielectrics, coats).
LU_INLINE bool MakeBSDF(const Material &material, const SurfaceInteraction &si, SampledWavelengths &lambda,
                        const SceneView &scene, BSDF *bsdf) {
    const Material &m = material.kind == MaterialKind::Mix ? ResolveMixMaterial(material, si, scene) : material;
    if (m.kind == MaterialKind::Interface) return false;
    TextureEvalContext ctx;
    ctx.p = si.p;
    ctx.n = si.n;
    ctx.uv = si.uv;
    bsdf->shadingFrame = Frame::FromXZ(si.dpdu, si.ns);
    if (m.normalMap != NoIndex)
        bsdf->shadingFrame = NormalMappedFrame(bsdf->shadingFrame, scene.images[m.normalMap], scene, si.uv, si.n);
    else if (m.displacement != NoIndex)
        bsdf->shadingFrame = BumpMappedFrame(bsdf->shadingFrame, scene.floatTextures[m.displacement], si, scene);
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
        ConductorEtaK(m, ctx, lambda, scene, &etas, &ks);
        bsdf->kind = BxDFKind::Conductor;
        bsdf->conductor = ConductorBxDF(distrib, etas, ks);
        return true;
    }
    case MaterialKind::Dielectric: {
        Float eta = SampleEta(m, ctx, lambda, scene);
        bsdf->kind = BxDFKind::Dielectric;
        bsdf->dielectric = DielectricBxDF(eta, MakeDistribution(m, ctx, scene));
        return true;
    }
    case MaterialKind::ThinDielectric: {
        Float eta = SampleEta(m, ctx, lambda, scene);
        bsdf->kind = BxDFKind::ThinDielectric;
        bsdf->thinDielectric = ThinDielectricBxDF(eta);
        return true;
    }
    case MaterialKind::CoatedDiffuse: {
        SampledSpectrum r = ClampSpectrum(EvalSpectrumTexture(m.reflectance, ctx, lambda, scene), 0, 1);
        TrowbridgeReitzDistribution distrib = MakeDistribution(m, ctx, scene);
        Float thick = EvalFloatTexture(m.thickness, ctx, scene);
        Float eta = SampleEta(m, ctx, lambda, scene);
        SampledSpectrum a = ClampSpectrum(EvalSpectrumTexture(m.albedo, ctx, lambda, scene), 0, 1);
        Float gg = Clamp(EvalFloatTexture(m.g, ctx, scene), Float(-1), Float(1));
        bsdf->kind = BxDFKind::CoatedDiffuse;
        bsdf->coatedDiffuse = CoatedDiffuseBxDF(DielectricBxDF(eta, distrib), DiffuseBxDF(r), thick, a, gg,
                                                m.maxDepth, m.nSamples);
        return true;
    }
    case MaterialKind::CoatedConductor: {
        // pbrt-v4's CoatedConductorMaterial::GetBxDF: the base's index is relative to the coat.
        TrowbridgeReitzDistribution interfaceDistrib = MakeDistribution(m, ctx, scene);
        Float thick = EvalFloatTexture(m.thickness, ctx, scene);
        Float ieta = SampleEta(m, ctx, lambda, scene);
        SampledSpectrum ce, ck;
        ConductorEtaK(m, ctx, lambda, scene, &ce, &ck);
        ce /= ieta;
        ck /= ieta;
        Float cu = EvalFloatTexture(m.conductorURoughness, ctx, scene);
        Float cv = EvalFloatTexture(m.conductorVRoughness, ctx, scene);
        if (m.remapRoughness) {
            cu = TrowbridgeReitzDistribution::RoughnessToAlpha(cu);
            cv = TrowbridgeReitzDistribution::RoughnessToAlpha(cv);
        }
        SampledSpectrum a = ClampSpectrum(EvalSpectrumTexture(m.albedo, ctx, lambda, scene), 0, 1);
        Float gg = Clamp(EvalFloatTexture(m.g, ctx, scene), Float(-1), Float(1));
        bsdf->kind = BxDFKind::CoatedConductor;
        bsdf->coatedConductor = CoatedConductorBxDF(DielectricBxDF(ieta, interfaceDistrib),
                                                    ConductorBxDF(TrowbridgeReitzDistribution(cu, cv), ce, ck), thick,
                                                    a, gg, m.maxDepth, m.nSamples);
        return true;
    }
    case MaterialKind::DiffuseTransmission: {
        SampledSpectrum r = ClampSpectrum(EvalSpectrumTexture(m.reflectance, ctx, lambda, scene) * m.scale, 0, 1);
        SampledSpectrum t = ClampSpectrum(EvalSpectrumTexture(m.transmittance, ctx, lambda, scene) * m.scale, 0, 1);
        bsdf->kind = BxDFKind::DiffuseTransmission;
        bsdf->diffuseTransmission = DiffuseTransmissionBxDF(r, t);
        return true;
    }
    case MaterialKind::Hair: {
        bsdf->kind = BxDFKind::Hair;
        bsdf->hair = MakeHairBxDF(m, ctx, si.uv, lambda, scene);
        return true;
    }
    case MaterialKind::Measured:
        // The tables stay in the scene: the BxDF points at the material's layout and the data.
        bsdf->kind = BxDFKind::Measured;
        bsdf->measured = MeasuredBxDF(&m.measured, scene.measuredData.ptr, lambda);
        return true;
    default: return false;
    }
}

}  // namespace lu
