// Tests of pbrt-v4's realistic camera (camera/realistic.h, scene/lens_build.cpp) on the test lens
// scenes/features/lenses/biconvex-50mm.dat (a stop 4 mm in front of a biconvex singlet, n = 1.5,
// radii +-50 mm, 5 mm thick): the lens table reader's located errors, the thick-lens focal
// length against the lensmaker's equation, focusing (rays from the focused point meet on the
// film), the camera ray weight against a brute-force projected solid angle, the image's
// orientation against the perspective camera, and the builder's errors.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "integrators/render_helpers.h"
#include "lucerna/camera/realistic.h"
#include "lucerna/sampling/rng.h"
#include "lucerna/scene/camera_build.h"
#include "lucerna/scene/error.h"

namespace lu::test {
namespace {

const std::string kLens = std::string(LUCERNA_SOURCE_DIR) + "/scenes/features/lenses/biconvex-50mm.dat";

std::string WriteTemp(const std::string &name, const std::string &text) {
    std::string path = testing::TempDir() + "/" + name;
    std::ofstream(path) << text;
    return path;
}

std::string LensError(const std::string &text) {
    try {
        ReadLensTable(WriteTemp("lens_error.dat", text), FileLoc());
    } catch (const SceneError &e) {
        return e.Loc().ToString() + ": " + e.Message();
    }
    return "";
}

struct Lens {
    std::vector<LensElement> elements;
    std::vector<Bounds2f> pupils;
    CameraData camera;
};

Lens MakeLens(Float apertureMm, Float focus, int pupilSamples = 1 << 18) {
    Lens l;
    std::string error;
    bool ok = MakeRealisticCamera(Transform(), 64, 64, 35, ReadLensTable(kLens, FileLoc()), apertureMm, focus, &l.camera,
                                  &l.elements, &l.pupils, &error, nullptr, 64, pupilSamples);
    EXPECT_TRUE(ok) << error;
    l.camera.lensElements = {l.elements.data(), uint32_t(l.elements.size())};
    l.camera.exitPupilBounds = {l.pupils.data(), uint32_t(l.pupils.size())};
    return l;
}

}  // namespace

TEST(RealisticCamera, LensTableReadsRowsAndLocatesErrors) {
    std::vector<LensTableRow> rows = ReadLensTable(kLens, FileLoc());
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].curvatureRadius, 0);
    EXPECT_EQ(rows[1].curvatureRadius, 50);
    EXPECT_EQ(rows[1].eta, 1.5);
    EXPECT_EQ(rows[2].apertureDiameter, 20);
    EXPECT_NE(LensError("0 4 1 14\n50 5 x 20\n").find("lens_error.dat:2:6: \"x\" is not a number"), std::string::npos)
        << LensError("0 4 1 14\n50 5 x 20\n");
    EXPECT_NE(LensError("# c\n0 4 1\n").find("lens_error.dat:2:1: a lens table row has 4 values"), std::string::npos);
    EXPECT_NE(LensError("50 5 1.5 -2\n").find("must be positive"), std::string::npos);
    EXPECT_NE(LensError("# nothing\n").find("holds no lens interface"), std::string::npos);
    EXPECT_THROW(ReadLensTable("/nonexistent/lens.dat", FileLoc()), SceneError);
}

// The thick-lens approximation's focal length is the lensmaker's: 1/f = (n-1) (1/R1 - 1/R2 +
// (n-1) d / (n R1 R2)) = 1 / 50.847 mm for R1 = 50, R2 = -50, d = 5, n = 1.5.
TEST(RealisticCamera, ThickLensFocalLengthIsTheLensmakers) {
    std::vector<LensElement> e;
    for (const LensTableRow &r : ReadLensTable(kLens, FileLoc()))
        e.push_back(LensElement{Float(r.curvatureRadius / 1000), Float(r.thickness / 1000), Float(r.eta),
                                Float(r.apertureDiameter / 2000)});
    Float pz[2], fz[2];
    ASSERT_TRUE(ComputeThickLensApproximation({e.data(), uint32_t(e.size())}, 0.035f, pz, fz));
    double n = 1.5, R1 = 50, R2 = -50, d = 5;
    double f = 1 / ((n - 1) * (1 / R1 - 1 / R2 + (n - 1) * d / (n * R1 * R2)));
    EXPECT_NEAR((fz[0] - pz[0]) * 1000, f, 0.01 * f);
    EXPECT_NEAR((pz[1] - fz[1]) * 1000, f, 0.01 * f);   // the same focal length from the film side
}

// Focused at 1 m (and 5 m), paraxial rays from the on-axis point at that distance from the film
// cross the axis on the film plane; the film sits farther from the lens for the nearer focus.
TEST(RealisticCamera, FocusedPointIsImagedOnTheFilm) {
    Float rear[2];
    int k = 0;
    for (Float focus : {1.f, 5.f}) {
        Lens l = MakeLens(4, focus, 1 << 10);   // the pupil bounds are not used here
        Span<LensElement> e = l.camera.lensElements;
        rear[k++] = LensRearZ(e);
        for (Float h : {0.2e-3f, 0.5e-3f, 1e-3f}) {
            Ray r, out;
            r.o = Vec3f(0, 0, focus);
            Vec3f front(h, 0, LensFrontZ(e));
            r.d = Normalize(front - r.o);
            ASSERT_TRUE(TraceLensesFromScene(e, r, &out)) << "h " << h;
            Float t = -out.o.x / out.d.x;
            Float z = out.o.z + t * out.d.z;
            EXPECT_NEAR(z * 1000, 0, 0.05) << "focus " << focus << " m, height " << h * 1000 << " mm";
        }
    }
    EXPECT_GT(rear[0], rear[1]);
}

