// Tests of SpectrumRegistry against pbrt-v4's colorimetric conventions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lucerna/spectrum/color.h"
#include "lucerna/spectra/registry.h"
#include "lucerna/spectrum/rgb_to_spectrum.h"

namespace lu {
namespace {

Spectrum TableSpectrum(uint32_t table) {
    Spectrum s;
    s.kind = SpectrumKind::Tabulated;
    s.scale = 1;
    s.table = table;
    return s;
}

TEST(SpectrumRegistry, CIEYIntegral) {
    SpectrumRegistry reg;
    SpectrumTables tab = reg.Tables();
    ASSERT_GE(tab.count, 4u);
    float sum = 0;  // pbrt-v4 sums in Float
    for (int i = 0; i < TabulatedSpectrumSize; ++i) sum += tab.data[TableCIE_Y * TabulatedSpectrumSize + i];
    EXPECT_NEAR(sum, CIE_Y_integral, 1e-4);
    // Peak of ybar is 1 at 555 nm; xbar peaks near 599 nm, zbar near 446 nm.
    EXPECT_FLOAT_EQ(tab.data[TableCIE_Y * TabulatedSpectrumSize + 555 - 360], 1.0f);
    EXPECT_NEAR(tab.data[TableCIE_X * TabulatedSpectrumSize + 599 - 360], 1.0629096, 1e-6);
    EXPECT_NEAR(tab.data[TableCIE_Z * TabulatedSpectrumSize + 446 - 360], 1.7829682, 1e-6);
}

TEST(SpectrumRegistry, D65Normalization) {
    SpectrumRegistry reg;
    // pbrt-v4 normalizes named illuminants so that sum_lambda Y(lambda) D65(lambda) = CIE_Y_integral.
    EXPECT_NEAR(reg.ToPhotometric(TableSpectrum(TableD65)), CIE_Y_integral, 1e-3);
    XYZ w = reg.ToXYZ(TableSpectrum(TableD65));
    EXPECT_NEAR(w[1], 1.0, 1e-5);
    EXPECT_NEAR(w[0] / (w[0] + w[1] + w[2]), 0.3127, 2e-4);
    EXPECT_NEAR(w[1] / (w[0] + w[1] + w[2]), 0.3290, 2e-4);
    // The named D65 is the same table.
    std::optional<Spectrum> named = reg.Named("stdillum-D65");
    ASSERT_TRUE(named);
    EXPECT_EQ(named->table, TableD65);
}

TEST(SpectrumRegistry, D65WhiteIsSRGBOne) {
    SpectrumRegistry reg;
    RGB rgb = XYZToRGB(reg.ToXYZ(TableSpectrum(TableD65)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 1.0, 1e-3) << c;
    // The device-side matrix in color.h agrees with the one computed here.
    for (int c = 0; c < 3; ++c) {
        XYZ e{0, 0, 0};
        e[c] = 1;
        RGB ref = XYZToRGB(e);
        Float in[3] = {e[0], e[1], e[2]}, out[3];
        XYZToLinearSRGB(in, out);
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(out[r], ref[r], 1e-6);
        RGB e2{0, 0, 0};
        e2[c] = 1;
        XYZ ref2 = RGBToXYZ(e2);
        Float in2[3] = {e2[0], e2[1], e2[2]}, out2[3];
        LinearSRGBToXYZ(in2, out2);
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(out2[r], ref2[r], 1e-6);
    }
    // Round trip.
    RGB x{0.2f, 0.7f, 0.4f};
    RGB y = XYZToRGB(RGBToXYZ(x));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-6);
}

// Reflectance spectrum under D65 -> XYZ -> sRGB reproduces the albedo RGB it came from.
TEST(SpectrumRegistry, AlbedoRoundTrip) {
    SpectrumRegistry reg;
    SpectrumTables tab = reg.Tables();
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> u(0.02f, 0.98f);
    double maxErr = 0;
    for (int n = 0; n < 200; ++n) {
        RGB rgb{u(rng), u(rng), u(rng)};
        Spectrum s = reg.FromRGB(rgb, SpectrumType::Albedo);
        ASSERT_EQ(s.kind, SpectrumKind::RGBAlbedo);
        double xyz[3] = {0, 0, 0};
        for (int i = 0; i < TabulatedSpectrumSize; ++i) {
            Float lambda = LambdaMin + i;
            double v = reg.Eval(s, lambda) * tab.data[TableD65 * TabulatedSpectrumSize + i];
            ASSERT_GE(reg.Eval(s, lambda), 0.f);
            ASSERT_LE(reg.Eval(s, lambda), 1.f);
            for (int c = 0; c < 3; ++c) xyz[c] += v * tab.data[c * TabulatedSpectrumSize + i];
        }
        RGB back = XYZToRGB({Float(xyz[0] / CIE_Y_integral), Float(xyz[1] / CIE_Y_integral),
                             Float(xyz[2] / CIE_Y_integral)});
        for (int c = 0; c < 3; ++c) maxErr = std::max(maxErr, std::abs(double(back[c]) - rgb[c]));
    }
    // The table is fitted with 5 nm data and Simpson quadrature; 1 nm evaluation differs slightly.
    EXPECT_LT(maxErr, 1e-2);
}

TEST(SpectrumRegistry, UniformRGBIsConstant) {
    SpectrumRegistry reg;
    for (float v : {0.f, 0.25f, 0.5f, 0.8f, 1.f}) {
        Spectrum s = reg.FromRGB({v, v, v}, SpectrumType::Albedo);
        for (Float lambda : {360.f, 500.f, 700.f, 830.f}) EXPECT_NEAR(reg.Eval(s, lambda), v, 1e-6) << v;
    }
    // Albedo clamps to [0, 1].
    Spectrum c = reg.FromRGB({2.f, 2.f, 2.f}, SpectrumType::Albedo);
    EXPECT_FLOAT_EQ(reg.Eval(c, 550), 1.f);
}

TEST(SpectrumRegistry, UnboundedScale) {
    SpectrumRegistry reg;
    Spectrum s = reg.FromRGB({3.f, 1.5f, 0.3f}, SpectrumType::Unbounded);
    EXPECT_EQ(s.kind, SpectrumKind::RGBUnbounded);
    EXPECT_FLOAT_EQ(s.scale, 6.f);
    // Equal to 2 max times the albedo spectrum of rgb / (2 max).
    Spectrum a = reg.FromRGB({0.5f, 0.25f, 0.05f}, SpectrumType::Albedo);
    for (Float lambda : {400.f, 550.f, 650.f}) EXPECT_NEAR(reg.Eval(s, lambda), 6 * reg.Eval(a, lambda), 1e-5);
    Spectrum zero = reg.FromRGB({0.f, 0.f, 0.f}, SpectrumType::Unbounded);
    EXPECT_EQ(reg.Eval(zero, 550), 0.f);
}

// An rgb (1,1,1) illuminant scaled by 1 / SpectrumToPhotometric has luminance Y = 1 and is
// sRGB white: pbrt-v4's "diffuse area light L = (1,1,1) renders as (1,1,1)".
TEST(SpectrumRegistry, IlluminantPhotometricScale) {
    SpectrumRegistry reg;
    Spectrum L = reg.FromRGB({1.f, 1.f, 1.f}, SpectrumType::Illuminant);
    ASSERT_EQ(L.kind, SpectrumKind::RGBIlluminant);
    EXPECT_EQ(L.table, TableD65);
    Float photometric = reg.ToPhotometric(L);
    EXPECT_NEAR(photometric, CIE_Y_integral, 1e-2);
    L.scale /= photometric;
    // Sensor Y (no 1/CIE_Y_integral) = sum ybar * L.
    SpectrumTables tab = reg.Tables();
    double sensor[3] = {0, 0, 0};
    for (int i = 0; i < TabulatedSpectrumSize; ++i)
        for (int c = 0; c < 3; ++c) sensor[c] += tab.data[c * TabulatedSpectrumSize + i] * reg.Eval(L, LambdaMin + i);
    EXPECT_NEAR(sensor[1], 1.0, 1e-4);
    RGB rgb = XYZToRGB({Float(sensor[0]), Float(sensor[1]), Float(sensor[2])});
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 1.0, 1e-3);
    // ToPhotometric of an RGB illuminant ignores the RGB multiplier (pbrt-v4).
    Spectrum red = reg.FromRGB({4.f, 0.5f, 0.5f}, SpectrumType::Illuminant);
    EXPECT_NEAR(reg.ToPhotometric(red), photometric, 1e-3);
}

TEST(SpectrumRegistry, Blackbody) {
    SpectrumRegistry reg;
    for (Float T : {2700.f, 5500.f, 6500.f}) {
        Spectrum s = reg.Blackbody(T);
        Float peakLambda = 2.8977721e-3f / T * 1e9f;
        EXPECT_NEAR(reg.Eval(s, peakLambda), 1.f, 1e-5);
        Float m = 0;
        for (Float l = 200; l < 3000; l += 0.5f) m = std::max(m, reg.Eval(s, l));
        EXPECT_NEAR(m, 1.f, 1e-4) << T;
    }
    // Hotter is bluer.
    XYZ warm = reg.ToXYZ(reg.Blackbody(2700)), cool = reg.ToXYZ(reg.Blackbody(9000));
    EXPECT_GT(warm[0] / warm[2], cool[0] / cool[2]);
    EXPECT_EQ(reg.Eval(reg.Blackbody(0), 500), 0.f);
}

TEST(SpectrumRegistry, FromPiecewise) {
    SpectrumRegistry reg;
    std::optional<Spectrum> s = reg.FromPiecewise({400, 500, 600.5}, {1, 3, 2});
    ASSERT_TRUE(s);
    EXPECT_EQ(s->kind, SpectrumKind::Tabulated);
    EXPECT_FLOAT_EQ(reg.Eval(*s, 400), 1);
    EXPECT_FLOAT_EQ(reg.Eval(*s, 450), 2);
    EXPECT_FLOAT_EQ(reg.Eval(*s, 500), 3);
    EXPECT_NEAR(reg.Eval(*s, 600), 3 - 100.0 / 100.5, 1e-5);
    EXPECT_EQ(reg.Eval(*s, 399), 0);  // pbrt-v4: zero outside the given range
    EXPECT_EQ(reg.Eval(*s, 650), 0);
    EXPECT_FALSE(reg.FromPiecewise({500, 400}, {1, 2}));
    EXPECT_FALSE(reg.FromPiecewise({400, 500}, {1}));
    EXPECT_FALSE(reg.FromPiecewise({}, {}));
}

TEST(SpectrumRegistry, NamedIlluminants) {
    SpectrumRegistry reg;
    std::vector<std::string> names = SpectrumRegistry::NamedSpectrumNames();
    for (const char *n : {"stdillum-A", "stdillum-D50", "stdillum-D65", "stdillum-F1", "stdillum-F12",
                          "illum-acesD60"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
        std::optional<Spectrum> s = reg.Named(n);
        ASSERT_TRUE(s) << n;
        EXPECT_NEAR(reg.ToPhotometric(*s), CIE_Y_integral, 1e-2) << n;
    }
    EXPECT_FALSE(reg.Named("no-such-spectrum"));
    // Illuminant A is much redder than D65.
    XYZ a = reg.ToXYZ(*reg.Named("stdillum-A"));
    EXPECT_NEAR(a[0] / (a[0] + a[1] + a[2]), 0.4476, 1e-3);
    // Repeated lookups reuse the table.
    EXPECT_EQ(reg.Named("stdillum-F1")->table, reg.Named("stdillum-F1")->table);
}

}  // namespace
}  // namespace lu

