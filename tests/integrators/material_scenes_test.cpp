// pbrt-v4's mix, diffusetransmission, coatedconductor and measured materials through the whole renderer:
// the feature scene (scenes/features/materials-*.pbrt) builds clean and renders finite; a quad
// under a uniform white environment (radiance = albedo) shows each material's analytic value:
// mix of equal materials = the material, per pixel; mix by amount a = the blend in the mean;
// diffusetransmission = R + T (seen from either side); coatedconductor <= 1; lossless hair = 1.
// Normal maps: a flat map ((0.5, 0.5, 1)) renders bit-identically to none, a tilted one does not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "integrators/render_helpers.h"

namespace lu::test {
namespace {

TEST(MaterialScenes, FeatureScenesBuildCleanAndRenderFinite) {
    std::vector<std::string> files = FeatureSceneFiles({"materials-"});
    ASSERT_EQ(files.size(), 4u);   // bump, hair, layered-mix, measured
    for (const std::string &file : files) {
        SCOPED_TRACE(file);
        auto scene = LoadCleanFeatureScene(file, 48, 24);   // no unsupported feature, no warning
        ExpectRendersFiniteAndLit(*scene);
    }
}

// A quad filling the view under a uniform environment L = 1; the camera looks at its front
// (back = true: at its back).
std::string QuadScene(const std::string &defs, const std::string &material, bool back = false) {
    return std::string(back ? "LookAt 0 0 2  0 0 0  0 1 0\n" : "LookAt 0 0 -2  0 0 0  0 1 0\n") +
           "Camera \"perspective\" \"float fov\" [ 40 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
           "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n" +
           defs + material + "\nShape \"bilinearmesh\" \"point3 P\" [ -2 -2 0  2 -2 0  -2 2 0  2 2 0 ]\n";
}

double MeanOf(const Image &img) {
    double s = 0;
    for (float v : img.pixels) s += v;
    return s / img.pixels.size();
}

TEST(MaterialScenes, MixOfEqualMaterialsIsTheMaterial) {
    auto ref = LoadSceneText("mix_ref", QuadScene("", "Material \"coateddiffuse\" \"rgb reflectance\" [ 0.4 0.3 0.2 ]"));
    std::string defs = "MakeNamedMaterial \"a\" \"string type\" \"coateddiffuse\" \"rgb reflectance\" [ 0.4 0.3 0.2 ]\n"
                       "MakeNamedMaterial \"b\" \"string type\" \"coateddiffuse\" \"rgb reflectance\" [ 0.4 0.3 0.2 ]\n";
    auto mix = LoadSceneText("mix_equal", QuadScene(defs, "Material \"mix\" \"string materials\" [ \"a\" \"b\" ] \"float amount\" 0.5"));
    RenderResultForTest r0 = RenderScene(*ref, 4, 5, 3), r1 = RenderScene(*mix, 4, 5, 3);
    ASSERT_EQ(r0.image.pixels.size(), r1.image.pixels.size());
    for (size_t i = 0; i < r0.image.pixels.size(); ++i) ASSERT_EQ(r0.image.pixels[i], r1.image.pixels[i]) << i;
}

TEST(MaterialScenes, MixBlendsByAmountInTheMean) {
    std::string defs = "MakeNamedMaterial \"dark\" \"string type\" \"diffuse\" \"rgb reflectance\" [ 0.2 0.2 0.2 ]\n"
                       "MakeNamedMaterial \"light\" \"string type\" \"diffuse\" \"rgb reflectance\" [ 0.8 0.8 0.8 ]\n";
    for (double amount : {0.25, 0.7}) {
        auto s = LoadSceneText("mix_blend", QuadScene(defs, "Material \"mix\" \"string materials\" [ \"dark\" \"light\" ] "
                                                            "\"float amount\" " + std::to_string(amount)));
        RenderResultForTest r = RenderScene(*s, 16, 5, 7);
        MeanSE m = RegionMean(r.image, 1, 0, 0, 16, 16);
        double expect = (1 - amount) * 0.2 + amount * 0.8;
        // Per pixel the estimate is a mean of 16 picks (each 0.2 or 0.8): sigma 0.6 sqrt(a(1-a)/16).
        EXPECT_NEAR(m.mean, expect, 4.5 * m.se + 0.01) << "amount " << amount;
        EXPECT_GT(m.se, 0.002);   // the picks vary over the quad (per pixel sd ~0.06 here)
    }
}

TEST(MaterialScenes, DiffuseTransmissionIsRPlusT) {
    for (bool back : {false, true}) {
        auto s = LoadSceneText("difftrans", QuadScene("", "Material \"diffusetransmission\" \"rgb reflectance\" [ 0.3 0.3 0.3 ] "
                                                          "\"rgb transmittance\" [ 0.5 0.5 0.5 ] \"float scale\" 1.2", back));
        RenderResultForTest r = RenderScene(*s, 8, 5, 1);
        // Lit by L = 1 from both sides: (R + T) scale = 0.96; only NEE and BSDF-sampling noise.
        EXPECT_NEAR(MeanOf(r.image), 0.96, 0.02) << (back ? "back" : "front");
    }
    auto defaults = LoadSceneText("difftrans_default", QuadScene("", "Material \"diffusetransmission\""));
    EXPECT_NEAR(MeanOf(RenderScene(*defaults, 8, 5, 1).image), 0.5, 0.02);   // pbrt-v4 defaults 0.25 + 0.25
}

TEST(MaterialScenes, CoatedConductorFurnace) {
    // A lossless coat (thickness 0) over a near-mirror ("reflectance" 0.9999 gives eta 1, k ~ 200).
    auto s = LoadSceneText("coatedcond", QuadScene("", "Material \"coatedconductor\" \"rgb reflectance\" [ 0.9999 0.9999 0.9999 ] "
                                                       "\"float thickness\" 0 \"float conductor.roughness\" 0"));
    RenderResultForTest r = RenderScene(*s, 4, 50, 1);
    double m = MeanOf(r.image);
    EXPECT_GT(m, 0.99);
    EXPECT_LT(m, 1.005);
}

// Hair in a white furnace: a quad of lossless fibers (sigma_a = 0; h = -1 + 2 v across the quad)
// under L = 1 scatters all light (the TT lobe through the quad, R and TRT back), so the image is
// 1 up to pbrt-v4's I0 approximation (HairBxDF's quadrature albedo is within 0.0035 of 1);
// absorption darkens it.
TEST(MaterialScenes, HairFurnace) {
    auto s = LoadSceneText("hairfurnace", QuadScene("", "Material \"hair\" \"rgb sigma_a\" [ 0 0 0 ] \"float beta_m\" 0.3"));
    RenderResultForTest r = RenderScene(*s, 16, 50, 1);
    double m = MeanOf(r.image);
    EXPECT_NEAR(m, 1, 0.01);
    auto dark = LoadSceneText("hairdark", QuadScene("", "Material \"hair\" \"float eumelanin\" 1.3"));
    double d = MeanOf(RenderScene(*dark, 16, 50, 1).image);
    if (getenv("LU_VERBOSE")) printf("hair furnace mean %.5f, eumelanin 1.3 mean %.5f\n", m, d);
    EXPECT_LT(d, 0.8 * m);
    EXPECT_GT(d, 0.02);
}

// The measured material of the feature scene's file against the analytic conductor it tabulates
// (tests/materials/measured_gen.h), on the quad under L = 1: each pixel is the directional
// albedo towards the camera. The means agree within 1% (measured 0.3%) plus noise.
TEST(MaterialScenes, MeasuredQuadMatchesItsAnalyticConductor) {
    std::string file = std::string(LUCERNA_SOURCE_DIR) + "/scenes/features/measured-tr-conductor.bsdf";
    auto measured = LoadSceneText("measured_quad", QuadScene("", "Material \"measured\" \"string filename\" \"" + file + "\""));
    auto analytic = LoadSceneText("measured_quad_ref", QuadScene("", "Material \"conductor\" \"float roughness\" 0.09 "
        "\"spectrum eta\" [ 360 1.4  400 1.4  750 0.2  830 0.2 ] \"spectrum k\" [ 360 1.9  400 1.9  750 3.6  830 3.6 ]"));
    RenderResultForTest rm = RenderScene(*measured, 16, 5, 3), ra = RenderScene(*analytic, 16, 5, 4);
    for (int c = 0; c < 3; ++c) {
        MeanSE m = RegionMean(rm.image, c, 0, 0, 16, 16), a = RegionMean(ra.image, c, 0, 0, 16, 16);
        if (getenv("LU_VERBOSE"))
            printf("channel %d: measured %.4f +- %.4f, analytic %.4f +- %.4f\n", c, m.mean, m.se, a.mean, a.se);
        EXPECT_NEAR(m.mean, a.mean, 0.01 * a.mean + 4.5 * (m.se + a.se)) << "channel " << c;
        EXPECT_GT(a.mean, 0.2);
    }
}

// A flat and a tilted normal map (EXR, exact values) in a scene's folder; a diffuse quad under a
// distant light at an angle, so that the shading normal matters.
std::string NormalMapScene(const std::string &dir, const std::string &material) {
    Image flat = MakeImage(4, 3, 3);
    Image tilted = MakeImage(4, 3, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            flat.At(x, y, 0) = 0.5f; flat.At(x, y, 1) = 0.5f; flat.At(x, y, 2) = 1;
            tilted.At(x, y, 0) = 0.5f + 0.1f * x; tilted.At(x, y, 1) = 0.4f; tilted.At(x, y, 2) = 0.9f;
        }
    WriteEXR(dir + "/flat.exr", flat);
    WriteEXR(dir + "/tilted.exr", tilted);
    return "LookAt 0 0 -2  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
           "WorldBegin\nLightSource \"distant\" \"point3 from\" [ 1 0.5 -1 ] \"point3 to\" [ 0 0 0 ]\n"
           "LightSource \"infinite\" \"rgb L\" [ 0.2 0.2 0.2 ]\n" + material +
           "\nShape \"bilinearmesh\" \"point3 P\" [ -2 -2 0  2 -2 0  -2 2 0  2 2 0 ] \"point2 uv\" [ 0 0 1 0 0 1 1 1 ]\n";
}

std::unique_ptr<HostScene> LoadNormalMapScene(const std::string &name, const std::string &material) {
    std::string dir = TempDir(name);
    std::ofstream(dir + "/scene.pbrt") << NormalMapScene(dir, material);
    Diagnostics diag;
    diag.quiet = true;
    return LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
}

TEST(MaterialScenes, FlatNormalMapIsBitIdentical) {
    for (const char *mat : {"Material \"diffuse\"", "Material \"conductor\" \"float roughness\" 0.2",
                            "Material \"coateddiffuse\" \"float roughness\" 0.1"}) {
        SCOPED_TRACE(mat);
        auto none = LoadNormalMapScene("nmap_none", mat);
        auto flat = LoadNormalMapScene("nmap_flat", std::string(mat) + " \"string normalmap\" \"flat.exr\"");
        auto tilted = LoadNormalMapScene("nmap_tilted", std::string(mat) + " \"string normalmap\" \"tilted.exr\"");
        ASSERT_NE(flat->materials.back().normalMap, NoIndex);
        RenderResultForTest r0 = RenderScene(*none, 4, 5, 2), r1 = RenderScene(*flat, 4, 5, 2),
                            r2 = RenderScene(*tilted, 4, 5, 2);
        ASSERT_EQ(r0.image.pixels.size(), r1.image.pixels.size());
        double maxDiff = 0;
        for (size_t i = 0; i < r0.image.pixels.size(); ++i) {
            ASSERT_EQ(r0.image.pixels[i], r1.image.pixels[i]) << i;
            maxDiff = std::max(maxDiff, double(std::abs(r2.image.pixels[i] - r0.image.pixels[i])));
            ASSERT_TRUE(std::isfinite(r2.image.pixels[i]));
        }
        EXPECT_GT(maxDiff, 0.01);   // the control: a tilted map changes the shading
    }
}

// A "texture" eta (pbrt-v4 accepts a float texture on the dielectric interfaces) evaluated per
// hit: a constant texture renders byte-identically to the plain float; a checkerboard of indices
// does not.
std::string EtaScene(const std::string &defs, const std::string &eta, const std::string &ieta) {
    return "LookAt 0 1 -4  0 0.4 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 45 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 16 ]\n"
           "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 0.6 0.6 0.6 ]\n"
           "LightSource \"distant\" \"point3 from\" [ -2 5 -4 ] \"point3 to\" [ 0 0 0 ] \"rgb L\" [ 2 2 2 ]\n" + defs +
           "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.6 0.5 0.4 ]\n"
           "Shape \"bilinearmesh\" \"point3 P\" [ -4 0 -4  4 0 -4  -4 0 4  4 0 4 ]\nAttributeEnd\n"
           "AttributeBegin\nMaterial \"dielectric\" " + eta + " \"float roughness\" 0.1\nTranslate -1.5 0.5 0\n"
           "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"
           "AttributeBegin\nMaterial \"thindielectric\" " + eta + "\nTranslate -0.5 0.5 0\n"
           "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"
           "AttributeBegin\nMaterial \"coateddiffuse\" " + eta + "\nTranslate 0.5 0.5 0\n"
           "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"
           "AttributeBegin\nMaterial \"coatedconductor\" " + ieta + "\nTranslate 1.5 0.5 0\n"
           "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n";
}

TEST(MaterialScenes, ConstantTextureEtaIsTheFloatEta) {
    auto plain = LoadSceneText("eta_float", EtaScene("", "\"float eta\" 1.33", "\"float interface.eta\" 1.33"));
    std::string defs = "Texture \"e\" \"float\" \"constant\" \"float value\" 1.33\n";
    auto tex = LoadSceneText("eta_tex", EtaScene(defs, "\"texture eta\" \"e\"", "\"texture interface.eta\" \"e\""));
    std::string checks = "Texture \"e\" \"float\" \"checkerboard\" \"float uscale\" 8 \"float vscale\" 8 "
                         "\"float tex1\" 1.33 \"float tex2\" 1.8\n";
    auto varying = LoadSceneText("eta_checks", EtaScene(checks, "\"texture eta\" \"e\"", "\"texture interface.eta\" \"e\""));
    ASSERT_TRUE(plain && tex && varying);
    for (const Material &m : tex->materials)
        if (m.kind != MaterialKind::Diffuse) {
            EXPECT_NE(m.etaTexture, NoIndex);
        }
    RenderResultForTest r0 = RenderScene(*plain, 8, 6, 5), r1 = RenderScene(*tex, 8, 6, 5), r2 = RenderScene(*varying, 8, 6, 5);
    ASSERT_EQ(r0.image.pixels.size(), r1.image.pixels.size());
    double maxDiff = 0;
    for (size_t i = 0; i < r0.image.pixels.size(); ++i) {
        ASSERT_EQ(r0.image.pixels[i], r1.image.pixels[i]) << i;
        ASSERT_TRUE(std::isfinite(r2.image.pixels[i]));
        maxDiff = std::max(maxDiff, double(std::abs(r2.image.pixels[i] - r0.image.pixels[i])));
    }
    EXPECT_GT(maxDiff, 0.01);   // the control: a varying index changes the image
}

}  // namespace
}  // namespace lu::test
