// Tests of `lucerna info`: the SceneSummary report, and the command's output and exit codes (the
// test_scene target depends on the lucerna target, so the binary is there; without it, a failure).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <zlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "lucerna/image/image.h"
#include "lucerna/scene/builder.h"
#include "lucerna/spectra/registry.h"
#include "support/test_support.h"

namespace lu {
namespace {

bool Contains(const std::string &s, const std::string &what) { return s.find(what) != std::string::npos; }

TEST(SceneSummary, ReportsWhatWasRead) {
    Diagnostics diag;
    diag.quiet = true;
    auto s = LoadScene(test::SharedPath("scenes/bitterli-veach-bidir/scene-v4.pbrt"), diag, BuildOptions{});
    std::string r = SceneSummary(*s, diag);
    EXPECT_TRUE(Contains(r, "resolution: 1024 x 1024")) << r;
    EXPECT_TRUE(Contains(r, "camera: perspective, fov 35 deg")) << r;
    EXPECT_TRUE(Contains(r, "integrator: bdpt -> path, maxdepth 7")) << r;
    EXPECT_TRUE(Contains(r, "sampler: independent, 64 spp")) << r;
    EXPECT_TRUE(Contains(r, "shapes: 14 (plymesh 12, trianglemesh 2)")) << r;
    EXPECT_TRUE(Contains(r, "triangles: 11544")) << r;
    EXPECT_TRUE(Contains(r, "lights: 4 (diffuse area 4)")) << r;
    EXPECT_TRUE(Contains(r, "materials: 4 (conductor 1, dielectric 1, diffuse 2)")) << r;
    EXPECT_TRUE(Contains(r, "bounds: (")) << r;
    EXPECT_TRUE(Contains(r, "unsupported: 1\n  Integrator \"bdpt\"")) << r;
    // Every warning is listed.
    EXPECT_TRUE(Contains(r, "warnings: " + std::to_string(diag.warnings.size()))) << r;
    for (const std::string &w : diag.warnings) EXPECT_TRUE(Contains(r, w));
}

TEST(InfoCommand, ExitCodesAndOutput) {
    const std::string binary = std::string(LUCERNA_BINARY_DIR) + "/lucerna";
    ASSERT_TRUE(std::filesystem::exists(binary)) << binary << " is missing (test_scene depends on the lucerna target)";
    std::string out;
    EXPECT_EQ(test::RunLucernaInfo(test::SharedPath("scenes/bitterli-cornell-box/scene-v4.pbrt"), &out), 0) << out;
    EXPECT_TRUE(Contains(out, "resolution: 1024 x 1024")) << out;
    EXPECT_TRUE(Contains(out, "triangles: 36")) << out;
    EXPECT_TRUE(Contains(out, "lights: 2 (diffuse area 2)")) << out;

    std::string dir = test::TempDir("info_cmd");
    std::ofstream(dir + "/bad.pbrt") << "Film \"rgb\"\nCamera \"perspective\" \"float fov\" [ 180 ]\nWorldBegin\n";
    std::string err;
    EXPECT_EQ(test::RunLucernaInfo(dir + "/bad.pbrt", &err), 2) << err;
    EXPECT_TRUE(Contains(err, "bad.pbrt:2:")) << err;
    EXPECT_TRUE(Contains(err, "error:")) << err;
    EXPECT_TRUE(Contains(err, "fov")) << err;
    // An error in an included file says where it was included from.
    std::ofstream(dir + "/top.pbrt") << "\nInclude \"bad.pbrt\"\n";
    std::string chained;
    EXPECT_EQ(test::RunLucernaInfo(dir + "/top.pbrt", &chained), 2) << chained;
    EXPECT_TRUE(Contains(chained, "In file included from " + dir + "/top.pbrt:2:1:\n" + dir + "/bad.pbrt:2:")) << chained;

    // Every unsupported feature at once, each at its file:line, the included one with its chain;
    // `lucerna render` refuses the scene with the same list.
    std::ofstream(dir + "/lights.pbrt") << "# included\nLightSource \"infinite\" \"point3 portal\" [ 0 0 0  1 0 0  1 1 0  0 1 0 ]\n";
    std::ofstream(dir + "/lens.dat") << "0 4 1 14\n50 5 1.5 20\n-50 48 1 20\n";
    std::ofstream(dir + "/many.pbrt") << "Camera \"realistic\" \"string aperture\" \"pentagon\" \"string lensfile\" \"lens.dat\"\nFilm \"rgb\" \"integer xresolution\" [ 8 ] "
                                         "\"integer yresolution\" [ 8 ]\nWorldBegin\nMaterial \"subsurface\"\n"
                                         "Shape \"sphere\"\nInclude \"lights.pbrt\"\nShape \"bilinearmesh\" \"point3 P\" "
                                         "[ 0 0 0 1 0 0 0 1 0 1 1 1 ] \"string emissionfilename\" \"e.png\"\n";
    for (const char *command : {"info", "render"}) {
        SCOPED_TRACE(command);
        std::string many;
        std::string cmd = std::string(LUCERNA_BINARY_DIR) + "/lucerna " + command + " '" + dir + "/many.pbrt' -o '" +
                          dir + "/many.exr' 2>&1";
        if (std::string(command) == "info") cmd = std::string(LUCERNA_BINARY_DIR) + "/lucerna info '" + dir + "/many.pbrt' 2>&1";
        FILE *p = popen(cmd.c_str(), "r");
        ASSERT_TRUE(p);
        char buf[4096];
        size_t n;
        while ((n = fread(buf, 1, sizeof buf, p)) > 0) many.append(buf, n);
        int status = pclose(p);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << many;
        EXPECT_TRUE(Contains(many, dir + "/many.pbrt:1:20: error: Camera \"realistic\" \"aperture\" \"pentagon\" is not supported")) << many;
        EXPECT_TRUE(Contains(many, dir + "/many.pbrt:4:1: error: Material type \"subsurface\" is not supported")) << many;
        EXPECT_TRUE(Contains(many, dir + "/many.pbrt:7:")) << many;
        EXPECT_TRUE(Contains(many, "error: bilinearmesh \"emissionfilename\" (textured emission) is not supported")) << many;
        EXPECT_TRUE(Contains(many, "In file included from " + dir + "/many.pbrt:6:1:\n" + dir + "/lights.pbrt:2:")) << many;
        EXPECT_TRUE(Contains(many, "error: infinite light \"portal\" is not supported")) << many;
        EXPECT_FALSE(std::filesystem::exists(dir + "/many.exr"));
    }

    std::string media;
    EXPECT_EQ(test::RunLucernaInfo(test::SharedPath("scenes/bitterli-volumetric-caustic/scene-v4.pbrt"), &media), 0) << media;
    EXPECT_TRUE(Contains(media, "media: 1 (homogeneous 1)")) << media;

    // A gzip-compressed scene reads as the plain one; a truncated one is exit 2 at the file.
    std::string text, gz = dir + "/cb.pbrt.gz", cut = dir + "/cut.pbrt.gz";
    {
        std::ifstream in(test::SharedPath("scenes/bitterli-cornell-box/scene-v4.pbrt"), std::ios::binary);
        text.assign(std::istreambuf_iterator<char>(in), {});
        gzFile f = gzopen(gz.c_str(), "wb");
        ASSERT_TRUE(f);
        ASSERT_EQ(gzwrite(f, text.data(), unsigned(text.size())), int(text.size()));
        gzclose(f);
        std::ifstream zin(gz, std::ios::binary);
        std::string bytes(std::istreambuf_iterator<char>(zin), {});
        std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    }
    std::string zipped;
    EXPECT_EQ(test::RunLucernaInfo(gz, &zipped), 0) << zipped;
    EXPECT_TRUE(Contains(zipped, "triangles: 36")) << zipped;
    std::string truncated;
    EXPECT_EQ(test::RunLucernaInfo(cut, &truncated), 2) << truncated;
    EXPECT_TRUE(Contains(truncated, cut + ": error: truncated gzip data")) << truncated;
}

// The film's color space: `lucerna info` names it, and the EXR carries its chromaticities
// (pbrt-v4 writes them for every space but sRGB, whose files have none).
TEST(InfoCommand, FilmColorSpaceInInfoAndExrHeader) {
    std::string dir = test::TempDir("info_colorspace");
    for (const char *space : {"dci-p3", "srgb"}) {
        SCOPED_TRACE(space);
        std::string scene = dir + "/" + space + ".pbrt";
        std::ofstream(scene) << "ColorSpace \"" << space << "\"\nFilm \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\n"
                             << "Camera \"perspective\"\nWorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n";
        std::string out;
        EXPECT_EQ(test::RunLucernaInfo(scene, &out), 0) << out;
        EXPECT_TRUE(Contains(out, std::string("color space: ") + space)) << out;
        std::string exr = dir + "/" + space + ".exr";
        test::ProcessResult r = test::RunProcess({test::LucernaBinary(), "render", scene, "-o", exr, "--spp", "16"});
        ASSERT_EQ(r.exitCode, 0) << r.output;
        Image img = ReadImage(exr);
        if (std::string(space) == "srgb") {
            EXPECT_FALSE(img.hasChromaticities);
            continue;
        }
        ASSERT_TRUE(img.hasChromaticities);
        const RGBColorSpace &cs = GetRGBColorSpace(ColorSpaceId::DCI_P3);
        const double want[8] = {0.68, 0.32, 0.265, 0.690, 0.15, 0.06, cs.w[0], cs.w[1]};
        for (int i = 0; i < 8; ++i) EXPECT_NEAR(img.chromaticities[i], want[i], 1e-6) << i;
        EXPECT_NEAR(cs.w[0], 0.3127, 2e-4);  // D65
        // The sky is the film's white: (1, 1, 1) in DCI-P3 (mean over the 16 pixels).
        for (int c = 0; c < 3; ++c) {
            double m = 0;
            for (int y = 0; y < 4; ++y)
                for (int x = 0; x < 4; ++x) m += img.At(x, y, c) / 16;
            EXPECT_NEAR(m, 1.0, 0.05) << c;
        }
    }
}

}  // namespace
}  // namespace lu
