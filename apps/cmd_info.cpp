// Lucerna CLI: `lucerna info SCENE` — load a pbrt-v4 scene and report what Lucerna reads from it
// (resolution, camera, counts by type, bounds, warnings, unsupported features). Exit 2 on bad input.
#include <cstdio>
#include <memory>
#include <string>

#include "apps/commands.h"
#include "apps/interrupt.h"
#include "lucerna/scene/builder.h"

namespace lu::app {

namespace {

struct InfoArgs {
    std::string scene;
};

int RunInfo(const InfoArgs &a) {
    InstallSignalHandlers();
    SetExitStage("reading the scene");
    Diagnostics diag;
    diag.quiet = true;  // warnings are part of the report
    std::unique_ptr<HostScene> scene;
    try {
        scene = LoadScene(a.scene, diag, BuildOptions{});
    } catch (const SceneError &e) {
        for (const std::string &w : diag.warnings) std::fprintf(stderr, "%s\n", w.c_str());
        std::fprintf(stderr, "%s\n", e.Format().c_str());
        return ExitBadInput;
    }
    std::printf("scene: %s\n%s", a.scene.c_str(), SceneSummary(*scene, diag).c_str());
    return ExitOk;
}

}  // namespace

void RegisterInfo(CLI::App &app, CommandTable &table) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App *sub = app.add_subcommand("info", "Report what Lucerna reads from a pbrt-v4 scene file");
    sub->add_option("scene", args->scene, "pbrt-v4 scene file")->required();
    table.Add(sub, [args] { return RunInfo(*args); });
}

}  // namespace lu::app
