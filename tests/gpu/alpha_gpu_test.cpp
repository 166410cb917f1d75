// CPU/GPU agreement on the alpha cut-out feature scene (scenes/features/alpha-cutouts.pbrt): the
// CUDA megakernel runs the shared alpha test in the shared BVH traversal. Block means over
// independent seeds with Sidak-corrected z-tests, as texture_gpu_test.cpp. Skips without a GPU.
#include <gtest/gtest.h>

#include "gpu/cpu_gpu_renders.h"
#include "gpu/render_compare.h"
#include "integrators/render_helpers.h"

#if defined(LUCERNA_HAVE_CUDA)
#include "lucerna/backend/cuda/cuda_api.h"
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
    test::CpuGpuRenders rr = test::RenderCpuAndGpu(*host, spp, seeds);
    int tests = (resX / block) * (resY / block) * 3;
    test::BlockComparison r = test::CompareBlockMeans(rr.cpu, rr.gpu, block, test::TwoSidedZ(test::SidakP(1e-3, tests)));
    std::printf("[ cpu/gpu  ] alpha-cutouts %s\n", r.Summary().c_str());
    EXPECT_EQ(r.failures, 0) << r.Summary();
    EXPECT_EQ(rr.gpuRejected, 0u);
#else
    GTEST_SKIP() << "built without CUDA";
#endif
}

}  // namespace
}  // namespace lu
