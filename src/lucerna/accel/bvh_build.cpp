// Lucerna: host BVH construction with Embree 3's generic builder (rtcBuildBVH, high quality =
// binned SAH with spatial splits, Stich et al. 2009), flattened into the GPU node layout of bvh.h;
// with object instances two levels: the top tree (node 0) then one tree per prototype.
#include "lucerna/accel/bvh_build.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <stdexcept>
#include <string>

#include "lucerna/geometry/shapes.h"

namespace lu {

namespace {

// ---- Primitive bounds ----

Bounds3f PadBounds(Bounds3f b) {
    Float mag = Max(MaxComponent(Abs(b.pMin)), MaxComponent(Abs(b.pMax)));
    Float pad = 1e-5f * mag + 1e-30f;
    b.pMin = b.pMin - Vec3f(pad, pad, pad);
    b.pMax = b.pMax + Vec3f(pad, pad, pad);
    return b;
}

bool IsAffine(const Transform &t) {
    return t.m.m[3][0] == 0 && t.m.m[3][1] == 0 && t.m.m[3][2] == 0 && t.m.m[3][3] == 1;
}

// Bounds of the 8 corners of an object-space box under a transform.
Bounds3f TransformedBox(const Transform &t, const Vec3f &lo, const Vec3f &hi) {
    Bounds3f b;
    for (int c = 0; c < 8; ++c)
        b.Expand(t.ApplyPoint(Vec3f(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z)));
    return b;
}

// Exact bounds of an ellipse/ellipsoid: an affine map M of the unit ball has half extent
// |row i of M| along axis i. `cols` says which columns of M span the shape (3 = ball, 2 = disk).
Bounds3f AffineRoundBounds(const Transform &t, const Vec3f &center, Float radius, int cols) {
    Vec3f c = t.ApplyPoint(center);
    Bounds3f b;
    for (int i = 0; i < 3; ++i) {
        double s = 0;
        for (int j = 0; j < cols; ++j) s += double(t.m.m[i][j]) * t.m.m[i][j];
        Float h = Float(double(radius) * std::sqrt(s));
        b.pMin[i] = c[i] - h;
        b.pMax[i] = c[i] + h;
    }
    return b;
}

// ---- Build state shared by the Embree callbacks ----

struct BuildContext {
    const std::vector<PrimRef> *refs = nullptr;
};

struct TmpNode {
    bool leaf;
};
struct TmpInner : TmpNode {
    TmpNode *child[2];
    Bounds3f box[2];
};
struct TmpLeaf : TmpNode {
    uint32_t count;
    uint32_t refs[1];   // `count` entries (allocated with room for all of them)
};

void *CreateNode(RTCThreadLocalAllocator alloc, unsigned int /*childCount*/, void *) {
    void *mem = rtcThreadLocalAlloc(alloc, sizeof(TmpInner), 16);
    TmpInner *n = new (mem) TmpInner;
    n->leaf = false;
    n->child[0] = n->child[1] = nullptr;
    return n;
}

void SetNodeChildren(void *nodePtr, void **children, unsigned int childCount, void *) {
    TmpInner *n = static_cast<TmpInner *>(nodePtr);
    for (unsigned i = 0; i < childCount && i < 2; ++i) n->child[i] = static_cast<TmpNode *>(children[i]);
}

void SetNodeBounds(void *nodePtr, const RTCBounds **bounds, unsigned int childCount, void *) {
    TmpInner *n = static_cast<TmpInner *>(nodePtr);
    for (unsigned i = 0; i < childCount && i < 2; ++i) {
        n->box[i].pMin = Vec3f(bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z);
        n->box[i].pMax = Vec3f(bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z);
    }
}

void *CreateLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive *prims, size_t count, void *) {
    size_t bytes = sizeof(TmpLeaf) + sizeof(uint32_t) * (count > 0 ? count - 1 : 0);
    void *mem = rtcThreadLocalAlloc(alloc, bytes, 16);
    TmpLeaf *leaf = new (mem) TmpLeaf;
    leaf->leaf = true;
    uint32_t n = 0;
    for (size_t i = 0; i < count; ++i) {
        // Pieces of one spatially split primitive can land in the same leaf: keep one.
        bool dup = false;
        for (uint32_t k = 0; k < n; ++k) dup |= leaf->refs[k] == prims[i].primID;
        if (!dup) leaf->refs[n++] = prims[i].primID;
    }
    leaf->count = n;
    return leaf;
}

// Spatial split: clips the primitive (within its current, possibly already clipped bounds) at
// `pos` along `dim`. Triangles are clipped exactly up to a conservative padding of the edge
// crossings; analytic shapes split their box.
void SplitPrimitive(const RTCBuildPrimitive *prim, unsigned int dim, float pos, RTCBounds *lOut, RTCBounds *rOut,
                    void *userPtr) {
    const BuildContext *ctx = static_cast<const BuildContext *>(userPtr);
    const PrimRef &ref = (*ctx->refs)[prim->primID];
    const float lo[3] = {prim->lower_x, prim->lower_y, prim->lower_z};
    const float hi[3] = {prim->upper_x, prim->upper_y, prim->upper_z};
    float lLo[3], lHi[3], rLo[3], rHi[3];
    if (ShapeKind(ref.kind) == ShapeKind::Triangles) {
        for (int i = 0; i < 3; ++i) {
            lLo[i] = rLo[i] = INFINITY;
            lHi[i] = rHi[i] = -INFINITY;
        }
        const float v[3][3] = {{ref.p0.x, ref.p0.y, ref.p0.z}, {ref.p1.x, ref.p1.y, ref.p1.z},
                               {ref.p2.x, ref.p2.y, ref.p2.z}};
        for (int e = 0; e < 3; ++e) {
            const float *a = v[e], *b = v[e == 2 ? 0 : e + 1];
            float da = a[dim] - pos, db = b[dim] - pos;
            if (a[dim] <= pos)
                for (int i = 0; i < 3; ++i) { lLo[i] = std::min(lLo[i], a[i]); lHi[i] = std::max(lHi[i], a[i]); }
            if (a[dim] >= pos)
                for (int i = 0; i < 3; ++i) { rLo[i] = std::min(rLo[i], a[i]); rHi[i] = std::max(rHi[i], a[i]); }
            if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
                float t = da / (da - db);
                for (int i = 0; i < 3; ++i) {
                    float c = i == int(dim) ? pos : a[i] + t * (b[i] - a[i]);
                    // Rounding of t and of the lerp stays well below 16 ulp of |a| + |b|.
                    float err = i == int(dim) ? 0.f : (std::abs(a[i]) + std::abs(b[i])) * 0x1p-20f;
                    lLo[i] = std::min(lLo[i], c - err); lHi[i] = std::max(lHi[i], c + err);
                    rLo[i] = std::min(rLo[i], c - err); rHi[i] = std::max(rHi[i], c + err);
                }
            }
        }
        for (int i = 0; i < 3; ++i) {   // stay within the current bounds
            lLo[i] = std::max(lLo[i], lo[i]); lHi[i] = std::min(lHi[i], hi[i]);
            rLo[i] = std::max(rLo[i], lo[i]); rHi[i] = std::min(rHi[i], hi[i]);
        }
    } else {
        for (int i = 0; i < 3; ++i) {
            lLo[i] = rLo[i] = lo[i];
            lHi[i] = rHi[i] = hi[i];
        }
    }
    lHi[dim] = std::min(lHi[dim], pos);
    rLo[dim] = std::max(rLo[dim], pos);
    // An empty side (the plane misses the clipped piece) becomes a flat face on the plane.
    auto fixEmpty = [&](float *bLo, float *bHi) {
        if (bLo[0] <= bHi[0] && bLo[1] <= bHi[1] && bLo[2] <= bHi[2]) return;
        for (int i = 0; i < 3; ++i) {
            bLo[i] = i == int(dim) ? pos : lo[i];
            bHi[i] = i == int(dim) ? pos : hi[i];
        }
    };
    fixEmpty(lLo, lHi);
    fixEmpty(rLo, rHi);
    *lOut = RTCBounds{lLo[0], lLo[1], lLo[2], 0, lHi[0], lHi[1], lHi[2], 0};
    *rOut = RTCBounds{rLo[0], rLo[1], rLo[2], 0, rHi[0], rHi[1], rHi[2], 0};
}

