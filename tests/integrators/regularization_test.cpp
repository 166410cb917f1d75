// Lucerna: selective path regularization. Unit tests of the cone kernel and its MIS weights, and
// the analytic consistency scene of docs/method.md: a point light above a floor beside a
// plane mirror (camera - floor - mirror - light). Plain path tracing cannot render the mirrored
// light; regpath must converge to its analytic irradiance, with a bias that shrinks with N.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "integrators/render_helpers.h"
#include "lucerna/camera/camera.h"
#include "lucerna/integrators/regularization.h"
#include "lucerna/lights/lights.h"
#include "lucerna/sampling/rng.h"
#include "lucerna/sampling/warp.h"

namespace lu::test {

// The kernel integrates to 1 over the sphere: uniform directions, Monte Carlo in double.
TEST(Regularization, ConeKernelIntegratesToOne) {
    for (Float sigma : {0.01f, 0.1f, 0.5f, 1.2f}) {
        Vec3f D = Normalize(Vec3f(0.3f, -0.2f, 0.9f));
        Float omc = OneMinusCosAngle(sigma);
        Float phi = ConePdfW(omc);
        // Exact: phi * solid angle of the cap = 1.
        EXPECT_NEAR(double(phi) * 2 * M_PI * (1 - std::cos(double(sigma))), 1.0, 1e-4) << sigma;
        // Monte Carlo over the sphere with stratified points.
        const int n = 400;
        double sum = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                Vec3f w = SampleUniformSphere(Vec2f((i + 0.5f) / n, (j + 0.5f) / n));
                if (OneMinusCosBetween(D, w) < omc) sum += phi / UniformSpherePDF();
            }
        double est = sum / (double(n) * n);
        EXPECT_NEAR(est, 1.0, sigma < 0.05f ? 0.5 : 0.03) << "sigma " << sigma;
    }
}

// cos sigma = d / sqrt(d^2 + r^2), its cancellation-free 1 - cos form, and the area-measure pdf
// at the light: p_impl(z) = cos theta_z / (2 pi (1 - cos sigma) d^2) ~ cos theta_z / (pi r^2).
TEST(Regularization, ConeGeometryAndPdfConversion) {
    for (Float d : {0.1f, 1.f, 100.f})
        for (Float r : {1e-4f, 1e-2f, 0.5f}) {
            double cosS = double(d) / std::sqrt(double(d) * d + double(r) * r);
            EXPECT_NEAR(ConeCosForDisc(d, r), cosS, 1e-6);
            EXPECT_NEAR(OneMinusConeCosForDisc(d, r) / (1 - cosS), 1.0, 1e-3) << d << " " << r;
            // Small-cone limit: the cap projects to a disc of radius r at distance d.
            double pdfA = ConePdfW(OneMinusConeCosForDisc(d, r)) / (double(d) * d);   // cos theta_z = 1
            if (r / d < 0.01) { EXPECT_NEAR(pdfA * M_PI * r * r, 1.0, 1e-3) << d << " " << r; }
        }
    RegularizationParams p = RegularizationForPass(true, 0.64f, 0.1f, 1.f / 6, 63);  // N = 64
    EXPECT_NEAR(p.radius, 0.64 / 2, 1e-6);
    EXPECT_NEAR(p.angle, 0.1 / 2, 1e-7);
}

// The two weights of one path sum to 1 and reach their limits.
TEST(Regularization, MisWeightsSumToOneAndLimits) {
    for (Float pi : {1e-3f, 0.5f, 2.f, 1e4f})
        for (Float pe : {1e-3f, 0.5f, 2.f, 1e4f})
            EXPECT_NEAR(RegularizedConnectionWeight(pi, pe) + RegularizedHitWeight(pi, pe), 1.0, 1e-6);
    // Area light, r -> 0: the cone pdf grows without bound and the implicit (unbiased) technique
    // takes the whole weight.
    Float pExpl = 0.7f;
    Float prev = 0;
    for (Float r : {1.f, 1e-1f, 1e-2f, 1e-3f}) {
        Float wImpl = RegularizedHitWeight(ConePdfW(OneMinusConeCosForDisc(2.f, r)), pExpl);
        EXPECT_GE(wImpl, prev);
        prev = wImpl;
    }
    EXPECT_GT(prev, 0.999999f);
    EXPECT_EQ(RegularizedHitWeight(Infinity, pExpl), 1.f);
    // Delta lights: no implicit technique; the regularized connection has weight 1.
    EXPECT_EQ(RegularizedConnectionWeight(ConePdfW(0.01f), Infinity), 1.f);
    EXPECT_EQ(RegularizedHitWeight(ConePdfW(0.01f), Infinity), 0.f);
    // Tiny light (p_expl >> p_impl): the regularized technique dominates.
    EXPECT_GT(RegularizedConnectionWeight(1.f, 1e4f), 0.999f);
}

