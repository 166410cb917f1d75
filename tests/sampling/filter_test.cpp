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
    FilterData s = MakeFilter("sinc");
    EXPECT_EQ(s.kind, FilterKind::LanczosSinc);
    EXPECT_FLOAT_EQ(s.radiusX, 4.f);
    EXPECT_FLOAT_EQ(s.radiusY, 4.f);
    EXPECT_FLOAT_EQ(s.tau, 3.f);
    EXPECT_FLOAT_EQ(MakeFilter("sinc", 2.f, 3.f, -1, NAN, NAN, 2.f).tau, 2.f);
    EXPECT_THROW(MakeFilter("lanczos"), std::invalid_argument);
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
                                  MakeFilter("mitchell"),                MakeFilter("mitchell", 1.f, 3.f, -1, 0.f, 0.5f),
                                  MakeFilter("sinc"),                    MakeFilter("sinc", 2.f, 3.f, -1, NAN, NAN, 2.f)};
    for (const FilterData &f : filters) {
        double num = Integrate2D([&](double x, double y) { return double(EvalFilter(f, Vec2f(Float(x), Float(y)))); },
                                 f.radiusX, f.radiusY, 1000);
        EXPECT_NEAR(num, FilterIntegral(f), 2e-3 * std::abs(FilterIntegral(f)) + 1e-6) << int(f.kind);
    }
}

// The Lanczos-windowed sinc: 1 at the center, zero at the integers (sinc's zeros), negative
// between 1 and 2, the window's zero at tau, cut at the radius.
TEST(Filter, SincIsTheWindowedSinc) {
    FilterData s = MakeFilter("sinc");
    EXPECT_FLOAT_EQ(EvalFilter(s, Vec2f(0, 0)), 1.f);
    for (int k = 1; k <= 3; ++k) EXPECT_NEAR(EvalFilter(s, Vec2f(Float(k), 0)), 0.f, 1e-6f) << k;
    EXPECT_LT(EvalFilter(s, Vec2f(1.5f, 0)), 0.f);
    EXPECT_GT(EvalFilter(s, Vec2f(2.5f, 0)), 0.f);
    // sinc(x) sinc(x / 3) at x = 0.5: (sin(pi/2) / (pi/2)) (sin(pi/6) / (pi/6)).
    double x = 0.5, want = (std::sin(M_PI * x) / (M_PI * x)) * (std::sin(M_PI * x / 3) / (M_PI * x / 3));
    EXPECT_NEAR(EvalFilter(s, Vec2f(0.5f, 0.5f)), want * want, 1e-6);
    EXPECT_EQ(EvalFilter(s, Vec2f(4.01f, 0)), 0.f);
    // With tau = radius = 1 the window's first zero is the support's edge (pbrt-v4's sinc of 1).
    FilterData s1 = MakeFilter("sinc", 1.f, 1.f, -1, NAN, NAN, 1.f);
    EXPECT_NEAR(EvalFilter(s1, Vec2f(0.5f, 0)), Sqr(2 / M_PI), 1e-6);
}

TEST(Filter, MitchellHasNegativeLobes) {
    FilterData m = MakeFilter("mitchell");
    EXPECT_LT(EvalFilter(m, Vec2f(1.5f, 0)), 0.f);
    EXPECT_GT(EvalFilter(m, Vec2f(0, 0)), 0.f);
    EXPECT_EQ(EvalFilter(m, Vec2f(2.1f, 0)), 0.f);
}

