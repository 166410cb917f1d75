// Lucerna tests: the shared scenes and ray sets for the BVH/GPU tests in tests/gpu. Header-only.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geometry/bvh_test_util.h"
#include "lucerna/scene/builder.h"
#if defined(LUCERNA_HAVE_CUDA)
#include "lucerna/backend/cuda/cuda_api.h"
#endif
#include "support/shared_scenes.h"
#include "support/test_support.h"

// GPU tests skip, with the reason, where no CUDA device is usable (and only there).
#if defined(LUCERNA_HAVE_CUDA)
#define LU_REQUIRE_GPU()                                                                      \
    do {                                                                                      \
        std::string why;                                                                      \
        if (!::lu::CudaDeviceAvailable(&why)) GTEST_SKIP() << "no usable CUDA device: " << why; \
    } while (0)
#else
#define LU_REQUIRE_GPU() GTEST_SKIP() << "built without CUDA (LUCERNA_HAVE_CUDA unset)"
#endif

namespace lu::test {

// The scene files Lucerna renders, from the one list (support/shared_scenes.h), relative to data/scenes/.
inline const std::vector<std::string> &SharedSceneFiles() {
    static const std::vector<std::string> files = [] {
        std::vector<std::string> f;
        for (const SharedScene &s : RenderedSharedScenes()) f.push_back(s.scene.substr(std::string("scenes/").size()));
        return f;
    }();
    return files;
}

// A shared scene (relative to data/scenes/) at res x res pixels (res 0: its own resolution).
inline std::unique_ptr<HostScene> LoadSharedSceneAt(const std::string &rel, int res) {
    Diagnostics diag;
    diag.quiet = true;
    BuildOptions opts;
    opts.resX = opts.resY = res;
    return LoadScene(SharedPath("scenes/" + rel), diag, opts);
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
