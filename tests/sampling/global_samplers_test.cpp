// Lucerna tests: pbrt-v4's global samplers (halton, sobol) and their sequences: prime table, radical
// inverses and their scramblings, the Sobol' matrices (primitive polynomials, (0,1)-sequences per
// dimension), pixel indexing (each sample lands in its pixel; a pixel's samples form nets).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "lucerna/sampling/sampler.h"
#include "lucerna/scene/sampler_build.h"
#include "support/chi2.h"

using namespace lu;

namespace {

Sampler Make(const char *name, int spp, const char *randomization, int seed, int w, int h) {
    SamplerOptions o;
    o.randomization = randomization;
    std::string report;
    return MakeSampler(name, spp, seed, w, h, o, &report);
}

int EulerPhi(int64_t n) {
    int64_t r = n;
    for (int64_t p = 2; p * p <= n; ++p)
        if (n % p == 0) {
            while (n % p == 0) n /= p;
            r -= r / p;
        }
    if (n > 1) r -= r / n;
    return int(r);
}

// Each of the n = 2^k points in its own cell of every 2^a x 2^(k-a) partition.
bool IsNet(const std::vector<Vec2f> &pts, int k) {
    for (int a = 0; a <= k; ++a) {
        int nx = 1 << a, ny = 1 << (k - a);
        std::vector<int> cnt(size_t(1) << k, 0);
        for (const Vec2f &p : pts)
            if (++cnt[size_t(std::min(int(p.y * ny), ny - 1) * nx + std::min(int(p.x * nx), nx - 1))] > 1) return false;
    }
    return true;
}

}  // namespace

TEST(Sequences, Primes) {
    EXPECT_EQ(Prime(0), 2);
    EXPECT_EQ(Prime(1), 3);
    EXPECT_EQ(Prime(2), 5);
    EXPECT_EQ(Prime(25), 101);
    EXPECT_EQ(Prime(kPrimeTableSize - 1), 7919);   // the 1000th prime
    for (int i = 1; i < kPrimeTableSize; ++i) ASSERT_GT(Prime(i), Prime(i - 1));
}

TEST(Sequences, RadicalInverses) {
    EXPECT_EQ(RadicalInverse(0, 1), 0.5f);
    EXPECT_EQ(RadicalInverse(0, 6), 0.375f);              // 110 -> 0.011
    EXPECT_FLOAT_EQ(RadicalInverse(1, 5), 7.f / 9.f);      // 12 (base 3) -> 0.21
    for (int b = 0; b < 6; ++b) {
        int base = Prime(b);
        // InverseRadicalInverse undoes the mirroring of the first nDigits digits.
        for (uint64_t a = 0; a < uint64_t(base * base * base); ++a) {
            uint64_t mirrored = 0, t = a;
            for (int i = 0; i < 3; ++i, t /= uint64_t(base)) mirrored = mirrored * uint64_t(base) + t % uint64_t(base);
            EXPECT_EQ(InverseRadicalInverse(mirrored, base, 3), a);
        }
    }
    // Digit permutations and Owen scrambling keep the stratification: the first base^2 indices fall
    // in distinct intervals of width base^-2, in every dimension and for every seed.
    // (Bases up to 41: n = base^2 cells stay wide against the float rounding of the values.)
    for (int b : {0, 1, 2, 5, 12}) {
        int base = Prime(b), n = base * base;
        for (uint32_t seed : {0u, 7u}) {
            // Plain values are k / n up to rounding: the nearest k. Scrambled ones lie inside their
            // cell (their later digits scrambled too); float rounding (as in pbrt-v4) moves them by
            // up to ~2^-24, so a value that close to a cell boundary is not counted.
            const double window = 64 * 0x1p-24 * n;   // in cell widths
            int skipped = 0;
            auto inside = [&](Float v) -> int {
                double x = double(v) * n, f = x - std::floor(x);
                if (f < window || f > 1 - window) { ++skipped; return -1; }
                return std::min(int(x), n - 1);
            };
            std::vector<int> perm(size_t(n), 0), owen(size_t(n), 0), plain(size_t(n), 0);
            for (int a = 0; a < n; ++a) {
                int c0 = inside(ScrambledRadicalInverse(b, uint64_t(a), seed));
                int c1 = inside(OwenScrambledRadicalInverse(b, uint64_t(a), seed * 977 + 1));
                if (c0 >= 0) perm[size_t(c0)]++;
                if (c1 >= 0) owen[size_t(c1)]++;
                plain[size_t(std::min(int(double(RadicalInverse(b, uint64_t(a))) * n + 0.5), n - 1))]++;
            }
            for (int i = 0; i < n; ++i) {
                ASSERT_LE(perm[size_t(i)], 1) << "base " << base << " seed " << seed;
                ASSERT_LE(owen[size_t(i)], 1) << "base " << base << " seed " << seed;
                ASSERT_EQ(plain[size_t(i)], 1) << "base " << base;
            }
            EXPECT_LT(skipped, 2 * n / 20 + 2) << "base " << base;
        }
    }
    // The permutations depend on the seed and are not the identity.
    int same = 0, ident = 0;
    for (uint64_t a = 1; a < 100; ++a) {
        same += ScrambledRadicalInverse(3, a, 1) == ScrambledRadicalInverse(3, a, 2);
        ident += ScrambledRadicalInverse(3, a, 1) == RadicalInverse(3, a);
    }
    EXPECT_LT(same, 5);
    EXPECT_LT(ident, 5);
}

