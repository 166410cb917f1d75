// Lucerna CLI tests: exit codes, interruption by SIGINT (a valid image with its pass count in the
// EXR metadata), checkpoint/resume bit-identical to an uninterrupted render, and `converge`.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli/cli_support.h"
#include "lucerna/image/image.h"

namespace lu::test {

namespace {
const std::string &kBin = Bin();
}  // namespace

// regpath reports the radius it used: the default 0.04 x bounding-box diagonal (docs/regularization.md;
// WriteScene's bounds are [-3,3] x [-0.6,2] x [-3,3]), or --reg-radius.
TEST(Cli, RegpathReportsItsRadius) {
    std::string dir = TempDir("cli_reg_radius");
    auto radius = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {"render", WriteScene(dir, 8, 1), "--integrator", "regpath", "-o", dir + "/r.exr",
                                         "--stats-json", dir + "/r.json"};
        args.insert(args.end(), extra.begin(), extra.end());
        EXPECT_EQ(RunLucerna(args), 0);
        std::stringstream js;
        js << std::ifstream(dir + "/r.json").rdbuf();
        std::string t = js.str();
        size_t k = t.find("\"reg_radius\": ");
        EXPECT_NE(k, std::string::npos) << t;
        return k == std::string::npos ? -1.0 : std::stod(t.substr(k + 14));
    };
    EXPECT_NEAR(radius({}), 0.04 * std::sqrt(36.0 + 2.6 * 2.6 + 36.0), 1e-4);
    EXPECT_NEAR(radius({"--reg-radius", "0.5"}), 0.5, 1e-6);
}

TEST(Cli, ExitCodes) {
    std::string dir = TempDir("cli_exit");
    EXPECT_EQ(RunLucerna({"render", dir + "/missing.pbrt"}), 2);
    std::ofstream(dir + "/bad.pbrt") << "WorldBegin\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 ]\n";
    EXPECT_EQ(RunLucerna({"render", dir + "/bad.pbrt", "-o", dir + "/bad.exr"}), 2);
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.exr"));
    {
        // --device cuda: exit 2 ("no CUDA GPU") without a GPU or CUDA build; on a GPU machine it
        // renders, and must then really have run on the GPU (never a silent CPU fallback).
        int rc = RunLucerna({"render", WriteScene(dir), "--device", "cuda", "--spp", "1", "-o", dir + "/c.exr",
                             "--stats-json", dir + "/c.json"});
        if (rc == 0) {
            std::stringstream js;
            js << std::ifstream(dir + "/c.json").rdbuf();
            EXPECT_NE(js.str().find("\"device\": \"cuda"), std::string::npos) << js.str();
        } else {
            EXPECT_EQ(rc, 2);
            EXPECT_FALSE(std::filesystem::exists(dir + "/c.exr"));
        }
    }
    EXPECT_EQ(RunLucerna({"render", WriteScene(dir), "--res", "0x10"}), 2);
    EXPECT_EQ(RunLucerna({"render", WriteScene(dir), "--integrator", "bdpt"}), 2);
    EXPECT_EQ(RunLucerna({"render", WriteScene(dir), "--spp", "2", "-o", dir + "/ok.exr", "--stats-json", dir + "/s.json"}), 0);
    ImageMetadata meta;
    Image img = ReadImage(dir + "/ok.exr", false, &meta);
    EXPECT_EQ(img.width, 48);
    EXPECT_EQ(meta["lucerna.spp"], "2");
    std::ifstream js(dir + "/s.json");
    std::string json((std::istreambuf_iterator<char>(js)), std::istreambuf_iterator<char>());
    EXPECT_NE(json.find("\"rejected_samples\": 0"), std::string::npos) << json;
    EXPECT_NE(json.find("\"rays_per_second\""), std::string::npos);
}

