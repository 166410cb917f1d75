// Near-specular regularization (issue 12 item 6; integrators/techniques.h, NearSpecularBsdf): rough
// conductors and dielectrics narrower than kNearSpecularAlpha, after a non-specular vertex, are
// widened for delta lights only, by at most the vertex's regularized kernel, back to their own lobe
// as the kernel shrinks; glints seen from the camera are left alone.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "integrators/render_helpers.h"
#include "lucerna/integrators/techniques.h"

namespace lu::test {
namespace {

BSDF Conductor(Float ax, Float ay) {
    BSDF b;
    b.kind = BxDFKind::Conductor;
    b.conductor = ConductorBxDF(TrowbridgeReitzDistribution(ax, ay), SampledSpectrum(0.2f), SampledSpectrum(3));
    return b;
}
BSDF Dielectric(Float eta, Float alpha) {
    BSDF b;
    b.kind = BxDFKind::Dielectric;
    b.dielectric = DielectricBxDF(eta, TrowbridgeReitzDistribution(alpha, alpha));
    return b;
}

BSDF CoatedDiffuse(Float coatAlpha, Float baseReflectance, Float eta = 1.5f) {
    BSDF b;
    b.kind = BxDFKind::CoatedDiffuse;
    b.coatedDiffuse = CoatedDiffuseBxDF(DielectricBxDF(eta, TrowbridgeReitzDistribution(coatAlpha, coatAlpha)),
                                        DiffuseBxDF(SampledSpectrum(baseReflectance)), 0.01f, SampledSpectrum(0), 0, 10, 1);
    return b;
}
BSDF CoatedConductor(Float coatAlpha, Float baseAlpha) {
    BSDF b;
    b.kind = BxDFKind::CoatedConductor;
    b.coatedConductor = CoatedConductorBxDF(DielectricBxDF(1.5f, TrowbridgeReitzDistribution(coatAlpha, coatAlpha)),
                                            ConductorBxDF(TrowbridgeReitzDistribution(baseAlpha, baseAlpha),
                                                          SampledSpectrum(0.2f), SampledSpectrum(3)),
                                            0.01f, SampledSpectrum(0), 0, 10, 1);
    return b;
}

// A table at z = 0 (diffuse 0.5), a glass slab (eta 1.5) between z = 0.45 and 0.5 with the given
// microfacet alpha, as wide as the table (two faces, normals outward, no side faces: side faces
// would fold light back by total internal reflection, a caustic of their own), a point light 1 m
// above the table's centre. The camera looks at the centre from below the slab (table points within
// 0.4 m of it), so it sees the table's caustic, never the slab's glint.
std::string SlabScene(double alpha, int spp) {
    std::string a = std::to_string(alpha);
    return "LookAt 0 -0.9 0.3  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 10 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 48 ] \"integer yresolution\" [ 48 ]\n"
           "Sampler \"zsobol\" \"integer pixelsamples\" [ " + std::to_string(spp) + " ]\n"
           "Integrator \"path\" \"integer maxdepth\" [ 6 ]\nPixelFilter \"box\"\nWorldBegin\n"
           "LightSource \"point\" \"point3 from\" [ 0 0 1 ] \"rgb I\" [ 1 1 1 ]\n"
           "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -2 -2 0  2 -2 0  2 2 0  -2 2 0 ]\n"
           "AttributeEnd\nAttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ] \"bool remaproughness\" false "
           "\"float roughness\" [ " + a + " ]\n"
           "Shape \"trianglemesh\" \"point3 P\" [ -2 -2 0.45  2 -2 0.45  2 2 0.45  -2 2 0.45 "
           " -2 -2 0.5  2 -2 0.5  2 2 0.5  -2 2 0.5 ]\n"
           "  \"integer indices\" [ 0 2 1  0 3 2  4 5 6  4 6 7 ]\n"
           "AttributeEnd\n";
}

}  // namespace

TEST(NearSpecular, RoughenWidensOnlyNarrowMicrofacetLobes) {
    BSDF c = Conductor(0.02f, 0.05f);
    EXPECT_TRUE(c.IsNearSpecular());
    ASSERT_TRUE(c.Roughen(0.04f));
    EXPECT_FLOAT_EQ(c.conductor.mfDistrib.alphaX, 0.04f);
    EXPECT_FLOAT_EQ(c.conductor.mfDistrib.alphaY, 0.05f);   // already rougher on that axis
    EXPECT_FALSE(c.Roughen(0.03f));                        // nothing narrower than 0.03 left
    BSDF d = Dielectric(1.5f, 0.01f);
    ASSERT_TRUE(d.Roughen(0.1f));
    EXPECT_FLOAT_EQ(d.dielectric.mfDistrib.alphaX, 0.1f);
    // Left alone: Dirac lobes (the cone kernel's), lobes at or above 0.1, index-matched glass, diffuse.
    BSDF smooth = Dielectric(1.5f, 0), rough = Conductor(0.1f, 0.1f), matched = Dielectric(1, 0.02f), diffuse;
    diffuse.kind = BxDFKind::Diffuse;
    for (BSDF *b : {&smooth, &rough, &matched, &diffuse}) {
        EXPECT_FALSE(b->IsNearSpecular()) << int(b->kind);
        EXPECT_FALSE(b->Roughen(0.08f)) << int(b->kind);
    }
    EXPECT_FALSE(Conductor(0.02f, 0.1f).IsNearSpecular());   // rough on one axis: not near-specular
    EXPECT_FLOAT_EQ(smooth.dielectric.mfDistrib.alphaX, 0);
    EXPECT_FLOAT_EQ(rough.conductor.mfDistrib.alphaX, 0.1f);
}

// Layered BSDFs: a smooth coat over a non-Dirac base is a Dirac lobe NEE cannot see (DiracCoat,
// widened after Dirac-only camera paths too); a narrow coat or a narrow conductor base is Narrow.
TEST(NearSpecular, RoughenWidensCoatsAndNarrowBases) {
    using K = BSDF::NearSpecularKind;
    BSDF varnish = CoatedDiffuse(0, 0.5f);
    EXPECT_FALSE(varnish.IsSpecular());
    EXPECT_EQ(varnish.NearSpecular(), K::DiracCoat);
    EXPECT_FALSE(varnish.Roughen(5e-4f)) << "too small to make the coat a lobe";
    EXPECT_FLOAT_EQ(varnish.coatedDiffuse.top.mfDistrib.alphaX, 0);
    ASSERT_TRUE(varnish.Roughen(0.05f, true));
    EXPECT_FLOAT_EQ(varnish.coatedDiffuse.top.mfDistrib.alphaX, 0.05f);
    EXPECT_FLOAT_EQ(varnish.coatedDiffuse.top.mfDistrib.alphaY, 0.05f);
    EXPECT_EQ(varnish.NearSpecular(), K::Narrow);   // now a narrow lobe

    BSDF glossy = CoatedDiffuse(0.02f, 0.5f);
    EXPECT_EQ(glossy.NearSpecular(), K::Narrow);
    EXPECT_FALSE(glossy.Roughen(0.05f, true)) << "narrow coats keep their lobe after Dirac-only camera paths";
    ASSERT_TRUE(glossy.Roughen(0.05f));
    EXPECT_FLOAT_EQ(glossy.coatedDiffuse.top.mfDistrib.alphaX, 0.05f);

    // Smooth coat over a narrow conductor: the coat always, the base only when narrow lobes may widen.
    BSDF lacquer = CoatedConductor(0, 0.02f);
    EXPECT_EQ(lacquer.NearSpecular(), K::DiracCoat);
    BSDF l2 = lacquer;
    ASSERT_TRUE(l2.Roughen(0.05f, true));
    EXPECT_FLOAT_EQ(l2.coatedConductor.top.mfDistrib.alphaX, 0.05f);
    EXPECT_FLOAT_EQ(l2.coatedConductor.bottom.mfDistrib.alphaX, 0.02f);
    ASSERT_TRUE(lacquer.Roughen(0.05f));
    EXPECT_FLOAT_EQ(lacquer.coatedConductor.top.mfDistrib.alphaX, 0.05f);
    EXPECT_FLOAT_EQ(lacquer.coatedConductor.bottom.mfDistrib.alphaX, 0.05f);
    BSDF roughCoat = CoatedConductor(0.3f, 0.02f);   // rough coat, narrow base: the base alone
    EXPECT_EQ(roughCoat.NearSpecular(), K::Narrow);
    ASSERT_TRUE(roughCoat.Roughen(0.05f));
    EXPECT_FLOAT_EQ(roughCoat.coatedConductor.top.mfDistrib.alphaX, 0.3f);
    EXPECT_FLOAT_EQ(roughCoat.coatedConductor.bottom.mfDistrib.alphaX, 0.05f);

    // Left alone: rough coats over diffuse, index-matched coats, a smooth coat over a black base
    // (Dirac as a whole: the regularized connection's), smooth coat over a smooth conductor (Dirac).
    BSDF rough = CoatedDiffuse(0.3f, 0.5f), matched = CoatedDiffuse(0, 0.5f, 1), black = CoatedDiffuse(0, 0),
         mirror = CoatedConductor(0, 0);
    EXPECT_TRUE(black.IsSpecular());
    EXPECT_TRUE(mirror.IsSpecular());
    for (BSDF *b : {&rough, &matched, &black, &mirror}) {
        EXPECT_EQ(b->NearSpecular(), K::None) << int(b->kind);
        EXPECT_FALSE(b->Roughen(0.08f)) << int(b->kind);
    }
}

// The widening follows the vertex's kernel: never beyond kNearSpecularAlpha, shrinking with the
// pass as N^-lambda, none after Dirac vertices from the camera, none once tan(sigma / 2) <= alpha.
TEST(NearSpecular, WideningShrinksToTheSurfacesOwnLobe) {
    auto scene = LoadSceneText("near_specular_kernel", SlabScene(0.02, 1));
    RenderSettings s = TestSettings(*scene, 1, 6);
    s.integrator = IntegratorKind::RegPath;
    ScatterVertex in;
    in.allSpecular = false;
    in.receiverT = 1.2f;   // the table, seen 1.2 m from the camera; the slab 0.5 m above it
    const Float T = 1.7f;
    BSDF glass = Dielectric(1.5f, 0.02f), wide;
    Float previous = kNearSpecularAlpha;
    int widened = 0;
    for (uint32_t pass : {0u, 100u, 10000u, 1000000u, 100000000u}) {
        PathSettings ps = s.ForPass(pass);
        if (!NearSpecularBsdf(ps, scene->View(), glass, in, T, &wide)) {
            // Past this pass the kernel is narrower than the lobe: the surface's own BSDF.
            Float sigma = RegularizedAngle(VertexRegularization(ps, scene->View(), in.receiverT, T));
            EXPECT_LE(std::tan(sigma / 2), 0.02f) << "pass " << pass;
            continue;
        }
        ++widened;
        Float a = wide.dielectric.mfDistrib.alphaX;
        EXPECT_GT(a, 0.02f);
        EXPECT_LE(a, previous) << "pass " << pass;
        previous = a;
    }
    EXPECT_GE(widened, 2);
    EXPECT_FALSE(NearSpecularBsdf(s.ForPass(100000000u), scene->View(), glass, in, T, &wide));
    // Camera paths through Dirac vertices only, and path tracing: never.
    in.allSpecular = true;
    EXPECT_FALSE(NearSpecularBsdf(s.ForPass(0), scene->View(), glass, in, T, &wide));
    in.allSpecular = false;
    s.integrator = IntegratorKind::Path;
    EXPECT_FALSE(NearSpecularBsdf(s.ForPass(0), scene->View(), glass, in, T, &wide));
}

// The caustic of a point light under a rough slab (alpha 0.02): path tracing reaches the light only
// by NEE at the slab's top face, evaluating its narrow lobe in the direction the table's bounce
// chose. regpath widens that lobe (0.1 while the kernel allows it): the same mean, at much lower
// variance at equal samples. With the widening off, regpath is path tracing here, bit for bit (no
// Dirac vertex: nothing else of regpath runs).
TEST(NearSpecular, RoughSlabCausticConvergesFasterAtEqualSamples) {
    auto scene = LoadSceneText("near_specular_slab", SlabScene(0.02, 256));
    RenderSettings s = TestSettings(*scene, 256, 6, 3);
    RenderResultForTest path = RenderScene(*scene, s);
    s.integrator = IntegratorKind::RegPath;
    RenderResultForTest reg = RenderScene(*scene, s);
    s.nearSpecular = false;
    RenderResultForTest off = RenderScene(*scene, s);
    EXPECT_EQ(off.image.pixels, path.image.pixels);
    // The bare table (no slab; NEE alone, nearly noise-free), for the slab's transmittance.
    std::string bareText = SlabScene(0.02, 16);
    bareText = bareText.substr(0, bareText.rfind("AttributeBegin"));
    auto bare = LoadSceneText("near_specular_bare", bareText);
    RenderResultForTest b = RenderScene(*bare, TestSettings(*bare, 16, 6, 3));
    // The table around its centre, below the light: 32 x 32 pixels.
    MeanSE mp = RegionMean(path.image, 1, 8, 8, 40, 40), mr = RegionMean(reg.image, 1, 8, 8, 40, 40);
    MeanSE mb = RegionMean(b.image, 1, 8, 8, 40, 40);
    std::printf("[ slab     ] bare table %.4f; path %.4f +- %.4f, regpath %.4f +- %.4f (pixel standard errors)\n", mb.mean,
                mp.mean, mp.se, mr.mean, mr.se);
    EXPECT_NEAR(mr.mean, mp.mean, 4 * std::sqrt(mp.se * mp.se + mr.se * mr.se) + 0.02 * mp.mean);
    // Two faces of glass of 1.5 near normal incidence pass 0.923 of the light, which the slab's
    // lateral shift concentrates by 1.034 (the source seems 1.7 cm nearer): 0.953 of the bare table
    // (a Monte Carlo ray trace of this geometry gives 0.9528; regpath's MNEE alone, smooth slab,
    // maxdepth 3: 0.953).
    EXPECT_NEAR(mr.mean / mb.mean, 0.953, 4 * mr.se / mb.mean + 0.03);
    EXPECT_LT(mr.se, 0.5 * mp.se);
}

// A point light's glint in a near-specular mirror, seen from the camera: the pixel integral
// samples it without bias, and regpath leaves it as path tracing renders it, bit for bit.
TEST(NearSpecular, GlintsSeenFromTheCameraAreLeftAlone) {
    std::string text =
        "LookAt 0 -1 1  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 20 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n"
        "Sampler \"zsobol\" \"integer pixelsamples\" [ 16 ]\nIntegrator \"path\" \"integer maxdepth\" [ 5 ]\n"
        "PixelFilter \"box\"\nWorldBegin\nLightSource \"point\" \"point3 from\" [ 0 1 1 ] \"rgb I\" [ 1 1 1 ]\n"
        "Material \"conductor\" \"bool remaproughness\" false \"float roughness\" [ 0.02 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ]\n";
    auto scene = LoadSceneText("near_specular_glint", text);
    RenderSettings s = TestSettings(*scene, 16, 5, 1);
    RenderResultForTest path = RenderScene(*scene, s);
    s.integrator = IntegratorKind::RegPath;
    RenderResultForTest reg = RenderScene(*scene, s);
    double peak = 0;
    for (float v : path.image.pixels) peak = std::max(peak, double(v));
    EXPECT_GT(peak, 0.1);   // the glint is there
    EXPECT_EQ(reg.image.pixels, path.image.pixels);
}

namespace {

// A varnished floor (coateddiffuse, smooth coat of eta 1.5 over a dark base) at z = 0, a point
// light 0.5 above it, a diffuse wall (0.5) at x = 1 and a black screen at x = 0.5 that hides the
// light from the wall points the camera sees (z 0.35..0.65 around y = 0), but not the light's
// image in the floor: those points are lit by the coat's mirror reflection alone (and a little
// light scattered by the dark base). Path tracing renders no mirror reflection of a point light.
constexpr double kVarnishBase = 0.05, kWallRho = 0.5;
const Vec3f kVarnishLight(0, 0, 0.5f);

std::string VarnishScene(int spp) {
    return "LookAt 0.2 -2 0.5  1 0 0.5  0 0 1\nCamera \"perspective\" \"float fov\" [ 8 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]\n"
           "Sampler \"zsobol\" \"integer pixelsamples\" [ " + std::to_string(spp) + " ]\n"
           "Integrator \"regpath\" \"integer maxdepth\" [ 2 ]\nPixelFilter \"box\"\nWorldBegin\n"
           "LightSource \"point\" \"point3 from\" [ 0 0 0.5 ] \"rgb I\" [ 1 1 1 ]\n"
           "AttributeBegin\nMaterial \"coateddiffuse\" \"rgb reflectance\" [ 0.05 0.05 0.05 ] \"float roughness\" [ 0 ]\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -3 -3 0  1 -3 0  1 3 0  -3 3 0 ]\n"
           "AttributeEnd\nAttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ 1 -3 0  1 3 0  1 3 3  1 -3 3 ]\n"
           "AttributeEnd\nAttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ 0.5 -0.6 0.2  0.5 0.6 0.2  0.5 0.6 1.2  0.5 -0.6 1.2 ]\n"
           "AttributeEnd\n";
}

// The wall's radiance from the light's mirror image (0, 0, -0.5) in the coat: rho / pi * R(theta)
// I cos / d^2, per pixel (box filter, 4 x 4 points), for the camera of the scene.
Image VarnishMirrorImage(const HostScene &scene) {
    const Vec3f image(kVarnishLight.x, kVarnishLight.y, -kVarnishLight.z);
    return AnalyticPixelImage(scene, [&](const Ray &ray) {
        Vec3f p = ray(Float((1 - ray.o.x) / ray.d.x));
        Vec3f d = image - p;
        double dist = Length(d);
        double cosWall = -d.x / dist, cosFloor = -d.z / dist;
        return kWallRho / M_PI * FrDielectric(Float(cosFloor), 1.5f) * cosWall / (dist * dist);
    });
}

}  // namespace

// The varnished floor's reflection of a point light on the wall (light - coat - wall - camera): no
// technique of path tracing samples it; regpath widens the smooth coat for the point light, and
// the difference to path (which shares every other random number and sample) is the mirror term.
TEST(NearSpecular, VarnishReflectsAPointLightOntoTheWall) {
    auto scene = LoadSceneText("near_specular_varnish", VarnishScene(256));
    Image mirror = VarnishMirrorImage(*scene);
    RenderSettings s = TestSettings(*scene, 256, 2, 5);
    s.integrator = IntegratorKind::Path;
    RenderResultForTest path = RenderScene(*scene, s);
    s.integrator = IntegratorKind::RegPath;
    RenderResultForTest reg = RenderScene(*scene, s);
    EXPECT_EQ(reg.stats.rejected, 0u);
    const int w = mirror.width, h = mirror.height;
    Image diff = mirror;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) diff.At(x, y, 0) = reg.image.At(x, y, 1) - path.image.At(x, y, 1);
    MeanSE d = RegionMean(diff, 0, 0, 0, w, h), m = RegionMean(mirror, 0, 0, 0, w, h);
    MeanSE p = RegionMean(path.image, 1, 0, 0, w, h);
    std::printf("[ varnish  ] wall: path %.5f (base light only), regpath - path %.5f +- %.5f, mirror term %.5f\n", p.mean,
                d.mean, d.se, m.mean);
    ASSERT_GT(m.mean, 2 * p.mean) << "the mirror term must dominate the wall";
    EXPECT_NEAR(d.mean, m.mean, 4 * d.se + 0.05 * m.mean);
    s.nearSpecular = false;
    EXPECT_EQ(RenderScene(*scene, s).image.pixels, path.image.pixels) << "off: path tracing, bit for bit";
}

