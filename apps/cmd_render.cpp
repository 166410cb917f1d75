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
#include "lucerna/scene/builder.h"

namespace lu::app {

namespace {

std::atomic<bool> gCancel{false};
std::atomic<int> gSignal{0};

extern "C" void OnSignal(int sig) {
    gSignal.store(sig);
    gCancel.store(true);
}

struct RenderArgs {
    std::string scene, output, integrator, res, statsJson, checkpoint, resume, device = "auto";
    int spp = 0, threads = 0, maxDepth = -1;
    long long seed = -1;
    double time = 0, checkpointEvery = 60, regRadius = -1, regLambda = -1, regAngle = -1;
    bool png = false, quiet = false;
};

void WriteStatsJson(const std::string &path, const RenderOutcome &o) {
    std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp);
        f << StatsJson(o);
    }
    std::filesystem::rename(tmp, path);
}

int RunRender(const RenderArgs &a) {
    RenderRequest req;
    req.sceneFile = a.scene;
    req.integrator = a.integrator;
    req.res = a.res;
    req.spp = a.spp;
    req.seed = a.seed;
    req.maxDepth = a.maxDepth;
    req.threads = a.threads;
    req.time = a.time;
    req.regRadius = a.regRadius;
    req.regLambda = a.regLambda;
    req.regAngle = a.regAngle;
    req.device = a.device;
    req.progress = !a.quiet;

    Prepared prep;
    int rc = PrepareRender(req, &prep);
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
        if (info.sceneHash != prep.sceneHash) {
            std::fprintf(stderr, "%s: checkpoint was made for a different scene or settings (%s, %s, seed %u)\n",
                         a.resume.c_str(), info.sceneFile.c_str(), info.integrator.c_str(), info.seed);
            return ExitBadInput;
        }
        secondsBefore = info.seconds;
        std::fprintf(stderr, "resuming %s at pass %u of %d\n", a.resume.c_str(), film.passes, prep.job.spp);
    }

    std::signal(SIGINT, OnSignal);
    std::signal(SIGTERM, OnSignal);
    prep.job.cancel = &gCancel;

    auto lastCheckpoint = std::chrono::steady_clock::now();
    auto saveCheckpoint = [&](const FilmAccumulator &f, double seconds) {
        if (a.checkpoint.empty()) return;
        CheckpointInfo info;
        info.sceneFile = a.scene;
        info.integrator = prep.integratorName;
        info.seed = prep.job.seed;
        info.sceneHash = prep.sceneHash;
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

    RenderOutcome out;
    rc = RunBackend(prep, film, onPass, &out);
    if (rc != ExitOk) return rc;
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
    if (!a.statsJson.empty()) WriteStatsJson(a.statsJson, out);
    std::printf("%s\n", SummaryLine(out).c_str());
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
    sub->add_option("--spp", args->spp, "Samples per pixel (passes); overrides the scene's Sampler")->check(CLI::Range(1, 1 << 24));
    sub->add_option("--time", args->time, "Time budget in seconds: stop at the first pass boundary after it")->check(CLI::NonNegativeNumber);
    sub->add_option("--integrator", args->integrator, "path or regpath (default: the scene's, else path)");
    sub->add_option("--res", args->res, "Film resolution WxH (overrides the scene's)");
    sub->add_option("--seed", args->seed, "Random seed")->check(CLI::Range(0LL, 4294967295LL));
    sub->add_option("--threads", args->threads, "CPU threads (default: all cores)")->check(CLI::Range(1, 4096));
    sub->add_option("--maxdepth", args->maxDepth, "Maximum path depth")->check(CLI::Range(0, 100000));
    sub->add_option("--stats-json", args->statsJson, "Write statistics as JSON");
    sub->add_flag("--png", args->png, "Also write an sRGB PNG preview next to the EXR");
    sub->add_option("--reg-radius", args->regRadius, "regpath: initial radius r0 in world units (default: derived from the scene)");
    sub->add_option("--reg-lambda", args->regLambda, "regpath: shrink exponent lambda (default 1/6)");
    sub->add_option("--reg-angle", args->regAngle, "regpath: initial angle sigma0 in degrees for distant/infinite lights");
    sub->add_option("--checkpoint", args->checkpoint, "Save the accumulation state to FILE (periodically and at the end)");
    sub->add_option("--checkpoint-every", args->checkpointEvery, "Seconds between checkpoints (default 60)")->check(CLI::PositiveNumber);
    sub->add_option("--resume", args->resume, "Continue a render from a checkpoint (up to --spp passes in total)");
    sub->add_option("--device", args->device, "cpu, cuda or auto (default: auto)")->check(CLI::IsMember({"auto", "cpu", "cuda"}));
    sub->add_flag("-q,--quiet", args->quiet, "No progress bar");
    table.Add(sub, [args] { return RunRender(*args); });
}

}  // namespace lu::app
