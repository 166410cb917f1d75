// Lucerna: the collimated beam light (lights/collimated.h), regularized at the light. A beam
// normal to a diffuse plane must deposit its power there (radiance albedo / pi times the beam's
// irradiance), with a spot blur whose second moment is the cone kernel's and shrinks with N;
// plain path tracing cannot reach the beam; the profile normalizes to "power"; bad parameters
// are located errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrators/render_helpers.h"
#include "lucerna/lights/collimated.h"
#include "lucerna/lights/light_sampler.h"
#include "lucerna/scene/light_build.h"
#include "lucerna/spectra/registry.h"

namespace lu::test {

namespace {

constexpr double kR = 0.1, kD = 1.0, kP = 2.0, kAlbedo = 0.5, kSigma0 = 0.2;
constexpr int kRes = 64;   // the film covers [-0.5, 0.5]^2 of the plane

// A beam of radius kR at height kD pointing down onto a diffuse plane at z = 0, seen from above
// by an orthographic camera (box filter: a pixel is the mean radiance over its square). The
// beam's spectrum and the albedo are constant, so the image's Y is the radiance per nm.
std::string BeamSceneWith(const std::string &aperture, const std::string &profile, const std::string &lightCtm = "") {
    char buf[2048];
    std::snprintf(buf, sizeof(buf), R"(
LookAt 0 0 2  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [-0.5 0.5 -0.5 0.5]
Film "rgb" "integer xresolution" %d "integer yresolution" %d "string filename" "x.exr"
PixelFilter "box"
Sampler "independent"
WorldBegin
AttributeBegin
%s
LightSource "collimated" "point3 from" [0 0 %g] "point3 to" [0 0 0] %s %s
    "spectrum E" [360 1 830 1] "float power" %g
AttributeEnd
Material "diffuse" "spectrum reflectance" [360 %g 830 %g]
Shape "trianglemesh" "integer indices" [0 1 2 0 2 3] "point3 P" [-4 -4 0 4 -4 0 4 4 0 -4 4 0]
)", kRes, kRes, lightCtm.c_str(), kD, aperture.c_str(), profile.c_str(), kP, kAlbedo, kAlbedo);
    return buf;
}
std::string BeamScene(const std::string &profile = "\"string profile\" \"uniform\"", double radius = kR) {
    return BeamSceneWith("\"float radius\" " + std::to_string(radius), profile);
}

// The radiance per nm of a pixel whose spectrum is constant: the film's Y is the integral of L
// times CIE y-bar (pbrt-v4's "cie1931" sensor), and y-bar integrates to CIE_Y_integral.
double gYbarIntegral = 0;
double PixelY(const Image &im, int x, int y) {
    XYZ xyz = RGBToXYZ(RGB{im.At(x, y, 0), im.At(x, y, 1), im.At(x, y, 2)});
    return xyz[1] / gYbarIntegral;
}
// Pixel centre on the plane (the sign of the axes does not matter to the moments used here).
double PixelPos(int i) { return -0.5 + (i + 0.5) / kRes; }
constexpr double kPixel = 1.0 / kRes;

// Renders passes [firstPass, firstPass + passes): r_N, sigma_N are those of N = firstPass + 1 ...
Image RenderBeamPasses(const HostScene &scene, bool regularize, uint32_t firstPass, int passes, uint32_t seed,
                       int strategy = 0) {
    RenderSettings settings = TestSettings(scene, int(firstPass) + passes, 1, seed);
    settings.integrator = regularize ? IntegratorKind::RegPath : IntegratorKind::Path;
    settings.regAngle = kSigma0 * 180 / M_PI;
    // These scenes have one kernel per path (no specular surface): the seed's schedule, which
    // PredictedRho2 assumes (scenes with a beam default to 1/8: CollimatedLens tests).
    EXPECT_DOUBLE_EQ(settings.regLambda, 1.0 / 8);
    settings.regLambda = 1.0 / 6;
    settings.lightStrategy = LightStrategy(strategy);
    return RenderFromPass(scene, settings, firstPass);
}

struct SpotMoments {
    double power = 0;    // integral of the radiance over the plane (per nm)
    double rho2 = 0;     // second moment of the spot about the axis
    double xx = 0, yy = 0, xy = 0;   // its second moments in the image's axes
    double centre = 0;   // mean radiance within rho < 0.5 R
};
SpotMoments Moments(const Image &im) {
    SpotMoments m;
    double w = 0, wr = 0, c = 0;
    int nc = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            double v = PixelY(im, x, y), px = PixelPos(x), py = PixelPos(y), r2 = Sqr(px) + Sqr(py);
            w += v;
            wr += v * r2;
            m.xx += v * px * px;
            m.yy += v * py * py;
            m.xy += v * px * py;
            if (r2 < Sqr(0.5 * kR)) { c += v; ++nc; }
        }
    m.power = w * kPixel * kPixel;
    m.rho2 = wr / w;
    m.xx /= w;
    m.yy /= w;
    m.xy /= w;
    m.centre = c / nc;
    return m;
}

// Mean and standard error over independent renders.
struct Stat {
    double mean = 0, se = 0;
};
template <typename F>
Stat OverSeeds(int n, F f) {
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        double v = f(uint32_t(i));
        s += v;
        s2 += v * v;
    }
    Stat st;
    st.mean = s / n;
    st.se = std::sqrt(std::max(0.0, s2 / n - st.mean * st.mean) / (n - 1));
    return st;
}

