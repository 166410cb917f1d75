// Lucerna CLI: `lucerna render` — check every output path, load a pbrt-v4 scene, render
// progressively (CPU or CUDA), write EXR/PNG atomically, checkpoint/resume, stop cleanly on a
// signal (apps/interrupt.h: never an empty image over a previous one).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "apps/interrupt.h"
#include "apps/output_paths.h"
#include "apps/render_common.h"
#include "lucerna/backend/cpu/cpu_render.h"
#include "lucerna/image/image.h"
#include "lucerna/render/distributed.h"
#include "lucerna/render/rejected_sample.h"
#include "lucerna/scene/builder.h"

namespace lu::app {

namespace {

// The render command's own arguments; the render settings are given by name (AddSettingOptions).
struct RenderArgs {
    std::string scene, output, res, statsJson, checkpoint, resume;
    SettingOverrides settings;
    double checkpointEvery = 60;
    bool png = false;
};

// The image and, with --png, its sRGB preview beside it (apps/render_common.cpp: WriteOutputs).
void AddImageOutputs(const std::string &output, bool png, const char *role, std::vector<NamedPath> *outputs) {
    outputs->push_back({output, role, true});
    if (png && Lower(std::filesystem::path(output).extension().string()) != ".png")
        outputs->push_back({PngPreviewPath(output), "--png", true});
}

void WriteStatsJson(const std::string &path, const Prepared &prep, const RenderOutcome &o) {
    std::string tmp = path + ".tmp-" + std::to_string(getpid());
    {
        std::ofstream f(tmp);
        f << StatsJson(prep, o);
        f.close();
        if (!f) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw std::runtime_error("cannot write " + tmp);
        }
    }
    std::filesystem::rename(tmp, path);
}

// Before the first pass of this run there is nothing to save: a signal ends the render at once.
constexpr const char *kNothingWritten[2] = {
    "reading the scene; nothing written, existing files left as they were",
    "building the acceleration structure or rendering the first pass; nothing written, existing files left as they were"};

int BadInput(const std::string &why) {
    std::fprintf(stderr, "lucerna: error: %s\n", why.c_str());
    return ExitBadInput;
}

int RunRender(const RenderArgs &a) {
    InstallSignalHandlers();
    SetExitStage("checking the arguments; nothing written");
    // ---- Every output is checked before the scene is read ----
    std::vector<NamedPath> outputs, inputs = {{a.scene, "the scene file"}};
    if (!a.output.empty()) AddImageOutputs(a.output, a.png, "-o", &outputs);
    if (!a.statsJson.empty()) outputs.push_back({a.statsJson, "--stats-json"});
    if (!a.checkpoint.empty()) outputs.push_back({a.checkpoint, "--checkpoint"});
    if (!a.resume.empty()) inputs.push_back({a.resume, "--resume"});
    // A render may continue a checkpoint and keep saving into the same file (it is read first).
    const std::vector<std::pair<std::string, std::string>> allowed = {{"--checkpoint", "--resume"}};
    if (std::string why = CheckOutputs(outputs); !why.empty()) return BadInput(why);
    if (std::string why = CheckDistinct(outputs, inputs, allowed); !why.empty()) return BadInput(why);

    SetExitStage(kNothingWritten[0]);
    Prepared prep;
    int rc = PrepareRender(a.scene, a.res, a.settings, &prep);
    if (rc != ExitOk) return rc;
    // The default output comes from the scene (Film "filename", else the scene's name); the
    // inputs are every file the scene read.
    std::string output = a.output.empty() ? DefaultOutputName(prep) : a.output;
    if (a.output.empty()) {
        std::vector<NamedPath> defaults;
        AddImageOutputs(output, a.png, "the output image (Film \"filename\" or the scene's name)", &defaults);
        if (std::string why = CheckOutputs(defaults); !why.empty()) return BadInput(why);
        outputs.insert(outputs.begin(), defaults.begin(), defaults.end());
    }
    for (size_t i = 1; i < prep.scene->inputFiles.size(); ++i)
        inputs.push_back({prep.scene->inputFiles[i], "the scene's input file"});
    if (std::string why = CheckDistinct(outputs, inputs, allowed); !why.empty()) return BadInput(why);

    FilmAccumulator film;
    double secondsBefore = 0;
    if (!a.resume.empty()) {
        CheckpointInfo info;
        try {
            LoadCheckpoint(a.resume, &film, &info);
        } catch (const std::exception &e) {
            return BadInput(e.what());
        }
        if (info.sceneHash != prep.checkpointKey || film.width != prep.scene->film.width ||
            film.height != prep.scene->film.height) {
            std::fprintf(stderr, "lucerna: error: %s: checkpoint was made for a different scene or settings (%s, %s, seed %u)\n",
                         a.resume.c_str(), info.sceneFile.c_str(), info.integrator.c_str(), info.seed);
            return ExitBadInput;
        }
        secondsBefore = info.seconds;
        std::fprintf(stderr, "resuming %s at pass %u of %d\n", a.resume.c_str(), film.passes, prep.settings.spp);
    }
    if (std::string why = CreateOutputFolders(outputs); !why.empty()) return BadInput(why);

    auto lastCheckpoint = std::chrono::steady_clock::now();
    auto saveCheckpoint = [&](const FilmAccumulator &f, double seconds) {
        CheckpointInfo info;
        info.sceneFile = a.scene;
        info.integrator = IntegratorName(prep.settings.integrator);
        info.seed = prep.settings.seed;
        info.sceneHash = prep.checkpointKey;
        info.seconds = secondsBefore + seconds;
        SaveCheckpoint(a.checkpoint, f, info);
    };
    PassCallback onPass = [&](const FilmAccumulator &f, const RenderStats &st) {
        SetExitStage(nullptr);   // the film holds a pass of this run: from now on a signal stops at the pass in flight
        auto now = std::chrono::steady_clock::now();
        if (!a.checkpoint.empty() && std::chrono::duration<double>(now - lastCheckpoint).count() >= a.checkpointEvery) {
            try {
                saveCheckpoint(f, st.seconds);
            } catch (const std::exception &e) {
                std::fprintf(stderr, "lucerna: warning: %s (the render goes on)\n", e.what());
            }
            lastCheckpoint = now;
        }
        return true;
    };

    SetExitStage(kNothingWritten[1]);
    RenderControl control;
    control.onPass = onPass;
    control.cancel = CancelFlag();
    control.syncSeconds = a.checkpoint.empty() ? 0 : a.checkpointEvery;   // under mpirun: reductions for the checkpoints
    // Under mpirun only rank 0 sees the pass callback that ends the exit stage: every rank stops at
    // the pass in flight from the start (render/distributed.h).
    if (MpiSession::Active()) SetExitStage(nullptr);
    RenderOutcome out;
    rc = RunBackend(prep, film, control, &out);
    SetExitStage(nullptr);
    if (rc != ExitOk) return rc;
    if (!out.writer) return out.stats.interrupted ? ExitInterrupted : ExitOk;   // an MPI rank other than 0
    const int sig = CaughtSignal();
    const bool interrupted = out.stats.interrupted || sig != 0;
    if (film.passes == 0) {   // nothing to save: existing files stay as they are
        std::fprintf(stderr, "lucerna: %s before the first pass; nothing written\n",
                     interrupted ? "interrupted" : "stopped");
        return interrupted ? ExitInterrupted : ExitInternal;
    }

    // ---- Outputs: each written whole (temporary file + rename) ----
    std::vector<std::string> written;
    if (!a.checkpoint.empty()) {
        try {
            saveCheckpoint(film, out.stats.seconds);
            written.push_back(a.checkpoint);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "lucerna: error: %s\n", e.what());
            return ExitInternal;
        }
    }
    try {
        WriteOutputs(prep, film, out, output, a.png);
        written.push_back(output);
        if (a.png && Lower(std::filesystem::path(output).extension().string()) != ".png")
            written.push_back(PngPreviewPath(output));
    } catch (const std::exception &e) {
        std::fprintf(stderr, "lucerna: cannot write the image: %s\n", e.what());
        return ExitInternal;
    }
    if (!a.statsJson.empty()) {
        try {
            WriteStatsJson(a.statsJson, prep, out);
            written.push_back(a.statsJson);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "lucerna: cannot write --stats-json: %s\n", e.what());
            return ExitInternal;
        }
    }
    std::printf("%s\n", SummaryLine(prep, out).c_str());
    if (out.stats.rejected > 0)
        std::fprintf(stderr, "lucerna: warning: %s kept off the film; the first %s\n",
                     out.stats.rejected == 1 ? "1 sample was" : (std::to_string(out.stats.rejected) + " samples were").c_str(),
                     DescribeRejectedSample(*prep.scene, out.stats.firstRejected).c_str());
    if (interrupted) {
        std::string list;
        for (const std::string &w : written) list += (list.empty() ? "" : ", ") + w;
        std::fprintf(stderr, "lucerna: interrupted by %s after %u passes (%u in this run); wrote %s\n",
                     sig ? SignalName(sig) : "a signal", film.passes, out.stats.passesThisRun, list.c_str());
        return ExitInterrupted;
    }
    return ExitOk;
}

}  // namespace

