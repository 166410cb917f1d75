// Lucerna: what a backend is asked to render and what it reports (host, backend-neutral).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "lucerna/render/film.h"

namespace lu {

struct RenderJob {
    int spp = 16;               // total passes wanted (one sample per pixel per pass)
    double timeLimit = 0;       // seconds; > 0: stop at the first pass boundary after it
    uint32_t seed = 0;
    int maxDepth = 5;
    bool regularize = false;
    double regRadius = 0;       // r0 (world units), resolved (> 0) when regularize
    double regLambda = 1.0 / 6;
    double regAngle = 0;        // sigma0 (radians), resolved
    int threads = 0;            // 0: all cores
    bool progress = true;       // progress bar on stderr
    std::string samplerName = "zsobol";
    int samplerSpp = 16;        // the sampling pattern's size (the scene's Sampler "pixelsamples"): fixed
                                // whatever the number of passes, so resumed or extended renders match
    int lightStrategy = 0;      // 0 MIS, 1 NEE only, 2 BSDF only (tests)
    const std::atomic<bool> *cancel = nullptr;  // set by SIGINT/SIGTERM: abandon the pass in flight
};

struct RenderStats {
    uint64_t samples = 0, rays = 0, shadowRays = 0, regConnections = 0;
    double regEnergy = 0, totalEnergy = 0;
    uint64_t rejected = 0;      // non-finite or negative sample values kept off the film
    int firstRejectedX = -1, firstRejectedY = -1, firstRejectedDepth = -1;
    double seconds = 0;         // rendering time of this run (passes), excluding scene setup
    double buildSeconds = 0;    // acceleration structure build
    uint32_t passesThisRun = 0;
    bool interrupted = false;
};

// Called after every committed pass; return false to stop after it.
using PassCallback = std::function<bool(const FilmAccumulator &film, const RenderStats &stats)>;

}  // namespace lu
