// Robustness of the scene builder against what users and fuzzers write: degenerate transforms
// (no crash, located warnings, nothing non-finite in the scene or the image), invalid light and
// material values (located SceneError, exit code 2), partial spectrum files, and lightless scenes.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "integrators/render_helpers.h"

namespace lu {
namespace {

using test::RenderScene;
using test::TempDir;

// Four header lines; world content starts on line 5.
const char *kHeader =
    "LookAt 0 0 -5  0 0 0  0 1 0\n"
    "Camera \"perspective\" \"float fov\" [ 40 ]\n"
    "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
    "WorldBegin\n";
// A lit backdrop (lines 5-6 after the header) so that renders have something finite to show.
const char *kBackdrop =
    "LightSource \"point\" \"point3 from\" [ 0 0 -4 ] \"rgb I\" [ 5 5 5 ]\n"
    "Shape \"trianglemesh\" \"point3 P\" [ -2 -2 1  2 -2 1  0 2 1 ]\n";

bool Contains(const std::string &s, const std::string &what) { return s.find(what) != std::string::npos; }

// Parses and builds a scene written to a temporary folder (so that relative files resolve);
// *diag gets the warnings.
std::unique_ptr<HostScene> BuildFile(const std::string &name, const std::string &text, Diagnostics *diag,
                                     const std::vector<std::pair<std::string, std::string>> &files = {}) {
    std::string dir = TempDir("robust_" + name);
    for (const auto &[file, content] : files) std::ofstream(dir + "/" + file) << content;
    std::ofstream(dir + "/scene.pbrt") << text;
    diag->quiet = true;
    return LoadScene(dir + "/scene.pbrt", *diag, {});
}

// The warnings mentioning `what`, each checked to be located at "scene.pbrt:LINE:".
int CountWarnings(const Diagnostics &diag, const std::string &what, int line) {
    int n = 0;
    for (const std::string &w : diag.warnings)
        if (Contains(w, what)) {
            EXPECT_TRUE(Contains(w, "scene.pbrt:" + std::to_string(line) + ":")) << w;
            ++n;
        }
    return n;
}

std::string AllWarnings(const Diagnostics &diag) {
    std::string s;
    for (const std::string &w : diag.warnings) s += w + "\n";
    return s;
}

// Every render-space number the backends read from the geometry is finite.
void ExpectFiniteGeometry(const HostScene &s) {
    for (const Vec3f &p : s.positions) EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    for (const Vec3f &n : s.normals) EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    auto finite = [](const Matrix4 &m) {
        for (const auto &row : m.m)
            for (Float x : row)
                if (!std::isfinite(x)) return false;
        return true;
    };
    for (const Sphere &sp : s.spheres) EXPECT_TRUE(finite(sp.renderFromObject.m) && finite(sp.renderFromObject.mInv));
    for (const Disk &d : s.disks) EXPECT_TRUE(finite(d.renderFromObject.m) && finite(d.renderFromObject.mInv));
    for (Float c : s.lightCdf) EXPECT_TRUE(std::isfinite(c));
}

// Renders with "path" and with "regpath" (regularized): no sample rejected, every pixel finite.
void ExpectCleanRenders(const HostScene &scene) {
    for (bool regularize : {false, true}) {
        SCOPED_TRACE(regularize ? "regpath" : "path");
        test::RenderResultForTest r = RenderScene(scene, 4, 5, 0, 2, 0, regularize, regularize ? 0.1 : 0, regularize ? 0.05 : 0);
        EXPECT_EQ(r.stats.rejected, 0u);
        for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v));
    }
}

