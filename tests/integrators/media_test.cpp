// Lucerna media tests: transmittance estimators against analytic optical depths (delta tracking
// and ratio tracking in a heterogeneous grid, through the majorant grid's DDA and a medium
// transform), Beer-Lambert through a slab, pbrt-v4's inside/outside convention of
// MediumInterface, furnaces with scattering and emitting media (integrator x tracer), estimator
// agreement in a chromatic medium (spectral MIS), pbrt-v4's procedural cloud (its density against
// an independent evaluation, tracking through it), and the shared scene with its medium.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "integrators/render_helpers.h"
#include "lucerna/integrators/volume.h"

namespace lu::test {
namespace {

// A grid of n density samples along x (ny = nz = 1) with a known piecewise-linear density.
std::vector<double> RampDensity(int n) {
    std::vector<double> v;
    for (int i = 0; i < n; ++i) v.push_back(0.2 + 1.5 * std::sin(0.7 * i) * std::sin(0.7 * i) + 0.05 * i);
    return v;
}

// The integral over x in [0, 1] of pbrt-v4's trilinear lookup of samples v at cell centers
// (0 outside, so the density falls to v/2 at the faces): trapezoids between the centers.
double RampIntegral(const std::vector<double> &v) {
    int n = int(v.size());
    double h = 1.0 / n, sum = 0.75 * v[0] * 0.5 * h + 0.75 * v[n - 1] * 0.5 * h;
    for (int i = 0; i + 1 < n; ++i) sum += 0.5 * (v[i] + v[i + 1]) * h;
    return sum;
}

std::string GridScene(const std::vector<double> &d, const std::string &transform, const std::string &sigmaS) {
    std::string values;
    for (double x : d) values += std::to_string(x) + " ";
    return "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nSampler \"independent\"\n"
           "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nWorldBegin\n"
           "AttributeBegin\n" + transform +
           "MakeNamedMedium \"grid\" \"string type\" \"uniformgrid\" \"integer nx\" [ " + std::to_string(d.size()) +
           " ] \"float density\" [ " + values + "] \"rgb sigma_a\" [ 0.8 0.8 0.8 ] \"rgb sigma_s\" [ " + sigmaS +
           " ] \"float scale\" [ 0.9 ]\nAttributeEnd\n"
           "Shape \"sphere\" \"float radius\" [ 0.01 ]\n";
}

struct TrEstimate {
    double ratio = 0, ratioSE = 0, delta = 0, deltaSE = 0;
};

// Means of the ratio-tracking (shadow rays) and delta-tracking (path segments) estimators of
// the transmittance along ray over [0, tMax] in medium 0, hero wavelength at 550 nm.
TrEstimate EstimateTransmittance(const HostScene &hs, const Ray &ray, Float tMax, int n) {
    SceneView s = hs.View();
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.41f);
    TrEstimate e;
    double r1 = 0, r2 = 0, d1 = 0, d2 = 0;
    for (int i = 0; i < n; ++i) {
        RNG rng(i, 99);
        ShadowTransmittance tr;
        Ray unit = ray;
        unit.d = Normalize(ray.d);
        SegmentTransmittance(s, s.media[0], unit, tMax * Length(ray.d), lambda, rng, &tr);
        r1 += tr.T[0];
        r2 += double(tr.T[0]) * tr.T[0];
        Sampler sampler = hs.sampler;
        sampler.StartPixelSample(i % 4, (i / 4) % 4, i / 16, 0);
        SampledSpectrum beta(1), L(0);
        WavelengthPdfs r;
        Vec3f p;
        MediumEvent ev = SampleMediumSegment(s, 0, ray, tMax, lambda, sampler, 0, 5, beta, r, L, &p);
        double v = ev == MediumEvent::Passed ? beta[0] : 0;
        d1 += v;
        d2 += v * v;
    }
    e.ratio = r1 / n;
    e.ratioSE = std::sqrt(std::max(0.0, r2 / n - e.ratio * e.ratio) / (n - 1));
    e.delta = d1 / n;
    e.deltaSE = std::sqrt(std::max(0.0, d2 / n - e.delta * e.delta) / (n - 1));
    return e;
}

}  // namespace

