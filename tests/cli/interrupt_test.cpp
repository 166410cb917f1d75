// Lucerna CLI tests: a signal at every stage of a render. Before the first pass (reading the
// scene, building the acceleration structure, the first pass in flight) it ends the process with
// exit 3 and a message naming the stage, and leaves every file as it was (no empty image over a
// previous one, no checkpoint, no statistics, no temporary file); later it stops at the pass in
// flight and writes what the film holds.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "cli/cli_support.h"

namespace lu::test {

namespace {

// A scene that takes seconds to read: it includes a file of 400 000 "Identity" directives 150
// times (540 MB of directives read from one 3.6 MB file; nothing accumulates in memory).
std::string WriteSlowScene(const std::string &dir) {
    {
        std::ofstream inc(dir + "/many.pbrt");
        for (int i = 0; i < 400000; ++i) inc << "Identity\n";
    }
    std::string scene = WriteScene(dir, 16, 1, "base.pbrt");
    std::ofstream main(dir + "/slow.pbrt");
    for (int i = 0; i < 150; ++i) main << "Include \"many.pbrt\"\n";
    main << "Include \"base.pbrt\"\n";
    return dir + "/slow.pbrt";
}

struct Previous {
    std::string dir, image, bytes;
};

// A previous good render at dir/out.exr.
Previous PreviousImage(const std::string &dir) {
    Previous p{dir, dir + "/out.exr", ""};
    EXPECT_EQ(RunLucerna({"render", WriteScene(dir, 16, 2, "small.pbrt"), "-o", p.image}), 0);
    p.bytes = FileBytes(p.image);
    EXPECT_GT(p.bytes.size(), 100u);
    return p;
}

void ExpectUntouched(const Previous &p) {
    EXPECT_EQ(FileBytes(p.image), p.bytes) << "the previous image was replaced";
    EXPECT_FALSE(std::filesystem::exists(p.dir + "/c.ckpt")) << "a checkpoint was written";
    EXPECT_FALSE(std::filesystem::exists(p.dir + "/s.json")) << "statistics were written";
    EXPECT_TRUE(TempFiles(p.dir).empty()) << TempFiles(p.dir).front();
}

}  // namespace

// SIGINT, SIGTERM and SIGHUP while the scene is read: exit 3 with a message at once (SIGTERM used
// to kill the process with status 143 and no word).
TEST(Interrupt, WhileReadingTheScene) {
    std::string dir = TempDir("int_reading");
    Previous prev = PreviousImage(dir);
    std::string scene = WriteSlowScene(dir);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
        SCOPED_TRACE(sig);
        Background render({"render", scene, "-o", prev.image, "--checkpoint", dir + "/c.ckpt", "--stats-json",
                           dir + "/s.json"});
        ASSERT_TRUE(render.WaitFor("device: ")) << "no device line";   // printed just before the scene is read
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        auto t0 = std::chrono::steady_clock::now();
        kill(render.pid, sig);
        ProcessResult r = render.Finish();
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        EXPECT_EQ(r.exitCode, 3) << r.output;
        const char *name = sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP";
        EXPECT_NE(r.output.find(std::string("interrupted by ") + name + " while reading the scene; nothing written"),
                  std::string::npos) << r.output;
        EXPECT_LT(seconds, 1.0) << "the signal must end the process at once";
        ExpectUntouched(prev);
    }
}

// A signal while the first pass is in flight (a 2000x2000 first pass on one thread takes seconds):
// the previous image stays (it used to be replaced by a 0-pass image, exit 3).
TEST(Interrupt, BeforeTheFirstPass) {
    std::string dir = TempDir("int_first_pass");
    Previous prev = PreviousImage(dir);
    std::string scene = WriteScene(dir, 16, 4);
    for (int sig : {SIGINT, SIGTERM}) {
        SCOPED_TRACE(sig);
        Background render({"render", scene, "--res", "2000x2000", "--threads", "1", "-o", prev.image, "--png",
                           "--checkpoint", dir + "/c.ckpt", "--stats-json", dir + "/s.json"});
        ASSERT_TRUE(render.WaitFor("device: ")) << "no device line";
        std::this_thread::sleep_for(std::chrono::milliseconds(700));
        kill(render.pid, sig);
        ProcessResult r = render.Finish();
        EXPECT_EQ(r.exitCode, 3) << r.output;
        EXPECT_NE(r.output.find("while building the acceleration structure or rendering the first pass; nothing "
                                "written, existing files left as they were"),
                  std::string::npos) << r.output;
        ExpectUntouched(prev);
        EXPECT_FALSE(std::filesystem::exists(dir + "/out.png"));
    }
}

// After the first pass a signal stops at the pass in flight; the image, its preview, the
// checkpoint and the statistics are written, and stderr lists them.
TEST(Interrupt, AfterPassesWritesEveryOutput) {
    std::string dir = TempDir("int_after");
    std::string scene = WriteScene(dir, 64, 100000);
    Background render({"render", scene, "-o", dir + "/o.exr", "--png", "--checkpoint", dir + "/c.ckpt", "--stats-json",
                       dir + "/s.json", "--threads", "1"});
    ASSERT_TRUE(render.WaitFor("device: ")) << "no device line";
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    kill(render.pid, SIGTERM);
    ProcessResult r = render.Finish();
    ASSERT_EQ(r.exitCode, 3) << r.output;
    ImageMetadata meta;
    Image img = ReadImage(dir + "/o.exr", false, &meta);
    int spp = std::stoi(meta["lucerna.spp"]);
    EXPECT_GE(spp, 1);
    EXPECT_EQ(meta["lucerna.interrupted"], "1");
    for (float v : img.pixels) ASSERT_TRUE(std::isfinite(v));
    std::string line = "interrupted by SIGTERM after " + std::to_string(spp) + " passes (" + std::to_string(spp) +
                       " in this run); wrote " + dir + "/c.ckpt, " + dir + "/o.exr, " + dir + "/o.png, " + dir + "/s.json";
    EXPECT_NE(r.output.find(line), std::string::npos) << r.output;
    EXPECT_TRUE(TempFiles(dir).empty());
}

}  // namespace lu::test
