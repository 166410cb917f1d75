// The material builder (scene/build_materials.cpp) for coatedconductor, diffusetransmission, mix
// and normal maps: pbrt-v4's parameter names and defaults, mix children in any MakeNamedMaterial
// order, and a located error for each kind of bad input.
#include <gtest/gtest.h>

#include <fstream>

#include "lucerna/image/image.h"
#include "lucerna/scene/builder.h"
#include "support/test_support.h"

namespace lu {
namespace {

const char *kHeader =
    "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
    "Camera \"perspective\" \"float fov\" [ 45 ]\n"
    "WorldBegin\n";
const char *kShape = "\nShape \"sphere\"\nLightSource \"point\"\n";

std::unique_ptr<HostScene> BuildWorld(const std::string &world, Diagnostics &diag) {
    diag.quiet = true;
    SceneDescription desc = ParseSceneString(std::string(kHeader) + world + kShape, "test.pbrt", diag);
    return BuildScene(desc, diag, BuildOptions{});
}

const Material &ShapeMaterial(const HostScene &s) { return s.materials[s.shapes[0].material]; }

void ExpectError(const std::string &world, int line, const std::string &needle) {
    Diagnostics diag;
    try {
        BuildWorld(world, diag);
        ADD_FAILURE() << "no SceneError for:\n" << world;
    } catch (const SceneError &e) {
        EXPECT_NE(e.Message().find(needle), std::string::npos) << e.Message();
        EXPECT_EQ(e.Loc().line, line) << e.Format();
    }
}

TEST(MaterialBuild, CoatedConductorDefaultsAndParameters) {
    Diagnostics diag;
    auto s = BuildWorld("Material \"coatedconductor\"", diag);
    EXPECT_TRUE(diag.warnings.empty());
    const Material &d = ShapeMaterial(*s);
    EXPECT_EQ(d.kind, MaterialKind::CoatedConductor);
    EXPECT_EQ(d.uRoughness.value, 0);
    EXPECT_EQ(d.conductorURoughness.value, 0);
    EXPECT_EQ(d.thickness.value, 0.01f);
    EXPECT_EQ(d.eta.scale, 1.5f);
    EXPECT_FALSE(d.useReflectance);          // copper eta and k
    EXPECT_EQ(d.conductorEta.value.kind, SpectrumKind::Tabulated);
    EXPECT_EQ(d.maxDepth, 10);
    EXPECT_EQ(d.nSamples, 1);
    EXPECT_TRUE(d.remapRoughness);

    auto t = BuildWorld("Material \"coatedconductor\" \"float interface.uroughness\" 0.1 \"float interface.vroughness\" 0.2 "
                        "\"float conductor.roughness\" 0.3 \"float interface.eta\" 1.7 \"float thickness\" 0.05 "
                        "\"rgb reflectance\" [ 0.5 0.6 0.7 ] \"integer maxdepth\" 4 \"integer nsamples\" 2 "
                        "\"float g\" 0.2 \"rgb albedo\" [ 0.3 0.3 0.3 ] \"bool remaproughness\" false", diag);
    const Material &m = ShapeMaterial(*t);
    EXPECT_EQ(m.uRoughness.value, 0.1f);
    EXPECT_EQ(m.vRoughness.value, 0.2f);
    EXPECT_EQ(m.conductorURoughness.value, 0.3f);
    EXPECT_EQ(m.conductorVRoughness.value, 0.3f);
    EXPECT_EQ(m.eta.scale, 1.7f);
    EXPECT_EQ(m.thickness.value, 0.05f);
    EXPECT_TRUE(m.useReflectance);
    EXPECT_EQ(m.maxDepth, 4);
    EXPECT_EQ(m.nSamples, 2);
    EXPECT_EQ(m.g.value, 0.2f);
    EXPECT_FALSE(m.remapRoughness);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
}

TEST(MaterialBuild, DiffuseTransmissionDefaults) {
    Diagnostics diag;
    auto s = BuildWorld("Material \"diffusetransmission\"", diag);
    const Material &m = ShapeMaterial(*s);
    EXPECT_EQ(m.kind, MaterialKind::DiffuseTransmission);
    EXPECT_EQ(m.reflectance.value.scale, 0.25f);
    EXPECT_EQ(m.transmittance.value.scale, 0.25f);
    EXPECT_EQ(m.scale, 1);
    auto t = BuildWorld("Material \"diffusetransmission\" \"float scale\" 0.5", diag);
    EXPECT_EQ(ShapeMaterial(*t).scale, 0.5f);
}

TEST(MaterialBuild, MixChildrenInAnyOrderAndNested) {
    Diagnostics diag;
    // "amix" sorts before its children; "outer" names "amix".
    auto s = BuildWorld("MakeNamedMaterial \"outer\" \"string type\" \"mix\" \"string materials\" [ \"amix\" \"zred\" ]\n"
                        "MakeNamedMaterial \"amix\" \"string type\" \"mix\" \"string materials\" [ \"zred\" \"zmetal\" ] "
                        "\"float amount\" 0.3\n"
                        "MakeNamedMaterial \"zred\" \"string type\" \"diffuse\"\n"
                        "MakeNamedMaterial \"zmetal\" \"string type\" \"conductor\"\n"
                        "NamedMaterial \"outer\"",
                        diag);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    const Material &outer = ShapeMaterial(*s);
    ASSERT_EQ(outer.kind, MaterialKind::Mix);
    EXPECT_EQ(outer.amount.value, 0.5f);   // pbrt-v4's default
    const Material &inner = s->materials[outer.mixMaterials[0]];
    ASSERT_EQ(inner.kind, MaterialKind::Mix);
    EXPECT_EQ(inner.amount.value, 0.3f);
    EXPECT_EQ(s->materials[inner.mixMaterials[0]].kind, MaterialKind::Diffuse);
    EXPECT_EQ(s->materials[inner.mixMaterials[1]].kind, MaterialKind::Conductor);
    EXPECT_EQ(outer.mixMaterials[1], inner.mixMaterials[0]);   // "zred" built once
    // Children come before their mix (so the shared code's loop over picks ends).
    EXPECT_LT(outer.mixMaterials[0], s->shapes[0].material);
}

TEST(MaterialBuild, Errors) {
    ExpectError("Material \"mix\" \"string materials\" [ \"a\" ]", 4, "two values");
    ExpectError("Material \"mix\" \"string materials\" [ \"a\" \"b\" ]", 4, "\"a\" not found");
    ExpectError("MakeNamedMaterial \"glass\" \"string type\" \"interface\"\n"
                "MakeNamedMaterial \"d\" \"string type\" \"diffuse\"\n"
                "Material \"mix\" \"string materials\" [ \"d\" \"glass\" ]",
                6, "an \"interface\" material cannot be used");
    ExpectError("MakeNamedMaterial \"a\" \"string type\" \"mix\" \"string materials\" [ \"b\" \"b\" ]\n"
                "MakeNamedMaterial \"b\" \"string type\" \"mix\" \"string materials\" [ \"a\" \"a\" ]",
                5, "contains itself (a cycle of mix materials)");   // found while building a's child b
    ExpectError("Material \"coatedconductor\" \"rgb reflectance\" [ 0.5 0.5 0.5 ] \"spectrum conductor.eta\" \"metal-Au-eta\"",
                4, "can't both be provided");
    ExpectError("Material \"coatedconductor\" \"float conductor.roughness\" -0.1", 4, "\"conductor.roughness\" must not be negative");
    ExpectError("Material \"coatedconductor\" \"float interface.vroughness\" -1", 4, "\"interface.vroughness\" must not be negative");
    ExpectError("Material \"coatedconductor\" \"float interface.eta\" 0", 4, "\"interface.eta\" (index of refraction) must be positive");
    ExpectError("Material \"coatedconductor\" \"float g\" 1.5", 4, "\"g\" must be in [-1, 1]");
    ExpectError("Material \"coatedconductor\" \"integer nsamples\" 0", 4, "\"nsamples\" must be at least 1");
    ExpectError("Material \"diffuse\" \"string normalmap\" \"missing.exr\"", 4, "missing.exr");
    ExpectError("Material \"diffuse\" \"texture displacement\" \"nope\"", 4, "couldn't find float texture named \"nope\"");
    ExpectError("Material \"dielectric\" \"texture eta\" \"nope\"", 4, "couldn't find float texture named \"nope\"");
}

TEST(MaterialBuild, DisplacementAndTexturedEta) {
    const char *defs = "Texture \"b\" \"float\" \"fbm\"\nTexture \"e\" \"float\" \"constant\" \"float value\" 1.33\n";
    for (std::string mat : {"Material \"diffuse\" \"texture displacement\" \"b\"",
                            "Material \"dielectric\" \"texture displacement\" \"b\" \"texture eta\" \"e\"",
                            "Material \"thindielectric\" \"texture displacement\" \"b\" \"texture eta\" \"e\"",
                            "Material \"coateddiffuse\" \"texture displacement\" \"b\" \"texture eta\" \"e\"",
                            "Material \"coatedconductor\" \"texture displacement\" \"b\" \"texture interface.eta\" \"e\""}) {
        SCOPED_TRACE(mat);
        Diagnostics diag;
        auto s = BuildWorld(defs + mat, diag);
        EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
        EXPECT_TRUE(diag.unsupported.empty());
        const Material &m = ShapeMaterial(*s);
        ASSERT_NE(m.displacement, NoIndex);
        EXPECT_EQ(s->floatTextures[m.displacement].kind, TextureKind::FBm);
        if (mat.find("eta") != std::string::npos) {
            ASSERT_NE(m.etaTexture, NoIndex);
            EXPECT_EQ(s->floatTextures[m.etaTexture].value, 1.33f);
        } else {
            EXPECT_EQ(m.etaTexture, NoIndex);
        }
    }
    // A float displacement is a constant node; a plain float eta stays a spectrum.
    Diagnostics diag;
    auto s = BuildWorld("Material \"dielectric\" \"float displacement\" 0.1 \"float eta\" 1.4", diag);
    const Material &m = ShapeMaterial(*s);
    ASSERT_NE(m.displacement, NoIndex);
    EXPECT_EQ(s->floatTextures[m.displacement].value, 0.1f);
    EXPECT_EQ(m.etaTexture, NoIndex);
    EXPECT_TRUE(m.eta.IsConstant());
}

TEST(MaterialBuild, NormalMapNeedsRGB) {
    std::string dir = test::TempDir("nmap_build");
    WriteEXR(dir + "/gray.exr", MakeImage(2, 2, 1, 0.5f));
    WriteEXR(dir + "/rgb.exr", MakeImage(2, 2, 3, 0.5f));
    std::ofstream(dir + "/ok.pbrt") << kHeader << "Material \"conductor\" \"string normalmap\" \"rgb.exr\"" << kShape;
    std::ofstream(dir + "/bad.pbrt") << kHeader << "Material \"diffuse\" \"string normalmap\" \"gray.exr\"" << kShape;
    Diagnostics diag;
    diag.quiet = true;
    auto s = LoadScene(dir + "/ok.pbrt", diag, BuildOptions{});
    const Material &m = ShapeMaterial(*s);
    ASSERT_NE(m.normalMap, NoIndex);
    EXPECT_EQ(s->images[m.normalMap].channels, 3u);
    EXPECT_EQ(s->images[m.normalMap].wrap, WrapMode::Repeat);
    try {
        LoadScene(dir + "/bad.pbrt", diag, BuildOptions{});
        ADD_FAILURE() << "a one-channel normal map was accepted";
    } catch (const SceneError &e) {
        EXPECT_NE(e.Message().find("must contain R, G, and B channels"), std::string::npos) << e.Message();
        EXPECT_EQ(e.Loc().line, 4);
    }
}

}  // namespace
}  // namespace lu
