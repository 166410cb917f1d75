// Tests of the scene builder: the shared scenes build (counts, bounds), refused scenes name the
// feature, area-light orientation, pbrt-v4's light scale / power normalizations against values
// computed by hand, film and camera options, materials, textures, instances, and one test per
// builder error class (message and line).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "lucerna/camera/camera.h"
#include "lucerna/geometry/shapes.h"
#include "lucerna/image/image.h"
#include "lucerna/lights/lights.h"
#include "lucerna/scene/builder.h"
#include "support/test_support.h"

namespace lu {
namespace {

// Three header lines; world content starts on line 4.
const char *kHeader =
    "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 16 ]\n"
    "Camera \"perspective\" \"float fov\" [ 45 ]\n"
    "WorldBegin\n";

std::unique_ptr<HostScene> Build(const std::string &text, Diagnostics &diag, const BuildOptions &opts = {}) {
    diag.quiet = true;
    SceneDescription desc = ParseSceneString(text, "test.pbrt", diag);
    return BuildScene(desc, diag, opts);
}

std::unique_ptr<HostScene> BuildWorld(const std::string &world, Diagnostics &diag) {
    return Build(std::string(kHeader) + world, diag);
}

// The SceneError thrown by parsing + building `text` (fails the test if none).
SceneError ErrorOf(const std::string &text) {
    Diagnostics diag;
    try {
        Build(text, diag);
    } catch (const SceneError &e) {
        return e;
    }
    ADD_FAILURE() << "no SceneError for:\n" << text;
    return SceneError(FileLoc{}, "");
}

bool Contains(const std::string &s, const std::string &what) { return s.find(what) != std::string::npos; }

// Scene text that must fail at `line` with a message containing `what`.
struct LocatedErrorCase {
    std::string text;
    int line;
    const char *what;
};
// Each case's text between prefix and suffix fails where and as it says.
void ExpectLocatedErrors(const std::string &prefix, std::initializer_list<LocatedErrorCase> cases,
                         const std::string &suffix = "") {
    for (const LocatedErrorCase &c : cases) {
        SceneError e = ErrorOf(prefix + c.text + suffix);
        EXPECT_TRUE(Contains(e.Message(), c.what)) << c.text << " -> " << e.Message();
        EXPECT_EQ(e.Loc().line, c.line) << e.Message();
    }
}


// ---- The shared scenes ----

struct SharedScene {
    const char *file;
    uint64_t triangles;
    int spheres;
    std::map<std::string, int> lights;
};

const SharedScene kShared[] = {
    {"bitterli-cornell-box/scene-v4.pbrt", 36, 0, {{"diffuse area", 2}}},
    {"bitterli-veach-mis/scene-v4.pbrt", 52, 3, {{"diffuse area", 3}}},
    {"bitterli-veach-bidir/scene-v4.pbrt", 11544, 0, {{"diffuse area", 4}}},
    {"bitterli-volumetric-caustic/scene-v4-nomedium.pbrt", 12, 1, {{"diffuse area", 2}}},
    {"bitterli-water-caustic/scene-v4.pbrt", 103487, 0, {{"diffuse area", 2}}},
    {"pbrt-v3-caustic-glass/scene-v4.pbrt", 88066, 0, {{"spot", 1}, {"infinite", 1}}},
    {"smallvcm-cornell/smallvcm-bs_c.pbrt", 20, 2, {{"diffuse area", 2}}},
    {"smallvcm-cornell/smallvcm-bs_p.pbrt", 10, 2, {{"point", 1}}},
};

TEST(SharedScenes, BuildWithoutPictureChangingUnsupportedFeatures) {
    for (const SharedScene &sc : kShared) {
        SCOPED_TRACE(sc.file);
        Diagnostics diag;
        diag.quiet = true;
        std::unique_ptr<HostScene> s;
        try {
            s = LoadScene(test::SharedPath(std::string("scenes/") + sc.file), diag, BuildOptions{});
        } catch (const SceneError &e) {
            FAIL() << e.Format();
        }
        // Everything refused for changing the picture is an error; what remains may only be the
        // integrator substitution (bdpt / sppm converge to the path tracer's image) and the sampler
        // substitution (another low-discrepancy pattern: the same expected image).
        for (const std::string &u : diag.unsupported)
            EXPECT_TRUE(u.rfind("Integrator ", 0) == 0 || u.rfind("Sampler ", 0) == 0) << u;
        for (const std::string &w : diag.warnings) EXPECT_FALSE(Contains(w, "is not used by")) << w;
        EXPECT_EQ(s->stats.triangles, sc.triangles);
        EXPECT_EQ(s->spheres.size(), size_t(sc.spheres));
        EXPECT_EQ(s->stats.lightsByType, sc.lights);
        size_t nLights = 0;
        for (auto &[k, n] : sc.lights) nLights += n;
        EXPECT_EQ(s->lights.size(), nLights);
        // Plausible bounds: finite, non-empty, room-sized.
        ASSERT_FALSE(s->bounds.Empty());
        EXPECT_TRUE(IsFinite(s->bounds.pMin) && IsFinite(s->bounds.pMax));
        Float diag3 = Length(s->bounds.Diagonal());
        EXPECT_GT(diag3, 1.f);
        EXPECT_LT(diag3, 500.f);
        // Light CDF: n + 1 entries from 0 to 1, non-decreasing.
        ASSERT_EQ(s->lightCdf.size(), s->lights.size() + 1);
        EXPECT_EQ(s->lightCdf.front(), 0.f);
        EXPECT_FLOAT_EQ(s->lightCdf.back(), 1.f);
        for (size_t i = 1; i < s->lightCdf.size(); ++i) EXPECT_GE(s->lightCdf[i], s->lightCdf[i - 1]);
        // Every shape's material exists (or is an interface).
        for (const Shape &sh : s->shapes) EXPECT_TRUE(sh.material == NoIndex || sh.material < s->materials.size());
        EXPECT_GT(s->film.width, 0);
        EXPECT_GT(s->camera.width, 0);
    }
}

TEST(SharedScenes, CornellBoxDetails) {
    Diagnostics diag;
    diag.quiet = true;
    auto s = LoadScene(test::SharedPath("scenes/bitterli-cornell-box/scene-v4.pbrt"), diag, BuildOptions{});
    EXPECT_EQ(s->film.width, 1024);
    EXPECT_EQ(s->film.height, 1024);
    EXPECT_EQ(s->settings.integrator, IntegratorKind::Path);
    EXPECT_EQ(s->settings.maxDepth, 65);
    EXPECT_EQ(s->stats.samplerName, "sobol");
    EXPECT_EQ(s->settings.spp, 64);
    EXPECT_EQ(s->outputFilename, "cornell-box.png");
    EXPECT_EQ(s->filter.kind, FilterKind::Triangle);
    EXPECT_FLOAT_EQ(s->filter.radiusX, 1.f);
    EXPECT_NEAR(s->stats.fov, 19.5, 1e-9);
    // The box spans [-1, 1] x [0, 2] x [-1, 1]; the camera sits at z = 6.8 looking down -z.
    EXPECT_NEAR(s->bounds.pMin.x, -1, 1e-3);
    EXPECT_NEAR(s->bounds.pMax.y, 2, 1e-3);
    EXPECT_NEAR(s->bounds.pMax.z, 1, 1e-3);
    EXPECT_NEAR(s->stats.cameraPosition.z, 6.8, 1e-4);
    EXPECT_NEAR(s->stats.cameraDirection.z, -1, 1e-4);
    EXPECT_EQ(s->stats.materialsByType.at("diffuse"), 8);
    // "rgb L" [17 12 4]: RGB illuminant spectrum, scale 1 / SpectrumToPhotometric(D65).
    const Light &l = s->lights[0];
    EXPECT_EQ(l.kind, LightKind::DiffuseArea);
    EXPECT_EQ(l.spectrum.kind, SpectrumKind::RGBIlluminant);
    EXPECT_NEAR(l.scale * CIE_Y_integral, 1, 2e-3);
    EXPECT_FALSE(l.twoSided);
}

TEST(SharedScenes, ScenesWithMediaBuild) {
    // The volumetric caustic with its medium: the gas fills the box behind the front-wall
    // interface (inside: the side away from its normal, which faces the camera), the sphere is
    // glass in vacuum inside the gas, the light's shape is gas outside.
    for (const char *f : {"bitterli-volumetric-caustic/scene-v4.pbrt", "bitterli-volumetric-caustic/scene-v4.gonsolo.pbrt"}) {
        SCOPED_TRACE(f);
        Diagnostics diag;
        diag.quiet = true;
        auto s = LoadScene(test::SharedPath(std::string("scenes/") + f), diag, BuildOptions{});
        ASSERT_EQ(s->media.size(), 1u);
        EXPECT_EQ(s->media[0].kind, MediumKind::Homogeneous);
        EXPECT_EQ(s->camera.medium, NoIndex);
        EXPECT_TRUE(s->walkInterfaces);
        int transitions = 0, intoGas = 0;
        for (const Shape &sh : s->shapes) {
            if (!sh.mediumTransition) continue;
            ++transitions;
            if (sh.insideMedium == 0 && sh.outsideMedium == NoIndex) ++intoGas;    // front wall
            if (sh.insideMedium == NoIndex && sh.outsideMedium == 0) continue;     // sphere, light
        }
        EXPECT_EQ(transitions, 3);
        EXPECT_EQ(intoGas, 1);
    }
}

TEST(SharedScenes, RefusedScenesNameTheFeature) {
    std::string dir = test::SharedPath("scenes/pbrt-v3-caustic-glass/pbrt-v3-original");
    int n = 0;
    for (const auto &entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".pbrt") continue;
        ++n;
        SCOPED_TRACE(entry.path().string());
        Diagnostics diag;
        diag.quiet = true;
        try {
            LoadScene(entry.path().string(), diag, BuildOptions{});
            ADD_FAILURE() << "built a pbrt-v3 scene";
        } catch (const SceneError &e) {
            // Named: a quoted directive / type / parameter, at a real line.
            EXPECT_TRUE(Contains(e.Message(), "\"")) << e.Message();
            EXPECT_GT(e.Loc().line, 0);
        }
    }
    EXPECT_EQ(n, 6);
}

// ---- Lucerna's own test scenes (scenes/test) ----

std::unique_ptr<HostScene> LoadTestScene(const std::string &name, Diagnostics &diag) {
    diag.quiet = true;
    return LoadScene(test::SourcePath("scenes/test/" + name), diag, BuildOptions{});
}

TEST(TestScenes, AllBuildWithoutWarnings) {
    for (const char *name : {"furnace.pbrt", "quad_light.pbrt", "features.pbrt"}) {
        SCOPED_TRACE(name);
        Diagnostics diag;
        try {
            LoadTestScene(name, diag);
        } catch (const SceneError &e) {
            FAIL() << e.Format();
        }
        // (features.pbrt asks for the halton sampler, implemented since.)
        EXPECT_TRUE(diag.unsupported.empty());
        for (const std::string &w : diag.warnings) ADD_FAILURE() << w;
    }
}

TEST(TestScenes, Features) {
    Diagnostics diag;
    auto s = LoadTestScene("features.pbrt", diag);
    EXPECT_EQ(s->settings.integrator, IntegratorKind::RegPath);
    EXPECT_EQ(s->settings.maxDepth, 8);
    EXPECT_EQ(s->stats.samplerName, "halton");
    EXPECT_FLOAT_EQ(s->film.imagingRatio, 2);
    EXPECT_EQ(s->filter.kind, FilterKind::Mitchell);
    EXPECT_EQ(s->stats.lightsByType.at("point"), 1);
    EXPECT_EQ(s->stats.lightsByType.at("spot"), 1);
    EXPECT_EQ(s->stats.lightsByType.at("distant"), 1);
    EXPECT_EQ(s->stats.lightsByType.at("infinite"), 1);
    EXPECT_EQ(s->stats.lightsByType.at("diffuse area"), 1);
    EXPECT_EQ(s->stats.triangles, 2u + 2 * 2);   // floor patch + two instanced quads
    EXPECT_EQ(s->spheres.size(), 2u);
    EXPECT_EQ(s->disks.size(), 2u);
    EXPECT_EQ(s->stats.instanceUses, 2);
    EXPECT_EQ(s->camera.lensRadius, 0.01f);
    // The box is used twice: one prototype in object space and two instances. The mirrored
    // instance swaps handedness (its triangles flip at the hit, geometry/shapes.h); the other not.
    ASSERT_EQ(s->triangleMeshes.size(), 2u);
    ASSERT_EQ(s->prototypes.size(), 1u);
    ASSERT_EQ(s->instances.size(), 2u);
    EXPECT_FALSE(s->triangleMeshes[1].flipNormals);
    EXPECT_EQ(s->instances[0].swapsHandedness, 0u);
    EXPECT_EQ(s->instances[1].swapsHandedness, 1u);
    const Material &gold = s->materials[s->shapes[1].material];
    EXPECT_EQ(gold.kind, MaterialKind::Conductor);
    EXPECT_FLOAT_EQ(gold.uRoughness.value, 0.1f);  // the constant texture
}

TEST(TestScenes, QuadLight) {
    Diagnostics diag;
    auto s = LoadTestScene("quad_light.pbrt", diag);
    ASSERT_EQ(s->lights.size(), 4u);
    // The bilinear patch (area 1, two triangles) gets the whole "power" per patch, as pbrt-v4.
    const double want = 10 / (3.14159265358979 * 1.0) / CIE_Y_integral;
    EXPECT_NEAR(s->lights[2].scale / want, 1, 2e-3);
    EXPECT_NEAR(s->lights[3].scale / want, 1, 2e-3);
    EXPECT_TRUE(s->triangleMeshes[2].flipNormals);  // ReverseOrientation
}

// ---- Area light orientation ----

const char *kQuadP = "\"point3 P\" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] \"integer indices\" [ 0 1 2 0 2 3 ]";

// Does the quad's light (triangle 0, at (0.5, -0.5, 0)) emit towards +z and towards -z?
std::pair<bool, bool> EmitsUpDown(const HostScene &s) {
    SceneView v = s.View();
    EXPECT_EQ(v.shapes.size, 1u);
    EXPECT_NE(v.shapes[0].areaLight, NoIndex);
    std::pair<bool, bool> r;
    for (int side = 0; side < 2; ++side) {
        Float z = side == 0 ? 5.f : -5.f;
        Ray ray{Vec3f(0.5f, -0.5f, z), Vec3f(0, 0, z > 0 ? -1.f : 1.f)};
        HitRecord hit;
        hit.t = 5;
        hit.shape = 0;
        hit.primitive = 0;
        hit.b1 = 0.5f;
        hit.b2 = 0.25f;
        SurfaceInteraction si = ComputeInteraction(v, hit, ray);
        EXPECT_NEAR(si.p.x, 0.5f, 1e-5f);
        EXPECT_NEAR(si.p.y, -0.5f, 1e-5f);
        const Light &l = v.lights[si.areaLight];
        SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
        SampledSpectrum L = AreaLightL(l, v, si.p, si.n, si.uv, si.wo, lambda);
        bool emits = L.Average() > 0;
        (side == 0 ? r.first : r.second) = emits;
    }
    return r;
}

TEST(AreaLight, OrientationFollowsWindingReverseOrientationHandednessAndN) {
    struct Case {
        std::string pre, extra;
        bool up, down;
    };
    const Case cases[] = {
        {"", "", true, false},                                           // winding: +z
        {"ReverseOrientation\n", "", false, true},                       // flipped
        {"Scale 1 1 -1\n", "", false, true},                             // handedness swap flips
        {"ReverseOrientation\nScale 1 1 -1\n", "", true, false},         // both: unchanged
        {"", "\"normal N\" [ 0 0 -1 0 0 -1 0 0 -1 0 0 -1 ]", false, true},  // N decides
        {"ReverseOrientation\n", "\"normal N\" [ 0 0 -1 0 0 -1 0 0 -1 0 0 -1 ]", true, false},  // N negated
        {"Scale 1 1 -1\n", "\"normal N\" [ 0 0 1 0 0 1 0 0 1 0 0 1 ]", false, true},  // N transformed: -z
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.pre + c.extra);
        Diagnostics diag;
        auto s = BuildWorld("AttributeBegin\n" + c.pre + "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\nShape \"trianglemesh\" " +
                                kQuadP + " " + c.extra + "\nAttributeEnd\n",
                            diag);
        auto [up, down] = EmitsUpDown(*s);
        EXPECT_EQ(up, c.up);
        EXPECT_EQ(down, c.down);
    }
    Diagnostics diag;
    auto s = BuildWorld("AreaLightSource \"diffuse\" \"bool twosided\" true\nShape \"trianglemesh\" " + std::string(kQuadP) + "\n", diag);
    auto [up, down] = EmitsUpDown(*s);
    EXPECT_TRUE(up && down);
}

