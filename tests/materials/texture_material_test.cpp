// Texture evaluation (constant, checkerboard, image maps with wrap modes, scale and invert, RGB
// -> spectrum; the other kinds: texture_test.cpp) and MakeBSDF (pbrt-v4's GetBxDF parameter handling for every material).
#include <gtest/gtest.h>

#include <vector>

#include "lucerna/spectra/registry.h"
#include "lucerna/spectrum/rgb_to_spectrum.h"
#include "materials/bxdf_test_helpers.h"

namespace lu::test {
namespace {

template <typename T>
Span<T> MakeSpan(const std::vector<T> &v) {
    Span<T> s; s.ptr = v.data(); s.size = uint32_t(v.size()); return s;
}

TextureEvalContext Ctx(Float u, Float v) {
    TextureEvalContext c; c.uv = Vec2f(u, v); c.n = Vec3f(0, 0, 1); return c;
}

SampledWavelengths Lambdas() {
    SampledWavelengths l = SampledWavelengths::SampleVisible(0.3f);
    return l;
}

TEST(Texture, ConstantAndCheckerboard) {
    SceneView scene;
    FloatTexture c; c.kind = TextureKind::Constant; c.value = 0.37f;
    EXPECT_EQ(EvalFloatTexture(c, Ctx(0.2f, 0.9f), scene), 0.37f);

    // Checkerboard children: constants in the scene's texture arrays.
    std::vector<FloatTexture> floats(2);
    floats[0].value = 0.2f; floats[1].value = 0.9f;
    std::vector<SpectrumTexture> spectra(2);
    spectra[0].value = Spectrum::Const(0.25f); spectra[1].value = Spectrum::Const(0.75f);
    scene.floatTextures = MakeSpan(floats);
    scene.spectrumTextures = MakeSpan(spectra);
    FloatTexture cb; cb.kind = TextureKind::Checkerboard; cb.tex[0] = 0; cb.tex[1] = 1;
    cb.mapping.su = 4; cb.mapping.sv = 4;
    EXPECT_EQ(EvalFloatTexture(cb, Ctx(0.1f, 0.1f), scene), 0.2f);    // (0.4, 0.4): even
    EXPECT_EQ(EvalFloatTexture(cb, Ctx(0.3f, 0.1f), scene), 0.9f);    // (1.2, 0.4): odd
    EXPECT_EQ(EvalFloatTexture(cb, Ctx(0.3f, 0.3f), scene), 0.2f);    // (1.2, 1.2): even
    EXPECT_EQ(EvalFloatTexture(cb, Ctx(-0.1f, 0.1f), scene), 0.9f);   // (-0.4, 0.4): floor -1, odd
    cb.mapping.du = 1;                                                // shift by one check
    EXPECT_EQ(EvalFloatTexture(cb, Ctx(0.1f, 0.1f), scene), 0.9f);

    SampledWavelengths lambda = Lambdas();
    SpectrumTexture sc; sc.kind = TextureKind::Checkerboard; sc.tex[0] = 0; sc.tex[1] = 1;
    sc.mapping.su = 2; sc.mapping.sv = 2;
    EXPECT_EQ(EvalSpectrumTexture(sc, Ctx(0.25f, 0.25f), lambda, scene)[2], 0.25f);
    EXPECT_EQ(EvalSpectrumTexture(sc, Ctx(0.75f, 0.25f), lambda, scene)[1], 0.75f);
    SpectrumTexture s; s.value = Spectrum::Const(0.6f);
    EXPECT_EQ(EvalSpectrumTexture(s, Ctx(0, 0), lambda, scene)[3], 0.6f);
}

TEST(Texture, ImageBilerpWrapScaleInvert) {
    // 2x2, one channel, row 0 at the top: [10 11; 12 13]. Texture t = 1 is the top row.
    std::vector<Float> texels = {10, 11, 12, 13};
    std::vector<ImageData> images(1);
    images[0].width = 2; images[0].height = 2; images[0].channels = 1; images[0].offset = 0;
    SceneView scene;
    scene.texels = MakeSpan(texels);
    scene.images = MakeSpan(images);
    FloatTexture t; t.kind = TextureKind::ImageMap; t.image = 0;
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(0.25f, 0.75f), scene), 10, 1e-5f);   // texel centers
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(0.75f, 0.75f), scene), 11, 1e-5f);
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(0.25f, 0.25f), scene), 12, 1e-5f);
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(0.5f, 0.5f), scene), 11.5f, 1e-5f);   // bilinear center
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(0.5f, 0.75f), scene), 10.5f, 1e-5f);
    // Across the right edge, between texel (1,0) and its neighbour (2,0).
    images[0].wrap = WrapMode::Repeat;
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(1.0f, 0.75f), scene), 10.5f, 1e-5f);
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(1.25f, 0.75f), scene), 10.0f, 1e-5f);   // repeats
    images[0].wrap = WrapMode::Clamp;
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(1.0f, 0.75f), scene), 11.0f, 1e-5f);
    images[0].wrap = WrapMode::Black;
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(1.0f, 0.75f), scene), 5.5f, 1e-5f);
    // Octahedral: past the right edge the neighbour of texel (1, 0) is texel (1, 1) (x mirrored
    // across u = 1, y across v = 0.5): image row 0 = 10 11, row 1 = 12 13.
    images[0].wrap = WrapMode::OctahedralSphere;
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(1.0f, 0.75f), scene), 12.0f, 1e-5f);
    // Past the top edge, texel (0, -1) is texel (1, 1) (x mirrored across u = 0.5, y -> -y, as
    // pbrt-v4's RemapPixelCoords writes it): at s = 0.25 on the edge, between 10 and 13.
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(0.25f, 1.0f), scene), 11.5f, 1e-5f);
    images[0].wrap = WrapMode::Repeat;
    // Scale, invert (1 - v, clamped at 0) and the uv mapping.
    t.scale = 0.05f;
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(0.25f, 0.25f), scene), 0.6f, 1e-5f);
    t.invert = true;
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(0.25f, 0.25f), scene), 0.4f, 1e-5f);
    t.scale = 1;
    EXPECT_EQ(EvalFloatTexture(t, Ctx(0.25f, 0.25f), scene), 0.0f);
    t.invert = false;
    t.mapping.su = 0.5f;   // s = u / 2
    EXPECT_NEAR(EvalFloatTexture(t, Ctx(1.5f, 0.75f), scene), 11, 1e-5f);
}

