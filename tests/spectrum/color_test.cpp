// Tests of visible-wavelength sampling and the sensor (color.h) Monte Carlo estimator.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "lucerna/spectrum/color.h"
#include "lucerna/spectra/registry.h"
#include "support/test_support.h"

namespace lu {
namespace {

double IntegratePDF(double a, double b) {
    const int n = 200;  // Simpson
    double h = (b - a) / n, s = VisibleWavelengthsPDF(Float(a)) + VisibleWavelengthsPDF(Float(b));
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * VisibleWavelengthsPDF(Float(a + i * h));
    return s * h / 3;
}

TEST(WavelengthSampling, PDFNormalized) { EXPECT_NEAR(IntegratePDF(LambdaMin, LambdaMax), 1.0, 1e-4); }

// The chi-square test (support/chi2.h) of SampleVisible's first wavelength against pdf, on 5 nm bins.
test::Chi2Result WavelengthChi2(const std::function<double(double)> &pdf) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    auto sample = [&](test::Chi2Point *p) {
        SampledWavelengths w = SampledWavelengths::SampleVisible(u(rng));
        // SampleVisible evaluates the pdf from y (no exponential): equal up to float rounding.
        Float ref = VisibleWavelengthsPDF(w.lambda[0]);
        EXPECT_NEAR(w.pdf[0], ref, 2e-6 * ref);
        p->x = w.lambda[0];
        return true;
    };
    test::Chi2Options opts;
    opts.samples = 200000;
    return test::Chi2SampleTest(test::IntervalDomain(LambdaMin, LambdaMax, 94), sample,
                                [&](const test::Chi2Point &p) { return pdf(p.x); }, opts);
}

TEST(WavelengthSampling, ChiSquareAgainstPDF) {
    EXPECT_TRUE(test::Chi2Accepts(WavelengthChi2([](double l) { return double(VisibleWavelengthsPDF(Float(l))); })));
    // A pdf centred 10 nm off (pbrt-v4's shape around 548 nm instead of 538 nm) is rejected.
    EXPECT_TRUE(test::Chi2Rejects(WavelengthChi2([](double l) {
        double e = std::exp(0.0144 * (l - 548));
        return 0.0039398042 * 4 * e / ((1 + e) * (1 + e));
    })));
}

TEST(WavelengthSampling, Stratified) {
    SampledWavelengths w = SampledWavelengths::SampleVisible(0.1f);
    for (int i = 0; i < NSpectrumSamples; ++i) {
        Float up = 0.1f + Float(i) / NSpectrumSamples;
        EXPECT_FLOAT_EQ(w.lambda[i], SampleVisibleWavelength(up > 1 ? up - 1 : up));
    }
}

TEST(Color, DenseNearestLookup) {
    SpectrumRegistry reg;
    const Float *y = reg.Tables().data + TableCIE_Y * TabulatedSpectrumSize;
    EXPECT_EQ(LookupDenseNearest(y, 555.4f), y[555 - 360]);
    EXPECT_EQ(LookupDenseNearest(y, 555.6f), y[556 - 360]);
    EXPECT_EQ(LookupDenseNearest(y, 359.4f), 0.f);
    EXPECT_EQ(LookupDenseNearest(y, 830.4f), y[470]);
    EXPECT_EQ(LookupDenseNearest(y, 830.6f), 0.f);
}

// The sensor estimator with visible-importance wavelengths converges to the XYZ of a smooth
// spectrum (sum over 1 nm of cmf * S, pbrt-v4's InnerProduct).
TEST(Color, SensorXYZConverges) {
    SpectrumRegistry reg;
    Spectrum s = reg.FromRGB({0.8f, 0.35f, 0.1f}, SpectrumType::Illuminant);
    s.scale /= reg.ToPhotometric(s);
    SpectrumTables tab = reg.Tables();
    double exact[3] = {0, 0, 0};
    for (int i = 0; i < TabulatedSpectrumSize; ++i)
        for (int c = 0; c < 3; ++c) exact[c] += tab.data[c * TabulatedSpectrumSize + i] * reg.Eval(s, LambdaMin + i);

    const int n = 100000;
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int k = 0; k < n; ++k) {
        SampledWavelengths w = SampledWavelengths::SampleVisible(u(rng));
        Float xyz[3];
        SensorXYZ(SampleSpectrum(s, w, tab), w, tab, 1.f, xyz);
        for (int c = 0; c < 3; ++c) {
            sum[c] += xyz[c];
            sum2[c] += double(xyz[c]) * xyz[c];
        }
    }
    for (int c = 0; c < 3; ++c) {
        double mean = sum[c] / n, var = sum2[c] / n - mean * mean, se = std::sqrt(var / n);
        // 5 standard errors plus the tiny bias of nearest-nm lookups vs. the 1 nm sum.
        EXPECT_NEAR(mean, exact[c], 5 * se + 2e-3 * exact[c]) << "channel " << c << " se " << se;
        EXPECT_LT(se, 0.01 * exact[c]);
    }
    // And imagingRatio scales linearly; terminated secondaries still count in the mean.
    SampledWavelengths w = SampledWavelengths::SampleVisible(0.3f);
    Float a[3], b[3];
    SensorXYZ(SampleSpectrum(s, w, tab), w, tab, 1.f, a);
    SensorXYZ(SampleSpectrum(s, w, tab), w, tab, 2.5f, b);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], 2.5f * a[c], 1e-5f * std::abs(a[c]) + 1e-7f);
    w.TerminateSecondary();
    SensorXYZ(SampleSpectrum(s, w, tab), w, tab, 1.f, b);
    Float v = EvalSpectrum(s, w.lambda[0], tab) / w.pdf[0];
    EXPECT_NEAR(b[1], LookupDenseNearest(tab.data + TabulatedSpectrumSize, w.lambda[0]) * v / NSpectrumSamples,
                1e-5f * std::abs(b[1]) + 1e-7f);
}

// pbrt-v4's headline invariant: an rgb (1,1,1) area light, scaled by 1/SpectrumToPhotometric,
// seen directly renders as sRGB (1,1,1).
TEST(Color, WhiteLightRendersWhite) {
    SpectrumRegistry reg;
    Spectrum L = reg.FromRGB({1.f, 1.f, 1.f}, SpectrumType::Illuminant);
    L.scale /= reg.ToPhotometric(L);
    SpectrumTables tab = reg.Tables();
    const int n = 1 << 16;
    double rgb[3] = {0, 0, 0};
    for (int k = 0; k < n; ++k) {  // stratified primary samples
        SampledWavelengths w = SampledWavelengths::SampleVisible((k + 0.5f) / n);
        Float out[3];
        SensorLinearSRGB(SampleSpectrum(L, w, tab), w, tab, 1.f, out);
        for (int c = 0; c < 3; ++c) rgb[c] += out[c];
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c] / n, 1.0, 2e-3) << c;
}

}  // namespace
}  // namespace lu