TEST(AreaLight, InterfaceMaterialIgnoresTheLight) {
    Diagnostics diag;
    auto s = BuildWorld("Material \"interface\"\nAreaLightSource \"diffuse\"\nShape \"trianglemesh\" " + std::string(kQuadP) + "\n", diag);
    EXPECT_TRUE(s->lights.empty());
    ASSERT_EQ(s->shapes.size(), 1u);
    EXPECT_EQ(s->shapes[0].material, NoIndex);
    EXPECT_EQ(s->shapes[0].areaLight, NoIndex);
}

// ---- Light normalizations (pbrt-v4's lights.cpp), against hand-computed values ----
// SpectrumToPhotometric of the sRGB illuminant (D65, normalized as pbrt-v4) is CIE_Y_integral.

Float OnlyLightScale(const std::string &world, LightKind kind) {
    Diagnostics diag;
    auto s = BuildWorld(world, diag);
    EXPECT_FALSE(s->lights.empty());
    if (s->lights.empty()) return 0;
    EXPECT_EQ(s->lights[0].kind, kind);
    return s->lights[0].scale;
}

TEST(LightScale, PointSpotDistantInfinite) {
    const double Y = CIE_Y_integral, pi = 3.14159265358979;
    auto near = [](double got, double want) { EXPECT_NEAR(got / want, 1.0, 2e-3) << got << " vs " << want; };
    near(OnlyLightScale("LightSource \"point\" \"rgb I\" [0.2 0.5 0.9] \"float scale\" 2.5\n", LightKind::Point), 2.5 / Y);
    near(OnlyLightScale("LightSource \"point\" \"float power\" 100\n", LightKind::Point), 100 / (4 * pi) / Y);
    {
        double cosEnd = std::cos(30 * pi / 180), cosStart = std::cos(25 * pi / 180);
        double k_e = 2 * pi * ((1 - cosStart) + (cosStart - cosEnd) / 2);
        near(OnlyLightScale("LightSource \"spot\" \"float power\" 50 \"point3 to\" [0 -1 0]\n", LightKind::Spot), 50 / k_e / Y);
    }
    near(OnlyLightScale("LightSource \"distant\" \"float illuminance\" 7 \"float scale\" 3\n", LightKind::Distant), 21 / Y);
    near(OnlyLightScale("LightSource \"infinite\" \"float illuminance\" 5\n", LightKind::UniformInfinite), 5 / pi / Y);
    near(OnlyLightScale("LightSource \"infinite\" \"rgb L\" [0.1 0.1 0.1]\n", LightKind::UniformInfinite), 1 / Y);
}

