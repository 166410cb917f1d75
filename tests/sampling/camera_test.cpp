// Tests of the perspective camera (film/camera.h): pbrt-v4's fov and screen-window conventions,
// left-handed camera space, thin lens focusing, and GetCameraSample.
#include <gtest/gtest.h>

#include <cmath>

#include "lucerna/scene/sampler_build.h"
#include "lucerna/scene/camera_build.h"
#include "lucerna/sampling/rng.h"

using namespace lu;

namespace {

Transform Identity() { return Transform(); }

// A rigid transform: rotation about y by 90 degrees (camera +z -> render +x), then translation.
Transform Rigid() {
    Matrix4 m;
    m.m[0][0] = 0; m.m[0][2] = 1; m.m[0][3] = 1;
    m.m[1][1] = 1; m.m[1][3] = 2;
    m.m[2][0] = -1; m.m[2][2] = 0; m.m[2][3] = 3;
    Matrix4 inv;
    Inverse(m, &inv);
    return Transform(m, inv);
}

double AngleDeg(Vec3f a, Vec3f b) { return Degrees(std::acos(Clamp(Dot(Normalize(a), Normalize(b)), -1.f, 1.f))); }

Ray Gen(const CameraData &c, float x, float y, Vec2f uLens = Vec2f(0.5f, 0.5f)) {
    Ray r;
    EXPECT_TRUE(GenerateRay(c, Vec2f(x, y), uLens, &r));
    return r;
}

}  // namespace

TEST(Camera, CenterRayLooksDownPlusZ) {
    CameraData c = MakePerspectiveCamera(Identity(), 100, 100, 60, 0, 1e6f, nullptr);
    Ray r = Gen(c, 50, 50);
    EXPECT_NEAR(r.d.x, 0, 1e-6);
    EXPECT_NEAR(r.d.y, 0, 1e-6);
    EXPECT_NEAR(r.d.z, 1, 1e-6);
    EXPECT_EQ(r.o, Vec3f(0, 0, 0));
    EXPECT_NEAR(Length(r.d), 1, 1e-6);
}

TEST(Camera, FovSpansTheShorterAxis) {
    // Landscape 200x100, fov 60: the vertical extent spans 60 degrees, the horizontal
    // atan(2 tan 30) on each side.
    CameraData c = MakePerspectiveCamera(Identity(), 200, 100, 60, 0, 1e6f, nullptr);
    Vec3f z(0, 0, 1);
    EXPECT_NEAR(AngleDeg(Gen(c, 100, 0).d, z), 30, 1e-3);
    EXPECT_NEAR(AngleDeg(Gen(c, 100, 100).d, z), 30, 1e-3);
    double half = Degrees(std::atan(2 * std::tan(Radians(30))));
    EXPECT_NEAR(AngleDeg(Gen(c, 0, 50).d, z), half, 1e-3);
    // Corner: direction proportional to (-2t, t, 1) with t = tan 30.
    Ray corner = Gen(c, 0, 0);
    double t = std::tan(Radians(30));
    EXPECT_NEAR(AngleDeg(corner.d, Vec3f(Float(-2 * t), Float(t), 1)), 0, 1e-2);
    // Portrait 100x200: the horizontal extent spans the fov.
    CameraData p = MakePerspectiveCamera(Identity(), 100, 200, 60, 0, 1e6f, nullptr);
    EXPECT_NEAR(AngleDeg(Gen(p, 0, 100).d, z), 30, 1e-3);
    EXPECT_NEAR(AngleDeg(Gen(p, 50, 0).d, z), half, 1e-3);
    // Square, fov 90: corner at acos(1/sqrt(3)).
    CameraData s = MakePerspectiveCamera(Identity(), 64, 64, 90, 0, 1e6f, nullptr);
    EXPECT_NEAR(AngleDeg(Gen(s, 64, 64).d, z), Degrees(std::acos(1 / std::sqrt(3.0))), 1e-3);
}

TEST(Camera, LeftHandedRasterAxes) {
    CameraData c = MakePerspectiveCamera(Identity(), 100, 80, 45, 0, 1e6f, nullptr);
    Ray center = Gen(c, 50, 40), right = Gen(c, 70, 40), down = Gen(c, 50, 60);
    EXPECT_GT(right.d.x, 0.1f);             // raster +x -> camera +x
    EXPECT_NEAR(right.d.y, 0, 1e-6);
    EXPECT_LT(down.d.y, -0.1f);             // raster +y -> camera -y
    EXPECT_NEAR(down.d.x, 0, 1e-6);
    EXPECT_GT(center.d.z, 0.99f);
    // pbrt-v4's left-handed camera frame: (image right, image up, forward) = (+x, +y, +z), so
    // the coordinate triple product of those directions is +1 (a mirrored image would give -1).
    Vec3f xr = Normalize(right.d - center.d * Dot(right.d, center.d));
    Vec3f yu = Normalize(center.d * Dot(down.d, center.d) - down.d);
    EXPECT_GT(Dot(Cross(xr, yu), center.d), 0.99f);
}

