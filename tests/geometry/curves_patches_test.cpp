// pbrt-v4's "curve" shape (geometry/curve.h) and native bilinear patches (geometry/bilinear_patch.h)
// against analytic answers: hits on a saddle patch lie on p(u, v) with its normal, the nearer of
// two hits, the patch area and its light sampling (chi-square of (u, v), pdfs, solid angle);
// curves hit within half their (interpolated) width with pbrt-v4's (u, v), cylinder normals that
// turn across the width, ribbons narrowed by their normals, bent curves hit where the true curve
// passes, the b-spline and quadratic conversions, instancing, located errors; Embree and the
// shared BVH (the CUDA backend's traversal) agree ray by ray.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "geometry/traced_scene.h"
#include "lucerna/lights/shape_sampling.h"
#include "lucerna/scene/error.h"
#include "support/chi2.h"

namespace lu::test {
namespace {

std::unique_ptr<Traced> Trace(const std::string &name, const std::string &world) {
    return TraceSceneText(name, "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                                "LightSource \"point\" \"point3 from\" [ 0 0 -4 ]\n" + world);
}

Ray MakeRay(Vec3f o, Vec3f d) {
    Ray r;
    r.o = o;
    r.d = d;
    return r;
}

// ---- Bilinear patches ----

// The saddle p(u, v) = (u, v, u v): p00 = 0, p10 = x, p01 = y, p11 = (1, 1, 1).
const char *kSaddle = "Shape \"bilinearmesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0  1 1 1 ]\n";

TEST(BilinearPatch, HitsLieOnTheSurfaceWithItsNormal) {
    auto t = Trace("bilinear_saddle", kSaddle);
    ASSERT_EQ(t->view.bilinearMeshes.size, 1u);   // not a parallelogram: kept as a patch
    ASSERT_EQ(t->view.triangleMeshes.size, 0u);
    Pcg32 rng(3);
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
        Float u = rng.Uniform(), v = rng.Uniform();
        Vec3f target(u, v, u * v);
        Vec3f o(rng.Uniform() * 2 - 0.5f, rng.Uniform() * 2 - 0.5f, i % 2 ? 3.f : -3.f);   // from both sides
        Ray r = MakeRay(o, (target - o) * (0.5f + rng.Uniform()));   // unnormalized directions
        for (bool useBVH : {false, true}) {
            HitRecord h;
            ASSERT_TRUE(t->Intersect(useBVH, r, &h)) << i;
            SurfaceInteraction si = ComputeInteraction(t->view, h, r);
            // The first hit along the ray; the target itself unless the ray crosses the saddle before.
            EXPECT_NEAR(si.p.z, si.p.x * si.p.y, 2e-5f);
            EXPECT_NEAR(si.uv.x, si.p.x, 2e-5f);
            EXPECT_NEAR(si.uv.y, si.p.y, 2e-5f);
            Vec3f n = Normalize(Vec3f(-si.uv.y, -si.uv.x, 1));
            EXPECT_GT(std::abs(Dot(si.n, n)), 1 - 1e-5f);
            EXPECT_LT(Distance(r(h.t), si.p), 1e-4f);
            if (Distance(si.p, target) < 1e-4f) ++hits;
        }
    }
    EXPECT_GT(hits, 600);   // most rays meet the saddle first at their target
    // Outside [0, 1]^2: no hit.
    HitRecord h;
    EXPECT_FALSE(t->Intersect(false, MakeRay({1.2f, 0.5f, -3}, {0, 0, 1}), &h));
    EXPECT_FALSE(t->Intersect(true, MakeRay({0.5f, -0.1f, -3}, {0, 0, 1}), &h));
}

TEST(BilinearPatch, TheNearerOfTwoHits) {
    auto t = Trace("bilinear_two_hits", kSaddle);
    // The line (s, s, s - 3/16) meets z = s^2 at s = 1/4 and s = 3/4.
    Ray r = MakeRay({0, 0, -0.1875f}, {1, 1, 1});
    for (bool useBVH : {false, true}) {
        HitRecord h;
        ASSERT_TRUE(t->Intersect(useBVH, r, &h));
        EXPECT_NEAR(h.t, 0.25f, 1e-5f);
        Ray r2 = MakeRay(r(0.5f), r.d);   // from between the two: the far one
        ASSERT_TRUE(t->Intersect(useBVH, r2, &h));
        EXPECT_NEAR(h.t, 0.25f, 1e-5f);
        EXPECT_NEAR(r2(h.t).x, 0.75f, 1e-5f);
    }
}

// Area by quadrature against a fine triangulation of the saddle; parallelograms exactly.
TEST(BilinearPatch, Area) {
    PatchCorners c{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}};
    double fine = 0;
    const int n = 400;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            auto P = [&](int a, int b) { return PatchPoint(c, Float(a) / n, Float(b) / n); };
            fine += 0.5 * Length(Cross(P(i + 1, j) - P(i, j), P(i, j + 1) - P(i, j)));
            fine += 0.5 * Length(Cross(P(i + 1, j) - P(i + 1, j + 1), P(i, j + 1) - P(i + 1, j + 1)));
        }
    std::printf("[ patch     ] saddle area: quadrature %.6f, %dx%d triangulation %.6f\n", BilinearPatchArea(c), n, n, fine);
    EXPECT_NEAR(BilinearPatchArea(c), fine, 2e-5 * fine);
    PatchCorners para{{0, 0, 0}, {2, 0, 0}, {1, 3, 0}, {3, 3, 0}};
    EXPECT_NEAR(BilinearPatchArea(para), 6, 1e-5f);
}

