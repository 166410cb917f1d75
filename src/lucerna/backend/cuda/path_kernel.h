// Lucerna CUDA backend (internal): the interface between the megakernel (cuda_render.cu, nvcc)
// and its pass loop (cuda_render.cpp, host compiler). Plain header; both sides must see the
// same layout, so it holds only plain structs.
#pragma once

#include "lucerna/geometry/bvh.h"
#include "lucerna/integrators/path.h"

namespace lu {

struct PathKernelArgs {
    BVHView bvh;
    Sampler sampler;           // the render's sampler; each thread starts its pixel sample from a copy
    PathSettings ps;           // this pass's
    uint32_t passIndex = 0;    // = the sample index of every pixel
    int width = 0, height = 0;
    float *xyzw = nullptr;     // device pass buffer, 4 floats per pixel (PassBuffer's layout)
    PassCounters *counters = nullptr;   // device, reset by the caller
};

// Enqueues one pass of the megakernel on `stream` (a cudaStream_t); throws CudaError if the
// launch fails. `scene` holds device spans (DeviceScene::View()).
void LaunchPathKernel(const SceneView &scene, const PathKernelArgs &args, void *stream);

}  // namespace lu