TEST(Cli, SigintWritesTheImageSoFar) {
    std::string dir = TempDir("cli_sigint");
    std::string scene = WriteScene(dir, 96, 100000);
    pid_t pid = 0;
    RunLucerna({"render", scene, "-o", dir + "/int.exr", "--threads", "1"}, true, &pid, false);
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));
    kill(pid, SIGINT);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 3);
    ImageMetadata meta;
    Image img = ReadImage(dir + "/int.exr", false, &meta);
    int spp = std::stoi(meta["lucerna.spp"]);
    EXPECT_GE(spp, 1);
    EXPECT_LT(spp, 100000);
    EXPECT_EQ(meta["lucerna.interrupted"], "1");
    for (float v : img.pixels) ASSERT_TRUE(std::isfinite(v));
    for (auto &e : std::filesystem::directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(Cli, ResumeIsBitIdentical) {
    std::string dir = TempDir("cli_resume");
    std::string scene = WriteScene(dir, 40, 8);
    ASSERT_EQ(RunLucerna({"render", scene, "--spp", "8", "--seed", "5", "-o", dir + "/full.exr"}), 0);
    ASSERT_EQ(RunLucerna({"render", scene, "--spp", "3", "--seed", "5", "--checkpoint", dir + "/c.ckpt", "-o", dir + "/part.exr"}), 0);
    ASSERT_EQ(RunLucerna({"render", scene, "--spp", "8", "--seed", "5", "--resume", dir + "/c.ckpt", "-o", dir + "/resumed.exr"}), 0);
    Image full = ReadImage(dir + "/full.exr"), resumed = ReadImage(dir + "/resumed.exr"), part = ReadImage(dir + "/part.exr");
    EXPECT_TRUE(SameImage(full, resumed));
    EXPECT_FALSE(SameImage(full, part));
    // A checkpoint of another seed is refused.
    EXPECT_EQ(RunLucerna({"render", scene, "--spp", "8", "--seed", "6", "--resume", dir + "/c.ckpt", "-o", dir + "/x.exr"}), 2);
    // A corrupt checkpoint is refused with exit 2, not a crash.
    std::ofstream(dir + "/bad.ckpt") << "LUCKPT01garbage";
    EXPECT_EQ(RunLucerna({"render", scene, "--resume", dir + "/bad.ckpt"}), 2);
}

TEST(Cli, InterruptThenResumeIsBitIdentical) {
    std::string dir = TempDir("cli_int_resume");
    std::string scene = WriteScene(dir, 64, 8);
    // Long enough that the interrupted render (1 thread) cannot finish within the 0.5 s before
    // SIGINT on a fast machine (~4 s at 600 k samples/s), short enough for the full reference render.
    const std::string total = "600";
    pid_t pid = 0;
    RunLucerna({"render", scene, "--spp", total, "--seed", "9", "--threads", "1", "--checkpoint", dir + "/c.ckpt", "-o",
         dir + "/a.exr"}, true, &pid, false);
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill(pid, SIGINT);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    ASSERT_EQ(WEXITSTATUS(status), 3);
    ASSERT_EQ(RunLucerna({"render", scene, "--spp", total, "--seed", "9", "--resume", dir + "/c.ckpt", "-o", dir + "/b.exr"}), 0);
    ASSERT_EQ(RunLucerna({"render", scene, "--spp", total, "--seed", "9", "-o", dir + "/full.exr"}), 0);
    EXPECT_TRUE(SameImage(ReadImage(dir + "/b.exr"), ReadImage(dir + "/full.exr")));
}

// Every subcommand is linked and registered (apps/commands.cpp has no stubs).
// Rejected samples are explained on stderr and in --stats-json, not only counted: here a light
// so bright (finite, 1e38) that the film's XYZ value overflows.
TEST(Cli, RejectedSamplesAreExplainedInWords) {
    std::string dir = TempDir("cli_rejected");
    std::ofstream(dir + "/bright.pbrt")
        << "LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\nWorldBegin\nAttributeBegin\n"
           "AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"float scale\" 1e38\n"
           "Shape \"sphere\" \"float radius\" [ 0.5 ]\nAttributeEnd\n";
    Background render({"render", dir + "/bright.pbrt", "--spp", "2", "-o", dir + "/b.exr", "--stats-json", dir + "/b.json"});
    ProcessResult r = render.Finish();
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("samples were kept off the film; the first at pixel ("), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("an infinite value at the film"), std::string::npos) << r.output;
    std::string js = FileBytes(dir + "/b.json");
    EXPECT_NE(js.find("\"cause\": \"film\""), std::string::npos) << js;
    EXPECT_NE(js.find("\"value\": \"an infinite value\""), std::string::npos) << js;
    // A clean render says nothing of the kind.
    Background clean({"render", WriteScene(dir, 8, 1), "-o", dir + "/c.exr"});
    ProcessResult c = clean.Finish();
    EXPECT_EQ(c.exitCode, 0);
    EXPECT_EQ(c.output.find("kept off the film"), std::string::npos) << c.output;
}

