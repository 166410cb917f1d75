// Tests of lights/: SampleLi against PDF_Li (per-sample agreement and chi-square over a direction
// grid, for every light type), pdf normalization, emitted radiance at the sampled point vs the
// intersected point, analytic irradiance, spot falloff, power-proportional light selection,
// the equal-area mapping and the RGB illuminant lookup.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "lucerna/geometry/shapes.h"
#include "lucerna/lights/lights.h"
#include "lucerna/scene/builder.h"
#include "lucerna/scene/light_build.h"
#include "lucerna/spectra/registry.h"
#include "support/test_support.h"
#include "support/test_transforms.h"

namespace lu {
namespace {

// ---- A SceneView built from vectors ----

template <typename T>
Span<T> SpanOf(const std::vector<T> &v) {
    return {v.data(), uint32_t(v.size())};
}

using test::Rotate;
using test::Translate;

// A HostScene filled by hand, with a constant spectrum as table 0 (the "illuminant") and an
// optional toy RGB-to-spectrum table in place of the registry's tables.
struct TestScene : HostScene {
    std::vector<Float> constantSpectra;  // table 0: constant 1
    std::vector<Float> rgbCoeffs, zNodes;
    uint32_t rgbRes = 0;

    TestScene() { constantSpectra.assign(TabulatedSpectrumSize, 1.f); }

    SceneView View() const {
        SceneView s = HostScene::View();
        s.spectra = {constantSpectra.data(), uint32_t(constantSpectra.size() / TabulatedSpectrumSize)};
        s.rgbToSpecCoeffs = SpanOf(rgbCoeffs);
        s.rgbToSpecZNodes = SpanOf(zNodes);
        s.rgbToSpecRes = rgbRes;
        s.illuminantTables[0] = 0;
        return s;
    }