// The chi-square test (support/chi2.h) of sampled filter positions on a 16x16 grid over the
// support against the density SampleFilter should follow: the exact |f| for box and triangle,
// the tabulated |f| (1/32-pixel cells, summed exactly per histogram cell) for gaussian and
// mitchell. weight(v) maps a table value to its sampling weight (|v|; negative tests change it).
test::Chi2Result FilterChi2(const FilterData &filter, uint64_t seed, Float (*weight)(Float) = nullptr) {
    FilterScene fs(filter);
    const FilterData &f = fs.f;
    const int hb = 16;
    RNG rng(seed);
    auto sample = [&](test::Chi2Point *p) {
        FilterSample s = SampleFilter(f, fs.view, Vec2f(rng.Uniform<float>(), rng.Uniform<float>()));
        *p = {s.p.x, s.p.y, 0};
        return true;
    };
    test::Chi2Domain domain = test::RectDomain(-f.radiusX, f.radiusX, -f.radiusY, f.radiusY, hb, hb);
    test::Chi2Options opts;
    opts.samples = 200000;
    if (f.distribution != NoIndex) {
        int nx = FilterTableSize(f.radiusX), ny = FilterTableSize(f.radiusY);
        std::vector<double> table(size_t(nx) * ny);
        double total = 0;
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                Float v = FilterTableValue(f, x, y, nx, ny);
                table[size_t(y) * nx + x] = weight ? weight(v) : std::abs(v);
                total += table[size_t(y) * nx + x];
            }
        // Table cells partly inside a histogram cell count by the overlapping fraction.
        opts.cellMass = [=](double u0, double u1, double v0, double v1) {
            double m = 0;
            for (int y = 0; y < ny; ++y) {
                double oy = std::max(0.0, std::min(v1 * ny, y + 1.0) - std::max(v0 * ny, double(y)));
                if (oy <= 0) continue;
                for (int x = 0; x < nx; ++x) {
                    double ox = std::max(0.0, std::min(u1 * nx, x + 1.0) - std::max(u0 * nx, double(x)));
                    if (ox > 0) m += ox * oy * table[size_t(y) * nx + x];
                }
            }
            return m / total;
        };
        return test::Chi2SampleTest(domain, sample, opts);
    }
    auto pdf1 = [&](double a, double r) {  // normalized |f_1D| on [-r, r]
        if (f.kind == FilterKind::Box) return 1 / (2 * r);
        return std::max(0.0, r - std::abs(a)) / (r * r);
    };
    return test::Chi2SampleTest(domain, sample, [&](const test::Chi2Point &p) {
        return pdf1(p.x, f.radiusX) * pdf1(p.y, f.radiusY);
    }, opts);
}

TEST(Filter, SampledPositionsFollowAbsFilter) {
    const FilterData filters[] = {MakeFilter("box"), MakeFilter("triangle"), MakeFilter("triangle", 1, 1.5f),
                                  MakeFilter("gaussian"), MakeFilter("mitchell"),
                                  MakeFilter("mitchell", 1.f, 2.f, -1, 0.f, 0.5f), MakeFilter("sinc"),
                                  MakeFilter("sinc", 1.5f, 2.5f, -1, NAN, NAN, 2.f)};
    for (const FilterData &f : filters) {
        SCOPED_TRACE(int(f.kind));
        bool tabulated = f.kind == FilterKind::Gaussian || f.kind == FilterKind::Mitchell ||
                         f.kind == FilterKind::LanczosSinc;
        ASSERT_EQ(tabulated, FilterScene(f).f.distribution != NoIndex);
        EXPECT_TRUE(test::Chi2Accepts(FilterChi2(f, 17), 1e-4, 6));
    }
}

// The harness rejects densities that are not the sampled one: mitchell's positive part only
// (sampling f instead of |f| would drop the negative lobes), and a flatter gaussian (|f|^0.8).
TEST(Filter, SampledPositionsRejectWrongDensities) {
    EXPECT_TRUE(test::Chi2Rejects(FilterChi2(MakeFilter("mitchell"), 17, [](Float v) { return std::max(v, Float(0)); })));
    EXPECT_TRUE(test::Chi2Rejects(FilterChi2(MakeFilter("sinc"), 17, [](Float v) { return std::max(v, Float(0)); })));
    EXPECT_TRUE(test::Chi2Rejects(FilterChi2(MakeFilter("gaussian", 1.5f, 1.5f, 0.5f), 17, [](Float v) {
        return std::pow(std::abs(v), Float(0.8));  // a flatter bell: |f|^0.8
    })));
}

TEST(Filter, WeightsAreFOverPdf) {
    for (const FilterData &filter : {MakeFilter("box"), MakeFilter("triangle"), MakeFilter("gaussian"),
                                     MakeFilter("mitchell"), MakeFilter("gaussian", 1.f, 2.f, 0.4f), MakeFilter("sinc"),
                                     MakeFilter("sinc", 2.f, 1.f, -1, NAN, NAN, 1.5f)}) {
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
            if (fc != 0) { EXPECT_EQ(s.weight < 0, fc < 0); }
            negatives += s.weight < 0;
            sum += s.weight;
            sum2 += double(s.weight) * s.weight;
        }
        if (f.kind == FilterKind::Mitchell || f.kind == FilterKind::LanczosSinc) EXPECT_GT(negatives, 0);
        else EXPECT_EQ(negatives, 0);
        // E[weight] = integral of the (tabulated) filter, close to the analytic integral.
        double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, signedIntegral, 5 * se + 1e-6);
        EXPECT_NEAR(signedIntegral, FilterIntegral(f), 1e-2 * FilterIntegral(f));
        // The film's divisor floor (FilmData::filterWeightFloor) is half that expectation for the
        // filters with negative lobes and 0 for the others.
        Float floor = FilterWeightFloor(f, fs.dists);
        if (negatives > 0) { EXPECT_NEAR(floor, 0.5 * signedIntegral, 1e-4 * signedIntegral); }
        else EXPECT_EQ(floor, 0.f);
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
