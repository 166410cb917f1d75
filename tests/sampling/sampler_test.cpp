// Tests of the pixel samplers (sampler.h): uniformity of every dimension, per-pixel
// stratification of the Sobol' kinds, determinism and order independence, indices past spp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "lucerna/scene/pmj02_build.h"
#include "lucerna/scene/sampler_build.h"
#include "lucerna/sampling/sampler.h"
#include "support/test_support.h"

using namespace lu;

namespace {

struct Config {
    const char *name;
    const char *randomization;
};

const Config kConfigs[] = {{"independent", ""}, {"zsobol", "fastowen"}, {"zsobol", "owen"},
                           {"zsobol", "permutedigits"}, {"paddedsobol", "fastowen"}, {"stratified", ""},
                           {"halton", "permutedigits"}, {"sobol", "fastowen"}, {"sobol", "owen"},
                           {"sobol", "permutedigits"}, {"pmj02bn", ""}};

// Halton and Sobol take the position in the pixel from unrandomized dimensions 0 and 1, and
// pmj02bn from its pixel table (pbrt-v4): the pixel sample is seed-independent, and these start
// their other dimensions at 2.
bool GlobalKind(const char *name) {
    return std::string(name) == "halton" || std::string(name) == "sobol" || std::string(name) == "pmj02bn";
}

// The pmj02bn tables by sample count, kept for the tests' samplers.
const std::vector<Vec2f> &PMJTables(int spp, int *tile) {
    static std::map<int, std::pair<std::vector<Vec2f>, int>> tables;
    auto it = tables.find(spp);
    if (it == tables.end()) {
        int t = 0;
        std::vector<Vec2f> v = BuildPMJ02BNTables(spp, 99, &t);
        it = tables.emplace(spp, std::make_pair(std::move(v), t)).first;
    }
    *tile = it->second.second;
    return it->second.first;
}

Sampler Make(const char *name, int spp, const char *randomization = "", int seed = 0, int w = 64, int h = 48) {
    SamplerOptions o;
    o.randomization = randomization;
    std::string report;
    Sampler s = MakeSampler(name, spp, seed, w, h, o, &report);
    if (s.kind == SamplerKind::PMJ02BN) s.pmjPoints = PMJTables(s.samplesPerPixel, &s.pmjTileSize).data();
    return s;
}

// The draws of one pixel sample: 1D, 2D, 1D, 1D, 2D, 2D (dims 0..9).
struct Draws {
    float v[10];
};
Draws Draw(Sampler &s, int x, int y, int index) {
    Draws d;
    s.StartPixelSample(x, y, index);
    d.v[0] = s.Get1D();
    Vec2f a = s.Get2D();
    d.v[1] = a.x; d.v[2] = a.y;
    d.v[3] = s.Get1D();
    d.v[4] = s.Get1D();
    Vec2f b = s.Get2D();
    d.v[5] = b.x; d.v[6] = b.y;
    Vec2f c = s.GetPixel2D();
    d.v[7] = c.x; d.v[8] = c.y;
    d.v[9] = s.Get1D();
    return d;
}

// Elementary-interval check: the n = 2^k points have exactly one point in every
// 2^a x 2^(k-a) cell, for every a.
bool IsNet(const std::vector<Vec2f> &pts, int k, std::string *why) {
    int n = 1 << k;
    for (int a = 0; a <= k; ++a) {
        int nx = 1 << a, ny = 1 << (k - a);
        std::vector<int> cnt(n, 0);
        for (const Vec2f &p : pts) {
            int ix = std::min(int(p.x * nx), nx - 1), iy = std::min(int(p.y * ny), ny - 1);
            if (++cnt[iy * nx + ix] > 1) {
                *why = "two points in one " + std::to_string(nx) + "x" + std::to_string(ny) + " cell";
                return false;
            }
        }
    }
    return true;
}

}  // namespace

