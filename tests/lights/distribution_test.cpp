// Tests of the piecewise-constant 1D/2D distributions (sampling/distribution.h): pdf against the
// function, sample/invert round trips, chi-square of samples, zero-function handling.
#include <gtest/gtest.h>

#include <random>

#include "lucerna/scene/distribution_build.h"
#include "support/test_support.h"

namespace lu {
namespace {

SceneView ViewOf(const std::vector<Float> &distData) {
    SceneView s;
    s.distData = {distData.data(), uint32_t(distData.size())};
    return s;
}

TEST(Distribution1D, PdfMatchesFunctionAndIntegral) {
    std::vector<float> f = {1, 0, 3, 2, 0, 4};
    std::vector<Float> data;
    Distribution1D d = BuildDistribution1D(f.data(), uint32_t(f.size()), data, -1, 2);
    SceneView s = ViewOf(data);
    // integral over [-1, 2]: sum f * (3 / 6)
    EXPECT_NEAR(d.integral, 10 * 0.5f, 1e-5f);
    for (size_t i = 0; i < f.size(); ++i) {
        Float x = -1 + (i + 0.5f) * 0.5f;
        EXPECT_NEAR(Distribution1DPDF(s, d, x), f[i] / 5.0f, 1e-6f) << i;
    }
    EXPECT_EQ(Distribution1DPDF(s, d, 2.5f), 0);
}

TEST(Distribution1D, SampleInvertRoundTrip) {
    std::vector<float> f = {0.5f, 2, 0, 1, 7, 0, 0, 3};
    std::vector<Float> data;
    Distribution1D d = BuildDistribution1D(f.data(), uint32_t(f.size()), data, 0, 4);
    SceneView s = ViewOf(data);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> U(0, 1);
    for (int i = 0; i < 2000; ++i) {
        Float u = U(rng), pdf;
        uint32_t o;
        Float x = SampleDistribution1D(s, d, u, &pdf, &o);
        ASSERT_GT(pdf, 0);  // zero bins are never sampled
        EXPECT_NEAR(pdf, Distribution1DPDF(s, d, x), 1e-5f);
        Float u2;
        ASSERT_TRUE(InvertDistribution1D(s, d, x, &u2));
        EXPECT_NEAR(u, u2, 2e-5f);
    }
}

TEST(Distribution1D, ChiSquareAndDiscrete) {
    std::vector<float> f = {1, 3, 0, 6, 2, 8};
    std::vector<Float> data;
    Distribution1D d = BuildDistribution1D(f.data(), uint32_t(f.size()), data);
    SceneView s = ViewOf(data);
    const int N = 100000;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(0, 1);
    // The continuous samples against the density f / integral (the function itself, not the
    // distribution's pdf), and the discrete ones against f / sum.
    auto density = [&](const std::vector<float> &g) {
        double sum = 0;
        for (float v : g) sum += v;
        return [g, sum](const test::Chi2Point &p) {
            return g[std::min(size_t(p.x * g.size()), g.size() - 1)] * g.size() / sum;
        };
    };
    auto sample = [&](test::Chi2Point *p) {
        Float pdf;
        p->x = SampleDistribution1D(s, d, U(rng), &pdf);
        return true;
    };
    test::Chi2Options opts;
    opts.samples = N;
    EXPECT_TRUE(test::Chi2Accepts(test::Chi2SampleTest(test::IntervalDomain(0, 1, 12), sample, density(f), opts)));
    // The harness rejects a function with one bin 20% off.
    std::vector<float> g = f;
    g[3] *= 1.2f;
    rng.seed(3);
    EXPECT_TRUE(test::Chi2Rejects(test::Chi2SampleTest(test::IntervalDomain(0, 1, 12), sample, density(g), opts)));

    std::vector<double> obsDiscrete(f.size(), 0), expd(f.size());
    for (int i = 0; i < N; ++i) {
        Float pmf;
        uint32_t k = SampleDiscrete1D(s, d, U(rng), &pmf);
        EXPECT_NEAR(pmf, f[k] / 20.0f, 1e-6f);
        obsDiscrete[k] += 1;
    }
    for (size_t i = 0; i < f.size(); ++i) expd[i] = N * f[i] / 20.0;
    EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(obsDiscrete, expd)));
}

TEST(Distribution1D, AllZeroIsUniformWithZeroPdf) {
    std::vector<float> f(4, 0.f);
    std::vector<Float> data;
    Distribution1D d = BuildDistribution1D(f.data(), 4, data);
    SceneView s = ViewOf(data);
    Float pdf = 1;
    Float x = SampleDistribution1D(s, d, 0.6f, &pdf);
    EXPECT_NEAR(x, 0.6f, 1e-6f);
    EXPECT_EQ(pdf, 0);
}

