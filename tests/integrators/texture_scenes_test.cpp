// Textures through the whole renderer: every scenes/features/textures-*.pbrt builds with nothing
// unsupported and no warnings and renders finite, non-black images; composites of constants
// render as the equivalent constant reflectance (same seed: per pixel).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "integrators/render_helpers.h"

namespace lu::test {
namespace {

std::vector<std::string> TextureFeatureScenes() { return FeatureSceneFiles({"textures-"}); }

TEST(TextureScenes, FeatureScenesBuildCleanAndRenderFinite) {
    std::vector<std::string> files = TextureFeatureScenes();
    ASSERT_EQ(files.size(), 4u);
    for (const std::string &file : files) {
        SCOPED_TRACE(file);
        auto scene = LoadCleanFeatureScene(file, 48, 24);   // no unsupported feature, no warning
        EXPECT_GT(scene->stats.floatTextures + scene->stats.spectrumTextures, 3);
        ExpectRendersFiniteAndLit(*scene);
    }
}

// A diffuse quad filling the view under a uniform environment; its reflectance given as a
// constant or as a texture that evaluates to the same constant everywhere.
std::string QuadScene(const std::string &textures, const std::string &reflectance) {
    return "LookAt 0 0 -2  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
           "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n" +
           textures + "Material \"diffuse\" " + reflectance +
           "\nShape \"bilinearmesh\" \"point3 P\" [ -2 -2 0  2 -2 0  -2 2 0  2 2 0 ]\n";
}

TEST(TextureScenes, CompositesOfConstantsRenderAsTheConstant) {
    auto reference = LoadSceneText("tex_const_ref", QuadScene("", "\"rgb reflectance\" [ 0.35 0.35 0.35 ]"));
    RenderResultForTest ref = RenderScene(*reference, 8, 3, 5);
    const std::string c = "\"rgb tex1\" [0.35 0.35 0.35] \"rgb tex2\" [0.35 0.35 0.35]";
    const char *cases[][2] = {
        {"Texture \"t\" \"spectrum\" \"mix\" \"rgb tex1\" [0.2 0.2 0.2] \"rgb tex2\" [0.8 0.8 0.8] \"float amount\" 0.25\n", "mix"},
        {"Texture \"a\" \"float\" \"constant\" \"float value\" 0.7\n"
         "Texture \"t\" \"spectrum\" \"scale\" \"rgb tex\" [0.5 0.5 0.5] \"texture scale\" \"a\"\n", "scale"},
        {nullptr, "checkerboard"}, {nullptr, "dots"}, {nullptr, "directionmix"},
        {"Texture \"t\" \"spectrum\" \"bilerp\" \"rgb v00\" [0.35 0.35 0.35] \"rgb v01\" [0.35 0.35 0.35] "
         "\"rgb v10\" [0.35 0.35 0.35] \"rgb v11\" [0.35 0.35 0.35]\n", "bilerp"},
        {"Texture \"w\" \"float\" \"wrinkled\"\n"
         "Texture \"t\" \"spectrum\" \"mix\" \"rgb tex1\" [0.35 0.35 0.35] \"rgb tex2\" [0.35 0.35 0.35] "
         "\"texture amount\" \"w\"\n", "mix by wrinkled"},
    };
    for (auto &cs : cases) {
        SCOPED_TRACE(cs[1]);
        std::string tex;
        if (cs[0]) tex = cs[0];
        else if (std::string(cs[1]) == "checkerboard")
            tex = "Texture \"t\" \"spectrum\" \"checkerboard\" \"integer dimension\" 3 " + c + "\n";
        else if (std::string(cs[1]) == "dots")
            tex = "Texture \"t\" \"spectrum\" \"dots\" \"float uscale\" 9 \"rgb inside\" [0.35 0.35 0.35] "
                  "\"rgb outside\" [0.35 0.35 0.35]\n";
        else
            tex = "Texture \"t\" \"spectrum\" \"directionmix\" \"vector3 dir\" [0 0.6 -0.8] " + c + "\n";
        auto scene = LoadSceneText("tex_const_case", QuadScene(tex, "\"texture reflectance\" \"t\""));
        RenderResultForTest r = RenderScene(*scene, 8, 3, 5);
        ASSERT_EQ(r.image.pixels.size(), ref.image.pixels.size());
        double maxDiff = 0, mean = 0;
        for (size_t i = 0; i < r.image.pixels.size(); ++i) {
            maxDiff = std::max(maxDiff, double(std::abs(r.image.pixels[i] - ref.image.pixels[i])));
            mean += ref.image.pixels[i];
        }
        EXPECT_LT(maxDiff, 1e-4);
        EXPECT_NEAR(mean / ref.image.pixels.size(), 0.35, 0.05);   // the quad lit by L = 1: radiance = albedo
    }
    // The control: a texture that is not the constant does change the picture.
    auto other = LoadSceneText("tex_const_other",
                               QuadScene("Texture \"t\" \"spectrum\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4 "
                                         "\"rgb tex1\" [0.35 0.35 0.35] \"rgb tex2\" [0.2 0.2 0.2]\n",
                                         "\"texture reflectance\" \"t\""));
    RenderResultForTest o = RenderScene(*other, 8, 3, 5);
    double maxDiff = 0;
    for (size_t i = 0; i < o.image.pixels.size(); ++i)
        maxDiff = std::max(maxDiff, double(std::abs(o.image.pixels[i] - ref.image.pixels[i])));
    EXPECT_GT(maxDiff, 0.05);
}

}  // namespace
}  // namespace lu::test
