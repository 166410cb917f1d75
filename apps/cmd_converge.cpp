// Lucerna CLI: `lucerna converge` — render each integrator progressively (K runs with different
// seeds), compute the error against a reference at checkpoints without re-rendering (powers of
// two in spp and twelve points in time), and write DIR/convergence.csv, final.csv, run.json,
// images at equal time and equal spp, then the plots and index.html (scripts/*.py, run without a
// shell). The directory layout is specified in docs/convergence.md.
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "apps/commands.h"
#include "apps/interrupt.h"
#include "apps/json.h"
#include "apps/render_common.h"
#include "lucerna/image/image.h"
#include "lucerna/image/metrics.h"

#ifndef LUCERNA_SOURCE_DIR
#define LUCERNA_SOURCE_DIR "."
#endif

extern char **environ;

namespace lu::app {

namespace {

struct ConvergeArgs {
    std::string scene, ref, integrators = "path,regpath", res, outDir, python;
    double time = 0;
    int spp = 0, runs = 1;
    long long seed = 0;
    SettingOverrides settings;   // the other render settings (--maxdepth, --reg-radius, --threads, ...)
    double excludeAbove = 100;
    bool noReport = false;
};

struct Snapshot {
    uint32_t spp;
    double seconds;
    Image image;
};

std::vector<std::string> Split(const std::string &s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

std::string Num(double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}

// The snapshot with the largest key <= limit (key = spp or seconds); the first one if none.
const Snapshot &PickSnapshot(const std::vector<Snapshot> &snaps, bool bySpp, double limit) {
    const Snapshot *best = &snaps.front();
    for (const Snapshot &s : snaps)
        if ((bySpp ? double(s.spp) : s.seconds) <= limit + 1e-9) best = &s;
    return *best;
}

void WriteBudgetImages(const std::string &dir, const std::string &integ, const std::string &budget, const Snapshot &s,
                       uint32_t seed) {
    ImageMetadata meta{{"lucerna.integrator", integ}, {"lucerna.spp", std::to_string(s.spp)},
                       {"lucerna.seconds", Num(s.seconds)}, {"lucerna.run", "0"}, {"lucerna.seed", std::to_string(seed)}};
    WriteEXR(dir + "/" + integ + "_" + budget + ".exr", s.image, meta);
    WritePNG(dir + "/" + integ + "_" + budget + ".png", s.image);
}

// Runs argv (argv[0] looked up on PATH) without a shell and waits; "" on success, else what failed.
std::string RunProgram(const std::vector<std::string> &argv) {
    std::vector<char *> args;
    for (const std::string &s : argv) args.push_back(const_cast<char *>(s.c_str()));
    args.push_back(nullptr);
    std::string what;
    for (const std::string &s : argv) what += (what.empty() ? "" : " ") + s;
    pid_t pid = 0;
    int err = posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ);
    if (err != 0) return "could not run " + what + ": " + std::strerror(err);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return "lost " + what + ": " + std::strerror(errno);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
    if (WIFEXITED(status)) return what + " exited with status " + std::to_string(WEXITSTATUS(status));
    return what + " was killed by signal " + std::to_string(WTERMSIG(status));
}

int RunConverge(const ConvergeArgs &a) {
    InstallSignalHandlers();
    SetExitStage("converging; the output folder is incomplete");
    if ((a.time > 0) == (a.spp > 0)) {
        std::fprintf(stderr, "lucerna converge: give exactly one of --time SECONDS or --spp N\n");
        return ExitBadInput;
    }
    Image ref;
    try {
        ref = ReadImage(a.ref);
    } catch (const ImageError &e) {
        std::fprintf(stderr, "lucerna converge: %s\n", e.what());
        return ExitBadInput;
    }
    // Directly visible emitters (reference above `excludeAbove`, dilated by the filter's pixel)
    // make pixel errors a lottery on sub-pixel light hits that every integrator shares; they are
    // excluded (set to zero in both images) unless --exclude-above 0.
    std::vector<uint8_t> mask(size_t(ref.width) * ref.height, 0);
    size_t masked = 0;
    if (a.excludeAbove > 0)
        for (int y = 0; y < ref.height; ++y)
            for (int x = 0; x < ref.width; ++x) {
                bool hot = false;
                for (int c = 0; c < std::min(3, ref.channels); ++c) hot |= ref.At(x, y, c) > a.excludeAbove;
                if (!hot) continue;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        int xx = x + dx, yy = y + dy;
                        if (xx >= 0 && yy >= 0 && xx < ref.width && yy < ref.height) mask[size_t(yy) * ref.width + xx] = 1;
                    }
            }
    for (uint8_t m : mask) masked += m;
    auto applyMask = [&](Image &img) {
        for (size_t p = 0; p < mask.size(); ++p)
            if (mask[p])
                for (int c = 0; c < img.channels; ++c) img.pixels[p * img.channels + c] = 0;
    };
    Image refMasked = ref;
    applyMask(refMasked);
    if (masked) std::fprintf(stderr, "converge: %zu pixels of directly visible emitters excluded from the errors\n", masked);
    auto errors = [&](const Image &img) {
        if (!masked) return ComputeErrors(img, ref);
        Image m = img;
        applyMask(m);
        return ComputeErrors(m, refMasked);
    };
    std::vector<std::string> integrators = Split(a.integrators);
    if (integrators.empty()) {
        std::fprintf(stderr, "lucerna converge: --integrators is empty\n");
        return ExitBadInput;
    }
    std::filesystem::create_directories(a.outDir);
    std::ofstream csv(a.outDir + "/convergence.csv");
    csv << "integrator,run,spp,seconds,mse,rmse,relmse,mape\n";

