// Lucerna: the render settings (scene/render_settings.h) and the sampler the builder makes: every
// setting reads back what was set, bad values are refused with the setting's name, the scene's
// Integrator/Sampler directives set them, the hash follows exactly the settings that change the
// image, and the Sampler directive's options reach the render.
#include <gtest/gtest.h>

#include <cstring>

#include "integrators/render_helpers.h"
#include "lucerna/scene/render_settings.h"

namespace lu::test {

TEST(RenderSettings, EverySettingRoundTripsThroughItsText) {
    RenderSettings s;
    const std::pair<const char *, const char *> values[] = {
        {"integrator", "regpath"}, {"maxdepth", "17"},   {"light-strategy", "nee"}, {"reg-radius", "0.25"},
        {"reg-lambda", "0.2"},     {"reg-angle", "3.5"}, {"reg-footprint", "2.5"}, {"mnee", "false"},         {"beam-segments", "false"}, {"near-specular", "false"}, {"seed", "4000000000"},
        {"spp", "300"},
        {"time", "12.5"},          {"threads", "3"},     {"device", "cpu"},         {"tracer", "bvh"},
        {"progress", "false"}};
    ASSERT_EQ(std::size(values), RenderSettingInfos().size()) << "a setting without a round-trip check";
    for (auto [name, value] : values) {
        std::string error;
        EXPECT_TRUE(SetRenderSetting(s, name, value, &error)) << name << ": " << error;
        EXPECT_EQ(RenderSettingValue(s, name), value) << name;
    }
    EXPECT_EQ(s.integrator, IntegratorKind::RegPath);
    EXPECT_EQ(s.maxDepth, 17);
    EXPECT_EQ(s.lightStrategy, LightStrategy::NEEOnly);
    EXPECT_DOUBLE_EQ(s.regRadius, 0.25);
    EXPECT_EQ(s.seed, 4000000000u);
    EXPECT_EQ(s.cpuTracer, CpuTracer::BVH);
    EXPECT_FALSE(s.progress);
    EXPECT_NE(DescribeRenderSettings(s).find("reg-radius 0.25"), std::string::npos) << DescribeRenderSettings(s);
}

TEST(RenderSettings, BadValuesAreRefusedByName) {
    const std::pair<const char *, const char *> bad[] = {
        {"reg-radius", "-1"}, {"reg-radius", "0"},  {"reg-lambda", "-0.1"}, {"reg-angle", "0"},   {"maxdepth", "-2"},
        {"maxdepth", "5x"},   {"spp", "0"},         {"spp", "1e3"},         {"time", "-1"},       {"time", "inf"},
        {"seed", "-1"},       {"integrator", "bdpt"}, {"device", "gpu"},    {"progress", "yes"},  {"threads", ""},
        {"nosuch", "1"}};
    for (auto [name, value] : bad) {
        RenderSettings s;
        std::string before = DescribeRenderSettings(s), error;
        EXPECT_FALSE(SetRenderSetting(s, name, value, &error)) << name << " " << value;
        EXPECT_NE(error.find(name), std::string::npos) << error;
        EXPECT_EQ(DescribeRenderSettings(s), before) << "a refused value changed the settings";
    }
}

TEST(RenderSettings, HashFollowsTheImageSettingsOnly) {
    RenderSettings a;
    uint64_t h = HashRenderSettings(a);
    for (const SettingInfo &info : RenderSettingInfos()) {
        RenderSettings b;
        std::string v = RenderSettingValue(b, info.name), w;
        // Another valid value of each setting.
        if (std::string(info.name) == "integrator") w = "regpath";
        else if (std::string(info.name) == "light-strategy") w = "bsdf";
        else if (std::string(info.name) == "device") w = "cuda";
        else if (std::string(info.name) == "tracer") w = "bvh";
        else if (std::string(info.name) == "progress" || std::string(info.name) == "mnee" ||
                 std::string(info.name) == "beam-segments" || std::string(info.name) == "near-specular")
            w = "false";
        else if (std::string(info.name) == "reg-lambda") w = "0.5";
        else w = "7";
        std::string error;
        ASSERT_TRUE(SetRenderSetting(b, info.name, w, &error)) << error;
        EXPECT_EQ(HashRenderSettings(b) != h, info.affectsImage) << info.name;
    }
}

TEST(RenderSettings, ReadFromTheScene) {
    auto scene = LoadSceneText("settings_scene",
        "Integrator \"regpath\" \"integer maxdepth\" 7 \"float radius\" 0.3 \"float lambda\" 0.2 \"float angle\" 4\n"
        "Sampler \"paddedsobol\" \"integer pixelsamples\" 8 \"integer seed\" 12\nWorldBegin\n"
        "Shape \"sphere\"\n");
    const RenderSettings &s = scene->settings;
    EXPECT_EQ(s.integrator, IntegratorKind::RegPath);
    EXPECT_EQ(s.maxDepth, 7);
    EXPECT_DOUBLE_EQ(s.regRadius, 0.3);
    EXPECT_DOUBLE_EQ(s.regLambda, 0.2);
    EXPECT_DOUBLE_EQ(s.regAngle, 4);
    EXPECT_EQ(s.spp, 8);
    EXPECT_EQ(s.seed, 12u);
    EXPECT_EQ(scene->sampler.kind, SamplerKind::PaddedSobol);
    EXPECT_EQ(scene->sampler.samplesPerPixel, 8);
    // No radius given: r0 = 0.04 x the bounding-box diagonal (a unit sphere: 0.04 x 2 sqrt 3).
    auto d = LoadSceneText("settings_default", "Integrator \"regpath\"\nWorldBegin\nShape \"sphere\"\n");
    EXPECT_NEAR(d->settings.ResolvedRegRadius(), 0.04 * 2 * std::sqrt(3.0), 1e-6);
    // ... and the footprint kernels of 16 pixels; a given radius turns them off, a given footprint
    // keeps them.
    EXPECT_DOUBLE_EQ(d->settings.ResolvedRegFootprint(), RenderSettings::kDefaultRegFootprint);
    EXPECT_DOUBLE_EQ(s.ResolvedRegFootprint(), 0);
    auto f = LoadSceneText("settings_footprint",
                           "Integrator \"regpath\" \"float radius\" 0.3 \"float footprint\" 4\nWorldBegin\nShape \"sphere\"\n");
    EXPECT_DOUBLE_EQ(f->settings.ResolvedRegFootprint(), 4);
    EXPECT_DOUBLE_EQ(f->settings.ResolvedRegRadius(), 0.3);
    // The techniques regpath adds, off from the scene.
    EXPECT_TRUE(d->settings.mnee);
    EXPECT_TRUE(d->settings.nearSpecular);
    auto t = LoadSceneText("settings_techniques",
                           "Integrator \"regpath\" \"bool mnee\" false \"bool near-specular\" false\nWorldBegin\nShape \"sphere\"\n");
    EXPECT_FALSE(t->settings.mnee);
    EXPECT_FALSE(t->settings.nearSpecular);
    // Bad values in the scene are located errors.
    for (const char *bad : {"Integrator \"regpath\" \"float radius\" -1\nWorldBegin\n",
                            "Integrator \"regpath\" \"float lambda\" 2\nWorldBegin\n",
                            "Integrator \"regpath\" \"float angle\" 0\nWorldBegin\n",
                            "Integrator \"regpath\" \"float footprint\" -2\nWorldBegin\n",
                            "Sampler \"zsobol\" \"string randomization\" \"bogus\"\nWorldBegin\n"}) {
        EXPECT_THROW(LoadSceneText("settings_bad", bad), SceneError) << bad;
    }
}

// The Sampler directive's options change the samples: randomization "none" and jitter false are
// not dropped on the way to the render.
TEST(RenderSettings, SamplerOptionsReachTheRender) {
    auto render = [](const std::string &sampler) {
        auto scene = LoadSceneText("sampler_options",
            "LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\"\n"
            "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n" + sampler +
            "\nWorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
            "Material \"diffuse\"\nShape \"sphere\"\n");
        return RenderScene(*scene, TestSettings(*scene, 2, 3, 5)).image;
    };
    auto differs = [](const Image &a, const Image &b) {
        return std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) != 0;
    };
    Image owen = render("Sampler \"zsobol\" \"integer pixelsamples\" 4");
    Image none = render("Sampler \"zsobol\" \"integer pixelsamples\" 4 \"string randomization\" \"none\"");
    Image owen2 = render("Sampler \"zsobol\" \"integer pixelsamples\" 4 \"string randomization\" \"fastowen\"");
    EXPECT_TRUE(differs(owen, none));
    EXPECT_FALSE(differs(owen, owen2));   // fastowen is the default
    Image jitter = render("Sampler \"stratified\" \"integer xsamples\" 2 \"integer ysamples\" 2");
    Image fixed = render("Sampler \"stratified\" \"integer xsamples\" 2 \"integer ysamples\" 2 \"bool jitter\" false");
    EXPECT_TRUE(differs(jitter, fixed));
    auto scene = LoadSceneText("sampler_jitter", "Sampler \"stratified\" \"bool jitter\" false\nWorldBegin\n");
    EXPECT_FALSE(scene->sampler.jitter);
    auto n = LoadSceneText("sampler_none", "Sampler \"zsobol\" \"string randomization\" \"none\"\nWorldBegin\n");
    EXPECT_EQ(n->sampler.randomize, RandomizeStrategy::None);
}

}  // namespace lu::test