TEST(Sampler, EveryDimensionIsUniform) {
    // 16x16 pixels x 16 spp = 4096 samples per dimension; 1D: 32 bins, 2D pairs: 8x8. With 128
    // samples per bin the test sees cell-mass errors of 25% (the power control), not 10%.
    const int nConfigs = int(sizeof(kConfigs) / sizeof(kConfigs[0]));
    const int nTests = nConfigs * (10 + 3);
    const double control = 0.25;
    for (const Config &c : kConfigs) {
        Sampler s = Make(c.name, 16, c.randomization, 3);
        std::vector<std::vector<double>> h1(10, std::vector<double>(32, 0));
        std::vector<std::vector<double>> h2(3, std::vector<double>(64, 0));
        std::vector<double> reused(64, 0);  // a pair drawing one dimension twice
        int n = 0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                for (int i = 0; i < 16; ++i) {
                    Draws d = Draw(s, x, y, i);
                    ++n;
                    for (int k = 0; k < 10; ++k) {
                        ASSERT_GE(d.v[k], 0.f);
                        ASSERT_LT(d.v[k], 1.f);
                        h1[k][int(d.v[k] * 32)] += 1;
                    }
                    const int pairs[3][2] = {{1, 2}, {5, 6}, {7, 8}};
                    for (int p = 0; p < 3; ++p)
                        h2[p][int(d.v[pairs[p][1]] * 8) * 8 + int(d.v[pairs[p][0]] * 8)] += 1;
                    reused[int(d.v[1] * 8) * 8 + int(d.v[1] * 8)] += 1;
                }
        for (int k = 0; k < 10; ++k)
            EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(h1[k], std::vector<double>(32, n / 32.0), control), 1e-4, nTests))
                << c.name << "/" << c.randomization << " dim " << k;
        for (int k = 0; k < 3; ++k)
            EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(h2[k], std::vector<double>(64, n / 64.0), control), 1e-4, nTests))
                << c.name << "/" << c.randomization << " pair " << k;
        // The same harness rejects a pair that reuses one dimension (all samples on the diagonal).
        EXPECT_TRUE(test::Chi2Rejects(test::Chi2Counts(reused, std::vector<double>(64, n / 64.0)), 1e-4, nTests))
            << c.name << "/" << c.randomization;
    }
}

TEST(Sampler, ZSobolPixelSamplesAreStratified) {
    for (const char *rnd : {"none", "permutedigits", "fastowen", "owen"}) {
        for (int k = 0; k <= 8; ++k) {
            int spp = 1 << k;
            Sampler s = Make("zsobol", spp, rnd, 11, 100, 70);
            ASSERT_EQ(s.SamplesPerPixel(), spp);
            for (int pixel = 0; pixel < 6; ++pixel) {
                int x = (pixel * 37) % 100, y = (pixel * 23) % 70;
                for (int dim : {0, 1, 2, 5, 9}) {
                    std::vector<Vec2f> pts;
                    std::vector<int> strata(spp, 0);
                    for (int i = 0; i < spp; ++i) {
                        s.StartPixelSample(x, y, i, dim);
                        pts.push_back(s.Get2D());
                        s.StartPixelSample(x, y, i, dim);
                        strata[std::min(int(s.Get1D() * spp), spp - 1)]++;
                    }
                    std::string why;
                    EXPECT_TRUE(IsNet(pts, k, &why)) << rnd << " spp " << spp << " pixel " << x << "," << y
                                                     << " dim " << dim << ": " << why;
                    for (int i = 0; i < spp; ++i)
                        ASSERT_EQ(strata[i], 1) << rnd << " spp " << spp << " 1D stratum " << i << " dim " << dim;
                }
            }
        }
    }
}

TEST(Sampler, PaddedSobolAndStratifiedAreStratified) {
    for (int k : {2, 4, 6}) {
        int spp = 1 << k;
        Sampler s = Make("paddedsobol", spp, "fastowen", 1);
        std::vector<Vec2f> pts;
        for (int i = 0; i < spp; ++i) {
            s.StartPixelSample(5, 9, i, 4);
            pts.push_back(s.Get2D());
        }
        std::string why;
        EXPECT_TRUE(IsNet(pts, k, &why)) << "paddedsobol spp " << spp << ": " << why;
    }
    Sampler st = Make("stratified", 12, "", 2);
    EXPECT_EQ(st.xPixelSamples * st.yPixelSamples, 12);
    std::vector<int> c1(12, 0), c2(12, 0);
    for (int i = 0; i < 12; ++i) {
        st.StartPixelSample(3, 4, i, 2);
        c1[int(st.Get1D() * 12)]++;
        Vec2f u = st.Get2D();
        c2[int(u.y * st.yPixelSamples) * st.xPixelSamples + int(u.x * st.xPixelSamples)]++;
    }
    for (int i = 0; i < 12; ++i) {
        EXPECT_EQ(c1[i], 1);
        EXPECT_EQ(c2[i], 1);
    }
}

