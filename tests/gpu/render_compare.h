// Lucerna tests: statistical comparison of two renderers' images (CPU vs GPU, Embree vs the shared
// BVH). Each side renders S seeds; per pixel and channel the mean and the variance over seeds give
// block means with standard errors, compared by a two-sample z-test with a Sidak-corrected
// threshold (as Mitsuba's reference-image tests do). Header-only.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "lucerna/render/pass_driver.h"
#include "lucerna/image/image.h"
#include "lucerna/scene/builder.h"

namespace lu::test {

// The settings `lucerna render SCENE --integrator I --spp N --seed S -q` would use.
inline RenderSettings SettingsFor(const HostScene &scene, const std::string &integrator, int spp, uint32_t seed) {
    RenderSettings s = scene.settings;
    s.integrator = integrator == "regpath" ? IntegratorKind::RegPath : IntegratorKind::Path;
    s.spp = spp;
    s.seed = seed;
    s.progress = false;
    return s;
}

// z such that P(|N(0,1)| > z) = p (bisection on erfc).
inline double TwoSidedZ(double p) {
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; ++i) {
        double mid = 0.5 * (lo + hi);
        (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Per-test p-value threshold for m tests at family-wise level alpha (Sidak).
inline double SidakP(double alpha, int m) { return 1 - std::pow(1 - alpha, 1.0 / std::max(1, m)); }

struct BlockComparison {
    int tests = 0, failures = 0;
    double maxAbsZ = 0;
    std::string worst;   // where |z| is largest
    std::string Summary() const {
        char buf[256];
        std::snprintf(buf, sizeof buf, "%d block tests, %d over threshold, max |z| %.2f at %s", tests, failures, maxAbsZ,
                      worst.c_str());
        return buf;
    }
};

// Mean over seeds and variance of that mean, per pixel and channel.
struct SeedMoments {
    int width = 0, height = 0, channels = 0;
    std::vector<double> mean, varOfMean;
};
inline SeedMoments MomentsOverSeeds(const std::vector<Image> &images) {
    SeedMoments m;
    const Image &f = images.front();
    m.width = f.width; m.height = f.height; m.channels = f.channels;
    size_t n = f.pixels.size();
    int s = int(images.size());
    m.mean.assign(n, 0);
    m.varOfMean.assign(n, 0);
    for (const Image &im : images)
        for (size_t i = 0; i < n; ++i) m.mean[i] += im.pixels[i];
    for (size_t i = 0; i < n; ++i) m.mean[i] /= s;
    for (const Image &im : images)
        for (size_t i = 0; i < n; ++i) m.varOfMean[i] += (im.pixels[i] - m.mean[i]) * (im.pixels[i] - m.mean[i]);
    for (size_t i = 0; i < n; ++i) m.varOfMean[i] /= double(s - 1) * s;
    return m;
}

// Compares block means (block x block pixels, every channel) of two seed sets rendered
// independently (different seeds). Pixels are treated as independent within a block. Each test
// fails when |z| exceeds zThreshold; the caller picks it (TwoSidedZ(SidakP(alpha, tests))).
// Blocks whose both sides have (near) zero variance must agree to `relTolDeterministic`.
inline BlockComparison CompareBlockMeans(const std::vector<Image> &a, const std::vector<Image> &b, int block,
                                         double zThreshold, double relTolDeterministic = 1e-4) {
    SeedMoments ma = MomentsOverSeeds(a), mb = MomentsOverSeeds(b);
    BlockComparison r;
    for (int by = 0; by < ma.height; by += block)
        for (int bx = 0; bx < ma.width; bx += block)
            for (int c = 0; c < ma.channels; ++c) {
                double sa = 0, sb = 0, va = 0, vb = 0;
                int n = 0;
                for (int y = by; y < std::min(by + block, ma.height); ++y)
                    for (int x = bx; x < std::min(bx + block, ma.width); ++x) {
                        size_t i = (size_t(y) * ma.width + x) * ma.channels + c;
                        sa += ma.mean[i]; sb += mb.mean[i];
                        va += ma.varOfMean[i]; vb += mb.varOfMean[i];
                        ++n;
                    }
                double meanA = sa / n, meanB = sb / n;
                // A floor for rounding differences in noise-free blocks (directly seen emitters, black).
                double floorSE = relTolDeterministic * std::max(std::abs(meanA), std::abs(meanB)) + 1e-7;
                double se = std::sqrt((va + vb) / (double(n) * n) + floorSE * floorSE);
                double z = (meanA - meanB) / se;
                ++r.tests;
                if (std::abs(z) > zThreshold) ++r.failures;
                if (std::abs(z) > r.maxAbsZ) {
                    r.maxAbsZ = std::abs(z);
                    char buf[160];
                    std::snprintf(buf, sizeof buf, "block (%d,%d) channel %d: %.5g vs %.5g (se %.2g)", bx, by, c, meanA,
                                  meanB, se);
                    r.worst = buf;
                }
            }
    return r;
}

inline bool AllFinite(const Image &img) {
    for (float v : img.pixels)
        if (!std::isfinite(v)) return false;
    return true;
}

}  // namespace lu::test
