// Lucerna CUDA backend: progressive rendering with the shared path integrator in one megakernel
// (one thread per pixel per pass), the GPU counterpart of backend/cpu/cpu_render.h. Plain header:
// host code compiled without nvcc may call it (defined in lucerna_cuda only).
#pragma once

#include "lucerna/render/pass_driver.h"
#include "lucerna/scene/builder.h"

namespace lu {

// Renders passes film.passes .. settings.spp - 1 on CUDA device 0 through the shared pass driver,
// with the same contract as RenderCPU (settings.threads and cpuTracer are ignored).
// stats.buildSeconds covers the BVH build and the upload. Throws CudaError
// (backend/cuda/device_buffer.h) on device failures.
RenderStats RenderCUDA(const HostScene &scene, const RenderSettings &settings, FilmAccumulator &film,
                       const RenderControl &control = {});

class DeviceScene;
// The same over a scene already on the device (DeviceScene of HostScene::View() and its BuildBVH),
// for callers that render one scene many times (tests, benchmarks); stats.buildSeconds is 0.
RenderStats RenderCUDA(const DeviceScene &scene, const Sampler &sceneSampler, const RenderSettings &settings,
                       FilmAccumulator &film, const RenderControl &control = {});

}  // namespace lu
