// Tests of the pixel filters (film/filter.h): analytic integrals, importance-sampled positions
// (chi-square against the sampled density) and weights (f / pdf, signed for mitchell).
#include <gtest/gtest.h>

#include <cmath>

#include "lucerna/scene/camera_build.h"
#include "lucerna/sampling/rng.h"
#include "support/test_support.h"

using namespace lu;

namespace {

struct FilterScene {
    FilterData f;
    std::vector<Distribution2D> dists;
    std::vector<Float> distData;
    SceneView view;
    explicit FilterScene(FilterData filter) : f(filter) {
        BuildFilterDistribution(f, dists, distData);
        view.distributions2D = {dists.data(), uint32_t(dists.size())};
        view.distData = {distData.data(), uint32_t(distData.size())};
    }
};

// Midpoint-rule integral of g over [-rx, rx] x [-ry, ry] with n x n cells.
template <typename G>
double Integrate2D(G g, double rx, double ry, int n) {
    double sum = 0, dx = 2 * rx / n, dy = 2 * ry / n;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) sum += g(-rx + (i + 0.5) * dx, -ry + (j + 0.5) * dy);
    return sum * dx * dy;
}

}  // namespace

TEST(Filter, MakeFilterDefaults) {
    FilterData g = MakeFilter("gaussian");
    EXPECT_EQ(g.kind, FilterKind::Gaussian);
    EXPECT_FLOAT_EQ(g.radiusX, 1.5f);
    EXPECT_FLOAT_EQ(g.sigma, 0.5f);
    EXPECT_FLOAT_EQ(MakeFilter("box").radiusY, 0.5f);
    EXPECT_FLOAT_EQ(MakeFilter("triangle").radiusX, 2.f);
    FilterData m = MakeFilter("mitchell");
    EXPECT_FLOAT_EQ(m.radiusX, 2.f);
    EXPECT_FLOAT_EQ(m.B, 1.f / 3);
    EXPECT_FLOAT_EQ(m.C, 1.f / 3);
    FilterData m2 = MakeFilter("mitchell", 1.5f, 2.5f, -1, 0.f, 0.5f);
    EXPECT_FLOAT_EQ(m2.radiusX, 1.5f);
    EXPECT_FLOAT_EQ(m2.radiusY, 2.5f);
    EXPECT_FLOAT_EQ(m2.B, 0.f);
    EXPECT_FLOAT_EQ(m2.C, 0.5f);
    EXPECT_THROW(MakeFilter("sinc"), std::invalid_argument);
}

TEST(Filter, IntegralsMatchAnalyticValues) {
    // Closed forms: box 4 rx ry; triangle rx^2 ry^2; mitchell rx ry / 4 (any B, C with the
    // normalization 6 - 2B ... of Mitchell-Netravali); gaussian from erf.
    EXPECT_NEAR(FilterIntegral(MakeFilter("box")), 1.0, 1e-6);
    EXPECT_NEAR(FilterIntegral(MakeFilter("triangle", 1, 1)), 1.0, 1e-6);
    EXPECT_NEAR(FilterIntegral(MakeFilter("triangle")), 16.0, 1e-5);
    EXPECT_NEAR(FilterIntegral(MakeFilter("mitchell")), 1.0, 1e-6);
    double s = 0.5, r = 1.5;
    double g1 = std::erf(r / (s * std::sqrt(2.0))) - 2 * r * std::exp(-r * r / (2 * s * s)) / std::sqrt(2 * M_PI * s * s);
    EXPECT_NEAR(FilterIntegral(MakeFilter("gaussian")), g1 * g1, 1e-5);
    // And numerically, for several parameter sets.
    const FilterData filters[] = {MakeFilter("box", 0.7f, 1.2f),        MakeFilter("triangle", 1.f, 2.f),
                                  MakeFilter("gaussian"),                MakeFilter("gaussian", 2.f, 1.f, 0.8f),
                                  MakeFilter("mitchell"),                MakeFilter("mitchell", 1.f, 3.f, -1, 0.f, 0.5f)};
    for (const FilterData &f : filters) {
        double num = Integrate2D([&](double x, double y) { return double(EvalFilter(f, Vec2f(Float(x), Float(y)))); },
                                 f.radiusX, f.radiusY, 1000);
        EXPECT_NEAR(num, FilterIntegral(f), 2e-3 * std::abs(FilterIntegral(f)) + 1e-6) << int(f.kind);
    }
}

TEST(Filter, MitchellHasNegativeLobes) {
    FilterData m = MakeFilter("mitchell");
    EXPECT_LT(EvalFilter(m, Vec2f(1.5f, 0)), 0.f);
    EXPECT_GT(EvalFilter(m, Vec2f(0, 0)), 0.f);
    EXPECT_EQ(EvalFilter(m, Vec2f(2.1f, 0)), 0.f);
}

