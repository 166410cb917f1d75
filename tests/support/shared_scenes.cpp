// Lucerna test support: the list of shared scenes (support/shared_scenes.h).
#include "support/shared_scenes.h"

#include <cctype>

namespace lu::test {

const std::vector<SharedScene> &SharedScenes() {
    static const std::vector<SharedScene> scenes = {
        {"cornell-box", "scenes/bitterli-cornell-box/scene-v4.pbrt", "refs/cornell-box.exr", "path", 128, 128, 8192},
        {"veach-mis", "scenes/bitterli-veach-mis/scene-v4.pbrt", "refs/veach-mis.exr", "path", 192, 108, 8192},
        {"veach-bidir", "scenes/bitterli-veach-bidir/scene-v4.pbrt", "refs/veach-bidir.exr", "bdpt", 128, 128, 2048},
        {"volumetric-caustic", "scenes/bitterli-volumetric-caustic/scene-v4-nomedium.pbrt", "refs/volumetric-caustic.exr",
         "bdpt", 128, 128, 2048},
        {"water-caustic", "scenes/bitterli-water-caustic/scene-v4.pbrt", "refs/water-caustic.exr", "sppm", 128, 128, 4096},
        {"caustic-glass", "scenes/pbrt-v3-caustic-glass/scene-v4.pbrt", "refs/caustic-glass.exr", "sppm", 84, 120, 4096},
        {"bs_c", "scenes/smallvcm-cornell/smallvcm-bs_c.pbrt", "refs/bs_c.exr", "bdpt", 128, 128, 2048},
        {"bs_p", "scenes/smallvcm-cornell/smallvcm-bs_p.pbrt", "refs/bs_p.exr", "sppm", 128, 128, 4096},
        // With participating media.
        {"volumetric-caustic-medium", "scenes/bitterli-volumetric-caustic/scene-v4.pbrt",
         "refs/volumetric-caustic-medium.exr", "bdpt", 96, 96, 1024},
        {"scene-v4.gonsolo", "scenes/bitterli-volumetric-caustic/scene-v4.gonsolo.pbrt", "", "", 0, 0, 0},
    };
    return scenes;
}

std::vector<SharedScene> RenderedSharedScenes() {
    std::vector<SharedScene> out;
    for (const SharedScene &s : SharedScenes())
        if (s.renders) out.push_back(s);
    return out;
}

const SharedScene *FindSharedScene(const std::string &name) {
    for (const SharedScene &s : SharedScenes())
        if (s.name == name) return &s;
    return nullptr;
}

void PrintTo(const SharedScene &s, std::ostream *os) { *os << s.name << " (" << s.scene << ")"; }

std::string SharedSceneTestName(const SharedScene &s) {
    std::string n;
    for (char c : s.name) n += (std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
    return n;
}

}  // namespace lu::test