TEST(Sampler, DeterministicAndPixelDependent) {
    for (const Config &c : kConfigs) {
        Sampler a = Make(c.name, 16, c.randomization, 5), b = Make(c.name, 16, c.randomization, 5);
        Sampler other = Make(c.name, 16, c.randomization, 6);
        int samePixel = 0, sameSeed = 0, total = 0;
        for (int i = 0; i < 16; ++i) {
            Draws d1 = Draw(a, 7, 3, i), d2 = Draw(b, 7, 3, i), d3 = Draw(a, 8, 3, i), d4 = Draw(other, 7, 3, i);
            for (int k = 0; k < 10; ++k) {
                ASSERT_EQ(d1.v[k], d2.v[k]) << c.name;
                samePixel += d1.v[k] == d3.v[k];
                if (GlobalKind(c.name) && (k == 7 || k == 8)) continue;   // seed-independent by design
                sameSeed += d1.v[k] == d4.v[k];
                ++total;
            }
        }
        EXPECT_LT(samePixel, total / 20) << c.name << ": neighbouring pixels get the same numbers";
        EXPECT_LT(sameSeed, total / 20) << c.name << ": another seed gives the same numbers";
    }
}

TEST(Sampler, IndependentOfCallOrder) {
    for (const Config &c : kConfigs) {
        Sampler s = Make(c.name, 8, c.randomization, 9);
        // Reference: pixels in scanline order, samples in order.
        std::vector<Draws> ref;
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x)
                for (int i = 0; i < 8; ++i) ref.push_back(Draw(s, x, y, i));
        // Shuffled order with a second sampler object (as another thread would).
        std::vector<int> order(ref.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = int(i);
        std::mt19937 g(1);
        std::shuffle(order.begin(), order.end(), g);
        Sampler t = Make(c.name, 8, c.randomization, 9);
        for (int j : order) {
            int x = (j / 8) % 4, y = j / 32, i = j % 8;
            Draws d = Draw(t, x, y, i);
            for (int k = 0; k < 10; ++k) ASSERT_EQ(d.v[k], ref[j].v[k]) << c.name;
        }
        // Starting at a dimension equals consuming the dimensions before it (Halton and Sobol:
        // after their two pixel dimensions 0 and 1, which StartPixelSample skips, as pbrt-v4).
        const int skip = GlobalKind(c.name) ? 2 : 0;
        for (int i = 0; i < 8; ++i) {
            Draws d = ref[size_t(2 * 32 + 1 * 8 + i)];  // pixel (1, 2)
            s.StartPixelSample(1, 2, i, 3 + skip);
            EXPECT_EQ(s.Get1D(), d.v[3]) << c.name;
            s.StartPixelSample(1, 2, i, 5 + skip);
            Vec2f u = s.Get2D();
            EXPECT_EQ(u.x, d.v[5]) << c.name;
            EXPECT_EQ(u.y, d.v[6]) << c.name;
            EXPECT_EQ(s.dimension, 7 + skip);
        }
    }
}

