// pbrt-v4's mix material (the per-intersection choice by "amount" with a hash of p and wo, nested
// mixes), the diffuse transmission BxDF (exact furnace, reciprocity across the surface) and
// MakeBSDF's parameter handling of diffusetransmission and coatedconductor; the normal map's
// shading frame (pbrt-v4's NormalMap).
#include <gtest/gtest.h>

#include <vector>

#include "materials/bxdf_test_helpers.h"

namespace lu::test {
namespace {

template <typename T>
Span<T> MakeSpan(const std::vector<T> &v) {
    Span<T> s; s.ptr = v.data(); s.size = uint32_t(v.size()); return s;
}
FloatTexture ConstF(Float v) { FloatTexture t; t.value = v; return t; }
SpectrumTexture ConstS(Float v) { SpectrumTexture t; t.value = Spectrum::Const(v); return t; }

Material DiffuseMat(Float r) {
    Material m; m.kind = MaterialKind::Diffuse; m.reflectance = ConstS(r); return m;
}
Material MixMat(uint32_t a, uint32_t b, Float amount) {
    Material m; m.kind = MaterialKind::Mix; m.mixMaterials[0] = a; m.mixMaterials[1] = b; m.amount = ConstF(amount);
    return m;
}

SurfaceInteraction RandomHit(RNG &rng) {
    SurfaceInteraction si;
    si.p = Vec3f(rng.UniformFloat() * 10 - 5, rng.UniformFloat() * 10 - 5, rng.UniformFloat());
    si.n = si.ns = Vec3f(0, 0, 1);
    si.dpdu = Vec3f(1, 0, 0);
    si.uv = Vec2f(rng.UniformFloat(), rng.UniformFloat());
    si.wo = SampleUniformHemisphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
    return si;
}

// The reflectance of the diffuse BSDF MakeBSDF built for material index mi at si.
Float PickedReflectance(const std::vector<Material> &mats, uint32_t mi, const SurfaceInteraction &si,
                        const SceneView &scene) {
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.4f);
    BSDF bsdf;
    EXPECT_TRUE(MakeBSDF(mats[mi], si, lambda, scene, &bsdf));
    EXPECT_EQ(bsdf.kind, BxDFKind::Diffuse);
    return bsdf.diffuse.R[0];
}

// Binomial z-test of the fraction of (p, wo) at which a mix picks its second material.
TEST(Mix, SelectionMatchesAmount) {
    for (Float amount : {0.1f, 0.3f, 0.5f, 0.85f}) {
        std::vector<Material> mats = {DiffuseMat(0.2f), DiffuseMat(0.7f), MixMat(0, 1, amount)};
        SceneView scene;
        scene.materials = MakeSpan(mats);
        RNG rng(7, uint64_t(amount * 1000));
        const int n = 40000;
        int second = 0;
        for (int i = 0; i < n; ++i) second += PickedReflectance(mats, 2, RandomHit(rng), scene) == 0.7f;
        double frac = double(second) / n, sigma = std::sqrt(amount * (1 - amount) / n);
        EXPECT_LT(std::abs(frac - amount), 4.5 * sigma) << "amount " << amount << ": picked the second in " << frac;
    }
}

TEST(Mix, ClampedAmountsAndDeterminism) {
    std::vector<Material> mats = {DiffuseMat(0.2f), DiffuseMat(0.7f), MixMat(0, 1, 0), MixMat(0, 1, 1),
                                  MixMat(0, 1, -2), MixMat(0, 1, 3), MixMat(0, 1, 0.5f)};
    SceneView scene;
    scene.materials = MakeSpan(mats);
    RNG rng(3, 3);
    int differs = 0;
    for (int i = 0; i < 2000; ++i) {
        SurfaceInteraction si = RandomHit(rng);
        EXPECT_EQ(PickedReflectance(mats, 2, si, scene), 0.2f);   // amount 0: the first
        EXPECT_EQ(PickedReflectance(mats, 3, si, scene), 0.7f);   // amount 1: the second
        EXPECT_EQ(PickedReflectance(mats, 4, si, scene), 0.2f);
        EXPECT_EQ(PickedReflectance(mats, 5, si, scene), 0.7f);
        // The same (p, wo) always picks the same material; another wo may pick the other one.
        Float a = PickedReflectance(mats, 6, si, scene);
        EXPECT_EQ(a, PickedReflectance(mats, 6, si, scene));
        SurfaceInteraction other = si;
        other.wo = Normalize(si.wo + Vec3f(0.01f, 0, 0));
        differs += a != PickedReflectance(mats, 6, other, scene);
    }
    EXPECT_GT(differs, 700);   // independent picks differ half the time
    EXPECT_LT(differs, 1300);
}

// mix(A, mix(B, C, 0.5), 0.5): A, B and C in proportion 1/2, 1/4, 1/4 (the hash of the inner
// mix uses its own children, so the two choices are independent).
TEST(Mix, NestedMixProportions) {
    std::vector<Material> mats = {DiffuseMat(0.1f), DiffuseMat(0.4f), DiffuseMat(0.8f), MixMat(1, 2, 0.5f),
                                  MixMat(0, 3, 0.5f)};
    SceneView scene;
    scene.materials = MakeSpan(mats);
    RNG rng(11, 1);
    const int n = 40000;
    int count[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        Float r = PickedReflectance(mats, 4, RandomHit(rng), scene);
        count[r == 0.1f ? 0 : r == 0.4f ? 1 : 2]++;
    }
    double expect[3] = {0.5, 0.25, 0.25};
    for (int k = 0; k < 3; ++k) {
        double frac = double(count[k]) / n, sigma = std::sqrt(expect[k] * (1 - expect[k]) / n);
        EXPECT_LT(std::abs(frac - expect[k]), 4.5 * sigma) << "child " << k << ": " << frac;
    }
}

// ---- Diffuse transmission ----

// Every sample's weight is (R or T) / (its lobe probability): with R + T = 1 in every channel and
// equal channels the furnace is exactly 1, from either side; otherwise it is R + T.
TEST(DiffuseTransmission, FurnaceIsRPlusT) {
    struct Case { Float r, t; };
    for (Case c : {Case{0.3f, 0.7f}, Case{1, 0}, Case{0, 1}, Case{0.25f, 0.25f}}) {
        BSDF b = MakeDiffuseTransmission(SampledSpectrum(c.r), SampledSpectrum(c.t));
        for (Float th : {20.f, 160.f}) {
            MeanEstimate e = SampledAlbedo(b, Dir(th, 30), 20000, 5);
            EXPECT_NEAR(e.mean, c.r + c.t, 1e-5) << "R " << c.r << " T " << c.t << " theta " << th;
        }
    }
}

TEST(DiffuseTransmission, ValuesFlagsAndReciprocity) {
    SampledSpectrum R = Spec(0.1f, 0.3f, 0.5f, 0.7f), T = Spec(0.6f, 0.4f, 0.2f, 0.05f);
    BSDF b = MakeDiffuseTransmission(R, T);
    EXPECT_EQ(b.Flags(), BxDF_DiffuseReflection | BxDF_DiffuseTransmission);
    EXPECT_EQ(MakeDiffuseTransmission(SampledSpectrum(0), T).Flags(), BxDF_DiffuseTransmission);
    EXPECT_EQ(MakeDiffuseTransmission(R, SampledSpectrum(0)).Flags(), BxDF_DiffuseReflection);
    EXPECT_FALSE(b.IsSpecular());
    RNG rng(2, 9);
    for (int i = 0; i < 500; ++i) {
        Vec3f a = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        Vec3f c = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        if (std::abs(a.z) < 1e-3f || std::abs(c.z) < 1e-3f) continue;
        Vec3f wo = b.shadingFrame.FromLocal(a), wi = b.shadingFrame.FromLocal(c);
        SampledSpectrum f = b.f(wo, wi), fr = b.f(wi, wo);
        const SampledSpectrum &ref = SameHemisphere(a, c) ? R : T;
        for (int k = 0; k < NSpectrumSamples; ++k) {
            EXPECT_FLOAT_EQ(f[k], ref[k] * InvPi);
            EXPECT_EQ(f[k], fr[k]);
        }
        // Restricted sampling: transmission only never reflects, and its pdf integrates the lobe alone.
        BSDFSample bs;
        if (b.Sample_f(wo, 0.1f, Vec2f(rng.UniformFloat(), rng.UniformFloat()), &bs, TransportMode::Radiance,
                       BxDF_SampleTransmission)) {
            EXPECT_TRUE(bs.IsTransmission());
            EXPECT_NEAR(bs.pdf, b.PDF(wo, bs.wi, TransportMode::Radiance, BxDF_SampleTransmission), 1e-5f * bs.pdf);
            EXPECT_NEAR(bs.pdf, std::abs(Dot(bs.wi, b.shadingFrame.z)) * InvPi, 1e-5f);
        }
    }
}

// ---- MakeBSDF of the new materials ----

SurfaceInteraction TestHit() {
    SurfaceInteraction si;
    si.p = Vec3f(1, 2, 3);
    si.n = Normalize(Vec3f(0, 0.2f, 1));
    si.ns = Normalize(Vec3f(0.1f, 0.1f, 1));
    si.dpdu = Vec3f(2, 0, 0.3f);
    si.uv = Vec2f(0.3f, 0.6f);
    si.wo = Normalize(Vec3f(0.3f, -0.2f, 1));
    return si;
}

TEST(MakeBSDF, DiffuseTransmissionScaleAndClamp) {
    SceneView scene;
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.3f);
    Material m; m.kind = MaterialKind::DiffuseTransmission;
    m.reflectance = ConstS(0.25f); m.transmittance = ConstS(0.6f); m.scale = 1.5f;
    BSDF bsdf;
    ASSERT_TRUE(MakeBSDF(m, TestHit(), lambda, scene, &bsdf));
    EXPECT_EQ(bsdf.kind, BxDFKind::DiffuseTransmission);
    EXPECT_FLOAT_EQ(bsdf.diffuseTransmission.R[0], 0.375f);
    EXPECT_FLOAT_EQ(bsdf.diffuseTransmission.T[2], 0.9f);   // scale times 0.6
    m.scale = 2;
    ASSERT_TRUE(MakeBSDF(m, TestHit(), lambda, scene, &bsdf));
    EXPECT_EQ(bsdf.diffuseTransmission.T[1], 1.0f);   // clamped to [0, 1]
}

