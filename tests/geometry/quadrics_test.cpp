// Tests of the quadrics of geometry/shapes.h against analytic answers: pbrt-v4's cylinder
// (open tube, uv, orientation), partial spheres (zmin, zmax, phimax: a ray whose near hit is cut
// away meets the far side), disk sectors (phimax), and their areas; transformed and reversed
// copies. The BVH and Embree agreement on such shapes is in bvh_test.cpp (AddAnalyticShapes).
#include <gtest/gtest.h>

#include "geometry/bvh_test_util.h"

namespace lu {
namespace {

using test::OwnedScene;
using test::Rotate;
using test::Translate;

struct Expected {
    Float t;
    Vec3f p, n;
    Vec2f uv;
};

// Intersects shape 0 of s with the ray and checks the hit against e (n: the oriented geometric
// normal, as pbrt-v4's Normalize(Cross(dpdu, dpdv)) flipped by the orientation).
void ExpectHit(const SceneView &s, const Ray &ray, const Expected &e, const char *what) {
    SCOPED_TRACE(what);
    HitRecord hit;
    hit.shape = 0;
    ASSERT_TRUE(IntersectQuadric(s, s.shapes[0], ray, Infinity, &hit.t));
    EXPECT_NEAR(hit.t, e.t, 1e-5f * (1 + e.t));
    SurfaceInteraction si = ComputeInteraction(s, hit, ray);
    EXPECT_LT(Distance(si.p, e.p), 1e-5f) << si.p.x << " " << si.p.y << " " << si.p.z;
    EXPECT_LT(Distance(si.n, e.n), 1e-5f) << si.n.x << " " << si.n.y << " " << si.n.z;
    EXPECT_NEAR(si.uv.x, e.uv.x, 1e-5f);
    EXPECT_NEAR(si.uv.y, e.uv.y, 1e-5f);
    // Just short of the hit: none.
    Float t;
    EXPECT_FALSE(IntersectQuadric(s, s.shapes[0], ray, e.t * (1 - 1e-4f), &t));
}

void ExpectMiss(const SceneView &s, const Ray &ray, const char *what) {
    Float t;
    EXPECT_FALSE(IntersectQuadric(s, s.shapes[0], ray, Infinity, &t)) << what << ": t " << t;
}

Ray MakeRay(Vec3f o, Vec3f d) {
    Ray r;
    r.o = o;
    r.d = d;
    return r;
}

TEST(Cylinder, HitsMatchAnalyticAnswers) {
    OwnedScene sc;
    sc.AddCylinder(Transform(), 1, -1, 1);
    SceneView s = sc.View();
    ExpectHit(s, MakeRay({3, 0, 0.5f}, {-1, 0, 0}), {2, {1, 0, 0.5f}, {1, 0, 0}, {0, 0.75f}}, "from outside");
    ExpectHit(s, MakeRay({0, 0, 0.3f}, {0, 1, 0}), {1, {0, 1, 0.3f}, {0, 1, 0}, {0.25f, 0.65f}}, "from inside");
    // In through the open top, onto the inside of the wall (unnormalized direction: t in its units).
    ExpectHit(s, MakeRay({0, 0, 2}, {0.5f, 0, -1}), {2, {1, 0, 0}, {1, 0, 0}, {0, 0.5f}}, "through the open end");
    ExpectMiss(s, MakeRay({3, 0, 1.5f}, {-1, 0, 0}), "above zmax");
    ExpectMiss(s, MakeRay({0.5f, 0, 3}, {0, 0, -1}), "parallel to the axis, inside");
    ExpectMiss(s, MakeRay({3, 1.01f, 0}, {-1, 0, 0}), "passing by");
    EXPECT_NEAR(PrimitiveArea(s, s.shapes[0], 0), 2 * 2 * Pi, 1e-5f);
}

TEST(Cylinder, PartialInPhiHitsTheFarSide) {
    OwnedScene sc;
    sc.AddCylinder(Transform(), 1, -1, 1, 180);
    SceneView s = sc.View();
    // Near hit (0, -1, 0) at phi = 270 degrees is cut away: the far side at phi = 90.
    ExpectHit(s, MakeRay({0, -3, 0}, {0, 1, 0}), {4, {0, 1, 0}, {0, 1, 0}, {0.5f, 0.5f}}, "far side");
    ExpectHit(s, MakeRay({0, 3, -0.5f}, {0, -1, 0}), {2, {0, 1, -0.5f}, {0, 1, 0}, {0.5f, 0.25f}}, "near side kept");
    ExpectMiss(s, MakeRay({3, -0.5f, 0}, {-1, 0, 0}), "through the cut half only, from +x");
    ExpectMiss(s, MakeRay({-3, -0.5f, 0}, {1, 0, 0}), "through the cut half only");
    EXPECT_NEAR(PrimitiveArea(s, s.shapes[0], 0), 2 * Pi, 1e-5f);
}

TEST(Cylinder, TransformedAndReversed) {
    Transform T = Translate({1, 2, 3}) * Rotate(90, Vec3f(1, 0, 0));
    for (bool flip : {false, true}) {
        SCOPED_TRACE(flip);
        OwnedScene sc;
        sc.AddCylinder(T, 0.5f, 0, 2);
        sc.cylinders[0].flipNormals = flip;
        SceneView s = sc.View();
        Vec3f n = Normalize(T.ApplyNormal(Vec3f(1, 0, 0)));
        ExpectHit(s, MakeRay(T.ApplyPoint({2, 0, 1.5f}), T.ApplyVector({-1, 0, 0})),
                  {1.5f, T.ApplyPoint({0.5f, 0, 1.5f}), flip ? -n : n, {0, 0.75f}}, "transformed");
    }
}

TEST(PartialSphere, CutAwayNearHitGivesWayToTheFarOne) {
    // A band zmin = -0.5, zmax = 0.5: thetaZMin = 2 pi / 3, thetaZMax = pi / 3.
    OwnedScene band;
    band.AddSphere(Transform(), 1, -0.5f, 0.5f);
    SceneView s = band.View();
    ExpectHit(s, MakeRay({3, 0, 0}, {-1, 0, 0}), {2, {1, 0, 0}, {1, 0, 0}, {0, 0.5f}}, "band equator");
    ExpectMiss(s, MakeRay({0, 0, 3}, {0, 0, -1}), "through both cut caps");
    EXPECT_NEAR(PrimitiveArea(s, s.shapes[0], 0), 2 * Pi * 1 * 1, 1e-5f);
    // zmax = 0.5 only: in through the cut cap, onto the inside of the far side at z = -0.707.
    OwnedScene cap;
    cap.AddSphere(Transform(), 1, -1, 0.5f);
    s = cap.View();
    Float h = std::sqrt(0.5f);
    // theta = 3 pi / 4, thetaZMin = pi, thetaZMax = pi / 3: v = 3 / 8.
    ExpectHit(s, MakeRay({-2, 0, 2}, {1, 0, -1}), {2 + h, {h, 0, -h}, {h, 0, -h}, {0, 3.f / 8}}, "far side through the cap");
    EXPECT_NEAR(PrimitiveArea(s, s.shapes[0], 0), 2 * Pi * 1.5f, 1e-5f);
    // phimax = 90: the near hit at phi = 150 degrees is cut away, the far one at phi = 30 kept.
    OwnedScene wedge;
    wedge.AddSphere(Transform(), 1, -1, 1, 90);
    s = wedge.View();
    Float c = std::sqrt(0.75f);
    ExpectHit(s, MakeRay({-3, 0.5f, 0}, {1, 0, 0}), {3 + c, {c, 0.5f, 0}, {c, 0.5f, 0}, {1.f / 3, 0.5f}}, "phi wedge");
    ExpectMiss(s, MakeRay({-3, -0.5f, 0}, {1, 0, 0}), "below the wedge");
    EXPECT_NEAR(PrimitiveArea(s, s.shapes[0], 0), Pi, 1e-5f);
    // zmin/zmax beyond the radius clamp: the full sphere, uv as pbrt-v4's full sphere.
    OwnedScene full;
    full.AddSphere(Translate({0, 0, 1}), 1, -5, 5, 400);
    s = full.View();
    EXPECT_FALSE(IsPartial(full.spheres[0]));
    ExpectHit(s, MakeRay({0, 0, 5}, {0, 0, -1}), {3, {0, 0, 2}, {0, 0, 1}, {0, 1}}, "full sphere pole");
}

TEST(PartialDisk, SectorAndAnnulus) {
    OwnedScene sc;
    sc.AddDisk(Transform(), 0.5f, 1, 0.2f, 90);
    SceneView s = sc.View();
    Float q = std::sqrt(0.125f);   // (q, q) at radius 0.5, phi = 45 degrees
    ExpectHit(s, MakeRay({q, q, 1.5f}, {0, 0, -1}), {1, {q, q, 0.5f}, {0, 0, 1}, {0.5f, (1 - 0.5f) / 0.8f}}, "in the sector");
    ExpectMiss(s, MakeRay({-q, q, 1.5f}, {0, 0, -1}), "outside the sector");
    ExpectMiss(s, MakeRay({0.1f, 0.05f, 1.5f}, {0, 0, -1}), "in the hole");
    EXPECT_NEAR(PrimitiveArea(s, s.shapes[0], 0), Pi / 4 * (1 - 0.04f), 1e-5f);
}

}  // namespace
}  // namespace lu