    std::map<std::string, std::vector<std::vector<Snapshot>>> snaps;   // integrator -> run -> snapshots
    std::string deviceName = "cpu";
    int width = 0, height = 0;
    for (const std::string &integ : integrators) snaps[integ];
    // Run-major order (run 0 of every integrator, then run 1, ...): on a shared machine, load
    // that drifts during the benchmark then affects every integrator alike at equal time.
    for (int run = 0; run < a.runs; ++run) {
        for (const std::string &integ : integrators) {
            SettingOverrides o = a.settings;
            o.emplace_back("integrator", integ);
            o.emplace_back("seed", std::to_string(a.seed + run));
            o.emplace_back("progress", "false");
            if (a.spp > 0) o.emplace_back("spp", std::to_string(a.spp));
            if (a.time > 0) o.emplace_back("time", Num(a.time));
            Prepared prep;
            int rc = PrepareRender(a.scene, a.res, o, &prep);
            if (rc != ExitOk) return rc;
            const FilmData &filmData = prep.scene->View().film;
            if (filmData.width != ref.width || filmData.height != ref.height) {
                std::fprintf(stderr, "lucerna converge: the render is %dx%d but the reference is %dx%d (use --res %dx%d)\n",
                             filmData.width, filmData.height, ref.width, ref.height, ref.width, ref.height);
                return ExitBadInput;
            }
            width = filmData.width;
            height = filmData.height;
            std::vector<Snapshot> &runSnaps = snaps[integ].emplace_back();
            int nextTimePoint = 1;
            constexpr int kTimePoints = 12;
            PassCallback onPass = [&](const FilmAccumulator &film, const RenderStats &st) {
                uint32_t spp = film.passes;
                bool pow2 = (spp & (spp - 1)) == 0;
                bool timePoint = false;
                if (a.time > 0)
                    while (nextTimePoint <= kTimePoints && st.seconds >= a.time * nextTimePoint / kTimePoints) {
                        timePoint = true;
                        ++nextTimePoint;
                    }
                bool last = (a.spp > 0 && int(spp) >= a.spp) || (a.time > 0 && st.seconds >= a.time);
                if (!pow2 && !timePoint && !last) return true;
                Image img = film.Resolve(filmData);
                ErrorStats e = errors(img);
                csv << integ << ',' << run << ',' << spp << ',' << Num(st.seconds) << ',' << Num(e.mse) << ','
                    << Num(e.rmse) << ',' << Num(e.relMSE) << ',' << Num(e.mape) << '\n';
                runSnaps.push_back({spp, st.seconds, std::move(img)});
                return true;
            };
            FilmAccumulator film;
            RenderOutcome out;
            RenderControl control;
            control.onPass = onPass;
            rc = RunBackend(prep, film, control, &out);
            if (rc != ExitOk) return rc;
            deviceName = prep.deviceName;
            std::fprintf(stderr, "converge: %s run %d: %u spp in %.2f s, final relMSE %s\n", integ.c_str(), run, film.passes,
                         out.stats.seconds, runSnaps.empty() ? "-" : Num(errors(runSnaps.back().image).relMSE).c_str());
        }
    }
    csv.close();

