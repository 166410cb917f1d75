// Tests of image/metrics.h: metric values on hand-made images, crops, block means, the
// bias^2/variance split, the distribution helpers (values from scipy.stats), and the calibration
// and power of the block z-tests.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lucerna/image/metrics.h"

namespace lu {
namespace {

Image FromValues(int w, int h, int c, std::vector<float> v) {
    Image im = MakeImage(w, h, c);
    im.pixels = std::move(v);
    return im;
}

TEST(Metrics, HandComputedValues) {
    // r = [0, 1], v = [0.1, 3] (one channel, 2x1):
    //   MSE = (0.01 + 4) / 2; relMSE = (0.01/0.01 + 4/1.01) / 2; MAPE = (0.1/0.01 + 2/1.01) / 2.
    Image r = FromValues(2, 1, 1, {0.f, 1.f}), v = FromValues(2, 1, 1, {0.1f, 3.f});
    ErrorStats s = ComputeErrors(v, r);
    EXPECT_NEAR(s.mse, 2.005, 1e-7);
    EXPECT_NEAR(s.rmse, 1.41598022585, 1e-7);
    EXPECT_NEAR(s.relMSE, 2.48019802, 1e-7);
    EXPECT_NEAR(s.mape, 5.99009901, 1e-6);
    EXPECT_EQ(s.count, 2u);
    EXPECT_EQ(s.nonFinite, 0u);
    EXPECT_DOUBLE_EQ(ComputeMetric(Metric::RelMSE, v, r), s.relMSE);
    EXPECT_DOUBLE_EQ(ComputeErrors(r, r).mse, 0.0);
}

TEST(Metrics, ChannelsAndAlpha) {
    // RGB vs RGBA: alpha is not compared; a Y image against RGB cannot be compared.
    Image rgb = MakeImage(2, 2, 3, 1.f), rgba = MakeImage(2, 2, 4, 1.f);
    rgba.At(1, 1, 3) = 100.f;  // alpha: ignored
    rgba.At(0, 0, 1) = 3.f;    // green: counted, (3-1)^2 = 4 over 12 values
    EXPECT_NEAR(ComputeErrors(rgba, rgb).mse, 4.0 / 12, 1e-12);
    EXPECT_EQ(ComputeErrors(rgba, rgb).count, 12u);
    EXPECT_THROW(ComputeErrors(MakeImage(2, 2, 1), rgb), ImageError);
    EXPECT_THROW(ComputeErrors(MakeImage(2, 3, 3), rgb), ImageError);
    EXPECT_EQ(ComparedChannels(MakeImage(1, 1, 2), MakeImage(1, 1, 1)), 1);
}

TEST(Metrics, CropIsHalfOpen) {
    Image r = MakeImage(4, 3, 3, 0.5f), v = r;
    v.At(2, 1, 0) = 1.5f;  // one differing value
    EXPECT_NEAR(ComputeErrors(v, r, Crop{2, 1, 3, 2}).mse, 1.0 / 3, 1e-12);
    EXPECT_EQ(ComputeErrors(v, r, Crop{0, 0, 2, 3}).mse, 0.0);  // x = 2 excluded
    EXPECT_EQ(ComputeErrors(v, r, Crop{3, 0, 4, 3}).mse, 0.0);
    EXPECT_NEAR(ComputeErrors(v, r).mse, 1.0 / 36, 1e-12);
    EXPECT_THROW(ComputeErrors(v, r, Crop{0, 0, 5, 3}), ImageError);
    EXPECT_THROW(ComputeErrors(v, r, Crop{-1, 0, 2, 2}), ImageError);
    EXPECT_THROW(ComputeErrors(v, r, Crop{2, 0, 2, 2}), ImageError);
}

TEST(Metrics, ParseCropAndMetric) {
    EXPECT_EQ(ParseCrop("1,2,30,40"), (Crop{1, 2, 30, 40}));
    EXPECT_EQ(ParseCrop(" 0, 0 ,8,8 "), (Crop{0, 0, 8, 8}));
    for (const char *bad : {"", "1,2,3", "1,2,3,4,5", "a,b,c,d", "4,0,2,8", "1;2;3;4", "0,0,8,8x"})
        EXPECT_THROW(ParseCrop(bad), ImageError) << bad;
    EXPECT_EQ(ParseMetric("RelMSE"), Metric::RelMSE);
    EXPECT_EQ(ParseMetric("mape"), Metric::MAPE);
    EXPECT_FALSE(ParseMetric("psnr").has_value());
    EXPECT_STREQ(MetricName(Metric::RMSE), "rmse");
}

TEST(Metrics, NonFiniteValuesPropagate) {
    Image r = MakeImage(2, 2, 1, 1.f), v = r;
    v.At(0, 1, 0) = std::nanf("");
    ErrorStats s = ComputeErrors(v, r);
    EXPECT_TRUE(std::isnan(s.mse));
    EXPECT_EQ(s.nonFinite, 1u);
}

TEST(Metrics, ErrorImagePerPixel) {
    Image r = FromValues(2, 1, 3, {1, 1, 1, 0, 0, 0}), v = FromValues(2, 1, 3, {2, 1, 1, 0, 0, 0.3f});
    Image e = ErrorImage(v, r, Metric::MSE);
    ASSERT_EQ(e.width, 2);
    ASSERT_EQ(e.channels, 1);
    EXPECT_NEAR(e.At(0, 0, 0), 1.0 / 3, 1e-7);
    EXPECT_NEAR(e.At(1, 0, 0), 0.09 / 3, 1e-7);
    Image rel = ErrorImage(v, r, Metric::RelMSE);
    EXPECT_NEAR(0.5 * (rel.At(0, 0, 0) + rel.At(1, 0, 0)), ComputeErrors(v, r).relMSE, 1e-6);
    Image cropped = ErrorImage(v, r, Metric::MAPE, Crop{1, 0, 2, 1});
    ASSERT_EQ(cropped.width, 1);
    EXPECT_NEAR(cropped.At(0, 0, 0), 0.3 / 0.01 / 3, 1e-5);
}

TEST(Metrics, BlockStatsTileTheCrop) {
    // 5x3 one-channel image, value x + 10 y; 2x2 blocks -> 3 x 2 blocks, edge blocks partial.
    Image im = MakeImage(5, 3, 1);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) im.At(x, y, 0) = float(x + 10 * y);
    BlockStats b = ComputeBlockStats(im, 2);
    ASSERT_EQ(b.blocksX, 3);
    ASSERT_EQ(b.blocksY, 2);
    EXPECT_EQ(b.Count(0, 0), 4);
    EXPECT_EQ(b.Count(2, 0), 2);
    EXPECT_EQ(b.Count(2, 1), 1);
    EXPECT_DOUBLE_EQ(b.Mean(0, 0, 0), 5.5);   // (0 + 1 + 10 + 11) / 4
    EXPECT_DOUBLE_EQ(b.Mean(2, 0, 0), 9.0);   // (4 + 14) / 2
    EXPECT_DOUBLE_EQ(b.Mean(1, 1, 0), 22.5);  // (22 + 23) / 2
    EXPECT_DOUBLE_EQ(b.variance[0], (2 * 5.5 * 5.5 + 2 * 4.5 * 4.5) / 3);
    BlockStats c = ComputeBlockStats(im, 2, Crop{1, 1, 5, 3});
    EXPECT_EQ(c.blocksX, 2);
    EXPECT_EQ(c.blocksY, 1);
    EXPECT_DOUBLE_EQ(c.Mean(0, 0, 0), 16.5);  // (11 + 12 + 21 + 22) / 4
    EXPECT_THROW(ComputeBlockStats(im, 0), ImageError);
}

TEST(Metrics, BlockMeansIgnoreZeroMeanNoise) {
    // A +-d checkerboard has zero mean in every 2x2 block: block MSE is 0, pixel MSE is d^2.
    Image r = MakeImage(8, 6, 3, 0.4f), v = r;
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) v.At(x, y, c) += ((x + y) % 2 ? 0.1f : -0.1f);
    EXPECT_NEAR(ComputeErrors(v, r).mse, 0.01, 1e-8);
    EXPECT_NEAR(CompareBlockMeans(v, r, 2).mse, 0.0, 1e-12);
    v.At(0, 0, 0) += 0.4f;  // now block (0,0) is off by 0.1 in one channel: 1 of 12 x 3 block values
    EXPECT_NEAR(CompareBlockMeans(v, r, 2).mse, 0.01 / 36, 1e-8);
}

