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

// ---- Orthographic and spherical cameras ----

TEST(OrthographicCamera, OriginsOnTheScreenWindowDirectionsAlongZ) {
    // 200x100: default screen window [-2, 2] x [-1, 1]; raster (0,0) is the top-left corner.
    CameraData c = MakeOrthographicCamera(Identity(), 200, 100, 0, 1e6f, nullptr);
    EXPECT_EQ(c.kind, CameraKind::Orthographic);
    struct P { float x, y, ox, oy; };
    for (P p : {P{0, 0, -2, 1}, P{200, 100, 2, -1}, P{100, 50, 0, 0}, P{50, 25, -1, 0.5f}}) {
        Ray r = Gen(c, p.x, p.y);
        EXPECT_NEAR(r.o.x, p.ox, 1e-5);
        EXPECT_NEAR(r.o.y, p.oy, 1e-5);
        EXPECT_NEAR(r.o.z, 0, 1e-6);
        EXPECT_NEAR(r.d.x, 0, 1e-7);
        EXPECT_NEAR(r.d.y, 0, 1e-7);
        EXPECT_NEAR(r.d.z, 1, 1e-7);
    }
    // An explicit screen window; a portrait image's default window [-1, 1] x [-2, 2].
    const Float sw[4] = {0, 10, -5, 5};
    CameraData w = MakeOrthographicCamera(Identity(), 100, 100, 0, 1e6f, sw);
    EXPECT_NEAR(Gen(w, 0, 0).o.x, 0, 1e-5);
    EXPECT_NEAR(Gen(w, 0, 0).o.y, 5, 1e-5);
    EXPECT_NEAR(Gen(w, 100, 100).o.x, 10, 1e-5);
    EXPECT_NEAR(Gen(w, 100, 100).o.y, -5, 1e-5);
    CameraData portrait = MakeOrthographicCamera(Identity(), 50, 100, 0, 1e6f, nullptr);
    EXPECT_NEAR(Gen(portrait, 0, 0).o.y, 2, 1e-5);
    EXPECT_NEAR(Gen(portrait, 50, 0).o.x, 1, 1e-5);
    // The camera transform moves origins and turns directions (camera +z -> render +x).
    CameraData rigid = MakeOrthographicCamera(Rigid(), 200, 100, 0, 1e6f, nullptr);
    Ray r = Gen(rigid, 0, 0);   // camera (-2, 1, 0)
    EXPECT_NEAR(r.o.x, 1, 1e-5);
    EXPECT_NEAR(r.o.y, 3, 1e-5);
    EXPECT_NEAR(r.o.z, 5, 1e-5);
    EXPECT_NEAR(r.d.x, 1, 1e-6);
}

TEST(OrthographicCamera, ThinLensFocusesAtTheFocalDistance) {
    // Rays of one raster point through any lens point meet at z = focaldistance, above the
    // pinhole origin; the lens points fill a disk of the lens radius around it.
    CameraData c = MakeOrthographicCamera(Identity(), 64, 64, 0.25f, 3, nullptr);
    RNG rng(5);
    double maxR = 0;
    for (int i = 0; i < 200; ++i) {
        Vec2f u(rng.Uniform<float>(), rng.Uniform<float>());
        Ray r = Gen(c, 16, 48, u);   // pinhole origin (-0.5, -0.5, 0)
        EXPECT_NEAR(r.o.z, 0, 1e-6);
        double rr = std::hypot(r.o.x + 0.5, r.o.y + 0.5);
        EXPECT_LE(rr, 0.25 + 1e-5);
        maxR = std::max(maxR, rr);
        Float t = 3 / r.d.z;
        EXPECT_NEAR(r.o.x + t * r.d.x, -0.5, 1e-4);
        EXPECT_NEAR(r.o.y + t * r.d.y, -0.5, 1e-4);
    }
    EXPECT_GT(maxR, 0.2);
}

TEST(SphericalCamera, MappingsRoundTrip) {
    for (CameraKind kind : {CameraKind::SphericalEqualArea, CameraKind::SphericalEquirect}) {
        CameraData c = MakeSphericalCamera(Identity(), 64, 64, kind);
        for (int y = 0; y < 64; y += 3)
            for (int x = 0; x < 64; x += 5) {
                Vec2f p(x + 0.37f, y + 0.61f);
                Ray r = Gen(c, p.x, p.y);
                EXPECT_EQ(r.o, Vec3f(0, 0, 0));
                EXPECT_NEAR(Length(r.d), 1, 1e-5);
                Vec2f uv = SphericalCameraImagePoint(kind, r.d);
                EXPECT_NEAR(uv.x * 64, p.x, 2e-3) << int(kind) << " " << x << "," << y;
                EXPECT_NEAR(uv.y * 64, p.y, 2e-3) << int(kind) << " " << x << "," << y;
            }
    }
    // Equirectangular conventions (pbrt-v4: theta = pi v from camera +y, phi = 2 pi u from +x
    // towards +z): the top row looks up (+y), the middle row at u = 0 along +x, u = 1/4 along +z.
    CameraData e = MakeSphericalCamera(Identity(), 200, 100, CameraKind::SphericalEquirect);
    EXPECT_NEAR(Gen(e, 100, 0).d.y, 1, 1e-5);
    EXPECT_NEAR(Gen(e, 0, 50).d.x, 1, 1e-5);
    EXPECT_NEAR(Gen(e, 50, 50).d.z, 1, 1e-5);
    EXPECT_NEAR(Gen(e, 100, 100).d.y, -1, 1e-5);
}

TEST(SphericalCamera, EqualAreaPixelsCoverEqualSolidAngles) {
    // Uniform directions land uniformly on the equal-area image (8x8 cells: chi-square-like bound),
    // and not on the equirectangular one (its polar cells are small).
    RNG rng(3);
    const int n = 64000, cells = 8;
    for (CameraKind kind : {CameraKind::SphericalEqualArea, CameraKind::SphericalEquirect}) {
        std::vector<int> cnt(cells * cells, 0);
        for (int i = 0; i < n; ++i) {
            Vec3f d = SampleUniformSphere(Vec2f(rng.Uniform<float>(), rng.Uniform<float>()));
            Vec2f uv = SphericalCameraImagePoint(kind, d);
            cnt[size_t(std::min(int(uv.y * cells), cells - 1) * cells + std::min(int(uv.x * cells), cells - 1))]++;
        }
        double chi2 = 0, e = double(n) / (cells * cells);
        for (int k : cnt) chi2 += (k - e) * (k - e) / e;
        if (kind == CameraKind::SphericalEqualArea) EXPECT_LT(chi2, 130) << "63 dof";
        else EXPECT_GT(chi2, 1000);
    }
    // The equal-area square's left edge is glued to itself mirrored ((0, v) ~ (0, 1 - v)), so the
    // wrap of a point just outside it continues the sphere smoothly.
    Vec3f a = SphericalCameraDirection(CameraKind::SphericalEqualArea, Vec2f(0, 0.3f));
    Vec3f b = SphericalCameraDirection(CameraKind::SphericalEqualArea, Vec2f(0, 0.7f));
    EXPECT_NEAR(Length(a - b), 0, 1e-5);
    Vec3f in = SphericalCameraDirection(CameraKind::SphericalEqualArea, Vec2f(0.001f, 0.3f));
    Vec3f out = SphericalCameraDirection(CameraKind::SphericalEqualArea, Vec2f(-0.001f, 0.3f));
    EXPECT_LT(Length(in - out), 0.01f);
    EXPECT_GT(Length(in - out), 1e-5f);
}
