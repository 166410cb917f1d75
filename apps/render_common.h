// Lucerna CLI: scene loading, settings and backend dispatch shared by `render` and `converge`.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lucerna/render/pass_driver.h"
#include "lucerna/scene/builder.h"

namespace lu::app {

// Render settings given on the command line, by name (scene/render_settings.h), in order.
using SettingOverrides = std::vector<std::pair<std::string, std::string>>;

// Registers every render setting as --NAME on `sub` (except those in `exclude`); the ones given
// are appended to *overrides when CLI11 parses them. Also -q/--quiet for "progress false".
void AddSettingOptions(CLI::App *sub, SettingOverrides *overrides, const std::vector<std::string> &exclude = {});

struct Prepared {
    std::unique_ptr<HostScene> scene;
    RenderSettings settings;      // the scene's, then the command line's
    std::string deviceName;       // what actually renders ("cpu", "cuda NAME")
    uint64_t checkpointKey = 0;   // scene file, resolution, sampler and the settings that determine the sums
    std::string sceneFile;
};

// Loads the scene and applies the overrides; prints diagnostics; returns an exit code (0 ok, 2 bad
// input). `res` is "" or "WxH". "time" given without "spp": passes until the time budget.
int PrepareRender(const std::string &sceneFile, const std::string &res, const SettingOverrides &overrides, Prepared *out);

struct RenderOutcome {
    RenderStats stats;
    uint32_t passes = 0;          // total passes in the film
    bool writer = true;           // writes the outputs (false: an MPI rank other than 0)
};

// Runs the chosen backend from film.passes up to settings.spp; under mpirun, every rank's share of
// the passes (render/distributed.h) with the sums and statistics on rank 0.
int RunBackend(Prepared &prep, FilmAccumulator &film, const RenderControl &control, RenderOutcome *out);
// EXR (with lucerna.* metadata, spp reached) and optionally PNG; atomic writes.
void WriteOutputs(const Prepared &prep, const FilmAccumulator &film, const RenderOutcome &out, const std::string &path, bool png);
std::string DefaultOutputName(const Prepared &prep);
// The sRGB preview --png writes beside an EXR output: the same name with ".png".
std::string PngPreviewPath(const std::string &output);
std::string Lower(std::string s);
std::string SummaryLine(const Prepared &prep, const RenderOutcome &o);
std::string StatsJson(const Prepared &prep, const RenderOutcome &o);

}  // namespace lu::app
