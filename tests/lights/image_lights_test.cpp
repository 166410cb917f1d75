// Tests of the two image lights of pbrt-v4: LightSource "projection" (irradiance on a plane from
// the texel each direction projects to, the image's orientation, zero outside the frustum and
// behind, "power" as luminous flux by numerical integration, Phi for the light sampler) and
// AreaLightSource "diffuse" with "filename" (radiance per uv against the bilinear lookup at
// (u, 1 - v), "power" and Phi with the image's mean).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "lucerna/image/image.h"
#include "lucerna/lights/lights.h"
#include "lucerna/scene/builder.h"
#include "lucerna/scene/light_build.h"
#include "lucerna/spectra/cie_data.h"
#include "lucerna/spectra/registry.h"
#include "support/test_support.h"

namespace lu {
namespace {

constexpr double kPi = 3.14159265358979323846;

const char *kHeader = "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
                      "Camera \"perspective\"\nWorldBegin\n";

// Writes scene.pbrt (kHeader + world: the world starts on line 4) in dir and loads it.
std::unique_ptr<HostScene> Load(const std::string &dir, const std::string &world) {
    std::ofstream(dir + "/scene.pbrt", std::ios::binary) << kHeader << world;
    Diagnostics diag;
    diag.quiet = true;
    return LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
}

// A synthetic RGB image whose texels all differ: (0.2 + x / w, 0.3 + y / h, 0.4 + ((x + 3 y) % 7) / 7).
Float TexelValue(int w, int h, int x, int y, int c) {
    if (c == 0) return Float(0.2 + double(x) / w);
    if (c == 1) return Float(0.3 + double(y) / h);
    return Float(0.4 + double((x + 3 * y) % 7) / 7);
}
void WriteSynthetic(const std::string &path, int w, int h) {
    Image img = MakeImage(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.At(x, y, c) = float(TexelValue(w, h, x, y, c));
    WriteEXR(path, img);
}

// Wavelengths 360 + 5 k nm, four at a time (pdfs 1: unused here).
SampledWavelengths Wavelengths(int first) {
    SampledWavelengths w;
    for (int i = 0; i < NSpectrumSamples; ++i) {
        w.lambda[i] = Float(std::min(360 + 5 * (first + i), 830));
        w.pdf[i] = 1;
    }
    return w;
}
constexpr int kWavelengthSteps = 95;   // 360..830 nm in 5 nm steps

// Luminance (the Y integral, as pbrt-v4's SpectrumToPhotometric: lights of "scale" 1 carry
// 1 / SpectrumToPhotometric) of a spectral function f given four wavelengths at a time; 5 nm
// rectangle rule.
template <typename F>
double Luminance(F f) {
    double y = 0;
    for (int k = 0; k < kWavelengthSteps; k += NSpectrumSamples) {
        SampledWavelengths w = Wavelengths(k);
        SampledSpectrum v = f(w);
        for (int i = 0; i < NSpectrumSamples && k + i < kWavelengthSteps; ++i)
            y += double(v[i]) * data::CIE_Y[int(w.lambda[i]) - 360] * 5;
    }
    return y;
}

// Radiance (L, per the light's scale) that SampleLi returns at p from light 0, or 0 when none.
SampledSpectrum LightLi(const HostScene &s, Vec3f p, Vec3f n, const SampledWavelengths &lambda, Vec3f *wi = nullptr) {
    SceneView v = s.View();
    LightSampleContext ctx{p, n, n};
    LightLiSample ls;
    if (!SampleLi(v.lights[0], v, ctx, Vec2f(0.5f, 0.5f), lambda, &ls)) return SampledSpectrum(0);
    EXPECT_TRUE(ls.isDelta);
    if (wi) *wi = ls.wi;
    return ls.L;
}

// ---- Projection ----

constexpr int kW = 48, kH = 32;   // aspect 1.5: the screen window is [-1.5, 1.5] x [-1, 1]

// The texel pbrt-v4 projects towards p (CTM space, the light at the origin looking down +z): its
// screen point is (x, -y) / (z tan(fov / 2)) (pbrt-v4 flips y so that the image's top row, row 0,
// is at +y), column 0 at the window's -x edge.
bool ExpectedTexel(Vec3f p, double tanHalf, int *col, int *row) {
    if (p.z <= 0) return false;
    double sx = p.x / (p.z * tanHalf), sy = -p.y / (p.z * tanHalf);
    if (std::abs(sx) > 1.5 || std::abs(sy) > 1) return false;
    *col = std::min(kW - 1, int((sx + 1.5) / 3 * kW));
    *row = std::min(kH - 1, int((sy + 1) / 2 * kH));
    return true;
}

TEST(ProjectionLight, IrradianceOnAPlaneFromEachTexel) {
    std::string dir = test::TempDir("projection_plane");
    WriteSynthetic(dir + "/slide.exr", kW, kH);
    auto s = Load(dir, "LightSource \"projection\" \"string filename\" \"slide.exr\" \"float fov\" 60 \"float scale\" 3\n");
    ASSERT_EQ(s->lights.size(), 1u);
    const Light &l = s->lights[0];
    EXPECT_EQ(l.kind, LightKind::Projection);
    EXPECT_NEAR(l.scale * CIE_Y_integral, 3, 3e-3);   // scale / SpectrumToPhotometric(illuminant)
    SceneView v = s->View();
    double tanHalf = std::tan(kPi / 6);
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.31f);
    // The plane z = 2 facing the light: E = I(w) cos / d^2 with I the texel's illuminant
    // spectrum times scale, at points across the whole window.
    int checked = 0, corners = 0;
    for (double X = -2.1 + 0.0123; X <= 2.1; X += 0.07)   // offsets: no point on a texel edge
        for (double Y = -1.5 + 0.0071; Y <= 1.5; Y += 0.05) {
            Vec3f p(Float(X), Float(Y), 2);
            int col, row;
            Vec3f wi;
            SampledSpectrum L = LightLi(*s, p, Vec3f(0, 0, -1), lambda, &wi);
            if (!ExpectedTexel(p, tanHalf, &col, &row)) {
                EXPECT_TRUE(L.IsBlack()) << X << " " << Y;
                continue;
            }
            double d2 = X * X + Y * Y + 4, cosT = 2 / std::sqrt(d2);
            Float rgb[3] = {TexelValue(kW, kH, col, row, 0), TexelValue(kW, kH, col, row, 1), TexelValue(kW, kH, col, row, 2)};
            SampledSpectrum I = SampleSpectrum(RGBIlluminantSpectrum(v, rgb), lambda, v.spectra) * l.scale;
            double E = double(L[0]) * double(Dot(wi, Vec3f(0, 0, -1)));   // wi: towards the light
            EXPECT_NEAR(E, double(I[0]) * cosT / d2, 1e-4 * double(I[0]) * cosT / d2) << X << " " << Y;
            EXPECT_NEAR(L[2], I[2] / Float(d2), 1e-4f * I[2] / Float(d2));
            ++checked;
            corners += (col == 0 && row == 0) || (col == kW - 1 && row == kH - 1);
        }
    EXPECT_GT(checked, 2000);
    EXPECT_GT(corners, 0);
    // Orientation, explicitly: the image's top-left texel (row 0, column 0) lights -x, +y; its
    // bottom-right one +x, -y (a distinct value per texel tells them apart).
    auto red = [&](Vec3f p) {
        SampledWavelengths one = SampledWavelengths::SampleVisible(0.9f);   // ~640 nm
        return double(LightLi(*s, p, Vec3f(0, 0, -1), one)[0]);
    };
    double edgeX = 2 * tanHalf * 1.5 * 0.98, edgeY = 2 * tanHalf * 0.98;
    EXPECT_LT(red(Vec3f(Float(-edgeX), Float(edgeY), 2)), red(Vec3f(Float(edgeX), Float(edgeY), 2)));   // red grows with x
    double topLeft = Luminance([&](const SampledWavelengths &w) { return LightLi(*s, Vec3f(Float(-edgeX), Float(edgeY), 2), Vec3f(0, 0, -1), w); });
    double d2 = edgeX * edgeX + edgeY * edgeY + 4;
    double wantTL = 0;
    {
        Float rgb[3] = {TexelValue(kW, kH, 0, 0, 0), TexelValue(kW, kH, 0, 0, 1), TexelValue(kW, kH, 0, 0, 2)};
        wantTL = Luminance([&](const SampledWavelengths &w) {
                     return SampleSpectrum(RGBIlluminantSpectrum(v, rgb), w, v.spectra) * l.scale;
                 }) / d2;
    }
    EXPECT_NEAR(topLeft, wantTL, 1e-4 * wantTL);
}

TEST(ProjectionLight, ZeroOutsideTheFrustumAndBehind) {
    std::string dir = test::TempDir("projection_outside");
    WriteSynthetic(dir + "/slide.exr", kW, kH);
    auto s = Load(dir, "LightSource \"projection\" \"string filename\" \"slide.exr\"\n");   // fov 90: tan 1
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    Vec3f n(0, 0, -1);
    EXPECT_FALSE(LightLi(*s, Vec3f(0, 0, 3), n, lambda).IsBlack());
    EXPECT_FALSE(LightLi(*s, Vec3f(1.45f * 3, 0, 3), n, lambda).IsBlack());    // inside the wide side
    EXPECT_TRUE(LightLi(*s, Vec3f(1.55f * 3, 0, 3), n, lambda).IsBlack());     // outside it
    EXPECT_FALSE(LightLi(*s, Vec3f(0, 0.95f * 3, 3), n, lambda).IsBlack());
    EXPECT_TRUE(LightLi(*s, Vec3f(0, 1.05f * 3, 3), n, lambda).IsBlack());     // outside the short side
    EXPECT_TRUE(LightLi(*s, Vec3f(0, 0, -3), -n, lambda).IsBlack());           // behind
    EXPECT_TRUE(LightLi(*s, Vec3f(3, 0, 0), Vec3f(-1, 0, 0), lambda).IsBlack()); // in the light's plane
    EXPECT_TRUE(LightLi(*s, Vec3f(0.5f, 0.2f, -3), -n, lambda).IsBlack());     // behind, the mirror of a lit point
    // The CTM turns the frustum: rotated 90 degrees about x, the axis +z goes to -y and the image's
    // top (+y) to +z.
    auto r = Load(dir, "Translate 0 3 0\nRotate 90 1 0 0\nLightSource \"projection\" \"string filename\" \"slide.exr\"\n");
    Vec3f up(0, 1, 0);
    EXPECT_FALSE(LightLi(*r, Vec3f(0, 0, 0), up, lambda).IsBlack());
    EXPECT_TRUE(LightLi(*r, Vec3f(0, 6, 0), -up, lambda).IsBlack());
    SampledWavelengths green = SampledWavelengths::SampleVisible(0.42f);   // ~535 nm: green grows with the row
    double towardsTop = double(LightLi(*r, Vec3f(0, 0, 2.5f), up, green)[0]) * (9 + 6.25);
    double towardsBottom = double(LightLi(*r, Vec3f(0, 0, -2.5f), up, green)[0]) * (9 + 6.25);
    EXPECT_LT(towardsTop, towardsBottom);   // rows near the top (small y) are less green
}

// The luminous flux of light 0 by integration over the sphere of directions around it (a grid of
// 6 x 6 cells per texel over the screen window on the plane at distance 1, d omega = cos^3 dA;
// SampleLi is 0 elsewhere, tested above), and at wavelengths lambda the spectral power.
double ProjectionFlux(const HostScene &s, const SampledWavelengths *lambda, SampledSpectrum *phi) {
    const Light &l = s.lights[0];
    const int nx = 6 * kW, ny = 6 * kH;
    double tanHalf = l.projectionTan, hx = l.projectionScreen.x * tanHalf, hy = l.projectionScreen.y * tanHalf;
    double dA = (2 * hx / nx) * (2 * hy / ny), flux = 0;
    if (phi) *phi = SampledSpectrum(0);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            double x = -hx + (i + 0.5) * 2 * hx / nx, y = -hy + (j + 0.5) * 2 * hy / ny;
            double r2 = 1 + x * x + y * y, dw = dA / (r2 * std::sqrt(r2));
            Vec3f pLight(Float(x), Float(y), 1);   // light space (flipped); unit distance in render space after normalizing
            Vec3f p = l.renderFromLight.ApplyPoint(pLight / Float(std::sqrt(r2)));
            auto I = [&](const SampledWavelengths &w) { return LightLi(s, p, Vec3f(0, 0, 0), w); };   // L at distance 1 = I
            flux += Luminance(I) * dw;
            if (phi) *phi += I(*lambda) * Float(dw);
        }
    return flux;
}

TEST(ProjectionLight, PowerIsTheLuminousFluxAndPhiMatches) {
    std::string dir = test::TempDir("projection_power");
    WriteSynthetic(dir + "/slide.exr", kW, kH);
    auto s = Load(dir, "LightSource \"projection\" \"string filename\" \"slide.exr\" \"float fov\" 70 \"float power\" 50\n");
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.2f);
    SampledSpectrum phi;
    double flux = ProjectionFlux(*s, &lambda, &phi);
    std::printf("projection: luminous flux %.4f for \"power\" 50\n", flux);
    EXPECT_NEAR(flux, 50, 50 * 5e-3);
    // pbrt-v4's Phi (the midpoint rule over texels) against the integral at the same wavelengths.
    SampledSpectrum want = LightPhi(s->lights[0], s->View(), lambda);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(want[i], phi[i], 1e-3 * phi[i]) << i;
    // Without "power": the same light at "scale" 1 emits the image's flux; scaled by power / flux.
    auto u = Load(dir, "LightSource \"projection\" \"string filename\" \"slide.exr\" \"float fov\" 70\n");
    double unscaled = ProjectionFlux(*u, nullptr, nullptr);
    EXPECT_NEAR(s->lights[0].scale / u->lights[0].scale, 50 / unscaled, 5e-3 * 50 / unscaled);
    // The light sampler: three times the power, three times the pick probability (the same fov:
    // pbrt-v4's light power is Phi at four wavelengths, so two frustums that weight the texels
    // differently need not pick in the ratio of their luminous fluxes).
    auto two = Load(dir, "LightSource \"projection\" \"string filename\" \"slide.exr\" \"float power\" 100\n"
                         "Rotate 90 0 1 0\nLightSource \"projection\" \"string filename\" \"slide.exr\" \"float power\" 300\n");
    ASSERT_EQ(two->lightCdf.size(), 3u);
    EXPECT_NEAR(two->lightCdf[1], 0.25, 2e-3);
}