TEST(Metrics, BiasVarianceSplit) {
    // Runs = reference + bias 0.05 + Gaussian noise of sigma 0.2: bias^2 = 0.0025, variance 0.04.
    const int w = 64, h = 64, k = 4;
    Image ref = MakeImage(w, h, 3);
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(0.2f, 2.f);
    for (float &x : ref.pixels) x = u(rng);
    std::normal_distribution<float> noise(0.f, 0.2f);
    std::vector<Image> runs(k, ref);
    for (Image &run : runs)
        for (float &x : run.pixels) x += 0.05f + noise(rng);
    BiasVariance bv = ComputeBiasVariance(runs, ref);
    EXPECT_EQ(bv.runs, k);
    // Sampling error: variance is a mean of 12288 chi^2_3 s^2 values, relative sd ~ sqrt(2/3/12288).
    EXPECT_NEAR(bv.variance, 0.04, 5 * 0.04 * std::sqrt(2.0 / 3 / (w * h * 3)));
    // Per value, (vbar - r)^2 - s^2/K has variance 4 b^2 sigma^2/K + 2 sigma^4/K^2 + 2 sigma^4/(K^2 (K-1)).
    double s2 = 0.04, b2 = 0.0025;
    double perValue = 4 * b2 * s2 / k + 2 * s2 * s2 / (k * k) + 2 * s2 * s2 / (k * k * (k - 1));
    EXPECT_NEAR(bv.bias2, b2, 5 * std::sqrt(perValue / (w * h * 3)));
    // mse = bias2 + variance is exactly the mean of the runs' MSEs.
    double meanMSE = 0;
    for (const Image &run : runs) meanMSE += ComputeErrors(run, ref).mse / k;
    EXPECT_NEAR(bv.mse, meanMSE, 1e-9 * meanMSE);
    EXPECT_GT(bv.relVariance, 0);
    EXPECT_THROW(ComputeBiasVariance({ref}, ref), ImageError);
}

