// CPU/GPU agreement on the texture feature scenes (scenes/features/textures-*.pbrt): the device
// evaluates the same texture graph (child spans, every kind and mapping). Block means over
// independent seeds with Sidak-corrected z-tests, as render_gpu_test.cpp. Skips without a GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "gpu/cpu_gpu_renders.h"
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

TEST(GpuTextures, FeatureScenesMatchCpu) {
#if defined(LUCERNA_HAVE_CUDA)
    std::string why;
    if (!CudaDeviceAvailable(&why)) GTEST_SKIP() << "no usable CUDA device: " << why;
    std::vector<std::string> files;
    for (const auto &e : std::filesystem::directory_iterator(std::string(LUCERNA_SOURCE_DIR) + "/scenes/features")) {
        std::string name = e.path().filename().string();
        if (name.rfind("textures-", 0) == 0 && e.path().extension() == ".pbrt") files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    ASSERT_EQ(files.size(), 4u);
    const int res = 64, spp = 16, seeds = 4, block = 16;
    int tests = int(files.size()) * (res / block) * (res / block) * 3;
    double z = test::TwoSidedZ(test::SidakP(1e-3, tests));
    for (const std::string &file : files) {
        SCOPED_TRACE(file);
        Diagnostics diag;
        diag.quiet = true;
        BuildOptions opts;
        opts.resX = opts.resY = res;
        auto host = LoadScene(file, diag, opts);
        test::CpuGpuRenders rr = test::RenderCpuAndGpu(*host, spp, seeds);
        test::BlockComparison r = test::CompareBlockMeans(rr.cpu, rr.gpu, block, z);
        std::printf("[ cpu/gpu  ] %-40s %s\n", std::filesystem::path(file).filename().c_str(), r.Summary().c_str());
        EXPECT_EQ(r.failures, 0) << r.Summary() << " (threshold " << z << ")";
        EXPECT_EQ(rr.gpuRejected, 0u);
    }
#else
    GTEST_SKIP() << "built without CUDA (LUCERNA_HAVE_CUDA unset)";
#endif
}

}  // namespace
}  // namespace lu