TEST(Camera, ScreenWindowOverride) {
    const Float sw[4] = {-1, 1, -1, 1};
    CameraData c = MakePerspectiveCamera(Identity(), 200, 100, 90, 0, 1e6f, sw);
    // Both axes now span tan(45) = 1 at the image edges: a non-uniform pixel aspect.
    Ray r = Gen(c, 200, 100);
    EXPECT_NEAR(r.d.x / r.d.z, 1, 1e-5);
    EXPECT_NEAR(r.d.y / r.d.z, -1, 1e-5);
}

TEST(Camera, RenderFromCameraIsApplied) {
    CameraData c = MakePerspectiveCamera(Rigid(), 100, 100, 60, 0, 1e6f, nullptr);
    Ray r = Gen(c, 50, 50);
    EXPECT_NEAR(r.o.x, 1, 1e-6);
    EXPECT_NEAR(r.o.y, 2, 1e-6);
    EXPECT_NEAR(r.o.z, 3, 1e-6);
    EXPECT_NEAR(r.d.x, 1, 1e-6);  // camera +z -> render +x
    Ray right = Gen(c, 100, 50);
    EXPECT_LT(right.d.z, -0.1f);  // camera +x -> render -z
}

TEST(Camera, ThinLensRaysMeetAtTheFocalPlane) {
    const Float focal = 5, lensRadius = 0.5f;
    for (bool rigid : {false, true}) {
        Transform xf = rigid ? Rigid() : Identity();
        CameraData pin = MakePerspectiveCamera(xf, 120, 90, 50, 0, 1e6f, nullptr);
        CameraData lens = MakePerspectiveCamera(xf, 120, 90, 50, lensRadius, focal, nullptr);
        Transform cameraFromRender = xf.Inverted();
        RNG rng(2);
        for (Vec2f pFilm : {Vec2f(60, 45), Vec2f(3.5f, 80.25f), Vec2f(119, 1)}) {
            Ray p = Gen(pin, pFilm.x, pFilm.y);
            Vec3f dc = cameraFromRender.ApplyVector(p.d);
            Vec3f focus = cameraFromRender.ApplyPoint(p.o) + dc * (focal / dc.z);
            for (int i = 0; i < 200; ++i) {
                Ray r = Gen(lens, pFilm.x, pFilm.y, Vec2f(rng.Uniform<float>(), rng.Uniform<float>()));
                Vec3f o = cameraFromRender.ApplyPoint(r.o), d = cameraFromRender.ApplyVector(r.d);
                EXPECT_NEAR(o.z, 0, 1e-5);
                EXPECT_LE(std::sqrt(o.x * o.x + o.y * o.y), lensRadius * 1.0001f);
                Vec3f hit = o + d * ((focal - o.z) / d.z);
                EXPECT_NEAR(hit.x, focus.x, 1e-4);
                EXPECT_NEAR(hit.y, focus.y, 1e-4);
                EXPECT_NEAR(Length(r.d), 1, 1e-5);
            }
        }
    }
}

TEST(Camera, GetCameraSampleUsesFiveDimensions) {
    FilterData f = MakeFilter("triangle", 1, 1);
    SceneView scene;
    std::string report;
    Sampler s = MakeSampler("zsobol", 16, 0, 32, 32, {}, &report);
    for (int i = 0; i < 16; ++i) {
        s.StartPixelSample(4, 7, i, 1);
        CameraSample cs = GetCameraSample(s, 4, 7, f, scene);
        EXPECT_EQ(s.dimension, 6);
        EXPECT_GE(cs.pFilm.x, 4 + 0.5f - 1);
        EXPECT_LE(cs.pFilm.x, 4 + 0.5f + 1);
        EXPECT_GE(cs.pFilm.y, 7 + 0.5f - 1);
        EXPECT_LE(cs.pFilm.y, 7 + 0.5f + 1);
        EXPECT_EQ(cs.filterWeight, 1.f);
        // Same dimensions drawn directly.
        s.StartPixelSample(4, 7, i, 1);
        Vec2f u = s.GetPixel2D();
        FilterSample fs = SampleFilter(f, scene, u);
        EXPECT_EQ(cs.pFilm.x, 4 + fs.p.x + 0.5f);
        s.StartPixelSample(4, 7, i, 4);
        Vec2f lensU = s.Get2D();
        EXPECT_EQ(cs.pLens.x, lensU.x);
        EXPECT_EQ(cs.pLens.y, lensU.y);
    }
}