TEST(LightScale, SpotGeometry) {
    Diagnostics diag;
    auto s = BuildWorld("Translate 1 2 3\nLightSource \"spot\" \"point3 from\" [0 1 0] \"point3 to\" [0 1 5] "
                        "\"float coneangle\" 40 \"float conedeltaangle\" 10\n",
                        diag);
    const Light &l = s->lights[0];
    EXPECT_NEAR(l.position.x, 1, 1e-6);
    EXPECT_NEAR(l.position.y, 3, 1e-6);
    EXPECT_NEAR(l.position.z, 3, 1e-6);
    Vec3f d = Normalize(l.renderFromLight.ApplyVector(Vec3f(0, 0, 1)));
    EXPECT_NEAR(d.z, 1, 1e-6);
    EXPECT_NEAR(l.cosFalloffEnd, std::cos(40 * Pi / 180), 1e-6);
    EXPECT_NEAR(l.cosFalloffStart, std::cos(30 * Pi / 180), 1e-6);
}

TEST(LightScale, DistantDirectionPointsTowardsTheLight) {
    Diagnostics diag;
    auto s = BuildWorld("LightSource \"distant\" \"point3 from\" [0 10 0] \"point3 to\" [0 0 0]\n", diag);
    EXPECT_NEAR(s->lights[0].direction.y, 1, 1e-6);
}

TEST(LightScale, AreaLightPowerUsesEachPrimitiveArea) {
    const double Y = CIE_Y_integral, pi = 3.14159265358979;
    // The quad's two triangles have area 2 each; pbrt-v4 gives each its own light with the power.
    for (bool twoSided : {false, true}) {
        Diagnostics diag;
        auto s = BuildWorld(std::string("AreaLightSource \"diffuse\" \"float power\" 10 \"float scale\" 3 \"bool twosided\" ") +
                                (twoSided ? "true" : "false") + "\nShape \"trianglemesh\" " + kQuadP + "\n",
                            diag);
        ASSERT_EQ(s->lights.size(), 2u);
        double want = 3 / Y * 10 / ((twoSided ? 2 : 1) * 2 * pi);
        for (const Light &l : s->lights) EXPECT_NEAR(l.scale / want, 1, 2e-3);
        EXPECT_EQ(s->lights[1].primitive, 1u);
        EXPECT_EQ(s->shapes[0].areaLight, 0u);
    }
    // Sphere: pbrt-v4 uses the object-space area 4 pi r^2.
    Diagnostics diag;
    auto s = BuildWorld("AreaLightSource \"diffuse\" \"float power\" 20\nShape \"sphere\" \"float radius\" 0.5\n", diag);
    ASSERT_EQ(s->lights.size(), 1u);
    EXPECT_NEAR(s->lights[0].scale / (20 / (pi * 4 * pi * 0.25) / Y), 1, 2e-3);
}

// Photometric normalization of a blackbody emitter, integrated here independently (1 nm sums of
// ybar times Planck's law normalized to its peak, as pbrt-v4's InnerProduct).
TEST(LightScale, BlackbodyNormalization) {
    Diagnostics diag;
    auto s = BuildWorld("LightSource \"point\" \"blackbody I\" [ 3000 ]\n", diag);
    SceneView v = s->View();
    const Float *ybar = v.spectra.data + size_t(TableCIE_Y) * TabulatedSpectrumSize;
    auto planck = [](double lambdaNm, double T) {
        const double c = 299792458., h = 6.62606957e-34, kb = 1.3806488e-23;
        double l = lambdaNm * 1e-9;
        return (2 * h * c * c) / (std::pow(l, 5) * (std::exp((h * c) / (l * kb * T)) - 1));
    };
    double peak = planck(2.8977721e-3 / 3000 * 1e9, 3000), sum = 0;
    for (int i = 0; i < TabulatedSpectrumSize; ++i) sum += ybar[i] * planck(360 + i, 3000) / peak;
    EXPECT_NEAR(s->lights[0].scale * sum, 1, 3e-3);
    EXPECT_EQ(s->lights[0].spectrum.kind, SpectrumKind::Blackbody);
}

