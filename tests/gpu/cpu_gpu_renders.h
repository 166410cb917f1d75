// Lucerna tests: one scene rendered with `path` on the CPU and on the GPU over independent seeds
// (CPU 1.., GPU 101..), the input of a CompareBlockMeans CPU/GPU agreement test. CUDA builds only.
#pragma once

#if defined(LUCERNA_HAVE_CUDA)
#include <gtest/gtest.h>

#include <vector>

#include "gpu/render_compare.h"
#include "lucerna/backend/cpu/cpu_render.h"
#include "lucerna/backend/cuda/cuda_render.h"
#include "lucerna/backend/cuda/device_scene.h"

namespace lu::test {

struct CpuGpuRenders {
    std::vector<Image> cpu, gpu;
    uint64_t gpuRejected = 0;   // samples the GPU kept off the film, over all seeds
};

// `seeds` renders of `spp` each on both sides; every GPU image must be finite.
inline CpuGpuRenders RenderCpuAndGpu(const HostScene &host, int spp, int seeds) {
    GpuBVH bvh = BuildBVH(host.View());
    DeviceScene dev(host.View(), bvh);
    CpuGpuRenders r;
    for (int s = 0; s < seeds; ++s) {
        FilmAccumulator fc, fg;
        RenderCPU(host, SettingsFor(host, "path", spp, uint32_t(1 + s)), fc);
        RenderStats sg = RenderCUDA(dev, host.sampler, SettingsFor(host, "path", spp, uint32_t(101 + s)), fg);
        r.gpuRejected += sg.rejected;
        r.cpu.push_back(fc.Resolve(host.View().film));
        r.gpu.push_back(fg.Resolve(host.View().film));
        EXPECT_TRUE(AllFinite(r.gpu.back()));
    }
    return r;
}

}  // namespace lu::test
#endif