TEST(Cli, HelpListsEveryCommand) {
    ProcessResult r = RunProcess({kBin, "--help"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char *cmd : {"info", "render", "diff", "converge"}) {
        ProcessResult sub = RunProcess({kBin, cmd, "--help"});
        EXPECT_EQ(sub.exitCode, 0) << cmd << ": " << sub.output;
        EXPECT_NE(r.output.find(std::string("\n  ") + cmd), std::string::npos) << cmd << " missing from\n" << r.output;
    }
}

TEST(Cli, ConvergeWritesCsvReportAndFallingError) {
    // The scene and reference sit in a folder whose name JSON must escape (quote, backslash, tab).
    std::string dir = TempDir("cli_converge") + "/a \"quoted\" back\\slash\ttab";
    std::filesystem::create_directories(dir);
    std::string scene = WriteScene(dir, 32, 8);
    // A converged reference made by the renderer itself (path converges on this scene).
    ASSERT_EQ(RunLucerna({"render", scene, "--spp", "1024", "--seed", "77", "-o", dir + "/ref.exr"}), 0);
    ProcessResult conv = RunProcess({kBin, "converge", scene, "--ref", dir + "/ref.exr", "--spp", "64", "--runs", "2",
                                     "--integrators", "path,regpath", "-o", dir + "/out", "--python", PythonExe()});
    ASSERT_EQ(conv.exitCode, 0) << conv.output;
    std::ifstream csv(dir + "/out/convergence.csv");
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line.rfind("integrator,run,spp,seconds,mse,rmse,relmse", 0), 0u);
    double first = -1, last = -1;
    while (std::getline(csv, line)) {
        if (line.rfind("path,0,", 0) != 0) continue;
        std::vector<std::string> f;
        size_t p = 0, q;
        while ((q = line.find(',', p)) != std::string::npos) { f.push_back(line.substr(p, q - p)); p = q + 1; }
        f.push_back(line.substr(p));
        double mse = std::stod(f[4]);
        if (first < 0) first = mse;
        last = mse;
    }
    EXPECT_GT(first, 0);
    EXPECT_LT(last, first / 8) << "error must fall with spp for path";
    // run.json is valid JSON holding the paths exactly (read back by Python's json module).
    ProcessResult js = RunProcess({PythonExe(), "-c",
                                   "import json, sys; d = json.load(open(sys.argv[1])); "
                                   "assert d['scene'] == sys.argv[2], d['scene']; assert d['reference'] == sys.argv[3]; "
                                   "assert d['integrators'] == ['path', 'regpath']; assert d['spp'] == 64; "
                                   "assert d['time'] is None; print('ok')",
                                   dir + "/out/run.json", scene, dir + "/ref.exr"});
    EXPECT_EQ(js.exitCode, 0) << js.output;
    std::ifstream html(dir + "/out/index.html");
    ASSERT_TRUE(html.good()) << "no index.html: the report scripts failed\n" << conv.output;
    std::string s((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
    size_t pos = 0;
    int refs = 0;
    while ((pos = s.find("src=\"", pos)) != std::string::npos) {
        pos += 5;
        std::string f = s.substr(pos, s.find('"', pos) - pos);
        EXPECT_TRUE(std::filesystem::exists(dir + "/out/" + f)) << f;
        ++refs;
    }
    EXPECT_GE(refs, 4);
    // The report names no absolute path (the scene's folder, the temporary folder).
    EXPECT_EQ(s.find(std::filesystem::temp_directory_path().string()), std::string::npos);
}

// A report script that cannot run or fails makes converge fail with a message naming it.
TEST(Cli, ConvergeReportsScriptFailure) {
    std::string dir = TempDir("cli_converge_fail");
    std::string scene = WriteScene(dir, 16, 2);
    ASSERT_EQ(RunLucerna({"render", scene, "--spp", "4", "-o", dir + "/ref.exr"}), 0);
    auto converge = [&](const std::string &python, const std::string &out) {
        return RunProcess({kBin, "converge", scene, "--ref", dir + "/ref.exr", "--spp", "2", "--integrators", "path",
                           "-o", dir + "/" + out, "--python", python});
    };
    ProcessResult missing = converge(dir + "/no-such-python", "a");
    EXPECT_EQ(missing.exitCode, 1) << missing.output;
    EXPECT_NE(missing.output.find("could not run " + dir + "/no-such-python"), std::string::npos) << missing.output;
    EXPECT_TRUE(std::filesystem::exists(dir + "/a/convergence.csv"));
    ProcessResult failing = converge("false", "b");
    EXPECT_EQ(failing.exitCode, 1) << failing.output;
    EXPECT_NE(failing.output.find("plot_convergence.py " + dir + "/b exited with status 1"), std::string::npos)
        << failing.output;
    // Without the report nothing runs and nothing fails.
    ProcessResult none = RunProcess({kBin, "converge", scene, "--ref", dir + "/ref.exr", "--spp", "2", "--integrators",
                                     "path", "-o", dir + "/c", "--no-report", "--python", "false"});
    EXPECT_EQ(none.exitCode, 0) << none.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/c/index.html"));
}

}  // namespace lu::test