namespace {

// Floor y = 0 (x < 0, albedo rho), mirror x = 0 facing -x (k huge: F ~ 1), point light at
// (-0.3, 1, 0) of intensity I; camera looking down at the floor. maxdepth 2 keeps exactly the
// direct light and the light via the mirror.
constexpr double kI = 10, kRho = 0.5;
const Vec3f kLight(-0.3f, 1, 0), kVirtual(0.3f, 1, 0);

std::string MirrorScene(double radius) {
    return "LookAt -1 3 0  -1 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]\nPixelFilter \"box\"\n"
           "Sampler \"zsobol\" \"integer pixelsamples\" [ 256 ]\n"
           "Integrator \"regpath\" \"integer maxdepth\" [ 2 ] \"float radius\" [ " + std::to_string(radius) + " ]\n"
           "WorldBegin\nLightSource \"point\" \"point3 from\" [ -0.3 1 0 ] \"rgb I\" [ 10 10 10 ]\n"
           "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -10 0 -10  0 0 -10  0 0 10  -10 0 10 ]\n"
           "AttributeEnd\nAttributeBegin\nMaterial \"conductor\" \"rgb eta\" [ 1 1 1 ] \"rgb k\" [ 1000 1000 1000 ] \"float roughness\" [ 0 ]\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ 0 -1 -10  0 10 -10  0 10 10  0 -1 10 ]\n"
           "AttributeEnd\n";
}

// Radiance of the floor at p: rho/pi * (E_direct + E_mirror), point-light irradiance I cos / d^2.
double FloorRadiance(const Vec3f &p, bool withMirror) {
    auto E = [&](const Vec3f &l) {
        Vec3f d = l - p;
        double dist = Length(d);
        return kI * (d.y / dist) / (dist * dist);
    };
    return kRho / M_PI * (E(kLight) + (withMirror ? E(kVirtual) : 0.0));
}

// The analytic pixel values (box filter: 4x4 points per pixel), channel 1.
Image AnalyticImage(const HostScene &scene, bool withMirror) {
    return AnalyticPixelImage(scene, [&](const Ray &ray) { return FloorRadiance(ray(-ray.o.y / ray.d.y), withMirror); });
}

double ImageMean(const Image &img) {
    double s = 0;
    for (float v : img.pixels) s += v;
    return s / img.pixels.size();
}

// Mean of (render - analytic) over the pixels, channel 1, and its standard error: the residuals
// of independent pixels are independent, so their spread measures the noise alone.
MeanSE ResidualMean(const Image &render, const Image &analytic) {
    Image res = analytic;
    for (int y = 0; y < res.height; ++y)
        for (int x = 0; x < res.width; ++x) res.At(x, y, 0) = render.At(x, y, 1) - analytic.At(x, y, 0);
    return RegionMean(res, 0, 0, 0, res.width, res.height);
}

// Renders passes [firstPass, firstPass + passes) only: the film starts empty at pass index
// firstPass, so r_N is that of passes N = firstPass + 1 ...
Image RenderPasses(const HostScene &scene, bool regularize, uint32_t firstPass, int passes, double radius) {
    RenderSettings settings = TestSettings(scene, int(firstPass) + passes, 2, 3);
    settings.integrator = regularize ? IntegratorKind::RegPath : IntegratorKind::Path;
    settings.regRadius = radius;
    settings.regAngle = 0.01 * 180 / M_PI;
    return RenderFromPass(scene, settings, firstPass);
}

}  // namespace

