// CPU/GPU agreement on the alpha cut-out feature scene (scenes/features/alpha-cutouts.pbrt): the
// CUDA megakernel runs the shared alpha test in the shared BVH traversal. Block means over
// independent seeds with Sidak-corrected z-tests, as texture_gpu_test.cpp. Skips without a GPU.
#include <gtest/gtest.h>

#include "gpu/render_compare.h"
#include "integrators/render_helpers.h"
#include "lucerna/backend/cpu/cpu_render.h"

#if defined(LUCERNA_HAVE_CUDA)
#include "lucerna/backend/cuda/cuda_api.h"
#include "lucerna/backend/cuda/cuda_render.h"
#include "lucerna/backend/cuda/device_scene.h"
#endif

namespace lu {
namespace {

TEST(GpuAlpha, FeatureSceneMatchesCpu) {
#if defined(LUCERNA_HAVE_CUDA)
    std::string why;
    if (!CudaDeviceAvailable(&why)) GTEST_SKIP() << "no usable CUDA device: " << why;
    std::vector<std::string> files = test::FeatureSceneFiles({"alpha-"});
    ASSERT_EQ(files.size(), 1u);
    const int resX = 64, resY = 40, spp = 16, seeds = 4, block = 8;
    auto host = test::LoadCleanFeatureScene(files[0], resX, resY);
    GpuBVH bvh = BuildBVH(host->View());
    DeviceScene dev(host->View(), bvh);
    std::vector<Image> cpu, gpu;
    uint64_t rejected = 0;
    for (int s = 0; s < seeds; ++s) {
        FilmAccumulator fc, fg;
        RenderCPU(*host, test::SettingsFor(*host, "path", spp, 1 + s), fc);
        RenderStats sg = RenderCUDA(dev, host->sampler, test::SettingsFor(*host, "path", spp, 101 + s), fg);
        rejected += sg.rejected;
        cpu.push_back(fc.Resolve(host->View().film));
        gpu.push_back(fg.Resolve(host->View().film));
        EXPECT_TRUE(test::AllFinite(gpu.back()));
    }
    int tests = (resX / block) * (resY / block) * 3;
    test::BlockComparison r = test::CompareBlockMeans(cpu, gpu, block, test::TwoSidedZ(test::SidakP(1e-3, tests)));
    std::printf("[ cpu/gpu  ] alpha-cutouts %s\n", r.Summary().c_str());
    EXPECT_EQ(r.failures, 0) << r.Summary();
    EXPECT_EQ(rejected, 0u);
#else
    GTEST_SKIP() << "built without CUDA";
#endif
}

}  // namespace
}  // namespace lu
