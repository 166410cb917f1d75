// Lucerna CPU backend: the scene's geometry in Embree 3 (triangles natively; spheres and disks as
// user geometry running the shared intersection routines), and the Tracer the integrator uses.
#pragma once

#include <embree3/rtcore.h>

#include <vector>

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"

namespace lu {

// Per-geometry payload of the analytic (user) geometries.
struct EmbreeUserData {
    const SceneView *view;
    uint32_t shape;
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
    const SceneView *view_ = nullptr;
    double buildSeconds_ = 0;
    std::vector<EmbreeUserData> userData_;  // stable: reserved before use
};

// The Tracer concept of integrators/path.h over an EmbreeScene.
struct EmbreeTracer {
    const EmbreeScene *scene;
    bool Intersect(const Ray &ray, HitRecord *hit) const { return scene->Intersect(ray, hit); }
    bool Occluded(const Ray &ray) const { return scene->Occluded(ray); }
};

}  // namespace lu
