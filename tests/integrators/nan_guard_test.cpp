// Lucerna: the NaN/Inf guard. Deliberately broken materials, lights and radiance values must never
// reach the film: their samples are rejected, counted, and the first one is reported in words
// (cause, value, and the scene entity with its file:line).
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/render_helpers.h"
#include "lucerna/render/rejected_sample.h"

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
    EXPECT_GE(r.stats.firstRejected.x, 0);
    EXPECT_GE(r.stats.firstRejected.y, 0);
    EXPECT_GE(r.stats.firstRejected.depth, 1);
    // The uniform infinite light is not sampled by NEE (pbrt-v4's allowIncompletePDF): the NaN
    // enters the path's throughput when the sphere's BSDF is sampled.
    EXPECT_EQ(r.stats.firstRejected.cause, RejectCause::Scatter);
    EXPECT_EQ(r.stats.firstRejected.badValue, BadValue::NaN);
    EXPECT_EQ(r.stats.firstRejected.entity, 0u);
    std::string words = DescribeRejectedSample(*scene, r.stats.firstRejected);
    EXPECT_NE(words.find("NaN in the path throughput after sampling the BSDF of Material \"diffuse\" at "),
              std::string::npos) << words;
    EXPECT_NE(words.find("scene.pbrt:6:1"), std::string::npos) << words;
    for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v));
    // The corner sees only the environment (radiance 1).
    EXPECT_NEAR(r.image.At(0, 0, 1), 1.0f, 0.02f);
}

// A camera inside an emitting sphere: every camera ray hits the light first.
std::unique_ptr<HostScene> InsideEmitter(const char *name) {
    return LoadSceneText(name,
        "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
        "WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"bool twosided\" true\n"
        "Shape \"sphere\" \"float radius\" [ 2 ]\nAttributeEnd\n");
}

TEST(NanGuard, EmitterWithNaNRadianceIsNamed) {
    auto scene = InsideEmitter("nanguard_emit");
    ASSERT_EQ(scene->lights.size(), 1u);
    scene->lights[0].scale = std::nanf("");
    auto r = RenderScene(*scene, 2, 5);
    EXPECT_EQ(r.stats.rejected, uint64_t(8 * 8 * 2));
    const RejectedSample &f = r.stats.firstRejected;
    EXPECT_EQ(f.x, 0);
    EXPECT_EQ(f.y, 0);
    EXPECT_EQ(f.depth, 0);
    EXPECT_EQ(f.cause, RejectCause::Emission);
    EXPECT_EQ(f.badValue, BadValue::NaN);
    std::string words = DescribeRejectedSample(*scene, f);
    EXPECT_NE(words.find("NaN in the radiance emitted by AreaLightSource \"diffuse\" on Shape \"sphere\" at "),
              std::string::npos) << words;
    EXPECT_NE(words.find("scene.pbrt:7:1"), std::string::npos) << words;   // the Shape
}

TEST(NanGuard, NegativeRadianceIsRejectedAndNamed) {
    auto scene = InsideEmitter("nanguard_negative");
    scene->lights[0].scale = -1;
    auto r = RenderScene(*scene, 1, 5);
    EXPECT_EQ(r.stats.rejected, uint64_t(8 * 8));
    EXPECT_EQ(r.stats.firstRejected.cause, RejectCause::Emission);
    EXPECT_EQ(r.stats.firstRejected.badValue, BadValue::Negative);
    for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v) && v == 0);
}

TEST(NanGuard, FilmOverflowIsTheFilmsCause) {
    // Finite radiance whose XYZ overflows at the film: no contribution is bad, the film value is.
    auto scene = InsideEmitter("nanguard_overflow");
    scene->lights[0].scale = 1e38f;
    auto r = RenderScene(*scene, 1, 1);
    EXPECT_GT(r.stats.rejected, 0u);
    EXPECT_EQ(r.stats.firstRejected.cause, RejectCause::Film);
    EXPECT_EQ(r.stats.firstRejected.badValue, BadValue::Infinite);
    EXPECT_NE(DescribeRejectedSample(*scene, r.stats.firstRejected).find("at the film"), std::string::npos);
}

TEST(RejectedSampleKey, RoundTripsAndOrdersByPixelThenDepth) {
    for (RejectCause c : {RejectCause::Emission, RejectCause::Direct, RejectCause::Scatter, RejectCause::Medium,
                          RejectCause::Film})
        for (BadValue v : {BadValue::NaN, BadValue::Infinite, BadValue::Negative})
            for (uint32_t e : {0u, 7u, RejectedNoEntity - 1, NoIndex}) {
                RejectedSample r = DecodeRejectedSampleKey(RejectedSampleKey(1919, 1079, 1920, 17, c, v, e), 1920);
                EXPECT_EQ(r.x, 1919);
                EXPECT_EQ(r.y, 1079);
                EXPECT_EQ(r.depth, 17);
                EXPECT_EQ(r.cause, c);
                EXPECT_EQ(r.badValue, v);
                EXPECT_EQ(r.entity, e);
            }
    // Entities past the key's range are reported as unidentified, not as another entity.
    EXPECT_EQ(DecodeRejectedSampleKey(RejectedSampleKey(0, 0, 4, 1, RejectCause::Emission, BadValue::NaN, 1u << 22), 4).entity,
              NoIndex);
    // Pixel first, then depth, whatever the cause and entity.
    EXPECT_LT(RejectedSampleKey(3, 0, 4, 9, RejectCause::Film, BadValue::Negative, NoIndex),
              RejectedSampleKey(0, 1, 4, 0, RejectCause::Emission, BadValue::NaN, 0));
    EXPECT_LT(RejectedSampleKey(2, 2, 4, 1, RejectCause::Medium, BadValue::Negative, NoIndex),
              RejectedSampleKey(2, 2, 4, 2, RejectCause::Emission, BadValue::NaN, 0));
    EXPECT_FALSE(DecodeRejectedSampleKey(~0ull, 4).Valid());
}

}  // namespace lu::test
