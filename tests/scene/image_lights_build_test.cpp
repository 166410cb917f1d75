// Scene-building tests of pbrt-v4's image lights (LightSource "projection", AreaLightSource
// "diffuse" with "filename"): bad input (both "L" and "filename", a missing image, an image
// without R, G and B, a NaN texel, a bad "fov", "power" of a black image) is an error at the
// parameter's FILE:LINE, exit 2 from the CLI; `lucerna info` lists both kinds.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "lucerna/image/image.h"
#include "lucerna/scene/builder.h"
#include "support/test_support.h"

namespace lu {
namespace {

bool Has(const std::string &s, const std::string &what) { return s.find(what) != std::string::npos; }

const char *kHeader = "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
                      "Camera \"perspective\"\nWorldBegin\n";
const char *kQuad = "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] \"integer indices\" [ 0 1 2  0 2 3 ]\n";

void Write(const std::string &path, const std::string &text) { std::ofstream(path, std::ios::binary) << text; }

std::string MakeImages(const std::string &name) {
    std::string dir = test::TempDir(name);
    WriteEXR(dir + "/rgb.exr", MakeImage(4, 2, 3, 0.5f));
    WriteEXR(dir + "/y.exr", MakeImage(4, 2, 1, 0.5f));
    WriteEXR(dir + "/black.exr", MakeImage(4, 2, 3, 0));
    Image nan = MakeImage(4, 2, 3, 0.5f);
    nan.At(2, 1, 1) = std::numeric_limits<float>::quiet_NaN();
    WriteEXR(dir + "/nan.exr", nan);
    return dir;
}

// The error of loading kHeader + world (the world's first line is line 4): its line and text.
std::string ErrorAt(const std::string &dir, const std::string &world, int line) {
    Write(dir + "/scene.pbrt", std::string(kHeader) + world);
    Diagnostics diag;
    diag.quiet = true;
    try {
        LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Loc().line, line) << e.Format();
        return e.Message();
    }
    ADD_FAILURE() << "no error for " << world;
    return "";
}

TEST(ImageLightErrors, BadImagesAreErrorsAtTheFilenameParameter) {
    std::string dir = MakeImages("image_light_errors");
    for (bool area : {false, true}) {
        SCOPED_TRACE(area ? "area" : "projection");
        // The directive on line 4 (area: line 5), "filename" on the line after it.
        std::string head = area ? "AttributeBegin\nAreaLightSource \"diffuse\"\n" : "LightSource \"projection\"\n";
        std::string tail = area ? std::string(kQuad) + "AttributeEnd\n" : "";
        int line = area ? 6 : 5;
        auto err = [&](const std::string &param) { return ErrorAt(dir, head + param + "\n" + tail, line); };
        EXPECT_TRUE(Has(err("\"string filename\" \"missing.exr\""), "missing.exr"));
        EXPECT_TRUE(Has(err("\"string filename\" \"y.exr\""), "must have R, G, and B channels"));
        EXPECT_TRUE(Has(err("\"string filename\" \"nan.exr\""), "not-a-number"));
        // "power" of a black image cannot be met: at "power" (the line after "filename").
        EXPECT_TRUE(Has(ErrorAt(dir, head + "\"string filename\" \"black.exr\"\n\"float power\" 10\n" + tail, line + 1),
                        "cannot be met"));
    }
    // Both "L" and "filename" (pbrt-v4 refuses it too).
    EXPECT_TRUE(Has(ErrorAt(dir, "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n  \"string filename\" \"rgb.exr\"\n" +
                                     std::string(kQuad) + "AttributeEnd\n", 6),
                    "both \"L\" and \"filename\""));
    // The projection light needs an image and an fov in (0, 180).
    EXPECT_TRUE(Has(ErrorAt(dir, "LightSource \"projection\"\n", 4), "must provide \"filename\""));
    EXPECT_TRUE(Has(ErrorAt(dir, "LightSource \"projection\" \"string filename\" \"rgb.exr\"\n  \"float fov\" 180\n", 5), "\"fov\""));
}

TEST(ImageLightErrors, CommandLineExitsTwoAndInfoListsTheLights) {
    std::string dir = MakeImages("image_light_cli");
    Write(dir + "/bad.pbrt", std::string(kHeader) + "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n"
                                                     "  \"string filename\" \"rgb.exr\"\n" + kQuad + "AttributeEnd\n");
    for (const char *cmd : {"info", "render"}) {
        std::vector<std::string> argv = {test::LucernaBinary(), cmd, dir + "/bad.pbrt"};
        if (std::string(cmd) == "render") argv.insert(argv.end(), {"-o", dir + "/bad.exr"});
        test::ProcessResult b = test::RunProcess(argv);
        EXPECT_EQ(b.exitCode, 2) << b.output;
        EXPECT_TRUE(Has(b.output, dir + "/bad.pbrt:6:")) << b.output;
        EXPECT_TRUE(Has(b.output, "both \"L\" and \"filename\"")) << b.output;
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.exr"));
    Write(dir + "/scene.pbrt", std::string(kHeader) + "LightSource \"projection\" \"string filename\" \"rgb.exr\"\n"
                                                       "AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"rgb.exr\"\n" +
                                   kQuad + "AttributeEnd\n");
    test::ProcessResult r = test::RunProcess({test::LucernaBinary(), "info", dir + "/scene.pbrt"});
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(Has(r.output, "lights: 3 (diffuse area (image) 2, projection 1)")) << r.output;
    EXPECT_TRUE(Has(r.output, "unsupported: 0\n")) << r.output;
}

}  // namespace
}  // namespace lu
