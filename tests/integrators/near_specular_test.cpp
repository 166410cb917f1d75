// Near-specular regularization (issue 12 item 6; integrators/techniques.h, NearSpecularBsdf): rough
// conductors and dielectrics narrower than kNearSpecularAlpha, after a non-specular vertex, are
// widened for delta lights only, by at most the vertex's regularized kernel, back to their own lobe
// as the kernel shrinks; glints seen from the camera are left alone.
#include <gtest/gtest.h>

#include <string>

#include "integrators/render_helpers.h"
#include "lucerna/integrators/techniques.h"

namespace lu::test {
namespace {

BSDF Conductor(Float ax, Float ay) {
    BSDF b;
    b.kind = BxDFKind::Conductor;
    b.conductor = ConductorBxDF(TrowbridgeReitzDistribution(ax, ay), SampledSpectrum(0.2f), SampledSpectrum(3));
    return b;
}
BSDF Dielectric(Float eta, Float alpha) {
    BSDF b;
    b.kind = BxDFKind::Dielectric;
    b.dielectric = DielectricBxDF(eta, TrowbridgeReitzDistribution(alpha, alpha));
    return b;
}

// A table at z = 0 (diffuse 0.5), a glass slab (eta 1.5) between z = 0.45 and 0.5 with the given
// microfacet alpha, as wide as the table (two faces, normals outward, no side faces: side faces
// would fold light back by total internal reflection, a caustic of their own), a point light 1 m
// above the table's centre. The camera looks at the centre from below the slab (table points within
// 0.4 m of it), so it sees the table's caustic, never the slab's glint.
std::string SlabScene(double alpha, int spp) {
    std::string a = std::to_string(alpha);
    return "LookAt 0 -0.9 0.3  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 10 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 48 ] \"integer yresolution\" [ 48 ]\n"
           "Sampler \"zsobol\" \"integer pixelsamples\" [ " + std::to_string(spp) + " ]\n"
           "Integrator \"path\" \"integer maxdepth\" [ 6 ]\nPixelFilter \"box\"\nWorldBegin\n"
           "LightSource \"point\" \"point3 from\" [ 0 0 1 ] \"rgb I\" [ 1 1 1 ]\n"
           "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -2 -2 0  2 -2 0  2 2 0  -2 2 0 ]\n"
           "AttributeEnd\nAttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ] \"bool remaproughness\" false "
           "\"float roughness\" [ " + a + " ]\n"
           "Shape \"trianglemesh\" \"point3 P\" [ -2 -2 0.45  2 -2 0.45  2 2 0.45  -2 2 0.45 "
           " -2 -2 0.5  2 -2 0.5  2 2 0.5  -2 2 0.5 ]\n"
           "  \"integer indices\" [ 0 2 1  0 3 2  4 5 6  4 6 7 ]\n"
           "AttributeEnd\n";
}

}  // namespace

TEST(NearSpecular, RoughenWidensOnlyNarrowMicrofacetLobes) {
    BSDF c = Conductor(0.02f, 0.05f);
    EXPECT_TRUE(c.IsNearSpecular());
    ASSERT_TRUE(c.Roughen(0.04f));
    EXPECT_FLOAT_EQ(c.conductor.mfDistrib.alphaX, 0.04f);
    EXPECT_FLOAT_EQ(c.conductor.mfDistrib.alphaY, 0.05f);   // already rougher on that axis
    EXPECT_FALSE(c.Roughen(0.03f));                        // nothing narrower than 0.03 left
    BSDF d = Dielectric(1.5f, 0.01f);
    ASSERT_TRUE(d.Roughen(0.1f));
    EXPECT_FLOAT_EQ(d.dielectric.mfDistrib.alphaX, 0.1f);
    // Left alone: Dirac lobes (the cone kernel's), lobes at or above 0.1, index-matched glass, diffuse.
    BSDF smooth = Dielectric(1.5f, 0), rough = Conductor(0.1f, 0.1f), matched = Dielectric(1, 0.02f), diffuse;
    diffuse.kind = BxDFKind::Diffuse;
    for (BSDF *b : {&smooth, &rough, &matched, &diffuse}) {
        EXPECT_FALSE(b->IsNearSpecular()) << int(b->kind);
        EXPECT_FALSE(b->Roughen(0.08f)) << int(b->kind);
    }
    EXPECT_FALSE(Conductor(0.02f, 0.1f).IsNearSpecular());   // rough on one axis: not near-specular
    EXPECT_FLOAT_EQ(smooth.dielectric.mfDistrib.alphaX, 0);
    EXPECT_FLOAT_EQ(rough.conductor.mfDistrib.alphaX, 0.1f);
}

// The widening follows the vertex's kernel: never beyond kNearSpecularAlpha, shrinking with the
// pass as N^-lambda, none after Dirac vertices from the camera, none once tan(sigma / 2) <= alpha.
TEST(NearSpecular, WideningShrinksToTheSurfacesOwnLobe) {
    auto scene = LoadSceneText("near_specular_kernel", SlabScene(0.02, 1));
    RenderSettings s = TestSettings(*scene, 1, 6);
    s.integrator = IntegratorKind::RegPath;
    ScatterVertex in;
    in.allSpecular = false;
    in.receiverT = 1.2f;   // the table, seen 1.2 m from the camera; the slab 0.5 m above it
    const Float T = 1.7f;
    BSDF glass = Dielectric(1.5f, 0.02f), wide;
    Float previous = kNearSpecularAlpha;
    int widened = 0;
    for (uint32_t pass : {0u, 100u, 10000u, 1000000u, 100000000u}) {
        PathSettings ps = s.ForPass(pass);
        if (!NearSpecularBsdf(ps, scene->View(), glass, in, T, &wide)) {
            // Past this pass the kernel is narrower than the lobe: the surface's own BSDF.
            Float sigma = RegularizedAngle(VertexRegularization(ps, scene->View(), in.receiverT, T));
            EXPECT_LE(std::tan(sigma / 2), 0.02f) << "pass " << pass;
            continue;
        }
        ++widened;
        Float a = wide.dielectric.mfDistrib.alphaX;
        EXPECT_GT(a, 0.02f);
        EXPECT_LE(a, previous) << "pass " << pass;
        previous = a;
    }
    EXPECT_GE(widened, 2);
    EXPECT_FALSE(NearSpecularBsdf(s.ForPass(100000000u), scene->View(), glass, in, T, &wide));
    // Camera paths through Dirac vertices only, and path tracing: never.
    in.allSpecular = true;
    EXPECT_FALSE(NearSpecularBsdf(s.ForPass(0), scene->View(), glass, in, T, &wide));
    in.allSpecular = false;
    s.integrator = IntegratorKind::Path;
    EXPECT_FALSE(NearSpecularBsdf(s.ForPass(0), scene->View(), glass, in, T, &wide));
}

// The caustic of a point light under a rough slab (alpha 0.02): path tracing reaches the light only
// by NEE at the slab's top face, evaluating its narrow lobe in the direction the table's bounce
// chose. regpath widens that lobe (0.1 while the kernel allows it): the same mean, at much lower
// variance at equal samples. With the widening off, regpath is path tracing here, bit for bit (no
// Dirac vertex: nothing else of regpath runs).
TEST(NearSpecular, RoughSlabCausticConvergesFasterAtEqualSamples) {
    auto scene = LoadSceneText("near_specular_slab", SlabScene(0.02, 256));
    RenderSettings s = TestSettings(*scene, 256, 6, 3);
    RenderResultForTest path = RenderScene(*scene, s);
    s.integrator = IntegratorKind::RegPath;
    RenderResultForTest reg = RenderScene(*scene, s);
    s.nearSpecular = false;
    RenderResultForTest off = RenderScene(*scene, s);
    EXPECT_EQ(off.image.pixels, path.image.pixels);
    // The bare table (no slab; NEE alone, nearly noise-free), for the slab's transmittance.
    std::string bareText = SlabScene(0.02, 16);
    bareText = bareText.substr(0, bareText.rfind("AttributeBegin"));
    auto bare = LoadSceneText("near_specular_bare", bareText);
    RenderResultForTest b = RenderScene(*bare, TestSettings(*bare, 16, 6, 3));
    // The table around its centre, below the light: 32 x 32 pixels.
    MeanSE mp = RegionMean(path.image, 1, 8, 8, 40, 40), mr = RegionMean(reg.image, 1, 8, 8, 40, 40);
    MeanSE mb = RegionMean(b.image, 1, 8, 8, 40, 40);
    std::printf("[ slab     ] bare table %.4f; path %.4f +- %.4f, regpath %.4f +- %.4f (pixel standard errors)\n", mb.mean,
                mp.mean, mp.se, mr.mean, mr.se);
    EXPECT_NEAR(mr.mean, mp.mean, 4 * std::sqrt(mp.se * mp.se + mr.se * mr.se) + 0.02 * mp.mean);
    // Two faces of glass of 1.5 near normal incidence pass 0.923 of the light, which the slab's
    // lateral shift concentrates by 1.034 (the source seems 1.7 cm nearer): 0.953 of the bare table
    // (a Monte Carlo ray trace of this geometry gives 0.9528; regpath's MNEE alone, smooth slab,
    // maxdepth 3: 0.953).
    EXPECT_NEAR(mr.mean / mb.mean, 0.953, 4 * mr.se / mb.mean + 0.03);
    EXPECT_LT(mr.se, 0.5 * mp.se);
}

// A point light's glint in a near-specular mirror, seen from the camera: the pixel integral
// samples it without bias, and regpath leaves it as path tracing renders it, bit for bit.
TEST(NearSpecular, GlintsSeenFromTheCameraAreLeftAlone) {
    std::string text =
        "LookAt 0 -1 1  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 20 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n"
        "Sampler \"zsobol\" \"integer pixelsamples\" [ 16 ]\nIntegrator \"path\" \"integer maxdepth\" [ 5 ]\n"
        "PixelFilter \"box\"\nWorldBegin\nLightSource \"point\" \"point3 from\" [ 0 1 1 ] \"rgb I\" [ 1 1 1 ]\n"
        "Material \"conductor\" \"bool remaproughness\" false \"float roughness\" [ 0.02 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ]\n";
    auto scene = LoadSceneText("near_specular_glint", text);
    RenderSettings s = TestSettings(*scene, 16, 5, 1);
    RenderResultForTest path = RenderScene(*scene, s);
    s.integrator = IntegratorKind::RegPath;
    RenderResultForTest reg = RenderScene(*scene, s);
    double peak = 0;
    for (float v : path.image.pixels) peak = std::max(peak, double(v));
    EXPECT_GT(peak, 0.1);   // the glint is there
    EXPECT_EQ(reg.image.pixels, path.image.pixels);
}

}  // namespace lu::test
