// libFuzzer target: the scene builder after the parser (scene/builder.cpp and build_*.cpp) must
// never crash, leak or hit undefined behavior on any parsed scene; bad input may only throw
// SceneError, and a built scene must be consistent: every index in range, every vertex, bound and
// light-selection probability finite. Include/Import are disabled; the resolution is fixed (16x16).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "lucerna/scene/builder.h"
#include "lucerna/scene/parser.h"

using namespace lu;

namespace {

void Check(bool ok) {
    if (!ok) std::abort();
}

bool Finite(const Vec3f &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void CheckScene(const HostScene &s) {
    SceneView v = s.View();
    for (uint32_t i = 0; i < v.shapes.size; ++i) {
        const Shape &sh = v.shapes[i];
        Check(sh.material == NoIndex || sh.material < v.materials.size);
        if (sh.kind == ShapeKind::Triangles) Check(sh.index < v.triangleMeshes.size);
        if (sh.kind == ShapeKind::Sphere) Check(sh.index < v.spheres.size);
        if (sh.kind == ShapeKind::Disk) Check(sh.index < v.disks.size);
        if (sh.kind == ShapeKind::Cylinder) Check(sh.index < v.cylinders.size);
        Check(sh.areaLight == NoIndex || uint64_t(sh.areaLight) + sh.primitiveCount <= v.lights.size);
    }
    for (uint32_t m = 0; m < v.triangleMeshes.size; ++m) {
        const TriangleMesh &tm = v.triangleMeshes[m];
        Check(uint64_t(tm.firstVertex) + tm.vertexCount <= v.positions.size);
        Check(uint64_t(tm.firstIndex) + 3 * uint64_t(tm.triangleCount) <= v.indices.size);
        for (uint64_t k = 0; k < 3 * uint64_t(tm.triangleCount); ++k) Check(v.indices[uint32_t(tm.firstIndex + k)] < tm.vertexCount);
        if (tm.normalOffset != NoIndex) Check(uint64_t(tm.normalOffset) + tm.vertexCount <= v.normals.size);
        if (tm.uvOffset != NoIndex) Check(uint64_t(tm.uvOffset) + tm.vertexCount <= v.uvs.size);
    }
    for (uint32_t i = 0; i < v.positions.size; ++i) Check(Finite(v.positions[i]));
    for (uint32_t i = 0; i < v.lights.size; ++i) Check(v.lights[i].shape == NoIndex || v.lights[i].shape < v.shapes.size);
    for (uint32_t i = 0; i < v.infiniteLights.size; ++i) Check(v.infiniteLights[i] < v.lights.size);
    if (!v.lights.empty()) {
        Check(v.lightCdf.size == v.lights.size + 1);
        for (uint32_t i = 0; i < v.lightCdf.size; ++i) {
            Check(std::isfinite(v.lightCdf[i]) && v.lightCdf[i] >= 0 && v.lightCdf[i] <= 1.0001f);
            if (i > 0) Check(v.lightCdf[i] >= v.lightCdf[i - 1]);
        }
    }
    Check(v.film.width == 16 && v.film.height == 16);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    std::string text(reinterpret_cast<const char *>(data), size);
    Diagnostics diag;
    diag.quiet = true;
    ParseOptions options;
    options.allowFileAccess = false;
    options.maxTotalValues = size_t(1) << 18;
    BuildOptions build;
    build.resX = build.resY = 16;
    build.maxSubdivisionTriangles = uint64_t(1) << 16;   // loopsubdiv "levels" amplify the input 4^levels times
    try {
        SceneDescription d = ParseSceneString(text, "fuzz.pbrt", diag, options);
        std::unique_ptr<HostScene> scene = BuildScene(d, diag, build);
        CheckScene(*scene);
    } catch (const SceneError &e) {
        (void)e.Format();
    }
    return 0;
}
