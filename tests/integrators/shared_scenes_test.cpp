// Lucerna: every scene file of the one list (support/shared_scenes.h, data/scenes/README.md) that Lucerna renders (no error, no NaN pixel,
// no rejected sample), and the diffuse-only cornell-box renders bit-identically with path and
// regpath for the same seed (regularization is selective: it costs nothing without specular
// surfaces).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "integrators/render_helpers.h"
#include "support/shared_scenes.h"

namespace lu::test {

class SharedSceneRender : public ::testing::TestWithParam<SharedScene> {};

TEST_P(SharedSceneRender, RendersWithoutNaN) {
    BuildOptions opts;
    opts.resX = 32;
    opts.resY = 32;
    Diagnostics diag;
    diag.quiet = true;
    auto scene = LoadScene(SharedPath(GetParam().scene), diag, opts);
    for (bool reg : {false, true}) {
        auto r = RenderScene(*scene, 2, scene->settings.maxDepth, 1, 0, 0, reg, 0.05, 0.03);
        EXPECT_EQ(r.stats.rejected, 0u) << (reg ? "regpath" : "path");
        double sum = 0;
        for (float v : r.image.pixels) {
            ASSERT_TRUE(std::isfinite(v));
            sum += v;
        }
        EXPECT_GT(sum, 0) << "a black image";
    }
}

INSTANTIATE_TEST_SUITE_P(All, SharedSceneRender, ::testing::ValuesIn(RenderedSharedScenes()),
                         [](const auto &info) { return SharedSceneTestName(info.param); });

TEST(SharedScenes, CornellBoxPathAndRegpathBitIdentical) {
    BuildOptions opts;
    opts.resX = 48;
    opts.resY = 48;
    Diagnostics diag;
    diag.quiet = true;
    auto scene = LoadScene(SharedPath("scenes/bitterli-cornell-box/scene-v4.pbrt"), diag, opts);
    auto a = RenderScene(*scene, 4, scene->settings.maxDepth, 21, 0, 0, false);
    auto b = RenderScene(*scene, 4, scene->settings.maxDepth, 21, 0, 0, true, 0.07, 0.03);
    EXPECT_EQ(b.stats.regConnections, 0u);
    EXPECT_EQ(a.stats.rays, b.stats.rays);
    ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
    EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(float)));
}

}  // namespace lu::test