TEST(LightScale, PowerProportionalCdf) {
    Diagnostics diag;
    auto s = BuildWorld("LightSource \"point\" \"rgb I\" [1 1 1]\nLightSource \"point\" \"rgb I\" [1 1 1] \"float scale\" 3\n", diag);
    ASSERT_EQ(s->lightCdf.size(), 3u);
    EXPECT_NEAR(s->lightCdf[1], 0.25, 1e-4);
    EXPECT_FLOAT_EQ(s->lightCdf[2], 1);
}

TEST(LightScale, InfiniteLightsAreListedAndGetTheSceneSphere) {
    Diagnostics diag;
    auto s = BuildWorld("LightSource \"infinite\"\nLightSource \"point\"\nShape \"sphere\" \"float radius\" 2\n", diag);
    ASSERT_EQ(s->infiniteLights.size(), 1u);
    const Light &l = s->lights[s->infiniteLights[0]];
    EXPECT_EQ(l.spectrum.kind, SpectrumKind::Tabulated);  // the color space's illuminant
    EXPECT_NEAR(l.sceneRadius, 2 * std::sqrt(3.f), 1e-4);
}

TEST(LightScale, ImageInfiniteLight) {
    std::string dir = test::TempDir("builder_envmap");
    Image img = MakeImage(8, 8, 3, 0.5f);
    img.At(1, 2, 0) = 4;
    WriteEXR(dir + "/env.exr", img);
    Diagnostics diag;
    diag.quiet = true;
    std::string scene = std::string(kHeader) + "LightSource \"infinite\" \"string filename\" \"env.exr\" \"float scale\" 2\n";
    std::ofstream(dir + "/scene.pbrt") << scene;
    auto s = LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
    ASSERT_EQ(s->lights.size(), 1u);
    const Light &l = s->lights[0];
    EXPECT_EQ(l.kind, LightKind::ImageInfinite);
    EXPECT_NEAR(l.scale * CIE_Y_integral / 2, 1, 2e-3);
    ASSERT_LT(l.image, s->images.size());
    const ImageData &im = s->images[l.image];
    EXPECT_EQ(im.width, 8u);
    EXPECT_EQ(im.channels, 3u);
    EXPECT_FLOAT_EQ(s->texels[im.offset + (2 * 8 + 1) * 3], 4.f);
    EXPECT_LT(l.distribution, s->distributions2D.size());
    // Non-square maps are not equal-area maps.
    WriteEXR(dir + "/wide.exr", MakeImage(8, 4, 3, 1));
    std::ofstream(dir + "/wide.pbrt") << std::string(kHeader) + "LightSource \"infinite\" \"string filename\" \"wide.exr\"\n";
    EXPECT_THROW(LoadScene(dir + "/wide.pbrt", diag, BuildOptions{}), SceneError);
}

// ---- Film and camera ----

TEST(Film, IsoExposureAndResolution) {
    Diagnostics diag;
    auto s = Build("Film \"rgb\" \"float iso\" 400 \"integer xresolution\" 64 \"integer yresolution\" 48\n"
                   "Camera \"perspective\" \"float shutterclose\" 0.5\nWorldBegin\n",
                   diag);
    EXPECT_FLOAT_EQ(s->film.imagingRatio, 2.f);  // 0.5 s * 400 / 100
    EXPECT_EQ(s->film.width, 64);
    EXPECT_EQ(s->camera.height, 48);
    // Defaults: 1280 x 720, imaging ratio 1; --res overrides.
    BuildOptions opts;
    opts.resX = 20;
    opts.resY = 10;
    auto d = Build("WorldBegin\n", diag);
    EXPECT_EQ(d->film.width, 1280);
    EXPECT_EQ(d->film.height, 720);
    EXPECT_FLOAT_EQ(d->film.imagingRatio, 1.f);
    auto o = Build("Film \"rgb\" \"integer xresolution\" 64 \"integer yresolution\" 48\nWorldBegin\n", diag, opts);
    EXPECT_EQ(o->film.width, 20);
    EXPECT_EQ(o->camera.width, 20);
    EXPECT_EQ(o->camera.height, 10);
}

TEST(Film, XYZToOutputIsSRGBAndWhiteBalanceAdaptsD65ToItself) {
    Diagnostics diag;
    auto s = Build("WorldBegin\n", diag);
    // D65 white (Y = 1) maps to RGB (1, 1, 1).
    Float x = 0.312717f, y = 0.329031f, X = x / y, Z = (1 - x - y) / y;
    for (int r = 0; r < 3; ++r)
        EXPECT_NEAR(s->film.xyzToOutput[r][0] * X + s->film.xyzToOutput[r][1] + s->film.xyzToOutput[r][2] * Z, 1, 2e-3);
    // White balancing for 6504 K daylight is (nearly) the identity; 3000 K warms whites to blue-free.
    auto w = Build("Film \"rgb\" \"float whitebalance\" 6504\nWorldBegin\n", diag);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(w->film.xyzToOutput[i][j], s->film.xyzToOutput[i][j], 2e-2);
    auto warm = Build("Film \"rgb\" \"float whitebalance\" 3000\nWorldBegin\n", diag);
    Float b = warm->film.xyzToOutput[2][0] * X + warm->film.xyzToOutput[2][1] + warm->film.xyzToOutput[2][2] * Z;
    Float r = warm->film.xyzToOutput[0][0] * X + warm->film.xyzToOutput[0][1] + warm->film.xyzToOutput[0][2] * Z;
    EXPECT_GT(b, r);  // a 3000 K balance turns D65 white blue
}

TEST(Camera, FovOnTheShorterAxis) {
    Diagnostics diag;
    auto s = Build("Film \"rgb\" \"integer xresolution\" 200 \"integer yresolution\" 100\nCamera \"perspective\" \"float fov\" 90\nWorldBegin\n", diag);
    // The ray through the top edge's middle makes 45 degrees with +z (vertical fov 90).
    Vec3f top = s->camera.cameraFromRaster.ApplyPoint(Vec3f(100, 0, 0));
    EXPECT_NEAR(std::abs(top.y / top.z), 1, 1e-4);
    Vec3f right = s->camera.cameraFromRaster.ApplyPoint(Vec3f(200, 50, 0));
    EXPECT_NEAR(std::abs(right.x / right.z), 2, 1e-4);
}

// ---- Materials and textures ----

