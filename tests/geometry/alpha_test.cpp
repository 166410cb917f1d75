// Shape alpha cut-outs (geometry/alpha.h, pbrt-v4's GeometricPrimitive alpha test) on every
// tracer: Embree (filter functions on triangles, user-geometry callbacks on spheres and disks,
// instances) and Lucerna's BVH (what the CUDA backend runs), by rays and by renders.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "geometry/traced_scene.h"
#include "gpu/render_compare.h"
#include "integrators/render_helpers.h"

namespace lu::test {
namespace {

std::unique_ptr<Traced> Trace(const std::string &name, const std::string &text) { return TraceSceneText(name, text); }

const char *kHead = "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
                    "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\nWorldBegin\n"
                    "LightSource \"point\" \"point3 from\" [ 0 0 -4 ] \"rgb I\" [ 1 1 1 ]\n";
// Shape 0: a wall at z = 2 facing the camera.
const char *kWall = "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] "
                    "\"point3 P\" [ -4 -4 2  -4 4 2  4 4 2  4 -4 2 ]\n";
std::string Quad(Float z, const std::string &alpha) {
    return "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -1 -1 " + std::to_string(z) +
           "  1 -1 " + std::to_string(z) + "  1 1 " + std::to_string(z) + "  -1 1 " + std::to_string(z) +
           " ] \"point2 uv\" [ 0 0  1 0  1 1  0 1 ] " + alpha + "\n";
}
// A quad, a sphere and a disk, all with the given alpha parameter, between the camera and the wall.
std::string Cutouts(const std::string &alpha) {
    return Quad(0, alpha) + "AttributeBegin\nTranslate 0 0 -1\nShape \"sphere\" \"float radius\" [ 0.5 ] " + alpha +
           "\nAttributeEnd\nAttributeBegin\nTranslate 0 0 -2.5\nShape \"disk\" \"float radius\" [ 0.8 ] " + alpha +
           "\nAttributeEnd\n";
}
// Rays from the camera side towards +z through the cut-outs (x, y in [-0.7, 0.7]).
Ray Through(Pcg32 &rng) {
    Ray r;
    r.o = Vec3f(1.4f * rng.Uniform() - 0.7f, 1.4f * rng.Uniform() - 0.7f, -4);
    r.d = Normalize(Vec3f(0.05f * (rng.Uniform() - 0.5f), 0.05f * (rng.Uniform() - 0.5f), 1));
    return r;
}

// (1) Alpha 0: camera and shadow rays pass the quad, the sphere and the disk (top level and in
// instanced prototypes) and hit the wall; with alpha 1 (control) they stop at the cut-outs.
TEST(Alpha, ZeroAlphaIsInvisibleToCameraAndShadowRays) {
    std::string instanced = "ObjectBegin \"cut\"\n" + Cutouts("\"float alpha\" [ 0 ]") + "ObjectEnd\n" +
                            "AttributeBegin\nObjectInstance \"cut\"\nAttributeEnd\n"
                            "AttributeBegin\nTranslate 0 0 -0.2\nObjectInstance \"cut\"\nAttributeEnd\n";
    struct Case {
        const char *name;
        std::string body;
        bool visible;
    } cases[] = {{"alpha0", Cutouts("\"float alpha\" [ 0 ]"), false},
                 {"alpha0_texture", "Texture \"zero\" \"float\" \"constant\" \"float value\" [ 0 ]\n" +
                                        Cutouts("\"texture alpha\" \"zero\""), false},
                 {"alpha0_instanced", instanced, false},
                 {"alpha1", Cutouts("\"float alpha\" [ 1 ]"), true}};
    for (const Case &c : cases) {
        auto t = Trace(std::string("alpha_zero_") + c.name, std::string(kHead) + kWall + c.body);
        if (std::string(c.name) == "alpha0_instanced") {
            ASSERT_GT(t->view.instances.size, 0u);
        }
        EXPECT_EQ(t->view.alphaShapes, c.visible ? 0u : 3u) << c.name;
        for (bool useBVH : {false, true}) {
            SCOPED_TRACE(std::string(c.name) + (useBVH ? " bvh" : " embree"));
            Pcg32 rng(7);
            int wall = 0, blocked = 0, n = 2000;
            for (int i = 0; i < n; ++i) {
                Ray r = Through(rng);
                HitRecord h;
                ASSERT_TRUE(t->Intersect(useBVH, r, &h));
                wall += h.shape == 0;
                Ray shadow = r;
                shadow.tMax = 5.5f;   // stops before the wall (t ~ 6)
                blocked += t->Occluded(useBVH, shadow);
            }
            if (c.visible) {
                EXPECT_EQ(wall, 0);
                EXPECT_EQ(blocked, n);
            } else {
                EXPECT_EQ(wall, n);
                EXPECT_EQ(blocked, 0);
            }
        }
    }
}

// (2) A constant alpha of 0.5 in front of the wall: about half the rays pass (binomial, 5 sigma);
// a ray decides the same way in closest-hit and shadow queries, and on both tracers (the
// decision hashes the ray: pbrt-v4's HashFloat(o, d)).
TEST(Alpha, HalfAlphaTransmitsHalf) {
    auto t = Trace("alpha_half", std::string(kHead) + kWall + Quad(0, "\"float alpha\" [ 0.5 ]"));
    const int n = 20000;
    int passed[2] = {0, 0}, disagree = 0, inconsistent = 0;
    Pcg32 rng(11);
    for (int i = 0; i < n; ++i) {
        Ray r = Through(rng);
        bool hitQuad[2];
        for (int b = 0; b < 2; ++b) {
            HitRecord h;
            ASSERT_TRUE(t->Intersect(b == 1, r, &h));
            hitQuad[b] = h.shape == 1;
            passed[b] += !hitQuad[b];
            Ray shadow = r;
            shadow.tMax = 5.5f;
            inconsistent += t->Occluded(b == 1, shadow) != hitQuad[b];
        }
        disagree += hitQuad[0] != hitQuad[1];
    }
    double tol = 5 * std::sqrt(0.25 / n);
    std::printf("[ alpha    ] passed: embree %.4f, bvh %.4f (n %d)\n", double(passed[0]) / n, double(passed[1]) / n, n);
    for (int b = 0; b < 2; ++b) EXPECT_NEAR(double(passed[b]) / n, 0.5, tol) << (b ? "bvh" : "embree");
    EXPECT_EQ(disagree, 0);
    EXPECT_EQ(inconsistent, 0);
    // Two such quads: the surfaces along one ray share u (pbrt-v4), so half the rays still pass.
    auto two = Trace("alpha_half_two", std::string(kHead) + kWall + Quad(0, "\"float alpha\" [ 0.5 ]") +
                                           Quad(0.5f, "\"float alpha\" [ 0.5 ]"));
    for (bool useBVH : {false, true}) {
        int wall = 0;
        Pcg32 r2(13);
        for (int i = 0; i < n; ++i) {
            HitRecord h;
            ASSERT_TRUE(two->Intersect(useBVH, Through(r2), &h));
            wall += h.shape == 0;
        }
        EXPECT_NEAR(double(wall) / n, 0.5, tol) << (useBVH ? "bvh" : "embree");
    }
}

// (2) Rendered: a black quad of alpha 0.5 in front of an emitter lets half its radiance through;
// an emitter of alpha 0.5 seen directly gives a quarter (pbrt-v4: the ray keeps the hit with
// probability 0.5, and DiffuseAreaLight::L masks the point by a second test, HashFloat(p)).
TEST(Alpha, HalfAlphaRendersHalfTheEmitter) {
    auto emitter = [](const std::string &alpha) {
        return "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n"
               "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -4 -4 2  -4 4 2  4 4 2  4 -4 2 ] " +
               alpha + "\nAttributeEnd\n";
    };
    const char *head = "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 20 ]\n"
                       "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n"
                       "Sampler \"independent\"\nWorldBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n";
    auto mean = [&](const std::string &name, const std::string &body) {
        auto scene = LoadSceneText(name, head + body);
        Image img = RenderScene(*scene, 64, 1, 3).image;
        double s = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) s += img.At(x, y, 1);
        return s / (img.width * img.height);
    };
    double open = mean("alpha_emit_open", emitter(""));
    ASSERT_GT(open, 0.5);
    // 32 x 32 x 64 camera rays: the binomial standard error of the fraction is 0.002.
    double behind = mean("alpha_emit_behind", emitter("") + Quad(0, "\"float alpha\" [ 0.5 ]")) / open;
    double masked = mean("alpha_emit_masked", emitter("\"float alpha\" [ 0.5 ]")) / open;
    std::printf("[ alpha    ] behind a 0.5 quad %.4f, emitter of alpha 0.5 %.4f (of the open emitter)\n", behind, masked);
    EXPECT_NEAR(behind, 0.5, 0.012);
    EXPECT_NEAR(masked, 0.25, 0.012);
}

// (3) A checkerboard cut-out (uv, 4 x 4 checks): a ray through the quad's (u, v) hits it exactly on
// the odd checks, on both tracers, for the mesh, its instanced copy and a sphere (pbrt-v4's uv).
TEST(Alpha, CheckerboardCoverage) {
    const char *tex = "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" [ 4 ] \"float vscale\" [ 4 ] "
                      "\"float tex1\" [ 0 ] \"float tex2\" [ 1 ]\n";
    std::string quad = Quad(0, "\"texture alpha\" \"checks\"");
    std::string instanced = std::string("ObjectBegin \"q\"\n") + quad + "ObjectEnd\nAttributeBegin\nObjectInstance \"q\"\n"
                            "AttributeEnd\nAttributeBegin\nTranslate 0 0 30\nObjectInstance \"q\"\nAttributeEnd\n";
    for (const std::string &body : {quad, instanced}) {
        auto t = Trace("alpha_checks", std::string(kHead) + kWall + tex + body);
        for (bool useBVH : {false, true}) {
            SCOPED_TRACE(useBVH ? "bvh" : "embree");
            int n = 0, wrong = 0, hits = 0;
            for (int j = 0; j < 64; ++j)
                for (int i = 0; i < 64; ++i) {
                    Float u = (i + 0.5f) / 64, v = (j + 0.5f) / 64;
                    Ray r;
                    r.o = Vec3f(2 * u - 1, 2 * v - 1, -4);
                    r.d = Vec3f(0, 0, 1);
                    HitRecord h;
                    ASSERT_TRUE(t->Intersect(useBVH, r, &h));
                    bool odd = (int(std::floor(4 * u)) + int(std::floor(4 * v))) % 2 == 1;
                    ++n;
                    hits += h.shape != 0;
                    wrong += (h.shape != 0) != odd;
                    Ray shadow = r;
                    shadow.tMax = 5.5f;
                    wrong += t->Occluded(useBVH, shadow) != odd;
                }
            EXPECT_EQ(wrong, 0);
            EXPECT_EQ(hits, n / 2);
        }
    }
    // A sphere crossed along +z: pbrt-v4's u = phi / 2 pi, v = 1 - theta / pi; 4 checks in u and 2
    // in v, so at one phi the near side (v = 1/6) and the far side (v = 5/6) have opposite parity:
    // the near side is kept on odd quadrants of phi, and where it is cut the far side is hit.
    const char *stex = "Texture \"q\" \"float\" \"checkerboard\" \"float uscale\" [ 4 ] \"float vscale\" [ 2 ] "
                       "\"float tex1\" [ 0 ] \"float tex2\" [ 1 ]\n";
    auto t = Trace("alpha_sphere", std::string(kHead) + kWall + stex + "Shape \"sphere\" \"texture alpha\" \"q\"\n");
    const Float zNear = -std::sqrt(0.75f);
    for (bool useBVH : {false, true}) {
        SCOPED_TRACE(useBVH ? "bvh" : "embree");
        int wrong = 0, n = 0, far = 0;
        for (int k = 0; k < 400; ++k) {
            Float phi = 2 * Pi * (k + 0.5f) / 400;
            Float inQuadrant = std::fmod(phi, Pi / 2);
            if (inQuadrant < 0.02f || inQuadrant > Pi / 2 - 0.02f) continue;
            Ray r;
            r.o = Vec3f(0.5f * std::cos(phi), 0.5f * std::sin(phi), -4);
            r.d = Vec3f(0, 0, 1);
            HitRecord h;
            ASSERT_TRUE(t->Intersect(useBVH, r, &h));
            bool odd = int(std::floor(phi / (Pi / 2))) % 2 == 1;
            Float zExpected = odd ? zNear : -zNear;
            ++n;
            far += !odd;
            wrong += h.shape != 1 || std::abs(r(h.t).z - zExpected) > 1e-3f;
            Ray shadow = r;
            shadow.tMax = 5.5f;
            wrong += !t->Occluded(useBVH, shadow);
        }
        EXPECT_GT(n, 300);
        EXPECT_GT(far, 100);
        EXPECT_EQ(wrong, 0);
    }
}

// (3) Rendered: the checkerboard cut-out (and a sphere of alpha 0.5) in front of a wall lit
// through them, Embree against the BVH tracer (independent seeds, block z-test).
TEST(Alpha, CheckerboardRendersTheSameOnBothTracers) {
    std::string text = "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
                       "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n"
                       "Sampler \"independent\"\nWorldBegin\n"
                       "LightSource \"point\" \"point3 from\" [ 0.5 0.5 -4 ] \"rgb I\" [ 20 20 20 ]\n"
                       "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" [ 4 ] \"float vscale\" [ 4 ] "
                       "\"float tex1\" [ 0 ] \"float tex2\" [ 1 ]\n" +
                       std::string(kWall) + "Material \"diffuse\" \"rgb reflectance\" [ 0.2 0.5 0.8 ]\n" +
                       Quad(0, "\"texture alpha\" \"checks\"") + "Translate 0.3 0.2 -1\nShape \"sphere\" \"float radius\" [ 0.3 ] "
                       "\"float alpha\" [ 0.5 ]\n";
    auto scene = LoadSceneText("alpha_render", text);
    ASSERT_TRUE(scene);
    const int seeds = 4, block = 8;
    std::vector<Image> embree, bvh;
    for (int s = 0; s < seeds; ++s) {
        RenderSettings job = SettingsFor(*scene, "path", 8, 100 + s);
        job.maxDepth = 3;
        embree.push_back(RenderScene(*scene, job).image);
        job.seed = 200 + s;
        job.cpuTracer = CpuTracer::BVH;
        bvh.push_back(RenderScene(*scene, job).image);
        EXPECT_TRUE(AllFinite(bvh.back()));
    }
    int tests = (32 / block) * (32 / block) * 3;
    BlockComparison c = CompareBlockMeans(embree, bvh, block, TwoSidedZ(SidakP(1e-3, tests)));
    EXPECT_EQ(c.failures, 0) << c.Summary();
}

// Light sampling and emitter hits see the same cut-out emitter: a checkerboard-masked emitter
// above a floor gives the same image with light sampling only and with BSDF sampling only
// (block z-test), about half the image of the uncut emitter.
TEST(Alpha, CutOutEmitterAgreesAcrossLightStrategies) {
    auto text = [](const std::string &alpha) {
        return "LookAt 0 -3 0.5  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
               "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]\n"
               "Sampler \"independent\"\nWorldBegin\n"
               "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" [ 2 ] \"float vscale\" [ 2 ] "
               "\"float tex1\" [ 0 ] \"float tex2\" [ 1 ]\n"
               "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\n"
               "Shape \"trianglemesh\" \"integer indices\" [ 0 2 1 0 3 2 ] \"point3 P\" [ -1 -1 1  1 -1 1  1 1 1  -1 1 1 ] "
               "\"point2 uv\" [ 0 0  1 0  1 1  0 1 ] " + alpha + "\nAttributeEnd\n"
               "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -3 -3 0  3 -3 0  3 3 0  -3 3 0 ]\n";
    };
    auto scene = LoadSceneText("alpha_emitter", text("\"texture alpha\" \"checks\""));
    auto open = LoadSceneText("alpha_emitter_open", text(""));
    ASSERT_TRUE(scene && open);
    std::vector<Image> nee, bsdf;
    double sumCut = 0, sumOpen = 0;
    for (int s = 0; s < 4; ++s) {
        nee.push_back(RenderScene(*scene, 32, 2, 10 + s, 0, int(LightStrategy::NEEOnly)).image);
        bsdf.push_back(RenderScene(*scene, 32, 2, 20 + s, 0, int(LightStrategy::BSDFOnly)).image);
        Image o = RenderScene(*open, 32, 2, 30 + s, 0, int(LightStrategy::NEEOnly)).image;
        for (size_t i = 0; i < o.pixels.size(); ++i) {
            sumCut += nee.back().pixels[i];
            sumOpen += o.pixels[i];
        }
    }
    int block = 6, tests = (24 / block) * (24 / block) * 3;
    BlockComparison c = CompareBlockMeans(nee, bsdf, block, TwoSidedZ(SidakP(1e-3, tests)));
    EXPECT_EQ(c.failures, 0) << c.Summary();
    // Half the emitter's area is cut: the floor gets about half the light (the checks are large
    // against the floor's distance, so only roughly).
    std::printf("[ alpha    ] nee vs bsdf: %s; cut / open %.4f\n", c.Summary().c_str(), sumCut / sumOpen);
    EXPECT_NEAR(sumCut / sumOpen, 0.5, 0.1);
}

// The feature scene (scenes/features/alpha-*.pbrt): builds clean, renders finite and lit, and the
// BVH tracer agrees with Embree (independent seeds, block z-test).
TEST(Alpha, FeatureSceneMatchesOnBothTracers) {
    std::vector<std::string> files = FeatureSceneFiles({"alpha-"});
    ASSERT_EQ(files.size(), 1u);
    const int resX = 48, resY = 32, block = 8, seeds = 4;
    auto scene = LoadCleanFeatureScene(files[0], resX, resY);
    ASSERT_TRUE(scene);
    EXPECT_GT(scene->View().alphaShapes, 5u);
    EXPECT_GT(scene->View().instances.size, 0u);
    ExpectRendersFiniteAndLit(*scene);
    std::vector<Image> embree, bvh;
    for (int s = 0; s < seeds; ++s) {
        RenderSettings job = SettingsFor(*scene, "path", 8, 1 + s);
        embree.push_back(RenderScene(*scene, job).image);
        job.seed = 101 + s;
        job.cpuTracer = CpuTracer::BVH;
        bvh.push_back(RenderScene(*scene, job).image);
    }
    int tests = (resX / block) * (resY / block) * 3;
    BlockComparison c = CompareBlockMeans(embree, bvh, block, TwoSidedZ(SidakP(1e-3, tests)));
    std::printf("[ alpha    ] embree vs bvh: %s\n", c.Summary().c_str());
    EXPECT_EQ(c.failures, 0) << c.Summary();
}

}  // namespace
}  // namespace lu::test
