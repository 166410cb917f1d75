// Tests of pbrt-v4's four RGB color spaces (spectra/registry.h RGBColorSpace): the matrices
// against published values and against their defining properties (each primary maps to its xy,
// white to the illuminant's white), and the round trip RGB -> sigmoid spectrum -> XYZ -> RGB
// through each space's generated table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "lucerna/spectra/cie_data.h"
#include "lucerna/spectra/registry.h"
#include "lucerna/spectrum/rgb_to_spectrum.h"

namespace lu {
namespace {

constexpr ColorSpaceId kAll[] = {ColorSpaceId::SRGB, ColorSpaceId::DCI_P3, ColorSpaceId::Rec2020,
                                 ColorSpaceId::ACES2065_1};

// XYZ (Y = 1) of a named 5 nm illuminant, summed here at 1 nm from the raw tables (linear
// between samples), independently of the registry.
std::array<double, 3> IlluminantWhite(const char *name) {
    const data::UniformSpectrumData *il = nullptr;
    for (const auto &d : data::Illuminants)
        if (std::string_view(d.name) == name) il = &d;
    EXPECT_NE(il, nullptr) << name;
    double W[3] = {0, 0, 0};
    for (int i = 0; i < data::CIESamples; ++i) {
        double x = (360.0 + i - il->lambda0) / il->step;
        // The last sample (830 nm) is the table's last value: no interpolation past its end.
        int k = std::clamp(int(x), 0, il->n - 2);
        double v = il->values[k] + (x - k) * (il->values[k + 1] - il->values[k]);
        W[0] += data::CIE_X[i] * v;
        W[1] += data::CIE_Y[i] * v;
        W[2] += data::CIE_Z[i] * v;
    }
    return {W[0] / W[1], 1.0, W[2] / W[1]};
}

TEST(ColorSpace, NamesAsPbrtV4) {
    EXPECT_EQ(ColorSpaceFromName("srgb"), ColorSpaceId::SRGB);
    EXPECT_EQ(ColorSpaceFromName("rec2020"), ColorSpaceId::Rec2020);
    EXPECT_EQ(ColorSpaceFromName("ACES2065-1"), ColorSpaceId::ACES2065_1);  // GetNamed lower-cases
    EXPECT_EQ(ColorSpaceFromName("dci-p3"), ColorSpaceId::DCI_P3);
    EXPECT_FALSE(ColorSpaceFromName("adobe"));
    for (ColorSpaceId id : kAll) EXPECT_EQ(ColorSpaceFromName(GetRGBColorSpace(id).name), id);
}

// Each primary's column of XYZFromRGB has that primary's chromaticity; RGB (1, 1, 1) is the
// illuminant's XYZ (Y = 1); the two matrices are inverse.
TEST(ColorSpace, PrimariesAndWhiteMapAsDefined) {
    for (ColorSpaceId id : kAll) {
        const RGBColorSpace &cs = GetRGBColorSpace(id);
        SCOPED_TRACE(cs.name);
        const std::array<double, 2> prim[3] = {cs.r, cs.g, cs.b};
        for (int c = 0; c < 3; ++c) {
            double X = cs.xyzFromRGB[0][c], Y = cs.xyzFromRGB[1][c], Z = cs.xyzFromRGB[2][c];
            EXPECT_NEAR(X / (X + Y + Z), prim[c][0], 1e-9) << "primary " << c;
            EXPECT_NEAR(Y / (X + Y + Z), prim[c][1], 1e-9) << "primary " << c;
        }
        std::array<double, 3> W = IlluminantWhite(cs.illuminant.c_str());
        for (int i = 0; i < 3; ++i) {
            double w = cs.xyzFromRGB[i][0] + cs.xyzFromRGB[i][1] + cs.xyzFromRGB[i][2];
            EXPECT_NEAR(w, W[i], 1e-5) << "white " << i;
        }
        EXPECT_NEAR(cs.w[0], W[0] / (W[0] + W[1] + W[2]), 1e-6);
        EXPECT_NEAR(cs.w[1], W[1] / (W[0] + W[1] + W[2]), 1e-6);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                double p = 0;
                for (int k = 0; k < 3; ++k) p += cs.rgbFromXYZ[i][k] * cs.xyzFromRGB[k][j];
                EXPECT_NEAR(p, i == j ? 1.0 : 0.0, 1e-12);
            }
    }
}

// Published RGB -> XYZ matrices (whites D65 0.3127 0.3290 / ACES 0.32168 0.33767; ours come
// from the illuminant spectra, which agree to ~1e-4 in xy).
TEST(ColorSpace, MatricesMatchPublishedValues) {
    struct Ref {
        ColorSpaceId id;
        double m[3][3];
    };
    const Ref refs[] = {
        {ColorSpaceId::SRGB, {{0.412391, 0.357584, 0.180481}, {0.212639, 0.715169, 0.072192}, {0.019331, 0.119195, 0.950532}}},
        {ColorSpaceId::Rec2020, {{0.636958, 0.144617, 0.168881}, {0.262700, 0.677998, 0.059302}, {0.0, 0.028073, 1.060985}}},
        {ColorSpaceId::DCI_P3, {{0.486571, 0.265668, 0.198217}, {0.228975, 0.691739, 0.079287}, {0.0, 0.045113, 1.043944}}},
        {ColorSpaceId::ACES2065_1, {{0.952552, 0.0, 0.000094}, {0.343966, 0.728166, -0.072133}, {0.0, 0.0, 1.008825}}},
    };
    for (const Ref &r : refs) {
        const RGBColorSpace &cs = GetRGBColorSpace(r.id);
        SCOPED_TRACE(cs.name);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) EXPECT_NEAR(cs.xyzFromRGB[i][j], r.m[i][j], 1.5e-3) << i << " " << j;
    }
}

