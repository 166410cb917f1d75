// Render tests of pbrt-v4's ColorSpace directive: flat Lambertian quads under a uniform white sky
// (the outgoing radiance is the albedo spectrum times the sky's), seen by an orthographic camera,
// so each pixel's RGB is the albedo's color expressed in the film's color space.
#include <gtest/gtest.h>

#include <string>

#include "integrators/render_helpers.h"
#include "lucerna/spectra/registry.h"

namespace lu::test {
namespace {

// Camera and film (after `head`, e.g. a ColorSpace), then the world: a white sky and, in
// `world`, quads. The image is 32 x 32.
std::string Scene(const std::string &head, const std::string &afterFilm, const std::string &world) {
    return head +
           "LookAt 0 0 5  0 0 0  0 1 0\n"
           "Camera \"orthographic\" \"float screenwindow\" [ -1 1 -1 1 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n" +
           afterFilm +
           "Sampler \"independent\" \"integer pixelsamples\" [ 16 ]\n"
           "Integrator \"path\" \"integer maxdepth\" [ 1 ]\n"
           "WorldBegin\n"
           "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n" +
           world;
}

std::string Quad(double x0, double x1, const std::string &rgb) {
    return "Material \"diffuse\" \"rgb reflectance\" [ " + rgb + " ]\nShape \"bilinearmesh\" \"point3 P\" [ " +
           std::to_string(x0) + " -3 0  " + std::to_string(x1) + " -3 0  " + std::to_string(x0) + " 3 0  " +
           std::to_string(x1) + " 3 0 ]\n";
}

// Mean RGB over columns [x0, x1) of all rows.
RGB MeanRGB(const Image &img, int x0, int x1) {
    double s[3] = {0, 0, 0};
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = x0; x < x1; ++x, ++n)
            for (int c = 0; c < 3; ++c) s[c] += img.At(x, y, c);
    return {Float(s[0] / n), Float(s[1] / n), Float(s[2] / n)};
}

void ExpectRGBNear(const RGB &got, const RGB &want, double tol, const char *what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tol) << what << " channel " << c;
}

RGB Convert(ColorSpaceId from, ColorSpaceId to, const RGB &rgb) {
    return GetRGBColorSpace(to).ToRGB(GetRGBColorSpace(from).ToXYZ(rgb));
}

}  // namespace

// Film and albedo in Rec. 2020 under a Rec. 2020 white sky: the image is the albedo.
TEST(ColorSpaceRender, Rec2020FurnaceGivesTheAlbedo) {
    auto scene = LoadSceneText("cs_rec2020", Scene("ColorSpace \"rec2020\"\n", "", Quad(-3, 3, "0.25 0.5 0.7")));
    EXPECT_EQ(scene->filmColorSpace, ColorSpaceId::Rec2020);
    auto r = RenderScene(*scene, 16, 1);
    RGB got = MeanRGB(r.image, 0, 32);
    ExpectRGBNear(got, {0.25f, 0.5f, 0.7f}, 0.01, "rec2020");
    std::printf("rec2020 furnace: %.4f %.4f %.4f (albedo 0.25 0.5 0.7)\n", got[0], got[1], got[2]);
}

// ACES2065-1: the sky's white is ACES D60 and the film's white too, so the image is the albedo;
// a D65 sky (sRGB's illuminant) would tint it.
TEST(ColorSpaceRender, Aces2065FurnaceGivesTheAlbedo) {
    auto scene = LoadSceneText("cs_aces", Scene("ColorSpace \"aces2065-1\"\n", "", Quad(-3, 3, "0.35 0.45 0.3")));
    auto r = RenderScene(*scene, 16, 1);
    RGB got = MeanRGB(r.image, 0, 32);
    ExpectRGBNear(got, {0.35f, 0.45f, 0.3f}, 0.01, "aces2065-1");
    std::printf("aces2065-1 furnace: %.4f %.4f %.4f (albedo 0.35 0.45 0.3)\n", got[0], got[1], got[2]);
}

// Two color spaces in one scene: the film in Rec. 2020, the world in sRGB; the left quad's
// block switches to Rec. 2020 and AttributeEnd restores sRGB for the right quad. Both have the
// same numbers: the left half shows them, the right half their sRGB color in Rec. 2020 (a
// builder that did not restore the space at AttributeEnd would make both halves equal).
TEST(ColorSpaceRender, AttributeBlocksMixColorSpaces) {
    // (pbrt-v4's camera space is left-handed: world x > 0 is the image's left half here.)
    const std::string world = "AttributeBegin\nColorSpace \"rec2020\"\n" + Quad(0, 3, "0.3 0.5 0.4") +
                              "AttributeEnd\n" + Quad(-3, 0, "0.3 0.5 0.4");
    auto scene = LoadSceneText("cs_mixed", Scene("ColorSpace \"rec2020\"\n", "ColorSpace \"srgb\"\n", world));
    auto r = RenderScene(*scene, 16, 1);
    RGB left = MeanRGB(r.image, 2, 14), right = MeanRGB(r.image, 18, 30);
    RGB wantRight = Convert(ColorSpaceId::SRGB, ColorSpaceId::Rec2020, {0.3f, 0.5f, 0.4f});
    ExpectRGBNear(left, {0.3f, 0.5f, 0.4f}, 0.01, "left (rec2020 block)");
    ExpectRGBNear(right, wantRight, 0.01, "right (srgb)");
    EXPECT_GT(std::abs(left[0] - right[0]), 0.05);  // the two halves differ
    std::printf("mixed: left %.4f %.4f %.4f, right %.4f %.4f %.4f (want %.4f %.4f %.4f)\n", left[0], left[1], left[2],
                right[0], right[1], right[2], wantRight[0], wantRight[1], wantRight[2]);
}

// The feature scene builds cleanly and renders.
TEST(ColorSpaceRender, FeatureSceneBuildsCleanAndRenders) {
    std::vector<std::string> files = FeatureSceneFiles({"colorspace-"});
    ASSERT_EQ(files.size(), 1u);
    auto scene = LoadCleanFeatureScene(files[0], 40, 24);
    EXPECT_EQ(scene->filmColorSpace, ColorSpaceId::Rec2020);
    ExpectRendersFiniteAndLit(*scene);
}

}  // namespace lu::test
