// Lucerna (host): the settings of a render as one object, after Tungsten's PathTracerSettings:
// each setting has a name, a default and a check; the scene's Integrator and Sampler directives
// set them (scene/builder.cpp), the command line overrides them by name, they print themselves and
// hash into checkpoints. Each pass hands the per-path code its PathSettings (ForPass).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lucerna/integrators/techniques.h"

namespace lu {

enum class IntegratorKind : uint8_t { Path, RegPath };
enum class DeviceKind : uint8_t { Auto, CPU, CUDA };
// The CPU backend's ray tracer: Embree, or the shared BVH traversal that the CUDA kernel runs.
enum class CpuTracer : uint8_t { Embree, BVH };

struct RenderSettings {
    // ---- Integrator: the scene's Integrator directive ("path", "regpath") ----
    IntegratorKind integrator = IntegratorKind::Path;
    int maxDepth = 5;                       // "maxdepth"
    LightStrategy lightStrategy = LightStrategy::MIS;   // direct-light techniques (tests, diagnosis)
    double regRadius = 0;                   // "radius": r0 in world units; 0 (auto): 0.04 x the scene's diagonal
    double regLambda = 1.0 / 6;             // "lambda": r_N = r0 N^-lambda
    double regAngle = 2;                    // "angle": sigma0 in degrees, for lights at infinity
    double regFootprint = -1;               // "footprint": K pixels, kernels from the pixel's footprint (0: off;
                                            // -1, auto: kDefaultRegFootprint unless a radius is given, else 0)
    bool mnee = true;                       // "mnee": regpath adds manifold NEE through refractive chains
    bool beamSegments = true;               // "beam-segments": regpath samples beams in media along ray segments
    bool nearSpecular = true;               // "near-specular": regpath widens near-specular lobes for delta lights
    // ---- Sampling: the scene's Sampler directive ----
    uint32_t seed = 0;                      // "seed"
    int spp = 16;                           // passes to render; default "pixelsamples"
    // ---- Run ----
    double timeLimit = 0;                   // seconds (0: none); stops at the first pass boundary after it
    int threads = 0;                        // CPU threads; 0: all cores
    DeviceKind device = DeviceKind::Auto;
    CpuTracer cpuTracer = CpuTracer::Embree;
    bool progress = true;                   // progress line on stderr

    // Not a setting: the scene's bounding-box diagonal (the builder), for the auto radius.
    double sceneDiagonal = 0;

    bool Regularizes() const { return integrator == IntegratorKind::RegPath; }
    // r0 in world units: the given radius, else 0.04 x the scene's diagonal (bench/reg_radius.sh).
    // Collimated beams always use it; the other lights when the footprint is 0.
    double ResolvedRegRadius() const { return regRadius > 0 ? regRadius : sceneDiagonal > 0 ? 0.04 * sceneDiagonal : 0.01; }
    // K in pixels (0: world-space kernels of radius r0): the given footprint, else the default
    // when no radius is given (bench/reg_footprint.sh, docs/regularization.md).
    double ResolvedRegFootprint() const { return regFootprint >= 0 ? regFootprint : regRadius > 0 ? 0 : kDefaultRegFootprint; }
    static constexpr double kDefaultRegFootprint = 16;
    // What the per-path code sees in pass `pass` (0-based): r_N and sigma_N of that pass.
    PathSettings ForPass(uint32_t pass) const;
};

// One setting as the command line and the printout name it.
struct SettingInfo {
    const char *name;   // "maxdepth", "reg-radius", ... (the command-line option is --NAME)
    const char *help;
    bool affectsImage;  // part of the checkpoint key: a film is resumed only with equal values
};
const std::vector<SettingInfo> &RenderSettingInfos();

// Sets setting `name` from its text form, checked; false with *error ("NAME: why") otherwise.
bool SetRenderSetting(RenderSettings &s, const std::string &name, const std::string &value, std::string *error);
// A setting's value as text (the form SetRenderSetting reads).
std::string RenderSettingValue(const RenderSettings &s, const std::string &name);
// "integrator regpath, maxdepth 5, reg-radius 0.18, ..." (every setting).
std::string DescribeRenderSettings(const RenderSettings &s);
// A hash of the settings that determine the image's sums (SettingInfo::affectsImage).
uint64_t HashRenderSettings(const RenderSettings &s, uint64_t seed = 1469598103934665603ull);

// Integrator kind by pbrt-v4/Lucerna name ("path", "regpath"); false for others.
bool ParseIntegratorName(const std::string &name, IntegratorKind *kind);
const char *IntegratorName(IntegratorKind k);

}  // namespace lu