// Runs the lucerna binary; returns its exit status (128 + signal when killed) and its stdout
// and stderr together.
int RunLucerna(const std::vector<std::string> &args, std::string *err = nullptr) {
    const std::string bin = std::string(LUCERNA_BINARY_DIR) + "/lucerna";
    std::string errFile = TempDir("robust_cli_stderr") + "/stderr.txt";
    pid_t pid = fork();
    if (pid == 0) {
        std::vector<char *> argv;
        argv.push_back(const_cast<char *>(bin.c_str()));
        for (const std::string &a : args) argv.push_back(const_cast<char *>(a.c_str()));
        argv.push_back(nullptr);
        if (!freopen(errFile.c_str(), "w", stdout) || dup2(fileno(stdout), fileno(stderr)) < 0) _exit(126);
        execv(bin.c_str(), argv.data());
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    if (err) {
        std::stringstream ss;
        ss << std::ifstream(errFile).rdbuf();
        *err = ss.str();
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// ---- 1. Shapes under singular transformations ----

struct SingularCase {
    const char *name;
    const char *world;  // after the header and the backdrop (its first line is line 7)
    int warningLine;    // where the builder's warning points
    const char *what;   // in the warning
    size_t lights;      // lights left (the backdrop's point light is one)
};

const SingularCase kSingular[] = {
    {"SphereScale101", "AttributeBegin\nScale 1 0 1\nShape \"sphere\"\nAttributeEnd\n", 9, "sphere: the transformation is singular", 1},
    {"SphereScale000", "AttributeBegin\nScale 0 0 0\nShape \"sphere\"\nAttributeEnd\n", 9, "sphere: the transformation is singular", 1},
    {"SphereAreaLight",
     "AttributeBegin\nScale 1 0 1\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\nShape \"sphere\"\nAttributeEnd\n", 10,
     "its area light is dropped", 1},
    {"DiskAreaLight",
     "AttributeBegin\nScale 0 0 0\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\nShape \"disk\"\nAttributeEnd\n", 10,
     "disk: the transformation is singular", 1},
    {"SphereInInstance", "ObjectBegin \"o\"\nScale 1 0 1\nShape \"sphere\"\nObjectEnd\nObjectInstance \"o\"\n", 9,
     "(object instance \"o\" used at", 1},
    {"WarnedOncePerShape", "ObjectBegin \"o\"\nScale 1 0 1\nShape \"sphere\"\nObjectEnd\nObjectInstance \"o\"\nObjectInstance \"o\"\n"
                           "ObjectInstance \"o\"\n", 9, "sphere: the transformation is singular", 1},
    {"InstanceTransform", "ObjectBegin \"o\"\nShape \"sphere\"\nObjectEnd\nAttributeBegin\nScale 0 0 0\nObjectInstance \"o\"\nAttributeEnd\n", 8,
     "sphere: the transformation is singular", 1},
    {"TriangleLightScale000",
     "AttributeBegin\nScale 0 0 0\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\n"
     "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0 ]\nAttributeEnd\n", 10, "has zero area under its singular", 1},
};

class Singular : public testing::TestWithParam<SingularCase> {};

TEST_P(Singular, DroppedWithALocatedWarningAndRendersClean) {
    const SingularCase &c = GetParam();
    Diagnostics diag;
    std::unique_ptr<HostScene> s = BuildFile(c.name, std::string(kHeader) + kBackdrop + c.world, &diag);
    EXPECT_EQ(CountWarnings(diag, c.what, c.warningLine), 1) << AllWarnings(diag);
    EXPECT_TRUE(s->spheres.empty());
    EXPECT_TRUE(s->disks.empty());
    EXPECT_EQ(s->lights.size(), c.lights);
    ExpectFiniteGeometry(*s);
    ExpectCleanRenders(*s);
}

INSTANTIATE_TEST_SUITE_P(Robust, Singular, testing::ValuesIn(kSingular),
                         [](const testing::TestParamInfo<SingularCase> &i) { return std::string(i.param.name); });

// A mesh that keeps its area under a singular transformation (a quad in the plane y = 0 under
// "Scale 1 0 1") is kept; its per-vertex normals, which need the inverse, are discarded.
TEST(Robust, FlattenedMeshKeepsItsAreaAndDropsItsNormals) {
    Diagnostics diag;
    std::unique_ptr<HostScene> s = BuildFile(
        "flat_mesh", std::string(kHeader) + kBackdrop +
                         "AttributeBegin\nScale 1 0 1\nShape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
                         "  \"point3 P\" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] \"normal N\" [ 0 1 0  0 1 0  0 1 0  0 1 0 ]\nAttributeEnd\n",
        &diag);
    EXPECT_EQ(CountWarnings(diag, "\"N\" are discarded", 9), 1) << AllWarnings(diag);
    ASSERT_EQ(s->triangleMeshes.size(), 2u);
    EXPECT_EQ(s->triangleMeshes[1].triangleCount, 2u);
    EXPECT_EQ(s->triangleMeshes[1].normalOffset, NoIndex);
    ExpectFiniteGeometry(*s);
    ExpectCleanRenders(*s);
}

// With zero emission everywhere the light CDF is uniform (pbrt-v4); a degenerate triangle of an
// emitting mesh must still never be picked (its area pdf is 1 / 0).
TEST(Robust, DegenerateEmitterIsNeverPicked) {
    Diagnostics diag;
    std::unique_ptr<HostScene> s = BuildFile(
        "degenerate_emitter", std::string(kHeader) +
                                  "AreaLightSource \"diffuse\" \"rgb L\" [ 0 0 0 ]\n"
                                  "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2  0 1 3 ]\n"
                                  "  \"point3 P\" [ -1 -1 1  1 -1 1  0 1 1  0 -1 1 ]\n",
        &diag);
    ASSERT_EQ(s->lights.size(), 2u);
    ASSERT_EQ(s->lightCdf.size(), 3u);
    EXPECT_FLOAT_EQ(s->lightCdf[1], 1.f);  // all of it on triangle 0, none on the degenerate triangle 1
    EXPECT_FLOAT_EQ(s->lightCdf[2], 1.f);
    ExpectCleanRenders(*s);
}

// A projective "Transform" can send a vertex to infinity: a located error, not a NaN in Embree.
TEST(Robust, NonFiniteVertexIsALocatedError) {
    Diagnostics diag;
    try {
        BuildFile("projective", std::string(kHeader) +
                                    "Transform [ 1 0 0 0  0 1 0 0  0 0 1 1  0 0 0 0 ]\n"
                                    "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0 ]\n",
                  &diag);
        ADD_FAILURE() << "no SceneError";
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Loc().line, 6) << e.what();
        EXPECT_TRUE(Contains(e.Message(), "not finite")) << e.what();
    }
}

// The CLI: the scene that aborted inside Embree (exit 134) renders with both integrators, and
// `lucerna info` names the dropped shape.
TEST(Robust, CliRendersSingularSphereLight) {
    std::string dir = TempDir("robust_cli_singular");
    std::string scene = dir + "/scene.pbrt";
    std::ofstream(scene) << kHeader << kBackdrop
                         << "AttributeBegin\nScale 1 0 1\nAreaLightSource \"diffuse\" \"rgb L\" [ 4 4 4 ]\nShape \"sphere\"\nAttributeEnd\n"
                         << "ObjectBegin \"o\"\nScale 0 0 0\nShape \"sphere\"\nObjectEnd\nObjectInstance \"o\"\n";
    for (const char *integrator : {"path", "regpath"}) {
        std::string err;
        EXPECT_EQ(RunLucerna({"render", scene, "--spp", "2", "-q", "--integrator", integrator, "-o", dir + "/out.exr"}, &err), 0)
            << integrator << ": " << err;
        EXPECT_TRUE(Contains(err, "scene.pbrt:10:1: warning: sphere: the transformation is singular")) << err;
        EXPECT_EQ(CountNonFinite(ReadImage(dir + "/out.exr")), 0u);
    }
    std::string out;
    EXPECT_EQ(RunLucerna({"info", scene}, &out), 0) << out;
    EXPECT_TRUE(Contains(out, "its area light is dropped")) << out;
}


// ---- 2. Values that would render NaN, infinity or negative radiance: located errors, exit 2 ----

struct BadInput {
    const char *name;
    const char *world;  // after the header: its first line is line 5
    int line;           // of the SceneError
    const char *what;   // in its message
};

// Spectrum files the bad inputs name (in the scene's folder).
const std::vector<std::pair<std::string, std::string>> kSpectrumFiles = {
    {"neg.spd", "400 1\n500 -1\n"},
    {"nan.spd", "# comment\n400 1\n500 nan\n"},
    {"inf.spd", "400 inf\n"},
    {"unsorted.spd", "400 1\n600 1\n500 1\n"},
    {"odd.spd", "400 1 500\n"},
    {"empty.spd", "# nothing\n"},
    {"word.spd", "400 one\n"},
    {"zero.spd", "400 0 500 1.5\n"},
};

const BadInput kBad[] = {
    // Lights: scale, power, illuminance, emission spectra, spot cone, degenerate directions.
    {"AreaScaleNegative", "AreaLightSource \"diffuse\" \"float scale\" -1\nShape \"sphere\"\n", 5, "\"scale\" must not be negative"},
    {"AreaPowerNegative", "AreaLightSource \"diffuse\" \"float power\" -2\nShape \"sphere\"\n", 5, "\"power\" must be positive"},
    {"AreaPowerZero", "AreaLightSource \"diffuse\" \"float power\" 0\nShape \"sphere\"\n", 5, "\"power\" must be positive"},
    {"AreaLNegativeFile", "AreaLightSource \"diffuse\" \"spectrum L\" \"neg.spd\"\nShape \"sphere\"\n", 5, "negative value -1 at 500 nm (line 2)"},
    {"AreaLNegativePairs", "\nAreaLightSource \"diffuse\" \"spectrum L\" [ 400 1 500 -0.5 ]\nShape \"sphere\"\n", 6, "negative value -0.5"},
    {"AreaLNegativeRGB", "AreaLightSource \"diffuse\" \"rgb L\" [ 1 -1 1 ]\nShape \"sphere\"\n", 5, "negative component"},  // existed
    {"PointScaleNegative", "LightSource \"point\" \"float scale\" -3\n", 5, "\"scale\" must not be negative"},
    {"PointPowerNegative", "LightSource \"point\" \"float power\" -3\n", 5, "\"power\" must be positive"},
    {"SpotPowerNegative", "LightSource \"spot\" \"float power\" -3\n", 5, "\"power\" must be positive"},
    {"SpotConeAngle", "LightSource \"spot\" \"float coneangle\" -10\n", 5, "\"coneangle\" must be in (0, 180]"},
    {"SpotConeDelta", "LightSource \"spot\" \"float coneangle\" 20 \"float conedeltaangle\" 30\n", 5, "\"conedeltaangle\""},
    {"SpotSameFromTo", "LightSource \"spot\" \"point3 from\" [ 1 1 1 ] \"point3 to\" [ 1 1 1 ]\n", 5, "must differ"},  // existed
    {"SpotCollapsed", "AttributeBegin\nScale 0 0 0\nLightSource \"spot\"\nAttributeEnd\n", 7, "collapses the light's direction"},
    {"DistantCollapsed", "AttributeBegin\nScale 0 0 0\nLightSource \"distant\"\nAttributeEnd\n", 7, "collapses the light's direction"},
    {"DistantIlluminance", "LightSource \"distant\" \"float illuminance\" -1\n", 5, "\"illuminance\" must be positive"},
    {"DistantScale", "LightSource \"distant\" \"float scale\" -1\n", 5, "\"scale\" must not be negative"},
    {"InfiniteScale", "LightSource \"infinite\" \"float scale\" -1\n", 5, "\"scale\" must not be negative"},
    {"InfiniteIlluminance", "LightSource \"infinite\" \"float illuminance\" -1\n", 5, "\"illuminance\" must be positive"},
    {"SphereProjective", "Transform [ 1 0 0 0  0 1 0 0  0 0 1 1  0 0 0 1 ]\nShape \"sphere\"\n", 6, "sends the shape to infinity"},
    {"PointProjective", "Transform [ 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 0 ]\nLightSource \"point\"\n", 6, "position to infinity"},
    // Spectrum files: non-finite, unsorted, malformed.
    {"FileNaN", "Material \"diffuse\" \"spectrum reflectance\" \"nan.spd\"\nShape \"sphere\"\n", 5, "line 3: \"nan\" is not a finite number"},
    {"FileInf", "AreaLightSource \"diffuse\" \"spectrum L\" \"inf.spd\"\nShape \"sphere\"\n", 5, "\"inf\" is not a finite number"},
    {"FileUnsorted", "LightSource \"point\" \"spectrum I\" \"unsorted.spd\"\n", 5, "line 3: wavelengths are not increasing"},
    {"FileOdd", "LightSource \"point\" \"spectrum I\" \"odd.spd\"\n", 5, "odd number of values"},
    {"FileEmpty", "LightSource \"point\" \"spectrum I\" \"empty.spd\"\n", 5, "no (wavelength, value) pairs"},
    {"FileWord", "LightSource \"point\" \"spectrum I\" \"word.spd\"\n", 5, "\"one\" is not a number"},
    // Materials.
    {"RoughnessNegative", "Material \"conductor\" \"float roughness\" -0.1\nShape \"sphere\"\n", 5, "\"roughness\" must not be negative"},
    {"URoughnessNegative", "Material \"dielectric\" \"float uroughness\" -0.1\nShape \"sphere\"\n", 5, "\"uroughness\" must not be negative"},
    {"RoughnessTexture", "Texture \"r\" \"float\" \"constant\" \"float value\" -1\n"
                         "Material \"coateddiffuse\" \"texture roughness\" \"r\"\nShape \"sphere\"\n", 6, "\"roughness\" must not be negative"},
    {"RoughnessChecker", "Texture \"r\" \"float\" \"checkerboard\" \"float tex1\" 0.1 \"float tex2\" -0.2\n"
                         "Material \"conductor\" \"texture roughness\" \"r\"\nShape \"sphere\"\n", 6, "(got -0.2)"},
    {"EtaZero", "Material \"dielectric\" \"float eta\" 0\nShape \"sphere\"\n", 5, "\"eta\" (index of refraction) must be positive"},
    {"EtaNegative", "Material \"thindielectric\" \"float eta\" -1.5\nShape \"sphere\"\n", 5, "must be positive"},
    {"EtaCoated", "Material \"coateddiffuse\" \"float eta\" -1.5\nShape \"sphere\"\n", 5, "must be positive"},
    {"EtaSpectrumZero", "Material \"dielectric\" \"spectrum eta\" \"zero.spd\"\nShape \"sphere\"\n", 5, "index of refraction must be positive, got 0 at 400 nm"},
    {"ConductorKNegative", "Material \"conductor\" \"spectrum k\" [ 400 -1 700 1 ]\nShape \"sphere\"\n", 5, "negative value -1"},
    {"CoatedThickness", "Material \"coateddiffuse\" \"float thickness\" -0.01\nShape \"sphere\"\n", 5, "\"thickness\" must not be negative"},
    {"CoatedG", "Material \"coateddiffuse\" \"float g\" 1.5\nShape \"sphere\"\n", 5, "\"g\" must be in [-1, 1]"},
    {"CoatedNSamples", "Material \"coateddiffuse\" \"integer nsamples\" 0\nShape \"sphere\"\n", 5, "\"nsamples\" must be at least 1"},
    {"CoatedMaxDepth", "Material \"coateddiffuse\" \"integer maxdepth\" -1\nShape \"sphere\"\n", 5, "\"maxdepth\" must not be negative"},
    {"NamedMaterialRoughness", "MakeNamedMaterial \"m\" \"string type\" \"conductor\" \"float roughness\" -1\n", 5, "must not be negative"},
    // Shapes (existing checks, kept under test).
    {"SphereRadius", "Shape \"sphere\" \"float radius\" -1\n", 5, "radius must be positive"},
    {"DiskRadius", "Shape \"disk\" \"float radius\" 1 \"float innerradius\" 2\n", 5, "innerradius < radius"},
};

class Bad : public testing::TestWithParam<BadInput> {};

TEST_P(Bad, IsALocatedSceneErrorAndExitCode2) {
    const BadInput &c = GetParam();
    std::string text = std::string(kHeader) + "LightSource \"point\" \"rgb I\" [ 1 1 1 ]\n" + c.world;
    // The extra light line moves the world down by one.
    int line = c.line + 1;
    Diagnostics diag;
    try {
        BuildFile(std::string("bad_") + c.name, text, &diag, kSpectrumFiles);
        ADD_FAILURE() << "no SceneError";
    } catch (const SceneError &e) {
        EXPECT_EQ(e.Loc().line, line) << e.what();
        EXPECT_TRUE(Contains(e.Message(), c.what)) << e.what();
    }
    std::string dir = TempDir(std::string("robust_bad_cli_") + c.name);
    for (const auto &[file, content] : kSpectrumFiles) std::ofstream(dir + "/" + file) << content;
    std::ofstream(dir + "/scene.pbrt") << text;
    std::string err;
    EXPECT_EQ(RunLucerna({"render", dir + "/scene.pbrt", "--spp", "1", "-q", "-o", dir + "/out.exr"}, &err), 2) << err;
    EXPECT_TRUE(Contains(err, "scene.pbrt:" + std::to_string(line) + ":")) << err;
}

INSTANTIATE_TEST_SUITE_P(Robust, Bad, testing::ValuesIn(kBad),
                         [](const testing::TestParamInfo<BadInput> &i) { return std::string(i.param.name); });

// pbrt-v4 evaluates a spectrum given over part of 360-830 nm as 0 outside it. For eta and k that
// is an index of refraction 0, whose Fresnel term is NaN (every sample of a rough conductor was
// rejected); Lucerna extends eta and k with their end values (and warns), and keeps pbrt-v4's 0
// for emission and reflectance.
TEST(Robust, PartialSpectrumFiles) {
    std::vector<std::pair<std::string, std::string>> files = {{"part.spd", "400 0.2\n500 0.5\n600 0.8\n"}};
    Diagnostics diag;
    std::unique_ptr<HostScene> s = BuildFile(
        "partial_spectrum", std::string(kHeader) +
                                "LightSource \"point\" \"point3 from\" [ 0 0 -4 ] \"rgb I\" [ 5 5 5 ]\n"
                                "AttributeBegin\nAreaLightSource \"diffuse\" \"spectrum L\" \"part.spd\"\n"
                                "Translate 0 1.5 -1\nShape \"sphere\" \"float radius\" 0.3\nAttributeEnd\n"
                                "Material \"conductor\" \"spectrum eta\" \"part.spd\" \"spectrum k\" \"part.spd\" \"float roughness\" 0.3\n"
                                "Shape \"trianglemesh\" \"point3 P\" [ -2 -2 1  2 -2 1  0 2 1 ]\n",
        &diag, files);
    EXPECT_EQ(CountWarnings(diag, "spectrum \"eta\" from \"part.spd\" covers 400-600 nm only", 11), 1) << AllWarnings(diag);
    EXPECT_EQ(CountWarnings(diag, "spectrum \"k\" from \"part.spd\" covers 400-600 nm only", 11), 1) << AllWarnings(diag);
    EXPECT_EQ(CountWarnings(diag, "spectrum \"L\"", 0), 0) << AllWarnings(diag);
    // eta and k: the end values outside [400, 600]; L: 0 outside, linear inside.
    SceneView v = s->View();
    const Material *conductor = nullptr;
    for (const Material &m : s->materials)
        if (m.kind == MaterialKind::Conductor) conductor = &m;
    ASSERT_NE(conductor, nullptr);
    const Material &m = *conductor;
    auto at = [&](const Spectrum &sp, Float lambda) {
        SampledWavelengths w = SampledWavelengths::SampleVisible(0.5f);
        for (int i = 0; i < NSpectrumSamples; ++i) w.lambda[i] = lambda;
        return SampleSpectrum(sp, w, v.spectra)[0];
    };
    EXPECT_NEAR(at(m.conductorEta.value, 380), 0.2f, 1e-6f);
    EXPECT_NEAR(at(m.conductorK.value, 700), 0.8f, 1e-6f);
    EXPECT_NEAR(at(m.conductorEta.value, 450), 0.35f, 1e-6f);
    const Light *area = nullptr;
    for (const Light &l : s->lights)
        if (l.kind == LightKind::DiffuseArea) area = &l;
    ASSERT_NE(area, nullptr);
    EXPECT_EQ(at(area->spectrum, 380), 0.f);
    EXPECT_EQ(at(area->spectrum, 700), 0.f);
    EXPECT_NEAR(at(area->spectrum, 550), 0.65f, 1e-6f);
    ExpectCleanRenders(*s);
}


// ---- 3. Scenes that can only render black say so (pbrt-v4 warns too) ----

// The whole-scene warning, located at the main file (no line): "DIR/scene.pbrt: warning: ...".
int CountFileWarnings(const Diagnostics &diag, const std::string &what) {
    int n = 0;
    for (const std::string &w : diag.warnings)
        if (Contains(w, what)) {
            EXPECT_TRUE(Contains(w, "/scene.pbrt: warning: ")) << w;
            ++n;
        }
    return n;
}

TEST(Robust, SceneWithoutLightsWarns) {
    Diagnostics diag;
    std::unique_ptr<HostScene> s = BuildFile("no_lights", std::string(kHeader) + "Shape \"sphere\"\n", &diag);
    EXPECT_EQ(CountFileWarnings(diag, "the scene has no light sources; the image will be black"), 1) << AllWarnings(diag);
    EXPECT_EQ(diag.warnings.size(), 1u) << AllWarnings(diag);
    // A light that is dropped (its sphere is flat) leaves the scene without lights as well.
    Diagnostics dropped;
    BuildFile("dropped_light", std::string(kHeader) + "Scale 1 0 1\nAreaLightSource \"diffuse\"\nShape \"sphere\"\n", &dropped);
    EXPECT_EQ(CountFileWarnings(dropped, "no light sources"), 1) << AllWarnings(dropped);
    // One light is enough.
    Diagnostics lit;
    BuildFile("lit", std::string(kHeader) + "LightSource \"distant\"\nShape \"sphere\"\n", &lit);
    EXPECT_TRUE(lit.warnings.empty()) << AllWarnings(lit);
}

TEST(Robust, EmptyFileWarnsInTheLibraryAndInInfo) {
    Diagnostics diag;
    std::unique_ptr<HostScene> s = BuildFile("empty_file", "", &diag);
    EXPECT_EQ(CountFileWarnings(diag, "the scene has no shapes and no light sources"), 1) << AllWarnings(diag);
    std::string dir = TempDir("robust_empty_cli");
    std::ofstream(dir + "/scene.pbrt") << "# nothing here\n";
    std::string out;
    EXPECT_EQ(RunLucerna({"info", dir + "/scene.pbrt"}, &out), 0) << out;
    EXPECT_TRUE(Contains(out, "scene.pbrt: warning: the scene has no shapes and no light sources")) << out;
    EXPECT_EQ(RunLucerna({"render", dir + "/scene.pbrt", "--res", "8x8", "--spp", "1", "-q", "-o", dir + "/out.exr"}, &out), 0) << out;
    EXPECT_TRUE(Contains(out, "no shapes and no light sources")) << out;
}


#ifndef NDEBUG
// Debug builds assert that nothing non-finite reaches Embree (backend/cpu/embree_scene.*; the
// asserts and this test are compiled out with NDEBUG, as in Release). A NaN inverse poked into
// a built scene, which the builder no longer produces, stops at the user-geometry hit.
TEST(RobustDeathTest, DebugBuildsAssertThatNoNaNReachesEmbree) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    Diagnostics diag;
    std::unique_ptr<HostScene> s = BuildFile("nan_poke", std::string(kHeader) + kBackdrop + "Shape \"sphere\"\n", &diag);
    ASSERT_EQ(s->spheres.size(), 1u);
    s->spheres[0].renderFromObject.mInv.m[0][0] = std::numeric_limits<Float>::quiet_NaN();
    EXPECT_DEATH(RenderScene(*s, 1, 5, 0, 1), "hit distance NaN");
}
#endif

}  // namespace
}  // namespace lu
