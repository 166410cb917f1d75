// Lucerna CUDA backend: the eye-light debug kernel (RenderGpu): one thread renders all samples of
// one pixel with |cos| shading over the shared BVH. The path integrator runs in cuda_render.cu.
#include <cuda_runtime.h>

#include <stdexcept>

#include "lucerna/backend/cuda/render_gpu.h"
#include "lucerna/geometry/bvh_traverse.h"
#include "lucerna/geometry/shapes.h"

namespace lu {

namespace {

void Check(cudaError_t err, const char *what) {
    if (err != cudaSuccess) throw CudaError(std::string(what) + ": " + cudaGetErrorString(err));
}

struct KernelParams {
    int width, height, spp;
    uint32_t seed;
    GpuRenderMode mode;
};

__device__ inline uint32_t Mix(uint32_t x) {   // lowbias32 (C. Wellons)
    x ^= x >> 16; x *= 0x7feb352du;
    x ^= x >> 15; x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// Pinhole camera ray through raster position (fx, fy) of the film (perspective cameras).
__device__ inline Ray CameraRay(const CameraData &cam, Float fx, Float fy) {
    Ray ray;
    Vec3f pCamera = cam.cameraFromRaster.ApplyPoint(Vec3f(fx, fy, 0));
    ray.o = cam.renderFromCamera.ApplyPoint(Vec3f(0, 0, 0));
    ray.d = Normalize(cam.renderFromCamera.ApplyVector(Normalize(pCamera)));
    return ray;
}

__global__ void RenderKernel(SceneView scene, BVHView bvh, KernelParams params, float *rgb) {
    int x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= params.width || y >= params.height) return;
    uint32_t state = Mix(uint32_t(y * params.width + x) ^ Mix(params.seed));
    auto uniform = [&state]() { state = Mix(state + 0x9e3779b9u); return (state >> 8) * 0x1p-24f; };
    Float sx = Float(scene.camera.width) / params.width, sy = Float(scene.camera.height) / params.height;
    float sum[3] = {0, 0, 0};
    for (int s = 0; s < params.spp; ++s) {
        Ray ray = CameraRay(scene.camera, (x + uniform()) * sx, (y + uniform()) * sy);
        // The path integrator itself runs in PathKernel (cuda_render.cu, RenderCUDA); this
        // kernel stays a debug view of the geometry.
        HitRecord hit;
        if (IntersectClosest(bvh, scene, ray, &hit)) {
            SurfaceInteraction si = ComputeInteraction(scene, hit, ray);
            Float v = AbsDot(si.n, si.wo);
            sum[0] += v; sum[1] += v; sum[2] += v;
        }
    }
    float inv = 1.0f / params.spp;
    float *out = rgb + 3 * (size_t(y) * params.width + x);
    out[0] = sum[0] * inv; out[1] = sum[1] * inv; out[2] = sum[2] * inv;
}

}  // namespace

std::vector<float> RenderGpu(const DeviceScene &scene, const GpuRenderSettings &settings) {
    if (settings.mode == GpuRenderMode::Path)
        throw std::runtime_error("RenderGpu: the path integrator runs in RenderCUDA (backend/cuda/cuda_render.h)");
    KernelParams p;
    p.width = settings.width > 0 ? settings.width : scene.View().film.width;
    p.height = settings.height > 0 ? settings.height : scene.View().film.height;
    p.spp = settings.spp > 0 ? settings.spp : 1;
    p.seed = settings.seed;
    p.mode = settings.mode;
    std::vector<float> rgb(size_t(p.width) * p.height * 3, 0.f);
    if (rgb.empty()) return rgb;
    DeviceBuffer<float> dRgb(rgb.size());
    dim3 block(16, 8), grid((p.width + 15) / 16, (p.height + 7) / 8);
    RenderKernel<<<grid, block>>>(scene.View(), scene.Bvh(), p, dRgb.Data());
    Check(cudaGetLastError(), "RenderKernel launch");
    Check(cudaDeviceSynchronize(), "RenderKernel");
    dRgb.Download(rgb.data(), rgb.size());
    return rgb;
}

}  // namespace lu
