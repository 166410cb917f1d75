// Lucerna scene reader: PLY triangle/quad meshes for pbrt-v4's "plymesh" shape (host only).
// Reads ASCII and binary (little/big endian) PLY with every read bounds-checked; the vertex and
// face properties pbrt-v4 reads (util/mesh.cpp) are used, others are skipped.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "lucerna/scene/error.h"
#include "lucerna/util/vecmath.h"

namespace lu {

struct PlyMesh {
    std::vector<Vec3f> P;          // positions (object space)
    std::vector<Vec3f> N;          // per-vertex normals (nx ny nz), empty if absent
    std::vector<Vec2f> uv;         // per-vertex (u v | s t | texture_u texture_v | texture_s texture_t), empty if absent
    std::vector<uint32_t> indices; // triangles: quads split (v0 v1 v2)(v0 v2 v3), larger polygons fanned
    std::vector<int> faceIndices;  // per-triangle "face_indices" when present (else empty)
    size_t quadCount = 0;          // faces that were quads (split into two triangles)
    size_t polygonCount = 0;       // faces with more than 4 vertices (fanned, with a warning)
};

// Reads a PLY file, gzip-compressed or not (told by its first bytes, whatever its name). Errors
// (missing, truncated, corrupt header or gzip data, counts exceeding the file size, indices out of
// range, NaN/Inf values) throw SceneError at referencedFrom with a message that names the file:
// "PLY file \"PATH\": ...". Warnings (skipped or fanned faces) go to diag if given.
PlyMesh ReadPlyMesh(const std::string &path, const FileLoc &referencedFrom, Diagnostics *diag = nullptr);

// The same for a PLY file already in memory (not compressed); `name` is used in messages.
PlyMesh ReadPlyMeshFromMemory(std::string_view data, const std::string &name, const FileLoc &referencedFrom,
                              Diagnostics *diag = nullptr);

// Upper bound on a PLY file read from disk (compressed and decompressed).
constexpr size_t MaxPlyFileBytes = size_t(1) << 32;

}  // namespace lu
