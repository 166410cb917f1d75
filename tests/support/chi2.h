// Lucerna test support: the one chi-square goodness-of-fit harness for every sampler, after
// Mitsuba 3's chi2.py: a 2D histogram of samples over a parameterization of the domain, expected
// counts by integrating the pdf over each cell, pooling of low-expectation cells, Sidak levels.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace lu::test {

// A point of a sampled domain: a direction (x, y, z), a point (x, y) of a rectangle, or x.
struct Chi2Point {
    double x = 0, y = 0, z = 0;
};

// A parameterization of a domain by (u, v) in [0,1]^2, histogrammed on nu x nv cells.
struct Chi2Domain {
    std::string name;
    int nu = 1, nv = 1;
    // (u, v) of a domain point; false if the point lies outside the domain.
    std::function<bool(const Chi2Point &, double *u, double *v)> toParams;
    // The domain point at (u, v) and the Jacobian: domain measure per unit (u, v) area.
    std::function<Chi2Point(double u, double v, double *jacobian)> fromParams;
};

// Unit directions; u = theta / pi (theta from +z), v = phi / 2 pi; measure: solid angle.
Chi2Domain SphereDomain(int nTheta = 20, int nPhi = 40);
// Unit directions within the cap {w : dot(w, axis) >= cosCap} (cosCap = -1: the whole sphere);
// u = (1 - cos theta) / (1 - cosCap), v = phi / 2 pi, so cells have equal solid angle.
Chi2Domain CapDomain(Chi2Point axis, double cosCap, int nTheta = 20, int nPhi = 24);
// Points (x, y) of [x0, x1] x [y0, y1]; measure: area.
Chi2Domain RectDomain(double x0, double x1, double y0, double y1, int nx, int ny);
// Points x of [x0, x1]; measure: length.
Chi2Domain IntervalDomain(double x0, double x1, int n);

struct Chi2Result {
    // p-value of Pearson's statistic; NaN when the test could not be run (too few cells after
    // pooling, non-finite or negative counts, no samples): such a result fails every assertion.
    double pValue = std::numeric_limits<double>::quiet_NaN();
    double chi2 = 0;
    int dof = 0;
    int pooledIn = 0, pooledOut = 0;  // low-expectation cells pooled, and the cells they became
    double observedTotal = 0, expectedTotal = 0;
    // Power control: the same observed counts against the expected counts perturbed by
    // +-controlError per cell (alternating, renormalized). Chi2Accepts requires that this wrong
    // hypothesis is rejected: a test that cannot see a controlError-sized error cannot pass.
    double controlError = 0;
    double controlPValue = std::numeric_limits<double>::quiet_NaN();
    // Chi2SampleTest only: integral of the pdf over the domain, samples drawn / failed / outside.
    double pdfIntegral = std::numeric_limits<double>::quiet_NaN();
    long samples = 0, failed = 0, outside = 0;
    std::string message;
    bool Valid() const { return std::isfinite(pValue); }
};

// Pearson's chi-square test of observed against expected counts. Cells are sorted by expected
// count; those below 5 are pooled into groups of at least 5. Observed samples in a cell with
// expected count 0 reject the hypothesis (p = 0). Fewer than 2 cells after pooling: NaN.
Chi2Result Chi2Counts(const std::vector<double> &observed, const std::vector<double> &expected,
                      double controlError = 0.1);

struct Chi2Options {
    long samples = 100000;
    double controlError = 0.1;
    // A pdf that integrates above 1 + integralTolerance over the domain is rejected.
    double integralTolerance = 1e-2;
    // true: a failed sample counts in one more cell that expects (1 - integral of the pdf) x
    // samples (a BSDF's absorbed samples). false: failed samples are set aside and only counted
    // (Chi2Result::failed), for samplers whose pdf covers points where a sample may be refused.
    bool failuresInHistogram = true;
    // Adaptive Gauss-Legendre integration of the pdf per cell (see AdaptiveIntegrator2D).
    double relTol = 2e-4;
    int minDepth = 1, maxDepth = 6;
    // When set, the exact probability of the parameter cell [u0, u1] x [v0, v1], used instead of
    // integrating the pdf (piecewise-constant densities whose steps do not align with the cells).
    std::function<double(double u0, double u1, double v0, double v1)> cellMass;
};

// Draws one sample; false when the sampler produces none (see Chi2Options::failuresInHistogram).
using Chi2Sampler = std::function<bool(Chi2Point *)>;
// Density of the samples with respect to the domain's measure.
using Chi2Pdf = std::function<double(const Chi2Point &)>;

// Histograms opts.samples samples over the domain's cells (plus a failed and an outside cell,
// the latter with expected count 0: samples outside the domain reject) and tests them against the pdf integrated over each cell.
// Cells with samples where the integral found no mass are integrated again on a finer grid
// (a sliver of support thinner than the integration nodes). Negative or NaN pdf values reject.
Chi2Result Chi2SampleTest(const Chi2Domain &domain, const Chi2Sampler &sample, const Chi2Pdf &pdf,
                          const Chi2Options &opts = {});
// The same with opts.cellMass giving the expected probabilities (no pdf).
Chi2Result Chi2SampleTest(const Chi2Domain &domain, const Chi2Sampler &sample, const Chi2Options &opts);

// Per-test level such that `tests` independent tests together have significance `level`.
double SidakLevel(double level, int tests);

// The sampler agrees with the pdf: a valid test, p >= the Sidak level, the power control rejected.
::testing::AssertionResult Chi2Accepts(const Chi2Result &r, double level = 1e-4, int tests = 1);
// The hypothesis is rejected by a valid test: p < the Sidak level (negative tests).
::testing::AssertionResult Chi2Rejects(const Chi2Result &r, double level = 1e-4, int tests = 1);

// Adaptive 2D integration of g(x, y) over a rectangle: 4x4 Gauss-Legendre per cell, compared
// against the sum over its 4 children; recursion stops at minDepth or later when they agree to
// relTol (or absTol), and at maxDepth.
class AdaptiveIntegrator2D {
  public:
    using Fn = std::function<double(double, double)>;
    AdaptiveIntegrator2D(Fn g, double relTol = 2e-4, double absTol = 1e-9, int maxDepth = 6, int minDepth = 0)
        : g_(std::move(g)), relTol_(relTol), absTol_(absTol), maxDepth_(maxDepth), minDepth_(minDepth) {}
    double Integrate(double x0, double x1, double y0, double y1);
    long evaluations = 0;

  private:
    double GL(double x0, double x1, double y0, double y1);
    double Recurse(double x0, double x1, double y0, double y1, double whole, int depth);
    Fn g_;
    double relTol_, absTol_;
    int maxDepth_, minDepth_;
};

}  // namespace lu::test