namespace lu {
namespace {

TEST(SpectrumRegistry, NamedMeasured) {
    SpectrumRegistry reg;
    std::vector<std::string> names = SpectrumRegistry::NamedSpectrumNames();
    for (const char *m : {"Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"})
        for (const char *q : {"-eta", "-k"}) {
            std::string n = std::string("metal-") + m + q;
            EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
            EXPECT_TRUE(reg.Named(n)) << n;
        }
    for (const char *g : {"glass-BK7", "glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5", "glass-F10", "glass-F11"})
        EXPECT_TRUE(reg.Named(g)) << g;
    // Schott N-BK7: n_d = 1.5168 at the helium d line (587.56 nm).
    EXPECT_NEAR(reg.Eval(*reg.Named("glass-BK7"), 587.56f), 1.5168f, 2e-4);
    // Copper: eta ~ 0.27, k ~ 3.24 at 620 nm; gold eta ~ 0.194, k ~ 3.06 at 620 nm.
    EXPECT_NEAR(reg.Eval(*reg.Named("metal-Cu-eta"), 619.920898f), 0.272f, 1e-3);
    EXPECT_NEAR(reg.Eval(*reg.Named("metal-Cu-k"), 619.920898f), 3.24f, 1e-2);
    EXPECT_NEAR(reg.Eval(*reg.Named("metal-Au-eta"), 619.920898f), 0.194f, 1e-3);
    EXPECT_NEAR(reg.Eval(*reg.Named("metal-CuZn-k"), 600.f), 3.253f, 1e-4);
    // Constant extension beyond the data (pbrt-v4 FromInterleaved): MgO ends at 767.68 nm.
    EXPECT_NEAR(reg.Eval(*reg.Named("metal-MgO-eta"), 830.f), 1.72872f, 1e-5);
    // Measured spectra are not normalized.
    EXPECT_GT(reg.Eval(*reg.Named("metal-Al-k"), 500.f), 5.f);
}

}  // namespace
}  // namespace lu