// Area-light sampling of a curved patch: (u, v) by the bilinear density (chi-square), ShapePDF
// equal to the sample's pdf, and the mean of 1 / pdf the solid angle the patch subtends.
TEST(BilinearPatch, LightSampling) {
    auto t = Trace("bilinear_light", "AttributeBegin\nAreaLightSource \"diffuse\"\n"
                                      "Shape \"bilinearmesh\" \"point3 P\" [ -1 -1 0  1 -1 0.5  -1 1 0.8  1 1 -0.4 ]\n"
                                      "AttributeEnd\n");
    ASSERT_EQ(t->view.bilinearMeshes.size, 1u);
    const SceneView &s = t->view;
    const Shape &shape = s.shapes[0];
    uint32_t vtx[4];
    PatchVertices(s.bilinearMeshes[0], s, 0, vtx);
    PatchCorners c = PatchPositions(s, vtx);
    Float w[4];
    PatchCornerWeights(c, w);
    Chi2Result chi = Chi2SampleTest(
        RectDomain(0, 1, 0, 1, 16, 16),
        [&](Chi2Point *p) {
            static Pcg32 rng(5);
            Vec2f uv = SampleBilinear(Vec2f(rng.Uniform(), rng.Uniform()), w);
            p->x = uv.x;
            p->y = uv.y;
            return true;
        },
        [&](const Chi2Point &p) { return double(BilinearPDF(Vec2f(Float(p.x), Float(p.y)), w)); });
    EXPECT_GT(chi.pValue, 1e-4) << chi.message;
    EXPECT_LT(chi.controlPValue, 1e-4);
    LightSampleContext ctx;
    ctx.p = Vec3f(0.2f, 0.1f, -2);
    ctx.n = ctx.ns = Vec3f(0, 0, 1);
    Pcg32 rng(9);
    const int n = 200000;
    double sum = 0, sum2 = 0;
    int mismatches = 0;
    for (int i = 0; i < n; ++i) {
        ShapeSample ss;
        if (!SampleShape(s, shape, 0, ctx, Vec2f(rng.Uniform(), rng.Uniform()), &ss)) continue;
        Vec3f wi = Normalize(ss.p - ctx.p);
        Float pdf = ShapePDF(s, shape, 0, ctx, wi, ss.p, ss.n);
        mismatches += std::abs(pdf - ss.pdf) > 1e-3f * ss.pdf;
        sum += 1 / ss.pdf;
        sum2 += 1 / (double(ss.pdf) * ss.pdf);
    }
    // The solid angle by a fine triangulation (sum of spherical triangles).
    double omega = 0;
    const int m = 200;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
            auto D = [&](int a, int b) { return Normalize(PatchPoint(c, Float(a) / m, Float(b) / m) - ctx.p); };
            omega += SphericalTriangleArea(D(i, j), D(i + 1, j), D(i + 1, j + 1));
            omega += SphericalTriangleArea(D(i, j), D(i + 1, j + 1), D(i, j + 1));
        }
    double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    std::printf("[ patch     ] solid angle: sampled %.5f +- %.5f, triangulated %.5f; pdf mismatches %d\n", mean, se,
                omega, mismatches);
    EXPECT_NEAR(mean, omega, 5 * se + 1e-4 * omega);
    EXPECT_LT(mismatches, n / 1000);
}