// ---- Diffuse area light with an image ----

// A 2 x 2 quad in the z = 0 plane, uv (0, 0) at (-1, -1), (1, 1) at (1, 1), emitting towards +z.
const char *kQuad = "Shape \"trianglemesh\" \"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] \"integer indices\" [ 0 1 2  0 2 3 ]\n"
                    "  \"point2 uv\" [ 0 0  1 0  1 1  0 1 ]\n";

const float kQuadTexels[2][2][3] = {{{0.9f, 0.1f, 0.1f}, {0.1f, 0.8f, 0.1f}},    // top row: red, green
                                    {{0.1f, 0.1f, 0.7f}, {0.6f, 0.6f, 0.2f}}};   // bottom row: blue, yellow
void WriteQuadImage(const std::string &path) {
    Image img = MakeImage(2, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c) img.At(x, y, c) = kQuadTexels[y][x][c];
    WriteEXR(path, img);
}

// pbrt-v4's Image::BilerpChannel with clamped edges, at image coordinates (s, t) (t = 0: top row).
double Bilerp2x2(double s, double t, int c) {
    double x = s * 2 - 0.5, y = t * 2 - 0.5;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    double dx = x - x0, dy = y - y0;
    auto at = [&](int xi, int yi) { return double(kQuadTexels[std::clamp(yi, 0, 1)][std::clamp(xi, 0, 1)][c]); };
    return (1 - dx) * (1 - dy) * at(x0, y0) + dx * (1 - dy) * at(x0 + 1, y0) + (1 - dx) * dy * at(x0, y0 + 1) +
           dx * dy * at(x0 + 1, y0 + 1);
}

