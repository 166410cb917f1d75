// Lucerna: the PCG32 random number generator (O'Neill 2014; XSH-RR output), host and device,
// with the same seeding (SetSequence) and jump-ahead (Advance) as pbrt-v4's util/rng.h, so a
// sequence index and offset give the same numbers as pbrt-v4.
#pragma once

#include "lucerna/sampling/hash.h"

namespace lu {

class RNG {
  public:
    static constexpr uint64_t DefaultState = 0x853c49e6748fea9bull;
    static constexpr uint64_t DefaultStream = 0xda3e39cb94b95bdbull;
    static constexpr uint64_t Mult = 0x5851f42d4c957f2dull;

    LU_HD RNG() : state(DefaultState), inc(DefaultStream) {}
    LU_HD RNG(uint64_t seqIndex, uint64_t offset) { SetSequence(seqIndex, offset); }
    LU_HD explicit RNG(uint64_t seqIndex) { SetSequence(seqIndex); }

    // Selects stream seqIndex (2^63 distinct streams) and a starting point given by seed.
    LU_HD void SetSequence(uint64_t seqIndex, uint64_t seed);
    LU_HD void SetSequence(uint64_t seqIndex) { SetSequence(seqIndex, MixBits(seqIndex)); }

    // Uniform<uint32_t>: all 32-bit values; Uniform<uint64_t>: two draws; Uniform<float> and
    // Uniform<double>: [0, 1), never 1.
    template <typename T>
    LU_HD T Uniform();

    // Short names for the two common draws (used by the stochastic BSDFs).
    LU_HD uint32_t Uniform32();
    LU_HD Float UniformFloat();

    // Uniform integer in [0, bound) without modulo bias (bound > 0).
    LU_HD uint32_t UniformBounded(uint32_t bound);

    // Skips delta draws (negative delta goes back) in O(log delta) (Brown 1994).
    LU_HD void Advance(int64_t idelta);

    // Number of draws from `other` to *this (same stream required).
    LU_HD int64_t operator-(const RNG &other) const {
        uint64_t curMult = Mult, curPlus = inc, curState = other.state;
        uint64_t theBit = 1u, distance = 0u;
        while (state != curState) {
            if ((state & theBit) != (curState & theBit)) {
                curState = curState * curMult + curPlus;
                distance |= theBit;
            }
            theBit <<= 1;
            curPlus = (curMult + 1ull) * curPlus;
            curMult *= curMult;
        }
        return int64_t(distance);
    }

    LU_HD bool operator==(const RNG &o) const { return state == o.state && inc == o.inc; }

  private:
    uint64_t state, inc;
};

#if !defined(__CUDA_ARCH__)
namespace detail {
// The LCG step s -> Mult s + inc applied 2^k times is s -> mult[k] s + inc * plus[k]
// (Brown 1994's squarings, which do not depend on the state or the stream): tabulated once, so
// Advance only visits the set bits of delta, with no chain of squarings.
struct PCGJumpTable {
    uint64_t mult[64], plus[64];
};
constexpr PCGJumpTable MakePCGJumpTable() {
    PCGJumpTable t{};
    uint64_t m = 0x5851f42d4c957f2dull, c = 1;
    for (int k = 0; k < 64; ++k) {
        t.mult[k] = m;
        t.plus[k] = c;
        c = (m + 1) * c;
        m *= m;
    }
    return t;
}
inline constexpr PCGJumpTable kPCGJump = MakePCGJumpTable();
}  // namespace detail
#endif

LU_INLINE void RNG::Advance(int64_t idelta) {
    uint64_t accMult = 1u, accPlus = 0u;
    uint64_t delta = uint64_t(idelta);
#if !defined(__CUDA_ARCH__) && defined(__GNUC__)
    while (delta > 0) {
        int k = __builtin_ctzll(delta);
        delta &= delta - 1;
        accMult *= detail::kPCGJump.mult[k];
        accPlus = accPlus * detail::kPCGJump.mult[k] + inc * detail::kPCGJump.plus[k];
    }
#else
    uint64_t curMult = Mult, curPlus = inc;
    while (delta > 0) {
        if (delta & 1) {
            accMult *= curMult;
            accPlus = accPlus * curMult + curPlus;
        }
        curPlus = (curMult + 1) * curPlus;
        curMult *= curMult;
        delta /= 2;
    }
#endif
    state = accMult * state + accPlus;
}

template <>
LU_INLINE uint32_t RNG::Uniform<uint32_t>() {
    uint64_t oldState = state;
    state = oldState * Mult + inc;
    uint32_t xorShifted = uint32_t(((oldState >> 18u) ^ oldState) >> 27u);
    uint32_t rot = uint32_t(oldState >> 59u);
    return (xorShifted >> rot) | (xorShifted << ((~rot + 1u) & 31));
}

template <>
LU_INLINE uint64_t RNG::Uniform<uint64_t>() {
    uint64_t v0 = Uniform<uint32_t>(), v1 = Uniform<uint32_t>();
    return (v0 << 32) | v1;
}

template <>
LU_INLINE float RNG::Uniform<float>() {
    return Min<float>(OneMinusEpsilon, Uniform<uint32_t>() * 0x1p-32f);
}

template <>
LU_INLINE double RNG::Uniform<double>() {
    return Min<double>(0x1.fffffffffffffp-1, Uniform<uint64_t>() * 0x1p-64);
}

LU_INLINE void RNG::SetSequence(uint64_t seqIndex, uint64_t seed) {
    state = 0u;
    inc = (seqIndex << 1u) | 1u;
    Uniform<uint32_t>();
    state += seed;
    Uniform<uint32_t>();
}

LU_INLINE uint32_t RNG::Uniform32() { return Uniform<uint32_t>(); }
LU_INLINE Float RNG::UniformFloat() { return Uniform<float>(); }

LU_INLINE uint32_t RNG::UniformBounded(uint32_t bound) {
    uint32_t threshold = (~bound + 1u) % bound;
    while (true) {
        uint32_t r = Uniform<uint32_t>();
        if (r >= threshold) return r % bound;
    }
}

}  // namespace lu