TEST(Materials, PbrtDefaultsAndNamedSpectra) {
    Diagnostics diag;
    auto s = BuildWorld("MakeNamedMaterial \"cu\" \"string type\" \"conductor\"\n"
                        "MakeNamedMaterial \"ag\" \"string type\" \"conductor\" \"spectrum eta\" \"metal-Ag-eta\" \"spectrum k\" \"metal-Ag-k\" \"float roughness\" 0.2\n"
                        "MakeNamedMaterial \"mirror\" \"string type\" \"conductor\" \"rgb reflectance\" [1 1 1]\n"
                        "MakeNamedMaterial \"bk7\" \"string type\" \"dielectric\" \"spectrum eta\" \"glass-BK7\"\n"
                        "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\" \"float eta\" 1.33 \"float uroughness\" 0.1\n"
                        "MakeNamedMaterial \"coat\" \"string type\" \"coateddiffuse\"\n"
                        "MakeNamedMaterial \"thin\" \"string type\" \"thindielectric\"\n"
                        "MakeNamedMaterial \"none\" \"string type\" \"interface\"\n",
                        diag);
    EXPECT_EQ(s->materials.size(), 7u);
    EXPECT_EQ(s->stats.materialsByType.at("conductor"), 3);
    EXPECT_EQ(s->stats.materialsByType.at("interface"), 1);
    // Named materials are created in name order: ag, bk7, coat, cu, glass, mirror, thin.
    const Material &ag = s->materials[0], &bk7 = s->materials[1], &coat = s->materials[2], &cu = s->materials[3],
                   &glass = s->materials[4], &mirror = s->materials[5], &thin = s->materials[6];
    EXPECT_EQ(cu.kind, MaterialKind::Conductor);
    EXPECT_FALSE(cu.useReflectance);
    EXPECT_EQ(cu.conductorEta.value.kind, SpectrumKind::Tabulated);  // metal-Cu-eta by default
    EXPECT_EQ(cu.uRoughness.value, 0.f);
    EXPECT_TRUE(cu.remapRoughness);
    EXPECT_EQ(ag.uRoughness.value, 0.2f);
    EXPECT_EQ(ag.vRoughness.value, 0.2f);
    EXPECT_NE(ag.conductorEta.value.table, cu.conductorEta.value.table);
    EXPECT_TRUE(mirror.useReflectance);
    EXPECT_EQ(mirror.reflectance.value.kind, SpectrumKind::RGBAlbedo);
    EXPECT_FALSE(mirror.reflectance.unbounded);
    EXPECT_EQ(bk7.eta.kind, SpectrumKind::Tabulated);
    EXPECT_EQ(glass.eta.kind, SpectrumKind::Constant);
    EXPECT_FLOAT_EQ(glass.eta.scale, 1.33f);
    EXPECT_FLOAT_EQ(glass.uRoughness.value, 0.1f);
    EXPECT_FLOAT_EQ(glass.vRoughness.value, 0.f);
    EXPECT_EQ(coat.kind, MaterialKind::CoatedDiffuse);
    EXPECT_FLOAT_EQ(coat.thickness.value, 0.01f);
    EXPECT_FLOAT_EQ(coat.eta.scale, 1.5f);
    EXPECT_FLOAT_EQ(coat.reflectance.value.scale, 0.5f);
    EXPECT_EQ(coat.maxDepth, 10);
    EXPECT_EQ(coat.nSamples, 1);
    EXPECT_EQ(thin.kind, MaterialKind::ThinDielectric);
    EXPECT_FLOAT_EQ(thin.eta.scale, 1.5f);
}

TEST(Materials, ShapesUseTheirMaterialAndDefault) {
    Diagnostics diag;
    auto s = BuildWorld("Shape \"sphere\"\nMaterial \"dielectric\"\nShape \"sphere\"\n"
                        "MakeNamedMaterial \"x\" \"string type\" \"interface\"\nNamedMaterial \"x\"\nShape \"sphere\"\n",
                        diag);
    ASSERT_EQ(s->shapes.size(), 3u);
    EXPECT_EQ(s->materials[s->shapes[0].material].kind, MaterialKind::Diffuse);  // pbrt-v4's default diffuse 0.5
    EXPECT_FLOAT_EQ(s->materials[s->shapes[0].material].reflectance.value.scale, 0.5f);
    EXPECT_EQ(s->materials[s->shapes[1].material].kind, MaterialKind::Dielectric);
    EXPECT_EQ(s->shapes[2].material, NoIndex);
}

TEST(Textures, CheckerboardAndImageMap) {
    std::string dir = test::TempDir("builder_textures");
    Image img = MakeImage(4, 2, 3, 0);
    img.At(0, 0, 0) = SRGBToLinear(128 / 255.f);
    WritePNG(dir + "/t.png", img);
    std::string scene = std::string(kHeader) +
                        "Texture \"checks\" \"spectrum\" \"checkerboard\" \"float uscale\" 8 \"float vscale\" 4 "
                        "\"rgb tex1\" [0.9 0.1 0.1] \"rgb tex2\" [0.1 0.1 0.9]\n"
                        "Texture \"img\" \"spectrum\" \"imagemap\" \"string filename\" \"t.png\" \"string wrap\" \"clamp\"\n"
                        "Texture \"rough\" \"float\" \"imagemap\" \"string filename\" \"t.png\" \"string encoding\" \"linear\"\n"
                        "Material \"diffuse\" \"texture reflectance\" \"checks\"\nShape \"sphere\"\n"
                        "Material \"conductor\" \"texture eta\" \"img\" \"texture roughness\" \"rough\"\nShape \"sphere\"\n";
    std::ofstream(dir + "/scene.pbrt") << scene;
    Diagnostics diag;
    diag.quiet = true;
    auto s = LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
    EXPECT_EQ(s->stats.spectrumTextures, 2);
    EXPECT_EQ(s->stats.floatTextures, 1);
    const Material &d = s->materials[s->shapes[0].material];
    EXPECT_EQ(d.reflectance.kind, TextureKind::Checkerboard);
    EXPECT_FLOAT_EQ(d.reflectance.mapping.su, 8);
    EXPECT_FLOAT_EQ(d.reflectance.mapping.sv, 4);
    ASSERT_NE(d.reflectance.tex[0], NoIndex);
    EXPECT_EQ(s->spectrumTextures[d.reflectance.tex[0]].value.kind, SpectrumKind::RGBAlbedo);
    EXPECT_FALSE(d.reflectance.unbounded);
    const Material &c = s->materials[s->shapes[1].material];
    EXPECT_EQ(c.conductorEta.kind, TextureKind::ImageMap);
    EXPECT_TRUE(c.conductorEta.unbounded);
    const ImageData &im = s->images[c.conductorEta.image];
    EXPECT_EQ(im.width, 4u);
    EXPECT_EQ(im.height, 2u);
    EXPECT_EQ(im.wrap, WrapMode::Clamp);
    // sRGB-decoded by default for PNG; "linear" keeps the 8-bit code value / 255.
    EXPECT_NEAR(s->texels[im.offset], SRGBToLinear(128 / 255.f), 2e-3);
    EXPECT_EQ(c.uRoughness.kind, TextureKind::ImageMap);
    const ImageData &lin = s->images[c.uRoughness.image];
    // A float texture of an RGB image reads the average of R, G and B (pbrt-v4's MIPMap).
    EXPECT_EQ(lin.channels, 1u);
    EXPECT_NEAR(s->texels[lin.offset], 128 / 255.f / 3, 2e-3);
    EXPECT_EQ(c.vRoughness.image, c.uRoughness.image);
}

// ---- Geometry ----

TEST(Shapes, TransformsNormalsAndBilinearPatches) {
    Diagnostics diag;
    auto s = BuildWorld("AttributeBegin\nTranslate 0 0 5\nScale 2 1 1\n"
                        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"normal N\" [1 0 1 1 0 1 1 0 1]\nAttributeEnd\n"
                        "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n"
                        "Shape \"disk\" \"float radius\" 3 \"float height\" 1\n",
                        diag);
    ASSERT_EQ(s->triangleMeshes.size(), 2u);
    const TriangleMesh &m = s->triangleMeshes[0];
    EXPECT_EQ(m.triangleCount, 1u);  // indices optional for exactly 3 points
    EXPECT_EQ(s->positions[m.firstVertex + 1].x, 2.f);
    EXPECT_EQ(s->positions[m.firstVertex + 1].z, 5.f);
    Vec3f n = s->normals[m.normalOffset];  // inverse transpose: (1/2, 0, 1)
    EXPECT_NEAR(n.x / n.z, 0.5f, 1e-6f);
    EXPECT_FALSE(m.flipNormals);
    const TriangleMesh &q = s->triangleMeshes[1];
    EXPECT_EQ(q.triangleCount, 2u);
    ASSERT_NE(q.uvOffset, NoIndex);
    EXPECT_EQ(s->uvs[q.uvOffset + 3].x, 1.f);  // the patch's (u, v) at p11
    EXPECT_EQ(s->uvs[q.uvOffset + 3].y, 1.f);
    EXPECT_EQ(s->stats.triangles, 3u);
    EXPECT_EQ(s->disks.size(), 1u);
    EXPECT_NEAR(s->bounds.pMin.x, -3, 1e-6);
    EXPECT_NEAR(s->bounds.pMax.z, 5, 1e-6);
}