TEST(Texture, ImageRGBToSpectrum) {
    RGBToSpectrumTableData table = SRGBToSpectrumTable();
    ASSERT_GT(table.res, 1u);
    // 2x1 RGB image: a reddish texel and a gray one; plus a 1-channel image.
    std::vector<Float> texels = {0.8f, 0.3f, 0.1f, 0.5f, 0.5f, 0.5f, 0.25f};
    std::vector<ImageData> images(2);
    images[0].width = 2; images[0].height = 1; images[0].channels = 3; images[0].offset = 0;
    images[0].wrap = WrapMode::Clamp;
    images[1].width = 1; images[1].height = 1; images[1].channels = 1; images[1].offset = 6;
    size_t n = size_t(table.res) * table.res * table.res * 9;
    std::vector<Float> coeffs(table.coeffs, table.coeffs + n), zNodes(table.zNodes, table.zNodes + table.res);
    SceneView scene;
    scene.texels = MakeSpan(texels);
    scene.images = MakeSpan(images);
    scene.rgbToSpecCoeffs = MakeSpan(coeffs);
    scene.rgbToSpecZNodes = MakeSpan(zNodes);
    scene.rgbToSpecRes = table.res;
    SampledWavelengths lambda = Lambdas();

    SpectrumTexture t; t.kind = TextureKind::ImageMap; t.image = 0;
    SampledSpectrum red = EvalSpectrumTexture(t, Ctx(0.25f, 0.5f), lambda, scene);
    Spectrum ref = RGBAlbedoSpectrum(table.coeffs, table.zNodes, table.res, 0.8f, 0.3f, 0.1f);
    for (int i = 0; i < NSpectrumSamples; ++i) {
        EXPECT_NEAR(red[i], EvalSpectrum(ref, lambda.lambda[i], scene.spectra), 1e-5f);
        EXPECT_GE(red[i], 0); EXPECT_LE(red[i], 1);
    }
    // Reddish: more reflectance at 650 nm than at 450 nm.
    SampledWavelengths two = lambda;
    two.lambda[0] = 650; two.lambda[1] = 450;
    SampledSpectrum r2 = EvalSpectrumTexture(t, Ctx(0.25f, 0.5f), two, scene);
    EXPECT_GT(r2[0], r2[1] + 0.3f);
    // Gray texels are exactly constant spectra.
    SampledSpectrum gray = EvalSpectrumTexture(t, Ctx(0.75f, 0.5f), lambda, scene);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(gray[i], 0.5f, 1e-5f);
    // Unbounded: scale 2 max(rgb) times the coefficients of rgb / scale.
    t.unbounded = true; t.scale = 2.5f;
    SampledSpectrum ub = EvalSpectrumTexture(t, Ctx(0.25f, 0.5f), lambda, scene);
    Spectrum refU = RGBUnboundedSpectrum(table.coeffs, table.zNodes, table.res, 2.0f, 0.75f, 0.25f);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(ub[i], EvalSpectrum(refU, lambda.lambda[i], scene.spectra), 1e-4f);
    // Albedo textures clamp the scaled RGB to [0,1]; invert is 1 - rgb.
    t.unbounded = false; t.scale = 1; t.invert = true;
    SampledSpectrum inv = EvalSpectrumTexture(t, Ctx(0.75f, 0.5f), lambda, scene);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(inv[i], 0.5f, 1e-5f);
    // One-channel image: a gray spectrum.
    SpectrumTexture g; g.kind = TextureKind::ImageMap; g.image = 1;
    SampledSpectrum gs = EvalSpectrumTexture(g, Ctx(0.3f, 0.3f), lambda, scene);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(gs[i], 0.25f, 1e-5f);
}