// The spot's second moment predicted for passes N = first+1 .. first+passes: the disc's R^2 / 2
// plus the kernel's d^2 <tan^2 theta> = d^2 (1 - cos sigma_N) / cos sigma_N (uniform cap), averaged
// over the passes (each deposits the same power), plus a pixel's own spread (2 px^2 / 12).
double PredictedRho2(uint32_t first, int passes) {
    double sum = 0;
    for (int k = 0; k < passes; ++k) {
        double sigma = kSigma0 * std::pow(double(first + k + 1), -1.0 / 6);
        sum += (1 - std::cos(sigma)) / std::cos(sigma);
    }
    return Sqr(kR) / 2 + Sqr(kD) * sum / passes + 2 * Sqr(kPixel) / 12;
}

}  // namespace

// The plane receives the beam's power: integral of L over the plane = albedo / pi * P / 470 nm
// (the radiance of a diffuse plane is albedo / pi times its irradiance; the spectrum is constant
// over 470 nm), early (wide kernel) and late; the centre of the spot has the sharp beam's
// irradiance P / (pi R^2) once the kernel is narrow; the spot's second moment is the kernel's and
// shrinks towards the sharp disc's R^2 / 2 as N grows.
TEST(Collimated, BeamNormalToADiffusePlaneDepositsItsPower) {
    auto scene = LoadSceneText("beam_uniform", BeamScene());
    gYbarIntegral = scene->spectra.ToPhotometric(Spectrum::Const(1));
    EXPECT_NEAR(gYbarIntegral, 106.856895, 0.01);
    const double perNm = kP / 470, power = kAlbedo / M_PI * perNm;
    const double centre = kAlbedo / M_PI * perNm / (M_PI * kR * kR);
    const int seeds = 6, passes = 16;
    const uint32_t late = 1u << 20;
    SpotMoments e[seeds], l[seeds];
    for (int s = 0; s < seeds; ++s) {
        e[s] = Moments(RenderBeamPasses(*scene, true, 0, passes, 7 + s));
        l[s] = Moments(RenderBeamPasses(*scene, true, late, passes, 17 + s));
    }
    Stat ePow = OverSeeds(seeds, [&](uint32_t i) { return e[i].power; });
    Stat lPow = OverSeeds(seeds, [&](uint32_t i) { return l[i].power; });
    Stat eRho = OverSeeds(seeds, [&](uint32_t i) { return e[i].rho2; });
    Stat lRho = OverSeeds(seeds, [&](uint32_t i) { return l[i].rho2; });
    Stat lCen = OverSeeds(seeds, [&](uint32_t i) { return l[i].centre; });
    EXPECT_NEAR(ePow.mean, power, 4 * ePow.se + 0.005 * power) << "se " << ePow.se;
    EXPECT_NEAR(lPow.mean, power, 4 * lPow.se + 0.005 * power) << "se " << lPow.se;
    EXPECT_NEAR(lCen.mean, centre, 4 * lCen.se + 0.01 * centre) << "se " << lCen.se;
    double eRhoPred = PredictedRho2(0, passes), lRhoPred = PredictedRho2(late, passes);
    std::printf("power early %.6g +- %.2g, late %.6g +- %.2g (expected %.6g); centre %.6g +- %.2g (expected %.6g); "
                "rho^2 early %.6g +- %.2g (predicted %.6g), late %.6g +- %.2g (predicted %.6g; sharp %.6g)\n",
                ePow.mean, ePow.se, lPow.mean, lPow.se, power, lCen.mean, lCen.se, centre, eRho.mean, eRho.se, eRhoPred,
                lRho.mean, lRho.se, lRhoPred, Sqr(kR) / 2);
    EXPECT_NEAR(eRho.mean, eRhoPred, 4 * eRho.se + 0.01 * eRhoPred) << "se " << eRho.se;
    EXPECT_NEAR(lRho.mean, lRhoPred, 4 * lRho.se + 0.01 * lRhoPred) << "se " << lRho.se;
    // The bias: early spots are about 3x wider (in rho^2) than the sharp one, late ones within 10%.
    EXPECT_GT(eRho.mean, 2.5 * Sqr(kR) / 2);
    EXPECT_LT(lRho.mean, 1.1 * Sqr(kR) / 2 + 2 * Sqr(kPixel) / 12);
}