TEST(Statistics, DistributionHelpersMatchScipy) {
    EXPECT_NEAR(NormalUpperTail(8.0), 6.22096057427174e-16, 1e-25);
    EXPECT_NEAR(NormalUpperTailInverse(0.025), 1.9599639845400545, 1e-9);
    EXPECT_NEAR(StudentTTwoSidedP(2.228138852, 10), 0.05, 1e-9);
    EXPECT_NEAR(StudentTTwoSidedP(5, 3), 0.015392438073302296, 1e-12);
    EXPECT_NEAR(StudentTTwoSidedP(1, 1), 0.5, 1e-12);  // Cauchy
    EXPECT_NEAR(StudentTTwoSidedP(0.7, 63), 0.4865042335720198, 1e-10);
    EXPECT_NEAR(StudentTTwoSidedP(1000, 5) / 1.898013113197973e-14, 1, 1e-6);
    EXPECT_NEAR(TToZ(3.1824463052842638, 3), 1.9599639845400545, 1e-7);
    EXPECT_NEAR(TToZ(-1000, 5), -7.657355093596486, 1e-6);
    EXPECT_DOUBLE_EQ(TToZ(1.5, INFINITY), 1.5);
    EXPECT_NEAR(SidakThreshold(0.05, 1), 1.9599639845400545, 1e-9);
    EXPECT_NEAR(SidakThreshold(1e-4, 1000), 5.326714809375471, 1e-6);
}

// ---- Z-tests ----

// A smooth reference with a wide dynamic range and a per-pixel noise sigma that varies with it.
struct NoisySetup {
    Image ref, sigma;
    NoisySetup(int w, int h, float noise = 1) : ref(MakeImage(w, h, 3)), sigma(MakeImage(w, h, 3)) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c) {
                    float r = 0.05f + 3.f * float(x) / w * (1 + c) + std::sin(0.3f * y);
                    ref.At(x, y, c) = std::abs(r);
                    sigma.At(x, y, c) = noise * (0.1f + 0.5f * std::abs(r));
                }
    }
    Image Render(std::mt19937 &rng, float bias = 0) const {
        std::normal_distribution<float> n(0.f, 1.f);
        Image v = ref;
        for (size_t i = 0; i < v.pixels.size(); ++i) v.pixels[i] += bias + sigma.pixels[i] * n(rng);
        return v;
    }
};

// Under the null hypothesis |z| > 1.96 must happen 5% of the time. With 2x2 blocks (3 degrees of
// freedom) a normal approximation of t would give ~15%: this checks the t -> z conversion.
TEST(ZTest, SpreadEstimatorIsCalibrated) {
    NoisySetup s(64, 32);
    std::mt19937 rng(7);
    ZTestOptions o;
    o.blockSize = 2;
    size_t tests = 0, beyond = 0;
    for (int i = 0; i < 8; ++i) {
        ZTestResult z = ZTestBlocks(s.Render(rng), s.ref, o);
        ASSERT_EQ(z.tests, size_t(32 * 16 * 3));
        for (double v : z.z) {
            tests += 1;
            beyond += std::abs(v) > 1.959964;
        }
    }
    double p = 0.05, expected = p * tests, sd = std::sqrt(tests * p * (1 - p));
    EXPECT_NEAR(double(beyond), expected, 5 * sd) << beyond << " of " << tests;
}