TEST(ImageAreaLight, RadianceIsTheBilinearTexelAtUOneMinusV) {
    std::string dir = test::TempDir("image_area_L");
    WriteQuadImage(dir + "/quad.exr");
    auto s = Load(dir, std::string("AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"quad.exr\" \"float scale\" 2\n") +
                           kQuad + "AttributeEnd\n");
    ASSERT_EQ(s->lights.size(), 2u);
    SceneView v = s->View();
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.6f);
    for (double u : {0.05, 0.25, 0.4, 0.5, 0.6, 0.75, 0.95})
        for (double vv : {0.05, 0.25, 0.45, 0.5, 0.55, 0.75, 0.95}) {
            Float rgb[3];
            for (int c = 0; c < 3; ++c) rgb[c] = Float(Bilerp2x2(u, 1 - vv, c));
            SampledSpectrum want = SampleSpectrum(RGBIlluminantSpectrum(v, rgb), lambda, v.spectra) * v.lights[0].scale;
            SampledSpectrum L = AreaLightL(v.lights[0], v, Vec3f(0, 0, 0), Vec3f(0, 0, 1), Vec2f(Float(u), Float(vv)),
                                           Vec3f(0, 0, 1), lambda);
            for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(L[i], want[i], 1e-5f + 1e-4f * want[i]) << u << " " << vv;
            // One-sided: nothing towards -z.
            EXPECT_TRUE(AreaLightL(v.lights[0], v, Vec3f(0, 0, 0), Vec3f(0, 0, 1), Vec2f(Float(u), Float(vv)), Vec3f(0, 0, -1), lambda)
                            .IsBlack());
        }
    // The image's top-left texel (red) is at uv (0, 1): the quad's (-1, 1) corner.
    SampledWavelengths red = SampledWavelengths::SampleVisible(0.9f);
    Float Lr = AreaLightL(v.lights[0], v, Vec3f(0, 0, 0), Vec3f(0, 0, 1), Vec2f(0.1f, 0.9f), Vec3f(0, 0, 1), red)[0];
    Float Lb = AreaLightL(v.lights[0], v, Vec3f(0, 0, 0), Vec3f(0, 0, 1), Vec2f(0.1f, 0.1f), Vec3f(0, 0, 1), red)[0];
    EXPECT_GT(Lr, 3 * Lb);
    // A light sample returns the same radiance as AreaLightL at the sampled point's uv (MIS needs
    // NEE and emitter hits to agree): the uv of the sampled point follows its position.
    for (int k = 0; k < 64; ++k) {
        Vec2f uS((k % 8 + 0.5f) / 8, (k / 8 + 0.5f) / 8);
        LightSampleContext ctx{Vec3f(0.3f, -0.2f, 2), Vec3f(0, 0, -1), Vec3f(0, 0, -1)};
        for (uint32_t li = 0; li < 2; ++li) {
            LightLiSample ls;
            if (!SampleLi(v.lights[li], v, ctx, uS, lambda, &ls)) continue;
            Vec2f uv((ls.pLight.x + 1) / 2, (ls.pLight.y + 1) / 2);
            EXPECT_NEAR(ls.uvLight.x, uv.x, 1e-4f);
            EXPECT_NEAR(ls.uvLight.y, uv.y, 1e-4f);
            SampledSpectrum want = AreaLightL(v.lights[li], v, ls.pLight, ls.nLight, uv, -ls.wi, lambda);
            EXPECT_NEAR(ls.L[1], want[1], 1e-4f * want[1]);
        }
    }
}