TEST(Shapes, InstancesAreFlattened) {
    Diagnostics diag;
    auto s = BuildWorld("ObjectBegin \"tri\"\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\nObjectEnd\n"
                        "AttributeBegin\nTranslate 10 0 0\nObjectInstance \"tri\"\nAttributeEnd\n"
                        "AttributeBegin\nTranslate -10 0 0\nObjectInstance \"tri\"\nAttributeEnd\n",
                        diag);
    EXPECT_EQ(s->stats.triangles, 2u);
    EXPECT_EQ(s->stats.instanceUses, 2);
    EXPECT_EQ(s->stats.instanceDefinitions, 1);
    EXPECT_NEAR(s->bounds.pMin.x, -10, 1e-6);
    EXPECT_NEAR(s->bounds.pMax.x, 11, 1e-6);
}

// ---- Settings ----

TEST(Settings, IntegratorsAndSamplers) {
    Diagnostics diag;
    auto s = Build("Integrator \"sppm\" \"integer maxdepth\" 9 \"float radius\" 0.01\nSampler \"independent\" \"integer pixelsamples\" 32\nWorldBegin\n", diag);
    EXPECT_EQ(s->settings.integrator, IntegratorKind::Path);
    EXPECT_EQ(s->stats.integratorAsRead, "sppm");
    EXPECT_EQ(s->settings.maxDepth, 9);
    EXPECT_EQ(s->stats.samplerName, "independent");
    EXPECT_EQ(s->sampler.kind, SamplerKind::Independent);
    EXPECT_EQ(s->settings.spp, 32);
    ASSERT_EQ(diag.unsupported.size(), 1u);
    EXPECT_EQ(diag.unsupported[0], "Integrator \"sppm\"");
    Diagnostics d2;
    auto r = Build("Integrator \"regpath\" \"float radius\" 0.05 \"float lambda\" 0.25 \"float angle\" 3\nWorldBegin\n", d2);
    EXPECT_EQ(r->settings.integrator, IntegratorKind::RegPath);
    EXPECT_TRUE(r->settings.Regularizes());
    EXPECT_DOUBLE_EQ(r->settings.regRadius, 0.05);
    EXPECT_DOUBLE_EQ(r->settings.regLambda, 0.25);
    EXPECT_DOUBLE_EQ(r->settings.regAngle, 3);
    Diagnostics d3;
    auto z = Build("WorldBegin\n", d3);
    EXPECT_EQ(z->stats.samplerName, "zsobol");
    EXPECT_EQ(z->sampler.kind, SamplerKind::ZSobol);
    EXPECT_EQ(z->settings.spp, 16);
    EXPECT_EQ(z->settings.maxDepth, 5);
    EXPECT_EQ(z->filter.kind, FilterKind::Gaussian);
    EXPECT_TRUE(d3.unsupported.empty());
}

TEST(Settings, UnusedParametersAreReportedByName) {
    Diagnostics diag;
    BuildWorld("Material \"diffuse\" \"float bogus\" 1\nShape \"sphere\" \"float radius\" 1 \"float zzz\" 2\n", diag);
    int found = 0;
    for (const std::string &w : diag.warnings)
        if ((Contains(w, "bogus") || Contains(w, "zzz")) && Contains(w, "not used")) ++found;
    EXPECT_EQ(found, 2);
}

// ---- Quadrics: pbrt-v4's cylinder, partial spheres and disks ----

TEST(Quadrics, CylinderPartialSphereAndDiskParameters) {
    Diagnostics diag;
    auto s = BuildWorld("LightSource \"point\"\nShape \"cylinder\"\n"
                        "AttributeBegin\nReverseOrientation\nShape \"cylinder\" \"float radius\" 0.5 \"float zmin\" 2 "
                        "\"float zmax\" -0.5 \"float phimax\" 400\nAttributeEnd\n"
                        "Shape \"sphere\" \"float radius\" 2 \"float zmin\" -3 \"float zmax\" 1 \"float phimax\" 90\n"
                        "Shape \"sphere\" \"float zmin\" -4 \"float zmax\" 4 \"float phimax\" 360\n"
                        "Shape \"disk\" \"float radius\" 2 \"float innerradius\" 1 \"float phimax\" 180\n",
                        diag);
    ASSERT_TRUE(s);
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    ASSERT_EQ(s->cylinders.size(), 2u);
    const Cylinder &c0 = s->cylinders[0], &c1 = s->cylinders[1];
    EXPECT_EQ(c0.radius, 1);
    EXPECT_EQ(c0.zMin, -1);
    EXPECT_EQ(c0.zMax, 1);
    EXPECT_EQ(c0.phiMax, 2 * Pi);
    EXPECT_FALSE(c0.flipNormals);
    EXPECT_EQ(c1.zMin, -0.5f);   // ordered, as pbrt-v4
    EXPECT_EQ(c1.zMax, 2);
    EXPECT_EQ(c1.phiMax, 2 * Pi);   // clamped to 360
    EXPECT_TRUE(c1.flipNormals);
    ASSERT_EQ(s->spheres.size(), 2u);
    const Sphere &sp = s->spheres[0];
    EXPECT_EQ(sp.zMin, -2);   // clamped to -radius
    EXPECT_EQ(sp.zMax, 1);
    EXPECT_NEAR(sp.thetaZMin, Pi, 1e-6f);
    EXPECT_NEAR(sp.thetaZMax, std::acos(0.5f), 1e-6f);
    EXPECT_NEAR(sp.phiMax, Pi / 2, 1e-6f);
    EXPECT_TRUE(IsPartial(sp));
    EXPECT_FALSE(IsPartial(s->spheres[1]));
    ASSERT_EQ(s->disks.size(), 1u);
    EXPECT_NEAR(s->disks[0].phiMax, Pi, 1e-6f);
    SceneView v = s->View();
    EXPECT_NEAR(PrimitiveArea(v, v.shapes[0], 0), 2 * 2 * Pi, 1e-5f);
    EXPECT_NEAR(PrimitiveArea(v, v.shapes[1], 0), 2.5f * 0.5f * 2 * Pi, 1e-5f);
    EXPECT_NEAR(PrimitiveArea(v, v.shapes[2], 0), Pi / 2 * 2 * 3, 1e-5f);
    EXPECT_NEAR(PrimitiveArea(v, v.shapes[4], 0), Pi / 2 * (4 - 1), 1e-5f);
    // pbrt-v4's bounds of the partial sphere: the z slab [-2, 1] of its box.
    EXPECT_NEAR(s->bounds.pMin.z, -2, 1e-5f);
    EXPECT_NEAR(s->bounds.pMax.z, 2, 1e-5f);   // the second cylinder reaches z = 2
    EXPECT_EQ(s->stats.shapesByType.at("cylinder"), 2);
}