// ---- Flattening into the GPU layout ----

struct Flattener {
    const std::vector<PrimRef> &refs;
    GpuBVH &out;

    // Emits a child and returns its encoding (node index, or ~first prim with *count).
    int32_t EmitChild(const TmpNode *n, uint32_t *count) {
        if (n->leaf) {
            const TmpLeaf *l = static_cast<const TmpLeaf *>(n);
            uint32_t first = uint32_t(out.prims.size());
            for (uint32_t i = 0; i < l->count; ++i) out.prims.push_back(refs[l->refs[i]]);
            *count = l->count;
            return ~int32_t(first);
        }
        *count = 0;
        return EmitInner(static_cast<const TmpInner *>(n));
    }
    int32_t EmitInner(const TmpInner *n) {
        int32_t idx = int32_t(out.nodes.size());
        out.nodes.emplace_back();
        BVHNode node;
        for (int i = 0; i < 2; ++i) {
            node.child[i] = EmitChild(n->child[i], &node.count[i]);
            node.SetChildBounds(i, n->box[i]);
        }
        out.nodes[idx] = node;
        return idx;
    }
};

void StatsRecurse(const GpuBVH &bvh, int32_t node, uint32_t depth, BVHStats *s, double *area) {
    const BVHNode &n = bvh.nodes[node];
    s->innerNodes++;
    for (int i = 0; i < 2; ++i) {
        Bounds3f b = n.ChildBounds(i);
        Vec3f d = b.Diagonal();
        double a = b.Empty() ? 0.0 : 2.0 * (double(d.x) * d.y + double(d.y) * d.z + double(d.z) * d.x);
        if (n.IsLeaf(i)) {
            if (n.count[i] == 0) continue;
            s->leaves++;
            s->references += n.count[i];
            s->maxLeafSize = std::max(s->maxLeafSize, n.count[i]);
            s->maxDepth = std::max(s->maxDepth, depth + 1);
            area[1] += a * n.count[i];
        } else {
            area[0] += a;
            StatsRecurse(bvh, n.child[i], depth + 1, s, area);
        }
    }
}

}  // namespace