// Next-event estimation alone and BSDF sampling alone estimate the same spot (the MIS pair of
// the beam: both pdfs in solid angle at the plane).
TEST(Collimated, ExplicitAndImplicitTechniquesAgree) {
    auto scene = LoadSceneText("beam_techniques", BeamScene());
    gYbarIntegral = scene->spectra.ToPhotometric(Spectrum::Const(1));
    const double power = kAlbedo / M_PI * kP / 470;
    for (int strategy : {1, 2}) {   // LightStrategy::NEEOnly, BSDFOnly
        Stat p = OverSeeds(4, [&](uint32_t s) { return Moments(RenderBeamPasses(*scene, true, 0, 16, 40 + s, strategy)).power; });
        EXPECT_NEAR(p.mean, power, 4 * p.se + 0.005 * power) << "strategy " << strategy << " se " << p.se;
    }
}

// A narrow beam under a wide kernel: R = 0.005 at d = 1 with sigma_N = 0.2 N^(-1/6) rad, the disc
// fills about 0.06% of the cone seen from the plane. The cone technique alone keeps almost no
// sample there; the disc-area technique keeps every one whose emitted direction lies in the cone.
// Next-event estimation alone (their even mixture) deposits the power with a relative standard
// error of 0.0026 over 4 seeds x 16 passes; with the cone technique alone (this test with
// SampleBeamLi and its pdf forced to the cone, when the mixture was added) it was 0.21.
TEST(Collimated, NarrowBeamUnderAWideKernelIsSampledThroughTheDisc) {
    auto scene = LoadSceneText("beam_narrow", BeamScene("\"string profile\" \"uniform\"", 0.005));
    gYbarIntegral = scene->spectra.ToPhotometric(Spectrum::Const(1));
    const double power = kAlbedo / M_PI * kP / 470;
    for (int strategy : {0, 1}) {   // LightStrategy::MIS, NEEOnly
        Stat p = OverSeeds(4, [&](uint32_t s) { return Moments(RenderBeamPasses(*scene, true, 0, 16, 80 + s, strategy)).power; });
        std::printf("strategy %d: power %.6g +- %.2g (expected %.6g), relative se %.3g\n", strategy, p.mean, p.se, power,
                    p.se / power);
        EXPECT_NEAR(p.mean, power, 4 * p.se + 0.005 * power) << "strategy " << strategy << " se " << p.se;
        EXPECT_LT(p.se, 0.03 * power) << "strategy " << strategy;
    }
}