    uint32_t AddTriangle(Vec3f a, Vec3f b, Vec3f c, bool flip = false, const Vec3f *vertexNormal = nullptr) {
        TriangleMesh m;
        m.firstVertex = uint32_t(positions.size());
        m.vertexCount = 3;
        m.firstIndex = uint32_t(indices.size());
        m.triangleCount = 1;
        m.flipNormals = flip;
        positions.insert(positions.end(), {a, b, c});
        indices.insert(indices.end(), {0u, 1u, 2u});
        if (vertexNormal) {
            m.normalOffset = uint32_t(normals.size());
            normals.insert(normals.end(), {*vertexNormal, *vertexNormal, *vertexNormal});
        }
        triangleMeshes.push_back(m);
        Shape s;
        s.kind = ShapeKind::Triangles;
        s.index = uint32_t(triangleMeshes.size() - 1);
        s.primitiveCount = 1;
        shapes.push_back(s);
        return uint32_t(shapes.size() - 1);
    }
    // A partial sphere when zmin > -r, zmax < r or phimax (degrees) < 360.
    uint32_t AddSphere(const Transform &t, Float r, Float zmin = -Infinity, Float zmax = Infinity, Float phimax = 360) {
        Sphere sp;
        sp.renderFromObject = t;
        sp.radius = r;
        SetSphereClip(sp, zmin, zmax, phimax);
        spheres.push_back(sp);
        Shape s;
        s.kind = ShapeKind::Sphere;
        s.index = uint32_t(spheres.size() - 1);
        shapes.push_back(s);
        return uint32_t(shapes.size() - 1);
    }
    uint32_t AddDisk(const Transform &t, Float r, Float h = 0, Float ri = 0, Float phimax = 360) {
        Disk d;
        d.renderFromObject = t;
        d.radius = r;
        d.height = h;
        d.innerRadius = ri;
        d.phiMax = PhiMaxRadians(phimax);
        disks.push_back(d);
        Shape s;
        s.kind = ShapeKind::Disk;
        s.index = uint32_t(disks.size() - 1);
        shapes.push_back(s);
        return uint32_t(shapes.size() - 1);
    }
    uint32_t AddCylinder(const Transform &t, Float r, Float zmin, Float zmax, Float phimax = 360, bool flip = false) {
        cylinders.push_back(Cylinder{t, r, zmin, zmax, PhiMaxRadians(phimax), flip});
        Shape s;
        s.kind = ShapeKind::Cylinder;
        s.index = uint32_t(cylinders.size() - 1);
        shapes.push_back(s);
        return uint32_t(shapes.size() - 1);
    }
    uint32_t AddAreaLight(uint32_t shape, Float L, bool twoSided = false) {
        Light l;
        l.kind = LightKind::DiffuseArea;
        l.spectrum = Spectrum::Const(L);
        l.shape = shape;
        l.primitive = 0;
        l.twoSided = twoSided;
        lights.push_back(l);
        shapes[shape].areaLight = uint32_t(lights.size() - 1);
        return uint32_t(lights.size() - 1);
    }
    // A gray or RGB image infinite light (texels row-major, `channels` per texel).
    uint32_t AddImageLight(const std::vector<float> &tex, int res, int channels, const Transform &renderFromLight) {
        ImageData im;
        im.width = im.height = uint32_t(res);
        im.channels = uint32_t(channels);
        im.offset = texels.size();
        texels.insert(texels.end(), tex.begin(), tex.end());
        images.push_back(im);
        Light l;
        l.kind = LightKind::ImageInfinite;
        l.image = uint32_t(images.size() - 1);
        l.renderFromLight = renderFromLight;
        l.distribution = BuildImageInfiniteDistributions(tex.data(), res, res, channels, distributions2D, distData);
        l.sceneRadius = 10;
        lights.push_back(l);
        infiniteLights.push_back(uint32_t(lights.size() - 1));
        return uint32_t(lights.size() - 1);
    }
};

// Intersects the ray with one shape (as a backend would) and rebuilds the hit.
bool HitShape(const SceneView &s, uint32_t shapeIndex, const Ray &ray, SurfaceInteraction *si) {
    const Shape &shape = s.shapes[shapeIndex];
    HitRecord hit;
    hit.shape = shapeIndex;
    Float t;
    bool found = false;
    switch (shape.kind) {
    case ShapeKind::Triangles: {
        uint32_t v[3];
        TriangleVertices(s, s.triangleMeshes[shape.index], 0, v);
        Float b1, b2;
        found = IntersectTriangle(s.positions[v[0]], s.positions[v[1]], s.positions[v[2]], ray, Infinity, &t, &b1, &b2);
        hit.b1 = b1;
        hit.b2 = b2;
        break;
    }
    default: found = IntersectQuadric(s, shape, ray, Infinity, &t); break;
    }
    if (!found) return false;
    hit.t = t;
    *si = ComputeInteraction(s, hit, ray);
    return true;
}

SampledWavelengths TestLambda() { return SampledWavelengths::SampleVisible(0.37f); }

// pdf of direction w at ctx for light li, via an intersection for area lights.
Float DirectionPDF(const SceneView &s, uint32_t li, const LightSampleContext &ctx, Vec3f w, bool incomplete) {
    const Light &l = s.lights[li];
    if (l.kind != LightKind::DiffuseArea) return PDF_Li(l, s, ctx, w, ctx.p + w, -w, incomplete);
    SurfaceInteraction si;
    if (!HitShape(s, l.shape, Ray{ctx.p, w, Infinity}, &si)) return 0;
    return PDF_Li(l, s, ctx, w, si.p, si.n, incomplete);
}

// ---- Chi-square of SampleLi directions against PDF_Li over a cap of directions ----

struct SamplingCheck {
    test::Chi2Result chi2;   // the harness's result (support/chi2.h)
    int pdfMismatches = 0;   // samples whose ls.pdf disagrees with PDF_Li
};

// The chi-square test (support/chi2.h) of SampleLi's directions against PDF_Li over the cap
// {w : dot(w, axis) >= cosCap} (nT x nP cells of equal solid angle); directions outside the cap
// reject. Samples SampleLi refuses are set aside and counted (chi2.failed): PDF_Li covers
// directions where a sample may still be refused. pdfOverride replaces PDF_Li (negative tests).
// failuresInHistogram: refused samples count in a cell expecting 1 - (integral of PDF_Li), for
// lights whose PDF_Li does not integrate to 1 (a one-sided cylinder seen from outside).
SamplingCheck CheckSampling(const SceneView &s, uint32_t li, const LightSampleContext &ctx, Vec3f axis, Float cosCap,
                            bool incomplete = false, int N = 100000, int nT = 20, int nP = 24,
                            const std::function<Float(Vec3f)> &pdfOverride = nullptr, double integralTol = 0.02,
                            bool failuresInHistogram = false) {
    SamplingCheck r;
    std::mt19937 rng(1234 + li);
    std::uniform_real_distribution<float> U(0, 1);
    SampledWavelengths lambda = TestLambda();
    const Light &l = s.lights[li];
    auto sample = [&](test::Chi2Point *p) {
        LightLiSample ls;
        if (!SampleLi(l, s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls, incomplete)) return false;
        if (!pdfOverride) {
            Float pdf = PDF_Li(l, s, ctx, ls.wi, ls.pLight, ls.nLight, incomplete);
            if (!(std::abs(pdf - ls.pdf) <= 1e-2f * ls.pdf)) ++r.pdfMismatches;
        }
        *p = {ls.wi.x, ls.wi.y, ls.wi.z};
        return true;
    };
    auto pdf = [&](const test::Chi2Point &p) {
        Vec3f w(Float(p.x), Float(p.y), Float(p.z));
        return double(pdfOverride ? pdfOverride(w) : DirectionPDF(s, li, ctx, w, incomplete));
    };
    test::Chi2Options opts;
    opts.samples = N;
    opts.failuresInHistogram = failuresInHistogram;
    opts.integralTolerance = integralTol;
    r.chi2 = test::Chi2SampleTest(test::CapDomain({axis.x, axis.y, axis.z}, cosCap, nT, nP), sample, pdf, opts);
    return r;
}

// Widest angle (as 1 - cos) from axis to any of the points seen from p, enlarged by 25%.
Float CapFor(Vec3f p, Vec3f axis, std::initializer_list<Vec3f> pts) {
    Float oneMinus = 0;
    for (Vec3f q : pts) oneMinus = Max(oneMinus, 1 - Dot(axis, Normalize(q - p)));
    return 1 - Min(Float(2), oneMinus * 1.25f);
}

// maxMismatches: image lights may disagree at texel seams where the uv -> direction -> uv round
// trip changes texel (as in pbrt-v4).
void ExpectGood(const SamplingCheck &r, double integralTol = 0.01, int maxMismatches = 0) {
    EXPECT_TRUE(test::Chi2Accepts(r.chi2));
    EXPECT_NEAR(r.chi2.pdfIntegral, 1.0, integralTol) << r.chi2.message;
    EXPECT_LE(r.pdfMismatches, maxMismatches);
}

// ---- Triangle lights ----

struct TriangleCase {
    Vec3f a, b, c;
    Vec3f p, n;   // reference point and its normal ((0,0,0): not on a surface)
    bool twoSided;
    const char *what;
};

TEST(TriangleLight, SamplingMatchesPdf) {
    const TriangleCase cases[] = {
        // spherical sampling with the cos warp (surface reference point)
        {{-0.5f, -0.4f, 1}, {0.6f, -0.3f, 1.2f}, {0.1f, 0.7f, 0.9f}, {0, 0, 0}, Normalize(Vec3f(0.3f, 0.1f, 1)), false, "near, warped"},
        // spherical sampling without the warp (medium-like point)
        {{-0.5f, -0.4f, 1}, {0.6f, -0.3f, 1.2f}, {0.1f, 0.7f, 0.9f}, {0, 0, 0}, {0, 0, 0}, false, "near, no normal"},
        // tilted, seen at a grazing angle, back side (two-sided)
        {{-1, 0.2f, 0.3f}, {1, 0.4f, 0.2f}, {0, 0.3f, 2.5f}, {0, -0.2f, 0}, Normalize(Vec3f(0, 0.5f, 1)), true, "grazing, two-sided"},
        // far away: below MinSphericalSampleArea -> area sampling
        {{-0.05f, 0, 10}, {0.05f, 0, 10}, {0, 0.08f, 10.1f}, {0, 0, 0}, {0, 0, 1}, false, "far (area sampling)"},
    };
    for (const TriangleCase &tc : cases) {
        SCOPED_TRACE(tc.what);
        TestScene ts;
        // Orient the normal towards p, or away from it for two-sided lights (emitting backwards).
        Vec3f ng = Cross(tc.b - tc.a, tc.c - tc.a);
        bool flip = (Dot(ng, tc.p - tc.a) < 0) != tc.twoSided;
        uint32_t sh = ts.AddTriangle(tc.a, tc.b, tc.c, flip);
        uint32_t li = ts.AddAreaLight(sh, 2.f, tc.twoSided);
        SceneView s = ts.View();
        LightSampleContext ctx{tc.p, tc.n, tc.n};
        Vec3f axis = Normalize((tc.a + tc.b + tc.c) / 3 - tc.p);
        Float cosCap = CapFor(tc.p, axis, {tc.a, tc.b, tc.c});
        SamplingCheck r = CheckSampling(s, li, ctx, axis, cosCap);
        ExpectGood(r, 0.02);
        EXPECT_LT(r.chi2.failed, 100);
    }
}

TEST(TriangleLight, HugeTriangleUsesUniformAreaSampling) {
    // Solid angle above MaxSphericalSampleArea: pbrt-v4 falls back to area sampling. The direction
    // pdf is then concentrated at grazing angles, so test uniformity on the triangle itself:
    // b1 has density 2 (1 - b1), and b2 is uniform on [0, 1 - b1].
    TestScene ts;
    Vec3f a(-20, -20, 0.01f), b(40, -20, 0.01f), c(-20, 40, 0.01f);
    uint32_t sh = ts.AddTriangle(a, b, c, true);  // normal -z, facing the origin
    uint32_t li = ts.AddAreaLight(sh, 1.f);
    SceneView s = ts.View();
    LightSampleContext ctx{{0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    ASSERT_GT(TriangleSolidAngle(GetTriangle(s, ts.triangleMeshes[0], 0), ctx.p), MaxSphericalSampleArea);
    // (b1, b2 / (1 - b1)) has density 2 (1 - b1) on the unit square.
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> U(0, 1);
    SampledWavelengths lambda = TestLambda();
    int mismatches = 0, failures = 0;
    auto sample = [&](test::Chi2Point *q) {
        LightLiSample ls;
        if (!SampleLi(s.lights[li], s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls)) {
            ++failures;
            return false;
        }
        Float p = PDF_Li(s.lights[li], s, ctx, ls.wi, ls.pLight, ls.nLight);
        if (!(std::abs(p - ls.pdf) <= 1e-3f * ls.pdf)) ++mismatches;
        // Barycentrics of pLight (the triangle is in the plane z = 0.01).
        double b1 = (ls.pLight.x + 20) / 60, b2 = (ls.pLight.y + 20) / 60;
        *q = {b1, b2 / std::max(1e-9, 1 - b1), 0};
        return true;
    };
    test::Chi2Options opts;
    opts.samples = 100000;
    test::Chi2Result r = test::Chi2SampleTest(test::RectDomain(0, 1, 0, 1, 10, 5), sample,
                                              [](const test::Chi2Point &q) { return 2 * (1 - q.x); }, opts);
    EXPECT_TRUE(test::Chi2Accepts(r));
    EXPECT_EQ(failures, 0);
    EXPECT_EQ(mismatches, 0);
}

TEST(TriangleLight, ChiSquareDetectsMissingWarp) {
    // Samples drawn with the cos warp must not pass against the unwarped pdf.
    TestScene ts;
    Vec3f a(-0.8f, -0.6f, 0.5f), b(0.9f, -0.5f, 0.6f), c(0.1f, 0.9f, 0.4f);
    uint32_t sh = ts.AddTriangle(a, b, c, Dot(Cross(b - a, c - a), -a) < 0);
    uint32_t li = ts.AddAreaLight(sh, 1.f);
    SceneView s = ts.View();
    Vec3f n = Normalize(Vec3f(1, 0, 0.3f));
    LightSampleContext ctx{{0, 0, 0}, n, n};
    Vec3f axis = Normalize((a + b + c) / 3);
    LightSampleContext noNormal{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    SamplingCheck r = CheckSampling(s, li, ctx, axis, CapFor({0, 0, 0}, axis, {a, b, c}), false, 100000, 20, 24,
                                    [&](Vec3f w) { return DirectionPDF(s, li, noNormal, w, false); });
    EXPECT_TRUE(test::Chi2Rejects(r.chi2));
}

TEST(TriangleLight, LMatchesIntersectedPoint) {
    TestScene ts;
    Vec3f a(-0.5f, -0.4f, 1), b(0.6f, -0.3f, 1.2f), c(0.1f, 0.7f, 0.9f);
    Vec3f vn = Normalize(Vec3f(0.1f, 0, -1));  // shading normal towards the origin decides the side
    uint32_t sh = ts.AddTriangle(a, b, c, false, &vn);
    uint32_t li = ts.AddAreaLight(sh, 3.f);
    SceneView s = ts.View();
    LightSampleContext ctx{{0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> U(0, 1);
    SampledWavelengths lambda = TestLambda();
    int ok = 0;
    for (int i = 0; i < 500; ++i) {
        LightLiSample ls;
        if (!SampleLi(s.lights[li], s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls)) continue;
        ++ok;
        SurfaceInteraction si;
        ASSERT_TRUE(HitShape(s, sh, Ray{ctx.p, ls.wi, Infinity}, &si));
        EXPECT_NEAR(Distance(si.p, ls.pLight), 0, 1e-4f);
        EXPECT_NEAR(Dot(si.n, ls.nLight), 1, 1e-5f);
        EXPECT_NEAR(ls.distance, Distance(ctx.p, ls.pLight), 1e-5f);
        SampledSpectrum L = AreaLightL(s.lights[li], s, si.p, si.n, si.uv, -ls.wi, lambda);
        for (int k = 0; k < NSpectrumSamples; ++k) EXPECT_FLOAT_EQ(L[k], ls.L[k]);
        EXPECT_FLOAT_EQ(ls.L[0], 3.f);
        EXPECT_FALSE(ls.isDelta);
    }
    EXPECT_EQ(ok, 500);
    // Seen from behind, a one-sided light gives nothing.
    LightSampleContext behind{{0, 0, 3}, {0, 0, 0}, {0, 0, 0}};
    LightLiSample ls;
    EXPECT_FALSE(SampleLi(s.lights[li], s, behind, Vec2f(0.3f, 0.6f), lambda, &ls));
}

// Irradiance from a uniformly emitting polygon (Lambert): E = L/2 sum_i angle_i (n . unit normal
// of the edge plane).
double PolygonIrradiance(Vec3f p, Vec3f n, const std::vector<Vec3f> &v, double L) {
    double sum = 0;
    for (size_t i = 0; i < v.size(); ++i) {
        Vec3f a = Normalize(v[i] - p), b = Normalize(v[(i + 1) % v.size()] - p);
        sum += AngleBetween(a, b) * Dot(n, Normalize(Cross(a, b)));
    }
    return std::abs(sum) * L / 2;
}

// Monte Carlo estimate of irradiance at ctx (normal ctx.n) from light li: mean and std. error.
void EstimateIrradiance(const SceneView &s, uint32_t li, const LightSampleContext &ctx, int N, double *mean,
                        double *stderr_) {
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> U(0, 1);
    SampledWavelengths lambda = TestLambda();
    double sum = 0, sum2 = 0;
    for (int i = 0; i < N; ++i) {
        LightLiSample ls;
        double v = 0;
        if (SampleLi(s.lights[li], s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls))
            v = ls.L[0] * std::max(0.f, Dot(ls.wi, ctx.n)) / ls.pdf;
        sum += v;
        sum2 += v * v;
    }
    *mean = sum / N;
    *stderr_ = std::sqrt(std::max(0.0, sum2 / N - *mean * *mean) / N);
}

TEST(TriangleLight, IrradianceMatchesAnalytic) {
    struct Case { Vec3f a, b, c; Vec3f n; };
    const Case cases[] = {
        {{-0.3f, -0.2f, 1}, {0.4f, -0.1f, 1.1f}, {0, 0.5f, 0.9f}, {0, 0, 1}},                 // spherical + warp
        {{-0.03f, -0.02f, 5}, {0.04f, -0.01f, 5}, {0, 0.05f, 5}, Normalize(Vec3f(0.2f, 0, 1))}, // area sampling
    };
    for (const Case &c : cases) {
        TestScene ts;
        uint32_t sh = ts.AddTriangle(c.a, c.b, c.c, Dot(Cross(c.b - c.a, c.c - c.a), -c.a) < 0);
        uint32_t li = ts.AddAreaLight(sh, 5.f);
        SceneView s = ts.View();
        LightSampleContext ctx{{0, 0, 0}, c.n, c.n};
        double mean, se;
        EstimateIrradiance(s, li, ctx, 200000, &mean, &se);
        double E = PolygonIrradiance({0, 0, 0}, c.n, {c.a, c.b, c.c}, 5.0);
        EXPECT_NEAR(mean, E, 5 * se + 2e-3 * E) << "stderr " << se;
    }
}

// ---- Sphere and disk lights ----

TEST(SphereLight, SamplingMatchesPdfOutsideAndInside) {
    struct Case { Vec3f center; Float r; Vec3f p, n; bool inside; const char *what; };
    const Case cases[] = {
        {{0.3f, 0.2f, 3}, 1.f, {0, 0, 0}, {0, 0, 1}, false, "outside"},
        {{0.3f, 0.2f, 1.3f}, 1.f, {0, 0, 0}, {0, 0, 0}, false, "outside, close"},
        {{0, 0.5f, 60}, 0.5f, {0, 0, 0}, {0, 0, 1}, false, "outside, tiny cone (Taylor branch)"},
        {{0.2f, -0.3f, 0.1f}, 1.f, {0, 0, 0}, {0, 0, 0}, true, "inside"},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.what);
        TestScene ts;
        uint32_t sh = ts.AddSphere(Translate(c.center) * Rotate(Degrees(0.7f), Vec3f(1, 1, 0)), c.r);
        uint32_t li = ts.AddAreaLight(sh, 1.f, c.inside);  // seen from inside: two-sided
        SceneView s = ts.View();
        LightSampleContext ctx{c.p, c.n, c.n};
        Vec3f axis = Normalize(c.center - c.p);
        Float cosCap = -1;
        if (!c.inside) {
            Float sin2 = Sqr(c.r) / DistanceSquared(c.p, c.center);
            cosCap = 1 - 1.25f * (1 - std::sqrt(1 - sin2));
        }
        SamplingCheck r = CheckSampling(s, li, ctx, axis, cosCap);
        ExpectGood(r, 0.02);
        EXPECT_EQ(r.chi2.failed, 0);
    }
}

TEST(SphereLight, IrradianceMatchesAnalytic) {
    for (Float d : {2.f, 8.f, 50.f}) {
        TestScene ts;
        uint32_t sh = ts.AddSphere(Translate({0, 0, d}), 0.7f);
        uint32_t li = ts.AddAreaLight(sh, 2.f);
        SceneView s = ts.View();
        LightSampleContext ctx{{0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
        double mean, se;
        EstimateIrradiance(s, li, ctx, 50000, &mean, &se);
        double E = Pi * 2.0 * Sqr(0.7) / Sqr(d);  // pi L sin^2(thetaMax)
        EXPECT_NEAR(mean, E, 5 * se + 1e-3 * E) << d;
    }
}

TEST(SphereLight, LMatchesIntersectedPoint) {
    TestScene ts;
    uint32_t sh = ts.AddSphere(Translate({0, 0, 3}), 1.f);
    uint32_t li = ts.AddAreaLight(sh, 4.f);
    SceneView s = ts.View();
    LightSampleContext ctx{{0.1f, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> U(0, 1);
    SampledWavelengths lambda = TestLambda();
    for (int i = 0; i < 300; ++i) {
        LightLiSample ls;
        ASSERT_TRUE(SampleLi(s.lights[li], s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls));
        SurfaceInteraction si;
        ASSERT_TRUE(HitShape(s, sh, Ray{ctx.p, ls.wi, Infinity}, &si));
        EXPECT_NEAR(Distance(si.p, ls.pLight), 0, 2e-3f);
        EXPECT_NEAR(Dot(si.n, ls.nLight), 1, 1e-3f);
        EXPECT_FLOAT_EQ(AreaLightL(s.lights[li], s, si.p, si.n, si.uv, -ls.wi, lambda)[1], ls.L[1]);
    }
}

TEST(DiskLight, SamplingMatchesPdfAndIrradiance) {
    TestScene ts;
    // Disk of radius 0.8 at z = 2, facing down (rotated by pi about x).
    uint32_t sh = ts.AddDisk(Translate({0.2f, 0, 2}) * Rotate(180, Vec3f(1, 0, 0)), 0.8f);
    uint32_t li = ts.AddAreaLight(sh, 1.5f);
    SceneView s = ts.View();
    LightSampleContext ctx{{0.2f, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    Vec3f axis(0, 0, 1);
    Float cosCap = 1 - 1.25f * (1 - 2 / std::sqrt(4 + Sqr(0.8f)));
    ExpectGood(CheckSampling(s, li, ctx, axis, cosCap), 0.02);
    double mean, se;
    EstimateIrradiance(s, li, ctx, 100000, &mean, &se);
    double E = Pi * 1.5 * Sqr(0.8) / (Sqr(0.8) + 4);  // on-axis disk
    EXPECT_NEAR(mean, E, 5 * se + 1e-3 * E);
    // Off-axis, tilted receiver.
    LightSampleContext ctx2{{-1, 0.5f, 0.3f}, {0, 0, 0}, {0, 0, 0}};
    Vec3f axis2 = Normalize(Vec3f(0.2f, 0, 2) - ctx2.p);
    Float cap2 = CapFor(ctx2.p, axis2, {Vec3f(1.0f, 0, 2), Vec3f(-0.6f, 0, 2), Vec3f(0.2f, 0.8f, 2), Vec3f(0.2f, -0.8f, 2)});
    ExpectGood(CheckSampling(s, li, ctx2, axis2, cap2 - 0.01f), 0.02);
}

// ---- Partial spheres, disk sectors and cylinders ----

// CapFor over the 8 corners of the object-space box [lo, hi] seen through t.
Float CapForBox(Vec3f p, Vec3f axis, const Transform &t, Vec3f lo, Vec3f hi) {
    Float cap = 1;
    for (int i = 0; i < 8; ++i)
        cap = Min(cap, CapFor(p, axis, {t.ApplyPoint(Vec3f((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z))}));
    return cap;
}

TEST(PartialSphereLight, SamplingMatchesPdfOutsideAndInside) {
    {
        // Outside: the cone of the whole sphere is sampled and directions that miss what is left
        // of it fail (counted against 1 - integral of the pdf); through the cut, the far side.
        SCOPED_TRACE("outside");
        TestScene ts;
        Vec3f center(0.3f, 0.2f, 3);
        uint32_t li = ts.AddAreaLight(ts.AddSphere(Translate(center) * Rotate(50, Vec3f(1, 0, 0)), 1, -0.4f, 0.6f, 270), 1, true);
        SceneView s = ts.View();
        LightSampleContext ctx{{0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
        Vec3f axis = Normalize(center);
        Float cosCap = 1 - 1.25f * (1 - std::sqrt(1 - 1 / LengthSquared(center)));
        SamplingCheck r = CheckSampling(s, li, ctx, axis, cosCap, false, 100000, 20, 24, nullptr, 0.02, true);
        EXPECT_TRUE(test::Chi2Accepts(r.chi2));
        EXPECT_EQ(r.pdfMismatches, 0);
        EXPECT_GT(r.chi2.failed, 5000);   // the cuts matter
        EXPECT_LT(r.chi2.pdfIntegral, 0.95);
    }
    {
        SCOPED_TRACE("inside");
        TestScene ts;
        uint32_t li = ts.AddAreaLight(ts.AddSphere(Translate({0.2f, -0.3f, 0.1f}) * Rotate(30, Vec3f(0, 1, 1)), 1, -0.7f, 0.8f, 300), 1, true);
        SceneView s = ts.View();
        LightSampleContext ctx{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        SamplingCheck r = CheckSampling(s, li, ctx, Vec3f(0, 0, 1), -1);
        ExpectGood(r, 0.02);
        EXPECT_EQ(r.chi2.failed, 0);
    }
}

// pbrt-v4's own partial-sphere sampling (the whole sphere's cone, cut-away points returned as
// they are) does not have the density PDF_Li gives: the check sees it.
TEST(PartialSphereLight, ChiSquareRejectsSamplingTheWholeSphere) {
    TestScene ts;
    Vec3f center(0.3f, 0.2f, 3);
    Transform t = Translate(center) * Rotate(50, Vec3f(1, 0, 0));
    uint32_t partial = ts.AddAreaLight(ts.AddSphere(t, 1, -0.4f, 0.6f, 270), 1, true);
    uint32_t whole = ts.AddAreaLight(ts.AddSphere(t, 1), 1, true);
    SceneView s = ts.View();
    LightSampleContext ctx{{0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    Vec3f axis = Normalize(center);
    Float cosCap = 1 - 1.25f * (1 - std::sqrt(1 - 1 / LengthSquared(center)));
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> U(0, 1);
    SampledWavelengths lambda = TestLambda();
    auto sample = [&](test::Chi2Point *p) {
        LightLiSample ls;
        if (!SampleLi(s.lights[whole], s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls)) return false;
        *p = {ls.wi.x, ls.wi.y, ls.wi.z};
        return true;
    };
    auto pdf = [&](const test::Chi2Point &p) {
        return double(DirectionPDF(s, partial, ctx, Vec3f(Float(p.x), Float(p.y), Float(p.z)), false));
    };
    test::Chi2Result r = test::Chi2SampleTest(test::CapDomain({axis.x, axis.y, axis.z}, cosCap, 20, 24), sample, pdf);
    EXPECT_TRUE(test::Chi2Rejects(r));
}

TEST(PartialDiskLight, SectorSamplingMatchesPdf) {
    TestScene ts;
    Transform t = Translate({0.2f, 0, 2}) * Rotate(180, Vec3f(1, 0, 0)) * Rotate(20, Vec3f(0, 0, 1));
    uint32_t li = ts.AddAreaLight(ts.AddDisk(t, 0.8f, 0.1f, 0.3f, 120), 1.5f);
    SceneView s = ts.View();
    LightSampleContext ctx{{0.2f, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    Vec3f axis(0, 0, 1);
    Float cosCap = 1 - 1.25f * (1 - 1.9f / std::sqrt(Sqr(1.9f) + Sqr(0.8f)));
    SamplingCheck r = CheckSampling(s, li, ctx, axis, cosCap);
    ExpectGood(r, 0.02);
    EXPECT_EQ(r.chi2.failed, 0);
}

TEST(CylinderLight, SamplingMatchesPdfOutsideAndInside) {
    // Axis along -y (object z), centered at (0, 0, 3); the reference point at mid-height sees the
    // outside of the tube only, whose back half (facing away) refuses its samples. The partial
    // tube's cut (object phi in [230, 360) degrees, turned by 155 about the axis) faces away
    // from it, where only the refused back half is missing.
    Transform t = Translate({0, 0, 3}) * Rotate(90, Vec3f(1, 0, 0));
    for (Float phimax : {360.f, 230.f}) {
        SCOPED_TRACE(phimax);
        TestScene ts;
        if (phimax < 360) t = t * Rotate(155, Vec3f(0, 0, 1));
        uint32_t li = ts.AddAreaLight(ts.AddCylinder(t, 0.5f, -0.8f, 0.8f, phimax), 2);
        SceneView s = ts.View();
        LightSampleContext ctx{{0.1f, 0.05f, 0}, {0, 0, 1}, {0, 0, 1}};
        Vec3f axis = Normalize(Vec3f(0, 0, 3) - ctx.p);
        Float cosCap = CapForBox(ctx.p, axis, t, {-0.5f, -0.5f, -0.8f}, {0.5f, 0.5f, 0.8f});
        SamplingCheck r = CheckSampling(s, li, ctx, axis, cosCap, false, 100000, 20, 24, nullptr, 0.02, true);
        EXPECT_TRUE(test::Chi2Accepts(r.chi2));
        EXPECT_EQ(r.pdfMismatches, 0);
        EXPECT_GT(r.chi2.failed, 10000);
    }
    {
        // Inside, normals reversed (facing the axis): every point is seen once.
        SCOPED_TRACE("inside");
        TestScene ts;
        uint32_t li = ts.AddAreaLight(ts.AddCylinder(t, 0.5f, -0.8f, 0.8f, 300, true), 2);
        SceneView s = ts.View();
        LightSampleContext ctx{{0.1f, 0.2f, 3.05f}, {0, 0, 0}, {0, 0, 0}};
        SamplingCheck r = CheckSampling(s, li, ctx, Vec3f(1, 0, 0), -1);
        ExpectGood(r, 0.02);
        EXPECT_EQ(r.chi2.failed, 0);
    }
}

// At the center of a tube of radius r and half-length h, facing along the axis, the inner wall
// of radiance L gives E = pi L h^2 / (h^2 + r^2) (the wall spans polar angles atan(r / h) to pi/2).
TEST(CylinderLight, IrradianceOnTheAxisMatchesAnalytic) {
    for (auto [r, h] : {std::pair<Float, Float>{0.5f, 1}, {1, 0.3f}}) {
        TestScene ts;
        uint32_t li = ts.AddAreaLight(ts.AddCylinder(Translate({0.3f, 0, 0}), r, -h, h, 360, true), 3);
        SceneView s = ts.View();
        LightSampleContext ctx{{0.3f, 0, 0}, {0, 0, 1}, {0, 0, 1}};
        double mean, se;
        EstimateIrradiance(s, li, ctx, 200000, &mean, &se);
        double E = Pi * 3.0 * Sqr(h) / (Sqr(h) + Sqr(r));
        EXPECT_NEAR(mean, E, 5 * se + 1e-3 * E) << "r " << r << " h " << h;
    }
}

// The flux leaving a one-sided emitter (outward normals) through a sphere of radius R around
// it, the integral of the inward irradiance over that sphere, is pi L A: estimated with one
// light sample at each of N uniform points of the sphere. Outward rays from these shapes' outer
// sides never meet them again, so no visibility test is needed. LightPhi is pi L A too.
TEST(QuadricLights, FluxIsPiLTimesArea) {
    struct Case { const char *what; Float area; };
    const Float L = 1.5f, R = 4;
    for (int k = 0; k < 4; ++k) {
        TestScene ts;
        Transform t = Translate({0.2f, -0.1f, 0.3f}) * Rotate(35, Vec3f(1, 1, 0));
        uint32_t sh;
        Float area;
        const char *what;
        if (k == 0) { sh = ts.AddCylinder(t, 0.6f, -0.5f, 0.9f); area = 1.4f * 0.6f * 2 * Pi; what = "cylinder"; }
        else if (k == 1) { sh = ts.AddCylinder(t, 0.6f, -0.5f, 0.9f, 250); area = 1.4f * 0.6f * Radians(250); what = "cylinder, phimax 250"; }
        else if (k == 2) { sh = ts.AddSphere(t, 0.8f, -0.3f, 0.7f, 200); area = Radians(200) * 0.8f * 1.0f; what = "partial sphere"; }
        else { sh = ts.AddDisk(t, 0.9f, 0.2f, 0.25f, 150); area = Radians(150) / 2 * (Sqr(0.9f) - Sqr(0.25f)); what = "disk sector"; }
        SCOPED_TRACE(what);
        uint32_t li = ts.AddAreaLight(sh, L);
        SceneView s = ts.View();
        SampledWavelengths lambda = TestLambda();
        EXPECT_NEAR(LightPhi(s.lights[li], s, lambda)[0], Pi * L * area, 1e-4f * area);
        Vec3f center = t.ApplyPoint(Vec3f(0, 0, 0));
        std::mt19937 rng(31 + k);
        std::uniform_real_distribution<float> U(0, 1);
        const int N = 400000;
        double sum = 0, sum2 = 0;
        for (int i = 0; i < N; ++i) {
            Vec3f dir = SampleUniformSphere(Vec2f(U(rng), U(rng)));
            LightSampleContext ctx{center + dir * R, -dir, -dir};
            LightLiSample ls;
            double v = 0;
            if (SampleLi(s.lights[li], s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls))
                v = ls.L[0] * std::max(0.f, Dot(ls.wi, ctx.n)) / ls.pdf;
            sum += v;
            sum2 += v * v;
        }
        double mean = sum / N, se = std::sqrt(std::max(0.0, sum2 / N - mean * mean) / N);
        double sphere = 4 * Pi * Sqr(R), flux = Pi * L * area;
        EXPECT_NEAR(mean * sphere, flux, 5 * se * sphere + 2e-3 * flux) << "se " << se * sphere;
    }
}

// ---- Infinite lights ----

TEST(UniformInfiniteLight, SamplingLeAndIncompletePdf) {
    TestScene ts;
    Light l;
    l.kind = LightKind::UniformInfinite;
    l.spectrum = Spectrum::Const(0.25f);
    l.scale = 2;
    l.sceneRadius = 5;
    ts.lights.push_back(l);
    SceneView s = ts.View();
    LightSampleContext ctx{{1, 2, 3}, {0, 0, 1}, {0, 0, 1}};
    ExpectGood(CheckSampling(s, 0, ctx, Vec3f(0, 0, 1), -1, false, 50000, 10, 12));
    SampledWavelengths lambda = TestLambda();
    EXPECT_FLOAT_EQ(InfiniteLightLe(s.lights[0], s, Vec3f(0, 1, 0), lambda)[2], 0.5f);
    LightLiSample ls;
    ASSERT_TRUE(SampleLi(s.lights[0], s, ctx, Vec2f(0.2f, 0.7f), lambda, &ls));
    EXPECT_FLOAT_EQ(ls.L[0], 0.5f);
    EXPECT_EQ(ls.distance, Infinity);
    EXPECT_NEAR(Distance(ls.pLight, ctx.p), 10, 1e-4f);
    // pbrt-v4's allowIncompletePDF: no light samples, pdf 0 (BSDF sampling covers it).
    EXPECT_FALSE(SampleLi(s.lights[0], s, ctx, Vec2f(0.2f, 0.7f), lambda, &ls, true));
    EXPECT_EQ(PDF_Li(s.lights[0], s, ctx, Vec3f(0, 0, 1), {}, {}, true), 0);
}

std::vector<float> SyntheticEnvMap(int res, int channels) {
    std::vector<float> t(size_t(res) * res * channels);
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            float v = 0.05f + 0.1f * ((x * 7 + y * 3) % 5) + (x == 2 && y == 5 ? 30.f : 0.f) + (y == 0 ? 2.f : 0.f);
            for (int c = 0; c < channels; ++c) t[(size_t(y) * res + x) * channels + c] = v;
        }
    return t;
}

TEST(ImageInfiniteLight, SamplingMatchesPdfBothDistributions) {
    TestScene ts;
    uint32_t li = ts.AddImageLight(SyntheticEnvMap(8, 3), 8, 3, Rotate(Degrees(0.9f), Vec3f(0.3f, 1, 0.2f)));
    SceneView s = ts.View();
    LightSampleContext ctx{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (bool incomplete : {false, true}) {
        SCOPED_TRACE(incomplete);
        SamplingCheck r = CheckSampling(s, li, ctx, Vec3f(0, 0, 1), -1, incomplete, 100000, 24, 32);
        ExpectGood(r, 0.005, 10);
        EXPECT_EQ(r.chi2.failed, 0);
    }
}

// The same checks reject pdfs that are not the sampled ones (each a plausible bug): a sphere's
// cone pdf for a 5% larger sphere, a disk's area-to-solid-angle conversion with the cosine
// squared, an image light's pdf without its rotation, and the huge triangle's barycentrics
// taken as uniform.
TEST(LightSampling, ChiSquareRejectsWrongPdfs) {
    {
        TestScene ts;
        Vec3f center(0.3f, 0.2f, 3);
        uint32_t li = ts.AddAreaLight(ts.AddSphere(Translate(center), 1.f), 1.f);
        SceneView s = ts.View();
        LightSampleContext ctx{{0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
        Vec3f axis = Normalize(center);
        Float cosMax = std::sqrt(1 - Sqr(1.05f) / LengthSquared(center));  // the larger sphere's cone
        Float cosCap = 1 - 1.25f * (1 - cosMax);
        SamplingCheck r = CheckSampling(s, li, ctx, axis, cosCap, false, 100000, 20, 24, [&](Vec3f w) {
            return Dot(w, axis) >= cosMax ? Float(1 / (2 * Pi * (1 - cosMax))) : Float(0);
        });
        EXPECT_TRUE(test::Chi2Rejects(r.chi2)) << "sphere";
    }
    {
        TestScene ts;
        uint32_t li = ts.AddAreaLight(ts.AddDisk(Translate({0.2f, 0, 2}) * Rotate(180, Vec3f(1, 0, 0)), 0.8f), 1.5f);
        SceneView s = ts.View();
        LightSampleContext ctx{{0.2f, 0, 0}, {0, 0, 1}, {0, 0, 1}};
        Float cosCap = 1 - 1.25f * (1 - 2 / std::sqrt(4 + Sqr(0.8f)));
        SamplingCheck r = CheckSampling(s, li, ctx, Vec3f(0, 0, 1), cosCap, false, 100000, 20, 24, [&](Vec3f w) {
            return DirectionPDF(s, li, ctx, w, false) / std::abs(w.z);  // d^2 / (A cos^2)
        }, 1.0);
        EXPECT_TRUE(test::Chi2Rejects(r.chi2)) << "disk";
    }
    {
        TestScene ts;
        uint32_t li = ts.AddImageLight(SyntheticEnvMap(8, 3), 8, 3, Rotate(Degrees(0.9f), Vec3f(0.3f, 1, 0.2f)));
        uint32_t unrotated = ts.AddImageLight(SyntheticEnvMap(8, 3), 8, 3, Transform());
        SceneView s = ts.View();
        LightSampleContext ctx{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        SamplingCheck r = CheckSampling(s, li, ctx, Vec3f(0, 0, 1), -1, false, 100000, 24, 32,
                                        [&](Vec3f w) { return DirectionPDF(s, unrotated, ctx, w, false); });
        EXPECT_TRUE(test::Chi2Rejects(r.chi2)) << "image light";
    }
    {
        TestScene ts;
        uint32_t li = ts.AddAreaLight(ts.AddTriangle({-20, -20, 0.01f}, {40, -20, 0.01f}, {-20, 40, 0.01f}, true), 1.f);
        SceneView s = ts.View();
        LightSampleContext ctx{{0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
        std::mt19937 rng(21);
        std::uniform_real_distribution<float> U(0, 1);
        SampledWavelengths lambda = TestLambda();
        auto sample = [&](test::Chi2Point *q) {
            LightLiSample ls;
            if (!SampleLi(s.lights[li], s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls)) return false;
            double b1 = (ls.pLight.x + 20) / 60, b2 = (ls.pLight.y + 20) / 60;
            *q = {b1, b2 / std::max(1e-9, 1 - b1), 0};
            return true;
        };
        test::Chi2Result r = test::Chi2SampleTest(test::RectDomain(0, 1, 0, 1, 10, 5), sample,
                                                  [](const test::Chi2Point &) { return 1.0; });
        EXPECT_TRUE(test::Chi2Rejects(r)) << "huge triangle";
    }
}

TEST(ImageInfiniteLight, LeMatchesTexelsAndSample) {
    TestScene ts;
    int res = 8;
    std::vector<float> tex = SyntheticEnvMap(res, 3);
    Transform rot = Rotate(Degrees(0.4f), Vec3f(1, 0, 0));
    uint32_t li = ts.AddImageLight(tex, res, 3, rot);
    ts.lights[li].scale = 1.5f;
    SceneView s = ts.View();
    SampledWavelengths lambda = TestLambda();
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> U(0, 1);
    LightSampleContext ctx{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int i = 0; i < 200; ++i) {
        LightLiSample ls;
        ASSERT_TRUE(SampleLi(s.lights[li], s, ctx, Vec2f(U(rng), U(rng)), lambda, &ls));
        // Le along the sampled direction equals the sample's L, and the gray texel value times scale
        // (the illuminant table is 1).
        SampledSpectrum Le = InfiniteLightLe(s.lights[li], s, ls.wi, lambda);
        EXPECT_NEAR(Le[0], ls.L[0], 1e-5f * ls.L[0]);
        Vec2f uv = EqualAreaSphereToSquare(Normalize(rot.Inverted().ApplyVector(ls.wi)));
        int x = Min(int(uv.x * res), res - 1), y = Min(int(uv.y * res), res - 1);
        EXPECT_NEAR(ls.L[3], 1.5f * tex[(size_t(y) * res + x) * 3], 1e-4f);
    }
}

// ---- Delta lights ----

TEST(PointSpotDistant, RadianceAndFalloff) {
    TestScene ts;
    Light p;
    p.kind = LightKind::Point;
    p.spectrum = Spectrum::Const(2);
    p.scale = 3;
    p.position = Vec3f(0, 0, 2);
    p.renderFromLight = Translate(p.position);
    ts.lights.push_back(p);
    // Spot at the origin pointing along +x: light +z maps to render +x.
    Light sp;
    sp.kind = LightKind::Spot;
    sp.spectrum = Spectrum::Const(1);
    sp.position = Vec3f(0, 0, 0);
    sp.renderFromLight = Rotate(90, Vec3f(0, 1, 0));
    sp.cosFalloffStart = std::cos(Radians(20));
    sp.cosFalloffEnd = std::cos(Radians(30));
    ts.lights.push_back(sp);
    Light d;
    d.kind = LightKind::Distant;
    d.spectrum = Spectrum::Const(0.5f);
    d.direction = Vec3f(0, 3, 4);
    d.sceneRadius = 7;
    ts.lights.push_back(d);
    SceneView s = ts.View();
    SampledWavelengths lambda = TestLambda();
    LightLiSample ls;
    LightSampleContext ctx{{0, 0, -2}, {0, 0, 1}, {0, 0, 1}};
    ASSERT_TRUE(SampleLi(s.lights[0], s, ctx, Vec2f(0.5f, 0.5f), lambda, &ls));
    EXPECT_FLOAT_EQ(ls.L[0], 6.f / 16);
    EXPECT_TRUE(ls.isDelta);
    EXPECT_EQ(ls.pdf, 1);
    EXPECT_NEAR(ls.distance, 4, 1e-6f);
    EXPECT_NEAR(ls.wi.z, 1, 1e-6f);
    EXPECT_EQ(PDF_Li(s.lights[0], s, ctx, ls.wi, ls.pLight, ls.nLight), 0);
    EXPECT_TRUE(IsDeltaLight(s.lights[0]) && IsDeltaLight(s.lights[1]) && IsDeltaLight(s.lights[2]));

    // Spot: full inside 20 degrees, smoothstep between 20 and 30, zero beyond.
    auto spotL = [&](Float deg) {
        Float r = 2;
        LightSampleContext c{{r * std::cos(Radians(deg)), r * std::sin(Radians(deg)), 0}, {}, {}};
        LightLiSample l2;
        bool ok = SampleLi(s.lights[1], s, c, Vec2f(0.5f, 0.5f), lambda, &l2);
        return ok ? l2.L[0] * r * r : 0.f;
    };
    EXPECT_NEAR(spotL(0), 1, 1e-5f);
    EXPECT_NEAR(spotL(15), 1, 1e-5f);
    EXPECT_NEAR(spotL(25), 0.570038f, 1e-4f);  // t = 0.546825, t^2 (3 - 2t)
    EXPECT_NEAR(spotL(29.9f), 0.0f, 1e-3f);
    EXPECT_EQ(spotL(35), 0.f);
    EXPECT_EQ(spotL(180), 0.f);
    EXPECT_NEAR(SmoothStep(0.5f, 0, 1), 0.5f, 1e-6f);

    ASSERT_TRUE(SampleLi(s.lights[2], s, ctx, Vec2f(0.1f, 0.9f), lambda, &ls));
    EXPECT_NEAR(ls.wi.y, 0.6f, 1e-6f);
    EXPECT_NEAR(ls.wi.z, 0.8f, 1e-6f);
    EXPECT_FLOAT_EQ(ls.L[1], 0.5f);
    EXPECT_EQ(ls.distance, Infinity);
    EXPECT_NEAR(Distance(ls.pLight, ctx.p), 14, 1e-4f);
}

// ---- Light selection ----

TEST(LightSampler, PmfProportionalToPower) {
    TestScene ts;
    Light p;
    p.kind = LightKind::Point;
    p.spectrum = Spectrum::Const(2);
    ts.lights.push_back(p);
    Light sp;
    sp.kind = LightKind::Spot;
    sp.spectrum = Spectrum::Const(3);
    sp.cosFalloffStart = 0.9f;
    sp.cosFalloffEnd = 0.7f;
    ts.lights.push_back(sp);
    uint32_t tri = ts.AddTriangle({0, 0, 0}, {2, 0, 0}, {0, 1, 0});  // area 1
    ts.AddAreaLight(tri, 1.5f, true);
    uint32_t disk = ts.AddDisk(Transform(), 0.5f);
    ts.AddAreaLight(disk, 4.f);
    Light u;
    u.kind = LightKind::UniformInfinite;
    u.spectrum = Spectrum::Const(0.01f);
    u.sceneRadius = 2;
    ts.lights.push_back(u);
    Light zero;
    zero.kind = LightKind::Point;
    zero.spectrum = Spectrum::Const(0);
    ts.lights.push_back(zero);
    uint32_t img = ts.AddImageLight(std::vector<float>(16, 0.02f), 4, 1, Transform());
    SceneView s0 = ts.View();
    ts.lightCdf = BuildLightCdf(s0);
    SceneView s = ts.View();
    // Constant spectra: every light's power carries the same wavelength factor, so ratios are
    // the analytic Phi ratios.
    const double phi[] = {4 * Pi * 2,
                          3 * 2 * Pi * ((1 - 0.9) + (0.9 - 0.7) / 2),
                          Pi * 2 * 1 * 1.5,
                          Pi * (Pi * 0.25) * 4,
                          4 * Pi * Pi * 4 * 0.01,
                          0,
                          4 * Pi * Pi * 100 * 0.02};
    ASSERT_EQ(img, 6u);
    double total = 0;
    for (double v : phi) total += v;
    for (uint32_t i = 0; i < 7; ++i) EXPECT_NEAR(LightPMF(s, i), phi[i] / total, 1e-5) << i;
    EXPECT_GT(LightPower(s.lights[0], s), 0);
    const int N = 200000;
    std::vector<double> obs(7, 0), expd(7);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> U(0, 1);
    for (int i = 0; i < N; ++i) {
        Float pmf;
        uint32_t k = SampleLight(s, U(rng), &pmf);
        ASSERT_LT(k, 7u);
        EXPECT_EQ(pmf, LightPMF(s, k));
        obs[k] += 1;
    }
    for (int i = 0; i < 7; ++i) expd[i] = N * phi[i] / total;
    EXPECT_TRUE(test::Chi2Accepts(test::Chi2Counts(obs, expd)));
}

TEST(LightSampler, NoLightsAndAllZeroPower) {
    TestScene ts;
    SceneView s = ts.View();
    Float pmf = 1;
    EXPECT_EQ(SampleLight(s, 0.5f, &pmf), NoIndex);
    EXPECT_EQ(pmf, 0);
    Light z;
    z.kind = LightKind::Point;
    z.spectrum = Spectrum::Const(0);
    ts.lights = {z, z, z, z};
    ts.lightCdf = BuildLightCdf(ts.View());
    s = ts.View();
    for (uint32_t i = 0; i < 4; ++i) EXPECT_NEAR(LightPMF(s, i), 0.25f, 1e-6f);
    EXPECT_EQ(SampleLight(s, 0.6f, &pmf), 2u);
}

// ---- Equal-area mapping and RGB illuminants ----

TEST(EqualArea, RoundTripAndUniformity) {
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> U(0, 1);
    int i = 0;
    auto sample = [&](test::Chi2Point *d) {
        Vec2f p(U(rng), U(rng));
        Vec3f w = EqualAreaSquareToSphere(p);
        EXPECT_NEAR(Length(w), 1, 1e-5f);
        Vec2f q = EqualAreaSphereToSquare(w);
        if (i++ < 2000) {
            EXPECT_NEAR(p.x, q.x, 2e-4f);
            EXPECT_NEAR(p.y, q.y, 2e-4f);
        }
        *d = {w.x, w.y, w.z};
        return true;
    };
    // Uniform over the sphere: cells of equal solid angle (the whole sphere as a cap).
    test::Chi2Result r = test::Chi2SampleTest(test::CapDomain({0, 0, 1}, -1, 10, 16), sample,
                                              [](const test::Chi2Point &) { return 1 / (4 * Pi); });
    EXPECT_TRUE(test::Chi2Accepts(r));
    // Octahedral wrap at the square's edge stays in range.
    int x = 8, y = 3;
    WrapOctahedral(&x, &y, 8, 8);
    EXPECT_EQ(x, 7);
    EXPECT_EQ(y, 4);
}

TEST(RGBIlluminant, GrayAndTableLookup) {
    TestScene ts;
    // Synthetic 3^3 table whose coefficients are constant (0, 0, 0.8) everywhere.
    ts.rgbRes = 3;
    ts.zNodes = {0, 0.5f, 1};
    ts.rgbCoeffs.assign(3 * 27 * 3, 0.f);
    for (size_t i = 2; i < ts.rgbCoeffs.size(); i += 3) ts.rgbCoeffs[i] = 0.8f;
    SceneView s = ts.View();
    SampledWavelengths lambda = TestLambda();
    Float gray[3] = {0.3f, 0.3f, 0.3f};
    SampledSpectrum g = SampleSpectrum(RGBIlluminantSpectrum(s, gray), lambda, s.spectra);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(g[i], 0.3f, 1e-6f);
    Float black[3] = {0, -1, 0};
    EXPECT_TRUE(SampleSpectrum(RGBIlluminantSpectrum(s, black), lambda, s.spectra).IsBlack());
    Float rgb[3] = {0.2f, 0.7f, 0.4f};
    Spectrum sp = RGBIlluminantSpectrum(s, rgb);
    EXPECT_NEAR(sp.scale, 1.4f, 1e-6f);
    EXPECT_NEAR(sp.c[2], 0.8f, 1e-6f);
    Float expected = 1.4f * (0.5f + 0.8f / (2 * std::sqrt(1 + 0.64f)));
    EXPECT_NEAR(SampleSpectrum(sp, lambda, s.spectra)[0], expected, 1e-5f);
}

TEST(RGBIlluminant, MatchesRegistryWithTheSRGBTable) {
    SpectrumRegistry reg;
    RGBToSpectrumTableData tab = SRGBToSpectrumTable();
    SceneView s;
    s.rgbToSpecCoeffs = {tab.coeffs, 3 * 3 * tab.res * tab.res * tab.res};
    s.rgbToSpecZNodes = {tab.zNodes, tab.res};
    s.rgbToSpecRes = tab.res;
    s.spectra = reg.Tables();
    s.illuminantTables[0] = TableD65;
    SampledWavelengths lambda = TestLambda();
    const Float rgbs[][3] = {{0.8f, 0.3f, 0.1f}, {0.05f, 0.2f, 1.7f}, {2, 2, 2}, {0.3f, -0.1f, 0.5f}};
    for (const auto &rgb : rgbs) {
        SampledSpectrum a = SampleSpectrum(RGBIlluminantSpectrum(s, rgb), lambda, s.spectra);
        Spectrum ref = reg.FromRGB(RGB{Max(rgb[0], 0.f), Max(rgb[1], 0.f), Max(rgb[2], 0.f)}, SpectrumType::Illuminant);
        SampledSpectrum b = SampleSpectrum(ref, lambda, s.spectra);
        for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(a[i], b[i], 1e-4f * (1 + b[i])) << rgb[0];
    }
}

}  // namespace
}  // namespace lu
