// Lucerna CUDA backend: progressive rendering with the shared path integrator in one megakernel
// (one thread per pixel per pass), the GPU counterpart of backend/cpu/cpu_render.h. Plain header:
// host code compiled without nvcc may call it (defined in lucerna_cuda only).
#pragma once

#include "lucerna/render/render_job.h"
#include "lucerna/scene/builder.h"

namespace lu {

// Renders passes film.passes .. job.spp-1 on CUDA device 0, with the same contract as RenderCPU:
// one pass is one sample per pixel (sample index = pass index, sampler from MakeSampler), the
// pass is committed to `film` on the host after each kernel, non-finite or negative samples are
// kept off the film and counted, job.timeLimit / job.cancel / onPass are honoured at pass
// boundaries (a cancelled pass is abandoned). job.threads is ignored. stats.buildSeconds covers
// the BVH build and the upload. Throws CudaError (backend/cuda/device_buffer.h) on device failures.
RenderStats RenderCUDA(const HostScene &scene, const RenderJob &job, FilmAccumulator &film, const PassCallback &onPass = {});

class DeviceScene;
// The same over a scene already on the device (DeviceScene of HostScene::View() and its BuildBVH),
// for callers that render one scene many times (tests, benchmarks); stats.buildSeconds is 0.
RenderStats RenderCUDA(const DeviceScene &scene, const RenderJob &job, FilmAccumulator &film, const PassCallback &onPass = {});

}  // namespace lu