TEST(Regularization, MirroredPointLightConvergesToAnalyticIrradiance) {
    const double r0 = 2.0;
    auto scene = LoadSceneText("reg_mirror", MirrorScene(r0));
    Image direct = AnalyticImage(*scene, false), full = AnalyticImage(*scene, true);
    double meanDirect = ImageMean(direct), meanFull = ImageMean(full);
    ASSERT_GT(meanFull, meanDirect * 1.3) << "the mirrored light must matter in this view";

    // Plain path tracing sees only the direct light.
    MeanSE path = ResidualMean(RenderPasses(*scene, false, 0, 64, r0), direct);
    EXPECT_LT(std::abs(path.mean), 4 * path.se + 0.002 * meanDirect);
    MeanSE pathVsFull = ResidualMean(RenderPasses(*scene, false, 0, 64, r0), full);
    EXPECT_GT(std::abs(pathVsFull.mean), 10 * pathVsFull.se);

    // regpath early (N = 1..256: r_N from 2 down to 0.8) and late (N = 2^20..: r_N ~ 0.2).
    MeanSE early = ResidualMean(RenderPasses(*scene, true, 0, 256, r0), full);
    MeanSE late = ResidualMean(RenderPasses(*scene, true, 1u << 20, 1024, r0), full);
    std::printf("analytic mean %.5f (direct only %.5f); path - direct %+.5f; regpath - analytic: N=1..256: %+.2f%% +- %.2f%%, "
                "N=2^20..: %+.2f%% +- %.2f%%\n",
                meanFull, meanDirect, path.mean, 100 * early.mean / meanFull, 100 * early.se / meanFull,
                100 * late.mean / meanFull, 100 * late.se / meanFull);
    // The bias is visible early and shrinks as N grows; late, the estimate agrees with the
    // analytic irradiance within its noise plus the residual bias of r_N ~ 0.2 (measured with a
    // fixed radius: about -1.5% of the total at r = 0.2, -0.6% at r = 0.1).
    EXPECT_GT(std::abs(early.mean), 4 * early.se);
    EXPECT_LT(std::abs(late.mean), std::abs(early.mean));
    EXPECT_LT(std::abs(late.mean), 4 * late.se + 0.02 * meanFull);
}

namespace {

// A glass ball (eta 1.5, radius 1, 5 units ahead) with a light 5 units behind it on the camera's
// axis and nothing else: the whole image is the light seen through the glass (E-S-S-L and longer
// internal chains), the paths that the regularized technique must carry with the right weight
// (two Fresnel transmissions and their radiance scaling).
std::string GlintScene(bool pointLight) {
    std::string light = pointLight
        ? "LightSource \"point\" \"point3 from\" [ 0 0 10 ] \"rgb I\" [ 1 1 1 ]\n"
        // Same intensity from a sphere of radius 0.05: I = L pi r^2.
        : "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 127.32395 127.32395 127.32395 ]\n"
          "Translate 0 0 10\nShape \"sphere\" \"float radius\" [ 0.05 ]\nAttributeEnd\n";
    return "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ 16 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\nPixelFilter \"box\"\n"
           "Sampler \"independent\" \"integer pixelsamples\" [ 256 ]\nWorldBegin\n" + light +
           "AttributeBegin\nMaterial \"dielectric\" \"float eta\" [ 1.5 ]\nTranslate 0 0 5\n"
           "Shape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n";
}

double ImageSum(const Image &img, int c) {
    double s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) s += img.At(x, y, c);
    return s;
}

}  // namespace

