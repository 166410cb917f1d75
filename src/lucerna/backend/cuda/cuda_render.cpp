// Lucerna CUDA backend: the pass loop of the megakernel (cuda_render.cu), after
// backend/cpu/cpu_render.cpp: same sampler, regularization schedule, NaN guard, statistics,
// progress line, cancellation and film commit on the host; pass k + 1 renders while pass k is
// committed. Host code (CUDA runtime API), compiled by the host compiler.
#include "lucerna/scene/sampler_build.h"
#include "lucerna/backend/cuda/cuda_render.h"

#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "lucerna/backend/cuda/device_scene.h"
#include "lucerna/backend/cuda/path_kernel.h"

namespace lu {

namespace {

void Check(cudaError_t err, const char *what) {
    if (err != cudaSuccess) throw CudaError(std::string(what) + ": " + cudaGetErrorString(err));
}

// The CPU backend's progress line (backend/cpu/cpu_render.cpp), same format.
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

// One pass in flight: device pass buffer and counters, the host buffer it is copied into
// (page-locked where cudaHostRegister allows, so the copy overlaps the next pass), and an event.
struct PassSlot {
    DeviceBuffer<float> xyzw;
    DeviceBuffer<PathPassCounters> counters;
    PassBuffer host;
    PathPassCounters *hostCounters = nullptr;   // page-locked (cudaMallocHost)
    bool registered = false;
    cudaEvent_t done = nullptr;
    uint32_t passIndex = 0;
    bool inFlight = false;
};

// Owns the stream and slots; waits for in-flight work and releases everything on scope exit.
class PassPipeline {
  public:
    PassPipeline(int width, int height) {
        try {
            Check(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking), "cudaStreamCreate");
            size_t pixels = size_t(width) * height;
            for (PassSlot &s : slots_) {
                s.xyzw.Allocate(pixels * 4);
                s.counters.Allocate(1);
                s.host.Resize(width, height);
                if (!s.host.xyzw.empty()) {
                    s.registered = cudaHostRegister(s.host.xyzw.data(), s.host.xyzw.size() * sizeof(float),
                                                    cudaHostRegisterDefault) == cudaSuccess;
                    if (!s.registered) cudaGetLastError();   // pageable copies still work, only synchronously
                }
                Check(cudaMallocHost(reinterpret_cast<void **>(&s.hostCounters), sizeof(PathPassCounters)), "cudaMallocHost");
                Check(cudaEventCreateWithFlags(&s.done, cudaEventDisableTiming), "cudaEventCreate");
            }
        } catch (...) {
            Release();
            throw;
        }
    }
    ~PassPipeline() { Release(); }
    PassPipeline(const PassPipeline &) = delete;
    PassPipeline &operator=(const PassPipeline &) = delete;

    PassSlot &Slot(int i) { return slots_[i]; }

    // Enqueues pass `passIndex` into slot s: counters reset, kernel, copies back, event.
    void Launch(PassSlot &s, const SceneView &scene, PathKernelArgs args, uint32_t passIndex) {
        *s.hostCounters = PathPassCounters();
        Check(cudaMemcpyAsync(s.counters.Data(), s.hostCounters, sizeof(PathPassCounters), cudaMemcpyHostToDevice, stream_),
              "cudaMemcpyAsync (counters)");
        args.passIndex = passIndex;
        args.xyzw = s.xyzw.Data();
        args.counters = s.counters.Data();
        LaunchPathKernel(scene, args, stream_);
        Check(cudaMemcpyAsync(s.host.xyzw.data(), s.xyzw.Data(), s.xyzw.Bytes(), cudaMemcpyDeviceToHost, stream_),
              "cudaMemcpyAsync (pass buffer)");
        Check(cudaMemcpyAsync(s.hostCounters, s.counters.Data(), sizeof(PathPassCounters), cudaMemcpyDeviceToHost, stream_),
              "cudaMemcpyAsync (counters)");
        Check(cudaEventRecord(s.done, stream_), "cudaEventRecord");
        s.passIndex = passIndex;
        s.inFlight = true;
    }
    void Wait(PassSlot &s) {
        Check(cudaEventSynchronize(s.done), "PathKernel");
        s.inFlight = false;
    }

  private:
    void Release() noexcept {
        if (stream_) cudaStreamSynchronize(stream_);
        for (PassSlot &s : slots_) {
            if (s.registered) cudaHostUnregister(s.host.xyzw.data());
            if (s.hostCounters) cudaFreeHost(s.hostCounters);
            if (s.done) cudaEventDestroy(s.done);
            s.registered = false;
            s.hostCounters = nullptr;
            s.done = nullptr;
        }
        if (stream_) cudaStreamDestroy(stream_);
        stream_ = nullptr;
    }

