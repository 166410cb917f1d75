// Lucerna (host): Loop subdivision surfaces, pbrt-v4's `Shape "loopsubdiv"`. The control mesh is
// refined `levels` times with Loop's rules (Loop 1987; the boundary rules of Hoppe et al. 1994,
// as pbrt-v4 uses them), its vertices are then moved to their limit positions and given the limit
// surface's normals. The result is a plain triangle mesh (no uv, as in pbrt-v4).
//
// pbrt-v4 assumes a manifold, consistently oriented control mesh and crashes (or loops) on
// others; here such a mesh is refused with the reason (LoopSubdivide returns false): an edge
// shared by more than two faces, two faces that traverse an edge in the same direction, or a
// vertex whose faces form more than one fan. Faces that repeat a vertex are dropped (counted in
// `droppedFaces`) and vertices no face uses are left out of the refinement.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lucerna/util/vecmath.h"

namespace lu {

struct LoopSubdivisionMesh {
    std::vector<Vec3f> P, N;          // limit positions and (unnormalized) limit normals
    std::vector<uint32_t> indices;    // three per triangle
    uint32_t droppedFaces = 0;        // control faces that repeat a vertex
};

// The number of triangles `levels` refinements of `faces` triangles make (4^levels each),
// saturating at UINT64_MAX.
uint64_t LoopSubdividedTriangleCount(uint64_t faces, int levels);

// Subdivides the triangle mesh (P, indices: three per face, each < P.size()) `levels` times
// (levels <= 0: no refinement, only the limit projection, as pbrt-v4). On a mesh it cannot
// subdivide, returns false with *error set.
bool LoopSubdivide(const std::vector<Vec3f> &P, const std::vector<uint32_t> &indices, int levels,
                   LoopSubdivisionMesh *out, std::string *error);

}  // namespace lu