TEST(MakeBSDF, CoatedConductorParameters) {
    SceneView scene;
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.3f);
    Material m; m.kind = MaterialKind::CoatedConductor;
    m.uRoughness = ConstF(0.09f); m.vRoughness = ConstF(0.16f);
    m.conductorURoughness = ConstF(0.25f); m.conductorVRoughness = ConstF(0.36f);
    m.conductorEta = ConstS(0.3f); m.conductorK = ConstS(3.0f);
    m.thickness = ConstF(0.02f); m.g = ConstF(2); m.albedo = ConstS(0.4f); m.maxDepth = 6; m.nSamples = 3;
    m.eta = Spectrum::Const(1.5f);
    BSDF bsdf;
    ASSERT_TRUE(MakeBSDF(m, TestHit(), lambda, scene, &bsdf));
    ASSERT_EQ(bsdf.kind, BxDFKind::CoatedConductor);
    const CoatedConductorBxDF &c = bsdf.coatedConductor;
    EXPECT_EQ(c.top.eta, 1.5f);
    EXPECT_FLOAT_EQ(c.top.mfDistrib.alphaX, 0.3f);     // remapped: sqrt(roughness)
    EXPECT_FLOAT_EQ(c.top.mfDistrib.alphaY, 0.4f);
    EXPECT_FLOAT_EQ(c.bottom.mfDistrib.alphaX, 0.5f);
    EXPECT_FLOAT_EQ(c.bottom.mfDistrib.alphaY, 0.6f);
    EXPECT_FLOAT_EQ(c.bottom.eta[0], 0.2f);            // relative to the coat: 0.3 / 1.5
    EXPECT_FLOAT_EQ(c.bottom.k[3], 2.0f);              // 3 / 1.5
    EXPECT_EQ(c.thickness, 0.02f);
    EXPECT_EQ(c.g, 1.0f);                              // clamped to [-1, 1]
    EXPECT_EQ(c.albedo[1], 0.4f);
    EXPECT_EQ(c.maxDepth, 6);
    EXPECT_EQ(c.nSamples, 3);
    EXPECT_EQ(bsdf.Flags(), BxDF_Reflection | BxDF_Diffuse);   // rough coat, scattering medium
    // "reflectance" instead of eta/k: eta 1, k = 2 sqrt(r) / sqrt(1 - r), both over the coat's index.
    m.useReflectance = true; m.reflectance = ConstS(0.64f); m.remapRoughness = false;
    ASSERT_TRUE(MakeBSDF(m, TestHit(), lambda, scene, &bsdf));
    EXPECT_FLOAT_EQ(bsdf.coatedConductor.bottom.eta[0], 1 / 1.5f);
    EXPECT_FLOAT_EQ(bsdf.coatedConductor.bottom.k[0], 2 * 0.8f / 0.6f / 1.5f);
    EXPECT_FLOAT_EQ(bsdf.coatedConductor.top.mfDistrib.alphaX, 0.09f);   // remaproughness false
    EXPECT_FLOAT_EQ(bsdf.coatedConductor.bottom.mfDistrib.alphaY, 0.36f);
    // A constant coat index keeps every wavelength.
    EXPECT_FALSE(lambda.SecondaryTerminated());
}

