// Lucerna: base-2 low-discrepancy building blocks (host and device), after pbrt-v4's
// util/lowdiscrepancy.h: the first two Sobol' dimensions (computed, no direction-number table),
// Morton codes, and the randomizers (random digit permutation, Laine-Karras/Burley fast Owen
// scrambling, and full hash-based Owen scrambling).
#pragma once

#include "lucerna/sampling/hash.h"
#include "lucerna/util/vecmath.h"

// Forced inlining for the per-dimension sampler paths (called ~20 times per camera sample).
#if defined(__CUDACC__)
#define LU_SAMPLER_INLINE __forceinline__
#elif defined(__GNUC__)
#define LU_SAMPLER_INLINE inline __attribute__((always_inline))
#else
#define LU_SAMPLER_INLINE inline
#endif

namespace lu {

// ---- Bit utilities ----

LU_HD LU_SAMPLER_INLINE uint32_t ReverseBits32(uint32_t n) {
#if defined(__CUDA_ARCH__)
    return __brev(n);
#else
#if defined(__GNUC__)
    n = __builtin_bswap32(n);
#else
    n = (n << 16) | (n >> 16);
    n = ((n & 0x00ff00ffu) << 8) | ((n & 0xff00ff00u) >> 8);
#endif
    n = ((n & 0x0f0f0f0fu) << 4) | ((n & 0xf0f0f0f0u) >> 4);
    n = ((n & 0x33333333u) << 2) | ((n & 0xccccccccu) >> 2);
    n = ((n & 0x55555555u) << 1) | ((n & 0xaaaaaaaau) >> 1);
    return n;
#endif
}

// floor(log2(v)) for v > 0.
LU_INLINE int Log2Int(uint64_t v) {
    int r = -1;
    while (v) { v >>= 1; ++r; }
    return r;
}
LU_INLINE bool IsPowerOf2(int64_t v) { return v > 0 && (v & (v - 1)) == 0; }
LU_INLINE int64_t RoundUpPow2(int64_t v) {
    int64_t p = 1;
    while (p < v) p <<= 1;
    return p;
}

// Spreads the low 32 bits of x to the even bit positions (Giesen's "Part1By1", 64-bit).
LU_INLINE uint64_t LeftShift2(uint64_t x) {
    x &= 0xffffffffull;
    x = (x ^ (x << 16)) & 0x0000ffff0000ffffull;
    x = (x ^ (x << 8)) & 0x00ff00ff00ff00ffull;
    x = (x ^ (x << 4)) & 0x0f0f0f0f0f0f0f0full;
    x = (x ^ (x << 2)) & 0x3333333333333333ull;
    x = (x ^ (x << 1)) & 0x5555555555555555ull;
    return x;
}

// Morton (Z-order) code: x in the even bits, y in the odd bits.
LU_INLINE uint64_t EncodeMorton2(uint32_t x, uint32_t y) { return (LeftShift2(y) << 1) | LeftShift2(x); }

// ---- Sobol' generator matrices of dimensions 0 and 1 ----

// Dimension 1 in bit-reversed form: bit j of the result is the XOR of the index bits k that
// contain j (C(k, j) odd, Lucas), i.e. a superset transform over GF(2) in 5 steps. Columns repeat
// after 32, so the high word of the index folds onto the low one.
LU_HD LU_SAMPLER_INLINE uint32_t SobolPascalReversed(uint64_t a) {
    uint32_t z = uint32_t(a) ^ uint32_t(a >> 32);
    z ^= (z >> 1) & 0x55555555u;
    z ^= (z >> 2) & 0x33333333u;
    z ^= (z >> 4) & 0x0f0f0f0fu;
    z ^= (z >> 8) & 0x00ff00ffu;
    z ^= (z >> 16) & 0x0000ffffu;
    return z;
}

// The 32-bit Sobol' value (before randomization) of index a in dimension 0 or 1. Dimension 0 is
// the van der Corput sequence (index bits above 31 do not contribute, as in pbrt-v4's table);
// dimension 1 is the Pascal matrix mod 2, whose columns satisfy c[k+1] = c[k] ^ (c[k] >> 1).
LU_INLINE uint32_t SobolGenerate(uint64_t a, int dimension) {
    return ReverseBits32(dimension == 0 ? uint32_t(a) : SobolPascalReversed(a));
}

// ---- Randomizers (pbrt-v4's RandomizeStrategy) ----

enum class RandomizeStrategy : uint8_t { None, PermuteDigits, FastOwen, Owen };

struct NoRandomizer {
    LU_HD uint32_t operator()(uint32_t v) const { return v; }
};

// Random digit permutation: in base 2, an XOR with a random word.
struct BinaryPermuteScrambler {
    uint32_t permutation;
    LU_HD explicit BinaryPermuteScrambler(uint32_t perm) : permutation(perm) {}
    LU_HD uint32_t operator()(uint32_t v) const { return permutation ^ v; }
};

// Fast approximate Owen scrambling: a hash that only propagates bits from high to low
// (Laine & Karras 2011, improved constants of Burley 2020 as used by pbrt-v4).
struct FastOwenScrambler {
    uint32_t seed;
    LU_HD explicit FastOwenScrambler(uint32_t seed) : seed(seed) {}
    // The scramble in bit-reversed form: operator()(v) == ReverseBits32(Reversed(ReverseBits32(v))).
    LU_HD uint32_t Reversed(uint32_t v) const {
        v ^= v * 0x3d20adeau;
        v += seed;
        v *= (seed >> 16) | 1;
        v ^= v * 0x05526c56u;
        v ^= v * 0x53a22864u;
        return v;
    }
    LU_HD uint32_t operator()(uint32_t v) const { return ReverseBits32(Reversed(ReverseBits32(v))); }
};

// Full Owen scrambling: bit b is flipped by a hash of the b higher bits.
struct OwenScrambler {
    uint32_t seed;
    LU_HD explicit OwenScrambler(uint32_t seed) : seed(seed) {}
    LU_HD uint32_t operator()(uint32_t v) const {
        if (seed & 1) v ^= 1u << 31;
        for (int b = 1; b < 32; ++b) {
            uint32_t mask = (~0u) << (32 - b);
            if (uint32_t(MixBits((v & mask) ^ seed)) & (1u << b)) v ^= 1u << (31 - b);
        }
        return v;
    }
};

// v / 2^32 as a float rounded toward zero: bits below the 24 leading significant bits are
// cleared first, so the conversion is exact. (pbrt-v4 rounds to nearest, which can carry a
// scrambled point across a stratum boundary; the two differ by at most one float ulp.)
LU_HD LU_SAMPLER_INLINE Float UInt32ToUnitFloat(uint32_t v) {
#if defined(__GNUC__) && !defined(__CUDA_ARCH__)
    // Keep the 24 bits below the leading one: shift = max(0, 8 - clz(v)).
    int shift = 8 - __builtin_clz(v | 1);
    if (shift > 0) v &= ~0u << shift;
    return Float(v) * 0x1p-32f;
#else
    uint32_t m = v | (v >> 1);
    m |= m >> 2;
    m |= m >> 4;
    m |= m >> 8;
    m |= m >> 16;
    return Float(v & ~(m >> 24)) * 0x1p-32f;
#endif
}

// Sobol' sample of index a in dimension 0 or 1, randomized, in [0, 1).
template <typename R>
LU_INLINE Float SobolSample(uint64_t a, int dimension, R randomizer) {
    return UInt32ToUnitFloat(randomizer(SobolGenerate(a, dimension)));
}

// The same with the randomizer chosen at run time; hash seeds the randomizer. The common
// fast-Owen case skips the bit reversals that cancel (the generator's and the scrambler's).
LU_HD LU_SAMPLER_INLINE Float SobolSample(uint64_t a, int dimension, RandomizeStrategy r, uint32_t hash) {
    switch (r) {
    case RandomizeStrategy::None: return SobolSample(a, dimension, NoRandomizer());
    case RandomizeStrategy::PermuteDigits: return SobolSample(a, dimension, BinaryPermuteScrambler(hash));
    case RandomizeStrategy::FastOwen: {
        uint32_t rev = dimension == 0 ? uint32_t(a) : SobolPascalReversed(a);
        return UInt32ToUnitFloat(ReverseBits32(FastOwenScrambler(hash).Reversed(rev)));
    }
    default: return SobolSample(a, dimension, OwenScrambler(hash));
    }
}

// Dimensions 0 and 1 of index a, fast-Owen scrambled with seeds hash0 and hash1.
LU_HD LU_SAMPLER_INLINE Vec2f SobolSample2DFastOwen(uint64_t a, uint32_t hash0, uint32_t hash1) {
    return {UInt32ToUnitFloat(ReverseBits32(FastOwenScrambler(hash0).Reversed(uint32_t(a)))),
            UInt32ToUnitFloat(ReverseBits32(FastOwenScrambler(hash1).Reversed(SobolPascalReversed(a))))};
}

// ---- The 24 permutations of a base-4 digit (ZSobol's per-digit shuffles) ----

// Element `digit` of permutation p (0 <= p < 24) in pbrt-v4's ZSobolSampler table order. The
// table is packed 2 bits per element, one byte per permutation, 8 permutations per word:
// {0123, 0132, 0213, 0231, 0321, 0312, 1023, 1032, 1203, 1230, 1320, 1302,
//  2103, 2130, 2013, 2031, 2301, 2310, 3120, 3102, 3210, 3201, 3021, 3012}.
LU_HD LU_SAMPLER_INLINE int PermuteBase4Digit(int p, int digit) {
#if defined(__CUDA_ARCH__)
    uint64_t word = p < 8 ? 0xb1e19c6c78d8b4e4ull : (p < 16 ? 0x72d236c68d2d39c9ull : 0x93634b1b87271e4eull);
    uint32_t perm = uint32_t(word >> (8 * (p & 7))) & 0xffu;
    return int((perm >> (2 * digit)) & 3u);
#else
    // One byte per element: p is a hash, so a branchy word selection would mispredict, and
    // variable shifts cost several micro-ops on x86.
    static constexpr uint8_t table[96] = {
        0, 1, 2, 3, 0, 1, 3, 2, 0, 2, 1, 3, 0, 2, 3, 1, 0, 3, 2, 1, 0, 3, 1, 2,
        1, 0, 2, 3, 1, 0, 3, 2, 1, 2, 0, 3, 1, 2, 3, 0, 1, 3, 2, 0, 1, 3, 0, 2,
        2, 1, 0, 3, 2, 1, 3, 0, 2, 0, 1, 3, 2, 0, 3, 1, 2, 3, 0, 1, 2, 3, 1, 0,
        3, 1, 2, 0, 3, 1, 0, 2, 3, 2, 1, 0, 3, 2, 0, 1, 3, 0, 2, 1, 3, 0, 1, 2};
    return table[4 * p + digit];
#endif
}

}  // namespace lu
