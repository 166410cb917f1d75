// Tests of the `lucerna diff` logic (image/diff.h) and of the binary's exit codes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "lucerna/image/diff.h"
#include "lucerna/image/image.h"
#include "lucerna/image/metrics.h"
#include "support/test_support.h"

namespace lu {
namespace {

struct DiffFiles {
    std::string dir, image, reference, small, corrupt;
    DiffFiles() : dir(test::TempDir("diff")) {
        image = dir + "/image.exr";
        reference = dir + "/reference.exr";
        small = dir + "/small.exr";
        corrupt = dir + "/corrupt.exr";
        Image r = MakeImage(8, 4, 3, 1.f), v = r;
        v.At(5, 2, 0) = 3.f;  // one value off by 2: mse = 4/96
        WriteEXR(reference, r);
        WriteEXR(image, v);
        WriteEXR(small, MakeImage(4, 4, 3, 1.f));
        std::ofstream(corrupt) << "\x76\x2f\x31\x01 broken";
    }
};

int RunDiffCaptured(const DiffOptions &o, std::string *out = nullptr, std::string *err = nullptr) {
    std::ostringstream os, es;
    int rc = RunDiff(o, os, es);
    if (out) *out = os.str();
    if (err) *err = es.str();
    return rc;
}

TEST(Diff, PrintsOneLinePerMetric) {
    DiffFiles f;
    DiffOptions o;
    o.image = f.image;
    o.reference = f.reference;
    std::string out;
    ASSERT_EQ(RunDiffCaptured(o, &out), 0);
    std::istringstream in(out);
    std::string name;
    double value;
    std::map<std::string, double> got;
    while (in >> name >> value) got[name] = value;
    ASSERT_EQ(got.size(), 4u) << out;
    EXPECT_NEAR(got["mse"], 4.0 / 96, 1e-9);
    EXPECT_NEAR(got["rmse"], std::sqrt(4.0 / 96), 1e-9);
    EXPECT_NEAR(got["relmse"], 4.0 / 1.01 / 96, 1e-9);
    EXPECT_NEAR(got["mape"], 2.0 / 1.01 / 96, 1e-9);

    o.metric = "mse";
    o.crop = "0,0,4,4";  // leaves the differing pixel out
    ASSERT_EQ(RunDiffCaptured(o, &out), 0);
    EXPECT_EQ(out, "mse 0\n");
}

TEST(Diff, WritesErrorImage) {
    DiffFiles f;
    DiffOptions o;
    o.image = f.image;
    o.reference = f.reference;
    o.metric = "mse";
    o.crop = "4,0,8,4";
    o.errorImage = f.dir + "/err.exr";
    ASSERT_EQ(RunDiffCaptured(o), 0);
    ImageMetadata meta;
    Image e = ReadImage(o.errorImage, false, &meta);
    ASSERT_EQ(e.width, 4);
    ASSERT_EQ(e.height, 4);
    ASSERT_EQ(e.channels, 1);
    EXPECT_NEAR(e.At(1, 2, 0), 4.0 / 3, 1e-6);
    EXPECT_EQ(e.At(0, 0, 0), 0.f);
    EXPECT_EQ(meta["lucerna.metric"], "mse");
}

TEST(Diff, BadInputExitsWith2) {
    DiffFiles f;
    auto expect2 = [&](DiffOptions o, const std::string &mention) {
        std::string err;
        EXPECT_EQ(RunDiffCaptured(o, nullptr, &err), 2) << mention;
        EXPECT_NE(err.find(mention), std::string::npos) << err;
    };
    DiffOptions o;
    o.image = f.image;
    o.reference = f.reference;
    DiffOptions missing = o;
    missing.image = f.dir + "/nope.exr";
    expect2(missing, "nope.exr");
    DiffOptions corrupt = o;
    corrupt.reference = f.corrupt;
    expect2(corrupt, "corrupt.exr");
    DiffOptions sizes = o;
    sizes.reference = f.small;
    expect2(sizes, "sizes differ");
    DiffOptions outside = o;
    outside.crop = "0,0,9,4";
    expect2(outside, "does not lie inside");
    DiffOptions badCrop = o;
    badCrop.crop = "1,2";
    expect2(badCrop, "bad crop");
    DiffOptions badMetric = o;
    badMetric.metric = "psnr";
    expect2(badMetric, "unknown metric");
    DiffOptions badOut = o;
    badOut.errorImage = f.dir + "/no/such/dir/e.exr";
    expect2(badOut, "e.exr");
}

TEST(Diff, BlockMeansAndZTest) {
    DiffFiles f;
    DiffOptions o;
    o.image = f.image;
    o.reference = f.reference;
    o.metric = "mse";
    o.blockSize = 4;
    std::string out;
    ASSERT_EQ(RunDiffCaptured(o, &out), 0);
    EXPECT_EQ(out, "mse 0.00260416667\n");  // block (1,0): R mean off by 2/16; 1 of 6 values
    o.zTest = true;
    ASSERT_EQ(RunDiffCaptured(o, &out), 0);
    EXPECT_NE(out.find("zbound"), std::string::npos);
    EXPECT_NE(out.find("ztest pass"), std::string::npos) << out;  // one outlier among 16 pixels
}

// The built binary (tests/CMakeLists.txt makes test_image depend on it): a missing binary or a
// binary without its diff command fails here.
TEST(Diff, BinaryExitCodes) {
    std::string exe = test::LucernaBinary();
    ASSERT_TRUE(std::filesystem::exists(exe)) << exe << " not built";
    DiffFiles f;
    std::string out;
    auto run = [&](std::vector<std::string> args) {
        args.insert(args.begin(), {exe, "diff"});
        test::ProcessResult r = test::RunProcess(args);
        out = r.output;
        return r.exitCode;
    };
    ASSERT_EQ(run({"--help"}), 0) << out;
    EXPECT_NE(out.find("relmse = (1/N) sum (v - r)^2 / (r^2 + 0.01)"), std::string::npos) << out;
    EXPECT_EQ(run({f.image, f.reference, "--metric", "MSE"}), 0) << out;
    EXPECT_EQ(out, "mse 0.0416666667\n");
    EXPECT_EQ(run({f.image, f.small}), 2);
    EXPECT_NE(out.find("sizes differ"), std::string::npos) << out;
    EXPECT_EQ(run({f.image, f.dir + "/missing.exr"}), 2);
    EXPECT_EQ(run({f.image, f.reference, "--crop", "0,0,100,100"}), 2);
    EXPECT_EQ(run({f.image, f.reference, "--metric", "nonsense"}), 2);
    EXPECT_EQ(run({f.image}), 2);
}

}  // namespace
}  // namespace lu
