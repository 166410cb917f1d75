// Lucerna integrator tests: analytic scenes (point light in a diffuse sphere), white furnaces,
// agreement of NEE-only / BSDF-only / MIS estimates, and thread-count independence.
#include <gtest/gtest.h>

#include <cstring>

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

// pbrt-v4's classic: a point light of intensity pi at the center of a diffuse sphere of albedo
// 0.5 gives radiance rho I / (pi R^2 (1 - rho)) = 1 everywhere on the inside.
TEST(Integrator, PointLightInDiffuseSphereIsOne) {
    auto scene = LoadSceneText("pointsphere", CameraHeader(24, 90, 64, 200) +
        "WorldBegin\nLightSource \"point\" \"rgb I\" [ 3.14159265 3.14159265 3.14159265 ]\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\nShape \"sphere\" \"float radius\" [ 1 ]\n");
    auto r = RenderScene(*scene, 64, 200);
    for (int c = 0; c < 3; ++c) {
        MeanSE m = RegionMean(r.image, c, 0, 0, 24, 24);
        EXPECT_NEAR(m.mean, 1.0, 4 * m.se + 0.01) << "channel " << c << " se " << m.se;
    }
    EXPECT_EQ(r.stats.rejected, 0u);
}

// Open white furnace: a diffuse convex object of albedo rho under a uniform environment of
// radiance 1 reflects exactly rho; the background is 1.
TEST(Integrator, FurnaceDiffuseSphere) {
    auto scene = LoadSceneText("furnace_diffuse",
        "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\nPixelFilter \"box\"\n"
        "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.8 0.8 0.8 ]\nShape \"sphere\" \"float radius\" [ 1 ]\n");
    auto r = RenderScene(*scene, 32, 50);
    for (int c = 0; c < 3; ++c) {
        MeanSE center = RegionMean(r.image, c, 12, 12, 20, 20);
        EXPECT_NEAR(center.mean, 0.8, 4 * center.se + 0.01) << "channel " << c;
        // The background is noisy only through wavelength sampling.
        MeanSE corner = RegionMean(r.image, c, 0, 0, 4, 4);
        EXPECT_NEAR(corner.mean, 1.0, 4 * corner.se + 0.003) << "channel " << c;
    }
}

// A non-absorbing glass sphere in a white furnace is invisible in expectation (energy is
// conserved by reflection + refraction, with Russian roulette keeping it unbiased).
TEST(Integrator, FurnaceGlassSphere) {
    auto scene = LoadSceneText("furnace_glass",
        "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\nPixelFilter \"box\"\n"
        "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
        "Material \"dielectric\" \"float eta\" [ 1.5 ]\nShape \"sphere\" \"float radius\" [ 1 ]\n");
    auto r = RenderScene(*scene, 64, 100);
    for (int c = 0; c < 3; ++c) {
        MeanSE center = RegionMean(r.image, c, 10, 10, 22, 22);
        EXPECT_NEAR(center.mean, 1.0, 4 * center.se + 0.01) << "channel " << c;
    }
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

}  // namespace lu::test