TEST(FindCdfInterval, SkipsZeroWidthBins) {
    const Float cdf[6] = {0, 0, 0.5f, 0.5f, 1, 1};
    EXPECT_EQ(FindCdfInterval(cdf, 5, 0.f), 1u);
    EXPECT_EQ(FindCdfInterval(cdf, 5, 0.25f), 1u);
    EXPECT_EQ(FindCdfInterval(cdf, 5, 0.5f), 3u);
    EXPECT_EQ(FindCdfInterval(cdf, 5, 0.99f), 3u);
    EXPECT_EQ(FindCdfInterval(cdf, 5, 1.f), 4u);
}

// A 2D function with structure and zero rows/columns.
std::vector<float> TestImage(int nx, int ny) {
    std::vector<float> f(size_t(nx) * ny);
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
            float v = 0.2f + std::sin(0.7f * x) * std::sin(0.7f * x) * (1 + y) + (x == 3 && y == 2 ? 20 : 0);
            if (y == 1 || x == 5) v = 0;
            f[size_t(y) * nx + x] = v;
        }
    return f;
}

TEST(Distribution2D, PdfSampleInvertRoundTrip) {
    int nx = 12, ny = 7;
    std::vector<float> f = TestImage(nx, ny);
    std::vector<Float> data;
    Distribution2D d = BuildDistribution2D(f.data(), nx, ny, data);
    SceneView s = ViewOf(data);
    double mean = 0;
    for (float v : f) mean += v;
    mean /= f.size();
    EXPECT_NEAR(d.integral, mean, 1e-4 * mean);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> U(0, 1);
    for (int i = 0; i < 3000; ++i) {
        Vec2f u(U(rng), U(rng));
        Float pdf;
        Vec2f p = SampleDistribution2D(s, d, u, &pdf);
        ASSERT_GT(pdf, 0);
        int ix = Min(int(p.x * nx), nx - 1), iy = Min(int(p.y * ny), ny - 1);
        EXPECT_NEAR(pdf, f[size_t(iy) * nx + ix] / mean, 1e-3 * pdf);
        EXPECT_NEAR(pdf, Distribution2DPDF(s, d, p), 1e-5f * pdf);
        Vec2f ui;
        ASSERT_TRUE(InvertDistribution2D(s, d, p, &ui));
        EXPECT_NEAR(ui.x, u.x, 1e-4f);
        EXPECT_NEAR(ui.y, u.y, 1e-4f);
    }
}

// Samples of the distribution of f against the density f / mean (the function, piecewise
// constant on its nx x ny cells), on a histogram of 2x2 cells per function cell.
test::Chi2Result Distribution2DChi2(const std::vector<float> &f, const std::vector<float> &g, int nx, int ny) {
    std::vector<Float> data;
    Distribution2D d = BuildDistribution2D(f.data(), nx, ny, data);
    SceneView s = ViewOf(data);
    double mean = 0;
    for (float v : g) mean += v;
    mean /= g.size();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> U(0, 1);
    auto sample = [&](test::Chi2Point *p) {
        Float pdf;
        Vec2f q = SampleDistribution2D(s, d, Vec2f(U(rng), U(rng)), &pdf);
        *p = {q.x, q.y, 0};
        return true;
    };
    auto density = [&](const test::Chi2Point &p) {
        int ix = std::min(int(p.x * nx), nx - 1), iy = std::min(int(p.y * ny), ny - 1);
        return g[size_t(iy) * nx + ix] / mean;
    };
    test::Chi2Options opts;
    opts.samples = 200000;
    return test::Chi2SampleTest(test::RectDomain(0, 1, 0, 1, 2 * nx, 2 * ny), sample, density, opts);
}

TEST(Distribution2D, ChiSquare) {
    int nx = 12, ny = 7;
    std::vector<float> f = TestImage(nx, ny);
    EXPECT_TRUE(test::Chi2Accepts(Distribution2DChi2(f, f, nx, ny)));
}

TEST(Distribution2D, ChiSquareDetectsWrongFunction) {
    // The harness must be able to fail: samples of f tested against a perturbed g.
    int nx = 12, ny = 7;
    std::vector<float> f = TestImage(nx, ny);
    std::vector<float> g = f;
    g[3] *= 1.3f;
    EXPECT_TRUE(test::Chi2Rejects(Distribution2DChi2(f, g, nx, ny)));
}

}  // namespace
}  // namespace lu
