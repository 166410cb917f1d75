// Lucerna: stack-based BVH traversal shared by the CPU and CUDA backends (no recursion, fixed stack;
// object instances: the top tree hands the ray, mapped to object space, to the prototype's tree).
// Ordered traversal of the Aila-Laine node layout (bvh.h); robust slab test after Ize 2013,
// "Robust BVH Ray Traversal" (far distances scaled by 1 + 2 gamma(3), as pbrt-v4's Bounds3::IntersectP).
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/geometry/alpha.h"
#include "lucerna/geometry/bvh.h"
#include "lucerna/geometry/shapes.h"

namespace lu {

constexpr int BVHStackSize = BVHMaxDepth + 4;

// 1 + 2 gamma(3) with gamma(n) = n u / (1 - n u), u = 2^-24 (Ize 2013; pbrt-v4 Bounds3::IntersectP).
constexpr Float BVHFarScale = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);

// Reciprocal of a direction component; zero components become a huge finite value of the same
// sign so that slab distances stay finite (0 * huge = 0, never NaN).
LU_INLINE Float SafeRcp(Float d) {
    constexpr Float tiny = 1e-30f;
    return 1 / (std::abs(d) < tiny ? std::copysign(tiny, d) : d);
}

// Loads a node; on the device through the read-only cache in four 16-byte loads.
LU_INLINE BVHNode LoadBVHNode(const BVHNode *p) {
#if defined(__CUDA_ARCH__)
    const float4 *q = reinterpret_cast<const float4 *>(p);
    float4 a = __ldg(q), b = __ldg(q + 1), c = __ldg(q + 2);
    int4 d = __ldg(reinterpret_cast<const int4 *>(p) + 3);
    BVHNode n;
    n.xy0[0] = a.x; n.xy0[1] = a.y; n.xy0[2] = a.z; n.xy0[3] = a.w;
    n.xy1[0] = b.x; n.xy1[1] = b.y; n.xy1[2] = b.z; n.xy1[3] = b.w;
    n.z01[0] = c.x; n.z01[1] = c.y; n.z01[2] = c.z; n.z01[3] = c.w;
    n.child[0] = d.x; n.child[1] = d.y;
    n.count[0] = uint32_t(d.z); n.count[1] = uint32_t(d.w);
    return n;
#else
    return *p;
#endif
}

LU_INLINE PrimRef LoadPrimRef(const PrimRef *p) {
#if defined(__CUDA_ARCH__)
    const float4 *q = reinterpret_cast<const float4 *>(p);
    float4 a = __ldg(q), b = __ldg(q + 1), c = __ldg(q + 2);
    PrimRef r;
    r.p0 = Vec3f(a.x, a.y, a.z); r.shape = __float_as_uint(a.w);
    r.p1 = Vec3f(b.x, b.y, b.z); r.primitive = __float_as_uint(b.w);
    r.p2 = Vec3f(c.x, c.y, c.z); r.kind = __float_as_uint(c.w);
    return r;
#else
    return *p;
#endif
}

// Slab test of both children of a node against the ray segment (0, tMax). On return hit[i]
// says whether child i's box is crossed and tNear[i] where the ray enters it.
LU_INLINE void IntersectChildBoxes(const BVHNode &n, const Vec3f &o, const Vec3f &invD, Float tMax, Float tNear[2],
                                   bool hit[2]) {
    const Float *xy[2] = {n.xy0, n.xy1};
    for (int i = 0; i < 2; ++i) {
        Float tx0 = (xy[i][0] - o.x) * invD.x, tx1 = (xy[i][1] - o.x) * invD.x;
        Float ty0 = (xy[i][2] - o.y) * invD.y, ty1 = (xy[i][3] - o.y) * invD.y;
        Float tz0 = (n.z01[2 * i] - o.z) * invD.z, tz1 = (n.z01[2 * i + 1] - o.z) * invD.z;
        Float t0 = Max(Max(Min(tx0, tx1), Min(ty0, ty1)), Max(Min(tz0, tz1), Float(0)));
        Float t1 = Min(Min(Max(tx0, tx1), Max(ty0, ty1)), Max(tz0, tz1)) * BVHFarScale;
        tNear[i] = t0;
        hit[i] = t0 <= Min(t1, tMax);
    }
}

