// The GPU BVH (built on the host, traversed by the shared code on the CPU) against Embree on every
// shared scene: camera, bounce, incoherent and segment rays. Runs without a GPU.
#include <gtest/gtest.h>

#include <chrono>

#include "gpu/gpu_test_util.h"

namespace lu {
namespace {

constexpr double kMaxDisagreement = 1e-3;   // fraction of rays (edge cases of two triangle tests)
constexpr Float kRelTol = 1e-4f;
constexpr Float kAbsTol = 1e-5f;            // times the scene diagonal

TEST(BVHSharedScenes, MatchEmbree) {
    for (const std::string &file : test::SharedSceneFiles()) {
        SCOPED_TRACE(file);
        std::unique_ptr<HostScene> host;
        try {
            host = test::LoadSharedScene(file);
        } catch (const std::exception &e) {
            ADD_FAILURE() << "cannot load " << file << ": " << e.what();
            continue;
        }
        SceneView v = host->View();
        GpuBVH bvh = BuildBVH(v);
        std::printf("[ bvh      ] %-52s %s\n", file.c_str(), test::StatsSummary(bvh.stats).c_str());
        test::EmbreeReference ref(v);
        Float absTol = kAbsTol * Length(bvh.bounds.Diagonal());

        std::vector<Ray> camera = test::CameraRays(v.camera, 96, 1);
        std::vector<HitRecord> cameraHits = test::TraceClosestCpu(bvh, v, camera);
        struct Set {
            const char *name;
            std::vector<Ray> rays;
        } sets[] = {{"camera", camera},
                    {"bounce", test::BounceRays(v, camera, cameraHits, 2)},
                    {"incoherent", test::IncoherentRays(bvh.bounds, 8000, 3)},
                    {"segments", test::SegmentRays(bvh.bounds, 8000, 4)}};
        for (const Set &set : sets) {
            std::vector<HitRecord> ours = test::TraceClosestCpu(bvh, v, set.rays), theirs(set.rays.size());
            std::vector<uint8_t> occ = test::TraceAnyCpu(bvh, v, set.rays);
            size_t anyBad = 0;
            for (size_t i = 0; i < set.rays.size(); ++i) {
                theirs[i] = ref.Closest(set.rays[i]);
                anyBad += bool(occ[i]) != ref.Occluded(set.rays[i]);
            }
            test::HitComparison c = test::CompareHits(ours, theirs, set.rays, v, kRelTol, absTol);
            std::printf("[ embree   ]   %-10s %s, %zu occlusion\n", set.name, c.Summary().c_str(), anyBad);
            EXPECT_LE(c.Disagreements(), kMaxDisagreement * c.rays) << set.name << ": " << c.Summary();
            EXPECT_LE(anyBad, kMaxDisagreement * c.rays) << set.name;
            if (std::string(set.name) == "camera") {
                EXPECT_GT(c.hits, c.rays / 4) << "the camera should see the scene";
            }
        }
    }
}

// Single-thread CPU throughput of the shared traversal next to Embree's rtcIntersect1 on the same
// rays (context for the GPU numbers). Disabled in test runs: bench/gpu/rays_bench.sh runs it.
TEST(BVHSharedScenes, DISABLED_CpuThroughput) {
    using Clock = std::chrono::steady_clock;
    for (const std::string &file : test::SharedSceneFiles()) {
        std::unique_ptr<HostScene> host = test::LoadSharedScene(file);
        SceneView v = host->View();
        GpuBVH bvh = BuildBVH(v);
        BVHBuildOptions binnedOpt;
        binnedOpt.spatialSplits = false;
        GpuBVH binned = BuildBVH(v, binnedOpt);
        test::EmbreeReference ref(v);
        std::vector<Ray> camera = test::CameraRays(v.camera, 256, 1);
        std::vector<Ray> bounce = test::BounceRays(v, camera, test::TraceClosestCpu(bvh, v, camera), 2);
        for (const auto &[name, rays] : {std::pair<const char *, const std::vector<Ray> &>{"camera", camera},
                                         std::pair<const char *, const std::vector<Ray> &>{"bounce", bounce}}) {
            auto time = [&](auto &&fn) {
                auto t0 = Clock::now();
                size_t hits = 0;
                for (const Ray &r : rays) hits += fn(r);
                double s = std::chrono::duration<double>(Clock::now() - t0).count();
                EXPECT_GT(hits, 0u);
                return rays.size() / s * 1e-6;
            };
            double ours = time([&](const Ray &r) { HitRecord h; return IntersectClosest(bvh.View(), v, r, &h); });
            double bin = time([&](const Ray &r) { HitRecord h; return IntersectClosest(binned.View(), v, r, &h); });
            double emb = time([&](const Ray &r) { return ref.Closest(r).Hit(); });
            std::printf("[ cpu Mr/s ] %-52s %-7s sbvh %6.2f  binned %6.2f  embree %6.2f  (sbvh build %.0f ms, binned %.0f ms)\n",
                        file.c_str(), name, ours, bin, emb, bvh.stats.buildSeconds * 1e3, binned.stats.buildSeconds * 1e3);
        }
    }
}

}  // namespace
}  // namespace lu
