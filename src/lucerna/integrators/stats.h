// Lucerna: counters of the per-path code (host and device): what one path did (PathStats) and what
// one pass of the image did (PassCounters), which every backend sums in its own way (per thread on
// the CPU, warp reductions and atomics on the GPU) and the pass driver adds up.
#pragma once

#include "lucerna/util/common.h"

namespace lu {

// Counters of one path.
struct PathStats {
    uint64_t rays = 0;               // camera + extension + shadow rays
    uint64_t shadowRays = 0;
    uint64_t regConnections = 0;     // regularized connections that contributed
    uint64_t mneeConnections = 0;    // manifold NEE connections that contributed
    Float regEnergy = 0;             // luminance-like sum (average over wavelengths) they carried
    Float totalEnergy = 0;           // same for the whole path
    bool invalid = false;            // the path's throughput became non-finite: the sample is rejected
};

// A rejected sample (non-finite or negative value kept off the film) identified by its pixel and
// path depth; the smallest key of a pass is its deterministic "first" rejected sample.
constexpr int RejectedDepthBits = 24;
LU_INLINE uint64_t RejectedSampleKey(int x, int y, int width, int depth) {
    uint64_t d = uint64_t(Min(Max(depth, 0), (1 << RejectedDepthBits) - 1));
    return ((uint64_t(y) * uint64_t(width) + uint64_t(x)) << RejectedDepthBits) | d;
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
