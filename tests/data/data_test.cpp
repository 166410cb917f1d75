// Tests of the repository's data and self-containedness: SharedPath stays inside the source
// tree, the scene list (support/shared_scenes.h) agrees with data/scenes/README.md and with each
// reference's .txt, every scene folder keeps its README/licence, and no source, script or doc
// names a path outside the repository (the old shared folder beside it, absolute paths of this
// machine).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "support/shared_scenes.h"
#include "support/test_support.h"

namespace lu::test {
namespace {

namespace fs = std::filesystem;

std::string ReadText(const fs::path &p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// p lies inside dir (both made canonical).
bool Inside(const fs::path &p, const fs::path &dir) {
    fs::path rel = fs::weakly_canonical(p).lexically_relative(fs::weakly_canonical(dir));
    return !rel.empty() && *rel.begin() != "..";
}

TEST(Data, SharedPathStaysInsideTheSourceTree) {
    fs::path root = SourcePath("");
    EXPECT_TRUE(Inside(SharedPath(""), root)) << SharedPath("");
    EXPECT_TRUE(Inside(SharedPath("scenes/README.md"), root));
    EXPECT_TRUE(fs::exists(SharedPath("README.md")));
    for (const SharedScene &s : SharedScenes()) {
        SCOPED_TRACE(s.name);
        EXPECT_TRUE(Inside(SharedPath(s.scene), root)) << SharedPath(s.scene);
        EXPECT_TRUE(fs::is_regular_file(SharedPath(s.scene))) << SharedPath(s.scene);
        if (s.HasReference()) {
            EXPECT_TRUE(fs::is_regular_file(SharedPath(s.reference))) << SharedPath(s.reference);
        }
    }
}

TEST(Data, SceneListMatchesTheReadme) {
    std::string readme = ReadText(SharedPath("scenes/README.md"));
    ASSERT_FALSE(readme.empty());
    // Table rows "| folder/file.pbrt | what it exercises |".
    std::set<std::string> table;
    std::regex row("\\| *([A-Za-z0-9_.-]+/[A-Za-z0-9_.-]+\\.pbrt) *\\|");
    for (auto it = std::sregex_iterator(readme.begin(), readme.end(), row); it != std::sregex_iterator(); ++it)
        table.insert("scenes/" + (*it)[1].str());
    EXPECT_GE(table.size(), 9u);
    std::set<std::string> listed, names;
    for (const SharedScene &s : SharedScenes()) {
        listed.insert(s.scene);
        EXPECT_TRUE(names.insert(s.name).second) << "duplicate name " << s.name;
        // Every listed file is in the table, or named in the README's text (kept-for-reference files).
        EXPECT_TRUE(table.count(s.scene) || readme.find(fs::path(s.scene).filename().string()) != std::string::npos)
            << s.scene << " is not in data/scenes/README.md";
    }
    for (const std::string &f : table) EXPECT_TRUE(listed.count(f)) << f << " (README) is missing from SharedScenes()";
    // The rendered ones come first, in the README's order.
    bool refused = false;
    for (const SharedScene &s : SharedScenes()) {
        if (!s.renders) refused = true;
        EXPECT_FALSE(refused && s.renders) << s.name << " follows a refused scene";
    }
    EXPECT_EQ(RenderedSharedScenes().size(), 10u);
    ASSERT_NE(FindSharedScene("cornell-box"), nullptr);
    EXPECT_TRUE(FindSharedScene("cornell-box")->ExactReference());
    EXPECT_EQ(FindSharedScene("no-such-scene"), nullptr);
}

TEST(Data, ReferencesMatchTheirProvenance) {
    std::set<std::string> listedRefs;
    for (const SharedScene &s : SharedScenes()) {
        if (!s.HasReference()) continue;
        SCOPED_TRACE(s.name);
        listedRefs.insert(s.reference);
        EXPECT_EQ(fs::path(s.reference).stem().string(), s.name);
        fs::path txt = fs::path(SharedPath(s.reference)).replace_extension(".txt");
        std::string t = ReadText(txt);
        ASSERT_FALSE(t.empty()) << txt;
        int w = 0, h = 0, spp = 0;
        size_t at = t.find("resolution: ");
        ASSERT_NE(at, std::string::npos) << txt;
        ASSERT_EQ(std::sscanf(t.c_str() + at, "resolution: %dx%d spp: %d", &w, &h, &spp), 3) << txt;
        EXPECT_EQ(w, s.refWidth);
        EXPECT_EQ(h, s.refHeight);
        EXPECT_EQ(spp, s.refSpp);
        EXPECT_NE(t.find("integrator: \"" + s.refIntegrator + "\""), std::string::npos) << t;
        // "scene variant: shared/scenes/FOLDER/ref-NAME.pbrt": the scene's folder, and the file is here.
        std::smatch m;
        ASSERT_TRUE(std::regex_search(t, m, std::regex("scene variant: *shared/(scenes/[^/ ]+)/(ref-[^ ]+\\.pbrt)"))) << t;
        EXPECT_EQ(m[1].str(), fs::path(s.scene).parent_path().string());
        EXPECT_TRUE(fs::is_regular_file(SharedPath(m[1].str() + "/" + m[2].str()))) << m[2].str();
    }
    // Every reference in data/refs is listed.
    int exrs = 0;
    for (const auto &e : fs::directory_iterator(SharedPath("refs"))) {
        if (e.path().extension() != ".exr") continue;
        ++exrs;
        EXPECT_TRUE(listedRefs.count("refs/" + e.path().filename().string())) << e.path() << " is not in SharedScenes()";
    }
    EXPECT_EQ(exrs, 9);
}

TEST(Data, SceneFoldersKeepReadmeAndLicence) {
    int folders = 0;
    for (const auto &e : fs::directory_iterator(SharedPath("scenes"))) {
        if (!e.is_directory()) continue;
        ++folders;
        SCOPED_TRACE(e.path().filename().string());
        std::string readme = ReadText(e.path() / "README.md");
        EXPECT_NE(readme.find("icense"), std::string::npos) << "README.md names no licence";
        // Every folder but pbrt-v3-caustic-glass (licence not verified, see its README) has the text.
        if (e.path().filename() != "pbrt-v3-caustic-glass") {
            EXPECT_TRUE(fs::exists(e.path() / "LICENSE.txt"));
        }
    }
    EXPECT_EQ(folders, 7);
}

// Text files of the source tree, without .git, data/, build trees (a CMakeCache.txt) and hidden
// folders; relative paths.
std::vector<fs::path> SourceFiles() {
    fs::path root = SourcePath("");
    std::vector<fs::path> out;
    const std::set<std::string> exts = {".cpp", ".h", ".cu", ".cuh", ".txt", ".md", ".py", ".sh", ".cmake", ".pbrt", ""};
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
        const fs::path &p = it->path();
        std::string name = p.filename().string();
        if (it->is_directory()) {
            if ((name.size() > 1 && name[0] == '.') || (it.depth() == 0 && name == "data") ||
                fs::exists(p / "CMakeCache.txt"))
                it.disable_recursion_pending();
            continue;
        }
        if (it->is_regular_file() && exts.count(p.extension().string()) && it->file_size() < 4000000 && name[0] != '.')
            out.push_back(p.lexically_relative(root));
    }
    return out;
}

// Files outside this work's reach that still cite the old shared folder in comments (METHOD.md,
// its README): to be fixed by their owners, then removed from here (the test fails while an entry
// is no longer needed).
const std::set<std::string> kSharedCitationsToFix = {};

TEST(Data, NoPathOutsideTheRepository) {
    const std::string shared = std::string("..") + "/shared";   // spelled so that this file passes
    const std::string sharedDir = std::string("LUCERNA_") + "SHARED_DIR";
    const std::string systemPython = std::string("/usr/bin/") + "python3";
    // This machine's absolute paths: the source tree's, and the old shared folder's beside it.
    fs::path root = fs::weakly_canonical(SourcePath(""));
    std::string rootStr = root.string();
    while (!rootStr.empty() && rootStr.back() == '/') rootStr.pop_back();
    std::string sharedAbs = (fs::path(rootStr).parent_path() / "shared").string();
    int checked = 0;
    for (const fs::path &rel : SourceFiles()) {
        std::string top = rel.begin()->string();
        std::string text = ReadText(SourcePath(rel.string()));
        ++checked;
        bool mine = top == "tests" || top == "bench" || top == "scripts" || top == "apps" || top == "fuzz" ||
                    top == "src" || top == "docs" || rel.filename() == "CMakeLists.txt";
        if (mine) {
            bool cites = text.find(shared) != std::string::npos;
            if (kSharedCitationsToFix.count(rel.string()))
                EXPECT_TRUE(cites) << rel << " no longer names " << shared << ": remove it from kSharedCitationsToFix";
            else
                EXPECT_FALSE(cites) << rel << " names " << shared;
            // The old CMake variable (LUCERNA_SHARED_DIRS, the shared-header folders, is another).
            for (size_t at = text.find(sharedDir); at != std::string::npos; at = text.find(sharedDir, at + 1))
                EXPECT_EQ(text.substr(at + sharedDir.size(), 1), "S") << rel << " names " << sharedDir;
            EXPECT_EQ(text.find(systemPython), std::string::npos) << rel << ": python3 is found on PATH";
        }
        EXPECT_EQ(text.find(rootStr + "/"), std::string::npos) << rel << " names this machine's " << rootStr;
        EXPECT_EQ(text.find(sharedAbs), std::string::npos) << rel << " names " << sharedAbs;
    }
    EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace lu::test

namespace lu::test {

// bench/convergence renders each reference from the original its provenance note names: the
// medium variant of volumetric-caustic from scene-v4.pbrt (with the medium), the plain one from
// scene-v4-nomedium.pbrt (it once took the medium-less file for both).
TEST(Data, ConvergenceBenchRendersTheSceneEachReferenceNames) {
    ProcessResult r = RunProcess({"bash", std::string(LUCERNA_SOURCE_DIR) + "/bench/convergence", "--dry-run",
                                  "--scenes", "volumetric-caustic,volumetric-caustic-medium", "--out", TempDir("conv_dry")});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::istringstream lines(r.output);
    std::string line;
    int seen = 0;
    while (std::getline(lines, line)) {
        if (line.find("converge ") == std::string::npos) continue;
        bool medium = line.find("refs/volumetric-caustic-medium.exr") != std::string::npos;
        std::string want = medium ? "bitterli-volumetric-caustic/scene-v4.pbrt " : "bitterli-volumetric-caustic/scene-v4-nomedium.pbrt ";
        EXPECT_NE(line.find(want), std::string::npos) << line;
        ++seen;
    }
    EXPECT_EQ(seen, 2) << r.output;
}

}  // namespace lu::test
