// Lucerna test support: the one list of the shared scenes (data/scenes/README.md) with their
// pbrt-v4 references (data/refs/NAME.txt); tests/data/data_test.cpp checks it against the files.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace lu::test {

struct SharedScene {
    std::string name;           // the reference's name ("cornell-box"), else the file's stem
    std::string scene;          // under data/ (SharedPath): "scenes/bitterli-cornell-box/scene-v4.pbrt"
    std::string reference;      // under data/: "refs/cornell-box.exr"; empty when there is none
    std::string refIntegrator;  // pbrt-v4 integrator of the reference: "path", "bdpt" or "sppm"
    int refWidth = 0, refHeight = 0, refSpp = 0;  // the reference's resolution and spp (sppm: iterations)
    bool renders = true;        // false: Lucerna refuses the file and names the feature (participating media)
    bool HasReference() const { return !reference.empty(); }
    // Unbiased and converged: the reference can be compared pixel by pixel ("path" references).
    bool ExactReference() const { return refIntegrator == "path"; }
};

// Every scene file of data/scenes/README.md, those Lucerna renders first (in the README's order).
const std::vector<SharedScene> &SharedScenes();
// The scenes Lucerna renders (renders == true).
std::vector<SharedScene> RenderedSharedScenes();
// The entry with this name; nullptr if there is none.
const SharedScene *FindSharedScene(const std::string &name);

// gtest printing of a parameter, and a test-name suffix ("cornell_box").
void PrintTo(const SharedScene &s, std::ostream *os);
std::string SharedSceneTestName(const SharedScene &s);

}  // namespace lu::test
