// The integrator over the shared BVH traversal (BVHTracer, what the CUDA megakernel runs) on the
// host against the CPU backend (Embree): with the same seed the images agree pixel by pixel
// except where a ray hits differently; with different seeds the block means agree
// statistically. Runs without a GPU; it also exercises the statistics of the CPU/GPU tests.
#include <gtest/gtest.h>

#include "gpu/gpu_test_util.h"
#include "gpu/render_compare.h"
#include "lucerna/backend/cpu/cpu_render.h"
#include "lucerna/geometry/bvh_traverse.h"
#include "lucerna/integrators/path.h"

namespace lu {
namespace {

// The CPU backend with the shared BVH traversal (what the CUDA megakernel runs) instead of Embree.
FilmAccumulator RenderWithBVHTracer(const HostScene &hs, RenderSettings settings, RenderStats *stats) {
    settings.cpuTracer = CpuTracer::BVH;
    FilmAccumulator film;
    *stats = RenderCPU(hs, settings, film);
    return film;
}

struct Case {
    const char *scene;
    const char *integrator;
    double minEqualPixels;   // same seed: fraction of pixels that must agree to 1e-3
};
// Triangles only (diffuse); spheres with mirror and glass; conductors and sphere lights. Paths
// bouncing between a convex mirror and a glass sphere magnify last-bit differences of the hit
// points at every bounce, so in bs_c a few percent of the pixels take another path at 2 spp.
const Case kCases[] = {{"cornell-box", "path", 0.995}, {"bs_c", "regpath", 0.85}, {"veach-mis", "path", 0.99}};

// The scene file of a case (relative to data/scenes/), from the one list.
std::string SceneOf(const Case &c) {
    const test::SharedScene *s = test::FindSharedScene(c.scene);
    EXPECT_NE(s, nullptr) << c.scene;
    return s ? s->scene.substr(std::string("scenes/").size()) : std::string();
}
constexpr int kRes = 48, kSpp = 8, kSeeds = 4;

// Same seed, same sample values: a pixel differs only where some ray of its paths hit
// differently (last-bit differences of the two triangle tests).
TEST(BVHTracerRender, SameSeedMatchesEmbreePerPixel) {
    for (const Case &c : kCases) {
        SCOPED_TRACE(c.scene);
        auto scene = test::LoadSharedSceneAt(SceneOf(c), kRes);
        RenderSettings job = test::SettingsFor(*scene, c.integrator, 2, 7);
        FilmAccumulator embree;
        RenderStats se = RenderCPU(*scene, job, embree);
        RenderStats sb;
        FilmAccumulator ours = RenderWithBVHTracer(*scene, job, &sb);
        size_t close = 0, n = size_t(kRes) * kRes;
        for (size_t i = 0; i < n; ++i) {
            bool same = true;
            for (int k = 0; k < 4; ++k) {
                double a = embree.xyzw[4 * i + k], b = ours.xyzw[4 * i + k];
                same &= std::abs(a - b) <= 1e-3 * (std::abs(a) + std::abs(b)) + 1e-6;
            }
            close += same;
        }
        double frac = double(close) / n;
        std::printf("[ same seed ] %-40s %-7s %.2f%% of pixels equal to 1e-3; rays %llu vs %llu\n", c.scene,
                    c.integrator, 100 * frac, (unsigned long long)se.rays, (unsigned long long)sb.rays);
        EXPECT_GE(frac, c.minEqualPixels);
        // The same paths: ray counts within a fraction of a percent.
        EXPECT_NEAR(double(sb.rays), double(se.rays), 0.01 * se.rays);
        EXPECT_EQ(sb.rejected, se.rejected);
    }
}

// Independent seeds: block means agree (z-test, Sidak-corrected over all blocks and channels).
TEST(BVHTracerRender, BlockMeansMatchEmbree) {
    const int block = 12;
    int tests = int(std::size(kCases)) * (kRes / block) * (kRes / block) * 3;
    double z = test::TwoSidedZ(test::SidakP(1e-3, tests));
    for (const Case &c : kCases) {
        SCOPED_TRACE(c.scene);
        auto scene = test::LoadSharedSceneAt(SceneOf(c), kRes);
        std::vector<Image> embree, ours;
        for (int s = 0; s < kSeeds; ++s) {
            RenderSettings job = test::SettingsFor(*scene, c.integrator, kSpp, 100 + s);
            FilmAccumulator fa;
            RenderCPU(*scene, job, fa);
            embree.push_back(fa.Resolve(scene->View().film));
            job.seed = 200 + s;
            RenderStats st;
            ours.push_back(RenderWithBVHTracer(*scene, job, &st).Resolve(scene->View().film));
            EXPECT_TRUE(test::AllFinite(ours.back()));
        }
        test::BlockComparison r = test::CompareBlockMeans(embree, ours, block, z);
        std::printf("[ blocks    ] %-40s %-7s %s (threshold %.2f)\n", c.scene, c.integrator, r.Summary().c_str(), z);
        EXPECT_EQ(r.failures, 0) << r.Summary();
    }
}

// pbrt-v4's cylinder and partial spheres and disks (scenes/features/shapes-quadrics.pbrt: every
// shape analytic, so Embree's user geometry and the shared BVH run the same intersection code):
// the same seed gives the same image, independent seeds agree block by block.
TEST(BVHTracerRender, QuadricsSceneMatchesEmbree) {
    Diagnostics diag;
    diag.quiet = true;
    BuildOptions opts;
    opts.resX = 64;
    opts.resY = 40;
    auto scene = LoadScene(std::string(LUCERNA_SOURCE_DIR) + "/scenes/features/shapes-quadrics.pbrt", diag, opts);
    ASSERT_TRUE(scene);
    ASSERT_TRUE(diag.unsupported.empty());
    ASSERT_EQ(scene->cylinders.size(), 2u);
    RenderSettings job = test::SettingsFor(*scene, "path", 2, 7);
    FilmAccumulator embree;
    RenderCPU(*scene, job, embree);
    RenderStats sb;
    FilmAccumulator ours = RenderWithBVHTracer(*scene, job, &sb);
    size_t same = 0, n = size_t(opts.resX) * opts.resY;
    for (size_t i = 0; i < n; ++i) {
        bool eq = true;
        for (int k = 0; k < 4; ++k) eq &= std::abs(embree.xyzw[4 * i + k] - ours.xyzw[4 * i + k]) <= 1e-5 * (std::abs(embree.xyzw[4 * i + k]) + 1e-6);
        same += eq;
    }
    std::printf("[ same seed ] shapes-quadrics: %.2f%% of pixels equal\n", 100.0 * same / n);
    EXPECT_GE(double(same) / n, 0.99);
    const int block = 8, seeds = 4;
    int tests = (opts.resX / block) * (opts.resY / block) * 3;
    double z = test::TwoSidedZ(test::SidakP(1e-3, tests));
    std::vector<Image> a, b;
    for (int s = 0; s < seeds; ++s) {
        RenderSettings j = test::SettingsFor(*scene, "path", 16, 500 + s);
        FilmAccumulator fa;
        RenderCPU(*scene, j, fa);
        a.push_back(fa.Resolve(scene->View().film));
        j.seed = 600 + s;
        RenderStats st;
        b.push_back(RenderWithBVHTracer(*scene, j, &st).Resolve(scene->View().film));
        EXPECT_TRUE(test::AllFinite(b.back()));
    }
    test::BlockComparison r = test::CompareBlockMeans(a, b, block, z);
    std::printf("[ blocks    ] shapes-quadrics: %s (threshold %.2f)\n", r.Summary().c_str(), z);
    EXPECT_EQ(r.failures, 0) << r.Summary();
}

// The comparison can fail: a 10% brighter image is caught at the same sample counts.
TEST(BVHTracerRender, BlockComparisonDetectsABias) {
    auto scene = test::LoadSharedSceneAt(SceneOf({"cornell-box", "path", 0}), kRes);
    std::vector<Image> a, b;
    for (int s = 0; s < kSeeds; ++s) {
        RenderSettings job = test::SettingsFor(*scene, "path", kSpp, 300 + s);
        FilmAccumulator fa;
        RenderCPU(*scene, job, fa);
        a.push_back(fa.Resolve(scene->View().film));
        job.seed = 400 + s;
        FilmAccumulator fb;
        RenderCPU(*scene, job, fb);
        b.push_back(fb.Resolve(scene->View().film));
        for (float &v : b.back().pixels) v *= 1.1f;
    }
    double z = test::TwoSidedZ(test::SidakP(1e-3, int(std::size(kCases)) * 16 * 3));
    test::BlockComparison r = test::CompareBlockMeans(a, b, 12, z);
    std::printf("[ blocks    ] cornell box, 10%% bias injected: %s\n", r.Summary().c_str());
    EXPECT_GT(r.failures, r.tests / 4) << r.Summary();
}

}  // namespace
}  // namespace lu
