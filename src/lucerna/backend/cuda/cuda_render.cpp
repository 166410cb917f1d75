// Lucerna CUDA backend: "render pass k" for the shared pass driver (render/pass_driver.h) with the
// megakernel (cuda_render.cu): pass k + 1 is launched before pass k is waited for, so the GPU
// renders while the host commits. Host code (CUDA runtime API), compiled by the host compiler.
#include "lucerna/backend/cuda/cuda_render.h"

#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "lucerna/backend/cuda/device_scene.h"
#include "lucerna/backend/cuda/path_kernel.h"
#include "lucerna/accel/bvh_build.h"

namespace lu {

namespace {

void Check(cudaError_t err, const char *what) {
    if (err != cudaSuccess) throw CudaError(std::string(what) + ": " + cudaGetErrorString(err));
}

// One pass in flight: device pass buffer and counters, the host buffer it is copied into
// (page-locked where cudaHostRegister allows, so the copy overlaps the next pass), and an event.
struct PassSlot {
    DeviceBuffer<float> xyzw;
    DeviceBuffer<PassCounters> counters;
    PassBuffer host;
    PassCounters *hostCounters = nullptr;   // page-locked (cudaMallocHost)
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
                Check(cudaMallocHost(reinterpret_cast<void **>(&s.hostCounters), sizeof(PassCounters)), "cudaMallocHost");
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
        *s.hostCounters = PassCounters();
        Check(cudaMemcpyAsync(s.counters.Data(), s.hostCounters, sizeof(PassCounters), cudaMemcpyHostToDevice, stream_),
              "cudaMemcpyAsync (counters)");
        args.passIndex = passIndex;
        args.xyzw = s.xyzw.Data();
        args.counters = s.counters.Data();
        LaunchPathKernel(scene, args, stream_);
        Check(cudaMemcpyAsync(s.host.xyzw.data(), s.xyzw.Data(), s.xyzw.Bytes(), cudaMemcpyDeviceToHost, stream_),
              "cudaMemcpyAsync (pass buffer)");
        Check(cudaMemcpyAsync(s.hostCounters, s.counters.Data(), sizeof(PassCounters), cudaMemcpyDeviceToHost, stream_),
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

RenderStats RenderCUDA(const DeviceScene &dev, const Sampler &sceneSampler, const RenderSettings &settings,
                       FilmAccumulator &film, const RenderControl &control) {
    const SceneView &scene = dev.View();
    int width = scene.film.width, height = scene.film.height;
    if (film.width != width || film.height != height) film.Resize(width, height);

    PathKernelArgs args;
    args.bvh = dev.Bvh();
    args.sampler = RenderSampler(sceneSampler, settings, scene);
    args.width = width;
    args.height = height;
    PassPipeline pipe(width, height);
    auto launch = [&](PassSlot &slot, uint32_t pass, const PathSettings &ps) {
        PathKernelArgs a = args;
        a.ps = ps;
        pipe.Launch(slot, scene, a, pass);
    };
    // The slot holding pass p (launched early as the previous call's `next`), else a fresh launch;
    // then the expected next pass into the other slot, then wait. A slot in flight with a pass
    // nobody asks for (the driver stopped early) is waited for and dropped.
    auto renderPass = [&](const PassRequest &req, PassCounters &counters) -> const PassBuffer * {
        PassSlot *cur = nullptr;
        for (int i = 0; i < 2; ++i)
            if (pipe.Slot(i).inFlight && pipe.Slot(i).passIndex == req.pass) cur = &pipe.Slot(i);
        if (!cur) {
            for (int i = 0; i < 2; ++i)
                if (pipe.Slot(i).inFlight) pipe.Wait(pipe.Slot(i));
            cur = &pipe.Slot(0);
            launch(*cur, req.pass, req.ps);
        }
        PassSlot &other = &pipe.Slot(0) == cur ? pipe.Slot(1) : pipe.Slot(0);
        if (req.next != NoPass && !other.inFlight) launch(other, req.next, req.nextPs);
        pipe.Wait(*cur);
        if (control.cancel && control.cancel->load(std::memory_order_relaxed)) return nullptr;
        counters = *cur->hostCounters;
        return &cur->host;
    };
    return RunPasses(settings, film, control, renderPass);
}

RenderStats RenderCUDA(const HostScene &hs, const RenderSettings &settings, FilmAccumulator &film,
                       const RenderControl &control) {
    auto b0 = std::chrono::steady_clock::now();
    SceneView view = hs.View();
    GpuBVH bvh = BuildBVH(view);
    DeviceScene dev(view, bvh);
    double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - b0).count();
    RenderStats stats = RenderCUDA(dev, hs.sampler, settings, film, control);
    stats.buildSeconds = buildSeconds;
    return stats;
}

}  // namespace lu
