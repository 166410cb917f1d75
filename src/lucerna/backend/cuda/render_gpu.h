// Lucerna CUDA backend: the rendering entry point (one megakernel, one thread per pixel).
// Plain header, callable from host code compiled without nvcc.
#pragma once

#include <cstdint>
#include <vector>

#include "lucerna/backend/cuda/device_scene.h"

namespace lu {

enum class GpuRenderMode : uint8_t {
    EyeLight,   // debug: |cos| between the geometric normal and the view direction, grey
    Path        // not here: the path integrator runs in RenderCUDA (backend/cuda/cuda_render.h)
};

struct GpuRenderSettings {
    int width = 0, height = 0;   // 0: the film resolution of the scene
    int spp = 1;
    uint32_t seed = 0;
    GpuRenderMode mode = GpuRenderMode::EyeLight;
};

// Renders the scene and returns width * height * 3 floats (linear RGB, row-major, top row
// first). Throws CudaError on device failures and std::runtime_error for GpuRenderMode::Path
// (use RenderCUDA).
std::vector<float> RenderGpu(const DeviceScene &scene, const GpuRenderSettings &settings);

}  // namespace lu