// The point light's image through the glass: plain path tracing cannot render it (delta light
// behind specular surfaces); regpath's total (the glint blurred by r_N, its energy kept) must
// equal what path renders for a small sphere light of the same intensity, where the implicit
// technique works. Measured: sums 602 (regpath, point) vs 605 +- 5 (path, sphere; 3 seeds).
TEST(Regularization, PointLightSeenThroughGlassHasTheEnergyOfASmallAreaLight) {
    auto point = LoadSceneText("reg_glint_point", GlintScene(true));
    auto sphere = LoadSceneText("reg_glint_sphere", GlintScene(false));
    const int kSeeds = 4, kSpp = 256, kDepth = 12;
    EXPECT_EQ(ImageSum(RenderScene(*point, 16, kDepth, 1).image, 1), 0.0) << "path cannot see a point light through glass";
    std::vector<double> reg, ref;
    for (int s = 0; s < kSeeds; ++s) {
        RenderResultForTest r = RenderScene(*point, kSpp, kDepth, 10 + s, 0, 0, true, 0.3, 0.01);
        EXPECT_GT(r.stats.regConnections, 1000u);
        reg.push_back(ImageSum(r.image, 1));
        ref.push_back(ImageSum(RenderScene(*sphere, kSpp, kDepth, 20 + s).image, 1));
    }
    auto meanSE = [](const std::vector<double> &v) {
        double m = 0, m2 = 0;
        for (double x : v) { m += x; m2 += x * x; }
        m /= v.size();
        return MeanSE{m, std::sqrt(std::max(0.0, m2 / v.size() - m * m) / (v.size() - 1))};
    };
    MeanSE a = meanSE(reg), b = meanSE(ref);
    std::printf("glint through glass, image sum (channel 1): regpath + point light %.1f +- %.1f, path + sphere light %.1f +- %.1f\n",
                a.mean, a.se, b.mean, b.se);
    ASSERT_GT(b.mean, 100.0);
    // Noise of both plus 3% for the blur (r_N >= 0.12 here) at the glint's edge.
    EXPECT_LT(std::abs(a.mean - b.mean), 4 * std::sqrt(a.se * a.se + b.se * b.se) + 0.03 * b.mean);
}

// The light-sample culling of regpath (RegularizedConeMayReach over Light::boundCenter/boundRadius)
// is conservative: every light point SampleLi returns inside a lobe's cone is reported reachable,
// for triangle, scaled sphere (points at the object-space radius, beyond the scaled surface), disk
// and spot lights; and it culls most random directions, or it would be useless.
TEST(Regularization, LightCullingIsConservativeAndEffective) {
    auto scene = LoadSceneText("reg_cull",
        "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
        "LightSource \"spot\" \"point3 from\" [ 1 2 0 ] \"point3 to\" [ 0 0 0 ] \"rgb I\" [ 1 1 1 ]\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 ] \"point3 P\" [ -1 2 -1  1 2 -1  0 2.5 1 ]\n"
        "AttributeEnd\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ]\n"
        "Translate -2 1 0\nScale 0.5 0.5 0.5\nShape \"sphere\" \"float radius\" [ 0.4 ]\nAttributeEnd\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"bool twosided\" true\n"
        "Translate 2 -1 1\nRotate 40 1 0 0\nShape \"disk\" \"float radius\" [ 0.3 ] \"float height\" [ 0.2 ]\nAttributeEnd\n");
    SceneView view = scene->View();
    ASSERT_EQ(view.lights.size, 4u);
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    RNG rng(7);
    int accepted = 0, culled = 0, tried = 0;
    for (uint32_t li = 0; li < view.lights.size; ++li) {
        const Light &light = view.lights[li];
        ASSERT_GE(light.boundRadius, 0) << "light " << li;
        for (int i = 0; i < 4000; ++i) {
            LightSampleContext ctx;
            ctx.p = Vec3f(4 * rng.UniformFloat() - 2, 4 * rng.UniformFloat() - 2, 4 * rng.UniformFloat() - 2);
            Float r = Float(0.3) * std::pow(rng.UniformFloat(), Float(3));   // radii from 0 to 0.3
            LightLiSample ls;
            if (!SampleLi(light, view, ctx, Vec2f(rng.UniformFloat(), rng.UniformFloat()), lambda, &ls) || ls.pdf == 0) continue;
            // A lobe direction inside the cone around the sampled point, near its edge.
            Float oneMinusCos = OneMinusConeCosForDisc(ls.distance, r);
            Vec3f jitter = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
            Vec3f D = Normalize(ls.wi + jitter * (std::sqrt(2 * oneMinusCos) * rng.UniformFloat()));
            if (OneMinusCosBetween(D, ls.wi) < oneMinusCos) {
                ++accepted;
                EXPECT_TRUE(RegularizedConeMayReach(ctx.p, D, light.boundCenter, light.boundRadius, r))
                    << "light " << li << " p " << ctx.p.x << "," << ctx.p.y << "," << ctx.p.z << " r " << r;
            }
            // A random lobe direction: usually nowhere near the light.
            Vec3f Dr = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
            ++tried;
            culled += !RegularizedConeMayReach(ctx.p, Dr, light.boundCenter, light.boundRadius, r);
        }
    }
    std::printf("culling: %d in-cone samples all reachable; %d of %d random directions culled\n", accepted, culled, tried);
    EXPECT_GT(accepted, 4000);
    EXPECT_GT(culled, tried * 3 / 4);
}

