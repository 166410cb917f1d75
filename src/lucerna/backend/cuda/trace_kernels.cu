// Lucerna CUDA backend: kernels running the shared BVH traversal (bvh_traverse.h), one thread per ray.
#include <cuda_runtime.h>

#include "lucerna/backend/cuda/trace.h"
#include "lucerna/geometry/bvh_traverse.h"

namespace lu {

namespace {

void Check(cudaError_t err, const char *what) {
    if (err != cudaSuccess) throw CudaError(std::string(what) + ": " + cudaGetErrorString(err));
}

constexpr int BlockSize = 128;

__global__ void ClosestKernel(SceneView scene, BVHView bvh, const Ray *rays, HitRecord *hits, uint32_t n) {
    uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    HitRecord h;
    IntersectClosest(bvh, scene, rays[i], &h);
    hits[i] = h;
}

__global__ void AnyKernel(SceneView scene, BVHView bvh, const Ray *rays, uint8_t *occluded, uint32_t n) {
    uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    occluded[i] = IntersectAny(bvh, scene, rays[i]) ? 1 : 0;
}

// ---- Benchmark ray generation ----

__device__ inline uint32_t Hash(uint32_t x) {   // lowbias32 (C. Wellons)
    x ^= x >> 16; x *= 0x7feb352du;
    x ^= x >> 15; x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
__device__ inline float Uniform(uint32_t &state) {
    state = Hash(state + 0x9e3779b9u);
    return (state >> 8) * 0x1p-24f;
}

__device__ inline Ray GenerateRay(const SceneView &scene, GpuRayKind kind, int x, int y, int width, int height,
                                  uint32_t pass) {
    Ray ray;
    uint32_t state = Hash(uint32_t(y * width + x) ^ Hash(pass));
    if (kind == GpuRayKind::Primary) {
        const CameraData &cam = scene.camera;
        // Map the benchmark grid onto the film raster.
        Float fx = (x + Uniform(state)) * Float(cam.width) / width;
        Float fy = (y + Uniform(state)) * Float(cam.height) / height;
        Vec3f pCamera = cam.cameraFromRaster.ApplyPoint(Vec3f(fx, fy, 0));
        ray.o = cam.renderFromCamera.ApplyPoint(Vec3f(0, 0, 0));
        ray.d = Normalize(cam.renderFromCamera.ApplyVector(Normalize(pCamera)));
        return ray;
    }
    Vec3f lo = scene.bounds.pMin, ext = scene.bounds.Diagonal();
    ray.o = lo + Vec3f(Uniform(state) * ext.x, Uniform(state) * ext.y, Uniform(state) * ext.z);
    Float z = 1 - 2 * Uniform(state), r = SafeSqrt(1 - z * z), phi = 2 * Pi * Uniform(state);
    ray.d = Vec3f(r * cosf(phi), r * sinf(phi), z);
    if (kind == GpuRayKind::Shadow) ray.tMax = Length(ext);
    return ray;
}

__global__ void BenchKernel(SceneView scene, BVHView bvh, GpuRayKind kind, int width, int height, uint32_t pass,
                            unsigned long long *hitCount) {
    int x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
    bool hit = false;
    if (x < width && y < height) {
        Ray ray = GenerateRay(scene, kind, x, y, width, height, pass);
        if (kind == GpuRayKind::Shadow) {
            hit = IntersectAny(bvh, scene, ray);
        } else {
            HitRecord h;
            hit = IntersectClosest(bvh, scene, ray, &h);
        }
    }
    // One atomic per warp.
    unsigned mask = __ballot_sync(0xffffffffu, hit);
    if ((threadIdx.x + threadIdx.y * blockDim.x) % 32 == 0 && mask) atomicAdd(hitCount, (unsigned long long)__popc(mask));
}

}  // namespace

std::vector<HitRecord> TraceClosestGpu(const DeviceScene &scene, const std::vector<Ray> &rays) {
    std::vector<HitRecord> hits(rays.size());
    if (rays.empty()) return hits;
    DeviceBuffer<Ray> dRays(rays);
    DeviceBuffer<HitRecord> dHits(rays.size());
    uint32_t n = uint32_t(rays.size());
    ClosestKernel<<<(n + BlockSize - 1) / BlockSize, BlockSize>>>(scene.View(), scene.Bvh(), dRays.Data(),
                                                                 dHits.Data(), n);
    Check(cudaGetLastError(), "ClosestKernel launch");
    Check(cudaDeviceSynchronize(), "ClosestKernel");
    dHits.Download(hits.data(), hits.size());
    return hits;
}

std::vector<uint8_t> TraceAnyGpu(const DeviceScene &scene, const std::vector<Ray> &rays) {
    std::vector<uint8_t> occluded(rays.size());
    if (rays.empty()) return occluded;
    DeviceBuffer<Ray> dRays(rays);
    DeviceBuffer<uint8_t> dOcc(rays.size());
    uint32_t n = uint32_t(rays.size());
    AnyKernel<<<(n + BlockSize - 1) / BlockSize, BlockSize>>>(scene.View(), scene.Bvh(), dRays.Data(), dOcc.Data(), n);
    Check(cudaGetLastError(), "AnyKernel launch");
    Check(cudaDeviceSynchronize(), "AnyKernel");
    dOcc.Download(occluded.data(), occluded.size());
    return occluded;
}

GpuRayBenchmark BenchmarkRaysGpu(const DeviceScene &scene, GpuRayKind kind, int width, int height, int passes) {
    GpuRayBenchmark result;
    DeviceBuffer<unsigned long long> dCount(1);
    unsigned long long zero = 0;
    CudaCopyToDevice(dCount.Data(), &zero, sizeof(zero));
    dim3 block(32, 4), grid((width + 31) / 32, (height + 3) / 4);
    BenchKernel<<<grid, block>>>(scene.View(), scene.Bvh(), kind, width, height, 0u, dCount.Data());   // warm-up
    Check(cudaGetLastError(), "BenchKernel launch");
    Check(cudaDeviceSynchronize(), "BenchKernel warm-up");
    CudaCopyToDevice(dCount.Data(), &zero, sizeof(zero));
    cudaEvent_t start, stop;
    Check(cudaEventCreate(&start), "cudaEventCreate");
    Check(cudaEventCreate(&stop), "cudaEventCreate");
    Check(cudaEventRecord(start), "cudaEventRecord");
    for (int p = 0; p < passes; ++p)
        BenchKernel<<<grid, block>>>(scene.View(), scene.Bvh(), kind, width, height, uint32_t(p + 1), dCount.Data());
    Check(cudaEventRecord(stop), "cudaEventRecord");
    Check(cudaEventSynchronize(stop), "BenchKernel");
    float ms = 0;
    Check(cudaEventElapsedTime(&ms, start, stop), "cudaEventElapsedTime");
    cudaEventDestroy(start);
    cudaEventDestroy(stop);
    unsigned long long hits = 0;
    CudaCopyToHost(&hits, dCount.Data(), sizeof(hits));
    result.rays = uint64_t(width) * height * passes;
    result.hits = hits;
    result.seconds = ms * 1e-3;
    result.raysPerSecond = result.seconds > 0 ? result.rays / result.seconds : 0;
    return result;
}

}  // namespace lu
