// Lucerna: pbrt-v4's "curve" shape (host and device): cubic Bezier segments of varying width,
// intersected as pbrt-v4's Curve (in a coordinate system with the ray along +z, by subdividing
// the segment until it is close to a line and testing the line's distance to the ray against the
// width), shaded as a ray-facing ribbon ("flat"), the same with normals turned as over a tube
// ("cylinder"), or a ribbon oriented by its end normals ("ribbon").
#pragma once

#include "lucerna/core/scene_data.h"

namespace lu {

// The point of a cubic Bezier curve at u (de Casteljau) and its derivative (pbrt-v4's
// EvaluateCubicBezier: a degenerate derivative falls back to the chord).
LU_INLINE Vec3f EvalCubicBezier(const Vec3f cp[4], Float u, Vec3f *deriv) {
    Vec3f a0 = cp[0] + (cp[1] - cp[0]) * u, a1 = cp[1] + (cp[2] - cp[1]) * u, a2 = cp[2] + (cp[3] - cp[2]) * u;
    Vec3f b0 = a0 + (a1 - a0) * u, b1 = a1 + (a2 - a1) * u;
    if (deriv) *deriv = LengthSquared(b1 - b0) > 0 ? (b1 - b0) * 3 : cp[3] - cp[0];
    return b0 + (b1 - b0) * u;
}

// The blossom P(a, b, c) of a cubic Bezier curve.
LU_INLINE Vec3f BlossomCubicBezier(const Vec3f cp[4], Float a, Float b, Float c) {
    Vec3f a0 = cp[0] + (cp[1] - cp[0]) * a, a1 = cp[1] + (cp[2] - cp[1]) * a, a2 = cp[2] + (cp[3] - cp[2]) * a;
    Vec3f b0 = a0 + (a1 - a0) * b, b1 = a1 + (a2 - a1) * b;
    return b0 + (b1 - b0) * c;
}

// The control points of the part u in [u0, u1] of a cubic Bezier curve.
LU_INLINE void CubicBezierPart(const Vec3f cp[4], Float u0, Float u1, Vec3f out[4]) {
    out[0] = BlossomCubicBezier(cp, u0, u0, u0);
    out[1] = BlossomCubicBezier(cp, u0, u0, u1);
    out[2] = BlossomCubicBezier(cp, u0, u1, u1);
    out[3] = BlossomCubicBezier(cp, u1, u1, u1);
}

LU_INLINE Float CurveWidth(const CurveSegment &seg, Float u) { return Lerp(u, seg.width[0], seg.width[1]); }

// A ribbon's normal at u: the end normals' spherical interpolation (pbrt-v4's CurveCommon).
LU_INLINE Vec3f RibbonNormal(const CurveSegment &seg, Float u) {
    Float cosAngle = Clamp(Dot(seg.n[0], seg.n[1]), Float(-1), Float(1));
    Float angle = std::acos(cosAngle);
    Float s = std::sin(angle);
    if (!(s > 1e-6f)) return seg.n[0];
    return seg.n[0] * (std::sin((1 - u) * angle) / s) + seg.n[1] * (std::sin(u * angle) / s);
}

// Piece `piece` of a segment split into 2^splitDepth: its u range.
LU_INLINE void CurvePieceRange(const CurveSet &cs, uint32_t piece, Float *u0, Float *u1) {
    Float inv = Float(1) / Float(1u << cs.splitDepth);
    *u0 = Float(piece) * inv;
    *u1 = Float(piece + 1) * inv;
}

LU_INLINE const CurveSegment &CurvePrimitiveSegment(const SceneView &s, const CurveSet &cs, uint32_t prim) {
    return s.curveSegments[cs.firstSegment + (prim >> cs.splitDepth)];
}

// Object-space box of primitive prim: its control points' box grown by half its widest width.
LU_INLINE Bounds3f CurvePieceObjectBounds(const SceneView &s, const CurveSet &cs, uint32_t prim) {
    const CurveSegment &seg = CurvePrimitiveSegment(s, cs, prim);
    Float u0, u1;
    CurvePieceRange(cs, prim & ((1u << cs.splitDepth) - 1), &u0, &u1);
    Vec3f cp[4];
    CubicBezierPart(seg.cp, u0, u1, cp);
    Bounds3f b;
    for (int i = 0; i < 4; ++i) b.Expand(cp[i]);
    Float h = Float(0.5) * Max(CurveWidth(seg, u0), CurveWidth(seg, u1));
    b.pMin = b.pMin - Vec3f(h, h, h);
    b.pMax = b.pMax + Vec3f(h, h, h);
    return b;
}

// The ray's hit on primitive prim of curve set cs in (0, tMax): t, and the segment's (u, v)
// (v across the width, 0.5 on the center line). ray is in the space cs is placed in (render
// space, or a prototype's), intersected in the curve's object space, as pbrt-v4's Curve.
// The recursion of pbrt-v4's RecursiveIntersect becomes a stack of (first leaf, depth) pairs;
// the control points of a part are recomputed from the piece's by blossoming.
LU_INLINE bool IntersectCurve(const SceneView &s, const CurveSet &cs, uint32_t prim, const Ray &rayIn, Float tMax,
                              Float *tHit, Float *uHit, Float *vHit) {
    const CurveSegment &seg = CurvePrimitiveSegment(s, cs, prim);
    Float uMin, uMax;
    CurvePieceRange(cs, prim & ((1u << cs.splitDepth) - 1), &uMin, &uMax);
    Vec3f o = cs.renderFromObject.Inverted().ApplyPoint(rayIn.o);
    Vec3f d = cs.renderFromObject.Inverted().ApplyVector(rayIn.d);
    Float rayLength = Length(d);
    if (!(rayLength > 0)) return false;
    Vec3f cpObj[4];
    CubicBezierPart(seg.cp, uMin, uMax, cpObj);
    // Ray space (pbrt-v4's LookAt(o, o + d, dx)): z along the ray, x and y across it.
    Vec3f dir = d / rayLength;
    Vec3f dx = Cross(dir, cpObj[3] - cpObj[0]), right, up;
    if (LengthSquared(dx) == 0) {
        CoordinateSystem(dir, &right, &up);
    } else {
        right = Normalize(Cross(Normalize(dx), dir));
        up = Cross(dir, right);
    }
    Vec3f cp[4];
    for (int i = 0; i < 4; ++i) {
        Vec3f q = cpObj[i] - o;
        cp[i] = Vec3f(Dot(q, right), Dot(q, up), Dot(q, dir));
    }
    Float zMax = rayLength * tMax;
    // pbrt-v4's refinement depth: subdivide until the curve is within 5% of the width of a line.
    Float L0 = 0;
    for (int i = 0; i < 2; ++i) {
        L0 = Max(L0, Max(Max(std::abs(cp[i].x - 2 * cp[i + 1].x + cp[i + 2].x),
                             std::abs(cp[i].y - 2 * cp[i + 1].y + cp[i + 2].y)),
                         std::abs(cp[i].z - 2 * cp[i + 1].z + cp[i + 2].z)));
    }
    Float eps = Max(seg.width[0], seg.width[1]) * .05f;
    int maxDepth = 0;
    if (L0 > 0 && eps > 0) {
        Float r = Float(1.41421356237) * 6 * L0 / (8 * eps);
        if (r >= 1) maxDepth = Clamp(int(std::floor(std::log2(r))) / 2, 0, 10);
    }
    bool found = false;
    Float tBest = zMax;   // in ray-space z
    // (first leaf index at maxDepth, depth) of the parts still to test.
    uint32_t stackLeaf[12];
    int stackDepth[12];
    int sp = 0;
    stackLeaf[sp] = 0;
    stackDepth[sp++] = 0;
    while (sp > 0) {
        --sp;
        uint32_t leaf = stackLeaf[sp];
        int depth = stackDepth[sp];
        Float span = Float(1) / Float(1u << depth);
        Float w0 = Float(leaf) / Float(1u << maxDepth), w1 = w0 + span;   // within the piece
        Vec3f c[4];
        CubicBezierPart(cp, w0, w1, c);
        Float u0 = Lerp(w0, uMin, uMax), u1 = Lerp(w1, uMin, uMax);
        Float half = Float(0.5) * Max(CurveWidth(seg, u0), CurveWidth(seg, u1));
        Bounds3f b;
        for (int i = 0; i < 4; ++i) b.Expand(c[i]);
        if (b.pMin.x - half > 0 || b.pMax.x + half < 0 || b.pMin.y - half > 0 || b.pMax.y + half < 0 ||
            b.pMax.z + half < 0 || b.pMin.z - half > tBest)
            continue;
        if (depth < maxDepth) {
            uint32_t halfLeaves = 1u << (maxDepth - depth - 1);
            // The second half below the first: the first is tested first.
            stackLeaf[sp] = leaf + halfLeaves;
            stackDepth[sp++] = depth + 1;
            stackLeaf[sp] = leaf;
            stackDepth[sp++] = depth + 1;
            continue;
        }
        // A part close to a line: pbrt-v4's test against the segment c[0] -> c[3]. The origin
        // must lie between the lines perpendicular to the curve at its two ends.
        Float edge = (c[1].y - c[0].y) * -c[0].y + c[0].x * (c[0].x - c[1].x);
        if (edge < 0) continue;
        edge = (c[2].y - c[3].y) * -c[3].y + c[3].x * (c[3].x - c[2].x);
        if (edge < 0) continue;
        Vec2f segDir(c[3].x - c[0].x, c[3].y - c[0].y);
        Float denom = segDir.x * segDir.x + segDir.y * segDir.y;
        if (denom == 0) continue;
        Float w = (-c[0].x * segDir.x - c[0].y * segDir.y) / denom;
        Float u = Clamp(Lerp(w, u0, u1), u0, u1);
        Float hitWidth = CurveWidth(seg, u);
        if (cs.type == CurveType::Ribbon) hitWidth *= std::abs(Dot(RibbonNormal(seg, u), d)) / rayLength;
        Vec3f dpcdw;
        Vec3f pc = EvalCubicBezier(c, Clamp(w, Float(0), Float(1)), &dpcdw);
        Float dist2 = pc.x * pc.x + pc.y * pc.y;
        if (dist2 > hitWidth * hitWidth * Float(0.25)) continue;
        if (pc.z < 0 || pc.z > tBest) continue;
        Float dist = std::sqrt(dist2);
        Float edgeFunc = dpcdw.x * -pc.y + pc.x * dpcdw.y;
        Float v = edgeFunc > 0 ? Float(0.5) + dist / hitWidth : Float(0.5) - dist / hitWidth;
        tBest = pc.z;
        *uHit = u;
        *vHit = Clamp(v, Float(0), Float(1));
        found = true;
    }
    if (!found) return false;
    Float t = tBest / rayLength;
    if (!(t > 0 && t < tMax)) return false;
    *tHit = t;
    return true;
}

// pbrt-v4's curve surface frame at (u, v) for a ray of object-space direction dObj: dp/du along
// the curve; dp/dv across it, of the hit's width: perpendicular to the ray (flat), that turned
// about dp/du by -theta, theta = lerp(v, -90, 90) degrees (cylinder), or across the ribbon's
// normal (ribbon).
LU_INLINE void CurveFrame(const CurveSet &cs, const CurveSegment &seg, Float u, Float v, const Vec3f &dObj, Vec3f *dpdu,
                          Vec3f *dpdv) {
    EvalCubicBezier(seg.cp, u, dpdu);
    Float dLen = Length(dObj);
    Vec3f dir = dLen > 0 ? dObj / dLen : Vec3f(0, 0, 1);
    Float hitWidth = CurveWidth(seg, u);
    if (cs.type == CurveType::Ribbon) {
        Vec3f nHit = RibbonNormal(seg, u);
        hitWidth *= std::abs(Dot(nHit, dir));
        Vec3f c = Cross(nHit, *dpdu);
        *dpdv = LengthSquared(c) > 0 ? Normalize(c) * hitWidth : Vec3f(0, 0, 0);
    } else {
        Vec3f c = Cross(dir, *dpdu);
        if (!(LengthSquared(c) > 0)) {
            Vec3f a, b;
            CoordinateSystem(Normalize(*dpdu), &a, &b);
            c = a;
        }
        *dpdv = Normalize(c) * hitWidth;
        if (cs.type == CurveType::Cylinder) {
            // Rotation by -theta about the unit axis a (Rodrigues).
            Float theta = Radians(Lerp(v, Float(-90), Float(90)));
            Vec3f a = Normalize(*dpdu);
            Float sinT = std::sin(-theta), cosT = std::cos(-theta);
            Vec3f p = *dpdv;
            *dpdv = p * cosT + Cross(a, p) * sinT + a * (Dot(a, p) * (1 - cosT));
        }
    }
    if (!(LengthSquared(*dpdv) > 0)) {
        Vec3f a, b;
        CoordinateSystem(Normalize(*dpdu), &a, &b);
        *dpdv = a * hitWidth;
    }
}

}  // namespace lu
