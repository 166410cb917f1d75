// Lucerna CLI tests: progress when stderr is not a terminal (a pipe, as in CI logs): a line every
// few seconds, not a frame per pass redrawn with '\r'; a time-bounded render shows time and
// passes, not the internal pass limit ("pass 49/16777216").
#include <gtest/gtest.h>

#include <sstream>

#include "cli/cli_support.h"

namespace lu::test {

namespace {

std::vector<std::string> ProgressLines(const std::string &output) {
    std::vector<std::string> lines;
    std::istringstream is(output);
    std::string line;
    while (std::getline(is, line))
        if (line.rfind("pass ", 0) == 0) lines.push_back(line);
    return lines;
}

}  // namespace

TEST(Progress, TimeBoundedRenderToAPipe) {
    std::string dir = TempDir("progress_time");
    std::string scene = WriteScene(dir, 8, 1);
    // 8x8 pixels for 3 s: thousands of passes.
    ProcessResult r = RunProcess({Bin(), "render", scene, "--time", "3", "-o", dir + "/o.exr", "--stats-json", dir + "/s.json"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find('\r'), std::string::npos) << "terminal redraws in a pipe";
    EXPECT_EQ(r.output.find("16777216"), std::string::npos) << r.output;
    std::vector<std::string> lines = ProgressLines(r.output);
    ASSERT_GE(lines.size(), 2u) << r.output;
    EXPECT_LE(lines.size(), 3u) << "a line every few seconds, not one per pass:\n" << r.output;
    // "pass N  T / 3 s ..." and the last one marked done with the final pass count.
    for (const std::string &l : lines) EXPECT_NE(l.find(" / 3 s"), std::string::npos) << l;
    EXPECT_NE(lines.back().find("(done)"), std::string::npos) << lines.back();
    std::string json = FileBytes(dir + "/s.json");
    size_t k = json.find("\n  \"spp\": ");   // the top-level one (the settings object has "spp" too)
    ASSERT_NE(k, std::string::npos) << json;
    int spp = std::stoi(json.substr(k + 10));
    EXPECT_GT(spp, 100) << "the scene renders thousands of passes in 3 s";
    EXPECT_EQ(lines.back().rfind("pass " + std::to_string(spp) + " ", 0), 0u) << lines.back();
}

TEST(Progress, PassBoundedRenderToAPipe) {
    std::string dir = TempDir("progress_spp");
    std::string scene = WriteScene(dir, 8, 1);
    ProcessResult r = RunProcess({Bin(), "render", scene, "--spp", "500", "-o", dir + "/o.exr"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find('\r'), std::string::npos);
    std::vector<std::string> lines = ProgressLines(r.output);
    ASSERT_GE(lines.size(), 1u) << r.output;
    EXPECT_LE(lines.size(), 3u) << r.output;
    EXPECT_EQ(lines.back().rfind("pass 500/500  100%", 0), 0u) << lines.back();
    EXPECT_NE(lines.back().find("(done)"), std::string::npos) << lines.back();
    // -q: none.
    r = RunProcess({Bin(), "render", scene, "--spp", "50", "-q", "-o", dir + "/o.exr"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(ProgressLines(r.output).empty()) << r.output;
}

}  // namespace lu::test
