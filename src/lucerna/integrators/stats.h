// Lucerna: counters of the per-path code (host and device): what one path did (PathStats) and what
// one pass of the image did (PassCounters), which every backend sums in its own way (per thread on
// the CPU, warp reductions and atomics on the GPU) and the pass driver adds up.
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/spectrum/sampled.h"

namespace lu {

// Why a sample was rejected: where the first non-finite or negative value of its path came from.
// Film: every contribution was finite and non-negative, but the film value was not (XYZ overflow,
// a non-finite filter weight).
enum class RejectCause : uint8_t { None = 0, Emission, Direct, Scatter, Medium, Film };
// What the value was: NaN, +-Inf, or negative.
enum class BadValue : uint8_t { NaN = 0, Infinite, Negative };

// Counters of one path.
struct PathStats {
    uint64_t rays = 0;               // camera + extension + shadow rays
    uint64_t shadowRays = 0;
    uint64_t regConnections = 0;     // regularized connections that contributed
    uint64_t mneeConnections = 0;    // manifold NEE connections that contributed
    Float regEnergy = 0;             // luminance-like sum (average over wavelengths) they carried
    Float totalEnergy = 0;           // same for the whole path
    bool invalid = false;            // the path's throughput became non-finite: the sample is rejected
    // The first bad value of the path (cause None: none yet): its source and the vertex depth.
    RejectCause cause = RejectCause::None;
    BadValue badValue = BadValue::NaN;
    uint32_t causeEntity = NoIndex;  // Emission: light; Direct, Scatter: material; Medium: medium
    int causeDepth = 0;
};

// The kind of bad value in v, or false when every wavelength is finite and non-negative.
LU_INLINE bool FindBadValue(const SampledSpectrum &v, BadValue *kind) {
    bool neg = false;
    for (int i = 0; i < NSpectrumSamples; ++i) {
        if (std::isnan(v[i])) { *kind = BadValue::NaN; return true; }
        if (std::isinf(v[i])) { *kind = BadValue::Infinite; return true; }
        neg |= v[i] < 0;
    }
    if (neg) *kind = BadValue::Negative;
    return neg;
}

// True when every wavelength is finite and non-negative (one pass of comparisons, no branches:
// NaN fails both).
LU_INLINE bool AllFiniteNonNegative(const SampledSpectrum &v) {
    int ok = 1;
    for (int i = 0; i < NSpectrumSamples; ++i) ok &= int(v[i] >= 0) & int(v[i] <= Float(3.402823466e38));
    return ok != 0;
}

// Records the first bad value of a path: a contribution (or throughput) v from `cause` at entity
// `entity` (light, material or medium index) and depth. Returns true when v is bad.
LU_INLINE bool NoteBadValue(PathStats &st, const SampledSpectrum &v, RejectCause cause, uint32_t entity, int depth) {
    if (AllFiniteNonNegative(v)) return false;
    BadValue kind;
    if (!FindBadValue(v, &kind)) return false;
    // The first bad value, except that a NaN or Inf later on the path outranks a negative value
    // (a NaN is what makes the sample rejected whatever else the path adds).
    if (st.cause == RejectCause::None || (st.badValue == BadValue::Negative && kind != BadValue::Negative)) {
        st.cause = cause;
        st.badValue = kind;
        st.causeEntity = entity;
        st.causeDepth = depth;
    }
    return true;
}

// A rejected sample (kept off the film) as one 64-bit key: pixel (28 bits, high), depth (10),
// cause (3), value kind (2), entity (21, all ones: none or out of range). The smallest key of a
// pass is its deterministic "first" rejected sample (by pixel, then depth); the GPU reduces keys
// with atomicMin, MPI with MPI_MIN, so the cause travels with the location.
constexpr int RejectedEntityBits = 21, RejectedKindBits = 2, RejectedCauseBits = 3, RejectedDepthBits = 10;
constexpr int RejectedLowBits = RejectedEntityBits + RejectedKindBits + RejectedCauseBits + RejectedDepthBits;
constexpr uint64_t RejectedMaxPixel = (1ull << (64 - RejectedLowBits)) - 1;
constexpr uint32_t RejectedNoEntity = (1u << RejectedEntityBits) - 1;

// The decoded key (x < 0: no rejected sample).
struct RejectedSample {
    int x = -1, y = -1, depth = -1;
    RejectCause cause = RejectCause::None;
    BadValue badValue = BadValue::NaN;
    uint32_t entity = NoIndex;
    LU_HD bool Valid() const { return x >= 0; }
};

LU_INLINE uint64_t RejectedSampleKey(int x, int y, int width, int depth, RejectCause cause = RejectCause::Film,
                                     BadValue kind = BadValue::NaN, uint32_t entity = NoIndex) {
    uint64_t pixel = Min<uint64_t>(uint64_t(y) * uint64_t(width) + uint64_t(x), RejectedMaxPixel);
    uint64_t d = uint64_t(Min(Max(depth, 0), (1 << RejectedDepthBits) - 1));
    uint64_t e = entity < RejectedNoEntity ? entity : RejectedNoEntity;
    return (pixel << RejectedLowBits) | (d << (RejectedEntityBits + RejectedKindBits + RejectedCauseBits)) |
           (uint64_t(cause) << (RejectedEntityBits + RejectedKindBits)) | (uint64_t(kind) << RejectedEntityBits) | e;
}

LU_INLINE RejectedSample DecodeRejectedSampleKey(uint64_t key, int width) {
    RejectedSample r;
    if (key == ~0ull || width <= 0) return r;
    uint64_t pixel = key >> RejectedLowBits;
    r.x = int(pixel % uint64_t(width));
    r.y = int(pixel / uint64_t(width));
    r.depth = int((key >> (RejectedEntityBits + RejectedKindBits + RejectedCauseBits)) & ((1u << RejectedDepthBits) - 1));
    r.cause = RejectCause((key >> (RejectedEntityBits + RejectedKindBits)) & ((1u << RejectedCauseBits) - 1));
    r.badValue = BadValue((key >> RejectedEntityBits) & ((1u << RejectedKindBits) - 1));
    uint32_t e = uint32_t(key & RejectedNoEntity);
    r.entity = e == RejectedNoEntity ? NoIndex : e;
    return r;
}

// Counters of one pass (or of a tile or warp of it).
struct PassCounters {
    unsigned long long rays = 0, shadowRays = 0, regConnections = 0, mneeConnections = 0, rejected = 0;
    unsigned long long firstRejected = ~0ull;   // smallest RejectedSampleKey
    double regEnergy = 0, totalEnergy = 0;

    LU_HD void Add(const PathStats &s) {
        rays += s.rays;
        shadowRays += s.shadowRays;
        regConnections += s.regConnections;
        mneeConnections += s.mneeConnections;
        regEnergy += double(s.regEnergy);
        totalEnergy += double(s.totalEnergy);
    }
    LU_HD void Reject(uint64_t key) {
        ++rejected;
        firstRejected = Min<unsigned long long>(firstRejected, key);
    }
    LU_HD void Merge(const PassCounters &c) {
        rays += c.rays;
        shadowRays += c.shadowRays;
        regConnections += c.regConnections;
        mneeConnections += c.mneeConnections;
        rejected += c.rejected;
        firstRejected = Min(firstRejected, c.firstRejected);
        regEnergy += c.regEnergy;
        totalEnergy += c.totalEnergy;
    }
};

}  // namespace lu
