// Lucerna CPU backend: one pass = RenderPixelSample for every pixel, tiles in parallel (oneTBB).
#include "lucerna/backend/cpu/cpu_render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <memory>

#include "lucerna/accel/bvh_build.h"
#include "lucerna/backend/cpu/embree_scene.h"
#include "lucerna/geometry/bvh_traverse.h"
#include "lucerna/integrators/path.h"

namespace lu {

namespace {

template <typename Tracer>
RenderStats RenderWith(const SceneView &scene, const Tracer &tracer, const Sampler &sampler,
                       const RenderSettings &settings, FilmAccumulator &film, const RenderControl &control) {
    constexpr int kTile = 16;
    int width = scene.film.width, height = scene.film.height;
    PassBuffer pass;
    pass.Resize(width, height);
    auto renderPass = [&](const PassRequest &req, PassCounters &counters) -> const PassBuffer * {
        tbb::combinable<PassCounters> tileCounters;
        tbb::parallel_for(tbb::blocked_range2d<int>(0, height, kTile, 0, width, kTile), [&](const tbb::blocked_range2d<int> &r) {
            if (control.cancel && control.cancel->load(std::memory_order_relaxed)) return;
            PassCounters &c = tileCounters.local();
            for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                for (int x = r.cols().begin(); x < r.cols().end(); ++x)
                    RenderPixelSample(x, y, req.pass, sampler, scene, tracer, req.ps,
                                      &pass.xyzw[(size_t(y) * width + x) * 4], c);
        });
        tileCounters.combine_each([&](const PassCounters &c) { counters.Merge(c); });
        if (control.cancel && control.cancel->load()) return nullptr;
        return &pass;
    };
    return RunPasses(settings, film, control, renderPass);
}

}  // namespace

RenderStats RenderCPU(const HostScene &hs, const RenderSettings &settings, FilmAccumulator &film,
                      const RenderControl &control) {
    SceneView scene = hs.View();
    if (film.width != scene.film.width || film.height != scene.film.height) film.Resize(scene.film.width, scene.film.height);
    std::unique_ptr<tbb::global_control> threadLimit;
    if (settings.threads > 0)
        threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            size_t(settings.threads));
    Sampler sampler = RenderSampler(hs.sampler, settings, scene);
    RenderStats stats;
    if (settings.cpuTracer == CpuTracer::BVH) {
        auto t0 = std::chrono::steady_clock::now();
        GpuBVH bvh = BuildBVH(scene);
        double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        BVHTracer tracer{bvh.View(), &scene};
        stats = RenderWith(scene, tracer, sampler, settings, film, control);
        stats.buildSeconds = buildSeconds;
    } else {
        EmbreeScene embree(scene);
        EmbreeTracer tracer{&embree};
        stats = RenderWith(scene, tracer, sampler, settings, film, control);
        stats.buildSeconds = embree.BuildSeconds();
    }
    return stats;
}

}  // namespace lu