// A point light's glint in a varnished floor seen from the camera (camera - coat - light): path
// tracing shows none; regpath's widened coat must carry the energy of the glint of a small sphere
// light of the same intensity (which path tracing renders by sampling the coat's Dirac lobe). Late
// passes (N = 2^20 ...): the kernel is then a few pixels wide and the glint lies inside the frame.
TEST(NearSpecular, VarnishGlintOfAPointLightHasTheEnergyOfASmallAreaLight) {
    auto text = [](bool point) {
        std::string light = point ? "LightSource \"point\" \"point3 from\" [ 0 0.5 0.5 ] \"rgb I\" [ 1 1 1 ]\n"
                                  // I = L pi r^2 for a sphere of radius 0.1
                                  : "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 31.830989 31.830989 31.830989 ]\n"
                                    "Translate 0 0.5 0.5\nShape \"sphere\" \"float radius\" [ 0.1 ]\nAttributeEnd\n";
        return "LookAt 0 -1 0.5  0 -0.25 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
               "Film \"rgb\" \"integer xresolution\" [ 48 ] \"integer yresolution\" [ 48 ]\n"
               "Sampler \"zsobol\" \"integer pixelsamples\" [ 64 ]\nIntegrator \"regpath\" \"integer maxdepth\" [ 1 ]\n"
               "PixelFilter \"box\"\nWorldBegin\n" + light +
               "Material \"coateddiffuse\" \"rgb reflectance\" [ 0.05 0.05 0.05 ] \"float roughness\" [ 0 ]\n"
               "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -3 -3 0  3 -3 0  3 3 0  -3 3 0 ]\n";
    };
    auto point = LoadSceneText("near_specular_varnish_point", text(true));
    auto sphere = LoadSceneText("near_specular_varnish_sphere", text(false));
    auto sum = [](const Image &img) {
        double s = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) s += img.At(x, y, 1);
        return s;
    };
    RenderSettings s = TestSettings(*point, 64, 1, 3);
    s.integrator = IntegratorKind::Path;
    double pathPoint = sum(RenderScene(*point, s).image);
    std::vector<double> ref, reg;
    for (uint32_t seed = 0; seed < 3; ++seed) {
        RenderSettings r = TestSettings(*sphere, 1024, 1, seed);
        r.integrator = IntegratorKind::Path;
        ref.push_back(sum(RenderScene(*sphere, r).image));
        r = TestSettings(*point, (1 << 20) + 64, 1, seed);
        r.integrator = IntegratorKind::RegPath;
        reg.push_back(sum(RenderFromPass(*point, r, 1u << 20)));
    }
    auto meanSE = [](const std::vector<double> &v) {
        double m = 0, q = 0;
        for (double x : v) m += x;
        m /= v.size();
        for (double x : v) q += (x - m) * (x - m);
        return MeanSE{m, std::sqrt(q / (v.size() - 1) / v.size())};
    };
    MeanSE a = meanSE(ref), b = meanSE(reg);
    std::printf("[ varnish  ] image sums: path, point light %.2f (no glint); path, sphere %.2f +- %.2f; regpath, point %.2f +- %.2f\n",
                pathPoint, a.mean, a.se, b.mean, b.se);
    ASSERT_GT(a.mean - pathPoint, 0.2 * a.mean) << "the glint must matter in this view";
    EXPECT_NEAR(b.mean, a.mean, 4 * std::sqrt(a.se * a.se + b.se * b.se) + 0.03 * (a.mean - pathPoint));
}

}  // namespace lu::test