// Intersects one primitive reference in (0, tMax); b1, b2: a triangle's barycentrics, a patch's or
// curve's (u, v), zero for quadrics.
LU_INLINE bool IntersectPrimRef(const PrimRef &p, const SceneView &scene, const Ray &ray, Float tMax, Float *t,
                                Float *b1, Float *b2) {
    switch (ShapeKind(p.kind)) {
    case ShapeKind::Triangles:
        return IntersectTriangle(p.p0, p.p1, p.p2, ray, tMax, t, b1, b2);
    case ShapeKind::Sphere:
        *b1 = *b2 = 0;
        return IntersectSphere(scene.spheres[scene.shapes[p.shape].index], ray, tMax, t);
    case ShapeKind::Disk:
        *b1 = *b2 = 0;
        return IntersectDisk(scene.disks[scene.shapes[p.shape].index], ray, tMax, t);
    case ShapeKind::Cylinder:
        *b1 = *b2 = 0;
        return IntersectCylinder(scene.cylinders[scene.shapes[p.shape].index], ray, tMax, t);
    case ShapeKind::BilinearPatches:
    case ShapeKind::Curves:
        return IntersectPatchOrCurve(scene, scene.shapes[p.shape], p.primitive, ray, tMax, t, b1, b2);
    }
    return false;
}

// IntersectPrimRef that also applies the shape's alpha cut-out (geometry/alpha.h): an ignored
// hit is no hit (a sphere's far side is tried next). `ray` is in the primitive's space, renderRay
// the same ray in render space, instance the one being traversed (NoIndex at the top level).
// Scenes without alpha shapes (scene.alphaShapes == 0) take IntersectPrimRef unchanged.
LU_INLINE bool IntersectPrimRefAlpha(const PrimRef &p, const SceneView &scene, const Ray &ray, const Ray &renderRay,
                                     uint32_t instance, Float tMax, Float *t, Float *b1, Float *b2) {
    if (scene.alphaShapes == 0) return IntersectPrimRef(p, scene, ray, tMax, t, b1, b2);
    if (IsQuadric(ShapeKind(p.kind))) {
        *b1 = *b2 = 0;
        return IntersectAnalyticAlpha(scene, p.shape, ray, renderRay, instance, tMax, t);
    }
    if (!IntersectPrimRef(p, scene, ray, tMax, t, b1, b2)) return false;
    uint32_t alpha = scene.shapes[p.shape].alpha;
    if (alpha == NoIndex) return true;
    HitRecord h;
    h.t = *t;
    h.shape = p.shape;
    h.primitive = p.primitive;
    h.b1 = *b1;
    h.b2 = *b2;
    h.instance = instance;
    return AlphaTestHit(scene, alpha, renderRay, renderRay, h);
}

// The ray in an instance's object space: same t (the direction is not renormalized).
LU_INLINE Ray InstanceRay(const Instance &in, const Ray &ray) {
    Ray r = ray;
    r.o = InstancePoint(in.instanceFromRender, ray.o);
    r.d = InstanceVector(in.instanceFromRender, ray.d);
    return r;
}

// Closest-hit traversal of the tree at `root` in (0, *tClosest), updating *tClosest and *best.
// The top level (TopLevel) enters an instance's prototype tree with the ray in object space; the
// bottom level is a separate instantiation (no recursion on the device). renderRay and instance
// are for alpha tests: the render-space ray and the instance traversed (NoIndex at the top).
template <bool TopLevel>
LU_INLINE void TraverseClosest(const BVHView &bvh, const SceneView &scene, int32_t root, const Ray &ray,
                               const Ray &renderRay, uint32_t instance, Float *tClosest, HitRecord *best) {
    Vec3f invD(SafeRcp(ray.d.x), SafeRcp(ray.d.y), SafeRcp(ray.d.z));
    int32_t stack[BVHStackSize];
    int sp = 0;
    int32_t node = root;
    while (true) {
        BVHNode n = LoadBVHNode(bvh.nodes.ptr + node);
        Float tNear[2];
        bool boxHit[2];
        IntersectChildBoxes(n, ray.o, invD, *tClosest, tNear, boxHit);
        int first = tNear[1] < tNear[0] ? 1 : 0;
        int32_t next[2];
        int nNext = 0;
        for (int k = 0; k < 2; ++k) {
            int i = k == 0 ? first : 1 - first;
            if (!boxHit[i]) continue;
            if (!n.IsLeaf(i)) {
                // A hit in the nearer leaf may already lie in front of this box.
                if (tNear[i] <= *tClosest) next[nNext++] = n.child[i];
                continue;
            }
            uint32_t begin = n.FirstPrim(i), end = begin + n.count[i];
            for (uint32_t j = begin; j < end; ++j) {
                PrimRef p = LoadPrimRef(bvh.prims.ptr + j);
                if constexpr (TopLevel) {
                    if (p.kind == PrimRefInstance) {
                        const Instance &in = scene.instances[p.shape];
                        int32_t r = bvh.prototypeRoots[in.prototype];
                        if (r < 0) continue;
                        Float tBefore = *tClosest;
                        TraverseClosest<false>(bvh, scene, r, InstanceRay(in, ray), renderRay, p.shape, tClosest, best);
                        if (*tClosest < tBefore) best->instance = p.shape;
                        continue;
                    }
                }
                Float t, b1, b2;
                if (IntersectPrimRefAlpha(p, scene, ray, renderRay, instance, *tClosest, &t, &b1, &b2)) {
                    *tClosest = t;
                    best->t = t;
                    best->shape = p.shape;
                    best->primitive = p.primitive;
                    best->b1 = b1;
                    best->b2 = b2;
                    best->instance = NoIndex;
                }
            }
        }
        if (nNext == 2) {
            if (sp < BVHStackSize) stack[sp++] = next[1];
            node = next[0];
        } else if (nNext == 1) {
            node = next[0];
        } else {
            if (sp == 0) break;
            node = stack[--sp];
        }
    }
}

