// Lucerna CLI tests: every output path (-o, --png, --stats-json, --checkpoint) is checked before
// the scene is read (a folder, an unknown image extension, a folder that cannot be made, a
// read-only file: exit 2) and, once it is read, against every file the render reads (the scene,
// an include, a PLY mesh, a texture, a spectrum file) and every other output, by filesystem
// identity. The unit checks of apps/output_paths.cpp come first.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "apps/output_paths.h"
#include "cli/cli_support.h"

namespace lu::test {

using app::ModeAllowsWrite;
using app::SameFile;

namespace {

ProcessResult Render(const std::vector<std::string> &args) {
    std::vector<std::string> argv = {Bin(), "render"};
    argv.insert(argv.end(), args.begin(), args.end());
    return RunProcess(argv);
}

// A scene that reads an included file, a PLY mesh, a texture image and a spectrum file.
struct InputScene {
    std::string dir, scene, include, ply, texture, spectrum;
};

InputScene WriteInputScene(const std::string &dir) {
    InputScene s{dir, dir + "/scene.pbrt", dir + "/inc.pbrt", dir + "/mesh.ply", dir + "/tex.png", dir + "/eta.spd"};
    std::ofstream(s.include) << "Material \"diffuse\" \"texture reflectance\" \"checks\"\n";
    std::ofstream(s.ply) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "-1 -0.6 -1\n1 -0.6 -1\n0 -0.6 1\n3 0 1 2\n";
    Image tex;
    tex.width = tex.height = 2;
    tex.channels = 3;
    tex.pixels = {0.2f, 0.2f, 0.2f, 0.8f, 0.8f, 0.8f, 0.8f, 0.8f, 0.8f, 0.2f, 0.2f, 0.2f};
    WritePNG(s.texture, tex);
    std::ofstream(s.spectrum) << "# wavelength eta\n300 1.5\n900 1.5\n";
    std::ofstream(s.scene) << "LookAt 0 1 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 50 ]\n"
                              "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
                              "Sampler \"zsobol\" \"integer pixelsamples\" [ 1 ]\nWorldBegin\n"
                              "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
                              "Texture \"checks\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.png\"\n"
                              "Include \"inc.pbrt\"\n"
                              "Shape \"plymesh\" \"string filename\" \"mesh.ply\"\n"
                              "Material \"dielectric\" \"spectrum eta\" \"eta.spd\"\n"
                              "Shape \"sphere\" \"float radius\" [ 0.5 ]\n";
    return s;
}

}  // namespace

TEST(OutputPaths, SameFileByIdentity) {
    std::string dir = TempDir("outpaths_same");
    std::filesystem::create_directories(dir + "/sub");
    std::ofstream(dir + "/a.txt") << "a";
    std::ofstream(dir + "/b.txt") << "b";
    EXPECT_TRUE(SameFile(dir + "/a.txt", dir + "/a.txt"));
    EXPECT_TRUE(SameFile(dir + "/a.txt", dir + "/sub/../a.txt"));
    EXPECT_TRUE(SameFile(dir + "/a.txt", dir + "/./a.txt"));
    EXPECT_FALSE(SameFile(dir + "/a.txt", dir + "/b.txt"));
    std::filesystem::create_hard_link(dir + "/a.txt", dir + "/hard.txt");
    std::filesystem::create_symlink(dir + "/a.txt", dir + "/link.txt");
    EXPECT_TRUE(SameFile(dir + "/a.txt", dir + "/hard.txt"));
    EXPECT_TRUE(SameFile(dir + "/link.txt", dir + "/a.txt"));
    // Files that do not exist yet: the same normalized absolute path.
    EXPECT_TRUE(SameFile(dir + "/new.exr", dir + "/sub/../new.exr"));
    EXPECT_FALSE(SameFile(dir + "/new.exr", dir + "/new.png"));
    std::filesystem::create_symlink(dir + "/sub", dir + "/sublink");
    EXPECT_TRUE(SameFile(dir + "/sublink/new.exr", dir + "/sub/new.exr"));
    // Relative to the working folder.
    std::filesystem::path cwd = std::filesystem::current_path();
    std::filesystem::current_path(dir);
    EXPECT_TRUE(SameFile("a.txt", dir + "/a.txt"));
    EXPECT_TRUE(SameFile("x/y.exr", dir + "/x/y.exr"));
    std::filesystem::current_path(cwd);
}

// The mode bits decide, for root too (access(W_OK) always says yes to root).
TEST(OutputPaths, ModeBitsDecideForEveryone) {
    unsigned me = geteuid(), myGroup = getegid(), other = me + 12345, otherGroup = myGroup + 12345;
    EXPECT_TRUE(ModeAllowsWrite(0644, me, myGroup));
    EXPECT_FALSE(ModeAllowsWrite(0444, me, myGroup));
    EXPECT_FALSE(ModeAllowsWrite(0466, me, myGroup)) << "the owner's bit decides for the owner";
    EXPECT_TRUE(ModeAllowsWrite(0464, other, myGroup));
    EXPECT_FALSE(ModeAllowsWrite(0646, other, myGroup)) << "the group's bit decides for the group";
    EXPECT_TRUE(ModeAllowsWrite(0442, other, otherGroup));
    EXPECT_FALSE(ModeAllowsWrite(0664, other, otherGroup));
}

// Bad output paths are refused before the scene is read: the scene here is not even valid, so the
// message must be about the path (before, each rendered in full and then failed with exit 1).
TEST(OutputPaths, CheckedBeforeTheSceneIsRead) {
    std::string dir = TempDir("outpaths_before");
    std::string bad = dir + "/bad.pbrt";
    std::ofstream(bad) << "WorldBegin\nShape \"nonsense\"\n";
    std::filesystem::create_directories(dir + "/folder");
    std::ofstream(dir + "/file") << "x";
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"-o", dir + "/folder"}, "-o " + dir + "/folder is a folder"},
        {{"-o", dir + "/out.jpg"}, "-o " + dir + "/out.jpg: unknown image format '.jpg'"},
        {{"-o", dir + "/out"}, "-o " + dir + "/out: unknown image format ''"},
        {{"-o", dir + "/file/out.exr"}, dir + "/file is not a folder"},
        {{"-o", dir + "/file/deeper/out.exr"}, dir + "/file is not a folder"},
        {{"--stats-json", dir + "/folder"}, "--stats-json " + dir + "/folder is a folder"},
        {{"--stats-json", dir + "/file/s.json"}, dir + "/file is not a folder"},
        {{"--checkpoint", dir + "/folder"}, "--checkpoint " + dir + "/folder is a folder"},
        {{"--checkpoint", dir + "/file/c.ckpt"}, dir + "/file is not a folder"},
        {{"--checkpoint", dir + "/x.ckpt", "--stats-json", dir + "/sub/../x.ckpt"},
         "--checkpoint " + dir + "/x.ckpt is the same file as --stats-json " + dir + "/sub/../x.ckpt"},
        {{"-o", dir + "/a.exr", "--png", "--stats-json", dir + "/a.png"}, "--stats-json " + dir + "/a.png is the same file as --png"},
        {{"-o", dir + "/x.exr", "--resume", dir + "/x.exr"}, "-o " + dir + "/x.exr would overwrite --resume"},
        {{"--checkpoint", bad}, "--checkpoint " + bad + " would overwrite the scene file " + bad},
        {{"-o", dir + "/out.exr", "--stats-json", dir + "/../" + std::filesystem::path(dir).filename().string() + "/bad.pbrt"},
         "would overwrite the scene file"},
        {{"--stats-json", "/dev/null"}, "--stats-json /dev/null is not a regular file"},
    };
    for (const Case &c : cases) {
        std::vector<std::string> args = {bad};
        args.insert(args.end(), c.args.begin(), c.args.end());
        ProcessResult r = Render(args);
        EXPECT_EQ(r.exitCode, 2) << c.message << "\n" << r.output;
        EXPECT_NE(r.output.find("lucerna: error: "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << "expected: " << c.message << "\n" << r.output;
        EXPECT_EQ(r.output.find("nonsense"), std::string::npos) << "the scene was read first:\n" << r.output;
    }
    EXPECT_EQ(FileBytes(bad), "WorldBegin\nShape \"nonsense\"\n");
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.ckpt"));
}

// An output that is a file the scene reads is refused once the scene is read, before rendering,
// naming both; the input is left as it was. (A checkpoint over the scene file replaced it.)
TEST(OutputPaths, OutputsThatAreInputsAreRefused) {
    std::string dir = TempDir("outpaths_inputs");
    InputScene s = WriteInputScene(dir);
    ASSERT_EQ(Render({s.scene, "-o", dir + "/ok.exr"}).exitCode, 0) << Render({s.scene, "-o", dir + "/ok.exr"}).output;
    std::filesystem::create_hard_link(s.scene, dir + "/hardlink.pbrt");
    std::filesystem::create_symlink(s.include, dir + "/inc-link.pbrt");
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    auto reads = [](const std::string &output, const std::string &input) {
        return output + " would overwrite " + input + ", which the render reads";
    };
    const std::string in = "the scene's input file ";
    const std::vector<Case> cases = {
        {{"--checkpoint", s.scene}, reads("--checkpoint " + s.scene, "the scene file " + s.scene)},
        {{"--checkpoint", dir + "/hardlink.pbrt"}, reads("--checkpoint " + dir + "/hardlink.pbrt", "the scene file " + s.scene)},
        {{"--stats-json", s.include}, reads("--stats-json " + s.include, in + s.include)},
        {{"--stats-json", dir + "/inc-link.pbrt"}, reads("--stats-json " + dir + "/inc-link.pbrt", in + s.include)},
        {{"--checkpoint", s.ply}, reads("--checkpoint " + s.ply, in + s.ply)},
        {{"-o", s.texture}, reads("-o " + s.texture, in + s.texture)},
        {{"-o", dir + "/tex.exr", "--png"}, reads("--png " + s.texture, in + s.texture)},
        {{"--stats-json", s.spectrum}, reads("--stats-json " + s.spectrum, in + s.spectrum)},
    };
    std::vector<std::string> before;
    for (const std::string &f : {s.scene, s.include, s.ply, s.texture, s.spectrum}) before.push_back(FileBytes(f));
    for (const Case &c : cases) {
        std::vector<std::string> args = {s.scene};
        if (c.args[0] != "-o") args.insert(args.end(), {"-o", dir + "/out.exr"});
        args.insert(args.end(), c.args.begin(), c.args.end());
        ProcessResult r = Render(args);
        EXPECT_EQ(r.exitCode, 2) << c.message << "\n" << r.output;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << "expected: " << c.message << "\n" << r.output;
        EXPECT_EQ(r.output.find("spp "), std::string::npos) << "rendered:\n" << r.output;
    }
    std::vector<std::string> after;
    for (const std::string &f : {s.scene, s.include, s.ply, s.texture, s.spectrum}) after.push_back(FileBytes(f));
    EXPECT_EQ(before, after);
    EXPECT_FALSE(std::filesystem::exists(dir + "/out.exr"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/tex.exr"));
}

// An environment map (read by the infinite light, not by a texture) is an input too.
TEST(OutputPaths, EnvironmentMapIsAnInput) {
    std::string dir = TempDir("outpaths_envmap");
    std::string env = dir + "/env.png", scene = dir + "/env.pbrt";
    Image img;
    img.width = img.height = 2;
    img.channels = 3;
    img.pixels.assign(12, 0.5f);
    WritePNG(env, img);
    std::ofstream(scene) << "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ]\n"
                            "Sampler \"zsobol\" \"integer pixelsamples\" [ 1 ]\nWorldBegin\n"
                            "LightSource \"infinite\" \"string filename\" \"env.png\"\n"
                            "Shape \"sphere\" \"float radius\" [ 0.5 ]\n";
    std::string before = FileBytes(env);
    ProcessResult ok = Render({scene, "-o", dir + "/ok.exr"});
    ASSERT_EQ(ok.exitCode, 0) << ok.output;
    ProcessResult r = Render({scene, "-o", env});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("-o " + env + " would overwrite the scene's input file " + env + ", which the render reads"),
              std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("spp "), std::string::npos) << "rendered:\n" << r.output;
    EXPECT_EQ(FileBytes(env), before);
}

// The default output name (Film "filename", else the scene's name) is checked like -o.
TEST(OutputPaths, DefaultOutputIsChecked) {
    std::string dir = TempDir("outpaths_default");
    std::string scene = dir + "/film.pbrt";
    std::ofstream(scene) << "Film \"rgb\" \"integer xresolution\" [ 4 ] \"integer yresolution\" [ 4 ] "
                            "\"string filename\" \"" << dir << "/picture.jpg\"\nWorldBegin\n"
                            "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n";
    ProcessResult r = Render({scene});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("picture.jpg: unknown image format '.jpg'"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("spp "), std::string::npos) << "rendered:\n" << r.output;
}

// A read-only output is refused before anything is read or rendered, and stays as it was. The
// mode bits decide, so this holds when the tests run as root.
TEST(OutputPaths, ReadOnlyOutputsAreRefused) {
    std::string dir = TempDir("outpaths_readonly");
    std::string scene = WriteScene(dir, 8, 1);
    for (const std::string opt : {"-o", "--stats-json", "--checkpoint"}) {
        std::string path = dir + "/ro" + (opt == "-o" ? ".exr" : ".out");
        std::ofstream(path) << "keep";
        ASSERT_EQ(chmod(path.c_str(), 0444), 0);
        std::vector<std::string> args = {scene, opt, path};
        if (opt != "-o") args.insert(args.end(), {"-o", dir + "/w.exr"});
        ProcessResult r = Render(args);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find(opt + " " + path + " is read-only (mode 0444)"), std::string::npos) << r.output;
        EXPECT_EQ(FileBytes(path), "keep");
        chmod(path.c_str(), 0644);
        std::filesystem::remove(path);
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/w.exr"));
    // The preview beside the image too.
    std::ofstream(dir + "/p.png") << "keep";
    ASSERT_EQ(chmod((dir + "/p.png").c_str(), 0400), 0);
    ProcessResult r = Render({scene, "-o", dir + "/p.exr", "--png"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--png " + dir + "/p.png is read-only (mode 0400)"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/p.exr"));
    // A writable one is replaced.
    std::ofstream(dir + "/rw.exr") << "old";
    EXPECT_EQ(Render({scene, "-o", dir + "/rw.exr"}).exitCode, 0);
    EXPECT_NE(FileBytes(dir + "/rw.exr"), "old");
}

// Missing folders are made for every output (as -o always did), once the scene is read.
TEST(OutputPaths, MissingFoldersAreMade) {
    std::string dir = TempDir("outpaths_folders");
    std::string scene = WriteScene(dir, 8, 1);
    ProcessResult r = Render({scene, "-o", dir + "/a/b/out.exr", "--png", "--stats-json", dir + "/c/s.json",
                              "--checkpoint", dir + "/d/e/c.ckpt"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char *f : {"/a/b/out.exr", "/a/b/out.png", "/c/s.json", "/d/e/c.ckpt"})
        EXPECT_TRUE(std::filesystem::is_regular_file(dir + f)) << f;
    // Not made when the scene cannot be read.
    std::ofstream(dir + "/bad.pbrt") << "Nonsense\n";
    r = Render({dir + "/bad.pbrt", "-o", dir + "/f/out.exr", "--stats-json", dir + "/g/s.json"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(std::filesystem::exists(dir + "/f"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/g"));
}

// A render may resume a checkpoint and keep saving into it; the result is the uninterrupted one.
TEST(OutputPaths, CheckpointMayBeTheResumedFile) {
    std::string dir = TempDir("outpaths_resume_same");
    std::string scene = WriteScene(dir, 16, 6);
    ASSERT_EQ(Render({scene, "--spp", "6", "-o", dir + "/full.exr"}).exitCode, 0);
    ASSERT_EQ(Render({scene, "--spp", "2", "--checkpoint", dir + "/c.ckpt", "-o", dir + "/p.exr"}).exitCode, 0);
    ASSERT_EQ(Render({scene, "--spp", "4", "--resume", dir + "/c.ckpt", "--checkpoint", dir + "/c.ckpt", "-o",
                      dir + "/p.exr"}).exitCode, 0);
    ProcessResult r = Render({scene, "--spp", "6", "--resume", dir + "/c.ckpt", "-o", dir + "/r.exr"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("at pass 4 of 6"), std::string::npos) << r.output;
    EXPECT_TRUE(SameImage(ReadImage(dir + "/r.exr"), ReadImage(dir + "/full.exr")));
}

}  // namespace lu::test
