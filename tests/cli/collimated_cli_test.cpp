// Lucerna CLI tests of the collimated beam light (docs/lights.md): `lucerna info` lists it, plain
// path tracing warns once per beam at its LightSource (it renders the beam black), regpath does
// not, and a bad parameter is a located error with exit status 2.
#include <gtest/gtest.h>

#include <fstream>

#include "cli/cli_support.h"

namespace lu::test {

namespace {
bool Has(const std::string &s, const std::string &what) { return s.find(what) != std::string::npos; }
}  // namespace

TEST(CollimatedCli, InfoWarningAndErrors) {
    std::string scene = SourcePath("scenes/laser/laser.pbrt");
    ProcessResult info = RunProcess({Bin(), "info", scene});
    EXPECT_EQ(info.exitCode, 0) << info.output;
    EXPECT_TRUE(Has(info.output, "lights: 3 (collimated 2, infinite 1)")) << info.output;

    std::string dir = TempDir("collimated_cli");
    ProcessResult path = RunProcess({Bin(), "render", scene, "--integrator", "path", "--res", "16x10", "--spp", "1", "-q",
                                     "-o", dir + "/p.exr"});
    EXPECT_EQ(path.exitCode, 0) << path.output;
    const std::string warning = "warning: collimated light: path cannot connect to a collimated beam";
    EXPECT_TRUE(Has(path.output, scene + ":31:1: " + warning)) << path.output;
    EXPECT_TRUE(Has(path.output, scene + ":36:1: " + warning)) << path.output;
    ProcessResult reg = RunProcess({Bin(), "render", scene, "--integrator", "regpath", "--res", "16x10", "--spp", "1", "-q",
                                    "-o", dir + "/r.exr"});
    EXPECT_EQ(reg.exitCode, 0) << reg.output;
    EXPECT_FALSE(Has(reg.output, warning)) << reg.output;

    std::string bad = dir + "/bad.pbrt";
    std::ofstream(bad) << "WorldBegin\nLightSource \"collimated\" \"float radius\" 0.01\n"
                          "    \"string profile\" \"gaussian\" \"float waist\" -1\n";
    ProcessResult err = RunProcess({Bin(), "render", bad, "-q", "-o", dir + "/b.exr"});
    EXPECT_EQ(err.exitCode, 2) << err.output;
    EXPECT_TRUE(Has(err.output, bad + ":3:")) << err.output;
    EXPECT_TRUE(Has(err.output, "error: collimated light: \"waist\" must be positive (got -1)")) << err.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/b.exr"));
}

}  // namespace lu::test
