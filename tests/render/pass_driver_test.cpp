// Lucerna: the shared pass driver (render/pass_driver.h) with a backend that is a function: it asks
// for each pass once, in order, with that pass's settings and the expected next pass; it commits
// passes, sums counters, keeps the first rejected sample, and stops at the pass count, the time
// limit, a false callback and a cancel (abandoning the pass in flight); a resumed film continues.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "lucerna/render/pass_driver.h"

namespace lu {
namespace {

// A 4x2 image; pass k writes k + 1 into every channel of every pixel, and counts 10 rays.
struct FakeBackend {
    PassBuffer buffer;
    std::vector<PassRequest> requests;
    std::function<void(uint32_t)> during;   // runs inside the pass (to cancel there)
    FakeBackend() { buffer.Resize(4, 2); }
    RenderPassFn Fn() {
        return [this](const PassRequest &req, PassCounters &c) -> const PassBuffer * {
            requests.push_back(req);
            if (during) during(req.pass);
            for (float &v : buffer.xyzw) v = float(req.pass + 1);
            c.rays += 10;
            if (req.pass == 2) {
                c.Reject(RejectedSampleKey(3, 1, 4, 5));
                c.Reject(RejectedSampleKey(1, 1, 4, 2));
            }
            return &buffer;
        };
    }
};

RenderSettings Settings(int spp) {
    RenderSettings s;
    s.spp = spp;
    s.progress = false;
    s.integrator = IntegratorKind::RegPath;
    s.regRadius = 1;
    return s;
}

TEST(PassDriver, RendersEachPassOnceInOrder) {
    FakeBackend b;
    FilmAccumulator film;
    film.Resize(4, 2);
    RenderStats st = RunPasses(Settings(5), film, {}, b.Fn());
    ASSERT_EQ(b.requests.size(), 5u);
    for (uint32_t k = 0; k < 5; ++k) {
        EXPECT_EQ(b.requests[k].pass, k);
        EXPECT_EQ(b.requests[k].next, k + 1 < 5 ? k + 1 : NoPass);
        // The per-path settings of the pass: r_N = r0 N^-lambda with N = k + 1.
        EXPECT_FLOAT_EQ(b.requests[k].ps.reg.radius, std::pow(float(k + 1), -1.f / 6));
        if (k + 1 < 5) { EXPECT_FLOAT_EQ(b.requests[k].nextPs.reg.radius, std::pow(float(k + 2), -1.f / 6)); }
    }
    EXPECT_EQ(film.passes, 5u);
    EXPECT_EQ(st.passesThisRun, 5u);
    EXPECT_EQ(st.samples, 5u * 8);
    EXPECT_EQ(st.rays, 50u);
    EXPECT_DOUBLE_EQ(film.xyzw[0], 1 + 2 + 3 + 4 + 5);
    EXPECT_EQ(st.rejected, 2u);
    EXPECT_EQ(st.firstRejected.x, 1);   // the smaller key of the two
    EXPECT_EQ(st.firstRejected.y, 1);
    EXPECT_EQ(st.firstRejected.depth, 2);
    EXPECT_FALSE(st.interrupted);
}

TEST(PassDriver, ResumedFilmContinues) {
    FakeBackend b;
    FilmAccumulator film;
    film.Resize(4, 2);
    RunPasses(Settings(2), film, {}, b.Fn());
    RenderStats st = RunPasses(Settings(5), film, {}, b.Fn());
    EXPECT_EQ(st.passesThisRun, 3u);
    EXPECT_EQ(b.requests.back().pass, 4u);
    EXPECT_DOUBLE_EQ(film.xyzw[0], 1 + 2 + 3 + 4 + 5);
}

TEST(PassDriver, CallbackStopsAfterItsPass) {
    FakeBackend b;
    FilmAccumulator film;
    film.Resize(4, 2);
    RenderControl c;
    c.onPass = [](const FilmAccumulator &f, const RenderStats &) { return f.passes < 3; };
    RunPasses(Settings(10), film, c, b.Fn());
    EXPECT_EQ(film.passes, 3u);
}

TEST(PassDriver, CancelAbandonsThePassInFlight) {
    FakeBackend b;
    std::atomic<bool> cancel{false};
    b.during = [&](uint32_t pass) {
        if (pass == 3) cancel = true;   // a signal arrives while pass 3 renders
    };
    FilmAccumulator film;
    film.Resize(4, 2);
    RenderControl c;
    c.cancel = &cancel;
    RenderStats st = RunPasses(Settings(10), film, c, b.Fn());
    EXPECT_TRUE(st.interrupted);
    EXPECT_EQ(film.passes, 3u);   // passes 0, 1, 2: the film keeps complete passes only
    EXPECT_DOUBLE_EQ(film.xyzw[0], 1 + 2 + 3);
}

TEST(PassDriver, TimeLimitStopsAtAPassBoundary) {
    FakeBackend b;
    b.during = [](uint32_t) { std::this_thread::sleep_for(std::chrono::milliseconds(20)); };
    FilmAccumulator film;
    film.Resize(4, 2);
    RenderSettings s = Settings(1 << 24);
    s.timeLimit = 0.1;
    RenderStats st = RunPasses(s, film, {}, b.Fn());
    EXPECT_GE(st.seconds, 0.1);
    EXPECT_GE(film.passes, 1u);
    EXPECT_LE(film.passes, 6u);   // each pass takes >= 20 ms
    EXPECT_FALSE(st.interrupted);
}

}  // namespace
}  // namespace lu