TEST(Sampler, IndicesPastSamplesPerPixel) {
    for (const Config &c : kConfigs) {
        Sampler s = Make(c.name, 16, c.randomization, 4);
        // Each further block of 16 (pass) is again stratified (Sobol' kinds), differs from pass 0,
        // and is deterministic.
        std::vector<Vec2f> pass0, pass1;
        for (int i = 0; i < 16; ++i) {
            s.StartPixelSample(2, 2, i, 1);
            pass0.push_back(s.Get2D());
            s.StartPixelSample(2, 2, 16 + i, 1);
            pass1.push_back(s.Get2D());
            s.StartPixelSample(2, 2, 16 + i, 1);
            Vec2f again = s.Get2D();
            EXPECT_EQ(again.x, pass1.back().x);
            EXPECT_EQ(again.y, pass1.back().y);
            EXPECT_GE(pass1.back().x, 0.f);
            EXPECT_LT(pass1.back().x, 1.f);
        }
        int same = 0;
        for (int i = 0; i < 16; ++i) same += pass0[i].x == pass1[i].x;
        EXPECT_LT(same, 3) << c.name;
        // (Halton and Sobol continue their global sequence: a pixel's later samples are not a net.)
        // (pmj02bn's points are rotated toroidally per pixel: stratified in 1D, no longer a net.)
        if (std::string(c.name) != "independent" && std::string(c.name) != "stratified" && !GlobalKind(c.name)) {
            std::string why;
            EXPECT_TRUE(IsNet(pass1, 4, &why)) << c.name << ": " << why;
        }
    }
    // Uniformity over many passes of one pixel (progressive rendering of a single pixel).
    Sampler z = Make("zsobol", 4, "fastowen", 0);
    std::vector<double> h(32, 0);
    const int n = 8192;
    for (int i = 0; i < n; ++i) {
        z.StartPixelSample(1, 1, i, 2);
        h[int(z.Get1D() * 32)] += 1;
    }
    EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(h, std::vector<double>(32, n / 32.0), 0.2)));
    // "none" randomization still gives new samples past spp.
    Sampler none = Make("zsobol", 4, "none", 0);
    none.StartPixelSample(0, 0, 1, 0);
    float a = none.Get1D();
    none.StartPixelSample(0, 0, 5, 0);
    EXPECT_NE(a, none.Get1D());
}

TEST(Sampler, MakeSamplerNamesAndReports) {
    std::string report;
    Sampler s = MakeSampler("zsobol", 6, 0, 32, 32, {}, &report);
    EXPECT_EQ(s.kind, SamplerKind::ZSobol);
    EXPECT_EQ(s.SamplesPerPixel(), 4);
    EXPECT_NE(report.find("rounded down"), std::string::npos);
    report.clear();
    s = MakeSampler("sobol", 64, 0, 32, 32, {}, &report);
    EXPECT_EQ(s.kind, SamplerKind::Sobol);
    EXPECT_EQ(s.SamplesPerPixel(), 64);
    EXPECT_EQ(s.randomize, RandomizeStrategy::FastOwen);   // pbrt-v4's default for sobol
    EXPECT_EQ(s.sobolLog2Scale, 5);
    EXPECT_TRUE(report.empty()) << report;
    s = MakeSampler("halton", 12, 0, 200, 20, {}, &report);
    EXPECT_EQ(s.kind, SamplerKind::Halton);
    EXPECT_EQ(s.SamplesPerPixel(), 12);
    EXPECT_EQ(s.randomize, RandomizeStrategy::PermuteDigits);   // pbrt-v4's default for halton
    EXPECT_EQ(s.haltonBaseScale[0], 128);   // 2^7 (at most 128), 3^3 = 27 >= 20
    EXPECT_EQ(s.haltonBaseScale[1], 27);
    EXPECT_EQ(s.haltonBaseExponent[0], 7);
    EXPECT_EQ(s.haltonBaseExponent[1], 3);
    EXPECT_EQ((s.haltonMultInverse[0] * 27) % 128, 1);
    EXPECT_EQ((s.haltonMultInverse[1] * 128) % 27, 1);
    EXPECT_TRUE(report.empty()) << report;
    report.clear();
    s = MakeSampler("pmj02bn", 64, 0, 32, 32, {}, &report);
    EXPECT_EQ(s.kind, SamplerKind::PMJ02BN);
    EXPECT_TRUE(report.empty()) << report;
    s = MakeSampler("pmj02bn", 32, 0, 32, 32, {}, &report);
    EXPECT_NE(report.find("power-of-4"), std::string::npos) << report;   // pbrt-v4's warning
    report.clear();
    s = MakeSampler("bogus", 6, 0, 32, 32, {}, &report);
    EXPECT_EQ(s.kind, SamplerKind::ZSobol);
    EXPECT_EQ(s.SamplesPerPixel(), 6);  // a fallback keeps the requested count
    EXPECT_NE(report.find("unknown sampler"), std::string::npos);
    report.clear();
    s = MakeSampler("independent", 7, 3, 32, 32, {}, &report);
    EXPECT_EQ(s.kind, SamplerKind::Independent);
    EXPECT_EQ(s.SamplesPerPixel(), 7);
    EXPECT_TRUE(report.empty());
    SamplerOptions o;
    o.xSamples = 2;
    o.ySamples = 3;
    s = MakeSampler("stratified", 6, 0, 8, 8, o, &report);
    EXPECT_EQ(s.xPixelSamples, 2);
    EXPECT_EQ(s.yPixelSamples, 3);
    s = MakeSampler("stratified", 32, 0, 8, 8, {}, &report);
    EXPECT_EQ(s.xPixelSamples * s.yPixelSamples, 32);
    o = {};
    o.randomization = "owen";
    s = MakeSampler("zsobol", 16, 0, 8, 8, o, &report);
    EXPECT_EQ(s.randomize, RandomizeStrategy::Owen);
}

