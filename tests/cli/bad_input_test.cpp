// Lucerna CLI tests: bad input on the command line is exit 2 with a message, before anything is
// rendered or written: a corrupted or old checkpoint (it used to be read back into NaN pixels),
// a resolution with trailing junk, out-of-range settings.
#include <gtest/gtest.h>

#include "cli/cli_support.h"

namespace lu::test {

namespace {

ProcessResult Render(const std::vector<std::string> &args) {
    std::vector<std::string> argv = {Bin(), "render"};
    argv.insert(argv.end(), args.begin(), args.end());
    return RunProcess(argv);
}

}  // namespace

TEST(BadInput, CorruptedCheckpointIsRefused) {
    std::string dir = TempDir("bad_ckpt");
    std::string scene = WriteScene(dir, 32, 8);
    ASSERT_EQ(Render({scene, "--spp", "2", "--checkpoint", dir + "/c.ckpt", "-o", dir + "/a.exr"}).exitCode, 0);
    std::string bytes = FileBytes(dir + "/c.ckpt");
    for (size_t i = 0; i < 16; ++i) bytes[bytes.size() / 2 + i] = char(0xff);
    std::ofstream(dir + "/bad.ckpt", std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    ProcessResult r = Render({scene, "--spp", "4", "--resume", dir + "/bad.ckpt", "-o", dir + "/b.exr"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("lucerna: error: " + dir + "/bad.ckpt: corrupt checkpoint: checksum mismatch"),
              std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/b.exr"));
    // The intact one resumes.
    r = Render({scene, "--spp", "4", "--resume", dir + "/c.ckpt", "-o", dir + "/b.exr"});
    EXPECT_EQ(r.exitCode, 0) << r.output;
    // Garbage after an old magic names the version.
    std::ofstream(dir + "/old.ckpt") << "LUCKPT01garbage";
    r = Render({scene, "--resume", dir + "/old.ckpt", "-o", dir + "/c.exr"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find(dir + "/old.ckpt: checkpoint format version 1"), std::string::npos) << r.output;
}

TEST(BadInput, ResolutionMustBeWxH) {
    std::string dir = TempDir("bad_res");
    std::string scene = WriteScene(dir, 8, 1);
    for (const char *res : {"32x24junk", "32x", "x24", "32*24", "-32x24", "32x24x2", "0x10", "32 x24", "99999x99999", ""}) {
        ProcessResult r = Render({scene, "--res", res, "-o", dir + "/o.exr"});
        EXPECT_EQ(r.exitCode, 2) << res << "\n" << r.output;
        if (*res) { EXPECT_NE(r.output.find(std::string("--res ") + res + ": expected WxH"), std::string::npos) << r.output; }
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/o.exr"));
    ProcessResult ok = Render({scene, "--res", "12x10", "-o", dir + "/o.exr"});
    ASSERT_EQ(ok.exitCode, 0) << ok.output;
    EXPECT_EQ(ReadImage(dir + "/o.exr").width, 12);
}

// The settings object refuses out-of-range values by name, before the scene is read.
TEST(BadInput, SettingsAreCheckedByName) {
    std::string dir = TempDir("bad_settings");
    std::string scene = WriteScene(dir, 8, 1);
    struct Case {
        std::vector<std::string> args;
        std::string name;
    };
    for (const Case &c : std::vector<Case>{{{"--reg-radius", "-1"}, "reg-radius"},
                                           {{"--reg-radius", "nan"}, "reg-radius"},
                                           {{"--reg-lambda", "2"}, "reg-lambda"},
                                           {{"--spp", "0"}, "spp"},
                                           {{"--spp", "12junk"}, "spp"},
                                           {{"--maxdepth", "-2"}, "maxdepth"},
                                           {{"--time", "-5"}, "time"},
                                           {{"--threads", "x"}, "threads"}}) {
        std::vector<std::string> args = {scene, "-o", dir + "/o.exr"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        ProcessResult r = Render(args);
        EXPECT_EQ(r.exitCode, 2) << c.args[0] << " " << c.args[1] << "\n" << r.output;
        EXPECT_NE(r.output.find("--" + c.name), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("device: "), std::string::npos) << "checked after the device and scene:\n" << r.output;
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/o.exr"));
}

}  // namespace lu::test
