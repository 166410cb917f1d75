// Lucerna integrator tests: render a scene given as text or file, with statistics over pixels.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

#include "lucerna/backend/cpu/cpu_render.h"
#include "lucerna/camera/camera.h"
#include "lucerna/image/image.h"
#include "lucerna/scene/builder.h"
#include "support/test_support.h"

namespace lu::test {

struct RenderResultForTest {
    Image image;
    RenderStats stats;
};

inline std::unique_ptr<HostScene> LoadSceneText(const std::string &name, const std::string &text, const BuildOptions &opts = {}) {
    std::string dir = TempDir(name);
    std::string path = dir + "/scene.pbrt";
    std::ofstream(path) << text;
    Diagnostics diag;
    diag.quiet = true;
    return LoadScene(path, diag, opts);
}

// The scenes of scenes/features/ whose file names start with one of the prefixes, sorted.
inline std::vector<std::string> FeatureSceneFiles(std::initializer_list<const char *> prefixes) {
    std::vector<std::string> files;
    for (const auto &e : std::filesystem::directory_iterator(std::string(LUCERNA_SOURCE_DIR) + "/scenes/features")) {
        std::string name = e.path().filename().string();
        if (e.path().extension() != ".pbrt") continue;
        for (const char *prefix : prefixes)
            if (name.rfind(prefix, 0) == 0) files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// A feature scene loaded at resX x resY that must read without an unsupported feature or a warning.
inline std::unique_ptr<HostScene> LoadCleanFeatureScene(const std::string &file, int resX, int resY) {
    Diagnostics diag;
    diag.quiet = true;
    BuildOptions opts;
    opts.resX = resX;
    opts.resY = resY;
    auto scene = LoadScene(file, diag, opts);
    EXPECT_TRUE(diag.unsupported.empty()) << diag.unsupported[0];
    EXPECT_TRUE(diag.warnings.empty()) << diag.warnings[0];
    return scene;
}

// The scene's own settings with a fixed pass count, quiet.
inline RenderSettings TestSettings(const HostScene &scene, int spp, int maxDepth, uint32_t seed = 0) {
    RenderSettings s = scene.settings;
    s.spp = spp;
    s.maxDepth = maxDepth;
    s.seed = seed;
    s.progress = false;
    return s;
}

inline RenderResultForTest RenderScene(const HostScene &scene, const RenderSettings &settings) {
    FilmAccumulator film;
    RenderResultForTest r;
    r.stats = RenderCPU(scene, settings, film);
    r.image = film.Resolve(scene.View().film);
    return r;
}

// Renders settings.spp - firstPass passes starting at pass firstPass (the regularization
// schedule's N = firstPass + 1 ...), expecting no rejected sample.
inline Image RenderFromPass(const HostScene &scene, const RenderSettings &settings, uint32_t firstPass) {
    FilmAccumulator film;
    film.Resize(scene.View().film.width, scene.View().film.height);
    film.passes = firstPass;
    RenderStats st = RenderCPU(scene, settings, film);
    EXPECT_EQ(st.rejected, 0u);
    return film.Resolve(scene.View().film);
}

// regAngle in radians (RenderSettings::regAngle is in degrees).
inline RenderResultForTest RenderScene(const HostScene &scene, int spp, int maxDepth, uint32_t seed = 0, int threads = 0,
                                       int strategy = 0, bool regularize = false, double regRadius = 0, double regAngle = 0) {
    RenderSettings s = TestSettings(scene, spp, maxDepth, seed);
    s.threads = threads;
    s.lightStrategy = LightStrategy(strategy);
    s.integrator = regularize ? IntegratorKind::RegPath : IntegratorKind::Path;
    if (regRadius > 0) s.regRadius = regRadius;
    if (regAngle > 0) s.regAngle = regAngle * 180 / 3.14159265358979323846;
    return RenderScene(scene, s);
}

// Mean and standard error of channel c over a pixel rectangle [x0,x1) x [y0,y1).
struct MeanSE {
    double mean = 0, se = 0;
};
inline MeanSE RegionMean(const Image &img, int c, int x0, int y0, int x1, int y1) {
    double s = 0, s2 = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            double v = img.At(x, y, c);
            s += v; s2 += v * v; ++n;
        }
    MeanSE m;
    m.mean = s / n;
    double var = std::max(0.0, s2 / n - m.mean * m.mean);
    m.se = std::sqrt(var / std::max(1, n - 1));
    return m;
}

// A one-channel image of an analytic radiance, per pixel the mean of radiance(ray) over 4 x 4
// points (a box filter), for the scene's camera (pinhole: the lens sample at its centre).
template <typename RadianceFn>
Image AnalyticPixelImage(const HostScene &scene, RadianceFn radiance) {
    const CameraData &cam = scene.View().camera;
    Image img;
    img.width = cam.width;
    img.height = cam.height;
    img.channels = 1;
    img.pixels.assign(size_t(cam.width) * cam.height, 0.f);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            double sum = 0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    Ray ray;
                    EXPECT_TRUE(GenerateRay(cam, Vec2f(x + (sx + 0.5f) / 4, y + (sy + 0.5f) / 4), Vec2f(0.5f, 0.5f), &ray));
                    sum += radiance(ray);
                }
            img.At(x, y, 0) = float(sum / 16);
        }
    return img;
}

// Renders 4 spp (maxdepth 5): no rejected sample, every value finite, and a mean above 0.05.
inline void ExpectRendersFiniteAndLit(const HostScene &scene) {
    auto r = RenderScene(scene, 4, 5);
    EXPECT_EQ(r.stats.rejected, 0u);
    double sum = 0;
    for (float v : r.image.pixels) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum / double(r.image.pixels.size()), 0.05);
}

}  // namespace lu::test
