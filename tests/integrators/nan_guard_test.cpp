// Lucerna: the NaN/Inf guard. A deliberately broken material (NaN reflectance) must never reach
// the film: its samples are rejected, counted, and the first offender is reported.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/render_helpers.h"

namespace lu::test {

TEST(NanGuard, BrokenMaterialIsCaughtAndCounted) {
    auto scene = LoadSceneText("nanguard",
        "LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]\n"
        "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\nShape \"sphere\" \"float radius\" [ 0.5 ]\n");
    ASSERT_EQ(scene->materials.size(), 1u);
    scene->materials[0].reflectance.kind = TextureKind::Constant;
    scene->materials[0].reflectance.value = Spectrum::Const(std::nanf(""));
    auto r = RenderScene(*scene, 4, 5);
    EXPECT_GT(r.stats.rejected, 0u);
    // Only the pixels that see the sphere are affected; background pixels stay valid.
    EXPECT_LT(r.stats.rejected, uint64_t(24 * 24 * 4));
    EXPECT_GE(r.stats.firstRejectedX, 0);
    EXPECT_GE(r.stats.firstRejectedY, 0);
    EXPECT_GE(r.stats.firstRejectedDepth, 1);
    for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v));
    // The corner sees only the environment (radiance 1).
    EXPECT_NEAR(r.image.At(0, 0, 1), 1.0f, 0.02f);
}

}  // namespace lu::test