// The builder keeps parallelograms (with affine uv) as triangle pairs and curved patches native.
TEST(BilinearPatch, BuilderSplitsFlatAndCurvedPatches) {
    auto t = Trace("bilinear_split", "Shape \"bilinearmesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0  1 1 0 "
                                     " 2 0 0  3 0 0  2 1 0  3 1 1 ] \"integer indices\" [ 0 1 2 3  4 5 6 7 ]\n"
                                     "Shape \"bilinearmesh\" \"point3 P\" [ 0 0 1  1 0 1  0 1 1  1 1 1 ]"
                                     " \"point2 uv\" [ 0 0  1 0  0 1  3 3 ]\n");
    ASSERT_EQ(t->view.triangleMeshes.size, 1u);
    EXPECT_EQ(t->view.triangleMeshes[0].triangleCount, 2u);
    ASSERT_EQ(t->view.bilinearMeshes.size, 2u);   // the curved patch, and the flat one with non-affine uv
    EXPECT_EQ(t->scene->stats.bilinearPatches, 2u);
    // The flat patch with bilinear uv: at (u, v) = (0.5, 0.5) the uv is the corners' mean (1, 1).
    HitRecord h;
    Ray r = MakeRay({0.5f, 0.5f, 3}, {0, 0, -1});   // from above: the z = 1 patch first
    for (bool useBVH : {false, true}) {
        ASSERT_TRUE(t->Intersect(useBVH, r, &h));
        EXPECT_EQ(t->view.shapes[h.shape].kind, ShapeKind::BilinearPatches);
    }
    SurfaceInteraction si = ComputeInteraction(t->view, h, r);
    EXPECT_NEAR(si.uv.x, 1, 1e-5f);
    EXPECT_NEAR(si.uv.y, 1, 1e-5f);
}

// ---- Curves ----

std::string StraightCurve(const std::string &extra) {
    return "Shape \"curve\" \"point3 P\" [ -1 0 0  -0.3333333 0 0  0.3333333 0 0  1 0 0 ] " + extra + "\n";
}

TEST(Curve, FlatHitsWithinHalfTheWidth) {
    auto t = Trace("curve_flat", StraightCurve("\"float width0\" [ 0.1 ] \"float width1\" [ 0.3 ]"));
    ASSERT_EQ(t->view.curveSets.size, 1u);
    EXPECT_EQ(t->view.shapes[0].primitiveCount, 8u);   // splitdepth 3
    Pcg32 rng(1);
    int hits = 0, n = 2000;
    for (int i = 0; i < n; ++i) {
        Float x = rng.Uniform() * 1.9f - 0.95f, y = rng.Uniform() * 0.4f - 0.2f;
        Float u = (x + 1) / 2, half = Lerp(u, Float(0.1), Float(0.3)) / 2;
        Ray r = MakeRay({x, y, -2}, {0, 0, 2});
        if (std::abs(std::abs(y) - half) < 1e-3f) continue;   // too close to the edge to call
        for (bool useBVH : {false, true}) {
            HitRecord h;
            bool hit = t->Intersect(useBVH, r, &h);
            ASSERT_EQ(hit, std::abs(y) < half) << x << " " << y;
            if (!hit) continue;
            ++hits;
            EXPECT_NEAR(h.t, 1, 1e-5f);
            SurfaceInteraction si = ComputeInteraction(t->view, h, r);
            EXPECT_NEAR(si.uv.x, u, 1e-4f);
            EXPECT_NEAR(si.uv.y, 0.5f + y / (2 * half), 1e-3f);   // v grows towards z x dp/du = +y
            EXPECT_GT(std::abs(si.n.z), 1 - 1e-5f);              // flat: facing the ray
            EXPECT_GT(std::abs(Normalize(si.dpdu).x), 1 - 1e-5f);
        }
    }
    EXPECT_GT(hits, n / 2);
}