TEST(Sequences, SobolPolynomialsArePrimitiveInOrder) {
    // The list is exactly the primitive polynomials by degree and value: all of degrees 1..12,
    // phi(2^s - 1) / s of each, then the first ones of degree 13.
    std::vector<uint64_t> expected;
    for (int s = 1; expected.size() < size_t(kSobolDimensions - 1); ++s) {
        int count = 0;
        for (uint64_t p = (uint64_t(1) << s) | 1; p < (uint64_t(2) << s); p += 2)
            if (detail::IsPrimitivePolynomial(p, s)) {
                ++count;
                if (expected.size() < size_t(kSobolDimensions - 1)) expected.push_back(p);
            }
        EXPECT_EQ(count, EulerPhi((int64_t(1) << s) - 1) / s) << "degree " << s;
    }
    for (int i = 0; i < kSobolDimensions - 1; ++i) ASSERT_EQ(uint64_t(kPrimitivePolynomials[i]), expected[size_t(i)]) << i;
    // The order test rejects reducible and irreducible-but-not-primitive polynomials.
    EXPECT_FALSE(detail::IsPrimitivePolynomial(0b101, 2));      // (x+1)^2
    EXPECT_FALSE(detail::IsPrimitivePolynomial(0b11111, 4));    // x^4+x^3+x^2+x+1: order 5, not 15
    EXPECT_TRUE(detail::IsPrimitivePolynomial(0b10011, 4));     // x^4+x+1
}

TEST(Sequences, SobolMatrices) {
    // Dimensions 0 and 1 agree with the computed generators (pbrt-v4's), high index bits included.
    for (uint64_t a : {uint64_t(0), uint64_t(1), uint64_t(12345), uint64_t(0xdeadbeef), uint64_t(1) << 40 | 77})
        for (int d = 0; d < 2; ++d) {
            uint32_t v = 0;
            for (int k = 0; k < kSobolMatrixSize; ++k)
                if ((a >> k) & 1) v ^= SobolDimensionColumns(d)[k];
            EXPECT_EQ(v, SobolGenerate(a, d)) << a << " dim " << d;
        }
    // Every dimension is a (0,1)-sequence: the first 2^k points are one per interval of 2^-k.
    for (int d = 0; d < kSobolDimensions; ++d) {
        const int k = 10, n = 1 << k;
        std::vector<char> seen(n, 0);
        for (int a = 0; a < n; ++a) {
            uint32_t cell = SobolGenerateAny(uint64_t(a), d) >> (32 - k);
            ASSERT_FALSE(seen[cell]) << "dimension " << d;
            seen[cell] = 1;
        }
        // ... and each later block of 2^k points again.
        std::fill(seen.begin(), seen.end(), 0);
        for (int a = 0; a < n; ++a) {
            uint32_t cell = SobolGenerateAny(uint64_t(7 * n + a), d) >> (32 - k);
            ASSERT_FALSE(seen[cell]) << "dimension " << d;
            seen[cell] = 1;
        }
    }
    // All dimensions are distinct sequences.
    std::set<std::vector<uint32_t>> matrices;
    for (int d = 0; d < kSobolDimensions; ++d)
        matrices.insert(std::vector<uint32_t>(SobolDimensionColumns(d), SobolDimensionColumns(d) + kSobolMatrixSize));
    EXPECT_EQ(matrices.size(), size_t(kSobolDimensions));
    // Consecutive dimensions (what Get2D pairs) have no gross 2D defect: the first 4096 (16384)
    // points put between 1/4 and 7/4 of the expected 64 into every cell of an 8x8 (16x16) grid.
    // (Purely random initial direction numbers fail this for 11 of the 1023 pairs.)
    int bad = 0;
    for (int d = 0; d + 1 < kSobolDimensions; ++d) {
        bool ok = true;
        for (int bits : {3, 4}) {
            int g = 1 << bits, n = 64 * g * g;
            std::vector<int> cnt(size_t(g * g), 0);
            for (uint64_t a = 0; a < uint64_t(n); ++a)
                cnt[size_t((SobolGenerateAny(a, d + 1) >> (32 - bits)) * uint32_t(g) + (SobolGenerateAny(a, d) >> (32 - bits)))]++;
            for (int c : cnt) ok = ok && c >= 16 && c <= 112;
        }
        if (!ok) ++bad;
    }
    EXPECT_EQ(bad, 0) << "pairs of consecutive dimensions with an empty or crowded 1/64 cell";
}