// Selectivity: without specular surfaces, regpath is bit-identical to path for the same seed.
TEST(Regularization, NoSpecularSurfacesIsBitIdentical) {
    auto scene = LoadSceneText("reg_selective",
        "LookAt 0 2 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 50 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]\n"
        "WorldBegin\nLightSource \"point\" \"point3 from\" [ 0 1 0 ] \"rgb I\" [ 2 2 2 ]\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -0.5 1.5 -0.5  0.5 1.5 -0.5  0.5 1.5 0.5  -0.5 1.5 0.5 ]\n"
        "AttributeEnd\nMaterial \"conductor\" \"float roughness\" [ 0.2 ]\nShape \"sphere\" \"float radius\" [ 0.3 ]\n"
        "Material \"coateddiffuse\" \"float roughness\" [ 0.1 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -2 -0.3 -2  2 -0.3 -2  2 -0.3 2  -2 -0.3 2 ]\n");
    auto a = RenderScene(*scene, 8, 6, 11, 0, 0, false);
    auto b = RenderScene(*scene, 8, 6, 11, 0, 0, true, 0.05, 0.01);
    EXPECT_EQ(b.stats.regConnections, 0u);
    ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
    EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(float)));
}

// Selectivity at camera-specular-light paths: a 2 cm sphere light seen in a smooth mirror is
// sampled by the pixel integral without bias, so regpath adds nothing there (it used to blur the
// glint to r_N: 209x path's MSE at 1024 spp). With only area lights, a chain of Dirac vertices
// from the camera gets no regularized connection at all: the same samples, the same image.
TEST(Regularization, GlintOfAnAreaLightInAMirrorIsLeftToThePixelIntegral) {
    auto scene = LoadSceneText("reg_mirror_glint",
        "LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\nWorldBegin\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 2000 2000 2000 ]\n"
        "Translate 0 0.6 -1.5\nShape \"sphere\" \"float radius\" [ 0.01 ]\nAttributeEnd\n"
        "AttributeBegin\nMaterial \"conductor\" \"float roughness\" [ 0 ] \"spectrum eta\" \"metal-Ag-eta\" "
        "\"spectrum k\" \"metal-Ag-k\"\nRotate 10 1 0 0\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ]\n"
        "AttributeEnd\n");
    auto a = RenderScene(*scene, 16, 5, 3, 0, 0, false);
    auto b = RenderScene(*scene, 16, 5, 3, 0, 0, true, 0.2, 0.01);
    EXPECT_GT(ImageSum(a.image, 1), 0.0) << "the glint is not in the picture";
    EXPECT_EQ(b.stats.regConnections, 0u);
    ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
    EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(float)));
    // The same mirror with a point light: there the regularized connection is the only technique.
    auto p = LoadSceneText("reg_mirror_point",
        "LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\nWorldBegin\n"
        "LightSource \"point\" \"point3 from\" [ 0 0.6 -1.5 ] \"rgb I\" [ 1 1 1 ]\n"
        "AttributeBegin\nMaterial \"conductor\" \"float roughness\" [ 0 ]\nRotate 10 1 0 0\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ]\n"
        "AttributeEnd\n");
    auto pr = RenderScene(*p, 16, 5, 3, 0, 0, true, 0.2, 0.01);
    EXPECT_GT(pr.stats.regConnections, 0u);
    EXPECT_GT(ImageSum(pr.image, 1), 0.0);
}

}  // namespace lu::test

