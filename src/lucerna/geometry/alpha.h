// Lucerna: shape alpha cut-outs (host and device), pbrt-v4's stochastic alpha test of
// GeometricPrimitive::Intersect / IntersectP and of its GPU any-hit program, used by every tracer
// (Lucerna's BVH, hence the CUDA backend, and Embree's filter and user-geometry callbacks).
#pragma once

#include "lucerna/geometry/shapes.h"
#include "lucerna/materials/texture.h"
#include "lucerna/sampling/hash.h"

namespace lu {

// pbrt-v4's decision at alpha value a: a >= 1 keeps the hit, a <= 0 drops it, otherwise the hit is
// kept when u <= a with u = HashFloat(o, d) of the ray (deterministic: the same ray decides the
// same way in closest-hit and shadow queries, on every tracer). `hashRay` is the render-space ray.
LU_INLINE bool AlphaKeeps(Float a, const Ray &hashRay) {
    if (a >= 1) return true;
    if (a <= 0) return false;
    return HashFloat(hashRay.o, hashRay.d) <= a;
}

// The test of a candidate hit on a shape whose alpha texture is floatTextures[alpha]: the texture
// at the hit's render-space point, geometric normal and uv (ComputeInteraction; an instance's
// shape through its instance, as pbrt-v4's GPU path), `renderRay` the render-space ray (same t).
LU_TEXTURE_NOINLINE LU_HD inline bool AlphaTestHit(const SceneView &s, uint32_t alpha, const Ray &renderRay,
                                                   const Ray &hashRay, const HitRecord &hit) {
    SurfaceInteraction si = ComputeInteraction(s, hit, renderRay);
    TextureEvalContext ctx;
    ctx.p = si.p;
    ctx.n = si.n;
    ctx.uv = si.uv;
    return AlphaKeeps(EvalFloatTexture(s.floatTextures[alpha], ctx, s), hashRay);
}

// Whether a candidate hit survives its shape's cut-out (true for opaque shapes, with no texture
// lookup). hit.t, shape, primitive, b1, b2 and instance must be set.
LU_INLINE bool AlphaKeepsHit(const SceneView &s, const Ray &renderRay, const HitRecord &hit) {
    uint32_t alpha = s.shapes[hit.shape].alpha;
    return alpha == NoIndex || AlphaTestHit(s, alpha, renderRay, renderRay, hit);
}

// An analytic shape (sphere, disk or cylinder) hit in (0, tMax) that survives the shape's alpha
// (pbrt-v4: after an ignored hit the ray continues, so a sphere's or cylinder's far side is tried
// next; pbrt-v4 respawns the ray at the ignored hit, so the far side's u hashes the ray from
// there). `ray` is in the space the shape is stored in (object space for a prototype's),
// renderRay the same in render space; instance: hit.instance.
LU_INLINE bool IntersectAnalyticAlpha(const SceneView &s, uint32_t shapeId, const Ray &ray, const Ray &renderRay,
                                      uint32_t instance, Float tMax, Float *tHit) {
    const Shape &shape = s.shapes[shapeId];
    Float t;
    if (!IntersectQuadric(s, shape, ray, tMax, &t)) return false;
    if (shape.alpha == NoIndex) {
        *tHit = t;
        return true;
    }
    HitRecord h;
    h.shape = shapeId;
    h.instance = instance;
    h.t = t;
    if (AlphaTestHit(s, shape.alpha, renderRay, renderRay, h)) {
        *tHit = t;
        return true;
    }
    Float tFar;
    if (shape.kind == ShapeKind::Sphere) {
        if (!IntersectSphere(s.spheres[shape.index], ray, tMax, &tFar, true)) return false;
    } else if (shape.kind == ShapeKind::Cylinder) {
        if (!IntersectCylinder(s.cylinders[shape.index], ray, tMax, &tFar, true)) return false;
    } else {
        return false;
    }
    Ray continued = renderRay;
    continued.o = renderRay(t);
    h.t = tFar;
    if (!AlphaTestHit(s, shape.alpha, renderRay, continued, h)) return false;
    *tHit = tFar;
    return true;
}

// A bilinear patch's or curve's hit in (0, tMax) that survives the shape's alpha: t and the
// primitive's (u, v). Unlike the quadrics' far side, a second hit on the same primitive behind
// an ignored one is not looked for (a patch folded over the ray, a curve bent back over it).
LU_INLINE bool IntersectPatchOrCurveAlpha(const SceneView &s, uint32_t shapeId, uint32_t prim, const Ray &ray,
                                          const Ray &renderRay, uint32_t instance, Float tMax, Float *t, Float *b1,
                                          Float *b2) {
    const Shape &shape = s.shapes[shapeId];
    if (!IntersectPatchOrCurve(s, shape, prim, ray, tMax, t, b1, b2)) return false;
    if (shape.alpha == NoIndex) return true;
    HitRecord h;
    h.t = *t;
    h.shape = shapeId;
    h.primitive = prim;
    h.b1 = *b1;
    h.b2 = *b2;
    h.instance = instance;
    return AlphaTestHit(s, shape.alpha, renderRay, renderRay, h);
}

}  // namespace lu