TEST(Filter, SampledPositionsFollowAbsFilter) {
    // Histogram of sampled positions on a 16x16 grid over the support against the sampled
    // density: the exact |f| for box and triangle, the tabulated |f| (1/32-pixel cells) for
    // gaussian and mitchell; 16x16 histogram cells are unions of whole table cells.
    const FilterData filters[] = {MakeFilter("box"), MakeFilter("triangle"), MakeFilter("triangle", 1, 1.5f),
                                  MakeFilter("gaussian"), MakeFilter("mitchell"),
                                  MakeFilter("mitchell", 1.f, 2.f, -1, 0.f, 0.5f)};
    const int nFilters = 6, hb = 16, n = 200000;
    const double alpha = 1 - std::pow(1 - 1e-4, 1.0 / nFilters);
    for (const FilterData &filter : filters) {
        FilterScene fs(filter);
        const FilterData &f = fs.f;
        bool tabulated = f.kind == FilterKind::Gaussian || f.kind == FilterKind::Mitchell;
        ASSERT_EQ(tabulated, f.distribution != NoIndex);
        std::vector<double> expected(hb * hb, 0), observed(hb * hb, 0);
        if (tabulated) {
            int nx = FilterTableSize(f.radiusX), ny = FilterTableSize(f.radiusY);
            ASSERT_EQ(nx % hb, 0);
            ASSERT_EQ(ny % hb, 0);
            double total = 0;
            for (int y = 0; y < ny; ++y)
                for (int x = 0; x < nx; ++x) {
                    double v = std::abs(FilterTableValue(f, x, y, nx, ny));
                    expected[(y / (ny / hb)) * hb + x / (nx / hb)] += v;
                    total += v;
                }
            for (double &e : expected) e *= n / total;
        } else {
            auto cdf1 = [&](double a, double r) {  // integral of |f_1D| from -r to a, normalized
                if (f.kind == FilterKind::Box) return (a + r) / (2 * r);
                return a < 0 ? 0.5 * (r + a) * (r + a) / (r * r) : 1 - 0.5 * (r - a) * (r - a) / (r * r);
            };
            for (int y = 0; y < hb; ++y)
                for (int x = 0; x < hb; ++x) {
                    double x0 = -f.radiusX + 2.0 * f.radiusX * x / hb, x1 = x0 + 2.0 * f.radiusX / hb;
                    double y0 = -f.radiusY + 2.0 * f.radiusY * y / hb, y1 = y0 + 2.0 * f.radiusY / hb;
                    expected[y * hb + x] = n * (cdf1(x1, f.radiusX) - cdf1(x0, f.radiusX)) *
                                           (cdf1(y1, f.radiusY) - cdf1(y0, f.radiusY));
                }
        }
        RNG rng(17);
        for (int i = 0; i < n; ++i) {
            Vec2f u(rng.Uniform<float>(), rng.Uniform<float>());
            FilterSample s = SampleFilter(f, fs.view, u);
            ASSERT_LE(std::abs(s.p.x), f.radiusX);
            ASSERT_LE(std::abs(s.p.y), f.radiusY);
            int ix = std::min(int((s.p.x + f.radiusX) / (2 * f.radiusX) * hb), hb - 1);
            int iy = std::min(int((s.p.y + f.radiusY) / (2 * f.radiusY) * hb), hb - 1);
            observed[iy * hb + ix] += 1;
        }
        std::string msg;
        EXPECT_GT(test::ChiSquarePValue(observed, expected, &msg), alpha) << "filter " << int(f.kind) << ": " << msg;
    }
}

TEST(Filter, WeightsAreFOverPdf) {
    for (const FilterData &filter : {MakeFilter("box"), MakeFilter("triangle"), MakeFilter("gaussian"),
                                     MakeFilter("mitchell"), MakeFilter("gaussian", 1.f, 2.f, 0.4f)}) {
        FilterScene fs(filter);
        const FilterData &f = fs.f;
        RNG rng(3);
        if (f.distribution == NoIndex) {
            for (int i = 0; i < 1000; ++i) {
                FilterSample s = SampleFilter(f, fs.view, Vec2f(rng.Uniform<float>(), rng.Uniform<float>()));
                EXPECT_EQ(s.weight, 1.f);
            }
            continue;
        }
        const Distribution2D &d = fs.dists[f.distribution];
        int nx = int(d.nx), ny = int(d.ny);
        double absIntegral = 0, signedIntegral = 0, cellArea = 4.0 * f.radiusX * f.radiusY / (nx * ny);
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                double v = FilterTableValue(f, x, y, nx, ny);
                absIntegral += std::abs(v) * cellArea;
                signedIntegral += v * cellArea;
            }
        int negatives = 0;
        const int n = 100000;
        double sum = 0, sum2 = 0;
        for (int i = 0; i < n; ++i) {
            FilterSample s = SampleFilter(f, fs.view, Vec2f(rng.Uniform<float>(), rng.Uniform<float>()));
            // weight = f(cell) / pdf with pdf = |f(cell)| / integral |f|: magnitude = integral |f|,
            // sign of f at the cell center.
            int ix = std::min(int((s.p.x + f.radiusX) / (2 * f.radiusX) * nx), nx - 1);
            int iy = std::min(int((s.p.y + f.radiusY) / (2 * f.radiusY) * ny), ny - 1);
            Float fc = FilterTableValue(f, ix, iy, nx, ny);
            EXPECT_NEAR(std::abs(s.weight), absIntegral, 1e-3 * absIntegral);
            if (fc != 0) EXPECT_EQ(s.weight < 0, fc < 0);
            negatives += s.weight < 0;
            sum += s.weight;
            sum2 += double(s.weight) * s.weight;
        }
        if (f.kind == FilterKind::Mitchell) EXPECT_GT(negatives, 0);
        else EXPECT_EQ(negatives, 0);
        // E[weight] = integral of the (tabulated) filter, close to the analytic integral.
        double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, signedIntegral, 5 * se + 1e-6);
        EXPECT_NEAR(signedIntegral, FilterIntegral(f), 1e-2 * FilterIntegral(f));
    }
}

TEST(Filter, WithoutTableFallsBackToUniform) {
    FilterData g = MakeFilter("gaussian");  // no BuildFilterDistribution
    SceneView empty;
    RNG rng(8);
    double sum = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) sum += SampleFilter(g, empty, Vec2f(rng.Uniform<float>(), rng.Uniform<float>())).weight;
    EXPECT_NEAR(sum / n, FilterIntegral(g), 0.02 * FilterIntegral(g));
}
