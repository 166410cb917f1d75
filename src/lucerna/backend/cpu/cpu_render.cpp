// Lucerna CPU backend: the pass loop, tiles, NaN guard, statistics and progress.
#include "lucerna/scene/sampler_build.h"
#include "lucerna/backend/cpu/cpu_render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>

#include "lucerna/backend/cpu/embree_scene.h"
#include "lucerna/integrators/path.h"

namespace lu {

namespace {

struct TileStats {
    PathStats path;
    uint64_t samples = 0, rejected = 0;
    int firstX = -1, firstY = -1, firstDepth = -1;
    uint64_t firstKey = ~0ull;   // smallest (y * width + x) rejected: deterministic "first"
};

void PrintProgress(uint32_t done, uint32_t total, double seconds, double samplesPerSec, double timeLimit, bool final) {
    double frac = total ? double(done) / total : 1;
    if (timeLimit > 0) frac = std::max(frac, std::min(1.0, seconds / timeLimit));
    double eta = frac > 0 ? seconds / frac - seconds : 0;
    int bars = int(frac * 30);
    char bar[31];
    for (int i = 0; i < 30; ++i) bar[i] = i < bars ? '#' : '.';
    bar[30] = 0;
    std::fprintf(stderr, "\r[%s] pass %u/%u  %.2f Msamples/s  elapsed %.1fs  ETA %.1fs   %s", bar, done, total,
                 samplesPerSec * 1e-6, seconds, eta, final ? "\n" : "");
    std::fflush(stderr);
}

}  // namespace

RenderStats RenderCPU(const HostScene &hs, const RenderJob &job, FilmAccumulator &film, const PassCallback &onPass) {
    RenderStats stats;
    SceneView scene = hs.View();
    int width = scene.film.width, height = scene.film.height;
    if (film.width != width || film.height != height) film.Resize(width, height);

    std::unique_ptr<tbb::global_control> threadLimit;
    if (job.threads > 0)
        threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(job.threads));

    EmbreeScene embree(scene);
    stats.buildSeconds = embree.BuildSeconds();
    EmbreeTracer tracer{&embree};
    Sampler baseSampler = MakeSampler(job.samplerName, job.samplerSpp, int(job.seed), width, height);

    PassBuffer pass;
    pass.Resize(width, height);
    auto t0 = std::chrono::steady_clock::now();
    double callbackSeconds = 0;   // time spent in onPass (error metrics, checkpoints): not render time
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() - callbackSeconds;
    };
    constexpr int kTile = 16;

    while (film.passes < uint32_t(job.spp)) {
        uint32_t passIndex = film.passes;
        PathSettings ps;
        ps.maxDepth = job.maxDepth;
        ps.strategy = LightStrategy(job.lightStrategy);
        ps.reg = RegularizationForPass(job.regularize, Float(job.regRadius), Float(job.regAngle), Float(job.regLambda), passIndex);
        tbb::combinable<TileStats> tileStats;
        bool cancelled = false;
        tbb::parallel_for(
            tbb::blocked_range2d<int>(0, height, kTile, 0, width, kTile),
            [&](const tbb::blocked_range2d<int> &r) {
                if (job.cancel && job.cancel->load(std::memory_order_relaxed)) return;
                TileStats &ts = tileStats.local();
                Sampler sampler = baseSampler;
                for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                    for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                        CameraSampleResult cs = RenderSample(x, y, passIndex, sampler, scene, tracer, ps, ts.path);
                        ++ts.samples;
                        Float xyz[3];
                        SensorXYZ(cs.L, cs.lambda, scene.spectra, scene.film.imagingRatio, xyz);
                        float *px = &pass.xyzw[(size_t(y) * width + x) * 4];
                        bool ok = std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2]) &&
                                  std::isfinite(cs.filterWeight) && cs.L.MinValue() >= 0;
                        if (!ok) {
                            ++ts.rejected;
                            uint64_t key = uint64_t(y) * width + x;
                            if (key < ts.firstKey) { ts.firstKey = key; ts.firstX = x; ts.firstY = y; ts.firstDepth = cs.depth; }
                            px[0] = px[1] = px[2] = px[3] = 0;
                            continue;
                        }
                        // pbrt-v4 RGBFilm: clamp the sample's largest component to maxComponentValue.
                        Float m = Max(xyz[0], Max(xyz[1], xyz[2]));
                        if (m > scene.film.maxComponentValue)
                            for (float &c : xyz) c *= scene.film.maxComponentValue / m;
                        px[0] = cs.filterWeight * xyz[0];
                        px[1] = cs.filterWeight * xyz[1];
                        px[2] = cs.filterWeight * xyz[2];
                        px[3] = cs.filterWeight;
                    }
            });
        if (job.cancel && job.cancel->load()) cancelled = true;
        if (cancelled) {  // abandon the partial pass: the film keeps only complete passes
            stats.interrupted = true;
            break;
        }
        film.Commit(pass);
        ++stats.passesThisRun;
        tileStats.combine_each([&](const TileStats &ts) {
            stats.samples += ts.samples;
            stats.rays += ts.path.rays;
            stats.shadowRays += ts.path.shadowRays;
            stats.regConnections += ts.path.regConnections;
            stats.regEnergy += ts.path.regEnergy;
            stats.totalEnergy += ts.path.totalEnergy;
            if (ts.rejected) {
                uint64_t key = stats.firstRejectedX < 0 ? ~0ull : uint64_t(stats.firstRejectedY) * width + stats.firstRejectedX;
                if (stats.rejected == 0 || ts.firstKey < key) {
                    stats.firstRejectedX = ts.firstX; stats.firstRejectedY = ts.firstY; stats.firstRejectedDepth = ts.firstDepth;
                }
                stats.rejected += ts.rejected;
            }
        });
        stats.seconds = elapsed();
        if (job.progress) PrintProgress(film.passes, uint32_t(job.spp), stats.seconds, stats.samples / std::max(1e-9, stats.seconds), job.timeLimit, false);
        if (onPass) {
            auto c0 = std::chrono::steady_clock::now();
            bool more = onPass(film, stats);
            callbackSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
            if (!more) break;
        }
        if (job.timeLimit > 0 && stats.seconds >= job.timeLimit) break;
    }
    stats.seconds = elapsed();
    if (job.progress) PrintProgress(film.passes, uint32_t(job.spp), stats.seconds, stats.samples / std::max(1e-9, stats.seconds), job.timeLimit, true);
    return stats;
}

}  // namespace lu