    // ---- Equal-time and equal-spp budgets (see docs/convergence.md) ----
    double timeBudget = 1e300;
    double sppBudget = 1e300;
    for (const auto &integ : integrators) {
        const Snapshot &last = snaps[integ][0].back();
        timeBudget = std::min(timeBudget, last.seconds);
        sppBudget = std::min(sppBudget, double(last.spp));
    }
    std::ofstream fin(a.outDir + "/final.csv");
    fin << "integrator,budget,runs,spp,seconds,mse,rmse,relmse,mape,bias2,variance,relbias2,relvariance,mse_median,mse_min,mse_max\n";
    for (const auto &integ : integrators) {
        for (const char *budget : {"time", "spp"}) {
            bool bySpp = std::string(budget) == "spp";
            std::vector<Image> images;
            std::vector<double> runMSE;
            double spp = 0, secs = 0, mse = 0, rmse = 0, relmse = 0, mape = 0;
            for (int run = 0; run < a.runs; ++run) {
                const auto &rs = snaps[integ][run];
                const Snapshot &s = (a.time > 0 && !bySpp) || (a.spp > 0 && bySpp)
                                        ? rs.back()
                                        : PickSnapshot(rs, bySpp, bySpp ? sppBudget : timeBudget);
                if (run == 0) WriteBudgetImages(a.outDir, integ, budget, s, uint32_t(a.seed));
                ErrorStats e = errors(s.image);
                runMSE.push_back(e.mse);
                spp += s.spp; secs += s.seconds; mse += e.mse; rmse += e.rmse; relmse += e.relMSE; mape += e.mape;
                images.push_back(s.image);
                if (masked) applyMask(images.back());
            }
            double k = a.runs;
            fin << integ << ',' << budget << ',' << a.runs << ',' << Num(spp / k) << ',' << Num(secs / k) << ','
                << Num(mse / k) << ',' << Num(rmse / k) << ',' << Num(relmse / k) << ',' << Num(mape / k);
            if (a.runs > 1) {
                BiasVariance bv = ComputeBiasVariance(images, refMasked);
                fin << ',' << Num(bv.bias2) << ',' << Num(bv.variance) << ',' << Num(bv.relBias2) << ',' << Num(bv.relVariance);
            } else {
                fin << ",,,,";
            }
            // Per-run spread of the MSE: heavy-tailed estimators (rare caustic hits) have a mean
            // far above their typical run; the mean estimates the expected MSE, the median the typical one.
            std::sort(runMSE.begin(), runMSE.end());
            size_t m = runMSE.size();
            double median = m % 2 ? runMSE[m / 2] : 0.5 * (runMSE[m / 2 - 1] + runMSE[m / 2]);
            fin << ',' << Num(median) << ',' << Num(runMSE.front()) << ',' << Num(runMSE.back());
            fin << '\n';
        }
    }
    fin.close();
    WritePNG(a.outDir + "/reference.png", ref);
    {
        std::time_t now = std::time(nullptr);
        char date[64];
        std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
        JsonObject j;
        j.Add("scene", a.scene).Add("reference", a.ref).Add("width", width).Add("height", height);
        j.Add("excluded_pixels", masked);
        if (a.time > 0) j.Add("time", a.time); else j.Add("time", nullptr);
        if (a.spp > 0) j.Add("spp", a.spp); else j.Add("spp", nullptr);
        j.Add("runs", a.runs).Add("integrators", integrators).Add("backend", deviceName).Add("device", deviceName);
        j.Add("date", date);
        std::ofstream(a.outDir + "/run.json") << j.Str() << "\n";
    }
    if (a.noReport) {
        std::printf("converge: wrote %s/convergence.csv, final.csv\n", a.outDir.c_str());
        return ExitOk;
    }
    // The report scripts need matplotlib and numpy; the interpreter: --python, else
    // $LUCERNA_PYTHON, else python3 on PATH.
    std::string python = a.python;
    if (python.empty()) {
        const char *env = std::getenv("LUCERNA_PYTHON");
        python = env && *env ? env : "python3";
    }
    std::string scripts = std::string(LUCERNA_SOURCE_DIR) + "/scripts";
    for (const char *script : {"plot_convergence.py", "make_report.py"}) {
        std::string failure = RunProgram({python, scripts + "/" + script, a.outDir});
        if (!failure.empty()) {
            std::fprintf(stderr,
                         "lucerna converge: error: the report failed: %s (the scripts need matplotlib and numpy: "
                         "scripts/setup.sh; choose the interpreter with --python or LUCERNA_PYTHON). "
                         "%s/convergence.csv and final.csv are written.\n",
                         failure.c_str(), a.outDir.c_str());
            return ExitInternal;
        }
    }
    std::printf("converge: wrote %s/convergence.csv, final.csv, index.html\n", a.outDir.c_str());
    return ExitOk;
}

}  // namespace