TEST(Sequences, SobolIntervalToIndex) {
    for (int m = 0; m <= 6; ++m) {
        int res = 1 << m;
        for (uint64_t frame : {uint64_t(0), uint64_t(1), uint64_t(5), uint64_t(1000)}) {
            std::set<uint64_t> indices;
            for (int y = 0; y < res; ++y)
                for (int x = 0; x < res; ++x) {
                    uint64_t i = SobolIntervalToIndex(m, frame, x, y);
                    ASSERT_EQ(i >> (2 * m), frame);
                    // The point lies in pixel (x, y) at scale 2^m.
                    if (m > 0) {
                        ASSERT_EQ(int(SobolGenerate(i, 0) >> (32 - m)), x) << m << " " << frame;
                        ASSERT_EQ(int(SobolGenerate(i, 1) >> (32 - m)), y) << m << " " << frame;
                    }
                    indices.insert(i);
                }
            EXPECT_EQ(indices.size(), size_t(res) * size_t(res));
        }
    }
    EXPECT_EQ(SobolIntervalToIndex(0, 9, 0, 0), 9u);
    // Scale 2^16 (the largest supported).
    uint64_t i = SobolIntervalToIndex(16, 3, 40000, 123);
    EXPECT_EQ(int(SobolGenerate(i, 0) >> 16), 40000);
    EXPECT_EQ(int(SobolGenerate(i, 1) >> 16), 123);
}

TEST(GlobalSamplers, SobolPixelSamplesAreNetsInTheirPixel) {
    // The points of a (0,2)-sequence that fall in one 2^-m square form, rescaled, a (0,k,2)-net for
    // the first 2^k of them: GetPixel2D of a pixel's first 2^k samples.
    for (const char *rnd : {"none", "fastowen", "owen", "permutedigits"}) {
        Sampler s = Make("sobol", 64, rnd, 3, 50, 30);
        ASSERT_EQ(s.sobolLog2Scale, 6);
        for (int pixel = 0; pixel < 5; ++pixel) {
            int x = (pixel * 17) % 50, y = (pixel * 11) % 30;
            for (int k = 0; k <= 6; ++k) {
                std::vector<Vec2f> pts;
                for (int i = 0; i < (1 << k); ++i) {
                    s.StartPixelSample(x, y, i);
                    Vec2f u = s.GetPixel2D();
                    ASSERT_GE(u.x, 0.f);
                    ASSERT_LT(u.x, 1.f);
                    pts.push_back(u);
                }
                EXPECT_TRUE(IsNet(pts, k)) << rnd << " pixel " << x << "," << y << " k " << k;
            }
        }
    }
}

TEST(GlobalSamplers, HaltonPixelIndexing) {
    // The global Halton point of every pixel sample lies in its pixel: dimension 0 scaled by 2^j
    // gives x mod 2^j, dimension 1 scaled by 3^k gives y mod 3^k; the pixel offset is what remains.
    for (int w : {1, 30, 200}) {
        Sampler s = Make("halton", 16, "permutedigits", 0, w, 40);
        int bx = s.haltonBaseScale[0], by = s.haltonBaseScale[1];
        for (int y = 0; y < 40; y += 3)
            for (int x = 0; x < w; x += 7)
                for (int i : {0, 1, 7, 15, 40}) {
                    s.StartPixelSample(x, y, i);
                    double d0 = RadicalInverse(0, s.globalIndex), d1 = RadicalInverse(1, s.globalIndex);
                    ASSERT_EQ(int(d0 * bx), (x % 128) % bx) << x << "," << y << " sample " << i;
                    ASSERT_EQ(int(d1 * by + 1e-9), (y % 128) % by) << x << "," << y << " sample " << i;
                    Vec2f u = s.GetPixel2D();
                    EXPECT_NEAR(u.x, d0 * bx - int(d0 * bx), 1e-5);
                    EXPECT_NEAR(u.y, d1 * by - int(d1 * by + 1e-9), 2e-5);
                    ASSERT_LT(u.x, 1.f);
                    ASSERT_LT(u.y, 1.f);
                    EXPECT_EQ(s.dimension, 2);
                }
    }
    // Consecutive samples of one pixel step through the sequence by the tile size 2^j 3^k.
    Sampler s = Make("halton", 16, "none", 0, 64, 64);
    s.StartPixelSample(5, 6, 0);
    uint64_t i0 = s.globalIndex;
    s.StartPixelSample(5, 6, 3);
    EXPECT_EQ(s.globalIndex, i0 + 3u * 64u * 81u);
    // "none": dimension d is the plain radical inverse in base Prime(d).
    s.StartPixelSample(5, 6, 2);
    EXPECT_EQ(s.Get1D(), RadicalInverse(2, s.globalIndex));
    Vec2f u = s.Get2D();
    EXPECT_EQ(u.x, RadicalInverse(3, s.globalIndex));
    EXPECT_EQ(u.y, RadicalInverse(4, s.globalIndex));
    // Past the prime table the dimensions wrap to 2, as pbrt-v4.
    s.StartPixelSample(5, 6, 2, kPrimeTableSize);
    EXPECT_EQ(s.Get1D(), RadicalInverse(2, s.globalIndex));
}

