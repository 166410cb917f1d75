// Tests of scripts/plot_convergence.py and scripts/make_report.py on a synthetic convergence
// directory (the layout of docs/convergence.md), run by the python3 with matplotlib that CMake
// found (LUCERNA_PYTHON); matplotlib is a declared dependency: without it these tests fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "lucerna/image/image.h"
#include "support/test_support.h"

namespace lu {
namespace {

namespace fs = std::filesystem;

// Runs scripts/NAME with the arguments; returns the exit status (output in *out).
int Script(const std::string &name, std::vector<std::string> args, std::string *out = nullptr) {
    args.insert(args.begin(), {test::PythonExe(), test::SourcePath("scripts/" + name)});
    test::ProcessResult r = test::RunProcess(args);
    if (out) *out = r.output;
    return r.exitCode;
}

std::string ReadText(const std::string &path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

::testing::AssertionResult HaveMatplotlib() {
    test::ProcessResult r = test::RunProcess({test::PythonExe(), "-c", "import matplotlib, numpy"});
    if (r.exitCode == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << test::PythonExe() << " cannot import matplotlib and numpy (install "
                                         << "python3-matplotlib: scripts/setup.sh, then reconfigure): " << r.output;
}

// A convergence directory as `lucerna converge` writes it: 2 integrators x 3 runs.
std::string MakeConvergenceDir(const std::string &name, bool withFinal) {
    std::string dir = test::TempDir(name);
    const int w = 48, h = 32;
    Image ref = MakeImage(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) ref.At(x, y, c) = 0.1f + 0.8f * float(x + c * y) / (w + 2 * h);
    WritePNG(dir + "/reference.png", ref);
    std::mt19937 rng(1);
    std::normal_distribution<float> n(0, 1);
    for (auto [integrator, sigma] : {std::pair{"path", 0.2f}, std::pair{"regpath", 0.05f}})
        for (const char *budget : {"time", "spp"}) {
            Image im = ref;
            for (int y = 0; y < h; ++y)
                for (int x = w / 2; x < w; ++x)  // noise only on the right: the crops must go there
                    for (int c = 0; c < 3; ++c) im.At(x, y, c) += sigma * n(rng);
            WritePNG(dir + "/" + integrator + "_" + budget + ".png", im);
        }
    std::ofstream csv(dir + "/convergence.csv");
    csv << "integrator,run,spp,seconds,mse,rmse,relmse\n";
    for (auto [integrator, c] : {std::pair{"path", 1.0}, std::pair{"regpath", 0.3}})
        for (int run = 0; run < 3; ++run)
            for (int spp = 1; spp <= 64; spp *= 2) {
                double mse = c / spp * (1 + 0.1 * run);
                csv << integrator << "," << run << "," << spp << "," << 0.05 * spp * (1 + 0.02 * run) << "," << mse
                    << "," << std::sqrt(mse) << "," << 2 * mse << "\n";
            }
    csv.close();
    if (withFinal) {
        std::ofstream f(dir + "/final.csv");
        f << "integrator,budget,runs,spp,seconds,mse,rmse,relmse,mape,bias2,variance,relbias2,relvariance\n"
             "path,time,3,64,3.2,0.0156,0.125,0.0312,0.1,0.0001,0.0155,0.0002,0.031\n"
             "regpath,time,3,50,3.2,0.006,0.077,0.012,0.05,0.001,0.005,0.002,0.01\n"
             "path,spp,3,50,2.5,0.02,0.141,0.04,0.12,,,,\n"
             "regpath,spp,3,50,3.2,0.006,0.077,0.012,0.05,,,,\n";
        std::ofstream j(dir + "/run.json");
        j << R"({"scene": "/x/bitterli-cornell-box/scene-v4.pbrt", "reference": "/x/refs/cornell-box.exr",)"
          << R"( "width": 48, "height": 32, "time": 3.2, "runs": 3, "integrators": ["path", "regpath"]})";
    }
    return dir;
}

TEST(ReportScripts, PythonHasMatplotlib) { EXPECT_TRUE(HaveMatplotlib()); }

TEST(ReportScripts, PlotsAndReportReferenceExistingFiles) {
    ASSERT_TRUE(HaveMatplotlib());
    std::string dir = MakeConvergenceDir("report_scripts", true);
    std::string out;
    ASSERT_EQ(Script("plot_convergence.py", {dir}, &out), 0) << out;
    for (const char *plot : {"plot_spp.png", "plot_time.png"}) {
        Image p = ReadImage(dir + "/" + plot);  // a real PNG
        EXPECT_GT(p.width, 300) << plot;
    }
    ASSERT_EQ(Script("make_report.py", {dir}, &out), 0) << out;
    std::string html = ReadText(dir + "/index.html");
    ASSERT_FALSE(html.empty());
    // No absolute path in the report: run.json's scene and reference are named by their file names.
    EXPECT_EQ(html.find("/x/"), std::string::npos);
    EXPECT_EQ(html.find(dir), std::string::npos);
    std::regex src("src=\"([^\"]+)\"");
    int images = 0;
    for (auto it = std::sregex_iterator(html.begin(), html.end(), src); it != std::sregex_iterator(); ++it) {
        std::string file = (*it)[1];
        EXPECT_TRUE(fs::exists(dir + "/" + file)) << file;
        ++images;
    }
    // 2 plots, 2 x (reference + 2 images), 2 x (boxes + 3 regions x 3 crops).
    EXPECT_EQ(images, 2 + 2 * 3 + 2 * (1 + 3 * 3));
    EXPECT_NE(html.find("cornell-box"), std::string::npos);
    EXPECT_NE(html.find("2.60&times; lower"), std::string::npos);  // regpath 0.012 vs path 0.0312
    EXPECT_NE(html.find("bias&sup2;"), std::string::npos);
    // Every zoomed region lies in the noisy right half (x >= 24) where the integrators differ.
    std::string regions = ReadText(dir + "/crops/regions.json");
    std::regex x0("\"x0\": (\\d+)");
    int found = 0;
    for (auto it = std::sregex_iterator(regions.begin(), regions.end(), x0); it != std::sregex_iterator(); ++it) {
        EXPECT_GE(std::stoi((*it)[1]), 24 - 8) << regions;  // a window may straddle the border a little
        ++found;
    }
    EXPECT_EQ(found, 6);
}

TEST(ReportScripts, WorksWithoutFinalCsvAndUpdatesBenchmarks) {
    ASSERT_TRUE(HaveMatplotlib());
    std::string dir = MakeConvergenceDir("report_minimal", false);
    std::string out;
    ASSERT_EQ(Script("make_report.py", {dir}, &out), 0) << out;
    std::string html = ReadText(dir + "/index.html");
    EXPECT_NE(html.find("Last checkpoint"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir + "/plot_time.png"));  // make_report ran the plot script

    std::string md = dir + "/benchmarks.md";
    std::ofstream(md) << "# Benchmarks\n\nintro\n\n<!-- BEGIN convergence (old) -->\nold\n<!-- END convergence -->\nafter\n";
    // The block between the markers is replaced (twice: the second run finds the first's markers).
    ASSERT_EQ(Script("make_report.py", {"--benchmarks", md, dir}, &out), 0) << out;
    ASSERT_EQ(Script("make_report.py", {"--benchmarks", md, dir}, &out), 0) << out;
    std::string text = ReadText(md);
    EXPECT_EQ(text.find(dir), std::string::npos) << "an absolute path in the benchmarks block";
    EXPECT_NE(text.find("reference in data/refs"), std::string::npos) << text;
    const std::string name = fs::path(dir).filename().string();  // the scene's name: the folder's (run.json has none)
    EXPECT_NE(text.find("| " + name + " |"), std::string::npos) << text;
    EXPECT_NE(text.find("intro"), std::string::npos);
    EXPECT_NE(text.find("after"), std::string::npos);
    EXPECT_EQ(text.find("\nold\n"), std::string::npos);
    size_t first = text.find("<!-- BEGIN convergence (generated");
    ASSERT_NE(first, std::string::npos);
    EXPECT_EQ(text.find("<!-- BEGIN convergence (generated", first + 1), std::string::npos);  // replaced, not appended twice
    EXPECT_TRUE(fs::exists(dir + "/benchmarks/" + name + "_time.png"));

    // Bad input: a CSV without the required columns.
    std::ofstream(dir + "/convergence.csv") << "integrator,spp\npath,1\n";
    EXPECT_NE(Script("plot_convergence.py", {dir}, &out), 0);
    EXPECT_NE(out.find("missing columns"), std::string::npos) << out;
}

}  // namespace
}  // namespace lu