void RegisterConverge(CLI::App &app, CommandTable &table) {
    auto args = std::make_shared<ConvergeArgs>();
    CLI::App *sub = app.add_subcommand("converge", "Error against a reference per sample and per second, with plots and a report");
    sub->add_option("scene", args->scene, "Scene file (.pbrt)")->required();
    sub->add_option("--ref", args->ref, "Reference image (.exr)")->required();
    sub->add_option("--integrators", args->integrators, "Comma-separated integrators (default path,regpath)");
    sub->add_option("--time", args->time, "Time budget per run in seconds")->check(CLI::PositiveNumber);
    sub->add_option("--spp", args->spp, "Samples per pixel per run")->check(CLI::Range(1, 1 << 24));
    sub->add_option("--runs", args->runs, "Independent runs (seeds) per integrator")->check(CLI::Range(1, 1000));
    sub->add_option("--res", args->res, "Resolution WxH (must match the reference)");
    sub->add_option("--seed", args->seed, "Seed of run 0 (run k uses seed + k)")->check(CLI::Range(0LL, 4294967295LL));
    AddSettingOptions(sub, &args->settings, {"integrator", "seed", "spp", "time", "progress"});
    sub->add_flag("--no-report", args->noReport, "Skip the plots and index.html");
    sub->add_option("--python", args->python,
                    "Python interpreter with matplotlib for the report (default: $LUCERNA_PYTHON, else python3 on PATH)");
    sub->add_option("--exclude-above", args->excludeAbove,
                    "Exclude pixels (and their 8 neighbours) where the reference exceeds this value: directly visible "
                    "emitters (default 100; 0 keeps every pixel)");
    sub->add_option("-o,--output", args->outDir, "Output directory")->required();
    table.Add(sub, [args] { return RunConverge(*args); });
}

}  // namespace lu::app