TEST(ColorSpace, IlluminantsAndLookup) {
    SpectrumRegistry reg;
    EXPECT_EQ(reg.IlluminantTable(ColorSpaceId::Rec2020), TableD65);
    EXPECT_EQ(reg.IlluminantTable(ColorSpaceId::DCI_P3), TableD65);
    EXPECT_NE(reg.IlluminantTable(ColorSpaceId::ACES2065_1), TableD65);
    EXPECT_EQ(reg.IlluminantTable(ColorSpaceId::ACES2065_1), reg.Named("illum-acesD60")->table);
    for (ColorSpaceId id : kAll) {
        const RGBColorSpace &cs = GetRGBColorSpace(id);
        EXPECT_EQ(LookupColorSpace(cs.r, cs.g, cs.b, cs.w), id);
    }
    EXPECT_FALSE(LookupColorSpace({0.64, 0.33}, {0.21, 0.71}, {0.15, 0.06}, {0.3127, 0.329}));  // Adobe RGB
}

// RGB in a grid over each space's cube -> the space's table -> spectrum (times its illuminant,
// as an RGB illuminant) -> XYZ -> RGB of the space: back within the fit's accuracy, for the grid
// colors inside the gamut the sigmoid spectra reach. "Inside" is taken as: Rec. 2020 coordinates
// (primaries on the spectral locus) in [0.1, 0.9]; colors beyond (ACES2065-1's cube is mostly
// imaginary colors) are fitted as closely as a smooth reflectance allows, which is no round trip.
TEST(ColorSpace, RoundTripThroughEachTable) {
    SpectrumRegistry reg;
    const RGBColorSpace &rec2020 = GetRGBColorSpace(ColorSpaceId::Rec2020);
    for (ColorSpaceId id : kAll) {
        const RGBColorSpace &cs = GetRGBColorSpace(id);
        SCOPED_TRACE(cs.name);
        double worst = 0;
        int n = 0;
        for (float r = 0.05f; r < 1.f; r += 0.1f)
            for (float g = 0.05f; g < 1.f; g += 0.1f)
                for (float b = 0.05f; b < 1.f; b += 0.1f) {
                    RGB rgb = {r, g, b};
                    RGB wide = rec2020.ToRGB(cs.ToXYZ(rgb));
                    bool inside = true;
                    for (int c = 0; c < 3; ++c) inside &= wide[c] >= 0.1f && wide[c] <= 0.9f;
                    if (!inside) continue;
                    ++n;
                    RGB back = cs.ToRGB(reg.ToXYZ(reg.FromRGB(rgb, SpectrumType::Illuminant, id)));
                    for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(back[c] - rgb[c])));
                }
        EXPECT_GT(n, 50);
        EXPECT_LT(worst, 3e-3);
        std::printf("%s: worst round-trip error %.2e over %d grid colors\n", cs.name.c_str(), worst, n);
    }
}

// The four tables are distinct (a wide-gamut space given sRGB's table would fail the round trip
// too); all share the resolution and z nodes.
TEST(ColorSpace, TablesDiffer) {
    RGBToSpectrumTableData s = RGBToSpectrumTable(ColorSpaceId::SRGB);
    for (ColorSpaceId id : {ColorSpaceId::DCI_P3, ColorSpaceId::Rec2020, ColorSpaceId::ACES2065_1}) {
        RGBToSpectrumTableData t = RGBToSpectrumTable(id);
        ASSERT_EQ(t.res, s.res);
        for (uint32_t k = 0; k < t.res; ++k) EXPECT_EQ(t.zNodes[k], s.zNodes[k]);
        Float a[3], b[3];
        RGBToSigmoidCoeffs(s.coeffs, s.zNodes, s.res, 0.7f, 0.3f, 0.2f, a);
        RGBToSigmoidCoeffs(t.coeffs, t.zNodes, t.res, 0.7f, 0.3f, 0.2f, b);
        EXPECT_GT(std::abs(SigmoidPolynomial(a, 620.f) - SigmoidPolynomial(b, 620.f)) +
                      std::abs(SigmoidPolynomial(a, 450.f) - SigmoidPolynomial(b, 450.f)),
                  1e-3);
    }
}

}  // namespace
}  // namespace lu
