// CPU/GPU agreement of the shared BVH traversal: the same rays through IntersectClosest /
// IntersectAny on the host and in the CUDA kernels (backend/cuda/trace.h). Skips without a GPU.
#include <gtest/gtest.h>

#include "gpu/gpu_test_util.h"

#if defined(LUCERNA_HAVE_CUDA)
#include "lucerna/backend/cuda/cuda_api.h"
#include "lucerna/backend/cuda/render_gpu.h"
#include "lucerna/backend/cuda/trace.h"
#endif

namespace lu {
namespace {

#if defined(LUCERNA_HAVE_CUDA)
// The device contracts a*b+c into FMAs, so distances may differ from the host in the last bits
// and a ray grazing an edge may rarely pick the neighbour.
constexpr double kMaxDisagreement = 2e-4;
constexpr Float kRelTol = 1e-5f;

void CompareCpuGpu(const SceneView &v, const std::vector<Ray> &rays, const char *what) {
    GpuBVH bvh = BuildBVH(v);
    DeviceScene dev(v, bvh);
    std::vector<HitRecord> cpu = test::TraceClosestCpu(bvh, v, rays);
    std::vector<HitRecord> gpu = TraceClosestGpu(dev, rays);
    ASSERT_EQ(gpu.size(), rays.size());
    test::HitComparison c = test::CompareHits(cpu, gpu, rays, v, kRelTol, 1e-6f * Length(bvh.bounds.Diagonal()));
    std::vector<uint8_t> occCpu = test::TraceAnyCpu(bvh, v, rays), occGpu = TraceAnyGpu(dev, rays);
    size_t occBad = 0;
    for (size_t i = 0; i < rays.size(); ++i) occBad += occCpu[i] != occGpu[i];
    std::printf("[ cpu/gpu  ] %-40s %s, %zu occlusion\n", what, c.Summary().c_str(), occBad);
    EXPECT_LE(c.Disagreements(), kMaxDisagreement * c.rays) << what << ": " << c.Summary();
    EXPECT_LE(occBad, kMaxDisagreement * c.rays) << what;
    EXPECT_GT(c.hits, 0u);
    // Exactly matching hits carry the same barycentrics up to rounding.
    size_t same = 0;
    for (size_t i = 0; i < rays.size(); ++i)
        if (cpu[i].Hit() && gpu[i].Hit() && cpu[i].shape == gpu[i].shape && cpu[i].primitive == gpu[i].primitive) {
            ++same;
            EXPECT_NEAR(cpu[i].b1, gpu[i].b1, 1e-4f);
            EXPECT_NEAR(cpu[i].b2, gpu[i].b2, 1e-4f);
        }
    EXPECT_GE(same + c.Disagreements(), c.hits);
}
#endif

TEST(GpuBVH, GeneratedScenesMatchCpu) {
    LU_REQUIRE_GPU();
#if defined(LUCERNA_HAVE_CUDA)
    test::OwnedScene s;
    test::AddSphereMesh(s, Vec3f(0.5f, 0.5f, 0.5f), 0.3f, 48, 24);
    test::AddGrid(s, 60, -0.2f, 1.2f, -0.2f, 1.2f, 0.0f, 0.02f, 2);
    test::AddTriangleSoup(s, 2000, 0.05f, 3);
    test::AddSlivers(s, 500, 4);
    test::AddAnalyticShapes(s);
    SceneView v = s.View();
    std::vector<Ray> rays = test::CoherentRays(v.bounds, 4, 128, 1);
    std::vector<Ray> inc = test::IncoherentRays(v.bounds, 50000, 2), seg = test::SegmentRays(v.bounds, 50000, 3);
    CompareCpuGpu(v, rays, "generated, coherent");
    CompareCpuGpu(v, inc, "generated, incoherent");
    CompareCpuGpu(v, seg, "generated, segments");
#endif
}

TEST(GpuBVH, SharedScenesMatchCpu) {
    LU_REQUIRE_GPU();
#if defined(LUCERNA_HAVE_CUDA)
    for (const std::string &file : test::SharedSceneFiles()) {
        SCOPED_TRACE(file);
        std::unique_ptr<HostScene> host = test::LoadSharedScene(file);
        SceneView v = host->View();
        std::vector<Ray> camera = test::CameraRays(v.camera, 256, 1);
        CompareCpuGpu(v, camera, (file + " camera").c_str());
        GpuBVH bvh = BuildBVH(v);
        std::vector<Ray> bounce = test::BounceRays(v, camera, test::TraceClosestCpu(bvh, v, camera), 2);
        CompareCpuGpu(v, bounce, (file + " bounce").c_str());
    }
#endif
}

// Reports rays/s (not a pass/fail threshold: the device varies); fails only on errors. Disabled
// in test runs: bench/gpu/rays_bench.sh runs it.
TEST(GpuBVH, DISABLED_RaysPerSecond) {
    LU_REQUIRE_GPU();
#if defined(LUCERNA_HAVE_CUDA)
    std::string name;
    CudaDeviceAvailable(&name);
    for (const std::string &file : test::SharedSceneFiles()) {
        std::unique_ptr<HostScene> host = test::LoadSharedScene(file);
        SceneView v = host->View();
        GpuBVH bvh = BuildBVH(v);
        DeviceScene dev(v, bvh);
        for (GpuRayKind kind : {GpuRayKind::Primary, GpuRayKind::Incoherent, GpuRayKind::Shadow}) {
            GpuRayBenchmark b = BenchmarkRaysGpu(dev, kind, 1024, 1024, 8);
            const char *k = kind == GpuRayKind::Primary ? "primary" : kind == GpuRayKind::Incoherent ? "incoherent" : "shadow";
            std::printf("[ rays/s   ] %-52s %-10s %8.1f Mrays/s (%.1f%% hit) on %s\n", file.c_str(), k,
                        b.raysPerSecond * 1e-6, 100.0 * b.hits / std::max<uint64_t>(1, b.rays), name.c_str());
            EXPECT_GT(b.raysPerSecond, 0);
        }
    }
#endif
}

// The megakernel scaffold runs and sees the scene (eye-light debug mode).
TEST(GpuRender, EyeLightSeesTheScene) {
    LU_REQUIRE_GPU();
#if defined(LUCERNA_HAVE_CUDA)
    std::unique_ptr<HostScene> host = test::LoadSharedScene("bitterli-cornell-box/scene-v4.pbrt");
    SceneView v = host->View();
    GpuBVH bvh = BuildBVH(v);
    DeviceScene dev(v, bvh);
    GpuRenderSettings rs;
    rs.width = 64;
    rs.height = 64;
    rs.spp = 4;
    std::vector<float> rgb = RenderGpu(dev, rs);
    ASSERT_EQ(rgb.size(), 64u * 64u * 3u);
    size_t lit = 0;
    for (float x : rgb) {
        ASSERT_TRUE(std::isfinite(x));
        ASSERT_GE(x, 0.f);
        ASSERT_LE(x, 1.0001f);
        lit += x > 0;
    }
    EXPECT_GT(lit, rgb.size() / 2) << "the box fills most of the image";
#endif
}

}  // namespace
}  // namespace lu
