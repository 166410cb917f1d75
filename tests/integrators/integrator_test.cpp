// Lucerna integrator tests: analytic scenes (point light in a diffuse sphere, inside an emitting
// sphere, white furnaces) over every integrator and both CPU tracers, agreement of NEE-only /
// BSDF-only / MIS estimates, and thread-count independence.
#include <gtest/gtest.h>

#include <cstring>
#include <tuple>
#include <vector>

#include "integrators/render_helpers.h"

namespace lu::test {

namespace {

// A camera at the origin looking down +z, square film.
std::string CameraHeader(int res, double fov, int spp, int maxDepth) {
    return "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ " + std::to_string(fov) +
           " ]\nFilm \"rgb\" \"integer xresolution\" [ " + std::to_string(res) + " ] \"integer yresolution\" [ " +
           std::to_string(res) + " ]\nSampler \"zsobol\" \"integer pixelsamples\" [ " + std::to_string(spp) +
           " ]\nIntegrator \"path\" \"integer maxdepth\" [ " + std::to_string(maxDepth) + " ]\nPixelFilter \"box\"\n";
}

}  // namespace

// ---- Analytic scenes x integrators x CPU tracers (after pbrt-v4's integrators_test.cpp) ----

// A scene whose image is known: every pixel of the region [x0,x1) x [y0,y1) has radiance
// `expected` in every channel. `slack` absorbs the wavelength-sampling noise floor of the tests.
struct AnalyticScene {
    const char *name;
    std::string text;
    int spp, maxDepth;
    int x0, y0, x1, y1;
    double expected, slack;
};

std::vector<AnalyticScene> AnalyticScenes() {
    // A camera at the center of a sphere of radius 1 that emits L = 1 inwards (black, reversed:
    // its normal points in, so the interior is the MediumInterface's "outside", pbrt-v4's
    // convention), filled with MEDIUM, in which the camera sits too.
    auto mediumFurnace = [](const std::string &medium, const std::string &type = "homogeneous") {
        return "MakeNamedMedium \"fog\" \"string type\" \"" + type + "\" " + medium +
               "\nMediumInterface \"\" \"fog\"\n" + CameraHeader(24, 90, 64, 400) +
               "WorldBegin\nAttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n"
               "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\nReverseOrientation\nMediumInterface \"\" \"fog\"\n"
               "Shape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n";
    };
    const std::string furnaceCamera =
        "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\nPixelFilter \"box\"\n"
        "Sampler \"zsobol\" \"integer pixelsamples\" [ 64 ]\n";
    return {
        // A point light of intensity pi at the center of a diffuse sphere of albedo 0.5:
        // rho I / (pi R^2 (1 - rho)) = 1 everywhere inside.
        {"PointLightInDiffuseSphere",
         CameraHeader(24, 90, 64, 200) +
             "WorldBegin\nLightSource \"point\" \"rgb I\" [ 3.14159265 3.14159265 3.14159265 ]\n"
             "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\nShape \"sphere\" \"float radius\" [ 1 ]\n",
         64, 200, 0, 0, 24, 24, 1.0, 0.01},
        // Inside a sphere that emits Le = 0.5 and reflects with albedo 0.5: Le / (1 - rho) = 1
        // (emitter hits by BSDF sampling and light samples, weighted by MIS).
        {"InsideEmittingDiffuseSphere",
         CameraHeader(24, 90, 64, 200) +
             "WorldBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
             "AreaLightSource \"diffuse\" \"rgb L\" [ 0.5 0.5 0.5 ]\nReverseOrientation\n"
             "Shape \"sphere\" \"float radius\" [ 1 ]\n",
         64, 200, 0, 0, 24, 24, 1.0, 0.01},
        // ... with a non-absorbing glass ball inside (0.35 off the camera): the radiance is still 1
        // everywhere. Under regpath the diffuse wall's paths through the ball reach the emitter by
        // the regularized connection (the footprint kernel of each glass vertex) and by BSDF
        // sampling, and MIS weights that did not read one kernel on both sides would miss the 1.
        {"InsideEmittingDiffuseSphereWithGlassBall",
         CameraHeader(24, 90, 64, 200) +
             "WorldBegin\nAttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
             "AreaLightSource \"diffuse\" \"rgb L\" [ 0.5 0.5 0.5 ]\nReverseOrientation\n"
             "Shape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n"
             "AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0 0 0.52\n"
             "Shape \"sphere\" \"float radius\" [ 0.45 ]\nAttributeEnd\n",
         64, 200, 0, 0, 24, 24, 1.0, 0.01},
        // Open white furnace: a convex diffuse object of albedo 0.8 under a uniform environment of
        // radiance 1 reflects exactly 0.8.
        {"FurnaceDiffuseSphere",
         furnaceCamera + "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                         "Material \"diffuse\" \"rgb reflectance\" [ 0.8 0.8 0.8 ]\nShape \"sphere\" \"float radius\" [ 1 ]\n",
         32, 50, 12, 12, 20, 20, 0.8, 0.01},
        // The background of the furnace is 1 (noisy only through wavelength sampling).
        {"FurnaceBackground",
         furnaceCamera + "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                         "Material \"diffuse\" \"rgb reflectance\" [ 0.8 0.8 0.8 ]\nShape \"sphere\" \"float radius\" [ 1 ]\n",
         32, 50, 0, 0, 4, 4, 1.0, 0.003},
        // A non-absorbing glass sphere in a white furnace is invisible in expectation (reflection +
        // refraction conserve energy; Russian roulette keeps it unbiased). regpath regularizes every
        // vertex here, and the cone average of a uniform environment is the environment: its
        // regularized connections and their MIS partners must add up to exactly 1 as well.
        {"FurnaceGlassSphere",
         furnaceCamera + "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                         "Material \"dielectric\" \"float eta\" [ 1.5 ]\nShape \"sphere\" \"float radius\" [ 1 ]\n",
         64, 100, 10, 10, 22, 22, 1.0, 0.01},
        // A thin glass sheet (reflection + transmission, both Dirac lobes, R + T = 1) is invisible too.
        {"FurnaceThinGlassSheet",
         furnaceCamera + "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                         "Material \"thindielectric\" \"float eta\" [ 1.5 ]\n"
                         "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] "
                         "\"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ]\n",
         64, 100, 12, 12, 20, 20, 1.0, 0.01},
        // A scattering medium of albedo 1 inside an emitter of radiance 1 (a furnace): every path
        // ends on the emitter, so the radiance is 1 everywhere, for any sigma_s(lambda).
        {"FurnaceScatteringMedium", mediumFurnace("\"rgb sigma_a\" [ 0 0 0 ] \"rgb sigma_s\" [ 1.5 1.5 1.5 ] \"float g\" [ 0.4 ]"),
         64, 400, 0, 0, 24, 24, 1.0, 0.01},
        // ... with a chromatic sigma_s: the wavelengths scatter differently (spectral MIS).
        {"FurnaceChromaticMedium", mediumFurnace("\"rgb sigma_a\" [ 0 0 0 ] \"rgb sigma_s\" [ 0.3 1.2 3 ] \"float g\" [ -0.3 ]"),
         64, 400, 0, 0, 24, 24, 1.0, 0.01},
        // ... with pbrt-v4's procedural cloud (null collisions against its sigma_t majorant),
        // its box larger than the sphere and placed off center.
        {"FurnaceCloudMedium",
         mediumFurnace("\"spectrum sigma_a\" [ 360 0 830 0 ] \"rgb sigma_s\" [ 2 3 4 ] \"float g\" 0.5 "
                       "\"float density\" 2 \"point3 p0\" [ -1.5 -0.8 -1.2 ] \"point3 p1\" [ 1.2 1.4 1.1 ]",
                       "cloud"),
         64, 400, 0, 0, 24, 24, 1.0, 0.01},
        // An absorbing, scattering medium that emits Le = 1 inside the same emitter: absorption
        // and emission balance (sigma_a Le = sigma_a L), so the radiance is again 1.
        {"EmittingAbsorbingMedium",
         mediumFurnace("\"rgb sigma_a\" [ 0.8 0.8 0.8 ] \"rgb sigma_s\" [ 0.7 0.7 0.7 ] \"rgb Le\" [ 1 1 1 ]"),
         64, 400, 0, 0, 24, 24, 1.0, 0.01},
    };
}

using AnalyticParam = std::tuple<int, IntegratorKind, CpuTracer>;

class IntegratorAnalytic : public ::testing::TestWithParam<AnalyticParam> {};

TEST_P(IntegratorAnalytic, MatchesTheAnalyticRadiance) {
    auto [index, integrator, tracer] = GetParam();
    AnalyticScene sc = AnalyticScenes()[index];
    auto scene = LoadSceneText(std::string("analytic_") + sc.name, sc.text);
    RenderSettings s = TestSettings(*scene, sc.spp, sc.maxDepth, 7);
    s.integrator = integrator;
    s.cpuTracer = tracer;
    RenderResultForTest r = RenderScene(*scene, s);
    EXPECT_EQ(r.stats.rejected, 0u);
    for (int c = 0; c < 3; ++c) {
        MeanSE m = RegionMean(r.image, c, sc.x0, sc.y0, sc.x1, sc.y1);
        EXPECT_NEAR(m.mean, sc.expected, 4 * m.se + sc.slack) << "channel " << c << ", se " << m.se;
    }
}

INSTANTIATE_TEST_SUITE_P(
    All, IntegratorAnalytic,
    ::testing::Combine(::testing::Range(0, int(AnalyticScenes().size())),
                       ::testing::Values(IntegratorKind::Path, IntegratorKind::RegPath),
                       ::testing::Values(CpuTracer::Embree, CpuTracer::BVH)),
    [](const ::testing::TestParamInfo<AnalyticParam> &info) {
        return std::string(AnalyticScenes()[std::get<0>(info.param)].name) + "_" +
               IntegratorName(std::get<1>(info.param)) + "_" +
               (std::get<2>(info.param) == CpuTracer::Embree ? "embree" : "bvh");
    });

// The tests above can fail: a scene whose true value is 1 is caught when 0.9 is expected.
TEST(IntegratorAnalytic, DetectsA10PercentError) {
    AnalyticScene sc = AnalyticScenes()[0];
    auto scene = LoadSceneText("analytic_negative", sc.text);
    RenderResultForTest r = RenderScene(*scene, TestSettings(*scene, sc.spp, sc.maxDepth, 7));
    MeanSE m = RegionMean(r.image, 1, sc.x0, sc.y0, sc.x1, sc.y1);
    EXPECT_GT(std::abs(m.mean - 0.9), 4 * m.se + sc.slack);
}

// The same direct+indirect lighting estimated by NEE only, BSDF sampling only and MIS agrees.
TEST(Integrator, NeeBsdfAndMisAgree) {
    std::string text =
        "LookAt 0 2 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 50 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]\nPixelFilter \"box\"\n"
        "WorldBegin\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.6 0.5 0.4 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -2 0 -2  2 0 -2  2 0 2  -2 0 2 ]\n"
        "AttributeBegin\nMaterial \"conductor\" \"float roughness\" [ 0.3 ]\n"
        "Translate 0.6 0.4 0\nShape \"sphere\" \"float radius\" [ 0.4 ]\nAttributeEnd\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -0.5 1.5 -0.5  0.5 1.5 -0.5  0.5 1.5 0.5  -0.5 1.5 0.5 ]\n"
        "AttributeEnd\n";
    auto scene = LoadSceneText("strategies", text);
    const char *names[3] = {"MIS", "NEE only", "BSDF only"};
    double mean[3][3], se[3][3];
    for (int s = 0; s < 3; ++s) {
        auto r = RenderScene(*scene, s == 2 ? 256 : 64, 5, 1, 0, s);
        for (int c = 0; c < 3; ++c) {
            MeanSE m = RegionMean(r.image, c, 0, 0, 24, 24);
            mean[s][c] = m.mean;
            se[s][c] = m.se;
        }
    }
    for (int s = 1; s < 3; ++s)
        for (int c = 0; c < 3; ++c) {
            double z = (mean[s][c] - mean[0][c]) / std::sqrt(se[s][c] * se[s][c] + se[0][c] * se[0][c]);
            EXPECT_LT(std::abs(z), 4.0) << names[s] << " vs MIS, channel " << c << ": " << mean[s][c] << " vs " << mean[0][c];
        }
    EXPECT_GT(mean[0][0], 0.01);
}

// Same seed, same image, whatever the number of threads.
TEST(Integrator, ThreadCountIndependent) {
    auto scene = LoadSceneText("threads",
        "LookAt 0 1 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 50 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 40 ] \"integer yresolution\" [ 30 ]\n"
        "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 0.5 0.6 0.7 ]\n"
        "AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nShape \"sphere\" \"float radius\" [ 0.7 ]\nAttributeEnd\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -3 -0.7 -3  3 -0.7 -3  3 -0.7 3  -3 -0.7 3 ]\n");
    auto a = RenderScene(*scene, 8, 8, 42, 1);
    auto b = RenderScene(*scene, 8, 8, 42, 2);
    ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
    EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(float)));
    auto c = RenderScene(*scene, 8, 8, 43, 2);
    EXPECT_NE(0, std::memcmp(a.image.pixels.data(), c.image.pixels.data(), a.image.pixels.size() * sizeof(float)));
}