namespace lu {
namespace {

TEST(RGBToSpectrumTable, EmbeddedTable) {
    RGBToSpectrumTableData t = SRGBToSpectrumTable();
    ASSERT_EQ(t.res, 64u);
    EXPECT_EQ(t.zNodes[0], 0.f);
    EXPECT_EQ(t.zNodes[63], 1.f);
    for (uint32_t k = 1; k < t.res; ++k) EXPECT_LT(t.zNodes[k - 1], t.zNodes[k]);
    // smoothstep(smoothstep(k / 63)) node spacing.
    auto ss = [](float x) { return x * x * (3 - 2 * x); };
    EXPECT_FLOAT_EQ(t.zNodes[21], ss(ss(21.f / 63.f)));
    size_t n = size_t(3) * t.res * t.res * t.res * 3;
    for (size_t i = 0; i < n; ++i) ASSERT_TRUE(std::isfinite(t.coeffs[i])) << i;
}

// Saturated and dark colors: the fitted reflectance still reproduces the color reasonably and
// stays in [0, 1]; the lookup is continuous across the max-component boundary.
TEST(RGBToSpectrumTable, HardColorsAndContinuity) {
    SpectrumRegistry reg;
    RGBToSpectrumTableData t = SRGBToSpectrumTable();
    auto xyzOf = [&](const Spectrum &s) {
        double xyz[3] = {0, 0, 0};
        const Float *d65 = reg.Tables().data + TableD65 * TabulatedSpectrumSize;
        for (int i = 0; i < TabulatedSpectrumSize; ++i)
            for (int c = 0; c < 3; ++c)
                xyz[c] += reg.Tables().data[c * TabulatedSpectrumSize + i] * reg.Eval(s, LambdaMin + i) * d65[i];
        return XYZToRGB({Float(xyz[0] / CIE_Y_integral), Float(xyz[1] / CIE_Y_integral), Float(xyz[2] / CIE_Y_integral)});
    };
    for (RGB rgb : {RGB{0.9f, 0.1f, 0.1f}, RGB{0.1f, 0.8f, 0.1f}, RGB{0.05f, 0.05f, 0.7f}, RGB{0.01f, 0.02f, 0.005f}}) {
        RGB back = xyzOf(reg.FromRGB(rgb, SpectrumType::Albedo));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], rgb[c], 0.02) << c;
    }
    Float a[3], b[3];
    RGBToSigmoidCoeffs(t.coeffs, t.zNodes, t.res, 0.6f, 0.6f - 1e-6f, 0.3f, a);
    RGBToSigmoidCoeffs(t.coeffs, t.zNodes, t.res, 0.6f - 1e-6f, 0.6f, 0.3f, b);
    for (Float lambda : {420.f, 550.f, 680.f})
        EXPECT_NEAR(SigmoidPolynomial(a, lambda), SigmoidPolynomial(b, lambda), 1e-3);
}

}  // namespace
}  // namespace lu