namespace lu::test {
namespace {

// A spot light at z = 0.5 shining up onto a 20 cm mirror at z = 1 (facing down), over a floor of
// 2 km (the scene's diagonal: 2.8 km, so r0 = 0.04 x diagonal is 113 m); the floor is lit only
// through the mirror, a 60 cm patch under it whose middle the camera sees (camera - floor - mirror
// - spot: the regularized connection's path). `direct`: the same floor under the spot's mirror
// image, a spot at z = 1.5 shining down (the mirror's reflectance is 1), where NEE alone is exact.
// 8 x 8 pixels: the kernel's angle is K pixel footprints over the floor-mirror distance, and its
// success rate grows with its square.
std::string KilometreMirrorScene(bool direct) {
    std::string light = direct ? "LightSource \"spot\" \"point3 from\" [ 0 0 1.5 ] \"point3 to\" [ 0 0 0 ] "
                                 "\"rgb I\" [ 1 1 1 ] \"float coneangle\" [ 30 ] \"float conedelta\" [ 5 ]\n"
                               : "LightSource \"spot\" \"point3 from\" [ 0 0 0.5 ] \"point3 to\" [ 0 0 1 ] "
                                 "\"rgb I\" [ 1 1 1 ] \"float coneangle\" [ 30 ] \"float conedelta\" [ 5 ]\n"
                                 "AttributeBegin\nMaterial \"conductor\" \"rgb reflectance\" [ 1 1 1 ] \"float roughness\" [ 0 ]\n"
                                 "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" "
                                 "[ -0.1 -0.1 1  0.1 -0.1 1  0.1 0.1 1  -0.1 0.1 1 ]\nAttributeEnd\n";
    return "LookAt 0 -1.2 0.6  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" [ 20 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\nPixelFilter \"box\"\n"
           "WorldBegin\n" + light +
           "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" "
           "[ -1000 -1000 0  1000 -1000 0  1000 1000 0  -1000 1000 0 ]\nAttributeEnd\n";
}

}  // namespace

// Issue 12, item 4: r0 = 0.04 x the scene's diagonal blurs the mirrored patch of a kilometre scene
// by 113 m, so the part in view gets a small fraction of its light; the footprint kernels
// (--reg-footprint K) blur by at most K N^-1/6 pixels wherever the path's light lands (K = 4
// here: at most 23 cm on the floor at N = 1, 4 cm at N = 65536), and the middle of the image (4 x 4
// pixels, 12 cm around the patch's centre) gets what the spot's mirror image gives it there.
// Per-pixel differences: their spread is the noise alone.
TEST(Regularization, FootprintKernelsKeepAKilometreSceneSharp) {
    auto mirror = LoadSceneText("reg_km_mirror", KilometreMirrorScene(false));
    auto direct = LoadSceneText("reg_km_direct", KilometreMirrorScene(true));
    EXPECT_GT(mirror->View().camera.pixelSpread, 0.04f);   // 20 degrees over 8 pixels: 0.0436 rad
    EXPECT_LT(mirror->View().camera.pixelSpread, 0.046f);
    auto render = [&](const HostScene &scene, bool reg, double footprint, int spp, uint32_t seed) {
        RenderSettings s = TestSettings(scene, spp, 3, seed);
        s.integrator = reg ? IntegratorKind::RegPath : IntegratorKind::Path;
        s.regFootprint = footprint;
        return RenderScene(scene, s);
    };
    Image ref = render(*direct, false, 0, 64, 1).image;
    auto fp = render(*mirror, true, 4, 65536, 2), world = render(*mirror, true, 0, 256, 3);
    auto diff = [&](const Image &img) {
        Image d = img;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) d.At(x, y, 1) = img.At(x, y, 1) - ref.At(x, y, 1);
        return RegionMean(d, 1, 2, 2, 6, 6);
    };
    MeanSE r = RegionMean(ref, 1, 2, 2, 6, 6), a = diff(fp.image), b = diff(world.image);
    std::printf("middle of the image: spot's image %.4g; regpath - that: footprint 4 px %+.4g +- %.2g (%llu connections), "
                "r0 = 0.04 x diagonal %+.4g +- %.2g\n",
                r.mean, a.mean, a.se, (unsigned long long)fp.stats.regConnections, b.mean, b.se);
    ASSERT_GT(r.mean, 0.01);
    EXPECT_LT(std::abs(a.mean), 4 * a.se + 0.05 * r.mean);
    EXPECT_LT(b.mean, -0.8 * r.mean) << "the world-space default should have blurred the patch away";
}

}  // namespace lu::test
