// The sampler, camera and shape feature scenes (scenes/features/samplers-*.pbrt, cameras-*.pbrt,
// shapes-*.pbrt) build with nothing unsupported and no warnings and render finite, non-black
// images; a spherical or orthographic camera under a uniform white sky sees the sky's radiance in
// every pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "integrators/render_helpers.h"

namespace lu::test {
namespace {

std::vector<std::string> FeatureScenes() { return FeatureSceneFiles({"samplers-", "cameras-", "shapes-"}); }

}  // namespace

TEST(FeatureScenes, SamplersAndCamerasBuildCleanAndRender) {
    std::vector<std::string> files = FeatureScenes();
    ASSERT_EQ(files.size(), 6u);
    for (const std::string &file : files) {
        SCOPED_TRACE(file);
        auto scene = LoadCleanFeatureScene(file, 32, 32);   // the equal-area scene is square; forcing 32x32 keeps it so
        ExpectRendersFiniteAndLit(*scene);
    }
}

TEST(FeatureScenes, CamerasUnderAUniformSkySeeItEverywhere) {
    for (const char *camera : {"\"spherical\" \"string mapping\" [ \"equalarea\" ]",
                               "\"spherical\" \"string mapping\" [ \"equirectangular\" ]",
                               "\"orthographic\" \"float lensradius\" [ 0.2 ] \"float focaldistance\" [ 2 ]"}) {
        SCOPED_TRACE(camera);
        std::string text = std::string("Camera ") + camera +
                           "\nFilm \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
                           "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 0.5 0.5 0.5 ]\n";
        auto scene = LoadSceneText("uniform_sky_camera", text);
        auto r = RenderScene(*scene, 16, 5);
        // Every pixel sees the sky: its channel mean is 0.5 up to the spectral (wavelength) noise,
        // and each channel's image mean is 0.5; a black pixel (a ray that missed) would fail.
        double lo = 1e30, hi = -1e30, sum[3] = {0, 0, 0};
        const int n = r.image.width * r.image.height;
        for (int i = 0; i < n; ++i) {
            double m = 0;
            for (int c = 0; c < 3; ++c) {
                double v = r.image.pixels[size_t(r.image.channels * i + c)];
                m += v / 3;
                sum[c] += v / n;
            }
            lo = std::min(lo, m);
            hi = std::max(hi, m);
        }
        EXPECT_GT(lo, 0.35);
        EXPECT_LT(hi, 0.65);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], 0.5, 0.02) << "channel " << c;
    }
}

}  // namespace lu::test