// The footprint kernel read on both sides of the MIS: inside the emitting sphere with a glass ball
// (InsideEmittingDiffuseSphereWithGlassBall, radiance 1 everywhere) at K = 1, 4 and 64 pixels,
// where the regularized connection and the implicit hit share the ball's paths in very different
// proportions; each must still render 1.
TEST(IntegratorAnalyticFootprint, EveryKernelWidthKeepsTheFurnace) {
    AnalyticScene sc;
    for (const AnalyticScene &a : AnalyticScenes())
        if (std::string(a.name) == "InsideEmittingDiffuseSphereWithGlassBall") sc = a;
    ASSERT_FALSE(sc.text.empty());
    auto scene = LoadSceneText("analytic_footprint", sc.text);
    for (double k : {1.0, 4.0, 64.0}) {
        RenderSettings s = TestSettings(*scene, sc.spp, sc.maxDepth, 9);
        s.integrator = IntegratorKind::RegPath;
        s.regFootprint = k;
        RenderResultForTest r = RenderScene(*scene, s);
        EXPECT_GT(r.stats.regConnections, 0u);
        MeanSE m = RegionMean(r.image, 1, sc.x0, sc.y0, sc.x1, sc.y1);
        EXPECT_NEAR(m.mean, sc.expected, 4 * m.se + sc.slack) << "K " << k << ", se " << m.se;
    }
}

}  // namespace lu::test
