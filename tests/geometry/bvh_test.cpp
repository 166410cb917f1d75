// Tests of the GPU BVH (geometry/bvh.h) and its shared traversal (bvh_traverse.h): structure,
// exact agreement with brute force over the same intersection routines, and agreement with Embree.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "geometry/bvh_test_util.h"

namespace lu {
namespace {

using test::OwnedScene;

// ---- Generated scenes ----

OwnedScene SoupScene() {
    OwnedScene s;
    test::AddTriangleSoup(s, 3000, 0.03f, 1);
    return s;
}
OwnedScene MixedScene() {
    OwnedScene s;
    test::AddSphereMesh(s, Vec3f(0.5f, 0.5f, 0.5f), 0.3f, 48, 24);
    test::AddGrid(s, 60, -0.2f, 1.2f, -0.2f, 1.2f, 0.0f, 0.02f, 2);
    test::AddTriangleSoup(s, 500, 0.05f, 3);
    test::AddAnalyticShapes(s);
    return s;
}
OwnedScene SliverScene() {
    OwnedScene s;
    test::AddSlivers(s, 1000, 4);
    return s;
}

struct NamedScene {
    const char *name;
    std::function<OwnedScene()> make;
};
const NamedScene kScenes[] = {{"soup", SoupScene}, {"mixed", MixedScene}, {"slivers", SliverScene}};

// ---- Structure checks ----

bool Contains(const Bounds3f &outer, const Bounds3f &inner) {
    return outer.pMin.x <= inner.pMin.x && outer.pMin.y <= inner.pMin.y && outer.pMin.z <= inner.pMin.z &&
           outer.pMax.x >= inner.pMax.x && outer.pMax.y >= inner.pMax.y && outer.pMax.z >= inner.pMax.z;
}
bool Overlaps(const Bounds3f &a, const Bounds3f &b) {
    return a.pMin.x <= b.pMax.x && a.pMin.y <= b.pMax.y && a.pMin.z <= b.pMax.z && b.pMin.x <= a.pMax.x &&
           b.pMin.y <= a.pMax.y && b.pMin.z <= a.pMax.z;
}

// Walks the tree checking nesting, leaf ranges and prim coverage. With exactBoxes (no spatial
// splits) each leaf box must contain its primitives' bounds; otherwise overlap them.
void CheckStructure(const GpuBVH &bvh, const SceneView &scene, bool exactBoxes, uint32_t maxLeaf) {
    ASSERT_FALSE(bvh.nodes.empty());
    std::vector<int> seen(bvh.nodes.size(), 0);
    std::vector<int> primUsed(bvh.prims.size(), 0);
    std::vector<std::pair<int32_t, Bounds3f>> todo;
    Bounds3f root = bvh.nodes[0].ChildBounds(0);
    root.Expand(bvh.nodes[0].ChildBounds(1));
    todo.push_back({0, root});
    while (!todo.empty()) {
        auto [idx, box] = todo.back();
        todo.pop_back();
        ASSERT_GE(idx, 0);
        ASSERT_LT(size_t(idx), bvh.nodes.size());
        ASSERT_EQ(seen[idx]++, 0) << "node reached twice";
        const BVHNode &n = bvh.nodes[idx];
        for (int i = 0; i < 2; ++i) {
            Bounds3f cb = n.ChildBounds(i);
            if (n.IsLeaf(i)) {
                if (n.count[i] == 0) continue;
                ASSERT_LE(n.count[i], maxLeaf);
                ASSERT_LE(size_t(n.FirstPrim(i)) + n.count[i], bvh.prims.size());
                EXPECT_TRUE(Contains(box, cb));
                for (uint32_t j = n.FirstPrim(i); j < n.FirstPrim(i) + n.count[i]; ++j) {
                    primUsed[j]++;
                    const PrimRef &p = bvh.prims[j];
                    Bounds3f pb = PrimitiveBounds(scene, p.shape, p.primitive);
                    if (exactBoxes) EXPECT_TRUE(Contains(cb, pb)) << "prim " << j;
                    else EXPECT_TRUE(Overlaps(cb, pb)) << "prim " << j;
                }
            } else {
                EXPECT_TRUE(Contains(box, cb)) << "child box outside its parent";
                todo.push_back({n.child[i], cb});
            }
        }
    }
    for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << "node " << i << " unreachable";
    for (size_t i = 0; i < primUsed.size(); ++i) EXPECT_EQ(primUsed[i], 1) << "prim ref " << i;
    // Every input primitive is referenced at least once.
    uint32_t total = 0;
    for (uint32_t s = 0; s < scene.shapes.size; ++s) total += scene.shapes[s].primitiveCount;
    std::vector<std::vector<int>> hitPrim(scene.shapes.size);
    for (uint32_t s = 0; s < scene.shapes.size; ++s) hitPrim[s].assign(scene.shapes[s].primitiveCount, 0);
    for (const PrimRef &p : bvh.prims) hitPrim[p.shape][p.primitive] = 1;
    uint32_t covered = 0;
    for (auto &v : hitPrim) for (int x : v) covered += x;
    EXPECT_EQ(covered, total);
    EXPECT_EQ(bvh.stats.primitives, total);
    EXPECT_EQ(bvh.stats.references, bvh.prims.size());
    EXPECT_LE(bvh.stats.maxDepth, uint32_t(BVHMaxDepth));
}

TEST(BVH, StructureWithAndWithoutSpatialSplits) {
    for (const NamedScene &ns : kScenes) {
        OwnedScene s = ns.make();
        SceneView v = s.View();
        for (bool splits : {false, true}) {
            BVHBuildOptions opt;
            opt.spatialSplits = splits;
            GpuBVH bvh = BuildBVH(v, opt);
            SCOPED_TRACE(std::string(ns.name) + (splits ? " sbvh" : " binned"));
            CheckStructure(bvh, v, !splits, opt.maxLeafSize);
            std::printf("[ stats    ] %-8s %-6s %s\n", ns.name, splits ? "sbvh" : "binned",
                        test::StatsSummary(bvh.stats).c_str());
            if (!splits) { EXPECT_EQ(bvh.stats.references, bvh.stats.primitives); }
        }
    }
}

TEST(BVH, SpatialSplitsLowerSahCostOnSlivers) {
    OwnedScene s = SliverScene();
    BVHBuildOptions binned;
    binned.spatialSplits = false;
    GpuBVH a = BuildBVH(s.View(), binned), b = BuildBVH(s.View());
    EXPECT_GT(b.stats.references, b.stats.primitives);
    EXPECT_LT(b.stats.sahCost, 0.8 * a.stats.sahCost) << a.stats.sahCost << " vs " << b.stats.sahCost;
}

TEST(BVH, EmptyAndTinyScenes) {
    OwnedScene empty;
    GpuBVH e = BuildBVH(empty.View());
    EXPECT_TRUE(e.nodes.empty());
    HitRecord h;
    Ray r;
    r.d = Vec3f(0, 0, 1);
    EXPECT_FALSE(IntersectClosest(e.View(), empty.View(), r, &h));
    EXPECT_FALSE(IntersectAny(e.View(), empty.View(), r));

    // One triangle: the root wraps a single leaf.
    OwnedScene one;
    one.AddMesh({Vec3f(-1, -1, 2), Vec3f(1, -1, 2), Vec3f(0, 1, 2)}, {0, 1, 2});
    GpuBVH b = BuildBVH(one.View());
    ASSERT_EQ(b.nodes.size(), 1u);
    ASSERT_TRUE(IntersectClosest(b.View(), one.View(), r, &h));
    EXPECT_FLOAT_EQ(h.t, 2.f);
    EXPECT_EQ(h.shape, 0u);
    EXPECT_EQ(h.primitive, 0u);
    Float t, b1, b2;
    ASSERT_TRUE(IntersectTriangle(one.positions[0], one.positions[1], one.positions[2], r, Infinity, &t, &b1, &b2));
    EXPECT_EQ(h.b1, b1);
    EXPECT_EQ(h.b2, b2);
    EXPECT_TRUE(IntersectAny(b.View(), one.View(), r));
    r.tMax = 2;   // open interval: a hit exactly at tMax does not count
    EXPECT_FALSE(IntersectAny(b.View(), one.View(), r));
    EXPECT_FALSE(IntersectClosest(b.View(), one.View(), r, &h));
    r.tMax = Infinity;
    r.d = Vec3f(0, 0, -1);
    EXPECT_FALSE(IntersectClosest(b.View(), one.View(), r, &h));

    // One sphere behind and in front of the origin.
    OwnedScene sph;
    sph.AddSphere(test::Translate(Vec3f(0, 0, 5)), 1);
    GpuBVH c = BuildBVH(sph.View());
    r.d = Vec3f(0, 0, 1);
    ASSERT_TRUE(IntersectClosest(c.View(), sph.View(), r, &h));
    EXPECT_NEAR(h.t, 4.f, 1e-5f);
    r.o = Vec3f(0, 0, 5);   // inside: exits at t = 1
    ASSERT_TRUE(IntersectClosest(c.View(), sph.View(), r, &h));
    EXPECT_NEAR(h.t, 1.f, 1e-5f);
}

// ---- Exact agreement with brute force (same intersection routines) ----

HitRecord BruteClosest(const GpuBVH &bvh, const SceneView &scene, const Ray &ray) {
    HitRecord best;
    Float tMax = ray.tMax;
    for (const PrimRef &p : bvh.prims) {
        Float t, b1, b2;
        if (IntersectPrimRef(p, scene, ray, tMax, &t, &b1, &b2)) {
            tMax = t;
            best.t = t; best.shape = p.shape; best.primitive = p.primitive; best.b1 = b1; best.b2 = b2;
        }
    }
    return best;
}

TEST(BVH, MatchesBruteForceExactly) {
    for (const NamedScene &ns : kScenes) {
        OwnedScene s = ns.make();
        SceneView v = s.View();
        for (bool splits : {false, true}) {
            BVHBuildOptions opt;
            opt.spatialSplits = splits;
            GpuBVH bvh = BuildBVH(v, opt);
            SCOPED_TRACE(std::string(ns.name) + (splits ? " sbvh" : " binned"));
            std::vector<Ray> rays = test::CoherentRays(v.bounds, 3, 12, 10);
            std::vector<Ray> inc = test::IncoherentRays(v.bounds, 500, 11);
            std::vector<Ray> seg = test::SegmentRays(v.bounds, 500, 12);
            rays.insert(rays.end(), inc.begin(), inc.end());
            rays.insert(rays.end(), seg.begin(), seg.end());
            size_t bad = 0, badAny = 0, hits = 0;
            for (const Ray &r : rays) {
                HitRecord a, b = BruteClosest(bvh, v, r);
                bool hit = IntersectClosest(bvh.View(), v, r, &a);
                hits += hit;
                // Identical routines: the closest t must be bit-identical (primitives may differ
                // only on an exact tie).
                if (hit != b.Hit() || (hit && a.t != b.t)) ++bad;
                if (IntersectAny(bvh.View(), v, r) != b.Hit()) ++badAny;
            }
            EXPECT_EQ(bad, 0u) << "of " << rays.size() << " rays";
            EXPECT_EQ(badAny, 0u);
            EXPECT_GT(hits, rays.size() / 10);
        }
    }
}

// ---- Agreement with Embree ----

// Embree's triangle test differs from the watertight one only at edges (a ray through a shared
// edge may report either triangle, or rarely slip through in one of them).
constexpr double kMaxDisagreement = 1e-3;
constexpr Float kRelTol = 1e-4f;      // distance, relative
constexpr Float kAbsTol = 1e-5f;      // distance, in units of the scene diagonal

TEST(BVH, MatchesEmbree) {
    for (const NamedScene &ns : kScenes) {
        OwnedScene s = ns.make();
        SceneView v = s.View();
        GpuBVH bvh = BuildBVH(v);
        test::EmbreeReference ref(v);
        struct Set {
            const char *name;
            std::vector<Ray> rays;
        } sets[] = {{"coherent", test::CoherentRays(v.bounds, 4, 50, 20)},
                    {"incoherent", test::IncoherentRays(v.bounds, 10000, 21)},
                    {"segments", test::SegmentRays(v.bounds, 10000, 22)}};
        for (const Set &set : sets) {
            std::vector<HitRecord> ours = test::TraceClosestCpu(bvh, v, set.rays), theirs(set.rays.size());
            size_t anyBad = 0;
            for (size_t i = 0; i < set.rays.size(); ++i) {
                theirs[i] = ref.Closest(set.rays[i]);
                anyBad += IntersectAny(bvh.View(), v, set.rays[i]) != ref.Occluded(set.rays[i]);
            }
            test::HitComparison c =
                test::CompareHits(ours, theirs, set.rays, v, kRelTol, kAbsTol * Length(v.bounds.Diagonal()));
            std::printf("[ embree   ] %-8s %-10s %s, %zu occlusion\n", ns.name, set.name, c.Summary().c_str(), anyBad);
            EXPECT_LE(c.Disagreements(), kMaxDisagreement * c.rays) << ns.name << " " << set.name << ": " << c.Summary();
            EXPECT_LE(anyBad, kMaxDisagreement * c.rays) << ns.name << " " << set.name;
            EXPECT_GT(c.hits, c.rays / 20) << "too few hits to mean anything";
        }
    }
}

}  // namespace
}  // namespace lu