// ---- MakeBSDF ----

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

FloatTexture ConstF(Float v) { FloatTexture t; t.value = v; return t; }
SpectrumTexture ConstS(Float v) { SpectrumTexture t; t.value = Spectrum::Const(v); return t; }

TEST(MakeBSDF, InterfaceAndDiffuse) {
    SceneView scene;
    SurfaceInteraction si = TestHit();
    SampledWavelengths lambda = Lambdas();
    BSDF bsdf;
    Material iface; iface.kind = MaterialKind::Interface;
    EXPECT_FALSE(MakeBSDF(iface, si, lambda, scene, &bsdf));

    Material m; m.kind = MaterialKind::Diffuse; m.reflectance = ConstS(0.5f);
    ASSERT_TRUE(MakeBSDF(m, si, lambda, scene, &bsdf));
    EXPECT_EQ(bsdf.kind, BxDFKind::Diffuse);
    // Shading frame: z = ns, x along dpdu (made orthogonal to ns).
    EXPECT_NEAR(Distance(bsdf.shadingFrame.z, si.ns), 0, 1e-6f);
    EXPECT_NEAR(Dot(bsdf.shadingFrame.x, si.ns), 0, 1e-6f);
    EXPECT_GT(Dot(bsdf.shadingFrame.x, Normalize(si.dpdu)), 0.95f);
    Vec3f wi = Normalize(Vec3f(-0.4f, 0.1f, 0.8f));
    EXPECT_NEAR(bsdf.f(si.wo, wi)[0], 0.5f * InvPi, 1e-6f);
    EXPECT_EQ(bsdf.f(si.wo, -wi)[0], 0);
    EXPECT_FALSE(bsdf.IsSpecular());
    // Reflectance is clamped to [0, 1].
    m.reflectance = ConstS(1.7f);
    ASSERT_TRUE(MakeBSDF(m, si, lambda, scene, &bsdf));
    EXPECT_NEAR(bsdf.f(si.wo, wi)[0], InvPi, 1e-6f);
    EXPECT_TRUE(lambda.SecondaryTerminated() == false);
}

TEST(MakeBSDF, ConductorRoughnessAndReflectance) {
    SceneView scene;
    SurfaceInteraction si = TestHit();
    SampledWavelengths lambda = Lambdas();
    BSDF bsdf;
    Material m; m.kind = MaterialKind::Conductor;
    m.conductorEta = ConstS(0.2f); m.conductorK = ConstS(3.9f);
    m.uRoughness = ConstF(0.09f); m.vRoughness = ConstF(0.16f);
    ASSERT_TRUE(MakeBSDF(m, si, lambda, scene, &bsdf));
    EXPECT_EQ(bsdf.kind, BxDFKind::Conductor);
    EXPECT_NEAR(bsdf.conductor.mfDistrib.alphaX, 0.3f, 1e-6f);   // remapped: sqrt(roughness)
    EXPECT_NEAR(bsdf.conductor.mfDistrib.alphaY, 0.4f, 1e-6f);
    EXPECT_EQ(bsdf.conductor.eta[1], 0.2f);
    EXPECT_EQ(bsdf.conductor.k[2], 3.9f);
    m.remapRoughness = false;
    ASSERT_TRUE(MakeBSDF(m, si, lambda, scene, &bsdf));
    EXPECT_NEAR(bsdf.conductor.mfDistrib.alphaX, 0.09f, 1e-7f);
    // Smooth conductor given by reflectance: eta = 1, k = 2 sqrt(r)/sqrt(1-r); F(normal) = r.
    Material r; r.kind = MaterialKind::Conductor; r.useReflectance = true; r.reflectance = ConstS(0.6f);
    r.uRoughness = ConstF(0); r.vRoughness = ConstF(0);
    ASSERT_TRUE(MakeBSDF(r, si, lambda, scene, &bsdf));
    EXPECT_TRUE(bsdf.IsSpecular());
    SpecularLobe lobes[2];
    ASSERT_EQ(bsdf.SpecularLobes(si.ns, lobes), 1);
    EXPECT_NEAR(lobes[0].weight[0], 0.6f, 1e-5f);
    EXPECT_NEAR(Distance(lobes[0].wi, si.ns), 0, 1e-5f);
}