// pmj02bn: every pixel's share of the first set is a (0,2)-net of spp points (the set is one over
// the tile of pixels); the pixel samples are the pixel's own, with no dimension consumed; 1D
// samples take each of the spp strata once; a 2D dimension's samples over a pixel are the set's
// first spp points (a net) rotated toroidally, so they keep one point per 1/sqrt(spp) column
// modulo the rotation.
TEST(Sampler, PMJ02BNIsStratifiedAsPbrtV4) {
    for (int spp : {1, 4, 16, 64, 256}) {
        int tile = 0;
        const std::vector<Vec2f> &t = PMJTables(spp, &tile);
        int log4 = 0;
        while ((1 << (2 * log4)) < spp) ++log4;
        EXPECT_EQ(tile, 1 << (8 - log4)) << spp;   // tile^2 spp = 65536
        ASSERT_EQ(t.size(), size_t(tile) * tile * spp + size_t(kPMJ02BNSets) * spp);
        Sampler s = Make("pmj02bn", spp, "", 7, 300, 200);
        for (int pixel = 0; pixel < 5; ++pixel) {
            int x = (pixel * 71) % 300, y = (pixel * 43) % 200;
            std::vector<Vec2f> pts;
            std::vector<int> strata(spp, 0);
            for (int i = 0; i < spp; ++i) {
                s.StartPixelSample(x, y, i, 0);
                pts.push_back(s.GetPixel2D());
                EXPECT_EQ(s.dimension, 2);
                strata[std::min(int(s.Get1D() * spp), spp - 1)]++;
            }
            std::string why;
            EXPECT_TRUE(IsNet(pts, 2 * log4, &why)) << "spp " << spp << " pixel " << x << "," << y << ": " << why;
            for (int i = 0; i < spp; ++i) ASSERT_EQ(strata[i], 1) << "spp " << spp << " stratum " << i;
        }
        // Pixels a tile apart share their pixel samples; neighbours do not.
        s.StartPixelSample(3, 5, 0);
        Vec2f a = s.GetPixel2D();
        s.StartPixelSample(3 + tile, 5 + tile, 0);
        Vec2f b = s.GetPixel2D();
        EXPECT_EQ(a.x, b.x);
        EXPECT_EQ(a.y, b.y);
        for (int k = 0; k < kPMJ02BNSets; ++k) {   // each set's first spp points: a net
            std::vector<Vec2f> set(t.begin() + ptrdiff_t(size_t(tile) * tile * spp + size_t(k) * spp),
                                   t.begin() + ptrdiff_t(size_t(tile) * tile * spp + size_t(k + 1) * spp));
            std::string why;
            EXPECT_TRUE(IsNet(set, 2 * log4, &why)) << "spp " << spp << " set " << k << ": " << why;
        }
    }
    // Sample counts above pbrt-v4's table size are refused.
    int tile = 0;
    EXPECT_THROW(BuildPMJ02BNTables(kPMJ02BNSamples * 2, 1, &tile), std::invalid_argument);
}