// ---- Transmittance estimators against analytic optical depths ----

TEST(MediaTransmittance, GridAlongAxisMatchesTheIntegral) {
    std::vector<double> d = RampDensity(24);
    auto hs = LoadSceneText("media_grid_axis", GridScene(d, "", "0 0 0"));
    ASSERT_EQ(hs->media.size(), 1u);
    Ray ray;
    ray.o = Vec3f(-1, 0.5f, 0.5f);
    ray.d = Vec3f(2, 0, 0);   // not unit: t in units of |d|, as the integrator's rays
    double expected = std::exp(-0.9 * 0.8 * RampIntegral(d));
    TrEstimate e = EstimateTransmittance(*hs, ray, 1.5f, 40000);
    EXPECT_NEAR(e.ratio, expected, 4 * e.ratioSE + 1e-4) << "ratio tracking";
    EXPECT_NEAR(e.delta, expected, 4 * e.deltaSE + 1e-4) << "delta tracking";
    // Stopping inside the medium: the integral up to x = 0.5 (t = 0.75) is half of a symmetric
    // part; check against the same trapezoids on the first half of the cells.
    std::vector<double> half(d.begin(), d.begin() + 12);
    double partial = 0.75 * d[0] * 0.5 / 24;
    for (int i = 0; i + 1 < 12; ++i) partial += 0.5 * (d[i] + d[i + 1]) / 24;
    partial += 0.5 * (d[11] + 0.5 * (d[11] + d[12])) * 0.5 / 24;   // from center 11 to x = 0.5
    double expectedHalf = std::exp(-0.9 * 0.8 * partial);
    TrEstimate h = EstimateTransmittance(*hs, ray, 0.75f, 40000);
    EXPECT_NEAR(h.ratio, expectedHalf, 4 * h.ratioSE + 1e-4);
    EXPECT_NEAR(h.delta, expectedHalf, 4 * h.deltaSE + 1e-4);
    // The test can fail: a 3% error in the optical depth is seen.
    EXPECT_GT(std::abs(e.ratio - std::exp(-0.9 * 0.8 * 1.03 * RampIntegral(d))), 4 * e.ratioSE);
}

TEST(MediaTransmittance, TransformedGridAlongADiagonal) {
    // The medium box [0,1]^3 placed at x in [2, 4] (scaled by 2 along x), crossed diagonally:
    // many majorant voxels; the optical depth by fine quadrature of the same lookup.
    std::vector<double> d = RampDensity(32);
    auto hs = LoadSceneText("media_grid_diag", GridScene(d, "Translate 2 0 0\nScale 2 1 1\n", "0 0 0"));
    SceneView s = hs->View();
    const Medium &m = s.media[0];
    Ray ray;
    ray.o = Vec3f(1.5f, 0.05f, 0.1f);
    ray.d = Normalize(Vec3f(2.8f, 0.9f, 0.7f));
    Float tMax = 4;
    double depth = 0;
    const int N = 200000;
    for (int i = 0; i < N; ++i) {
        Float t = (i + 0.5f) * tMax / N;
        Vec3f pm = m.renderFromMedium.Inverted().ApplyPoint(ray(t));
        bool inside = pm.x >= 0 && pm.x <= 1 && pm.y >= 0 && pm.y <= 1 && pm.z >= 0 && pm.z <= 1;
        if (inside) depth += 0.9 * 0.8 * LookupGrid(s, m.density, BoundsOffset(m.bounds, pm)) * tMax / N;
    }
    ASSERT_GT(depth, 0.3);
    double expected = std::exp(-depth);
    TrEstimate e = EstimateTransmittance(*hs, ray, tMax, 40000);
    EXPECT_NEAR(e.ratio, expected, 4 * e.ratioSE + 2e-4);
    EXPECT_NEAR(e.delta, expected, 4 * e.deltaSE + 2e-4);
}

