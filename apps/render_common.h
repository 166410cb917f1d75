// Lucerna CLI: scene loading and backend dispatch shared by `render` and `converge`.
#pragma once

#include <memory>
#include <string>

#include "lucerna/render/render_job.h"
#include "lucerna/scene/builder.h"

namespace lu::app {

struct RenderRequest {
    std::string sceneFile, integrator, res, device = "auto";
    int spp = 0, maxDepth = -1, threads = 0;
    long long seed = -1;
    double time = 0, regRadius = -1, regLambda = -1, regAngle = -1;
    bool progress = true;
};

struct Prepared {
    std::unique_ptr<HostScene> scene;
    RenderJob job;
    std::string integratorName;   // "path" or "regpath"
    std::string deviceName;       // what actually renders
    uint64_t sceneHash = 0;       // scene file + settings that determine the sums (checkpoints)
    std::string sceneFile;
};

struct RenderOutcome {
    RenderStats stats;
    uint32_t passes = 0;          // total passes in the film
    int width = 0, height = 0;
    std::string integrator, device, sceneFile;
    double regRadius = 0, regLambda = 0, regAngle = 0;   // regpath: r0 (world units), lambda, sigma0 (radians)
};

// Loads and validates; prints diagnostics; returns an exit code (0 ok, 2 bad input).
int PrepareRender(const RenderRequest &req, Prepared *out);
// Default r0: a fraction of the scene bounding-box diagonal (see docs/regularization.md).
double DefaultRegRadius(const Bounds3f &bounds);
// Runs the chosen backend from film.passes up to job.spp.
int RunBackend(Prepared &prep, FilmAccumulator &film, const PassCallback &onPass, RenderOutcome *out);
// EXR (with lucerna.* metadata, spp reached) and optionally PNG; atomic writes.
void WriteOutputs(const Prepared &prep, const FilmAccumulator &film, const RenderOutcome &out, const std::string &path, bool png);
std::string DefaultOutputName(const Prepared &prep);
std::string SummaryLine(const RenderOutcome &o);
std::string StatsJson(const RenderOutcome &o);

}  // namespace lu::app
