// Lucerna: the deterministic randomness used inside stochastic BSDFs (the layered coateddiffuse
// model): MurmurHash64A over the raw bytes of the arguments and the PCG32 generator, with the
// same seeding as pbrt-v4's Hash(...) and RNG(seqIndex, offset) (util/hash.h, util/rng.h).
#pragma once

#include <cstring>

#include "lucerna/util/vecmath.h"

namespace lu {

// MurmurHash64A (Austin Appleby) of len bytes at key (8-byte aligned), seed 0 unless given.
LU_INLINE uint64_t MurmurHash64A(const unsigned char *key, int len, uint64_t seed = 0) {
    const uint64_t m = 0xc6a4a7935bd1e995ull;
    const int r = 47;
    uint64_t h = seed ^ (uint64_t(len) * m);
    int nBlocks = len / 8;
    for (int b = 0; b < nBlocks; ++b) {
        uint64_t k;
        memcpy(&k, key + 8 * b, 8);
        k *= m;
        k ^= k >> r;
        k *= m;
        h ^= k;
        h *= m;
    }
    const unsigned char *tail = key + 8 * nBlocks;
    int rem = len & 7;
    if (rem > 0) {
        for (int i = rem - 1; i >= 0; --i) h ^= uint64_t(tail[i]) << (8 * i);
        h *= m;
    }
    h ^= h >> r;
    h *= m;
    h ^= h >> r;
    return h;
}

// Hash of the concatenated bytes of the arguments (as pbrt-v4's variadic Hash()).
namespace detail {
LU_INLINE void HashCopy(unsigned char *) {}
template <typename T, typename... Args>
LU_INLINE void HashCopy(unsigned char *buf, const T &v, const Args &...args) {
    memcpy(buf, &v, sizeof(T));
    HashCopy(buf + sizeof(T), args...);
}
}  // namespace detail

template <typename... Args>
LU_INLINE uint64_t Hash(const Args &...args) {
    constexpr size_t size = (sizeof(Args) + ... + 0);
    uint64_t buf[(size + 7) / 8 > 0 ? (size + 7) / 8 : 1];
    detail::HashCopy(reinterpret_cast<unsigned char *>(buf), args...);
    return MurmurHash64A(reinterpret_cast<const unsigned char *>(buf), int(size));
}

// PCG32 (O'Neill): 64-bit LCG state, XSH-RR output.
struct RNG {
    uint64_t state = 0x853c49e6748fea9bULL, inc = 0xda3e39cb94b95bdbULL;

    LU_HD RNG() = default;
    LU_HD RNG(uint64_t seqIndex, uint64_t offset) { SetSequence(seqIndex, offset); }

    LU_HD void SetSequence(uint64_t seqIndex, uint64_t offset) {
        state = 0u;
        inc = (seqIndex << 1u) | 1u;
        Uniform32();
        state += offset;
        Uniform32();
    }
    LU_HD uint32_t Uniform32() {
        uint64_t old = state;
        state = old * 0x5851f42d4c957f2dULL + inc;
        uint32_t xorShifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = uint32_t(old >> 59u);
        return (xorShifted >> rot) | (xorShifted << ((~rot + 1u) & 31));
    }
    // Uniform in [0, 1).
    LU_HD Float UniformFloat() { return Min(OneMinusEpsilon, Float(Uniform32()) * 0x1p-32f); }
};

}  // namespace lu
