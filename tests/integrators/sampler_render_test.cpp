// Lucerna: the cornell-box renders with pbrt-v4's halton and sobol samplers (every randomization
// they accept) agree with the independent sampler in 8x8-pixel block means, within the block
// noise measured between two independent renders; a 4% brighter image fails the same test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "integrators/render_helpers.h"
#include "lucerna/scene/pmj02_build.h"
#include "lucerna/scene/sampler_build.h"

namespace lu::test {

namespace {

std::vector<double> BlockMeans(const Image &img, int block) {
    std::vector<double> m;
    for (int by = 0; by + block <= img.height; by += block)
        for (int bx = 0; bx + block <= img.width; bx += block) {
            double s = 0;
            for (int c = 0; c < 3; ++c) s += RegionMean(img, c, bx, by, bx + block, by + block).mean;
            m.push_back(s / 3);
        }
    return m;
}

// Largest block difference in units of the block noise sigma (the rms difference of two
// independent renders over sqrt 2), and the rms difference in the same units.
struct Agreement {
    double maxZ = 0, rmsZ = 0;
};
Agreement Compare(const std::vector<double> &a, const std::vector<double> &b, double sigma) {
    Agreement r;
    double s2 = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        double z = std::abs(a[i] - b[i]) / sigma;
        r.maxZ = std::max(r.maxZ, z);
        s2 += z * z;
    }
    r.rmsZ = std::sqrt(s2 / double(a.size()));
    return r;
}

}  // namespace

TEST(SamplerRender, HaltonSobolAndPMJ02BNAgreeWithIndependent) {
    BuildOptions opts;
    opts.resX = 32;
    opts.resY = 32;
    Diagnostics diag;
    diag.quiet = true;
    auto scene = LoadScene(SharedPath("scenes/bitterli-cornell-box/scene-v4.pbrt"), diag, opts);
    const int spp = 64, depth = 8;
    auto render = [&](const char *name, const char *rnd, uint32_t seed) {
        SamplerOptions o;
        o.randomization = rnd;
        std::string report;
        scene->sampler = MakeSampler(name, spp, int(seed), scene->film.width, scene->film.height, o, &report);
        scene->pmjPoints.clear();
        if (scene->sampler.kind == SamplerKind::PMJ02BN)
            scene->pmjPoints = BuildPMJ02BNTables(spp, 5, &scene->sampler.pmjTileSize);
        return BlockMeans(RenderScene(*scene, spp, depth, seed).image, 8);
    };
    std::vector<double> ind1 = render("independent", "", 1), ind2 = render("independent", "", 2);
    double s2 = 0;
    for (size_t i = 0; i < ind1.size(); ++i) s2 += (ind1[i] - ind2[i]) * (ind1[i] - ind2[i]);
    double sigma = std::sqrt(s2 / double(ind1.size()) / 2);   // one independent render's block noise
    ASSERT_GT(sigma, 0);
    // The reference is the mean of the two independent renders (noise sigma / sqrt 2); a QMC render
    // has at most the independent noise, so the difference is at most sigma * sqrt(1.5).
    std::vector<double> ref(ind1.size());
    for (size_t i = 0; i < ref.size(); ++i) ref[i] = 0.5 * (ind1[i] + ind2[i]);
    const char *configs[][2] = {{"halton", "permutedigits"}, {"halton", "owen"}, {"halton", "none"},
                                {"sobol", "fastowen"},       {"sobol", "owen"},  {"sobol", "permutedigits"},
                                {"sobol", "none"},           {"pmj02bn", ""}};
    // The block noise has heavy tails (fireflies of the reference renders): a block may stray
    // to 5-6 sigma; the rms over the 16 blocks is the sharper criterion.
    const double kMaxZ = 7, kRmsZ = 1.8;
    for (auto &c : configs) {
        std::vector<double> m = render(c[0], c[1], 3);
        Agreement a = Compare(m, ref, sigma);
        for (double &v : m) v *= 1.04;
        Agreement biased = Compare(m, ref, sigma);
        std::printf("[ sampler ] %s/%s: block z rms %.2f max %.2f; 4%% brighter: rms %.2f max %.2f\n", c[0], c[1],
                    a.rmsZ, a.maxZ, biased.rmsZ, biased.maxZ);
        EXPECT_LT(a.maxZ, kMaxZ) << c[0] << "/" << c[1];
        EXPECT_LT(a.rmsZ, kRmsZ) << c[0] << "/" << c[1];
        // Power: the same criterion rejects the render made 4% brighter.
        EXPECT_TRUE(biased.rmsZ >= kRmsZ || biased.maxZ >= kMaxZ)
            << c[0] << "/" << c[1] << ": the test cannot see a 4% bias (rms z " << biased.rmsZ << ")";
    }
}

}  // namespace lu::test

namespace lu::test {

// Option "disablewavelengthjitter": every camera sample takes pbrt-v4's wavelengths of u = 0.5
// (about 546, 617, 830 and 479 nm). An environment emitting only in 575-590 nm, seen directly,
// is then black in every pixel; with the jitter it is not.
TEST(SamplerRender, DisabledWavelengthJitterUsesFixedWavelengths) {
    const std::string world =
        "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\n"
        "Camera \"perspective\" \"float fov\" 45\n"
        "WorldBegin\n"
        "LightSource \"infinite\" \"spectrum L\" [ 570 0 575 1 585 1 590 0 ]\n";
    auto fixed = LoadSceneText("wavelength_jitter_off", "Option \"disablewavelengthjitter\" true\n" + world);
    auto jittered = LoadSceneText("wavelength_jitter_on", world);
    ASSERT_TRUE(fixed->film.disableWavelengthJitter);
    Image a = RenderScene(*fixed, TestSettings(*fixed, 16, 1)).image;
    Image b = RenderScene(*jittered, TestSettings(*jittered, 16, 1)).image;
    double sumA = 0, sumB = 0;
    for (int c = 0; c < 3; ++c) {
        sumA += std::abs(RegionMean(a, c, 0, 0, 8, 8).mean);
        sumB += RegionMean(b, c, 0, 0, 8, 8).mean;
    }
    EXPECT_EQ(sumA, 0.0);
    EXPECT_GT(sumB, 1e-3);
}

}  // namespace lu::test
