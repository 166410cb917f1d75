// Lucerna CUDA backend: the path-tracing megakernel. One thread renders one sample of one pixel
// per pass through the shared per-pixel body (RenderPixelSample, integrators/path.h) over the
// shared BVH traversal (geometry/bvh_traverse.h), exactly what the CPU backend runs per pixel.
#include <cuda_runtime.h>

#include <string>

#include "lucerna/backend/cuda/device_buffer.h"
#include "lucerna/backend/cuda/path_kernel.h"
#include "lucerna/geometry/bvh_traverse.h"

namespace lu {

namespace {

// A warp covers 8 x 4 pixels (coherent camera rays); 128 threads per block.
constexpr int kBlockX = 8, kBlockY = 16;

template <typename T>
__device__ inline T WarpSum(T v) {
    for (int o = 16; o > 0; o >>= 1) v += __shfl_down_sync(0xffffffffu, v, o);
    return v;
}
__device__ inline unsigned long long WarpMin(unsigned long long v) {
    for (int o = 16; o > 0; o >>= 1) v = min(v, __shfl_down_sync(0xffffffffu, v, o));
    return v;
}

__global__ void __launch_bounds__(kBlockX * kBlockY)
PathKernel(const __grid_constant__ SceneView scene, const __grid_constant__ PathKernelArgs args) {
    int x = blockIdx.x * kBlockX + threadIdx.x, y = blockIdx.y * kBlockY + threadIdx.y;
    PassCounters c;
    if (x < args.width && y < args.height) {
        BVHTracer tracer{args.bvh, &scene};
        float xyzw[4];
        RenderPixelSample(x, y, args.passIndex, args.sampler, scene, tracer, args.ps, xyzw, c);
        reinterpret_cast<float4 *>(args.xyzw)[size_t(y) * args.width + x] = make_float4(xyzw[0], xyzw[1], xyzw[2], xyzw[3]);
    }
    // ---- Counters: warp reductions, one atomic per warp and counter ----
    unsigned long long rays = WarpSum(c.rays), shadow = WarpSum(c.shadowRays), reg = WarpSum(c.regConnections);
    unsigned long long mnee = WarpSum(c.mneeConnections);
    unsigned long long rej = WarpSum(c.rejected), first = WarpMin(c.firstRejected);
    double regE = WarpSum(c.regEnergy), totalE = WarpSum(c.totalEnergy);
    if (((threadIdx.y * kBlockX + threadIdx.x) & 31) == 0) {
        PassCounters *out = args.counters;
        if (rays) atomicAdd(&out->rays, rays);
        if (shadow) atomicAdd(&out->shadowRays, shadow);
        if (reg) atomicAdd(&out->regConnections, reg);
        if (mnee) atomicAdd(&out->mneeConnections, mnee);
        if (regE != 0) atomicAdd(&out->regEnergy, regE);
        if (totalE != 0) atomicAdd(&out->totalEnergy, totalE);
        if (rej) {
            atomicAdd(&out->rejected, rej);
            atomicMin(&out->firstRejected, first);
        }
    }
}

}  // namespace

void LaunchPathKernel(const SceneView &scene, const PathKernelArgs &args, void *stream) {
    dim3 block(kBlockX, kBlockY), grid((args.width + kBlockX - 1) / kBlockX, (args.height + kBlockY - 1) / kBlockY);
    PathKernel<<<grid, block, 0, static_cast<cudaStream_t>(stream)>>>(scene, args);
    cudaError_t err = cudaGetLastError();
    if (err != cudaSuccess) throw CudaError(std::string("PathKernel launch: ") + cudaGetErrorString(err));
}

}  // namespace lu