TEST(MediaTransmittance, HomogeneousIsBeerLambert) {
    auto hs = LoadSceneText("media_homog_tr",
        "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nSampler \"independent\"\nWorldBegin\n"
        "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.3 0.3 0.3 ] "
        "\"rgb sigma_s\" [ 0.5 0.5 0.5 ] \"float scale\" [ 2 ]\nShape \"sphere\" \"float radius\" [ 0.01 ]\n");
    Ray ray;
    ray.o = Vec3f(0, 0, 0);
    ray.d = Vec3f(0, 0, 3);
    TrEstimate e = EstimateTransmittance(*hs, ray, 0.5f, 20000);
    double expected = std::exp(-2 * 0.8 * 1.5);
    EXPECT_NEAR(e.ratio, expected, 1e-5);   // exact: no collisions to sample
    // Delta tracking: Passed only without a real collision (any collision is real here).
    EXPECT_NEAR(e.delta, expected, 4 * e.deltaSE + 1e-4);
}

// ---- pbrt-v4's procedural cloud ----

namespace {

// pbrt-v4's CloudMedium::Density, evaluated here in double precision on top of Noise (checked
// against its own definition in texture_test): the forward-difference gradient perturbation,
// five octaves, the height falloff.
double ReferenceCloudDensity(double x, double y, double z, double density, double wispiness, double frequency) {
    double p[3] = {frequency * x, frequency * y, frequency * z};
    auto noise = [](const double q[3]) { return double(Noise(Float(q[0]), Float(q[1]), Float(q[2]))); };
    if (wispiness > 0) {
        double vOmega = 0.05 * wispiness, vLambda = 10;
        for (int i = 0; i < 2; ++i) {
            double q[3] = {vLambda * p[0], vLambda * p[1], vLambda * p[2]}, n = noise(q), g[3];
            for (int a = 0; a < 3; ++a) {
                double qa[3] = {q[0], q[1], q[2]};
                qa[a] += 0.01;
                g[a] = (noise(qa) - n) / 0.01;
            }
            for (int a = 0; a < 3; ++a) p[a] += vOmega * g[a];
            vOmega *= 0.5;
            vLambda *= 1.99;
        }
    }
    double d = 0, omega = 0.5, lambda = 1;
    for (int i = 0; i < 5; ++i) {
        double q[3] = {lambda * p[0], lambda * p[1], lambda * p[2]};
        d += omega * noise(q);
        omega *= 0.5;
        lambda *= 1.99;
    }
    d = std::clamp((1 - y) * 4.5 * density * d, 0.0, 1.0);
    d += 2 * std::max(0.0, 0.5 - y);
    return std::clamp(d, 0.0, 1.0);
}

std::string CloudScene(const std::string &transform, const std::string &params) {
    return "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nSampler \"independent\"\n"
           "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\nWorldBegin\n"
           "AttributeBegin\n" + transform + "MakeNamedMedium \"cloud\" \"string type\" \"cloud\" " + params +
           "\nAttributeEnd\nShape \"sphere\" \"float radius\" [ 0.01 ]\n";
}

}  // namespace