// A weak beam next to a strong lamp: the narrow beam above beside a point light of 1000 W under
// the plane (it lights the far side only). By power alone the beam would get a pmf of 2e-3 and
// its spot, which only next-event estimation finds, a few samples per pass; the selection's beam
// share gives it half of them, and the spot converges as it does alone.
TEST(Collimated, WeakBeamBesideAStrongLampKeepsItsLightSamples) {
    auto scene = LoadSceneText("beam_weak", BeamSceneWith("\"float radius\" 0.005", "",
                                                          "LightSource \"point\" \"point3 from\" [0 0 -1] \"float power\" 1000"));
    gYbarIntegral = scene->spectra.ToPhotometric(Spectrum::Const(1));
    ASSERT_EQ(scene->lights.size(), 2u);
    const SceneView view = scene->View();
    uint32_t beam = scene->lights[0].kind == LightKind::Collimated ? 0 : 1;
    double beamPower = LightPower(scene->lights[beam], view), lampPower = LightPower(scene->lights[1 - beam], view);
    EXPECT_GT(lampPower, 100 * beamPower);
    double byPower = beamPower / (beamPower + lampPower);
    EXPECT_NEAR(LightPMF(view, beam), kBeamSelectionShare + (1 - kBeamSelectionShare) * byPower, 1e-6);
    EXPECT_NEAR(LightPMF(view, 1 - beam), (1 - kBeamSelectionShare) * (1 - byPower), 1e-6);
    const double power = kAlbedo / M_PI * kP / 470;
    Stat p = OverSeeds(4, [&](uint32_t s) { return Moments(RenderBeamPasses(*scene, true, 0, 16, 120 + s)).power; });
    std::printf("weak beam: power %.6g +- %.2g (expected %.6g), relative se %.3g; pmf by power %.3g\n", p.mean, p.se, power,
                p.se / power, byPower);
    EXPECT_NEAR(p.mean, power, 4 * p.se + 0.005 * power) << "se " << p.se;
    EXPECT_LT(p.se, 0.03 * power);
}

// Plain path tracing never reaches the beam: black.
TEST(Collimated, PathRendersTheBeamBlack) {
    auto scene = LoadSceneText("beam_path", BeamScene());
    gYbarIntegral = scene->spectra.ToPhotometric(Spectrum::Const(1));
    Image im = RenderBeamPasses(*scene, false, 0, 4, 1);
    EXPECT_EQ(Moments(im).power, 0.0);
}

// The gaussian profile (waist w, truncated at R) deposits the same power, and it is more
// concentrated: its second moment is the truncated gaussian's plus the kernel's.
TEST(Collimated, GaussianProfileNormalizesToPower) {
    const double w = 0.06;
    char prof[128];
    std::snprintf(prof, sizeof(prof), "\"string profile\" \"gaussian\" \"float waist\" %g", w);
    auto scene = LoadSceneText("beam_gauss", BeamScene(prof));
    gYbarIntegral = scene->spectra.ToPhotometric(Spectrum::Const(1));
    // The light's own numbers: the integral of E over wavelength and disc is P (host quadrature).
    const Light &l = scene->lights[0];
    ASSERT_EQ(l.kind, LightKind::Collimated);
    double integral = 0;
    const int n = 400;
    for (int i = 0; i < n; ++i) {
        double rho = (i + 0.5) / n * kR;
        double e = 0;
        for (int lam = 360; lam <= 830; ++lam)
            e += (lam == 360 || lam == 830 ? 0.5 : 1.0) * scene->spectra.Eval(l.spectrum, Float(lam));
        integral += e * l.scale * BeamProfile(l, Vec2f(Float(rho), 0)) * 2 * M_PI * rho * (kR / n);
    }
    EXPECT_NEAR(integral, kP, 1e-3 * kP);
    // Light selection sees the same power (LightPhi at the sampled wavelengths).
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.3f);
    SampledSpectrum phi = LightPhi(l, scene->View(), lambda);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(phi[i], kP / 470, 1e-3 * kP / 470);
    EXPECT_NEAR(LightPower(l, scene->View()), kP, 1e-3 * kP);
    // Through the renderer.
    const double power = kAlbedo / M_PI * kP / 470;
    SpotMoments m[4];
    for (int s = 0; s < 4; ++s) m[s] = Moments(RenderBeamPasses(*scene, true, 1u << 20, 16, 60 + s));
    Stat p = OverSeeds(4, [&](uint32_t i) { return m[i].power; });
    Stat r = OverSeeds(4, [&](uint32_t i) { return m[i].rho2; });
    EXPECT_NEAR(p.mean, power, 4 * p.se + 0.005 * power) << "se " << p.se;
    // <rho^2> of exp(-2 rho^2 / w^2) truncated at R: w^2 / 2 - R^2 e^(-a) / (1 - e^(-a)), a = 2 R^2 / w^2.
    double a = 2 * kR * kR / (w * w);
    double gauss = w * w / 2 - kR * kR * std::exp(-a) / (1 - std::exp(-a));
    double pred = gauss + (PredictedRho2(1u << 20, 16) - Sqr(kR) / 2);
    EXPECT_NEAR(r.mean, pred, 4 * r.se + 0.01 * pred) << "se " << r.se;
}

