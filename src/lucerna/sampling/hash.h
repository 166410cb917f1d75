// Lucerna: deterministic hashing for samplers and seeds (host and device), after pbrt-v4's
// util/hash.h (MurmurHash64A, MixBits = Stafford's variant 13 finalizer) and Kensler's
// PermutationElement (pbrt-v4 util/math.h). Never std::hash: values must match on CPU and GPU.
#pragma once

#include <cstring>

#include "lucerna/util/common.h"

namespace lu {

// 64-bit finalizer (Stafford mix13, as pbrt-v4's MixBits): a bijection with good avalanche.
LU_INLINE uint64_t MixBits(uint64_t v) {
    v ^= (v >> 31);
    v *= 0x7fb5d329728ea185ull;
    v ^= (v >> 27);
    v *= 0x81dadef4bc2dd44dull;
    v ^= (v >> 33);
    return v;
}

// MurmurHash64A over len bytes (Austin Appleby, public domain), byte-wise tail as pbrt-v4.
LU_INLINE uint64_t MurmurHash64A(const unsigned char *key, size_t len, uint64_t seed = 0) {
    const uint64_t m = 0xc6a4a7935bd1e995ull;
    const int r = 47;
    uint64_t h = seed ^ (uint64_t(len) * m);
    size_t nBlocks = len / 8;
    for (size_t i = 0; i < nBlocks; ++i) {
        uint64_t k;
        memcpy(&k, key + 8 * i, 8);
        k *= m;
        k ^= k >> r;
        k *= m;
        h ^= k;
        h *= m;
    }
    const unsigned char *tail = key + 8 * nBlocks;
    size_t rest = len & 7;
    if (rest > 0) {
        for (size_t i = rest; i-- > 0;) h ^= uint64_t(tail[i]) << (8 * i);
        h *= m;
    }
    h ^= h >> r;
    h *= m;
    h ^= h >> r;
    return h;
}

LU_INLINE uint64_t HashBuffer(const void *ptr, size_t size, uint64_t seed = 0) {
    return MurmurHash64A(static_cast<const unsigned char *>(ptr), size, seed);
}

namespace detail {
LU_INLINE void HashCopy(unsigned char *) {}
template <typename T, typename... Args>
LU_INLINE void HashCopy(unsigned char *buf, T v, Args... args) {
    memcpy(buf, &v, sizeof(T));
    HashCopy(buf + sizeof(T), args...);
}
}  // namespace detail

// Hash of the bytes of several trivially copyable values, packed without padding (as pbrt-v4's
// Hash(args...)): Hash(1, 2.f) hashes the 8 bytes of an int followed by a float.
template <typename... Args>
LU_INLINE uint64_t Hash(Args... args) {
    constexpr size_t sz = (sizeof(Args) + ... + 0);
    unsigned char buf[sz > 0 ? sz : 1];
    detail::HashCopy(buf, args...);
    return MurmurHash64A(buf, sz, 0);
}

// A uniform float in [0,1) from a hash of the arguments.
template <typename... Args>
LU_INLINE Float HashFloat(Args... args) {
    return uint32_t(Hash(args...)) * 0x1p-32f;
}

// The i-th element (i < n) of a pseudo-random permutation of [0, n) selected by seed p
// (Kensler 2013, "Correlated Multi-Jittered Sampling", as pbrt-v4's PermutationElement).
LU_INLINE int PermutationElement(uint32_t i, uint32_t n, uint32_t p) {
    uint32_t w = n - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    do {
        i ^= p;
        i *= 0xe170893d;
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i *= 0x0929eb3f;
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i *= 1 | p >> 27;
        i *= 0x6935fa69;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3;
        i ^= (i & w) >> 2;
        i *= 0xc860a3df;
        i &= w;
        i ^= i >> 5;
    } while (i >= n);
    return int((i + p) % n);
}

}  // namespace lu
