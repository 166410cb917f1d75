// Lucerna CPU backend: the scene's geometry in Embree 3 (triangles natively; spheres, disks, cylinders, curved
// bilinear patches and curve pieces as
// user geometry running the shared intersection routines, so that they are hit as pbrt-v4 and the
// shared BVH hit them; Embree's own curves and grids differ), and the Tracer the integrator uses.
// Shape alpha cut-outs (geometry/alpha.h): a filter function on the triangle meshes that have
// one (no filter elsewhere), the user geometries' callbacks test it themselves.
// Object instances: one RTCScene per prototype, and one user geometry whose primitives are the
// instances (its callbacks map the ray to object space and query the prototype's scene): 68-105
// bytes per instance against 443 for Embree's native instance geometry (docs/benchmarks.md).
#pragma once

#include <embree3/rtcore.h>

#include <cassert>
#include <memory>
#include <vector>

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"

namespace lu {

// Per-geometry payload of the analytic (user) geometries.
struct EmbreeUserData {
    const SceneView *view;
    uint32_t shape;
};

// The intersect context of every query: Embree's, then what shape alpha tests need (the
// render-space ray, and the instance whose prototype is traversed, NoIndex at the top level).
// Filter and user-geometry callbacks cast their context back to it.
struct EmbreeAlphaContext {
    RTCIntersectContext ctx;
    const Ray *renderRay = nullptr;
    uint32_t instance = NoIndex;
};

// Payload of the instances' user geometry.
struct EmbreeInstanceData {
    const SceneView *view;
    const std::vector<RTCScene> *prototypes;
};

class EmbreeScene {
  public:
    explicit EmbreeScene(const SceneView &scene);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene &) = delete;
    EmbreeScene &operator=(const EmbreeScene &) = delete;

    bool Intersect(const Ray &ray, HitRecord *hit) const;
    bool Occluded(const Ray &ray) const;   // any hit in (0, ray.tMax)
    double BuildSeconds() const { return buildSeconds_; }

  private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<RTCScene> prototypeScenes_;   // per SceneView::prototypes entry
    const SceneView *view_ = nullptr;
    double buildSeconds_ = 0;
    std::vector<EmbreeUserData> userData_;  // stable: reserved before use
    std::unique_ptr<EmbreeInstanceData> instanceData_;
};

// What Embree may be given (checked by assert in debug builds; NDEBUG, as in Release, compiles
// the checks out): a finite origin, a finite nonzero direction, tMax >= 0 (infinity allowed).
// A NaN there aborts inside Embree ("Assertion 'ray.valid()' failed") or silently loses hits.
inline bool EmbreeValidRay(const Ray &r) {
    return std::isfinite(r.o.x) && std::isfinite(r.o.y) && std::isfinite(r.o.z) && std::isfinite(r.d.x) &&
           std::isfinite(r.d.y) && std::isfinite(r.d.z) && (r.d.x != 0 || r.d.y != 0 || r.d.z != 0) && r.tMax >= 0;
}

// The queries are inline: the integrator calls them several times per sample.
inline bool EmbreeScene::Intersect(const Ray &ray, HitRecord *hit) const {
    assert(EmbreeValidRay(ray) && "EmbreeScene::Intersect: NaN/infinite ray");
    EmbreeAlphaContext ctx;
    rtcInitIntersectContext(&ctx.ctx);
    ctx.renderRay = &ray;
    RTCRayHit rh;
    rh.ray.org_x = ray.o.x; rh.ray.org_y = ray.o.y; rh.ray.org_z = ray.o.z;
    rh.ray.dir_x = ray.d.x; rh.ray.dir_y = ray.d.y; rh.ray.dir_z = ray.d.z;
    rh.ray.tnear = 0;
    rh.ray.tfar = ray.tMax;
    rh.ray.time = 0;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx.ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit->t = rh.ray.tfar;
    hit->shape = rh.hit.geomID;
    hit->primitive = rh.hit.primID;
    hit->b1 = rh.hit.u;
    hit->b2 = rh.hit.v;
    hit->instance = rh.hit.instID[0];   // RTC_INVALID_GEOMETRY_ID == NoIndex: not an instance
    return true;
}

inline bool EmbreeScene::Occluded(const Ray &ray) const {
    assert(EmbreeValidRay(ray) && "EmbreeScene::Occluded: NaN/infinite ray");
    EmbreeAlphaContext ctx;
    rtcInitIntersectContext(&ctx.ctx);
    ctx.renderRay = &ray;
    RTCRay r;
    r.org_x = ray.o.x; r.org_y = ray.o.y; r.org_z = ray.o.z;
    r.dir_x = ray.d.x; r.dir_y = ray.d.y; r.dir_z = ray.d.z;
    r.tnear = 0;
    r.tfar = ray.tMax;
    r.time = 0;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    rtcOccluded1(scene_, &ctx.ctx, &r);
    return r.tfar < 0;
}

// The Tracer concept of integrators/path.h over an EmbreeScene.
struct EmbreeTracer {
    const EmbreeScene *scene;
    bool Intersect(const Ray &ray, HitRecord *hit) const { return scene->Intersect(ray, hit); }
    bool Occluded(const Ray &ray) const { return scene->Occluded(ray); }
};

}  // namespace lu
