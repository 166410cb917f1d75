// Lucerna (host): builds the shared binary BVH of geometry/bvh.h over a SceneView with Embree's
// SAH builder (rtcBuildBVH, spatial splits), into host arrays ready to upload.
#pragma once

#include <vector>

#include "lucerna/geometry/bvh.h"

namespace lu {

// Statistics of a built BVH. SAH cost uses traversal cost 1 and intersection cost 1 per prim:
// C = (sum over inner nodes of area + sum over leaves of area * count) / root area.
struct BVHStats {
    uint32_t primitives = 0;     // input primitives
    uint32_t references = 0;     // prim refs in leaves (> primitives with spatial splits)
    uint32_t innerNodes = 0, leaves = 0, maxDepth = 0, maxLeafSize = 0;
    double sahCost = 0;
    double buildSeconds = 0;
};

// A BVH built on the host, ready to upload (one copy per array).
struct GpuBVH {
    std::vector<BVHNode> nodes;
    std::vector<PrimRef> prims;
    std::vector<int32_t> prototypeRoots;   // per SceneView::prototypes entry: its tree's root node
    Bounds3f bounds;             // of the whole scene (all primitives)
    BVHStats stats;

    BVHView View() const {
        BVHView v;
        v.nodes = Span<BVHNode>{nodes.data(), uint32_t(nodes.size())};
        v.prims = Span<PrimRef>{prims.data(), uint32_t(prims.size())};
        v.prototypeRoots = Span<int32_t>{prototypeRoots.data(), uint32_t(prototypeRoots.size())};
        return v;
    }
};

// Build options; the defaults are what every backend uses.
struct BVHBuildOptions {
    bool spatialSplits = true;   // SBVH-style splits (Embree's high-quality builder)
    uint32_t maxLeafSize = 4;
    float traversalCost = 1.0f, intersectionCost = 1.0f;
};

// Builds the BVH over every triangle, sphere and disk of `scene` (all shapes, interfaces
// included; with instances the top tree holds the render-space shapes and the instances, and each
// prototype gets a tree of its own) with Embree's SAH builder (rtcBuildBVH, RTC_BUILD_QUALITY_HIGH). Host only.
GpuBVH BuildBVH(const SceneView &scene, const BVHBuildOptions &options = {});

// Render-space bounds of one primitive (analytic shapes: exact bounds of the transformed
// sphere/disk, slightly padded for rounding). Host only.
Bounds3f PrimitiveBounds(const SceneView &scene, uint32_t shape, uint32_t primitive);

// Render-space bounds of one instance: its prototype's object-space box mapped, padded. Host only.
Bounds3f InstanceBounds(const SceneView &scene, uint32_t instance);

// Recomputes the statistics (SAH cost, depth, counts) of a built tree. Host only.
BVHStats ComputeBVHStats(const GpuBVH &bvh);

}  // namespace lu