// A rectangular aperture, 0.3 x 0.1 turned 30 degrees about the beam, deposits its power in its
// own shape: late, the spot's second-moment matrix is the uniform rectangle's, R diag(a^2, b^2) R^T
// / 3 (a, b the half sizes), plus the kernel's isotropic blur (half of d^2 <tan^2 theta> per axis)
// and a pixel's spread. A disc, or the rectangle unturned, would fail the off-diagonal term.
TEST(Collimated, RectangleApertureDepositsItsPowerInItsShape) {
    const double a = 0.15, b = 0.05, turn = 30 * M_PI / 180;
    auto scene = LoadSceneText("beam_rect", BeamSceneWith("\"string aperture\" \"rect\" \"float width\" 0.3 \"float height\" 0.1",
                                                          "", "Rotate 30 0 0 1"));
    gYbarIntegral = scene->spectra.ToPhotometric(Spectrum::Const(1));
    const Light &l = scene->lights[0];
    ASSERT_TRUE(BeamIsRectangle(l));
    EXPECT_NEAR(l.beamRadius, std::sqrt(a * a + b * b), 1e-6);
    EXPECT_NEAR(LightPower(l, scene->View()), kP, 1e-3 * kP);
    const double power = kAlbedo / M_PI * kP / 470;
    const uint32_t late = 1u << 20;
    SpotMoments m[4];
    for (int s = 0; s < 4; ++s) m[s] = Moments(RenderBeamPasses(*scene, true, late, 16, 90 + s));
    Stat p = OverSeeds(4, [&](uint32_t i) { return m[i].power; });
    Stat xx = OverSeeds(4, [&](uint32_t i) { return m[i].xx; });
    Stat yy = OverSeeds(4, [&](uint32_t i) { return m[i].yy; });
    Stat xy = OverSeeds(4, [&](uint32_t i) { return m[i].xy; });
    EXPECT_NEAR(p.mean, power, 4 * p.se + 0.005 * power) << "se " << p.se;
    double blur = (PredictedRho2(late, 16) - Sqr(kR) / 2) / 2;   // per axis: kernel and pixel
    double c = std::cos(turn), sn = std::sin(turn), A = a * a / 3, B = b * b / 3;
    double pxx = c * c * A + sn * sn * B + blur, pyy = sn * sn * A + c * c * B + blur, pxy = c * sn * (A - B);
    std::printf("rectangle: power %.6g +- %.2g (expected %.6g); xx %.6g (%.6g) yy %.6g (%.6g) xy %.6g (%.6g)\n", p.mean,
                p.se, power, xx.mean, pxx, yy.mean, pyy, xy.mean, pxy);
    // The image's y axis may run either way (PixelPos): compare |xy|.
    EXPECT_NEAR(xx.mean, pxx, 4 * xx.se + 0.01 * pxx);
    EXPECT_NEAR(yy.mean, pyy, 4 * yy.se + 0.01 * pyy);
    EXPECT_NEAR(std::abs(xy.mean), pxy, 4 * xy.se + 0.01 * pxy);
}

