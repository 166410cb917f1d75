// The measured material in the scene builder and `lucerna info`: a missing filename, a missing
// file and a malformed file are errors at the Material's "filename" (file:line, exit 2); the
// feature scene reads with nothing unsupported, its data in SceneView::measuredData.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "lucerna/scene/builder.h"
#include "materials/measured_gen.h"
#include "support/test_support.h"

namespace lu {
namespace {

bool Contains(const std::string &s, const std::string &what) { return s.find(what) != std::string::npos; }

const char *kHeader = "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
                      "Camera \"perspective\"\nWorldBegin\n";

// The SceneError of loading text as dir/scene.pbrt (fails the test if none).
SceneError ErrorOfScene(const std::string &dir, const std::string &text) {
    std::ofstream(dir + "/scene.pbrt") << text;
    Diagnostics diag;
    diag.quiet = true;
    try {
        LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
    } catch (const SceneError &e) {
        return e;
    }
    ADD_FAILURE() << "no SceneError for:\n" << text;
    return SceneError(FileLoc{}, "");
}

TEST(Measured, BuilderLocatesMissingAndBadFiles) {
    std::string dir = test::TempDir("measured_builder");
    std::vector<uint8_t> good = test::GenerateMeasuredFile();
    std::ofstream(dir + "/cut.bsdf", std::ios::binary).write(reinterpret_cast<const char *>(good.data()), 1000);
    std::ofstream(dir + "/junk.bsdf") << "not a tensor file at all";
    struct Case {
        const char *material;
        const char *what;
    } cases[] = {
        {"Material \"measured\"\n", "needs a \"string filename\""},
        {"Material \"measured\" \"string filename\" \"absent.bsdf\"\n", "absent.bsdf\": unable to open"},
        {"Material \"measured\" \"string filename\" \"cut.bsdf\"\n", "cut.bsdf\": truncated tensor file"},
        {"Material \"measured\" \"string filename\" \"junk.bsdf\"\n", "junk.bsdf\": not a tensor file"},
        {"MakeNamedMaterial \"m\" \"string type\" \"measured\" \"string filename\" \"cut.bsdf\"\n", "cut.bsdf\": truncated"},
    };
    for (const Case &c : cases) {
        SceneError e = ErrorOfScene(dir, std::string(kHeader) + "\n" + c.material + "Shape \"sphere\"\n");
        EXPECT_TRUE(Contains(e.Message(), c.what)) << c.material << " -> " << e.Message();
        EXPECT_EQ(e.Loc().line, 5) << e.Message();
    }
    // `lucerna info` on the truncated file: exit 2, file:line and the file's name.
    std::ofstream(dir + "/info.pbrt") << kHeader << "\nMaterial \"measured\" \"string filename\" \"cut.bsdf\"\nShape \"sphere\"\n";
    std::string out;
    EXPECT_EQ(test::RunLucernaInfo(dir + "/info.pbrt", &out), 2) << out;
    EXPECT_TRUE(Contains(out, dir + "/info.pbrt:5:")) << out;
    EXPECT_TRUE(Contains(out, "cut.bsdf\": truncated tensor file")) << out;
}

TEST(Measured, FeatureSceneReadsWithNothingUnsupported) {
    std::string file = std::string(LUCERNA_SOURCE_DIR) + "/scenes/features/materials-measured.pbrt";
    std::string out;
    EXPECT_EQ(test::RunLucernaInfo(file, &out), 0) << out;
    EXPECT_TRUE(Contains(out, "unsupported: 0\n")) << out;
    EXPECT_TRUE(Contains(out, "measured 1")) << out;
    Diagnostics diag;
    diag.quiet = true;
    auto s = LoadScene(file, diag, BuildOptions{});
    SceneView v = s->View();
    uint32_t measured = 0;
    for (uint32_t i = 0; i < v.materials.size; ++i) measured += v.materials[i].kind == MaterialKind::Measured;
    EXPECT_EQ(measured, 1u);
    EXPECT_GT(v.measuredData.size, 100000u);
    // Two materials naming one file share its tables.
    std::string dir = test::TempDir("measured_shared");
    std::filesystem::copy_file(std::string(LUCERNA_SOURCE_DIR) + "/scenes/features/measured-tr-conductor.bsdf",
                               dir + "/a.bsdf", std::filesystem::copy_options::overwrite_existing);
    std::ofstream(dir + "/two.pbrt") << kHeader << "Material \"measured\" \"string filename\" \"a.bsdf\"\nShape \"sphere\"\n"
                                     << "Material \"measured\" \"string filename\" \"a.bsdf\"\nShape \"sphere\"\n";
    auto two = LoadScene(dir + "/two.pbrt", diag, BuildOptions{});
    EXPECT_EQ(two->View().measuredData.size, v.measuredData.size);
}

}  // namespace
}  // namespace lu