TEST(Sampler, ZSobolMatchesPbrtValues) {
    // Values of pbrt-v4's ZSobolSampler (fastowen, 200x150 film) for Get1D, Get2D, Get1D, computed
    // by a transcription of its GetSampleIndex/SobolSample; Lucerna rounds toward zero where
    // pbrt-v4 rounds to nearest, hence the 2^-24 tolerance.
    struct Case {
        int seed, spp, x, y, index;
        float v[4];
    };
    const Case cases[] = {{0, 16, 13, 7, 5, {0.718378663f, 0.593983173f, 0.92645973f, 0.857842565f}},
                          {7, 8, 199, 149, 3, {0.491197646f, 0.30173704f, 0.533415318f, 0.828687131f}},
                          {0, 1, 0, 0, 0, {0.72051084f, 0.344412565f, 0.270580232f, 0.181050017f}},
                          {-3, 128, 64, 100, 127, {0.160213828f, 0.473196775f, 0.991638899f, 0.599192917f}}};
    for (const Case &c : cases) {
        Sampler s = Make("zsobol", c.spp, "fastowen", c.seed, 200, 150);
        s.StartPixelSample(c.x, c.y, c.index);
        float a = s.Get1D();
        Vec2f b = s.Get2D();
        float d = s.Get1D();
        EXPECT_NEAR(a, c.v[0], 0x1p-24);
        EXPECT_NEAR(b.x, c.v[1], 0x1p-24);
        EXPECT_NEAR(b.y, c.v[2], 0x1p-24);
        EXPECT_NEAR(d, c.v[3], 0x1p-24);
    }
}

TEST(LowDiscrepancy, SobolMatricesAndFloatConversion) {
    // pbrt-v4's SobolMatrices32 columns: dimension 0 is van der Corput, dimension 1 starts
    // 0x80000000, 0xc0000000, 0xa0000000, 0xf0000000, 0x88000000 and repeats after 32 columns.
    const uint32_t dim1[5] = {0x80000000u, 0xc0000000u, 0xa0000000u, 0xf0000000u, 0x88000000u};
    for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(SobolGenerate(uint64_t(1) << i, 0), 0x80000000u >> i);
        EXPECT_EQ(SobolGenerate(uint64_t(1) << i, 1), dim1[i]);
        EXPECT_EQ(SobolGenerate(uint64_t(1) << (32 + i), 1), dim1[i]);
    }
    EXPECT_EQ(SobolGenerate(uint64_t(1) << 31, 1), 0xffffffffu);
    EXPECT_EQ(SobolGenerate(uint64_t(1) << 33, 0), 0u);
    EXPECT_LT(UInt32ToUnitFloat(0xffffffffu), 1.f);
    EXPECT_EQ(UInt32ToUnitFloat(0xffffffffu), OneMinusEpsilon);
    EXPECT_EQ(UInt32ToUnitFloat(0x00ffffffu), float(0x00ffffff) * 0x1p-32f);  // exact below 2^24
    EXPECT_EQ(UInt32ToUnitFloat(0x80000000u), 0.5f);
    EXPECT_EQ(UInt32ToUnitFloat(0x7fffffffu), 0.5f - 0x1p-25f);  // rounded toward zero, not up to 0.5
    // Fast and full Owen scrambling are bijections that keep every prefix (nested scrambles).
    for (uint32_t seed : {1u, 0x12345678u}) {
        FastOwenScrambler fo(seed);
        OwenScrambler ow(seed);
        for (int bits = 1; bits <= 6; ++bits) {
            std::vector<int> seenF(1 << bits, 0), seenO(1 << bits, 0);
            for (uint32_t prefix = 0; prefix < (1u << bits); ++prefix) {
                uint32_t v = prefix << (32 - bits);
                seenF[fo(v) >> (32 - bits)]++;
                seenO[ow(v) >> (32 - bits)]++;
                EXPECT_EQ(fo(v) >> (32 - bits), fo(v | ((1u << (32 - bits)) - 1)) >> (32 - bits));
            }
            for (int i = 0; i < (1 << bits); ++i) {
                EXPECT_EQ(seenF[i], 1);
                EXPECT_EQ(seenO[i], 1);
            }
        }
    }
}
