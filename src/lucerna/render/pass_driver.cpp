// Lucerna (host): the shared pass loop and its progress line.
#include "lucerna/render/pass_driver.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace lu {

namespace {

using Clock = std::chrono::steady_clock;

// Progress on stderr: a bar redrawn in place on a terminal (at most ~8 times a second), else one
// line every few seconds. Time-bounded renders show time and passes instead of a pass total.
class Progress {
  public:
    Progress(const RenderSettings &s, uint32_t firstPass)
        : enabled_(s.progress), tty_(isatty(STDERR_FILENO) != 0), total_(uint32_t(s.spp)), timeLimit_(s.timeLimit),
          firstPass_(firstPass) {}

    void Update(uint32_t passes, double seconds, uint64_t samples, bool final) {
        if (!enabled_) return;
        auto now = Clock::now();
        double sinceLast = std::chrono::duration<double>(now - last_).count();
        if (!final && printed_ && sinceLast < (tty_ ? 0.125 : 5.0)) return;
        last_ = now;
        printed_ = true;
        // Fraction done: passes of this run, or time, whichever is further.
        double frac = total_ > firstPass_ ? double(passes - firstPass_) / double(total_ - firstPass_) : 1;
        if (timeLimit_ > 0) frac = std::max(frac, std::min(1.0, seconds / timeLimit_));
        double eta = frac > 0 ? seconds / frac - seconds : 0;
        double rate = samples / std::max(1e-9, seconds) * 1e-6;
        char what[96];
        if (timeLimit_ > 0 && total_ >= (1u << 24))   // time-bounded: no meaningful pass total
            std::snprintf(what, sizeof what, "pass %u  %.1f / %.0f s", passes, seconds, timeLimit_);
        else
            std::snprintf(what, sizeof what, "pass %u/%u", passes, total_);
        if (tty_) {
            int bars = int(frac * 30);
            char bar[31];
            for (int i = 0; i < 30; ++i) bar[i] = i < bars ? '#' : '.';
            bar[30] = 0;
            std::fprintf(stderr, "\r[%s] %s  %.2f Msamples/s  elapsed %.1fs  ETA %.1fs   %s", bar, what, rate, seconds,
                         final ? 0.0 : eta, final ? "\n" : "");
        } else {
            std::fprintf(stderr, "%s  %.0f%%  %.2f Msamples/s  elapsed %.1fs  ETA %.1fs%s\n", what, 100 * frac, rate,
                         seconds, final ? 0.0 : eta, final ? "  (done)" : "");
        }
        std::fflush(stderr);
    }

  private:
    bool enabled_, tty_;
    uint32_t total_;
    double timeLimit_;
    uint32_t firstPass_;
    bool printed_ = false;
    Clock::time_point last_ = Clock::now();
};

void AddCounters(RenderStats &stats, const PassCounters &c, int width) {
    stats.rays += c.rays;
    stats.shadowRays += c.shadowRays;
    stats.regConnections += c.regConnections;
    stats.mneeConnections += c.mneeConnections;
    stats.regEnergy += c.regEnergy;
    stats.totalEnergy += c.totalEnergy;
    if (c.rejected == 0) return;
    uint64_t prev = stats.firstRejected.Valid()
                        ? RejectedSampleKey(stats.firstRejected.x, stats.firstRejected.y, width, stats.firstRejected.depth,
                                            stats.firstRejected.cause, stats.firstRejected.badValue, stats.firstRejected.entity)
                        : ~0ull;
    if (stats.rejected == 0 || c.firstRejected < prev) stats.firstRejected = DecodeRejectedSampleKey(c.firstRejected, width);
    stats.rejected += c.rejected;
}

}  // namespace

Sampler RenderSampler(const Sampler &sceneSampler, const RenderSettings &settings, const SceneView &view) {
    Sampler s = sceneSampler;
    s.seed = int(settings.seed);
    s.pmjPoints = view.pmjPoints.ptr;
    return s;
}

RenderStats RunPasses(const RenderSettings &settings, FilmAccumulator &film, const RenderControl &control,
                      const RenderPassFn &renderPass) {
    RenderStats stats;
    auto cancelled = [&] { return control.cancel && control.cancel->load(std::memory_order_relaxed); };
    uint32_t total = uint32_t(std::max(settings.spp, 0));
    Progress progress(settings, film.passes);
    auto t0 = Clock::now();
    double callbackSeconds = 0;   // time spent in onPass (error metrics, checkpoints): not render time
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count() - callbackSeconds; };
    uint64_t pixels = uint64_t(film.width) * uint64_t(film.height);

    while (film.passes < total) {
        if (cancelled()) {
            stats.interrupted = true;
            break;
        }
        PassRequest request;
        request.pass = film.passes;
        request.next = request.pass + 1 < total ? request.pass + 1 : NoPass;
        request.ps = settings.ForPass(request.pass);
        if (request.next != NoPass) request.nextPs = settings.ForPass(request.next);
        PassCounters counters;
        const PassBuffer *buffer = renderPass(request, counters);
        if (!buffer || cancelled()) {   // abandon the partial pass: the film keeps only complete passes
            stats.interrupted = true;
            break;
        }
        film.Commit(*buffer);
        ++stats.passesThisRun;
        stats.samples += pixels;
        AddCounters(stats, counters, film.width);
        stats.seconds = elapsed();
        progress.Update(film.passes, stats.seconds, stats.samples, false);
        if (control.onPass) {
            auto c0 = Clock::now();
            bool more = control.onPass(film, stats);
            callbackSeconds += std::chrono::duration<double>(Clock::now() - c0).count();
            if (!more) break;
        }
        if (settings.timeLimit > 0 && stats.seconds >= settings.timeLimit) break;
    }
    stats.seconds = elapsed();
    progress.Update(film.passes, stats.seconds, stats.samples, true);
    return stats;
}

}  // namespace lu
