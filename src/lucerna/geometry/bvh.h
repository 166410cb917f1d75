// Lucerna: the GPU-friendly binary BVH as plain data (built on the host by accel/bvh_build.h,
// traversed by geometry/bvh_traverse.h); one level, or two with object instances.
// Node layout after Aila & Laine 2009 ("Understanding the efficiency of ray traversal on GPUs"):
// each node stores both children's boxes so one 64-byte fetch decides the traversal order.
#pragma once

#include "lucerna/core/scene_data.h"

namespace lu {

// An inner node with two children. A child is either another node (index >= 0 into the node
// array) or a leaf (index < 0): prim refs ~child .. ~child + count - 1. The root is node 0.
// Boxes are interleaved for three 16-byte loads: xy0 = child 0 (lo.x, hi.x, lo.y, hi.y),
// xy1 = child 1 (same), z01 = (lo.z 0, hi.z 0, lo.z 1, hi.z 1).
struct alignas(64) BVHNode {
    Float xy0[4] = {0, 0, 0, 0};
    Float xy1[4] = {0, 0, 0, 0};
    Float z01[4] = {0, 0, 0, 0};
    int32_t child[2] = {0, 0};
    uint32_t count[2] = {0, 0};   // leaf children: number of prim refs (0 = empty slot)

    LU_HD bool IsLeaf(int i) const { return child[i] < 0; }
    LU_HD uint32_t FirstPrim(int i) const { return uint32_t(~child[i]); }
    LU_HD Bounds3f ChildBounds(int i) const {
        const Float *xy = i == 0 ? xy0 : xy1;
        Bounds3f b;
        b.pMin = Vec3f(xy[0], xy[2], z01[2 * i]);
        b.pMax = Vec3f(xy[1], xy[3], z01[2 * i + 1]);
        return b;
    }
    LU_HD void SetChildBounds(int i, const Bounds3f &b) {
        Float *xy = i == 0 ? xy0 : xy1;
        xy[0] = b.pMin.x; xy[1] = b.pMax.x; xy[2] = b.pMin.y; xy[3] = b.pMax.y;
        z01[2 * i] = b.pMin.z; z01[2 * i + 1] = b.pMax.z;
    }
};
static_assert(sizeof(BVHNode) == 64, "BVHNode must stay 64 bytes");

// One primitive reference in a leaf: the geometry id and primitive, plus a copy of the
// triangle's render-space vertices so a leaf test needs no index indirection (three 16-byte
// loads on the GPU). Spheres, disks and cylinders leave p0..p2 zero and are read from SceneView.
// With spatial splits a primitive may be referenced from several leaves.
struct alignas(16) PrimRef {
    Vec3f p0;
    uint32_t shape = 0;       // geometry id: index into SceneView::shapes
    Vec3f p1;
    uint32_t primitive = 0;   // triangle index within its mesh; 0 for analytic shapes
    Vec3f p2;
    uint32_t kind = 0;        // ShapeKind of the shape (saves a Shape fetch for triangles)
};
static_assert(sizeof(PrimRef) == 48, "PrimRef must stay 48 bytes");

// PrimRef::kind of an object instance in the top-level tree: `shape` is the index into
// SceneView::instances; its prototype's tree (object space) starts at BVHView::prototypeRoots.
// Outside ShapeKind's range (a uint8_t).
constexpr uint32_t PrimRefInstance = 0x100;

// The BVH as spans (host or device memory). An empty `nodes` span means an empty scene.
// Two levels with object instances: node 0 is the root of the top-level tree (render-space
// shapes and instances), prototypeRoots[p] the root of prototype p's tree (-1: empty).
struct BVHView {
    Span<BVHNode> nodes;
    Span<PrimRef> prims;
    Span<int32_t> prototypeRoots;
};

// Maximum tree depth the builder produces; the traversal stacks are sized from it.
constexpr int BVHMaxDepth = 60;

}  // namespace lu
