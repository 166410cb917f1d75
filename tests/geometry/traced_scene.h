// Lucerna geometry tests: a scene from pbrt-v4 text with both CPU tracers over it, Embree and
// Lucerna's BVH (what the CUDA backend traverses), so that a test asks each the same query.
#pragma once

#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "geometry/bvh_test_util.h"
#include "integrators/render_helpers.h"

namespace lu::test {

struct Traced {
    std::unique_ptr<HostScene> scene;
    SceneView view;
    GpuBVH bvh;
    std::unique_ptr<EmbreeScene> embree;
    bool Intersect(bool useBVH, const Ray &r, HitRecord *hit) const {
        return useBVH ? IntersectClosest(bvh.View(), view, r, hit) : embree->Intersect(r, hit);
    }
    bool Occluded(bool useBVH, const Ray &r) const {
        return useBVH ? IntersectAny(bvh.View(), view, r) : embree->Occluded(r);
    }
};

inline std::unique_ptr<Traced> TraceSceneText(const std::string &name, const std::string &text) {
    auto t = std::make_unique<Traced>();
    t->scene = LoadSceneText(name, text);
    EXPECT_TRUE(t->scene);
    t->view = t->scene->View();
    t->bvh = BuildBVH(t->view);
    t->embree = std::make_unique<EmbreeScene>(t->view);
    return t;
}

}  // namespace lu::test