// A gaussian profile on a rectangle integrates (wavelengths x aperture) to the power; the light's
// profile integral is the separable erf product, checked by quadrature over the rectangle.
TEST(Collimated, GaussianRectangleNormalizesToPower) {
    auto scene = LoadSceneText("beam_rect_gauss", BeamSceneWith("\"string aperture\" \"rect\" \"float width\" 0.2 "
                                                                "\"float height\" 0.08",
                                                                "\"string profile\" \"gaussian\" \"float waist\" 0.05"));
    gYbarIntegral = scene->spectra.ToPhotometric(Spectrum::Const(1));
    const Light &l = scene->lights[0];
    double q = 0;
    const int n = 400;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Vec2f xy(Float(((i + 0.5) / n - 0.5) * 0.2), Float(((j + 0.5) / n - 0.5) * 0.08));
            q += BeamProfile(l, xy) * (0.2 / n) * (0.08 / n);
        }
    EXPECT_NEAR(BeamProfileIntegral(l), q, 1e-4 * q);
    EXPECT_EQ(BeamProfile(l, Vec2f(0.099f, 0.039f)) > 0, true);
    EXPECT_EQ(BeamProfile(l, Vec2f(0.101f, 0)), 0);
    EXPECT_EQ(BeamProfile(l, Vec2f(0, 0.041f)), 0);
    EXPECT_NEAR(LightPower(l, scene->View()), kP, 1e-3 * kP);
    const double power = kAlbedo / M_PI * kP / 470;
    Stat p = OverSeeds(4, [&](uint32_t s) { return Moments(RenderBeamPasses(*scene, true, 1u << 20, 16, 70 + s)).power; });
    EXPECT_NEAR(p.mean, power, 4 * p.se + 0.005 * power) << "se " << p.se;
}

// The beam techniques in media partition the medium points by the beam's region (a function of
// the point, InBeamRegion); the segment technique samples a ray's crossing of it
// (BeamRegionInterval). The two must agree: along 2000 random rays, every point strictly inside
// the interval is in the region and every point outside it is not (a margin of 1e-4 of the
// interval's scale at its ends), for a kernel of 0.2 rad, and for one of 90 degrees (an infinite
// radius: the axial slab alone).
TEST(Collimated, BeamRegionIntervalMatchesTheRegion) {
    auto scene = LoadSceneText("beam_region", BeamScene());
    const Light &l = scene->lights[0];
    ASSERT_GT(BeamReach(l), kD);
    RNG rng(7, 11);
    for (Float omc : {OneMinusCosAngle(Float(0.2)), Float(1)}) {
        Float rc = BeamRegionRadius(l, omc);
        if (omc == 1) {
            EXPECT_EQ(rc, Infinity);
        }
        int crossed = 0, bad = 0;
        for (int i = 0; i < 2000; ++i) {
            Vec3f o(rng.Uniform<Float>() * 4 - 2, rng.Uniform<Float>() * 4 - 2, rng.Uniform<Float>() * 4 - 2);
            Vec3f d = Normalize(Vec3f(rng.Uniform<Float>() - 0.5f, rng.Uniform<Float>() - 0.5f, rng.Uniform<Float>() - 0.5f));
            Float tMax = rng.Uniform<Float>() * 6, t0 = -1, t1 = -1;
            bool any = BeamRegionInterval(l, o, d, tMax, rc, &t0, &t1);
            crossed += any;
            for (int k = 0; k <= 200; ++k) {
                Float t = tMax * k / 200;
                bool in = InBeamRegion(l, o + d * t, rc);
                Float margin = 1e-4f * (1 + tMax);
                if (any && t > t0 + margin && t < t1 - margin) bad += !in;
                if ((!any || t < t0 - margin || t > t1 + margin) && t > 0) bad += in;
            }
        }
        EXPECT_EQ(bad, 0) << "1 - cos sigma " << omc;
        EXPECT_GT(crossed, 100) << "1 - cos sigma " << omc;   // the test sees both cases
        EXPECT_LT(crossed, 1900) << "1 - cos sigma " << omc;
    }
}

