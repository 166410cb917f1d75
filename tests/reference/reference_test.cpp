// Lucerna reference tests: whole images against pbrt-v4 references in data/refs, with a
// tolerance derived from the measured noise. K independent renders give every pixel a sample
// variance; block means (8x8) of the average image then have a known standard error, and the
// z-score of (ours - reference) per block and channel must look like noise: at most a small
// fraction of blocks beyond |z| = 3.29 (p = 0.001 two-sided; 0.1% expected under agreement), and
// the image-wide mean within 1.5%. Heavy-tailed noise (rare fireflies from glossy reflections of
// small lights, present in pbrt-v4's 8192-spp veach-mis reference too) makes a per-pixel variance
// from K runs underestimate the true one exactly where a firefly was missed, so that case adds a
// stated relative tolerance to the standard error (2% of the block mean).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "integrators/render_helpers.h"
#include "lucerna/image/metrics.h"
#include "support/shared_scenes.h"

namespace lu::test {

namespace {

struct RefCase {
    const char *name;           // in SharedScenes(): an unbiased ("path") reference
    int sppPerRun, runs;
    double maxOutlierFraction;  // fraction of block-channels allowed beyond |z| = 3.29
    double relTolerance;        // added to the standard error: relTolerance * reference block mean
};

void CompareWithReference(const RefCase &rc) {
    const SharedScene *s = FindSharedScene(rc.name);
    ASSERT_NE(s, nullptr) << rc.name;
    ASSERT_TRUE(s->ExactReference()) << rc.name << ": its reference is " << s->refIntegrator;
    BuildOptions opts;
    opts.resX = s->refWidth;
    opts.resY = s->refHeight;
    Diagnostics diag;
    diag.quiet = true;
    auto scene = LoadScene(SharedPath(s->scene), diag, opts);
    Image ref = ReadImage(SharedPath(s->reference));
    ASSERT_EQ(ref.width, s->refWidth);
    ASSERT_EQ(ref.height, s->refHeight);
    const int w = s->refWidth, h = s->refHeight;
    const int n = w * h;
    std::vector<double> sum(size_t(n) * 3, 0), sum2(size_t(n) * 3, 0);
    for (int k = 0; k < rc.runs; ++k) {
        auto r = RenderScene(*scene, rc.sppPerRun, scene->settings.maxDepth, 1000 + k);
        ASSERT_EQ(r.stats.rejected, 0u);
        for (int i = 0; i < n * 3; ++i) {
            double v = r.image.pixels[i];
            ASSERT_TRUE(std::isfinite(v));
            sum[i] += v;
            sum2[i] += v * v;
        }
    }
    const int K = rc.runs, B = 8;
    // Reference noise: pbrt's image at S spp; its variance per pixel ~ ours * (our spp / S).
    const double refVarRatio = double(rc.sppPerRun * K) / s->refSpp;
    int blocks = 0, outliers = 0;
    double maxZ = 0, ourTotal = 0, refTotal = 0;
    for (int by = 0; by + B <= h; by += B)
        for (int bx = 0; bx + B <= w; bx += B)
            for (int c = 0; c < 3; ++c) {
                double m = 0, r = 0, var = 0;
                for (int y = by; y < by + B; ++y)
                    for (int x = bx; x < bx + B; ++x) {
                        size_t i = (size_t(y) * w + x) * 3 + c;
                        double mean = sum[i] / K;
                        double v = std::max(0.0, (sum2[i] - K * mean * mean) / (K - 1));
                        m += mean;
                        r += ref.pixels[(size_t(y) * w + x) * ref.channels + c];
                        var += v / K;
                    }
                m /= B * B;
                r /= B * B;
                double se = std::sqrt(var * (1 + refVarRatio) / double(B * B * B * B) + Sqr(rc.relTolerance * r));
                ourTotal += m;
                refTotal += r;
                double z = se > 0 ? (m - r) / se : (std::abs(m - r) < 1e-6 ? 0 : 1e9);
                ++blocks;
                maxZ = std::max(maxZ, std::abs(z));
                if (std::abs(z) > 3.29) ++outliers;
            }
    double frac = double(outliers) / blocks;
    std::printf("%s: %d block-channels, %d beyond |z|=3.29 (%.2f%%), max |z| %.2f, mean ours %.5f ref %.5f (%.3f%%)\n",
                s->scene.c_str(), blocks, outliers, 100 * frac, maxZ, ourTotal / blocks, refTotal / blocks,
                100 * (ourTotal - refTotal) / refTotal);
    EXPECT_LE(frac, rc.maxOutlierFraction);
    EXPECT_NEAR(ourTotal / refTotal, 1.0, 0.015);
}

}  // namespace

// The volumetric caustic with its homogeneous medium (scene-v4.pbrt) against pbrt-v4's bdpt at
// 96x96, 1024 spp, in 16x16-block means: one render, the standard error of each block's mean
// difference from the spread of the per-pixel differences (so the reference's own noise is in
// it), Sidak-corrected at family-wise 1e-3 (image/metrics.h, ZTestBlocks), with a 2%
// systematic tolerance as for veach-mis (heavy tails: at 64 spp the floor corner is 14% low with
// |z| 4.6 unaided; scaling the render by 0.95 fails the regpath check). The 15% allowed before
// was for a gap that is path's, not a bias: on the scene without its medium (ref-volumetric-
// caustic.pbrt, 128x128, 256 spp) regpath is within 1-2% of pbrt-v4's bdpt in every 16-row band
// below the light's own rows (with and without MNEE), while path is 5-10% low on the walls and
// the ceiling: light reflected and refracted by the glass ball off a 5x4 mm light is reached by
// path only by hitting that light.
// regpath is tested on every block; path, unbiased but sampling the light through the glass
// ball only by hitting the 5x4 mm light, on the blocks that light does not reach through the
// ball (the top rows, above the ball and its beam): at CI's spp its mean there is far below
// the expectation, as heavy-tailed estimators are.
ZTestResult MediumReferenceZTest(IntegratorKind integrator, int spp, int rows) {
    const SharedScene *s = FindSharedScene("volumetric-caustic-medium");
    BuildOptions opts;
    opts.resX = s->refWidth;
    opts.resY = s->refHeight;
    Diagnostics diag;
    diag.quiet = true;
    auto scene = LoadScene(SharedPath(s->scene), diag, opts);
    RenderSettings rs = TestSettings(*scene, spp, scene->settings.maxDepth, 5);
    rs.integrator = integrator;
    auto r = RenderScene(*scene, rs);
    EXPECT_EQ(r.stats.rejected, 0u);
    Image ref = ReadImage(SharedPath(s->reference));
    ZTestOptions zo;
    zo.blockSize = 16;
    zo.alpha = 1e-3;
    zo.relTolerance = 0.02;
    zo.crop = Crop{0, 0, s->refWidth, rows};
    ZTestResult z = ZTestBlocks(r.image, ref, zo);
    std::printf("volumetric-caustic-medium %s %d spp: %s\n", IntegratorName(integrator), spp, z.Summary().c_str());
    return z;
}

TEST(Reference, VolumetricCausticMedium) {
    ZTestResult reg = MediumReferenceZTest(IntegratorKind::RegPath, 64, 96);
    EXPECT_TRUE(reg.Passed()) << reg.Summary();
    ZTestResult path = MediumReferenceZTest(IntegratorKind::Path, 48, 32);
    EXPECT_TRUE(path.Passed()) << path.Summary();
}

TEST(Reference, CornellBox) {
    CompareWithReference({"cornell-box", 64, 4, 0.01, 0.0});
}

TEST(Reference, VeachMis) {
    // Fireflies (see the header): 2% relative tolerance per block, 1% of block-channels beyond |z| 3.29.
    CompareWithReference({"veach-mis", 64, 4, 0.01, 0.02});
}

}  // namespace lu::test
