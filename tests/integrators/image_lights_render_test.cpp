// Renders with pbrt-v4's image lights: an image area light seen by camera rays shows each texel
// in its corner of the quad (the orientation of pbrt-v4's (u, 1 - v) lookup); a diffuse floor lit
// by it renders the same with light sampling only, BSDF sampling only and MIS (block means within
// their standard errors: NEE and emitter hits must evaluate the same radiance); a projection
// the feature scenes lights-*.pbrt build cleanly and render.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "integrators/render_helpers.h"

namespace lu::test {
namespace {

const float kTexels[2][2][3] = {{{0.9f, 0.1f, 0.1f}, {0.1f, 0.8f, 0.1f}},    // top row: red, green
                                {{0.1f, 0.1f, 0.7f}, {0.6f, 0.6f, 0.2f}}};   // bottom row: blue, yellow

std::string WriteQuadImage(const std::string &name) {
    std::string dir = TempDir(name);
    Image img = MakeImage(2, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c) img.At(x, y, c) = kTexels[y][x][c];
    WriteEXR(dir + "/quad.exr", img);
    return dir;
}

std::unique_ptr<HostScene> LoadIn(const std::string &dir, const std::string &text) {
    std::ofstream(dir + "/scene.pbrt") << text;
    Diagnostics diag;
    diag.quiet = true;
    return LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
}

// The 2 x 2 quad in z = 0, uv (0, 0) at (-1, -1) and (1, 1) at (1, 1).
const char *kQuad = "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] \"integer indices\" [ 0 1 2  0 2 3 ]\n"
                    "  \"point2 uv\" [ 0 0  1 0  1 1  0 1 ]\n";

TEST(ImageAreaLightRender, CameraSeesEachTexelInItsCorner) {
    std::string dir = WriteQuadImage("image_area_camera");
    // From -z looking at +z (pbrt-v4's left-handed camera: raster right is world +x, up is +y);
    // the quad exactly fills the film; two-sided, so the camera sees the side facing -z.
    auto s = LoadIn(dir, "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"orthographic\" \"float screenwindow\" [ -1 1 -1 1 ]\n"
                         "Sampler \"independent\" \"integer pixelsamples\" 64\nPixelFilter \"box\"\n"
                         "Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16 \"string filename\" \"x.exr\"\n"
                         "WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"quad.exr\" \"bool twosided\" true\n" +
                             std::string(kQuad) + "AttributeEnd\n");
    auto r = RenderScene(*s, 64, 1);
    // The outer 4 x 4 pixel corners lie where the bilinear lookup clamps to one texel: raster
    // top-left is the quad's (-1, 1), uv (0, 1), image (s, t) = (0, 0): the image's top-left texel.
    for (int ty = 0; ty < 2; ++ty)
        for (int tx = 0; tx < 2; ++tx)
            for (int c = 0; c < 3; ++c) {
                int x0 = tx ? 12 : 0, y0 = ty ? 12 : 0;
                MeanSE m = RegionMean(r.image, c, x0, y0, x0 + 4, y0 + 4);
                std::printf("corner (%d, %d) channel %d: %.4f +- %.4f, texel %.2f\n", tx, ty, c, m.mean, m.se, kTexels[ty][tx][c]);
                EXPECT_NEAR(m.mean, kTexels[ty][tx][c], 0.02 + 4 * m.se) << tx << " " << ty << " " << c;
            }
    // The middle: the four texels' average (bilinear at the center).
    for (int c = 0; c < 3; ++c) {
        double avg = (kTexels[0][0][c] + kTexels[0][1][c] + kTexels[1][0][c] + kTexels[1][1][c]) / 4;
        MeanSE m = RegionMean(r.image, c, 7, 7, 9, 9);
        EXPECT_NEAR(m.mean, avg, 0.03 + 4 * m.se) << c;
    }
}

// A diffuse floor (z = 0) just under the image quad, scaled to 1.2 x 1.2 and lifted to z = 0.3
// (two-sided), seen obliquely: each part of the floor is lit mostly by the nearest texels.
std::string FloorScene() {
    return "LookAt 0 -3.5 3  0 0 0.3  0 0 1\nCamera \"perspective\" \"float fov\" 50\n"
           "Film \"rgb\" \"integer xresolution\" 24 \"integer yresolution\" 24 \"string filename\" \"x.exr\"\n"
           "WorldBegin\n"
           "Material \"diffuse\" \"rgb reflectance\" [ 0.7 0.7 0.7 ]\n"
           "Shape \"trianglemesh\" \"point3 P\" [ -3 -3 0  3 -3 0  3 3 0  -3 3 0 ] \"integer indices\" [ 0 1 2  0 2 3 ]\n"
           "AttributeBegin\nTranslate 0 0 0.3\nScale 0.6 0.6 0.6\n"
           "AreaLightSource \"diffuse\" \"string filename\" \"quad.exr\" \"bool twosided\" true \"float scale\" 3\n" +
           std::string(kQuad) + "AttributeEnd\n";
}

TEST(ImageAreaLightRender, LightSamplingBSDFSamplingAndMISAgree) {
    std::string dir = WriteQuadImage("image_area_mis");
    auto s = LoadIn(dir, FloorScene());
    // Per strategy, kSeeds independent renders (direct lighting only); a block's mean over them
    // and its standard error from their spread.
    const int kSeeds = 16;
    const char *names[3] = {"MIS", "NEE only", "BSDF only"};
    std::vector<double> blocks[3][kSeeds];
    for (int k = 0; k < 3; ++k)
        for (int seed = 0; seed < kSeeds; ++seed) {
            RenderResultForTest r = RenderScene(*s, k == 2 ? 256 : 64, 1, uint32_t(100 * k + seed), 0, k);
            EXPECT_EQ(r.stats.rejected, 0u) << names[k];
            for (int by = 0; by < 6; ++by)
                for (int bx = 0; bx < 6; ++bx)
                    for (int c = 0; c < 3; ++c)
                        blocks[k][seed].push_back(RegionMean(r.image, c, 4 * bx, 4 * by, 4 * bx + 4, 4 * by + 4).mean);
        }
    // 6 x 6 blocks of 4 x 4 pixels, 3 channels, 3 pairs: 324 comparisons at 6 standard errors (a t
    // statistic of about 30 degrees of freedom: about 1e-6 each, false alarm well below 1%).
    int compared = 0;
    double worst = 0;
    for (int by = 0; by < 6; ++by)
        for (int bx = 0; bx < 6; ++bx)
            for (int c = 0; c < 3; ++c) {
                MeanSE m[3];
                size_t i = size_t((by * 6 + bx) * 3 + c);
                for (int k = 0; k < 3; ++k) {
                    double sum = 0, sum2 = 0;
                    for (int seed = 0; seed < kSeeds; ++seed) {
                        sum += blocks[k][seed][i];
                        sum2 += blocks[k][seed][i] * blocks[k][seed][i];
                    }
                    m[k].mean = sum / kSeeds;
                    m[k].se = std::sqrt(std::max(0.0, sum2 / kSeeds - m[k].mean * m[k].mean) / (kSeeds - 1));
                }
                for (int a = 0; a < 3; ++a)
                    for (int b = a + 1; b < 3; ++b) {
                        double se = std::sqrt(m[a].se * m[a].se + m[b].se * m[b].se) + 1e-5;
                        double z = std::abs(m[a].mean - m[b].mean) / se;
                        worst = std::max(worst, z);
                        EXPECT_LT(z, 6) << names[a] << " vs " << names[b] << " block " << bx << "," << by << " channel " << c
                                        << ": " << m[a].mean << " vs " << m[b].mean;
                        ++compared;
                    }
            }
    std::printf("NEE / BSDF / MIS: %d block comparisons, worst %.2f standard errors\n", compared, worst);
}

}  // namespace

TEST(FeatureScenes, LightsBuildCleanAndRender) {
    std::vector<std::string> files = FeatureSceneFiles({"lights-"});
    ASSERT_EQ(files.size(), 2u);
    for (const std::string &file : files) {
        SCOPED_TRACE(file);
        auto scene = LoadCleanFeatureScene(file, 32, 24);
        ExpectRendersFiniteAndLit(*scene);
    }
}

}  // namespace lu::test