// Bad parameters: a located error (the parameter's position), and nothing built.
TEST(Collimated, BadParametersAreLocatedErrors) {
    struct Case {
        const char *params, *message;
    } cases[] = {
        {"\"float radius\" -1", "\"radius\" must be positive"},
        {"\"float radius\" 0", "\"radius\" must be positive"},
        {"\"string profile\" \"gaussian\" \"float waist\" 0", "\"waist\" must be positive"},
        {"\"string profile\" \"gaussian\" \"float waist\" -2", "\"waist\" must be positive"},
        {"\"float waist\" 0.1", "\"waist\" applies to the \"gaussian\" profile only"},
        {"\"string profile\" \"tophat\"", "unknown \"profile\" \"tophat\""},
        {"\"float wavelength\" 1064", "\"wavelength\" must be in [360, 830] nm"},
        {"\"float wavelength\" 300", "\"wavelength\" must be in [360, 830] nm"},
        {"\"float wavelength\" 532 \"float bandwidth\" 0.1", "\"bandwidth\" (full width at half maximum) must be in [1, 470]"},
        {"\"float bandwidth\" 2", "\"bandwidth\" needs \"wavelength\""},
        {"\"float wavelength\" 532 \"blackbody E\" 3000", "give either \"E\" or \"wavelength\""},
        {"\"float power\" 0", "\"power\" must be positive"},
        {"\"float scale\" -1", "\"scale\" must not be negative"},
        {"\"point3 from\" [0 0 1] \"point3 to\" [0 0 1]", "\"from\" and \"to\" must differ"},
        {"\"string aperture\" \"square\"", "unknown \"aperture\" \"square\""},
        {"\"string aperture\" \"rect\" \"float width\" 0", "\"width\" must be positive"},
        {"\"string aperture\" \"rect\" \"float height\" -1", "\"height\" must be positive"},
        {"\"string aperture\" \"rect\" \"float radius\" 0.1", "\"radius\" applies to the \"disc\" aperture only"},
        {"\"float width\" 0.1", "\"width\" applies to the \"rect\" aperture only"},
    };
    for (const Case &c : cases) {
        std::string text = std::string("WorldBegin\nLightSource \"collimated\"\n    ") + c.params + "\n";
        try {
            LoadSceneText("beam_bad", text);
            ADD_FAILURE() << "accepted: " << c.params;
        } catch (const SceneError &e) {
            EXPECT_NE(e.Message().find(c.message), std::string::npos) << c.params << ": " << e.Message();
            EXPECT_EQ(e.Loc().line, 3) << c.params << ": " << e.Format();   // at the parameter
            EXPECT_GT(e.Loc().col, 4) << c.params << ": " << e.Format();
        }
    }
    // A non-uniform scale would make the disc an ellipse.
    try {
        LoadSceneText("beam_bad", "WorldBegin\nScale 1 2 1\nLightSource \"collimated\"\n");
        ADD_FAILURE() << "accepted a non-uniform scale";
    } catch (const SceneError &e) {
        EXPECT_NE(e.Message().find("scales the aperture unevenly"), std::string::npos) << e.Message();
        EXPECT_EQ(e.Loc().line, 3);
    }
    // A laser line of 532 nm, and a uniform scale (the radius scales with it).
    auto ok = LoadSceneText("beam_ok", "WorldBegin\nScale 2 2 2\nLightSource \"collimated\" \"float wavelength\" 532 "
                                       "\"float radius\" 0.01 \"float power\" 1\n");
    ASSERT_EQ(ok->lights.size(), 1u);
    const Light &l = ok->lights[0];
    EXPECT_NEAR(l.beamRadius, 0.02, 1e-7);
    EXPECT_GT(ok->spectra.Eval(l.spectrum, 532), 100 * ok->spectra.Eval(l.spectrum, 540));
    EXPECT_NEAR(ok->spectra.Eval(l.spectrum, 533) / ok->spectra.Eval(l.spectrum, 532), 0.0625, 1e-3);   // FWHM 1 nm: 2^-4 at 1 nm
    // The light sampler's power of the 1 nm line is its 1 W, not what four wavelengths happen to see.
    EXPECT_NEAR(LightPower(l, ok->View()), 1.0, 1e-3);
    // What `lucerna info` lists for it (render-space sizes).
    ASSERT_EQ(ok->stats.lightProfiles.size(), 1u);
    EXPECT_EQ(ok->stats.lightProfiles[0], "light 0: collimated disc radius 0.02, uniform, 532 nm line (1 nm wide), 1 W");
}

}  // namespace lu::test
