// libFuzzer target: the PLY reader must never crash or read out of bounds; bad input may only
// throw SceneError, and a returned mesh must be consistent.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "lucerna/scene/ply.h"

using namespace lu;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    Diagnostics diag;
    diag.quiet = true;
    FileLoc from{std::make_shared<const std::string>("fuzz.pbrt"), 1, 1};
    try {
        PlyMesh m = ReadPlyMeshFromMemory(std::string_view(reinterpret_cast<const char *>(data), size), "fuzz.ply",
                                          from, &diag);
        if (m.indices.size() % 3 != 0) std::abort();
        for (uint32_t i : m.indices)
            if (i >= m.P.size()) std::abort();
        if (!m.N.empty() && m.N.size() != m.P.size()) std::abort();
        if (!m.uv.empty() && m.uv.size() != m.P.size()) std::abort();
        if (!m.faceIndices.empty() && m.faceIndices.size() * 3 != m.indices.size()) std::abort();
        for (const Vec3f &p : m.P)
            if (!IsFinite(p)) std::abort();
    } catch (const SceneError &e) {
        (void)e.Format();
    }
    return 0;
}