TEST(ImageAreaLight, PowerUsesTheImageMeanLuminanceAndPhi) {
    std::string dir = test::TempDir("image_area_power");
    WriteQuadImage(dir + "/quad.exr");
    for (bool twoSided : {false, true}) {
        SCOPED_TRACE(twoSided);
        auto s = Load(dir, std::string("AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"quad.exr\" \"float power\" 40") +
                               (twoSided ? " \"bool twosided\" true" : "") + "\n" + kQuad + "AttributeEnd\n");
        SceneView v = s->View();
        // Luminous flux: pi (sides) * integral over the quad of the luminance of L, on a uv grid
        // aligned with the bilinear pieces (the midpoint rule is exact on each).
        const int n = 40;
        double flux = 0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                Vec2f uv(Float((i + 0.5) / n), Float((j + 0.5) / n));
                uint32_t li = uv.y > uv.x ? 1 : 0;   // triangle 0: below the diagonal
                flux += Luminance([&](const SampledWavelengths &w) {
                            return AreaLightL(v.lights[li], v, Vec3f(0, 0, 0), Vec3f(0, 0, 1), uv, Vec3f(0, 0, 1), w);
                        }) * (4.0 / (n * n));
            }
        flux *= kPi * (twoSided ? 2 : 1);
        std::printf("image area light: luminous flux %.4f for \"power\" 40 (two-sided %d)\n", flux, int(twoSided));
        // pbrt-v4 normalizes each emitting primitive (one DiffuseAreaLight per triangle) to
        // "power": the quad's two triangles emit twice it.
        EXPECT_NEAR(flux, 2 * 40, 2 * 40 * 5e-3);
        // Phi at some wavelengths: pi A (sides) times the mean texel spectrum, per triangle.
        SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.45f);
        SampledSpectrum mean(0);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x) {
                Float rgb[3] = {kQuadTexels[y][x][0], kQuadTexels[y][x][1], kQuadTexels[y][x][2]};
                mean += SampleSpectrum(RGBIlluminantSpectrum(v, rgb), lambda, v.spectra) * 0.25f;
            }
        SampledSpectrum phi = LightPhi(v.lights[0], v, lambda);
        for (int i = 0; i < NSpectrumSamples; ++i)
            EXPECT_NEAR(phi[i], mean[i] * v.lights[0].scale * Float(kPi * 2 * (twoSided ? 2 : 1)), 1e-4f * phi[i]);
    }
    // The light sampler sees the image's mean: a quad with a grey image (texels 0.2, 0.4, 0.6,
    // 1.0: grey RGB illuminants are the illuminant times the value) and a quad of constant "L" =
    // the mean grey 0.55 get the same pick probability; taking the image as white would give 0.65.
    Image grey = MakeImage(2, 2, 3);
    const float levels[4] = {0.2f, 0.4f, 0.6f, 1.0f};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) grey.At(i % 2, i / 2, c) = levels[i];
    WriteEXR(dir + "/grey.exr", grey);
    auto s = Load(dir, std::string("AttributeBegin\nAreaLightSource \"diffuse\" \"string filename\" \"grey.exr\"\n") + kQuad +
                           "AttributeEnd\nAttributeBegin\nTranslate 0 0 5\nAreaLightSource \"diffuse\" \"rgb L\" [ 0.55 0.55 0.55 ]\n" +
                           kQuad + "AttributeEnd\n");
    ASSERT_EQ(s->lightCdf.size(), 5u);
    std::printf("image area light: pick probability %.5f against its mean grey's 0.5\n", double(s->lightCdf[2]));
    EXPECT_NEAR(s->lightCdf[2], 0.5, 2e-3);
}

}  // namespace
}  // namespace lu
