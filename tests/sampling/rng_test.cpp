// Tests of PCG32 (rng.h) and the hashing helpers (hash.h).
#include <gtest/gtest.h>

#include <set>

#include "lucerna/sampling/hash.h"
#include "lucerna/sampling/rng.h"
#include "support/test_support.h"

using namespace lu;

TEST(RNG, MatchesPcg32Reference) {
    // pcg32_srandom(42, 54) from the PCG reference implementation (pcg32-demo output).
    RNG rng(54, 42);
    const uint32_t expected[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    for (uint32_t e : expected) EXPECT_EQ(rng.Uniform<uint32_t>(), e);
}

TEST(RNG, Deterministic) {
    RNG a(7), b(7), c(8);
    int same = 0;
    for (int i = 0; i < 1000; ++i) {
        uint32_t va = a.Uniform<uint32_t>(), vb = b.Uniform<uint32_t>(), vc = c.Uniform<uint32_t>();
        EXPECT_EQ(va, vb);
        same += (va == vc);
    }
    EXPECT_LT(same, 3);  // another stream gives other numbers
}

TEST(RNG, AdvanceAndDistance) {
    RNG a(3, 99), b(3, 99);
    for (int i = 0; i < 12345; ++i) a.Uniform<uint32_t>();
    RNG start = b;
    b.Advance(12345);
    EXPECT_TRUE(a == b);
    EXPECT_EQ(a.Uniform<uint32_t>(), b.Uniform<uint32_t>());
    EXPECT_EQ(b - start, 12346);
    b.Advance(-12346);
    EXPECT_TRUE(b == start);
}

TEST(RNG, FloatsInUnitInterval) {
    RNG rng(1);
    for (int i = 0; i < 100000; ++i) {
        float u = rng.Uniform<float>();
        ASSERT_GE(u, 0.f);
        ASSERT_LT(u, 1.f);
        double d = rng.Uniform<double>();
        ASSERT_GE(d, 0.0);
        ASSERT_LT(d, 1.0);
    }
}

TEST(RNG, ChiSquareUniform1DAnd2D) {
    RNG rng(12, 34);
    test::Chi2Options opts;
    opts.samples = 200000;
    auto uniform = [](const test::Chi2Point &) { return 1.0; };
    auto sample1 = [&](test::Chi2Point *p) { p->x = rng.Uniform<float>(); return true; };
    auto sample2 = [&](test::Chi2Point *p) {
        p->x = rng.Uniform<float>();
        p->y = rng.Uniform<float>();
        return true;
    };
    EXPECT_TRUE(test::Chi2Accepts(test::Chi2SampleTest(test::IntervalDomain(0, 1, 100), sample1, uniform, opts), 1e-4, 2));
    EXPECT_TRUE(test::Chi2Accepts(test::Chi2SampleTest(test::RectDomain(0, 1, 0, 1, 16, 16), sample2, uniform, opts), 1e-4, 2));
    // A generator with too few bits (values on a 1/64 grid) is rejected by the 100-bin histogram.
    auto coarse = [&](test::Chi2Point *p) { p->x = std::floor(rng.Uniform<float>() * 64) / 64; return true; };
    EXPECT_TRUE(test::Chi2Rejects(test::Chi2SampleTest(test::IntervalDomain(0, 1, 100), coarse, uniform, opts)));
}

TEST(RNG, BoundedIsUniform) {
    RNG rng(5);
    const int n = 60000, k = 6;
    std::vector<double> h(k, 0), e(k, double(n) / k);
    for (int i = 0; i < n; ++i) {
        uint32_t v = rng.UniformBounded(k);
        ASSERT_LT(v, uint32_t(k));
        h[v] += 1;
    }
    EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(h, e)));
}

TEST(Hash, DeterministicAndSensitive) {
    EXPECT_EQ(Hash(1, 2, 3), Hash(1, 2, 3));
    EXPECT_NE(Hash(1, 2, 3), Hash(1, 2, 4));
    EXPECT_NE(Hash(1, 2, 3), Hash(3, 2, 1));
    EXPECT_NE(Hash(uint64_t(5)), Hash(uint32_t(5)));  // the byte count matters
    EXPECT_EQ(MixBits(0), 0u);
    std::set<uint64_t> seen;
    for (uint64_t i = 0; i < 1000; ++i) seen.insert(MixBits(i));
    EXPECT_EQ(seen.size(), 1000u);  // a bijection
    float f = HashFloat(1.5f, 7);
    EXPECT_GE(f, 0.f);
    EXPECT_LT(f, 1.f);
}

TEST(Hash, PermutationElementIsAPermutation) {
    for (uint32_t n : {1u, 2u, 5u, 16u, 37u, 1000u}) {
        for (uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
            std::vector<int> seen(n, 0);
            for (uint32_t i = 0; i < n; ++i) {
                int e = PermutationElement(i, n, seed);
                ASSERT_GE(e, 0);
                ASSERT_LT(e, int(n));
                seen[e]++;
            }
            for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "n " << n << " seed " << seed;
        }
    }
}