// ---- Normal map ----

// A 2x2 RGB map of one colour at every texel (repeat wrap).
struct OneColourMap {
    std::vector<Float> texels;
    std::vector<ImageData> images;
    SceneView scene;
    OneColourMap(Float r, Float g, Float b) {
        for (int i = 0; i < 4; ++i) { texels.push_back(r); texels.push_back(g); texels.push_back(b); }
        ImageData d; d.width = d.height = 2; d.channels = 3; d.offset = 0; d.wrap = WrapMode::Repeat;
        images.push_back(d);
        scene.texels = MakeSpan(texels);
        scene.images = MakeSpan(images);
    }
};

TEST(NormalMap, FlatMapKeepsTheFrameBitForBit) {
    OneColourMap flat(0.5f, 0.5f, 1);
    RNG rng(5, 5);
    for (int i = 0; i < 500; ++i) {
        Vec3f n = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        Vec3f dpdu = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        Frame f = Frame::FromXZ(dpdu, n);
        Frame r = NormalMappedFrame(f, flat.images[0], flat.scene, Vec2f(rng.UniformFloat(), rng.UniformFloat()), n);
        ASSERT_EQ(r.x, f.x);
        ASSERT_EQ(r.y, f.y);
        ASSERT_EQ(r.z, f.z);
    }
}