void RegisterRender(CLI::App &app, CommandTable &table) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App *sub = app.add_subcommand("render", "Render a pbrt-v4 scene");
    sub->add_option("scene", args->scene, "Scene file (.pbrt)")->required();
    sub->add_option("-o,--output", args->output, "Output image (.exr, or .png for an sRGB preview)");
    sub->add_option("--res", args->res, "Film resolution WxH (overrides the scene's)")
        ->check([](const std::string &s) { return s.empty() ? std::string("--res: expected WxH, not nothing") : std::string(); });
    sub->add_option("--stats-json", args->statsJson, "Write statistics as JSON");
    sub->add_flag("--png", args->png, "Also write an sRGB PNG preview next to the EXR");
    sub->add_option("--checkpoint", args->checkpoint, "Save the accumulation state to FILE (periodically and at the end)");
    sub->add_option("--checkpoint-every", args->checkpointEvery, "Seconds between checkpoints (default 60)")->check(CLI::PositiveNumber);
    sub->add_option("--resume", args->resume, "Continue a render from a checkpoint (up to --spp passes in total)");
    AddSettingOptions(sub, &args->settings);
    table.Add(sub, [args] {
        MpiSession mpi;   // under mpirun (render/distributed.h); nothing otherwise
        return mpi.Finish(RunRender(*args));
    });
}

}  // namespace lu::app
