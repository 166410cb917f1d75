// The hair material's builder (scene/build_materials.cpp ReadHair): pbrt-v4's parameter names
// and defaults, the three ways of giving the absorption and which one wins, and located errors
// for values the model has no meaning for.
#include <gtest/gtest.h>

#include "lucerna/scene/builder.h"
#include "support/test_support.h"

namespace lu {
namespace {

const char *kHairHeader =
    "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
    "Camera \"perspective\" \"float fov\" [ 45 ]\n"
    "WorldBegin\n";

std::unique_ptr<HostScene> BuildHair(const std::string &world, Diagnostics &diag) {
    diag.quiet = true;
    SceneDescription desc =
        ParseSceneString(std::string(kHairHeader) + world + "\nShape \"sphere\"\nLightSource \"point\"\n", "hair.pbrt", diag);
    return BuildScene(desc, diag, BuildOptions{});
}

const Material &First(const HostScene &s) { return s.materials[s.shapes[0].material]; }

bool AnyContains(const std::vector<std::string> &v, const std::string &needle) {
    for (const std::string &s : v)
        if (s.find(needle) != std::string::npos) return true;
    return false;
}

TEST(HairBuild, DefaultsAreEumelanin13) {
    Diagnostics diag;
    auto s = BuildHair("Material \"hair\"", diag);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    const Material &m = First(*s);
    EXPECT_EQ(m.kind, MaterialKind::Hair);
    EXPECT_EQ(m.hairColor, HairColor::Melanin);
    EXPECT_EQ(m.eumelanin.value, 1.3f);
    EXPECT_EQ(m.pheomelanin.value, 0.f);
    EXPECT_EQ(m.hairEta.value, 1.55f);
    EXPECT_EQ(m.betaM.value, 0.3f);
    EXPECT_EQ(m.betaN.value, 0.3f);
    EXPECT_EQ(m.hairAlpha.value, 2.f);
    EXPECT_EQ(s->stats.materialsByType.at("hair"), 1);
}

TEST(HairBuild, TheThreeColourOptions) {
    Diagnostics diag;
    auto a = BuildHair("Material \"hair\" \"rgb sigma_a\" [ 0.2 0.4 0.8 ] \"float eta\" 1.6 \"float beta_m\" 0.2 "
                       "\"float beta_n\" 0.5 \"float alpha\" 3",
                       diag);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    const Material &ma = First(*a);
    EXPECT_EQ(ma.hairColor, HairColor::SigmaA);
    EXPECT_EQ(ma.hairSigmaA.value.kind, SpectrumKind::RGBUnbounded);   // sigma_a is unbounded, not an albedo
    EXPECT_EQ(ma.hairEta.value, 1.6f);
    EXPECT_EQ(ma.betaM.value, 0.2f);
    EXPECT_EQ(ma.betaN.value, 0.5f);
    EXPECT_EQ(ma.hairAlpha.value, 3.f);

    auto r = BuildHair("Material \"hair\" \"rgb reflectance\" [ 0.5 0.3 0.2 ]", diag);
    EXPECT_EQ(First(*r).hairColor, HairColor::Reflectance);
    EXPECT_EQ(First(*r).reflectance.value.kind, SpectrumKind::RGBAlbedo);
    // pbrt-v4 also accepts "color" for the reflectance.
    auto c = BuildHair("Material \"hair\" \"rgb color\" [ 0.5 0.3 0.2 ]", diag);
    EXPECT_EQ(First(*c).hairColor, HairColor::Reflectance);
    EXPECT_EQ(First(*c).reflectance.value.kind, SpectrumKind::RGBAlbedo);

    // Only pheomelanin: eumelanin is 0 (not the 1.3 default).
    auto p = BuildHair("Material \"hair\" \"float pheomelanin\" 0.8", diag);
    EXPECT_EQ(First(*p).hairColor, HairColor::Melanin);
    EXPECT_EQ(First(*p).eumelanin.value, 0.f);
    EXPECT_EQ(First(*p).pheomelanin.value, 0.8f);
    // Float textures are accepted for the concentrations and roughnesses.
    auto t = BuildHair("Texture \"e\" \"float\" \"checkerboard\" \"float tex1\" 0.5 \"float tex2\" 2\n"
                       "Texture \"e2\" \"float\" \"constant\" \"float value\" 0.4\n"
                       "MakeNamedMaterial \"h\" \"string type\" \"hair\" \"texture eumelanin\" \"e\" \"texture beta_m\" \"e2\"\n",
                       diag);
    (void)t;
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
}

TEST(HairBuild, SigmaAWinsOverTheOthersWithAWarning) {
    Diagnostics diag;
    auto s = BuildHair("Material \"hair\" \"rgb sigma_a\" [ 0.2 0.4 0.8 ] \"rgb reflectance\" [ 0.5 0.3 0.2 ] "
                       "\"float eumelanin\" 2",
                       diag);
    EXPECT_EQ(First(*s).hairColor, HairColor::SigmaA);
    ASSERT_EQ(diag.warnings.size(), 2u);
    EXPECT_TRUE(AnyContains(diag.warnings, "hair.pbrt:4:")) << diag.warnings[0];
    EXPECT_TRUE(AnyContains(diag.warnings, "ignoring \"reflectance\" since \"sigma_a\"")) << diag.warnings[0];
    EXPECT_TRUE(AnyContains(diag.warnings, "ignoring \"eumelanin\" since \"sigma_a\"")) << diag.warnings[1];

    Diagnostics d2;
    auto r = BuildHair("Material \"hair\" \"rgb color\" [ 0.5 0.3 0.2 ] \"float pheomelanin\" 2", d2);
    EXPECT_EQ(First(*r).hairColor, HairColor::Reflectance);
    ASSERT_EQ(d2.warnings.size(), 1u);
    EXPECT_TRUE(AnyContains(d2.warnings, "ignoring \"pheomelanin\" since \"color\"")) << d2.warnings[0];

    // pbrt-v4's hair has no normal or bump map: reported as unused.
    Diagnostics d3;
    BuildHair("Material \"hair\" \"float displacement\" 0.1", d3);
    EXPECT_TRUE(AnyContains(d3.warnings, "displacement")) << (d3.warnings.empty() ? "" : d3.warnings[0]);
}

void ExpectHairError(const std::string &params, const std::string &needle) {
    Diagnostics diag;
    try {
        BuildHair("\nMaterial \"hair\"\n  " + params, diag);
        ADD_FAILURE() << "no SceneError for " << params;
    } catch (const SceneError &e) {
        EXPECT_NE(e.Message().find(needle), std::string::npos) << e.Message();
        EXPECT_EQ(e.Loc().line, 6) << e.Format();   // the parameter's line
    }
}

TEST(HairBuild, BadValuesAreLocatedErrors) {
    ExpectHairError("\"float beta_m\" -0.1", "\"beta_m\" must be in (0, 1]");
    ExpectHairError("\"float beta_m\" 0", "\"beta_m\" must be in (0, 1]");
    ExpectHairError("\"float beta_n\" 1.5", "\"beta_n\" must be in (0, 1]");
    ExpectHairError("\"float beta_n\" -2", "\"beta_n\" must be in (0, 1]");
    ExpectHairError("\"float eta\" 0", "\"eta\" (index of refraction) must be positive");
    ExpectHairError("\"float eta\" -1.5", "\"eta\" (index of refraction) must be positive");
    ExpectHairError("\"float eumelanin\" -1", "\"eumelanin\" must not be negative");
    ExpectHairError("\"float pheomelanin\" -0.5", "\"pheomelanin\" must not be negative");
    ExpectHairError("\"rgb sigma_a\" [ -1 0 0 ]", "sigma_a");
    // Limits are accepted.
    Diagnostics diag;
    auto s = BuildHair("Material \"hair\" \"float beta_m\" 1 \"float beta_n\" 0.01", diag);
    EXPECT_EQ(First(*s).betaM.value, 1.f);
}

// No hair material is reported unsupported any more; a scene using one builds without errors.
TEST(HairBuild, NotUnsupported) {
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription desc = ParseSceneString(std::string(kHairHeader) + "MakeNamedMaterial \"h\" \"string type\" \"hair\"\n"
                                                                         "NamedMaterial \"h\"\nShape \"sphere\"\nLightSource \"point\"\n",
                                             "hair.pbrt", diag);
    auto s = BuildScene(desc, diag, BuildOptions{});
    EXPECT_EQ(First(*s).kind, MaterialKind::Hair);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    EXPECT_TRUE(diag.unsupported.empty());
}

}  // namespace
}  // namespace lu
