// The optimized sampler paths (sampler.h, lowdiscrepancy.h) against straightforward reference
// versions of the same formulas (the pre-optimization code): every value must be bit-identical.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <vector>

#include "lucerna/scene/sampler_build.h"
#include "lucerna/sampling/sampler.h"

using namespace lu;

namespace {

uint32_t RefReverseBits32(uint32_t n) {
    uint32_t r = 0;
    for (int i = 0; i < 32; ++i) r |= ((n >> i) & 1u) << (31 - i);
    return r;
}

uint32_t RefSobolGenerate(uint64_t a, int dimension) {
    if (dimension == 0) return RefReverseBits32(uint32_t(a));
    uint32_t v = 0, c = 0x80000000u;
    for (; a != 0; a >>= 1) {
        if (a & 1) v ^= c;
        c ^= c >> 1;
    }
    return v;
}

uint32_t RefFastOwen(uint32_t v, uint32_t seed) {
    v = RefReverseBits32(v);
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return RefReverseBits32(v);
}

// Reference: keep the 24 leading significant bits of v (what a float holds exactly), found by a
// plain scan for the highest set bit, then scale by 2^-32.
float RefUInt32ToUnitFloat(uint32_t v) {
    int top = 31;
    while (top >= 0 && ((v >> top) & 1u) == 0) --top;
    if (top >= 24) v &= ~((1u << (top - 23)) - 1u);
    return float(v) * 0x1p-32f;
}

int RefPermuteBase4Digit(int p, int digit) {
    static const char *perms[24] = {"0123", "0132", "0213", "0231", "0321", "0312", "1023", "1032",
                                    "1203", "1230", "1320", "1302", "2103", "2130", "2013", "2031",
                                    "2301", "2310", "3120", "3102", "3210", "3201", "3021", "3012"};
    return perms[p][digit] - '0';
}

// pbrt-v4's ZSobolSampler::GetSampleIndex, digit loop from high to low as written there.
uint64_t RefZSobolIndex(uint64_t mortonIndex, int dimension, int log2Spp, int nBase4Digits) {
    uint64_t index = 0;
    bool pow2Samples = log2Spp & 1;
    int lastDigit = pow2Samples ? 1 : 0;
    uint64_t dimMix = uint64_t(int64_t(int32_t(0x55555555u * uint32_t(dimension))));
    for (int i = nBase4Digits - 1; i >= lastDigit; --i) {
        int digitShift = 2 * i - (pow2Samples ? 1 : 0);
        int digit = int((mortonIndex >> digitShift) & 3);
        uint64_t higherDigits = mortonIndex >> (digitShift + 2);
        int p = int((MixBits(higherDigits ^ dimMix) >> 24) % 24);
        index |= uint64_t(RefPermuteBase4Digit(p, digit)) << digitShift;
    }
    if (pow2Samples) index |= (mortonIndex & 1) ^ (MixBits((mortonIndex >> 1) ^ dimMix) & 1);
    return index;
}

// The digit-shuffle levels this CPU runs (0: scalar, 1: AVX2, 2: AVX-512).
const std::vector<uint8_t> &SupportedLevels() {
    static std::vector<uint8_t> levels = [] {
        std::vector<uint8_t> l = {0};
#if defined(LU_ZSOBOL_SIMD)
        for (uint8_t i = 1; i <= detail::ZSobolSimdLevel(); ++i) l.push_back(i);
#endif
        return l;
    }();
    return levels;
}

}  // namespace

TEST(SamplerFastPath, SimdDigitShufflesMatchReference) {
    std::printf("ZSobol digit levels tested: %zu (0 scalar, 1 AVX2, 2 AVX-512)\n", SupportedLevels().size());
    std::mt19937_64 rng(5);
    for (int i = 0; i < 100000; ++i) {
        int log2Spp = int(rng() % 2);   // exercise both the even and the odd (extra binary digit) layouts
        int nDigits = 1 + int(rng() % 31);   // below 64 bits (pbrt-v4 shifts by 64 at 32 digits)
        uint64_t rest = rng();
        if (nDigits < 32) rest &= (uint64_t(1) << (2 * nDigits)) - 1;
        int dimension = int(rng() % 4096) - (i % 7 == 0 ? 2048 : 0);
        uint64_t morton = log2Spp ? (rest << 1) | (rng() & 1) : rest;
        uint64_t ref = RefZSobolIndex(morton, dimension, log2Spp, nDigits + log2Spp);
        Sampler s;
        s.log2SamplesPerPixel = log2Spp;
        s.nBase4Digits = nDigits + log2Spp;
        s.mortonIndex = morton;
        s.dimension = dimension;
        for (uint8_t level : SupportedLevels()) {
            s.simd = level;
            ASSERT_EQ(s.ZSobolSampleIndex(), ref) << "level " << int(level) << " nDigits " << nDigits;
        }
    }
}