TEST(Quadrics, AreaLightPowerUsesThePartialArea) {
    // pbrt-v4's "power" normalization over Area(): (zmax - zmin) r phimax = 2 x 0.5 x pi for the
    // half cylinder, phimax r (zmax - zmin) = pi / 2 x 1.5 for the partial sphere, phimax / 2
    // (r^2 - ri^2) = pi / 4 x 0.75 for the disk sector.
    const double Y = CIE_Y_integral, pi = 3.14159265358979;
    const std::pair<const char *, double> cases[] = {
        {"Shape \"cylinder\" \"float radius\" 0.5 \"float phimax\" 180", pi},
        {"Shape \"sphere\" \"float zmin\" -0.5 \"float phimax\" 90", pi / 2 * 1.5},
        {"Shape \"disk\" \"float innerradius\" 0.5 \"float phimax\" 90", pi / 4 * 0.75},
    };
    for (auto [shape, area] : cases) {
        SCOPED_TRACE(shape);
        Diagnostics diag;
        auto s = BuildWorld(std::string("AreaLightSource \"diffuse\" \"float power\" 20\n") + shape + "\n", diag);
        ASSERT_EQ(s->lights.size(), 1u);
        EXPECT_NEAR(s->lights[0].scale / (20 / (pi * area) / Y), 1, 2e-3);
    }
}

TEST(Quadrics, EmptyShapesAreDroppedWithAWarning) {
    Diagnostics diag;
    auto s = BuildWorld("LightSource \"point\"\nShape \"sphere\"\nShape \"cylinder\" \"float zmin\" 0.5 \"float zmax\" 0.5\n"
                        "Shape \"sphere\" \"float phimax\" 0\nShape \"disk\" \"float phimax\" -10\n",
                        diag);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->shapes.size(), 1u);
    ASSERT_EQ(diag.warnings.size(), 3u);
    for (const std::string &w : diag.warnings) EXPECT_TRUE(Contains(w, "no area")) << w;
}

// ---- One test per builder error class: message and line ----

void ExpectError(const std::string &world, int line, const std::string &needle) {
    SceneError e = ErrorOf(std::string(kHeader) + world);
    EXPECT_TRUE(Contains(e.Message(), needle)) << e.Message();
    EXPECT_EQ(e.Loc().line, line) << e.Format();
}

TEST(Errors, UnknownMaterial) { ExpectError("Shape \"sphere\"\nMaterial \"plastic\"\nShape \"sphere\"\n", 5, "\"plastic\""); }
TEST(Errors, UnsupportedMaterial) { ExpectError("Material \"mix\" \"string materials\" [\"a\" \"b\"]\n", 4, "\"mix\""); }
TEST(Errors, UnknownShape) { ExpectError("Shape \"sphere\"\nShape \"teapot\"\n", 5, "\"teapot\""); }
TEST(Errors, CurveWithoutControlPoints) { ExpectError("Shape \"curve\"\n", 4, "0 control points"); }
TEST(Errors, CylinderRadius) {
    ExpectError("Shape \"sphere\"\nShape \"cylinder\"\n  \"float radius\" -1\n", 6, "cylinder radius must be positive");
}
TEST(Errors, UnknownLight) { ExpectError("LightSource \"laser\"\n", 4, "\"laser\""); }
TEST(Errors, UnsupportedLight) {
    ExpectError("LightSource \"infinite\"\n  \"point3 portal\" [ 0 0 0  1 0 0  1 1 0  0 1 0 ]\n", 5, "\"portal\"");
}
TEST(Errors, UnknownNamedSpectrum) {
    ExpectError("Material \"conductor\"\n  \"spectrum eta\" \"metal-Unobtainium-eta\"\nShape \"sphere\"\n", 5, "metal-Unobtainium-eta");
}
TEST(Errors, UndefinedNamedMaterial) { ExpectError("NamedMaterial \"nope\" Shape \"sphere\"\n", 4, "nope"); }
TEST(Errors, UndefinedTexture) {
    ExpectError("Material \"diffuse\"\n  \"texture reflectance\" \"wood\"\nShape \"sphere\"\n", 5, "wood");
}
TEST(Errors, UnknownTextureType) { ExpectError("Texture \"t\" \"float\" \"plasma\"\n", 4, "\"plasma\""); }
TEST(Errors, BadResolution) {
    SceneError e = ErrorOf("Film \"rgb\" \"integer xresolution\" [ 0 ]\nWorldBegin\n");
    EXPECT_TRUE(Contains(e.Message(), "resolution")) << e.Message();
    EXPECT_EQ(e.Loc().line, 1);
    SceneError huge = ErrorOf("Film \"rgb\"\n \"integer xresolution\" [ 100000 ] \"integer yresolution\" [ 100000 ]\nWorldBegin\n");
    EXPECT_TRUE(Contains(huge.Message(), "too large")) << huge.Message();
    EXPECT_EQ(huge.Loc().line, 2);
}
TEST(Errors, BadFov) {
    for (const char *fov : {"180", "0", "-5", "200"}) {
        SceneError e = ErrorOf(std::string("Film \"rgb\"\nCamera \"perspective\" \"float fov\" [ ") + fov + " ]\nWorldBegin\n");
        EXPECT_TRUE(Contains(e.Message(), "fov")) << e.Message();
        EXPECT_EQ(e.Loc().line, 2);
    }
}
// Malformed media: errors at the offending line, naming what is wrong.
TEST(Errors, Media) {
    ExpectLocatedErrors(kHeader, {
        {"MakeNamedMedium \"fog\" \"string type\" \"smoke\"\n", 4, "unknown medium type \"smoke\""},
        {"MakeNamedMedium \"fog\" \"float scale\" 2\n", 4, "no \"string type\""},
        {"MakeNamedMedium \"fog\" \"string type\" \"uniformgrid\" \"integer nx\" 2\n  \"float density\" [ 1 -0.5 ]\n", 5,
         "\"density\" value 1 is -0.5"},
        {"MakeNamedMedium \"fog\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"integer ny\" 2\n  \"float density\" [ 1 2 3 ]\n",
         5, "3 \"density\" values, but nx*ny*nz = 2*2*1 = 4"},
        {"MakeNamedMedium \"fog\" \"string type\" \"uniformgrid\"\n", 4, "no \"density\" values"},
        {"MakeNamedMedium \"fog\" \"string type\" \"rgbgrid\" \"integer nx\" 2\n  \"rgb sigma_a\" [ 1 1 1 ]\n", 5,
         "1 \"sigma_a\" values, but nx*ny*nz = 2*1*1 = 2"},
        {"MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"float g\" 1\n", 4, "\"g\" must be in (-1"},
        {"MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n  \"rgb sigma_a\" [ -1 0 0 ]\n", 5, "negative"},
        {"MakeNamedMedium \"fog\" \"string type\" \"cloud\"\n  \"float density\" -2\n", 5, "\"density\" must be in [0"},
        {"MakeNamedMedium \"fog\" \"string type\" \"cloud\" \"float wispiness\" nan\n", 4, "non-finite"},
        {"MakeNamedMedium \"fog\" \"string type\" \"cloud\"\n  \"point3 p0\" [ 0 2 0 ]\n", 4, "p0 < p1"},
        {"MakeNamedMedium \"fog\" \"string type\" \"nanovdb\"\n  \"string filename\" \"missing.nvdb\"\n", 5, "cannot read NanoVDB file"},
        {"MediumInterface \"mist\" \"\"\nShape \"sphere\"\n", 5, "medium \"mist\" is not defined"},
    });
    // A NaN in a grid is refused where it is written.
    SceneError e = ErrorOf(std::string(kHeader) + "MakeNamedMedium \"fog\" \"string type\" \"uniformgrid\" \"integer nx\" 2\n"
                                                  "  \"float density\" [ 1 nan ]\n");
    EXPECT_EQ(e.Loc().line, 5) << e.Message();
}
TEST(Errors, AlbedoAboveOne) { ExpectError("Material \"diffuse\" \"rgb reflectance\" [ 1.5 0 0 ]\n", 4, "reflectance"); }
TEST(Errors, UnknownIntegratorAndFilter) {
    SceneError e = ErrorOf("Integrator \"photonmap\"\nWorldBegin\n");
    EXPECT_TRUE(Contains(e.Message(), "\"photonmap\"")) << e.Message();
    SceneError f = ErrorOf("PixelFilter \"lanczos\"\nWorldBegin\n");
    EXPECT_TRUE(Contains(f.Message(), "\"lanczos\"")) << f.Message();
    EXPECT_EQ(f.Loc().line, 1);
    SceneError t = ErrorOf("PixelFilter \"sinc\"\n  \"float tau\" 0\nWorldBegin\n");
    EXPECT_TRUE(Contains(t.Message(), "tau")) << t.Message();
    EXPECT_EQ(t.Loc().line, 2);
}