TEST(MediaCloud, DensityIsPbrtV4s) {
    struct Case {
        std::string params;
        double density, wispiness, frequency, sigmaA, sigmaS;
    } cases[] = {
        {"", 1, 1, 5, 1, 1},   // pbrt-v4's defaults
        {"\"float density\" 3 \"float wispiness\" 0.5 \"float frequency\" 2.5 \"float g\" 0.7 "
         "\"spectrum sigma_a\" [ 360 0.25 830 0.25 ] \"spectrum sigma_s\" [ 360 4 830 4 ] "
         "\"point3 p0\" [ -1 -0.5 -1 ] \"point3 p1\" [ 2 1.5 1 ]", 3, 0.5, 2.5, 0.25, 4},
        {"\"float wispiness\" 0 \"float frequency\" 7", 1, 0, 7, 1, 1},
    };
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.3f);
    for (const Case &c : cases) {
        SCOPED_TRACE(c.params);
        // The medium space is the CTM at MakeNamedMedium: x scaled by 2, then moved by (1, 0, 3).
        auto hs = LoadSceneText("media_cloud", CloudScene("Translate 1 0 3\nScale 2 1 1\n", c.params));
        ASSERT_EQ(hs->media.size(), 1u);
        SceneView s = hs->View();
        const Medium &m = s.media[0];
        ASSERT_EQ(m.kind, MediumKind::Cloud);
        RNG rng(5, 6);
        int inBetween = 0;
        double maxErr = 0;
        for (int i = 0; i < 400; ++i) {
            // Medium-space points in [-1, 2] x [-0.3, 1.3] x [-1, 1].
            double x = -1 + 3 * rng.Uniform<Float>(), y = -0.3 + 1.6 * rng.Uniform<Float>(), z = -1 + 2 * rng.Uniform<Float>();
            Vec3f pRender(Float(1 + 2 * x), Float(y), Float(3 + z));
            double ref = ReferenceCloudDensity(x, y, z, c.density, c.wispiness, c.frequency);
            MediumProperties mp = SampleMediumPoint(s, m, pRender, lambda);
            maxErr = std::max({maxErr, std::abs(mp.sigmaA[0] - c.sigmaA * ref), std::abs(mp.sigmaS[2] - c.sigmaS * ref) / c.sigmaS});
            EXPECT_TRUE(mp.Le.IsBlack());
            if (ref > 0.01 && ref < 0.99) ++inBetween;
            if (y <= 0) { EXPECT_FLOAT_EQ(mp.sigmaS[0], Float(c.sigmaS)); }   // dense below y = 0
        }
        EXPECT_LT(maxErr, 1e-3);   // float vs double lookups, amplified up to 13x by the octaves and the 4.5 density
        EXPECT_GT(inBetween, 40);   // the points exercise the noise, not only the clamps
        // The majorant is sigma_t over the medium's box, as pbrt-v4's (one segment).
        Ray ray;
        ray.o = Vec3f(-5, 0.4f, 3.2f);
        ray.d = Vec3f(1, 0, 0);
        MajorantIterator it = MediumMajorants(s, m, ray, 100, lambda);
        MajorantSegment seg;
        Bounds3f b = m.bounds;
        ASSERT_TRUE(it.Next(s, &seg));
        EXPECT_NEAR(seg.tMin, 5 + 1 + 2 * b.pMin.x, 1e-4);
        EXPECT_NEAR(seg.tMax, 5 + 1 + 2 * b.pMax.x, 1e-4);
        EXPECT_NEAR(seg.sigmaMaj[0], c.sigmaA + c.sigmaS, 1e-5);
        EXPECT_FALSE(it.Next(s, &seg));
    }
}

TEST(MediaTransmittance, CloudMatchesQuadrature) {
    auto hs = LoadSceneText("media_cloud_tr", CloudScene("Rotate 30 0 0 1\n",
                                                         "\"float density\" 2 \"spectrum sigma_a\" [ 360 0.5 830 0.5 ] "
                                                         "\"spectrum sigma_s\" [ 360 1.5 830 1.5 ] \"float frequency\" 3"));
    SceneView s = hs->View();
    const Medium &m = s.media[0];
    Ray ray;
    ray.o = Vec3f(-0.5f, 0.3f, 0.2f);
    ray.d = Normalize(Vec3f(1.3f, 0.35f, 0.5f));
    Float tMax = 3;
    double depth = 0;
    const int N = 100000;
    for (int i = 0; i < N; ++i) {
        Float t = (i + 0.5f) * tMax / N;
        Vec3f pm = m.renderFromMedium.Inverted().ApplyPoint(ray(t));
        bool inside = pm.x >= 0 && pm.x <= 1 && pm.y >= 0 && pm.y <= 1 && pm.z >= 0 && pm.z <= 1;
        if (inside) depth += 2 * CloudDensity(m, pm) * tMax / N;
    }
    ASSERT_GT(depth, 0.3);
    double expected = std::exp(-depth);
    TrEstimate e = EstimateTransmittance(*hs, ray, tMax, 40000);
    EXPECT_NEAR(e.ratio, expected, 4 * e.ratioSE + 2e-4) << "ratio tracking";
    EXPECT_NEAR(e.delta, expected, 4 * e.deltaSE + 2e-4) << "delta tracking";
    EXPECT_GT(std::abs(e.ratio - std::exp(-1.03 * depth)), 4 * e.ratioSE);   // a 3% error is seen
}

// ---- Rendered: Beer-Lambert, the inside/outside convention, estimator agreement ----

