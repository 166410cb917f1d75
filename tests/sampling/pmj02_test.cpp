// The pmj02 generator (scene/pmj02_build.h): every 2^k prefix of each generated sequence is a
// (0,2)-net (all elementary intervals of area 2^-k hold one point), for several seeds; the check
// itself rejects a broken net; the points are uniform (chi-square over a grid finer than the
// prefix's strata, across seeds); different seeds give different sequences.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "lucerna/scene/pmj02_build.h"
#include "support/chi2.h"

namespace lu {
namespace {

TEST(PMJ02, EveryPowerOfTwoPrefixIsAZeroTwoNet) {
    for (uint64_t seed : {0ull, 1ull, 7ull, 12345ull}) {
        int restarts = -1;
        std::vector<Vec2f> pts = GeneratePMJ02(4096, seed, &restarts);
        ASSERT_EQ(pts.size(), 4096u);
        EXPECT_GE(restarts, 0);
        for (int k = 0; k <= 12; ++k) EXPECT_TRUE(IsZeroTwoNet(pts, k)) << "seed " << seed << ", prefix 2^" << k;
    }
}

TEST(PMJ02, LargerSetsStayNets) {
    auto t0 = std::chrono::steady_clock::now();
    std::vector<Vec2f> pts = GeneratePMJ02(16384, 3);
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (int k = 0; k <= 14; ++k) EXPECT_TRUE(IsZeroTwoNet(pts, k)) << "prefix 2^" << k;
    RecordProperty("seconds_16384", std::to_string(s));
}

TEST(PMJ02, CheckRejectsABrokenNet) {
    std::vector<Vec2f> pts = GeneratePMJ02(64, 5);
    ASSERT_TRUE(IsZeroTwoNet(pts, 6));
    std::vector<Vec2f> bad = pts;
    bad[17] = bad[3];   // two points in the same finest intervals
    EXPECT_FALSE(IsZeroTwoNet(bad, 6));
    bool anyBroken = false;
    for (int i = 0; i < 64 && !anyBroken; ++i) {
        std::vector<Vec2f> b = pts;
        b[i].x = float(std::fmod(b[i].x + 0.5f / 64, 1.0));   // shift one point by half an x stratum
        anyBroken = !IsZeroTwoNet(b, 6);
    }
    EXPECT_TRUE(anyBroken);
    EXPECT_FALSE(IsZeroTwoNet(pts, 7));   // too few points for a 2^7 net
}

TEST(PMJ02, UniformAcrossSeeds) {
    // 16-point prefixes of 2000 seeds binned on a 32 x 32 grid (finer than the 16-point strata):
    // each randomized set is uniform in distribution.
    const int grid = 32, sets = 2000, n = 16;
    std::vector<double> observed(grid * grid, 0), expected(grid * grid, double(sets) * n / (grid * grid));
    for (int s = 0; s < sets; ++s) {
        std::vector<Vec2f> pts = GeneratePMJ02(n, uint64_t(1000 + s));
        for (const Vec2f &p : pts) observed[int(p.y * grid) * grid + int(p.x * grid)] += 1;
    }
    EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(observed, expected), 1e-4));
}

TEST(PMJ02, SeedsGiveDifferentSequences) {
    std::vector<Vec2f> a = GeneratePMJ02(256, 1), b = GeneratePMJ02(256, 2), c = GeneratePMJ02(256, 1);
    int same = 0;
    for (int i = 0; i < 256; ++i) same += a[i].x == b[i].x && a[i].y == b[i].y;
    EXPECT_LT(same, 3);
    for (int i = 0; i < 256; ++i) ASSERT_TRUE(a[i].x == c[i].x && a[i].y == c[i].y) << i;   // deterministic
}

}  // namespace
}  // namespace lu