Bounds3f PrimitiveBounds(const SceneView &scene, uint32_t shapeId, uint32_t primitive) {
    const Shape &shape = scene.shapes[shapeId];
    Bounds3f b;
    switch (shape.kind) {
    case ShapeKind::Triangles: {
        const TriangleMesh &m = scene.triangleMeshes[shape.index];
        uint32_t v[3];
        TriangleVertices(scene, m, primitive, v);
        for (int k = 0; k < 3; ++k) b.Expand(scene.positions[v[k]]);
        return b;
    }
    case ShapeKind::Sphere: {
        const Sphere &s = scene.spheres[shape.index];
        Float r = s.radius;
        b = IsAffine(s.renderFromObject) ? AffineRoundBounds(s.renderFromObject, Vec3f(0, 0, 0), r, 3)
                                         : TransformedBox(s.renderFromObject, Vec3f(-r, -r, -r), Vec3f(r, r, r));
        return PadBounds(b);
    }
    case ShapeKind::Disk: {
        const Disk &d = scene.disks[shape.index];
        Float r = d.radius;
        b = IsAffine(d.renderFromObject)
                ? AffineRoundBounds(d.renderFromObject, Vec3f(0, 0, d.height), r, 2)
                : TransformedBox(d.renderFromObject, Vec3f(-r, -r, d.height), Vec3f(r, r, d.height));
        return PadBounds(b);
    }
    case ShapeKind::Cylinder: {   // the whole tube's box, also for a partial one
        const Cylinder &c = scene.cylinders[shape.index];
        Float r = c.radius;
        return PadBounds(TransformedBox(c.renderFromObject, Vec3f(-r, -r, c.zMin), Vec3f(r, r, c.zMax)));
    }
    case ShapeKind::BilinearPatches:
    case ShapeKind::Curves: return PadBounds(PatchOrCurveBounds(scene, shape, primitive));
    }
    return b;
}

BVHStats ComputeBVHStats(const GpuBVH &bvh) {
    BVHStats s = bvh.stats;
    s.innerNodes = s.leaves = s.references = s.maxDepth = s.maxLeafSize = 0;
    s.sahCost = 0;
    if (bvh.nodes.empty()) return s;
    double area[2] = {0, 0};   // inner, leaf * count
    StatsRecurse(bvh, 0, 0, &s, area);
    Bounds3f root = bvh.nodes[0].ChildBounds(0);
    root.Expand(bvh.nodes[0].ChildBounds(1));
    Vec3f d = root.Diagonal();
    double rootArea = 2.0 * (double(d.x) * d.y + double(d.y) * d.z + double(d.z) * d.x);
    s.sahCost = rootArea > 0 ? (rootArea + area[0] + area[1]) / rootArea : double(s.references);
    return s;
}

