// Tests of the chi-square harness itself (tests/support/chi2.h): p-values against tabulated
// chi-square quantiles, pooling, the rules that reject or invalidate, the power control, the
// Sidak level, and the domains' measures and parameterizations.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/chi2.h"

namespace lu::test {
namespace {

// Counts whose Pearson statistic is exactly x with k cells of expected count e each:
// all the deviation in the first two cells (+d, -d), 2 d^2 / e = x.
std::vector<double> WithStatistic(double x, int k, double e) {
    std::vector<double> o(k, e);
    double d = std::sqrt(x * e / 2);
    o[0] += d;
    o[1] -= d;
    return o;
}

TEST(Chi2Harness, PValuesMatchTabulatedQuantiles) {
    // Upper 5% and 0.1% points of the chi-square distribution (standard tables).
    struct Q { int dof; double x05, x001; };
    for (Q q : {Q{1, 3.841, 10.828}, Q{10, 18.307, 29.588}, Q{100, 124.342, 149.449}}) {
        int k = q.dof + 1;
        Chi2Result a = Chi2Counts(WithStatistic(q.x05, k, 1000), std::vector<double>(k, 1000), 0);
        Chi2Result b = Chi2Counts(WithStatistic(q.x001, k, 1000), std::vector<double>(k, 1000), 0);
        EXPECT_EQ(a.dof, q.dof);
        EXPECT_NEAR(a.chi2, q.x05, 1e-6);
        EXPECT_NEAR(a.pValue, 0.05, 2e-4) << q.dof;
        EXPECT_NEAR(b.pValue, 0.001, 1e-5) << q.dof;
    }
}

TEST(Chi2Harness, PoolsLowCells) {
    // 10 cells expecting 1 (pooled into 2 groups of 5) and 4 expecting 100: 6 cells, dof 5.
    std::vector<double> e(10, 1.0), o(10, 1.0);
    for (int i = 0; i < 4; ++i) { e.push_back(100); o.push_back(100); }
    Chi2Result r = Chi2Counts(o, e, 0);
    EXPECT_EQ(r.pooledIn, 10);
    EXPECT_EQ(r.pooledOut, 2);
    EXPECT_EQ(r.dof, 5);
    EXPECT_NEAR(r.chi2, 0, 1e-12);
    EXPECT_NEAR(r.pValue, 1, 1e-12);
    // A remainder below 5 joins the last pool: 7 cells of 1 -> one pool of 7.
    Chi2Result s = Chi2Counts({1, 1, 1, 1, 1, 1, 1, 50, 50}, {1, 1, 1, 1, 1, 1, 1, 50, 50}, 0);
    EXPECT_EQ(s.pooledOut, 1);
    EXPECT_EQ(s.dof, 2);
}

TEST(Chi2Harness, InvalidTestsFailBothWays) {
    // Too few cells after pooling: the test cannot be run, and nothing passes.
    Chi2Result few = Chi2Counts({3, 2}, {2.5, 2.5});
    EXPECT_FALSE(few.Valid());
    EXPECT_FALSE(Chi2Accepts(few));
    EXPECT_FALSE(Chi2Rejects(few));
    Chi2Result one = Chi2Counts({100}, {100});
    EXPECT_FALSE(one.Valid());
    EXPECT_FALSE(Chi2Accepts(one));
    // Non-finite or negative counts, no samples, mismatched sizes.
    EXPECT_FALSE(Chi2Counts({1, std::nan(""), 3}, {1, 2, 3}).Valid());
    EXPECT_FALSE(Chi2Counts({1, 2, 3}, {1, -2, 3}).Valid());
    EXPECT_FALSE(Chi2Counts({0, 0, 0}, {1, 2, 3}).Valid());
    EXPECT_FALSE(Chi2Counts({1, 2}, {1, 2, 3}).Valid());
}

TEST(Chi2Harness, SamplesWhereNoneAreExpectedReject) {
    std::vector<double> e = {1000, 1000, 1000, 0}, o = {1000, 1000, 999, 1};
    Chi2Result r = Chi2Counts(o, e);
    EXPECT_TRUE(r.Valid());
    EXPECT_EQ(r.pValue, 0);
    EXPECT_TRUE(Chi2Rejects(r));
}

TEST(Chi2Harness, PowerControlAndSidak) {
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> cell(0, 49);
    // 100000 uniform samples on 50 cells: accepted, and the 10% control is rejected.
    std::vector<double> o(50, 0), e(50, 2000);
    for (int i = 0; i < 100000; ++i) o[cell(rng)] += 1;
    Chi2Result r = Chi2Counts(o, e);
    EXPECT_TRUE(Chi2Accepts(r));
    EXPECT_LT(r.controlPValue, 1e-10);
    // 500 samples on the same cells cannot see a 10% error: Chi2Accepts fails for lack of power.
    std::vector<double> o2(50, 0), e2(50, 10);
    for (int i = 0; i < 500; ++i) o2[cell(rng)] += 1;
    Chi2Result weak = Chi2Counts(o2, e2);
    EXPECT_GT(weak.pValue, 1e-4);
    EXPECT_FALSE(Chi2Accepts(weak));
    EXPECT_NE(std::string(Chi2Accepts(weak).message()).find("no power"), std::string::npos);
    // Sidak: 1 - (1 - a)^(1/n).
    EXPECT_NEAR(SidakLevel(1e-4, 1), 1e-4, 1e-15);
    EXPECT_NEAR(SidakLevel(0.05, 10), 1 - std::pow(0.95, 0.1), 1e-15);
    EXPECT_LT(SidakLevel(1e-4, 22), 1e-4 / 21.9);
}

// Each domain's Jacobian integrates to its measure, and toParams inverts fromParams.
TEST(Chi2Harness, DomainsMeasureAndInvert) {
    struct D { Chi2Domain d; double measure; };
    const double pi = 3.14159265358979323846;
    D domains[] = {{SphereDomain(8, 16), 4 * pi},
                   {CapDomain({0.3, -0.2, 0.9}, 0.6, 8, 16), 2 * pi * 0.4},
                   {CapDomain({0, 0, -1}, -1, 8, 16), 4 * pi},
                   {RectDomain(-1, 3, 2, 2.5, 8, 4), 2},
                   {IntervalDomain(360, 830, 10), 470}};
    for (const D &t : domains) {
        SCOPED_TRACE(t.d.name);
        AdaptiveIntegrator2D integ([&](double u, double v) {
            double j = 0;
            t.d.fromParams(u, v, &j);
            return j;
        });
        EXPECT_NEAR(integ.Integrate(0, 1, 0, 1), t.measure, 1e-6 * t.measure);
        for (double u : {0.1, 0.5, 0.93})
            for (double v : {0.05, 0.6}) {
                double j, uu, vv;
                Chi2Point p = t.d.fromParams(u, v, &j);
                ASSERT_TRUE(t.d.toParams(p, &uu, &vv));
                EXPECT_NEAR(uu, u, 1e-9);
                if (t.d.nv > 1) {
                    EXPECT_NEAR(vv, v, 1e-9);
                }
            }
    }
    // Points off the domain are outside.
    double u, v;
    EXPECT_FALSE(CapDomain({0, 0, 1}, 0.9, 4, 4).toParams({1, 0, 0}, &u, &v));
    EXPECT_FALSE(SphereDomain().toParams({0, 0, 2}, &u, &v));  // not a unit vector
    EXPECT_FALSE(RectDomain(0, 1, 0, 1, 2, 2).toParams({1.5, 0.5, 0}, &u, &v));
}

// End to end on a known sampler: cosine-weighted directions (Malley) against cos/pi passes; the
// same samples against the uniform hemisphere pdf are rejected; samples below the hemisphere
// where the pdf is 0 are rejected; a pdf that integrates to 2 is rejected.
TEST(Chi2Harness, SampleTestEndToEnd) {
    const double pi = 3.14159265358979323846;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(0, 1);
    auto cosine = [&](Chi2Point *p) {
        double r = std::sqrt(U(rng)), phi = 2 * pi * U(rng);
        *p = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - r * r))};
        return true;
    };
    auto cosPdf = [&](const Chi2Point &w) { return w.z > 0 ? w.z / pi : 0.0; };
    auto uniformPdf = [&](const Chi2Point &w) { return w.z > 0 ? 1 / (2 * pi) : 0.0; };
    Chi2Options opts;
    opts.samples = 100000;
    EXPECT_TRUE(Chi2Accepts(Chi2SampleTest(SphereDomain(), cosine, cosPdf, opts)));
    EXPECT_TRUE(Chi2Rejects(Chi2SampleTest(SphereDomain(), cosine, uniformPdf, opts)));
    auto flipped = [&](Chi2Point *p) {
        cosine(p);
        if (U(rng) < 0.01) p->z = -p->z;
        return true;
    };
    Chi2Result below = Chi2SampleTest(SphereDomain(), flipped, cosPdf, opts);
    EXPECT_TRUE(Chi2Rejects(below));
    auto doubled = [&](const Chi2Point &w) { return 2 * cosPdf(w); };
    Chi2Result twice = Chi2SampleTest(SphereDomain(), cosine, doubled, opts);
    EXPECT_TRUE(Chi2Rejects(twice));
    EXPECT_NEAR(twice.pdfIntegral, 2, 1e-3);
    // Failed samples: a sampler that refuses 30% of its draws, with a pdf of mass 0.7, passes.
    auto lossy = [&](Chi2Point *p) { return U(rng) < 0.7 && cosine(p); };
    Chi2Result lost = Chi2SampleTest(SphereDomain(), lossy, [&](const Chi2Point &w) { return 0.7 * cosPdf(w); }, opts);
    EXPECT_TRUE(Chi2Accepts(lost));
    EXPECT_NEAR(double(lost.failed) / opts.samples, 0.3, 0.01);
    // A sliver of support between the integration nodes is found by the finer integration.
    // (The support [0.32, 0.322] falls between the nodes of the first integration of [0.3, 0.4].)
    auto sliver = [&](Chi2Point *p) { p->x = 0.32 + 0.002 * U(rng); return true; };
    Chi2Result s = Chi2SampleTest(IntervalDomain(0, 1, 10), sliver,
                                  [](const Chi2Point &p) { return p.x >= 0.32 && p.x < 0.322 ? 500.0 : 0.0; }, opts);
    EXPECT_NE(s.message.find("re-integrated"), std::string::npos) << s.message;
    EXPECT_GT(s.pdfIntegral, 0.5);
}

}  // namespace
}  // namespace lu::test