TEST(NormalMap, TiltedMapRotatesTheNormalInTangentSpace) {
    // rgb (0.8, 0.5, 0.9) -> tangent-space normal (0.6, 0, 0.8): tilted towards the shading x axis.
    OneColourMap tilted(0.8f, 0.5f, 0.9f);
    Frame f = TestFrame();
    Frame r = NormalMappedFrame(f, tilted.images[0], tilted.scene, Vec2f(0.3f, 0.7f), f.z);
    Vec3f expect = f.FromLocal(Vec3f(0.6f, 0, 0.8f));
    EXPECT_LT(Distance(r.z, expect), 1e-5f);
    // An orthonormal, right-handed frame whose x is the old x made orthogonal to the new normal.
    EXPECT_NEAR(Dot(r.x, r.z), 0, 1e-6f);
    EXPECT_NEAR(Length(r.x), 1, 1e-6f);
    EXPECT_LT(Distance(r.y, Cross(r.z, r.x)), 1e-6f);
    EXPECT_LT(Distance(r.x, f.FromLocal(Vec3f(0.8f, 0, -0.6f))), 1e-5f);
    // Seen from the other side of the geometric normal the mapped normal is flipped to that side.
    Frame back = NormalMappedFrame(f, tilted.images[0], tilted.scene, Vec2f(0.3f, 0.7f), -f.z);
    EXPECT_LT(Distance(back.z, -expect), 1e-5f);
    // MakeBSDF applies the material's map: a diffuse BSDF's cosine now follows the new normal.
    Material m; m.kind = MaterialKind::Diffuse; m.reflectance = ConstS(0.5f); m.normalMap = 0;
    SurfaceInteraction si;
    si.p = Vec3f(0, 0, 0); si.n = si.ns = Vec3f(0, 0, 1); si.dpdu = Vec3f(1, 0, 0); si.uv = Vec2f(0.2f, 0.2f);
    si.wo = Normalize(Vec3f(0.1f, 0.2f, 1));
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    BSDF bsdf;
    ASSERT_TRUE(MakeBSDF(m, si, lambda, tilted.scene, &bsdf));
    EXPECT_LT(Distance(bsdf.shadingFrame.z, Vec3f(0.6f, 0, 0.8f)), 1e-5f);
    // Below the mapped normal's tangent plane but above the geometric one: no reflection.
    Vec3f wi = Normalize(Vec3f(-0.9f, 0, 0.3f));
    EXPECT_EQ(bsdf.f(si.wo, wi)[0], 0);
}

}  // namespace
}  // namespace lu::test