TEST(SamplerFastPath, BitUtilitiesMatchReference) {
    std::mt19937_64 rng(7);
    for (int i = 0; i < 200000; ++i) {
        uint64_t a = rng();
        if (i % 3 == 1) a >>= (i % 64);
        uint32_t v = uint32_t(rng() >> (i % 32));
        ASSERT_EQ(ReverseBits32(v), RefReverseBits32(v));
        ASSERT_EQ(SobolGenerate(a, 0), RefSobolGenerate(a, 0));
        ASSERT_EQ(SobolGenerate(a, 1), RefSobolGenerate(a, 1)) << a;
        ASSERT_EQ(UInt32ToUnitFloat(v), RefUInt32ToUnitFloat(v)) << v;
        uint32_t seed = uint32_t(rng());
        ASSERT_EQ(FastOwenScrambler(seed)(v), RefFastOwen(v, seed));
        for (int dim = 0; dim < 2; ++dim) {
            float ref = RefUInt32ToUnitFloat(RefFastOwen(RefSobolGenerate(a, dim), seed));
            ASSERT_EQ(SobolSample(a, dim, RandomizeStrategy::FastOwen, seed), ref);
            ASSERT_EQ(SobolSample(a, dim, RandomizeStrategy::PermuteDigits, seed),
                      RefUInt32ToUnitFloat(seed ^ RefSobolGenerate(a, dim)));
            ASSERT_EQ(SobolSample(a, dim, RandomizeStrategy::None, seed), RefUInt32ToUnitFloat(RefSobolGenerate(a, dim)));
        }
    }
    for (uint32_t v : {0u, 1u, 0xffu, 0xffffffu, 0x1000000u, 0x1ffffffu, 0x80000000u, 0xffffffffu})
        EXPECT_EQ(UInt32ToUnitFloat(v), RefUInt32ToUnitFloat(v)) << v;
    for (int p = 0; p < 24; ++p)
        for (int d = 0; d < 4; ++d) EXPECT_EQ(PermuteBase4Digit(p, d), RefPermuteBase4Digit(p, d));
}

TEST(SamplerFastPath, ZSobolIndexAndValuesMatchReference) {
    std::mt19937 rng(11);
    for (int spp : {1, 2, 4, 8, 16, 64, 128, 1024}) {
        for (auto [w, h] : {std::pair{1, 1}, {32, 32}, {128, 128}, {192, 108}, {1280, 720}}) {
            Sampler s = MakeSampler("zsobol", spp, 3, w, h);
            for (int trial = 0; trial < 200; ++trial) {
                s.simd = SupportedLevels()[trial % SupportedLevels().size()];
                int x = int(rng() % w), y = int(rng() % h), index = int(rng() % (2 * spp));
                s.StartPixelSample(x, y, index);
                for (int dim = 0; dim < 40; ++dim) {
                    uint64_t ref = RefZSobolIndex(s.mortonIndex, s.dimension, s.log2SamplesPerPixel, s.nBase4Digits);
                    ASSERT_EQ(s.ZSobolSampleIndex(), ref) << spp << " " << w << "x" << h << " dim " << dim;
                    // The value path: pbrt-v4's SobolSample with the dimension's hash.
                    int d = s.dimension;
                    uint64_t bits = MixBits(uint64_t(int64_t((d + 2) ^ s.passSeed)));
                    Vec2f u = s.Get2D();
                    ASSERT_EQ(u.x, RefUInt32ToUnitFloat(RefFastOwen(RefSobolGenerate(ref, 0), uint32_t(bits))));
                    ASSERT_EQ(u.y, RefUInt32ToUnitFloat(RefFastOwen(RefSobolGenerate(ref, 1), uint32_t(bits >> 32))));
                    s.dimension = d + 1;   // next start: the following dimension
                }
            }
        }
    }
}