    cudaStream_t stream_ = nullptr;
    PassSlot slots_[2];
};

}  // namespace

RenderStats RenderCUDA(const HostScene &hs, const RenderJob &job, FilmAccumulator &film, const PassCallback &onPass) {
    auto b0 = std::chrono::steady_clock::now();
    SceneView view = hs.View();
    GpuBVH bvh = BuildBVH(view);
    DeviceScene dev(view, bvh);
    double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - b0).count();
    RenderStats stats = RenderCUDA(dev, job, film, onPass);
    stats.buildSeconds = buildSeconds;
    return stats;
}

RenderStats RenderCUDA(const DeviceScene &dev, const RenderJob &job, FilmAccumulator &film, const PassCallback &onPass) {
    RenderStats stats;
    const SceneView &scene = dev.View();
    int width = scene.film.width, height = scene.film.height;
    if (film.width != width || film.height != height) film.Resize(width, height);

    PathKernelArgs args;
    args.bvh = dev.Bvh();
    args.sampler = MakeSampler(job.samplerName, job.samplerSpp, int(job.seed), width, height);
    args.width = width;
    args.height = height;
    args.ps.maxDepth = job.maxDepth;
    args.ps.strategy = LightStrategy(job.lightStrategy);
    auto argsForPass = [&](uint32_t passIndex) {
        PathKernelArgs a = args;
        a.ps.reg = RegularizationForPass(job.regularize, Float(job.regRadius), Float(job.regAngle), Float(job.regLambda), passIndex);
        return a;
    };
    uint64_t pixels = uint64_t(width) * height;

    PassPipeline pipe(width, height);
    auto t0 = std::chrono::steady_clock::now();
    double callbackSeconds = 0;   // time spent in onPass (error metrics, checkpoints): not render time
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() - callbackSeconds;
    };
    auto cancelled = [&] { return job.cancel && job.cancel->load(std::memory_order_relaxed); };

    // Pass k + 1 is launched before pass k is committed on the host, so the GPU never waits for
    // the film; a pass launched speculatively past a stop (time limit, onPass, cancel) is dropped.
    uint32_t total = uint32_t(std::max(job.spp, 0));
    int cur = 0;
    if (film.passes < total && !cancelled()) pipe.Launch(pipe.Slot(cur), dev.View(), argsForPass(film.passes), film.passes);
    while (film.passes < total) {
        if (cancelled()) { stats.interrupted = true; break; }
        PassSlot &slot = pipe.Slot(cur);
        if (!slot.inFlight) break;   // cancelled before the first launch
        if (slot.passIndex + 1 < total)
            pipe.Launch(pipe.Slot(1 - cur), dev.View(), argsForPass(slot.passIndex + 1), slot.passIndex + 1);
        pipe.Wait(slot);
        if (cancelled()) {   // abandon the pass in flight: the film keeps only complete passes
            stats.interrupted = true;
            break;
        }
        film.Commit(slot.host);
        ++stats.passesThisRun;
        const PathPassCounters &c = *slot.hostCounters;
        stats.samples += pixels;
        stats.rays += c.rays;
        stats.shadowRays += c.shadowRays;
        stats.regConnections += c.regConnections;
        stats.regEnergy += c.regEnergy;
        stats.totalEnergy += c.totalEnergy;
        if (c.rejected) {
            uint64_t key = c.firstRejected >> PathDepthBits;
            uint64_t prev = stats.firstRejectedX < 0 ? ~0ull : uint64_t(stats.firstRejectedY) * width + stats.firstRejectedX;
            if (stats.rejected == 0 || key < prev) {
                stats.firstRejectedX = int(key % uint64_t(width));
                stats.firstRejectedY = int(key / uint64_t(width));
                stats.firstRejectedDepth = int(c.firstRejected & ((1ull << PathDepthBits) - 1));
            }
            stats.rejected += c.rejected;
        }
        stats.seconds = elapsed();
        if (job.progress) PrintProgress(film.passes, total, stats.seconds, stats.samples / std::max(1e-9, stats.seconds), job.timeLimit, false);
        if (onPass) {
            auto c0 = std::chrono::steady_clock::now();
            bool more = onPass(film, stats);
            callbackSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
            if (!more) break;
        }
        if (job.timeLimit > 0 && stats.seconds >= job.timeLimit) break;
        cur = 1 - cur;
    }
    stats.seconds = elapsed();
    if (job.progress) PrintProgress(film.passes, total, stats.seconds, stats.samples / std::max(1e-9, stats.seconds), job.timeLimit, true);
    return stats;
}

}  // namespace lu
