// Lucerna (host): progressive multi-jittered (0,2) sample sequences (Christensen, Kensler,
// Kilpatrick 2018, "Progressive Multi-Jittered Sample Sequences", the pmj02 construction), our own
// generator: every prefix of 2^k points is a (0,2)-net in base 2 (each elementary interval of area
// 2^-k holds exactly one point). Built at scene-build time for the pmj02bn sampler's tables.
#pragma once

#include <cstdint>
#include <vector>

#include "lucerna/sampling/sampler.h"
#include "lucerna/util/vecmath.h"

namespace lu {

// count points (a power of two, 1 .. 2^20) of one pmj02 sequence, from seed. *restarts (when
// given) receives how many times the construction met a dead end and began again.
std::vector<Vec2f> GeneratePMJ02(uint32_t count, uint64_t seed, int *restarts = nullptr);

// Whether points[0, 2^log2n) is a (0,2)-net in base 2: for every a in 0..log2n, each of the
// 2^a x 2^(log2n - a) elementary intervals holds exactly one point.
bool IsZeroTwoNet(const std::vector<Vec2f> &points, int log2n);

// The pmj02bn sampler's tables (pbrt-v4's PMJ02BNSampler with Lucerna's own sequences instead of
// pbrt-v4's tabulated ones): kPMJ02BNSets sequences; the first (kPMJ02BNSamples points) spread
// over a tile of tileSize^2 pixels, spp in each (pixel samples, their offsets within the pixel),
// then spp points of each set. Laid out as the sampler reads them (Sampler::pmjPoints):
// [tileSize^2 * spp pixel samples][set 0 .. set 4, spp points each]. Throws
// std::invalid_argument for spp outside [1, kPMJ02BNSamples].
std::vector<Vec2f> BuildPMJ02BNTables(int spp, uint64_t seed, int *tileSize);

}  // namespace lu