TEST(MakeBSDF, DielectricsAndDispersion) {
    SurfaceInteraction si = TestHit();
    SceneView scene;
    // A tabulated (dispersive) index: 1.6 at 360 nm falling linearly to 1.5 at 830 nm.
    std::vector<Float> table(TabulatedSpectrumSize);
    for (int i = 0; i < TabulatedSpectrumSize; ++i) table[i] = 1.6f - 0.1f * i / (TabulatedSpectrumSize - 1);
    scene.spectra.data = table.data();
    scene.spectra.count = 1;
    BSDF bsdf;
    Material m; m.kind = MaterialKind::Dielectric; m.eta = Spectrum::Const(1.33f);
    SampledWavelengths lambda = Lambdas();
    ASSERT_TRUE(MakeBSDF(m, si, lambda, scene, &bsdf));
    EXPECT_EQ(bsdf.kind, BxDFKind::Dielectric);
    EXPECT_EQ(bsdf.dielectric.eta, 1.33f);
    EXPECT_TRUE(bsdf.IsSpecular());
    EXPECT_FALSE(lambda.SecondaryTerminated());
    Spectrum disp; disp.kind = SpectrumKind::Tabulated; disp.scale = 1; disp.table = 0;
    m.eta = disp;
    ASSERT_TRUE(MakeBSDF(m, si, lambda, scene, &bsdf));
    EXPECT_TRUE(lambda.SecondaryTerminated());
    EXPECT_NEAR(bsdf.dielectric.eta, 1.6f - 0.1f * (lambda.lambda[0] - 360) / 470, 1e-4f);
    m.eta = Spectrum::Const(0);   // pbrt-v4 treats eta 0 as 1
    SampledWavelengths l2 = Lambdas();
    ASSERT_TRUE(MakeBSDF(m, si, l2, scene, &bsdf));
    EXPECT_EQ(bsdf.dielectric.eta, 1.0f);
    Material thin; thin.kind = MaterialKind::ThinDielectric; thin.eta = Spectrum::Const(1.5f);
    ASSERT_TRUE(MakeBSDF(thin, si, l2, scene, &bsdf));
    EXPECT_EQ(bsdf.kind, BxDFKind::ThinDielectric);
    EXPECT_EQ(bsdf.thinDielectric.eta, 1.5f);
    // A rough dielectric (roughness 0.04 -> alpha 0.2) is not Dirac.
    m.eta = Spectrum::Const(1.5f); m.uRoughness = ConstF(0.04f); m.vRoughness = ConstF(0.04f);
    ASSERT_TRUE(MakeBSDF(m, si, l2, scene, &bsdf));
    EXPECT_NEAR(bsdf.dielectric.mfDistrib.alphaX, 0.2f, 1e-6f);
    EXPECT_FALSE(bsdf.IsSpecular());
}

TEST(MakeBSDF, CoatedDiffuseParameters) {
    SceneView scene;
    SurfaceInteraction si = TestHit();
    SampledWavelengths lambda = Lambdas();
    Material m; m.kind = MaterialKind::CoatedDiffuse;
    m.reflectance = ConstS(0.4f); m.uRoughness = ConstF(0); m.vRoughness = ConstF(0);
    m.thickness = ConstF(0.02f); m.g = ConstF(-3); m.albedo = ConstS(1.4f); m.maxDepth = 7; m.nSamples = 2;
    m.eta = Spectrum::Const(1.45f);
    BSDF bsdf;
    ASSERT_TRUE(MakeBSDF(m, si, lambda, scene, &bsdf));
    EXPECT_EQ(bsdf.kind, BxDFKind::CoatedDiffuse);
    const CoatedDiffuseBxDF &c = bsdf.coatedDiffuse;
    EXPECT_EQ(c.top.eta, 1.45f);
    EXPECT_EQ(c.bottom.R[0], 0.4f);
    EXPECT_EQ(c.thickness, 0.02f);
    EXPECT_EQ(c.g, -1.0f);           // clamped to [-1, 1]
    EXPECT_EQ(c.albedo[3], 1.0f);    // clamped to [0, 1]
    EXPECT_EQ(c.maxDepth, 7);
    EXPECT_EQ(c.nSamples, 2);
    EXPECT_EQ(bsdf.Flags(), BxDF_Reflection | BxDF_Specular | BxDF_Diffuse);
    // Zero thickness is kept positive (pbrt-v4 clamps to the smallest normal float).
    m.thickness = ConstF(0);
    ASSERT_TRUE(MakeBSDF(m, si, lambda, scene, &bsdf));
    EXPECT_GT(bsdf.coatedDiffuse.thickness, 0);
}

}  // namespace
}  // namespace lu::test