TEST(GlobalSamplers, DimensionsAreUniformAndIndependent) {
    // Over 24x24 pixels x 16 samples, dimensions 2..9 (1D: 32 bins) and pairs (2,3), (3,4), (8,9)
    // (2D: 8x8) are uniform, for every randomization.
    const char *configs[][2] = {{"halton", "permutedigits"}, {"halton", "owen"}, {"halton", "none"},
                                {"sobol", "fastowen"},       {"sobol", "owen"}, {"sobol", "permutedigits"},
                                {"sobol", "none"}};
    const int nTests = 7 * 11;
    for (auto &c : configs) {
        Sampler s = Make(c[0], 16, c[1], 1, 24, 24);
        std::vector<std::vector<double>> h1(8, std::vector<double>(32, 0)), h2(3, std::vector<double>(64, 0));
        int n = 0;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 24; ++x)
                for (int i = 0; i < 16; ++i) {
                    s.StartPixelSample(x, y, i);
                    float v[10];
                    for (int d = 2; d < 10; ++d) v[d] = s.Get1D();
                    for (int d = 2; d < 10; ++d) {
                        ASSERT_GE(v[d], 0.f);
                        ASSERT_LT(v[d], 1.f);
                        h1[size_t(d - 2)][size_t(v[d] * 32)] += 1;
                    }
                    const int pairs[3][2] = {{2, 3}, {3, 4}, {8, 9}};
                    for (int p = 0; p < 3; ++p)
                        h2[size_t(p)][size_t(int(v[pairs[p][1]] * 8) * 8 + int(v[pairs[p][0]] * 8))] += 1;
                    ++n;
                }
        for (int d = 0; d < 8; ++d)
            EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(h1[size_t(d)], std::vector<double>(32, n / 32.0), 0.25), 1e-4, nTests))
                << c[0] << "/" << c[1] << " dim " << d + 2;
        for (int p = 0; p < 3; ++p)
            EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(h2[size_t(p)], std::vector<double>(64, n / 64.0), 0.25), 1e-4, nTests))
                << c[0] << "/" << c[1] << " pair " << p;
    }
}

TEST(GlobalSamplers, SobolSampleIndicesFollowPbrt) {
    // Dimension d >= 2 of the sobol sampler is the d-th Sobol' dimension at the pixel sample's global
    // index, scrambled with the hash of (d, seed); Get2D takes two consecutive dimensions.
    Sampler s = Make("sobol", 16, "none", 0, 40, 40);
    s.StartPixelSample(3, 4, 5);
    uint64_t idx = s.globalIndex;
    EXPECT_EQ(idx, SobolIntervalToIndex(6, 5, 3, 4));
    EXPECT_EQ(s.Get1D(), UInt32ToUnitFloat(SobolGenerateAny(idx, 2)));
    Vec2f u = s.Get2D();
    EXPECT_EQ(u.x, UInt32ToUnitFloat(SobolGenerateAny(idx, 3)));
    EXPECT_EQ(u.y, UInt32ToUnitFloat(SobolGenerateAny(idx, 4)));
    Sampler f = Make("sobol", 16, "fastowen", 9, 40, 40);
    f.StartPixelSample(3, 4, 5, 7);
    uint32_t hash = uint32_t(MixBits((uint64_t(7) << 32) ^ 9u));
    EXPECT_EQ(f.Get1D(), UInt32ToUnitFloat(FastOwenScrambler(hash)(SobolGenerateAny(idx, 7))));
    // Past the last dimension the sampler wraps to 2.
    f.StartPixelSample(3, 4, 5, kSobolDimensions);
    Float wrapped = f.Get1D();
    f.StartPixelSample(3, 4, 5, 2);
    EXPECT_EQ(wrapped, f.Get1D());
}