// Under a uniform sky of L the film center sees L times the projected solid angle of the
// directions that get through the lens: integral of cos(theta) over them, estimated here by
// brute force over a cone of directions (no pupil bound, no camera weight). The rendered center
// pixels (pupil sampling with weight cos^4 / (pdf z^2)) must match it.
TEST(RealisticCamera, CenterSeesTheProjectedSolidAngleOfTheLens) {
    Lens l = MakeLens(8, 5, 1 << 10);   // only the elements, focused as the scene below
    Span<LensElement> e = l.camera.lensElements;
    const Float cosMax = std::cos(Radians(20.f));
    RNG rng(11);
    const int n = 400000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        Float cosTheta = 1 - rng.Uniform<float>() * (1 - cosMax), phi = 2 * Pi * rng.Uniform<float>();
        Float sinTheta = std::sqrt(std::max(0.f, 1 - cosTheta * cosTheta));
        Ray r;
        r.o = Vec3f(0, 0, 0);
        r.d = Vec3f(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
        if (TraceLensesFromFilm(e, r, nullptr) != 0) sum += cosTheta;
    }
    double projected = sum / n * 2 * Pi * (1 - cosMax);
    ASSERT_GT(projected, 0.005);   // an 8 mm stop at about 50 mm: pi (4/50)^2 = 0.02
    std::string text = "Camera \"realistic\" \"string lensfile\" [ \"" + kLens +
                       "\" ] \"float aperturediameter\" [ 8 ] \"float focusdistance\" [ 5 ]\n"
                       "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n"
                       "PixelFilter \"box\"\nWorldBegin\nLightSource \"infinite\" \"rgb L\" [ 0.5 0.5 0.5 ]\n";
    auto scene = LoadSceneText("realistic_sky", text);
    auto r = RenderScene(*scene, 64, 1);
    double center = 0;
    for (int y = 14; y < 18; ++y)
        for (int x = 14; x < 18; ++x)
            for (int c = 0; c < 3; ++c) center += r.image.At(x, y, c) / 48;
    EXPECT_NEAR(center, 0.5 * projected, 0.03 * 0.5 * projected) << "projected solid angle " << projected;
    // The corners are darker (vignetting and cos^4).
    EXPECT_LT(r.image.At(0, 0, 1), 0.9 * center);
}

// The lens inverts the image and pbrt-v4 mirrors the film to undo it: a small bright sphere up
// and to the left of the view lands in the same image quadrant as with the perspective camera.
TEST(RealisticCamera, ImageIsUprightAsThePerspectiveCamera) {
    const std::string world =
        "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 32 ]\n"
        "WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\n"
        "Translate -0.8 0.6 5\nShape \"sphere\" \"float radius\" [ 0.3 ]\nAttributeEnd\n";
    auto quadrant = [](const Image &img) {
        double q[4] = {0, 0, 0, 0};   // top-left, top-right, bottom-left, bottom-right
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                q[(y >= img.height / 2) * 2 + (x >= img.width / 2)] += img.At(x, y, 1);
        return int(std::max_element(q, q + 4) - q);
    };
    auto persp = LoadSceneText("persp", "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n" + world);
    auto real = LoadSceneText("real", "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"realistic\" \"string lensfile\" [ \"" + kLens +
                                          "\" ] \"float aperturediameter\" [ 8 ] \"float focusdistance\" [ 5 ]\n" + world);
    EXPECT_EQ(quadrant(RenderScene(*persp, 16, 1).image), 0);
    EXPECT_EQ(quadrant(RenderScene(*real, 16, 1).image), 0);
}

TEST(RealisticCamera, BuilderReportsBadParameters) {
    auto expectError = [](const std::string &camera, const std::string &what) {
        try {
            LoadSceneText("bad_realistic", "Camera \"realistic\" " + camera + "\nWorldBegin\n");
            ADD_FAILURE() << "no error for " << camera;
        } catch (const SceneError &e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    expectError("", "no lens description file");
    expectError("\"string lensfile\" [ \"missing.dat\" ]", "cannot read the lens description file");
    expectError("\"string lensfile\" [ \"" + kLens + "\" ] \"float focusdistance\" [ 0.02 ]", "cannot focus");
    expectError("\"string lensfile\" [ \"" + kLens + "\" ] \"float aperturediameter\" [ -1 ]", "must be positive");
    // A larger aperture than the stop keeps the stop's, with a warning; other apertures are unsupported.
    std::string path = TempDir("realistic_wide") + "/scene.pbrt";
    std::ofstream(path) << "Camera \"realistic\" \"string lensfile\" [ \"" + kLens +
                               "\" ] \"float aperturediameter\" [ 30 ]\nWorldBegin\n";
    Diagnostics diag;
    diag.quiet = true;
    LoadScene(path, diag, {});
    bool warned = false;
    for (const auto &w : diag.warnings) warned |= w.find("larger than the lens's stop") != std::string::npos;
    EXPECT_TRUE(warned);
}

}  // namespace lu::test