TEST(ZTest, RunsAndVarianceEstimatorsAreCalibrated) {
    NoisySetup s(48, 48);
    std::mt19937 rng(11);
    ZTestOptions o;
    o.blockSize = 4;
    size_t tests = 0, beyondRuns = 0, beyondVar = 0;
    for (int i = 0; i < 6; ++i) {
        std::vector<Image> runs;
        for (int k = 0; k < 3; ++k) runs.push_back(s.Render(rng));  // 2 degrees of freedom
        ZTestResult zr = ZTestBlocks(runs, s.ref, o);
        Image var = s.sigma;
        for (float &x : var.pixels) x *= x;
        ZTestResult zv = ZTestBlocksWithVariance(runs[0], var, s.ref, o);
        for (size_t j = 0; j < zr.z.size(); ++j) {
            ++tests;
            beyondRuns += std::abs(zr.z[j]) > 1.959964;
            beyondVar += std::abs(zv.z[j]) > 1.959964;
        }
    }
    double p = 0.05, expected = p * tests, sd = std::sqrt(tests * p * (1 - p));
    EXPECT_NEAR(double(beyondRuns), expected, 5 * sd);
    EXPECT_NEAR(double(beyondVar), expected, 5 * sd);
}

TEST(ZTest, PassesUnbiasedRendersAndFindsABiasedRegion) {
    NoisySetup s(64, 64, 0.25f);  // block standard errors ~1.5% of the block means
    std::mt19937 rng(3);
    ZTestOptions o;  // 8x8 blocks, alpha 1e-4
    for (int i = 0; i < 5; ++i) {
        ZTestResult z = ZTestBlocks(s.Render(rng), s.ref, o);
        EXPECT_TRUE(z.Passed()) << z.Summary();
        EXPECT_EQ(z.tests, size_t(8 * 8 * 3));
        EXPECT_NEAR(z.threshold, SidakThreshold(1e-4, 192), 1e-12);
    }
    // 20% too bright in pixels [40,48) x [16,24), channel 1: found there.
    Image v = s.Render(rng);
    for (int y = 16; y < 24; ++y)
        for (int x = 40; x < 48; ++x) v.At(x, y, 1) += 0.2f * s.ref.At(x, y, 1);
    ZTestResult z = ZTestBlocks(v, s.ref, o);
    EXPECT_FALSE(z.Passed());
    EXPECT_EQ(z.worstBx, 5);
    EXPECT_EQ(z.worstBy, 2);
    EXPECT_EQ(z.worstC, 1);
    EXPECT_NE(z.Summary().find("FAILED"), std::string::npos);
    EXPECT_NE(z.Summary().find("[40,48)x[16,24)"), std::string::npos) << z.Summary();
    // A 25% relative tolerance accepts it.
    o.relTolerance = 0.25;
    EXPECT_TRUE(ZTestBlocks(v, s.ref, o).Passed());
    // The crop can leave the region out.
    o.relTolerance = 0;
    o.crop = Crop{0, 0, 40, 64};
    EXPECT_TRUE(ZTestBlocks(v, s.ref, o).Passed());
}

TEST(ZTest, RunsDetectAUniformBiasTheSpreadCannotHide) {
    NoisySetup s(32, 32);
    std::mt19937 rng(5);
    std::vector<Image> good, biased;
    for (int k = 0; k < 8; ++k) {
        good.push_back(s.Render(rng));
        biased.push_back(s.Render(rng, 0.3f));
    }
    EXPECT_TRUE(ZTestBlocks(good, s.ref).Passed()) << ZTestBlocks(good, s.ref).Summary();
    EXPECT_FALSE(ZTestBlocks(biased, s.ref).Passed());
    EXPECT_THROW(ZTestBlocks(std::vector<Image>{good[0]}, s.ref), ImageError);
}

TEST(ZTest, ExactAgreementAndNaN) {
    Image r = MakeImage(16, 16, 3, 0.f), v = r;
    ZTestResult z = ZTestBlocks(v, r);
    EXPECT_TRUE(z.Passed());
    EXPECT_EQ(z.maxAbsZ, 0);
    // Render black where the reference is not, with no spread: infinitely significant.
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) r.At(x, y, 0) = 1.f;
    EXPECT_FALSE(ZTestBlocks(v, r).Passed());
    Image n = MakeImage(16, 16, 3, 0.f);
    n.At(9, 9, 2) = std::nanf("");
    ZTestResult zn = ZTestBlocks(n, MakeImage(16, 16, 3, 0.f));
    EXPECT_FALSE(zn.Passed());
    EXPECT_EQ(zn.worstBx, 1);
    EXPECT_EQ(zn.worstC, 2);
    Image zi = zn.ZImage();
    EXPECT_EQ(zi.width, 2);
    EXPECT_EQ(zi.channels, 3);
}

}  // namespace
}  // namespace lu