namespace {

// A camera at z = -4 looking down +z through MIDDLE at a two-sided emitter of radiance 1 at z = 3.
std::string EmitterBehind(const std::string &media, const std::string &middle, double fov) {
    return media + "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ " + std::to_string(fov) +
           " ]\nFilm \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\nPixelFilter \"box\"\n"
           "Sampler \"zsobol\" \"integer pixelsamples\" [ 64 ]\nIntegrator \"path\" \"integer maxdepth\" [ 20 ]\n"
           "WorldBegin\n" + middle +
           "AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n"
           "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"bool twosided\" true\n"
           "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -9 -9 3  9 -9 3  9 9 3  -9 9 3 ]\n"
           "AttributeEnd\n";
}

// Mean over the image of exp(-sigma * length(pixel-center ray)) for a camera at z = -4 with a
// square film and this fov, where length(dir) is the path length inside the absorber.
template <typename F>
double ExpectedMean(double fov, F length) {
    double s = std::tan(fov * 3.14159265358979 / 360), sum = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            double px = (2 * (x + 0.5) / 16 - 1) * s, py = (2 * (y + 0.5) / 16 - 1) * s;
            double n = std::sqrt(px * px + py * py + 1);
            sum += length(px / n, py / n, 1 / n);
        }
    return sum / 256;
}

MeanSE RenderMean(const std::string &name, const std::string &text, int strategy = 0, int spp = 64, uint32_t seed = 3) {
    auto scene = LoadSceneText(name, text);
    RenderResultForTest r = RenderScene(*scene, spp, scene->settings.maxDepth, seed, 0, strategy);
    EXPECT_EQ(r.stats.rejected, 0u);
    return RegionMean(r.image, 1, 0, 0, r.image.width, r.image.height);
}

const char *kAbsorber = "MakeNamedMedium \"ink\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.7 0.7 0.7 ] "
                        "\"rgb sigma_s\" [ 0 0 0 ]\n";

}  // namespace

TEST(MediaRender, SlabIsBeerLambert) {
    // Two interface quads bound a slab z in [0, 1] filled with ink (their normals point out).
    std::string slab =
        "AttributeBegin\nMaterial \"interface\"\nMediumInterface \"ink\" \"\"\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -9 -9 0  9 -9 0  9 9 0  -9 9 0 ] "
        "\"normal N\" [ 0 0 -1  0 0 -1  0 0 -1  0 0 -1 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -9 -9 1  9 -9 1  9 9 1  -9 9 1 ] "
        "\"normal N\" [ 0 0 1  0 0 1  0 0 1  0 0 1 ]\nAttributeEnd\n";
    double fov = 30;
    double expected = ExpectedMean(fov, [](double, double, double dz) { return std::exp(-0.7 / dz); });
    MeanSE m = RenderMean("media_slab", EmitterBehind(kAbsorber, slab, fov));
    EXPECT_NEAR(m.mean, expected, 4 * m.se + 0.004) << "se " << m.se;
    EXPECT_GT(std::abs(m.mean - std::exp(-0.7 * 1.05)), 4 * m.se + 0.004);   // can fail
}

TEST(MediaRender, InsideAndOutsideFollowPbrtV4) {
    // A sphere of ink (radius 0.6): inside is the side away from the (outward) normal; ReverseOrientation
    // flips the normal and so the sides; "" "ink" without it puts the ink outside the sphere,
    // between it and the emitter (the camera's ray starts in vacuum).
    double fov = 6;
    auto chord = [](double /*dx*/, double /*dy*/, double dz) {   // ray from (0,0,-4) through the sphere
        double b = 4 * dz, c = 16 - 0.36, disc = b * b - c;
        return disc > 0 ? 2 * std::sqrt(disc) : 0.0;
    };
    auto exitToEmitter = [&](double /*dx*/, double /*dy*/, double dz) {   // from the sphere's far side to z = 3
        double b = 4 * dz, disc = b * b - (16 - 0.36);
        if (disc <= 0) return 0.0;
        double tExit = b + std::sqrt(disc), tEmit = 7 / dz;
        return tEmit - tExit;
    };
    double inside = ExpectedMean(fov, [&](double x, double y, double z) { return std::exp(-0.7 * chord(x, y, z)); });
    double outside = ExpectedMean(fov, [&](double x, double y, double z) { return std::exp(-0.7 * exitToEmitter(x, y, z)); });
    auto sphere = [](const std::string &pre) {
        return "AttributeBegin\nMaterial \"interface\"\n" + pre + "Shape \"sphere\" \"float radius\" [ 0.6 ]\nAttributeEnd\n";
    };
    MeanSE a = RenderMean("media_inside", EmitterBehind(kAbsorber, sphere("MediumInterface \"ink\" \"\"\n"), fov));
    MeanSE b = RenderMean("media_reversed", EmitterBehind(kAbsorber, sphere("ReverseOrientation\nMediumInterface \"\" \"ink\"\n"), fov));
    MeanSE c = RenderMean("media_outside", EmitterBehind(kAbsorber, sphere("MediumInterface \"\" \"ink\"\n"), fov));
    EXPECT_NEAR(a.mean, inside, 4 * a.se + 0.004);
    EXPECT_NEAR(b.mean, inside, 4 * b.se + 0.004);
    EXPECT_NEAR(c.mean, outside, 4 * c.se + 0.004);
    EXPECT_GT(std::abs(inside - outside), 0.1);
}