namespace {

// Primitive references of shapes [first, end): triangles with their vertices, analytic shapes.
void AddShapeRefs(const SceneView &scene, uint32_t first, uint32_t end, std::vector<PrimRef> *refs,
                  std::vector<Bounds3f> *boxes) {
    for (uint32_t s = first; s < end; ++s) {
        const Shape &shape = scene.shapes[s];
        if (shape.kind == ShapeKind::Triangles) {
            const TriangleMesh &m = scene.triangleMeshes[shape.index];
            for (uint32_t t = 0; t < m.triangleCount; ++t) {
                uint32_t v[3];
                TriangleVertices(scene, m, t, v);
                PrimRef r;
                r.shape = s;
                r.primitive = t;
                r.kind = uint32_t(ShapeKind::Triangles);
                r.p0 = scene.positions[v[0]];
                r.p1 = scene.positions[v[1]];
                r.p2 = scene.positions[v[2]];
                if (!IsFinite(r.p0) || !IsFinite(r.p1) || !IsFinite(r.p2)) continue;
                Bounds3f b;
                b.Expand(r.p0); b.Expand(r.p1); b.Expand(r.p2);
                refs->push_back(r);
                boxes->push_back(b);
            }
        } else {
            // Quadrics (one primitive), patches and curve pieces.
            uint32_t count = IsQuadric(shape.kind) ? 1 : shape.primitiveCount;
            for (uint32_t prim = 0; prim < count; ++prim) {
                PrimRef r;
                r.shape = s;
                r.primitive = prim;
                r.kind = uint32_t(shape.kind);
                Bounds3f b = PrimitiveBounds(scene, s, prim);
                if (!IsFinite(b.pMin) || !IsFinite(b.pMax)) continue;
                refs->push_back(r);
                boxes->push_back(b);
            }
        }
    }
}

// Builds one tree over refs and appends it to bvh (nodes and prims); returns its root node, or
// -1 for no primitives. The first tree appended is the top level (node 0).
int32_t BuildTree(const std::vector<PrimRef> &refs, const std::vector<Bounds3f> &boxes,
                  const BVHBuildOptions &options, GpuBVH &bvh) {
    if (refs.empty()) return -1;
    Bounds3f all;
    for (const Bounds3f &b : boxes) all.Expand(b);
    size_t capacity = options.spatialSplits ? 2 * refs.size() : refs.size();
    std::vector<RTCBuildPrimitive> prims(capacity);
    for (size_t i = 0; i < refs.size(); ++i) {
        RTCBuildPrimitive &p = prims[i];
        p.lower_x = boxes[i].pMin.x; p.lower_y = boxes[i].pMin.y; p.lower_z = boxes[i].pMin.z;
        p.upper_x = boxes[i].pMax.x; p.upper_y = boxes[i].pMax.y; p.upper_z = boxes[i].pMax.z;
        p.geomID = 0;
        p.primID = unsigned(i);
    }
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("BuildBVH: cannot create an Embree device");
    RTCBVH ebvh = rtcNewBVH(device);
    BuildContext ctx;
    ctx.refs = &refs;

    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.byteSize = sizeof(args);
    args.buildQuality = RTC_BUILD_QUALITY_HIGH;
    args.buildFlags = RTC_BUILD_FLAG_NONE;
    args.maxBranchingFactor = 2;
    args.maxDepth = BVHMaxDepth;
    args.sahBlockSize = 1;
    args.minLeafSize = 1;
    args.maxLeafSize = std::max(1u, std::min(options.maxLeafSize, unsigned(RTC_BUILD_MAX_PRIMITIVES_PER_LEAF)));
    args.traversalCost = options.traversalCost;
    args.intersectionCost = options.intersectionCost;
    args.bvh = ebvh;
    args.primitives = prims.data();
    args.primitiveCount = refs.size();
    args.primitiveArrayCapacity = capacity;
    args.createNode = CreateNode;
    args.setNodeChildren = SetNodeChildren;
    args.setNodeBounds = SetNodeBounds;
    args.createLeaf = CreateLeaf;
    args.splitPrimitive = options.spatialSplits ? SplitPrimitive : nullptr;
    args.buildProgress = nullptr;
    args.userPtr = &ctx;

    TmpNode *root = static_cast<TmpNode *>(rtcBuildBVH(&args));
    RTCError err = rtcGetDeviceError(device);
    if (!root || err != RTC_ERROR_NONE) {
        rtcReleaseBVH(ebvh);
        rtcReleaseDevice(device);
        throw std::runtime_error("BuildBVH: rtcBuildBVH failed (Embree error " + std::to_string(int(err)) + ")");
    }

    // ---- Flatten ----
    Flattener flat{refs, bvh};
    bvh.nodes.reserve(bvh.nodes.size() + refs.size());
    bvh.prims.reserve(bvh.prims.size() + refs.size() + refs.size() / 4);
    int32_t rootIndex = int32_t(bvh.nodes.size());
    if (root->leaf) {
        // A single leaf: wrap it in a root whose second child is an empty leaf.
        BVHNode node;
        node.child[0] = flat.EmitChild(root, &node.count[0]);
        node.SetChildBounds(0, all);
        node.child[1] = ~int32_t(0);
        node.count[1] = 0;
        Bounds3f empty;
        empty.pMin = empty.pMax = all.pMin;
        node.SetChildBounds(1, empty);
        bvh.nodes.push_back(node);
    } else {
        flat.EmitInner(static_cast<const TmpInner *>(root));
    }
    rtcReleaseBVH(ebvh);
    rtcReleaseDevice(device);
    return rootIndex;
}

}  // namespace