// pbrt-v4's "cylinder": dp/dv turned by -theta, theta = lerp(v, -90, 90) degrees, about dp/du: the
// normal is (0, sin phi, cos phi) with phi = (v - 1/2) pi for a ray along +z over a curve along +x.
TEST(Curve, CylinderNormalsTurnAcrossTheWidth) {
    auto t = Trace("curve_cylinder", StraightCurve("\"float width\" [ 0.2 ] \"string type\" \"cylinder\""));
    for (Float y : {-0.09f, -0.05f, 0.f, 0.03f, 0.07f}) {
        Ray r = MakeRay({0.1f, y, -2}, {0, 0, 1});
        HitRecord h;
        ASSERT_TRUE(t->Intersect(false, r, &h));
        SurfaceInteraction si = ComputeInteraction(t->view, h, r);
        Float v = 0.5f + y / 0.2f, phi = (v - 0.5f) * Pi;
        EXPECT_NEAR(si.uv.y, v, 1e-4f);
        EXPECT_NEAR(si.n.x, 0, 1e-4f);
        EXPECT_NEAR(si.n.y, std::sin(phi), 1e-3f) << y;
        EXPECT_NEAR(si.n.z, std::cos(phi), 1e-3f) << y;
    }
}

// Ribbons: the width times |cos| of the angle between the normal and the ray.
TEST(Curve, RibbonWidthFollowsItsNormal) {
    const Float c60 = 0.5f, s60 = 0.8660254f;
    auto facing = Trace("curve_ribbon", StraightCurve("\"float width\" [ 0.2 ] \"string type\" \"ribbon\" "
                                                      "\"normal N\" [ 0 " + std::to_string(s60) + " " +
                                                      std::to_string(c60) + "  0 " + std::to_string(s60) + " " +
                                                      std::to_string(c60) + " ]"));
    for (Float y : {0.04f, 0.06f}) {
        HitRecord h;
        bool hit = facing->Intersect(true, MakeRay({0, y, -2}, {0, 0, 1}), &h);
        EXPECT_EQ(hit, y < 0.05f) << y;   // half of 0.2 cos 60
        HitRecord he;
        EXPECT_EQ(facing->Intersect(false, MakeRay({0, y, -2}, {0, 0, 1}), &he), hit);
    }
}

// A bent curve (a quarter circle of radius 1 as a Bezier): rays along z hit exactly where the
// curve's true distance (dense sampling) is under half the width.
TEST(Curve, BentCurveHitsWhereTheCurvePasses) {
    const Float k = 0.5522847f;
    auto t = Trace("curve_bent", "Shape \"curve\" \"point3 P\" [ 1 0 0  1 " + std::to_string(k) + " 0  " +
                                     std::to_string(k) + " 1 0  0 1 0 ] \"float width\" [ 0.05 ]\n");
    Vec3f cp[4] = {{1, 0, 0}, {1, k, 0}, {k, 1, 0}, {0, 1, 0}};
    std::vector<Vec3f> dense;
    for (int i = 0; i <= 20000; ++i) dense.push_back(EvalCubicBezier(cp, Float(i) / 20000, nullptr));
    Pcg32 rng(2);
    int hits = 0, checked = 0;
    for (int i = 0; i < 3000; ++i) {
        Float a = rng.Uniform() * Pi / 2 * 0.9f + Pi / 40, rr = 0.94f + 0.12f * rng.Uniform();
        Vec3f p(rr * std::cos(a), rr * std::sin(a), 0);
        Float d = Infinity;
        for (const Vec3f &q : dense) d = Min(d, Distance(q, p));
        if (std::abs(d - 0.025f) < 1.5e-3f) continue;   // subdivision accuracy: 5% of the width
        ++checked;
        for (bool useBVH : {false, true}) {
            HitRecord h;
            bool hit = t->Intersect(useBVH, MakeRay(p - Vec3f(0, 0, 3), {0, 0, 1}), &h);
            EXPECT_EQ(hit, d < 0.025f) << "distance " << d;
            hits += hit;
        }
    }
    EXPECT_GT(checked, 2000);
    EXPECT_GT(hits, 1000);
}