// ---- The Option directive (pbrt-v4's BasicSceneBuilder::Option) ----

TEST(OptionDirective, SetsJitterAndSeedAsPbrtV4) {
    Diagnostics diag;
    auto s = Build("Option \"disablepixeljitter\" true\nOption \"Disable_Wavelength-Jitter\" true\nOption \"seed\" 7\n" +
                       std::string(kHeader),
                   diag);
    EXPECT_TRUE(s->filter.disableJitter);
    EXPECT_TRUE(s->film.disableWavelengthJitter);
    EXPECT_EQ(s->settings.seed, 7u);  // the sampler's default seed
    EXPECT_TRUE(diag.unsupported.empty());
    // A Sampler's own "seed" wins; without Options nothing is set.
    auto t = Build("Option \"seed\" 7\nSampler \"zsobol\" \"integer seed\" 3\n" + std::string(kHeader), diag);
    EXPECT_EQ(t->settings.seed, 3u);
    auto u = Build(std::string(kHeader), diag);
    EXPECT_FALSE(u->filter.disableJitter);
    EXPECT_FALSE(u->film.disableWavelengthJitter);
    EXPECT_EQ(u->settings.seed, 0u);
    // Options that change only pbrt-v4's run are accepted without a report.
    Diagnostics quiet;
    Build("Option \"wavefront\" false\nOption \"disabletexturefiltering\" true\nOption \"rendercoordsys\" \"world\"\n" +
              std::string(kHeader),
          quiet);
    Diagnostics baseline;   // the header alone warns of its missing light
    Build(std::string(kHeader), baseline);
    EXPECT_TRUE(quiet.unsupported.empty());
    EXPECT_EQ(quiet.warnings.size(), baseline.warnings.size());
    // pixelstats and the MSE reference are reported by name, the picture is unchanged.
    Diagnostics listed;
    Build("Option \"pixelstats\" true\nOption \"msereferenceimage\" \"ref.exr\"\n" + std::string(kHeader), listed);
    EXPECT_EQ(listed.unsupported.size(), 2u);
}

// With the pixel jitter off every camera sample is the pixel center with weight 1 (the filter
// sample is still drawn: the sampler's dimensions stay pbrt-v4's).
TEST(OptionDirective, DisabledPixelJitterSamplesThePixelCenter) {
    Diagnostics diag;
    auto s = Build("Option \"disablepixeljitter\" true\nPixelFilter \"mitchell\"\n" + std::string(kHeader), diag);
    SceneView view = s->View();
    Sampler sampler = s->sampler;
    for (int i = 0; i < 16; ++i) {
        sampler.StartPixelSample(3, 5, i, 0);
        CameraSample cs = GetCameraSample(sampler, 3, 5, s->filter, view);
        EXPECT_EQ(cs.pFilm.x, 3.5f);
        EXPECT_EQ(cs.pFilm.y, 5.5f);
        EXPECT_EQ(cs.filterWeight, 1.f);
    }
    s->filter.disableJitter = false;
    int offCenter = 0;
    for (int i = 0; i < 16; ++i) {
        sampler.StartPixelSample(3, 5, i, 0);
        offCenter += GetCameraSample(sampler, 3, 5, s->filter, view).pFilm.x != 3.5f;
    }
    EXPECT_GT(offCenter, 12);
}

TEST(OptionDirective, BadOptionsAreLocated) {
    ExpectLocatedErrors("", {
        {"# comment\nOption \"fastmode\" true\n", 2, "unknown option"},
        {"Option \"disablepixeljitter\" yes\n", 1, "true or false"},
        {"Option \"disablepixeljitter\" \"true\"\n", 1, "true or false"},
        {"\nOption \"seed\" 1.5\n", 2, "integer"},
        {"Option \"rendercoordsys\" \"screen\"\n", 1, "coordinate system"},
        {"Option \"rendercoordsys\" world\n", 1, "quoted string"},
        {"Option \"forcediffuse\" true\n", 1, "forcediffuse"},
    }, kHeader);
}

// ---- Shape alpha (pbrt-v4's getAlphaTexture) ----

// "float alpha" >= 1 is opaque (no texture); below 1 a constant node; "texture alpha" the named
// texture; every shape of the directive (the triangles of a mesh, a prototype's shapes) carries it.
TEST(ShapeAlpha, ResolvesToAFloatTexture) {
    Diagnostics diag;
    auto s = BuildWorld("Texture \"checks\" \"float\" \"checkerboard\" \"float tex1\" 0 \"float tex2\" 1\n"
                        "Shape \"sphere\" \"float alpha\" 1\n"
                        "Shape \"sphere\" \"float alpha\" 0.25\n"
                        "Shape \"disk\" \"texture alpha\" \"checks\"\n"
                        "ObjectBegin \"o\"\nShape \"sphere\" \"float alpha\" 0\nObjectEnd\n"
                        "ObjectInstance \"o\"\nObjectInstance \"o\"\n",
                        diag);
    ASSERT_TRUE(s);
    ASSERT_EQ(s->shapes.size(), 4u);
    EXPECT_EQ(s->shapes[0].alpha, NoIndex);
    ASSERT_NE(s->shapes[1].alpha, NoIndex);
    EXPECT_EQ(s->floatTextures[s->shapes[1].alpha].kind, TextureKind::Constant);
    EXPECT_FLOAT_EQ(s->floatTextures[s->shapes[1].alpha].value, 0.25f);
    ASSERT_NE(s->shapes[2].alpha, NoIndex);
    EXPECT_EQ(s->floatTextures[s->shapes[2].alpha].kind, TextureKind::Checkerboard);
    ASSERT_EQ(s->prototypes.size(), 1u);
    EXPECT_NE(s->shapes[3].alpha, NoIndex);   // the prototype's sphere
    EXPECT_EQ(s->View().alphaShapes, 3u);
    EXPECT_TRUE(diag.unsupported.empty());
}

// Bad input: an alpha texture that does not exist, a wrong type, and the invisible emitter
// (constant alpha 0 on an area light, which pbrt-v4 samples as a delta light) Lucerna refuses.
TEST(ShapeAlpha, BadInputNamesTheParameter) {
    ExpectError("Shape \"sphere\"\nShape \"sphere\" \"texture alpha\" \"nope\"\n", 5,
                "couldn't find float texture named \"nope\" for parameter \"alpha\"");
    ExpectError("Shape \"sphere\" \"rgb alpha\" [ 1 1 1 ]\n", 4, "\"rgb alpha\" has the wrong type");
    ExpectError("AttributeBegin\nAreaLightSource \"diffuse\"\nShape \"sphere\" \"float alpha\" 0\nAttributeEnd\n", 6,
                "area light with a constant \"alpha\" of 0");
    // The CLI: file:line:col, exit 2, nothing written.
    std::string dir = test::TempDir("alpha_bad");
    std::ofstream(dir + "/bad.pbrt") << kHeader << "LightSource \"point\"\nShape \"sphere\" \"texture alpha\" \"nope\"\n";
    test::ProcessResult r = test::RunProcess({test::LucernaBinary(), "render", dir + "/bad.pbrt", "-o", dir + "/bad.exr"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_TRUE(Contains(r.output, dir + "/bad.pbrt:5:16: error: couldn't find float texture named \"nope\"")) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.exr"));
}

}  // namespace
}  // namespace lu
