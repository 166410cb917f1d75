// Lucerna CUDA backend: the path-tracing megakernel. One thread renders one sample of one pixel
// per pass through the shared integrator (integrators/path.h) over the shared BVH traversal
// (geometry/bvh_traverse.h); the film write and NaN guard are those of backend/cpu/cpu_render.cpp.
#include <cuda_runtime.h>

#include <string>

#include "lucerna/backend/cuda/device_buffer.h"
#include "lucerna/backend/cuda/path_kernel.h"
#include "lucerna/geometry/bvh_traverse.h"
#include "lucerna/spectrum/color.h"

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
    PathStats st;
    unsigned long long rejected = 0, firstKey = ~0ull;
    if (x < args.width && y < args.height) {
        Sampler sampler = args.sampler;
        BVHTracer tracer{args.bvh, &scene};
        CameraSampleResult cs = RenderSample(x, y, args.passIndex, sampler, scene, tracer, args.ps, st);
        Float xyz[3];
        SensorXYZ(cs.L, cs.lambda, scene.spectra, scene.film.imagingRatio, xyz);
        float4 out = make_float4(0, 0, 0, 0);
        // The CPU backend's NaN guard: the sample is kept off the film and counted.
        bool ok = IsFinite(xyz[0]) && IsFinite(xyz[1]) && IsFinite(xyz[2]) && IsFinite(cs.filterWeight) &&
                  cs.L.MinValue() >= 0;
        if (!ok) {
            rejected = 1;
            unsigned long long depth = (unsigned long long)Min(Max(cs.depth, 0), (1 << PathDepthBits) - 1);
            firstKey = ((unsigned long long)y * args.width + x) << PathDepthBits | depth;
        } else {
            // pbrt-v4 RGBFilm: clamp the sample's largest component to maxComponentValue.
            Float m = Max(xyz[0], Max(xyz[1], xyz[2]));
            if (m > scene.film.maxComponentValue)
                for (Float &c : xyz) c *= scene.film.maxComponentValue / m;
            out = make_float4(cs.filterWeight * xyz[0], cs.filterWeight * xyz[1], cs.filterWeight * xyz[2], cs.filterWeight);
        }
        reinterpret_cast<float4 *>(args.xyzw)[size_t(y) * args.width + x] = out;
    }
    // ---- Statistics: warp reductions, one atomic per warp and counter ----
    unsigned long long rays = WarpSum((unsigned long long)st.rays);
    unsigned long long shadow = WarpSum((unsigned long long)st.shadowRays);
    unsigned long long reg = WarpSum((unsigned long long)st.regConnections);
    unsigned long long rej = WarpSum(rejected);
    unsigned long long first = WarpMin(firstKey);
    double regE = WarpSum(double(st.regEnergy)), totalE = WarpSum(double(st.totalEnergy));
    if (((threadIdx.y * kBlockX + threadIdx.x) & 31) == 0) {
        PathPassCounters *c = args.counters;
        if (rays) atomicAdd(&c->rays, rays);
        if (shadow) atomicAdd(&c->shadowRays, shadow);
        if (reg) atomicAdd(&c->regConnections, reg);
        if (regE != 0) atomicAdd(&c->regEnergy, regE);
        if (totalE != 0) atomicAdd(&c->totalEnergy, totalE);
        if (rej) {
            atomicAdd(&c->rejected, rej);
            atomicMin(&c->firstRejected, first);
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