// pbrt-v4's basis conversions: a cubic b-spline's segment and a quadratic Bezier, elevated.
TEST(Curve, BasisConversions) {
    auto t = Trace("curve_bases", "Shape \"curve\" \"string basis\" \"bspline\" \"point3 P\" [ 0 0 0  1 0 0  1 1 0  2 1 0  2 2 0 ]\n"
                                  "Shape \"curve\" \"integer degree\" [ 2 ] \"point3 P\" [ 0 0 1  1 0 1  1 1 1  1 2 1  0 3 1 ]\n"
                                  "Shape \"curve\" \"integer degree\" [ 2 ] \"string basis\" \"bspline\" \"point3 P\" [ 0 0 2  2 0 2  2 2 2 ]\n");
    const SceneView &s = t->view;
    ASSERT_EQ(s.curveSets.size, 3u);
    EXPECT_EQ(s.curveSets[0].segmentCount, 2u);
    EXPECT_EQ(s.curveSets[1].segmentCount, 2u);
    EXPECT_EQ(s.curveSets[2].segmentCount, 1u);
    auto near = [](Vec3f a, Vec3f b) { return Distance(a, b) < 1e-5f; };
    const CurveSegment &b0 = s.curveSegments[0];
    EXPECT_TRUE(near(b0.cp[0], Vec3f(5.f / 6, 1.f / 6, 0)));   // (p0 + 4 p1 + p2) / 6
    EXPECT_TRUE(near(b0.cp[1], Vec3f(1, 1.f / 3, 0)));          // (2 p1 + p2) / 3
    EXPECT_TRUE(near(b0.cp[2], Vec3f(1, 2.f / 3, 0)));          // (p1 + 2 p2) / 3
    EXPECT_TRUE(near(b0.cp[3], Vec3f(7.f / 6, 5.f / 6, 0)));    // (p1 + 4 p2 + p3) / 6
    const CurveSegment &q1 = s.curveSegments[3];                // the quadratic Bezier's second segment
    EXPECT_TRUE(near(q1.cp[0], Vec3f(1, 1, 1)));
    EXPECT_TRUE(near(q1.cp[1], Vec3f(1, 5.f / 3, 1)));
    EXPECT_TRUE(near(q1.cp[2], Vec3f(2.f / 3, 7.f / 3, 1)));
    EXPECT_TRUE(near(q1.cp[3], Vec3f(0, 3, 1)));
    const CurveSegment &qb = s.curveSegments[4];                // quadratic b-spline: (1,0) (2,0) (2,1), elevated
    EXPECT_TRUE(near(qb.cp[0], Vec3f(1, 0, 2)));
    EXPECT_TRUE(near(qb.cp[3], Vec3f(2, 1, 2)));
    EXPECT_TRUE(near(qb.cp[1], Vec3f(5.f / 3, 0, 2)));
    // Widths spread over the segments: width0 1 -> width1 1 (defaults).
    EXPECT_EQ(b0.width[0], 1.f);
}

TEST(Curve, InstancedCurvesAreHitWhereTheirInstanceIs) {
    auto t = Trace("curve_instanced", "ObjectBegin \"hair\"\n" + StraightCurve("\"float width\" [ 0.2 ]") +
                                          "ObjectEnd\nAttributeBegin\nTranslate 0 1 0\nObjectInstance \"hair\"\nAttributeEnd\n"
                                          "AttributeBegin\nTranslate 0 -1 0\nRotate 90 0 0 1\nObjectInstance \"hair\"\nAttributeEnd\n");
    ASSERT_GT(t->view.instances.size, 0u);
    for (bool useBVH : {false, true}) {
        HitRecord h;
        Ray r = MakeRay({0.5f, 1.05f, -2}, {0, 0, 1});
        ASSERT_TRUE(t->Intersect(useBVH, r, &h));
        SurfaceInteraction si = ComputeInteraction(t->view, h, r);
        EXPECT_NEAR(si.p.z, 0, 1e-5f);
        EXPECT_NEAR(si.uv.x, 0.75f, 1e-4f);
        EXPECT_FALSE(t->Intersect(useBVH, MakeRay({0.5f, 1.15f, -2}, {0, 0, 1}), &h));
        // The rotated one runs along y through (0, -1).
        ASSERT_TRUE(t->Intersect(useBVH, MakeRay({0.05f, -1.5f, -2}, {0, 0, 1}), &h));
        EXPECT_FALSE(t->Intersect(useBVH, MakeRay({0.15f, -1.5f, -2}, {0, 0, 1}), &h));
    }
}

