// Lucerna CLI: `lucerna render` — load a pbrt-v4 scene, render progressively (CPU or CUDA),
// write EXR/PNG atomically, checkpoint/resume, stop cleanly on SIGINT/SIGTERM.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "apps/commands.h"
#include "apps/render_common.h"
#include "lucerna/backend/cpu/cpu_render.h"
#include "lucerna/image/image.h"
#include "lucerna/render/distributed.h"
#include "lucerna/scene/builder.h"

namespace lu::app {

namespace {

std::atomic<bool> gCancel{false};
std::atomic<int> gSignal{0};

extern "C" void OnSignal(int sig) {
    gSignal.store(sig);
    gCancel.store(true);
}

// The render command's own arguments; the render settings are given by name (AddSettingOptions).
struct RenderArgs {
    std::string scene, output, res, statsJson, checkpoint, resume;
    SettingOverrides settings;
    double checkpointEvery = 60;
    bool png = false;
};

void WriteStatsJson(const std::string &path, const Prepared &prep, const RenderOutcome &o) {
    std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp);
        f << StatsJson(prep, o);
    }
    std::filesystem::rename(tmp, path);
}

int RunRender(const RenderArgs &a) {
    Prepared prep;
    int rc = PrepareRender(a.scene, a.res, a.settings, &prep);
    if (rc != ExitOk) return rc;

    FilmAccumulator film;
    double secondsBefore = 0;
    if (!a.resume.empty()) {
        CheckpointInfo info;
        try {
            LoadCheckpoint(a.resume, &film, &info);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "%s\n", e.what());
            return ExitBadInput;
        }
        if (info.sceneHash != prep.checkpointKey) {
            std::fprintf(stderr, "%s: checkpoint was made for a different scene or settings (%s, %s, seed %u)\n",
                         a.resume.c_str(), info.sceneFile.c_str(), info.integrator.c_str(), info.seed);
            return ExitBadInput;
        }
        secondsBefore = info.seconds;
        std::fprintf(stderr, "resuming %s at pass %u of %d\n", a.resume.c_str(), film.passes, prep.settings.spp);
    }

    std::signal(SIGINT, OnSignal);
    std::signal(SIGTERM, OnSignal);

    auto lastCheckpoint = std::chrono::steady_clock::now();
    auto saveCheckpoint = [&](const FilmAccumulator &f, double seconds) {
        if (a.checkpoint.empty()) return;
        CheckpointInfo info;
        info.sceneFile = a.scene;
        info.integrator = IntegratorName(prep.settings.integrator);
        info.seed = prep.settings.seed;
        info.sceneHash = prep.checkpointKey;
        info.seconds = secondsBefore + seconds;
        SaveCheckpoint(a.checkpoint, f, info);
    };
    PassCallback onPass = [&](const FilmAccumulator &f, const RenderStats &st) {
        auto now = std::chrono::steady_clock::now();
        if (!a.checkpoint.empty() && std::chrono::duration<double>(now - lastCheckpoint).count() >= a.checkpointEvery) {
            saveCheckpoint(f, st.seconds);
            lastCheckpoint = now;
        }
        return true;
    };

    RenderControl control;
    control.onPass = onPass;
    control.cancel = &gCancel;
    control.syncSeconds = a.checkpoint.empty() ? 0 : a.checkpointEvery;   // under mpirun: reductions for the checkpoints
    RenderOutcome out;
    rc = RunBackend(prep, film, control, &out);
    if (rc != ExitOk) return rc;
    if (!out.writer) return out.stats.interrupted ? ExitInterrupted : ExitOk;   // an MPI rank other than 0
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    saveCheckpoint(film, out.stats.seconds);

    std::string output = a.output.empty() ? DefaultOutputName(prep) : a.output;
    try {
        WriteOutputs(prep, film, out, output, a.png);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "lucerna: cannot write the image: %s\n", e.what());
        return ExitInternal;
    }
    if (!a.statsJson.empty()) WriteStatsJson(a.statsJson, prep, out);
    std::printf("%s\n", SummaryLine(prep, out).c_str());
    if (out.stats.interrupted || gSignal.load() != 0) {
        std::fprintf(stderr, "interrupted by signal %d after %u passes; image written to %s\n", gSignal.load(), film.passes,
                     output.c_str());
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
    sub->add_option("--res", args->res, "Film resolution WxH (overrides the scene's)");
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
