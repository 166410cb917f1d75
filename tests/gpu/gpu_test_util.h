// Lucerna tests: the shared scenes and ray sets for the BVH/GPU tests in tests/gpu. Header-only.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geometry/bvh_test_util.h"
#include "lucerna/scene/builder.h"
#include "support/test_support.h"

namespace lu::test {

// The scene files Lucerna must render (shared/scenes/README.md).
inline const std::vector<std::string> &SharedSceneFiles() {
    static const std::vector<std::string> files = {
        "bitterli-cornell-box/scene-v4.pbrt",          "bitterli-veach-mis/scene-v4.pbrt",
        "bitterli-veach-bidir/scene-v4.pbrt",          "bitterli-volumetric-caustic/scene-v4-nomedium.pbrt",
        "bitterli-water-caustic/scene-v4.pbrt",        "pbrt-v3-caustic-glass/scene-v4.pbrt",
        "smallvcm-cornell/smallvcm-bs_c.pbrt",         "smallvcm-cornell/smallvcm-bs_p.pbrt"};
    return files;
}

inline std::unique_ptr<HostScene> LoadSharedScene(const std::string &rel) {
    Diagnostics diag;
    diag.quiet = true;
    BuildOptions opts;
    return LoadScene(SharedPath("scenes/" + rel), diag, opts);
}

// Pinhole rays through a res x res grid over the film (perspective cameras: cameraFromRaster
// maps raster points onto the z = 1 plane's direction), as the CUDA benchmark kernel does.
inline std::vector<Ray> CameraRays(const CameraData &cam, int res, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<Ray> rays;
    Vec3f o = cam.renderFromCamera.ApplyPoint(Vec3f(0, 0, 0));
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            Float fx = (x + rng.Uniform()) * cam.width / res, fy = (y + rng.Uniform()) * cam.height / res;
            Vec3f pCamera = cam.cameraFromRaster.ApplyPoint(Vec3f(fx, fy, 0));
            Ray r;
            r.o = o;
            r.d = Normalize(cam.renderFromCamera.ApplyVector(Normalize(pCamera)));
            rays.push_back(r);
        }
    return rays;
}

// Secondary rays leaving the hit points of `primary` in uniform random directions, origins offset
// off the surface as the integrator does (OffsetRayOrigin): the self-intersection-prone case.
inline std::vector<Ray> BounceRays(const SceneView &scene, const std::vector<Ray> &primary,
                                   const std::vector<HitRecord> &hits, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<Ray> rays;
    for (size_t i = 0; i < primary.size(); ++i) {
        if (!hits[i].Hit()) continue;
        SurfaceInteraction si = ComputeInteraction(scene, hits[i], primary[i]);
        Vec3f w = rng.Direction();
        if (Dot(w, si.n) * Dot(si.wo, si.n) < 0 && (i & 1)) w = -w;   // half reflected, half random
        Ray r;
        r.o = OffsetRayOrigin(si.p, si.n, w);
        r.d = w;
        rays.push_back(r);
    }
    return rays;
}

}  // namespace lu::test
