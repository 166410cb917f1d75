// Lucerna CUDA backend: ray queries through the shared BVH traversal (geometry/bvh_traverse.h)
// on the GPU, for the CPU/GPU agreement tests and the rays/s benchmark. Plain header.
#pragma once

#include <cstdint>
#include <vector>

#include "lucerna/backend/cuda/device_scene.h"
#include "lucerna/core/interaction.h"

namespace lu {

// Closest hit of each ray (one thread per ray); misses keep HitRecord's defaults.
std::vector<HitRecord> TraceClosestGpu(const DeviceScene &scene, const std::vector<Ray> &rays);

// Occlusion of each ray in (0, ray.tMax): 1 if anything is hit, else 0.
std::vector<uint8_t> TraceAnyGpu(const DeviceScene &scene, const std::vector<Ray> &rays);

enum class GpuRayKind : uint8_t {
    Primary,     // pinhole rays through the pixel grid of SceneView::camera (coherent)
    Incoherent,  // random origins in the scene bounds, uniform random directions
    Shadow       // Incoherent rays as any-hit queries with tMax = scene diagonal
};

struct GpuRayBenchmark {
    uint64_t rays = 0, hits = 0;
    double seconds = 0;          // kernel time only (CUDA events), ray generation included
    double raysPerSecond = 0;
};

// Generates and traces width x height rays per pass on the device, `passes` times after one
// warm-up pass. Primary rays need a perspective camera in the scene (cameraFromRaster).
GpuRayBenchmark BenchmarkRaysGpu(const DeviceScene &scene, GpuRayKind kind, int width, int height, int passes);

}  // namespace lu