// NEE only, BSDF/phase sampling only and MIS agree through chromatic media: a homogeneous fog
// box and a heterogeneous grid around a diffuse floor under an area light (ratio tracking and
// spectral weights on one side, delta tracking on the other).
TEST(MediaRender, EstimatorsAgreeInChromaticMedia) {
    std::string header =
        "LookAt 0 2.5 -4  0 0.3 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 45 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\nPixelFilter \"box\"\n"
        "Sampler \"zsobol\"\nIntegrator \"path\" \"integer maxdepth\" [ 6 ]\n";
    std::string world =
        "WorldBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0.6 0.5 0.4 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -3 0 -3  3 0 -3  3 0 3  -3 0 3 ]\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 6 6 6 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ -0.5 2 -0.5  0.5 2 -0.5  0.5 2 0.5  -0.5 2 0.5 ]\n"
        "AttributeEnd\n"
        "AttributeBegin\nMaterial \"interface\"\nMediumInterface \"fog\" \"\"\nTranslate 0 0.8 0\n"
        "Shape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n";
    std::vector<std::string> media = {
        "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.1 0.3 0.6 ] "
        "\"rgb sigma_s\" [ 1.2 0.6 0.2 ] \"float g\" [ 0.3 ]\n",
        "MakeNamedMedium \"fog\" \"string type\" \"uniformgrid\" \"integer nx\" [ 2 ] \"integer ny\" [ 2 ] \"integer nz\" [ 2 ] "
        "\"float density\" [ 0.2 1.5 0.7 2 0 1 1.3 0.4 ] \"rgb sigma_a\" [ 0.2 0.4 0.6 ] \"rgb sigma_s\" [ 1 0.5 0.2 ] "
        "\"point3 p0\" [ -1 -0.2 -1 ] \"point3 p1\" [ 1 1.8 1 ]\n"};
    const char *names[3] = {"MIS", "NEE only", "BSDF only"};
    for (const std::string &m : media) {
        SCOPED_TRACE(m);
        auto scene = LoadSceneText("media_strategies", m + header + world);
        double mean[3][3], se[3][3];
        for (int s = 0; s < 3; ++s) {
            auto r = RenderScene(*scene, s == 2 ? 1024 : 256, 6, 11, 0, s);
            EXPECT_EQ(r.stats.rejected, 0u);
            for (int c = 0; c < 3; ++c) {
                MeanSE q = RegionMean(r.image, c, 0, 0, 16, 16);
                mean[s][c] = q.mean;
                se[s][c] = q.se;
            }
        }
        for (int s = 1; s < 3; ++s)
            for (int c = 0; c < 3; ++c) {
                double z = (mean[s][c] - mean[0][c]) / std::sqrt(se[s][c] * se[s][c] + se[0][c] * se[0][c]);
                EXPECT_LT(std::abs(z), 4.0) << names[s] << " vs MIS, channel " << c << ": " << mean[s][c] << " vs " << mean[0][c];
            }
        EXPECT_GT(mean[0][0], 0.01);
    }
}

}  // namespace lu::test
