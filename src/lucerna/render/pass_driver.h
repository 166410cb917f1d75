// Lucerna (host): the pass loop that every backend shares. One pass is one sample per pixel; the
// driver asks the backend for pass k with that pass's PathSettings, commits it to the film, sums
// the counters, shows progress, calls back, and stops at the pass count, the time limit, a false
// callback or a cancel. A backend supplies only "render pass k" (RenderPassFn).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "lucerna/integrators/stats.h"
#include "lucerna/render/film.h"
#include "lucerna/scene/render_settings.h"

namespace lu {

struct RenderStats {
    uint64_t samples = 0, rays = 0, shadowRays = 0, regConnections = 0, mneeConnections = 0;
    double regEnergy = 0, totalEnergy = 0;
    uint64_t rejected = 0;      // non-finite or negative sample values kept off the film
    RejectedSample firstRejected;   // the smallest (pixel, depth) one, with its cause (integrators/stats.h)
    double seconds = 0;         // rendering time of this run (passes), excluding scene setup
    double buildSeconds = 0;    // acceleration structure build (and upload)
    uint32_t passesThisRun = 0;
    bool interrupted = false;
};

// Called after every committed pass; return false to stop after it.
using PassCallback = std::function<bool(const FilmAccumulator &film, const RenderStats &stats)>;

// How the caller steers a render besides its settings.
struct RenderControl {
    PassCallback onPass;                        // optional
    const std::atomic<bool> *cancel = nullptr;  // set (by SIGINT/SIGTERM): abandon the pass in flight
    double syncSeconds = 0;   // distributed (render/distributed.h): seconds between film reductions; 0: at the end only
};

constexpr uint32_t NoPass = ~0u;

// One pass for the backend: its index (the sample index of every pixel), the pass the driver
// expects to ask for next (NoPass: none; a backend may start it early and must drop it if asked
// for another), and the per-path settings of both.
struct PassRequest {
    uint32_t pass = 0, next = NoPass;
    PathSettings ps, nextPs;   // of pass and of next
};

// Renders the pass into a buffer the backend owns (valid until its next call) and adds to
// `counters`; returns nullptr when the pass was abandoned because control.cancel was set.
using RenderPassFn = std::function<const PassBuffer *(const PassRequest &request, PassCounters &counters)>;

// Renders passes film.passes .. settings.spp - 1 (a resumed film continues where it stopped).
// The film must have the scene's resolution.
RenderStats RunPasses(const RenderSettings &settings, FilmAccumulator &film, const RenderControl &control,
                      const RenderPassFn &renderPass);

// The render's sampler: the scene's (every option of its Sampler directive) with the seed of the
// settings and its tables bound to the view's (host or device) arrays.
Sampler RenderSampler(const Sampler &sceneSampler, const RenderSettings &settings, const SceneView &view);

}  // namespace lu