// Closest hit along the ray in (0, ray.tMax). On a hit fills *hit (t, shape, primitive, b1, b2,
// instance) and returns true; otherwise leaves *hit untouched.
LU_INLINE bool IntersectClosest(const BVHView &bvh, const SceneView &scene, const Ray &ray, HitRecord *hit) {
    if (bvh.nodes.size == 0) return false;
    Float tClosest = ray.tMax;
    HitRecord best;
    TraverseClosest<true>(bvh, scene, 0, ray, ray, NoIndex, &tClosest, &best);
    if (!best.Hit()) return false;
    *hit = best;
    return true;
}

// Any hit in (0, ray.tMax) in the tree at `root` (levels as TraverseClosest).
template <bool TopLevel>
LU_INLINE bool TraverseAny(const BVHView &bvh, const SceneView &scene, int32_t root, const Ray &ray,
                           const Ray &renderRay, uint32_t instance) {
    Vec3f invD(SafeRcp(ray.d.x), SafeRcp(ray.d.y), SafeRcp(ray.d.z));
    int32_t stack[BVHStackSize];
    int sp = 0;
    int32_t node = root;
    while (true) {
        BVHNode n = LoadBVHNode(bvh.nodes.ptr + node);
        Float tNear[2];
        bool boxHit[2];
        IntersectChildBoxes(n, ray.o, invD, ray.tMax, tNear, boxHit);
        int32_t next[2];
        int nNext = 0;
        for (int i = 0; i < 2; ++i) {
            if (!boxHit[i]) continue;
            if (!n.IsLeaf(i)) {
                next[nNext++] = n.child[i];
                continue;
            }
            uint32_t begin = n.FirstPrim(i), end = begin + n.count[i];
            for (uint32_t j = begin; j < end; ++j) {
                PrimRef p = LoadPrimRef(bvh.prims.ptr + j);
                if constexpr (TopLevel) {
                    if (p.kind == PrimRefInstance) {
                        const Instance &in = scene.instances[p.shape];
                        int32_t r = bvh.prototypeRoots[in.prototype];
                        if (r >= 0 && TraverseAny<false>(bvh, scene, r, InstanceRay(in, ray), renderRay, p.shape)) return true;
                        continue;
                    }
                }
                Float t, b1, b2;
                if (IntersectPrimRefAlpha(p, scene, ray, renderRay, instance, ray.tMax, &t, &b1, &b2)) return true;
            }
        }
        if (nNext == 2) {
            int nearer = tNear[1] < tNear[0] ? 1 : 0;   // nearer first finds occluders sooner
            int32_t a = n.child[nearer], b = n.child[1 - nearer];
            if (sp < BVHStackSize) stack[sp++] = b;
            node = a;
        } else if (nNext == 1) {
            node = next[0];
        } else {
            if (sp == 0) break;
            node = stack[--sp];
        }
    }
    return false;
}

// Any hit in (0, ray.tMax) (shadow rays; tMax exclusive). Returns true if something is hit.
LU_INLINE bool IntersectAny(const BVHView &bvh, const SceneView &scene, const Ray &ray) {
    if (bvh.nodes.size == 0) return false;
    return TraverseAny<true>(bvh, scene, 0, ray, ray, NoIndex);
}

// The Tracer of integrators/path.h over this BVH (the CUDA megakernel's; works on the host too).
struct BVHTracer {
    BVHView bvh;
    const SceneView *scene = nullptr;
    LU_HD bool Intersect(const Ray &ray, HitRecord *hit) const { return IntersectClosest(bvh, *scene, ray, hit); }
    LU_HD bool Occluded(const Ray &ray) const { return IntersectAny(bvh, *scene, ray); }
};

}  // namespace lu