// Embree's user geometry and the shared BVH give the same hits (shape, primitive, t) on curves of
// every type and curved patches, under a rotation and a non-uniform scale.
TEST(CurvesAndPatches, EmbreeAndBVHAgree) {
    std::string world = "AttributeBegin\nRotate 30 1 1 0\nScale 1 2 1\n"
                        "Shape \"curve\" \"point3 P\" [ -1 -1 0  -0.5 1 0.5  0.5 -1 -0.5  1 1 0 ] \"float width0\" [ 0.2 ] \"float width1\" [ 0.05 ]\n"
                        "Shape \"curve\" \"string type\" \"cylinder\" \"point3 P\" [ -1 0 0.3  0 1 0.3  1 0 0.3  1 -1 0.3 ] \"float width\" [ 0.1 ]\n"
                        "Shape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [ 0 -1 -0.3  0.2 0 -0.3  0 1 -0.3  0.5 1.5 -0.3 ] "
                        "\"normal N\" [ 0 0 1  1 0 1 ] \"float width\" [ 0.15 ]\n"
                        "Shape \"bilinearmesh\" \"point3 P\" [ -1 -1 1  1 -1 1.5  -1 1 1.2  1 1 0.6 ]\nAttributeEnd\n";
    auto t = Trace("curves_patches_agree", world);
    std::vector<Ray> rays = IncoherentRays(t->view.bounds, 20000, 17);
    int agree = 0, hits = 0;
    for (const Ray &r : rays) {
        HitRecord a, b;
        bool ha = t->Intersect(false, r, &a), hb = t->Intersect(true, r, &b);
        hits += ha;
        bool same = ha == hb && (!ha || (a.shape == b.shape && a.primitive == b.primitive &&
                                         std::abs(a.t - b.t) <= 1e-5f * (1 + a.t)));
        agree += same;
    }
    std::printf("[ tracers   ] curves and patches: %d of %zu rays agree, %d hits\n", agree, rays.size(), hits);
    EXPECT_GT(hits, 500);
    EXPECT_GE(agree, int(rays.size()) - 2);   // exact ties at shared piece boundaries aside
}

TEST(Curve, LocatedErrors) {
    struct Case {
        std::string shape;
        const char *what;
    } cases[] = {
        {"Shape \"curve\" \"point3 P\" [ 0 0 0  1 0 0  2 0 0  3 0 0  4 0 0 ]", "a degree 3 Bezier curve needs 4 + k * 3"},
        {"Shape \"curve\" \"string basis\" \"bspline\" \"point3 P\" [ 0 0 0  1 0 0  2 0 0 ]", "needs at least 4"},
        {"Shape \"curve\" \"integer degree\" [ 4 ] \"point3 P\" [ 0 0 0  1 0 0  2 0 0  3 0 0 ]", "\"degree\" must be 2 or 3"},
        {"Shape \"curve\" \"string type\" \"tube\" \"point3 P\" [ 0 0 0  1 0 0  2 0 0  3 0 0 ]", "unknown \"type\" \"tube\""},
        {"Shape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [ 0 0 0  1 0 0  2 0 0  3 0 0 ]", "needs 2 normals"},
        {"Shape \"curve\" \"float width\" [ -1 ] \"point3 P\" [ 0 0 0  1 0 0  2 0 0  3 0 0 ]", "not negative"},
        {"AreaLightSource \"diffuse\"\nShape \"curve\" \"point3 P\" [ 0 0 0  1 0 0  2 0 0  3 0 0 ]", "AreaLightSource on a \"curve\""},
    };
    for (const Case &c : cases) {
        std::string text = "Camera \"perspective\"\nWorldBegin\n" + c.shape + "\n";
        std::string dir = TempDir("curve_errors");
        std::string path = dir + "/scene.pbrt";
        std::ofstream(path) << text;
        Diagnostics diag;
        diag.quiet = true;
        try {
            LoadScene(path, diag, BuildOptions{});
            ADD_FAILURE() << "no error for " << c.shape;
        } catch (const SceneError &e) {
            EXPECT_NE(e.Message().find(c.what), std::string::npos) << e.Message();
            EXPECT_GE(e.Loc().line, 3) << e.Format();
            EXPECT_NE(e.Format().find("scene.pbrt:"), std::string::npos) << e.Format();
        }
    }
}

}  // namespace
}  // namespace lu::test