Bounds3f InstanceBounds(const SceneView &scene, uint32_t instance) {
    const Instance &in = scene.instances[instance];
    const Bounds3f &ob = scene.prototypes[in.prototype].bounds;
    Bounds3f b;
    for (int c = 0; c < 8; ++c)
        b.Expand(InstancePoint(in.renderFromInstance,
                               Vec3f(c & 1 ? ob.pMax.x : ob.pMin.x, c & 2 ? ob.pMax.y : ob.pMin.y, c & 4 ? ob.pMax.z : ob.pMin.z)));
    return PadBounds(b);
}

GpuBVH BuildBVH(const SceneView &scene, const BVHBuildOptions &options) {
    auto start = std::chrono::steady_clock::now();
    GpuBVH bvh;

    // ---- Top level: render-space shapes and one reference per instance ----
    std::vector<PrimRef> refs;
    std::vector<Bounds3f> boxes;
    AddShapeRefs(scene, 0, TopLevelShapeCount(scene), &refs, &boxes);
    for (uint32_t i = 0; i < scene.instances.size; ++i) {
        PrimRef r;
        r.shape = i;
        r.primitive = 0;
        r.kind = PrimRefInstance;
        Bounds3f b = InstanceBounds(scene, i);
        if (!IsFinite(b.pMin) || !IsFinite(b.pMax)) continue;
        refs.push_back(r);
        boxes.push_back(b);
    }
    bvh.stats.primitives = uint32_t(refs.size());
    for (const Bounds3f &b : boxes) bvh.bounds.Expand(b);
    // With instances the top tree is built without spatial splits: splitting instance boxes buys
    // little and doubles the builder's arrays (3.2 M instances: 1.34 GB peak and 84 s with
    // splits; docs/benchmarks.md). Scenes without instances build as before.
    BVHBuildOptions topOptions = options;
    if (scene.instances.size > 0) topOptions.spatialSplits = false;
    BuildTree(refs, boxes, topOptions, bvh);

    // ---- Bottom levels: one tree per prototype (object space) ----
    for (uint32_t p = 0; p < scene.prototypes.size; ++p) {
        const Prototype &proto = scene.prototypes[p];
        refs.clear();
        boxes.clear();
        AddShapeRefs(scene, proto.firstShape, proto.firstShape + proto.shapeCount, &refs, &boxes);
        bvh.stats.primitives += uint32_t(refs.size());
        bvh.prototypeRoots.push_back(bvh.nodes.empty() ? -1 : BuildTree(refs, boxes, options, bvh));
    }

    bvh.stats.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!bvh.nodes.empty()) bvh.stats = ComputeBVHStats(bvh);
    else bvh.stats.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

}  // namespace lu
