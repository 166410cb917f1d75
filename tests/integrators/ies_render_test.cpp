// Rendered irradiance under IES luminaires: an orthographic camera looks down at a diffuse plane
// lit by a cosine and a batwing IES profile (goniometric light, point light with "iesfile"; the
// cosine also as type B and type A webs, whose photometric axis is the type C nadir); the
// image, averaged over rings of pixels, follows E = I(theta, phi) cos(theta) / d^2 within 1%
// (relative to the ring under the light, so that albedo and color conversion cancel).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>

#include "integrators/render_helpers.h"

namespace lu::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
double Rad(double deg) { return deg * kPi / 180; }

// An LM-63-2002 type C file of intensity(v, h) at vertical 0-90 (2.5 degree steps) and the
// horizontal angles h.
std::string IESText(const std::vector<double> &h, const std::function<double(double, double)> &intensity) {
    std::ostringstream o;
    o.precision(10);
    o << "IESNA:LM-63-2002\n[TEST] lucerna render test\nTILT=NONE\n1 -1 1 37 " << h.size() << " 1 2 0 0 0\n1 1 0\n";
    for (int i = 0; i <= 36; ++i) o << i * 2.5 << (i < 36 ? " " : "\n");
    for (size_t j = 0; j < h.size(); ++j) o << h[j] << (j + 1 < h.size() ? " " : "\n");
    for (double hj : h) {
        for (int i = 0; i <= 36; ++i) o << intensity(i * 2.5, hj) << (i < 36 ? " " : "\n");
    }
    return o.str();
}

// A type B (2) or A (3) file of I = 800 cos(angle from the photometric axis) = 800 cos(v) cos(h),
// vertical -90-90 and horizontal 0-90 (laterally symmetric), 2.5 degree steps.
std::string CosineTextAB(int type) {
    std::ostringstream o;
    o.precision(10);
    o << "IESNA:LM-63-2002\n[TEST] lucerna render test\nTILT=NONE\n1 -1 1 73 37 " << type << " 2 0 0 0\n1 1 0\n";
    for (int i = 0; i <= 72; ++i) o << -90 + i * 2.5 << (i < 72 ? " " : "\n");
    for (int j = 0; j <= 36; ++j) o << j * 2.5 << (j < 36 ? " " : "\n");
    for (int j = 0; j <= 36; ++j)
        for (int i = 0; i <= 72; ++i) o << 800 * std::cos(Rad(-90 + i * 2.5)) * std::cos(Rad(j * 2.5)) << (i < 72 ? " " : "\n");
    return o.str();
}

// Renders the plane y = 0 seen from above over [-6, 6]^2 (48 x 48 pixels of 0.25) under `light`
// placed 3 above the origin; compares the rings r in [k, k + 1) (k = 0..4) of pixel centers with
// the footprint-averaged analytic irradiance E(x, z) of the same pixels.
void ExpectRenderedIrradiance(const std::string &name, const std::string &iesText, const std::string &light,
                              const std::function<double(double, double)> &intensity) {
    std::string dir = TempDir(name);
    std::ofstream(dir + "/lum.ies") << iesText;
    std::string scene =
        "LookAt 0 10 0  0 0 0  0 0 1\n"
        "Camera \"orthographic\" \"float screenwindow\" [ -6 6 -6 6 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 48 ] \"integer yresolution\" [ 48 ]\n"
        "PixelFilter \"box\" \"float xradius\" 0.5 \"float yradius\" 0.5\n"
        "Sampler \"zsobol\" \"integer pixelsamples\" [ 64 ]\n"
        "Integrator \"path\" \"integer maxdepth\" [ 1 ]\n"
        "WorldBegin\n"
        "AttributeBegin\nTranslate 0 3 0\n" + light + "\nAttributeEnd\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
        "Shape \"bilinearmesh\" \"point3 P\" [ -8 0 -8  8 0 -8  -8 0 8  8 0 8 ]\n";
    std::ofstream(dir + "/scene.pbrt") << scene;
    Diagnostics diag;
    diag.quiet = true;
    auto s = LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
    ASSERT_EQ(s->lights.size(), 1u);
    RenderResultForTest r = RenderScene(*s, TestSettings(*s, 64, 1));
    ASSERT_EQ(r.image.width, 48);
    auto E = [&](double x, double z) {
        double d2 = x * x + 9 + z * z, cosT = 3 / std::sqrt(d2);
        double phi = std::atan2(-z, x) * 180 / kPi;
        return intensity(std::acos(cosT) * 180 / kPi, phi < 0 ? phi + 360 : phi) * cosT / d2;
    };
    const int rings = 5;
    double got[rings] = {}, want[rings] = {};
    for (int py = 0; py < 48; ++py)
        for (int px = 0; px < 48; ++px) {
            // Pixel centers at -6 + (i + 0.5) / 4 on both axes (the image may be mirrored: the
            // profiles are symmetric under x -> -x and z -> -z, and the rings under both).
            double x = -6 + (px + 0.5) / 4, z = -6 + (py + 0.5) / 4;
            int ring = int(std::sqrt(x * x + z * z));
            if (ring >= rings) continue;
            double footprint = 0;
            for (int j = 0; j < 8; ++j)
                for (int i = 0; i < 8; ++i) footprint += E(x + ((i + 0.5) / 8 - 0.5) / 4, z + ((j + 0.5) / 8 - 0.5) / 4) / 64;
            double lum = 0.2126 * r.image.At(px, py, 0) + 0.7152 * r.image.At(px, py, 1) + 0.0722 * r.image.At(px, py, 2);
            got[ring] += lum;
            want[ring] += footprint;
        }
    ASSERT_GT(got[0], 0);
    for (int k = 1; k < rings; ++k) {
        double ratio = (got[k] / got[0]) / (want[k] / want[0]);
        EXPECT_NEAR(ratio, 1, 0.01) << name << " ring " << k;
        std::printf("%s ring %d: rendered / analytic %.4f\n", name.c_str(), k, ratio);
    }
}

TEST(IESRender, CosineLuminaireLightsThePlaneAsCosineToTheFourth) {
    ExpectRenderedIrradiance("ies_render_cos", IESText({0}, [](double v, double) { return 800 * std::cos(Rad(v)); }),
                             "LightSource \"goniometric\" \"string filename\" \"lum.ies\"",
                             [](double v, double) { return 800 * std::cos(Rad(v)); });
}

TEST(IESRender, TypeBAndTypeACosineLuminaires) {
    for (int type : {2, 3})
        ExpectRenderedIrradiance(type == 2 ? "ies_render_type_b" : "ies_render_type_a", CosineTextAB(type),
                                 "LightSource \"point\" \"string iesfile\" \"lum.ies\"",
                                 [](double v, double) { return 800 * std::cos(Rad(v)); });
}

TEST(IESRender, BatwingLuminaire) {
    auto batwing = [](double v, double h) {
        double s = std::sin(Rad(v)), c = std::cos(Rad(h));
        return 500 * std::cos(Rad(v)) * (1 + 2 * s * s * c * c);
    };
    std::vector<double> h;
    for (int i = 0; i <= 18; ++i) h.push_back(i * 5);
    ExpectRenderedIrradiance("ies_render_batwing", IESText(h, batwing), "LightSource \"point\" \"string iesfile\" \"lum.ies\"",
                             batwing);
}

}  // namespace
}  // namespace lu::test
