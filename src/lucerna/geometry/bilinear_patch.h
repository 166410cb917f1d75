// Lucerna: pbrt-v4's bilinear patches (host and device): the ray test (Reshetov 2019, "Cool
// Patches: A Geometric Approach to Ray/Bilinear Patch Intersections", as pbrt-v4's
// IntersectBilinearPatch), the surface at (u, v), its inverse, area and pbrt-v4's area sampling.
// A patch has the corners p00, p10, p01, p11 (render space, or a prototype's object space) and
// the surface p(u, v) = lerp(v, lerp(u, p00, p10), lerp(u, p01, p11)).
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/sampling/warp.h"

namespace lu {

// A double-precision 3-vector for the few tests that need one.
struct DVec3 {
    double x, y, z;
};
LU_INLINE DVec3 operator+(const DVec3 &a, const DVec3 &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
LU_INLINE DVec3 operator-(const DVec3 &a, const DVec3 &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
LU_INLINE DVec3 operator*(const DVec3 &a, double s) { return {a.x * s, a.y * s, a.z * s}; }
LU_INLINE double DDot(const DVec3 &a, const DVec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
LU_INLINE DVec3 DCross(const DVec3 &a, const DVec3 &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

struct PatchCorners {
    Vec3f p00, p10, p01, p11;
};

// Absolute vertex indices of patch `prim` (p00, p10, p01, p11).
LU_INLINE void PatchVertices(const BilinearMesh &m, const SceneView &s, uint32_t prim, uint32_t v[4]) {
    const uint32_t *idx = s.indices.ptr + m.firstIndex + 4 * prim;
    for (int k = 0; k < 4; ++k) v[k] = m.firstVertex + idx[k];
}

LU_INLINE PatchCorners PatchPositions(const SceneView &s, const uint32_t v[4]) {
    return {s.positions[v[0]], s.positions[v[1]], s.positions[v[2]], s.positions[v[3]]};
}

LU_INLINE Vec3f PatchPoint(const PatchCorners &c, Float u, Float v) {
    return (c.p00 * (1 - u) + c.p10 * u) * (1 - v) + (c.p01 * (1 - u) + c.p11 * u) * v;
}
LU_INLINE Vec3f PatchDpdu(const PatchCorners &c, Float v) { return (c.p10 - c.p00) * (1 - v) + (c.p11 - c.p01) * v; }
LU_INLINE Vec3f PatchDpdv(const PatchCorners &c, Float u) { return (c.p01 - c.p00) * (1 - u) + (c.p11 - c.p10) * u; }

// The ray's hit on the patch in (0, tMax): t and the patch's (u, v). For each root u of the
// quadratic that says where the segment lerp(u, p00, p10) -> lerp(u, p01, p11) meets the ray
// (they are coplanar: det[pa - o, pb - pa, d] = 0), the closest points of that segment's line
// and the ray give v and t. Solved in double: the coefficients cancel for near-planar patches.
LU_INLINE bool IntersectBilinearPatch(const PatchCorners &c, const Ray &ray, Float tMax, Float *tHit, Float *uHit,
                                      Float *vHit) {
    auto dv = [](const Vec3f &a) { return DVec3{double(a.x), double(a.y), double(a.z)}; };
    DVec3 o = dv(ray.o), d = dv(ray.d), p00 = dv(c.p00), p10 = dv(c.p10), p01 = dv(c.p01), p11 = dv(c.p11);
    double a = DDot(DCross(p10 - p00, p01 - p11), d);
    double cc = DDot(DCross(p00 - o, d), p01 - p00);
    double b = DDot(DCross(p10 - o, d), p11 - p10) - (a + cc);
    double roots[2];
    int n = 0;
    double scale = std::abs(a) + std::abs(b) + std::abs(cc);
    if (!(scale > 0)) return false;
    if (std::abs(a) <= 1e-12 * scale) {   // a parallelogram-like patch: linear in u
        if (b == 0) return false;
        roots[n++] = -cc / b;
    } else {
        double disc = b * b - 4 * a * cc;
        if (disc < 0) return false;
        double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        roots[n++] = q / a;
        if (q != 0) roots[n++] = cc / q;
    }
    double dLen2 = DDot(d, d);
    // Hits closer than this (relative to the patch's and ray's size) are the ray's own origin.
    double eps = 1e-7 * (std::abs(o.x) + std::abs(o.y) + std::abs(o.z) + std::abs(p00.x) + std::abs(p00.y) +
                         std::abs(p00.z) + std::abs(p11.x) + std::abs(p11.y) + std::abs(p11.z)) /
                 std::sqrt(dLen2);
    bool found = false;
    double tBest = tMax;
    for (int i = 0; i < n; ++i) {
        double u = roots[i];
        if (!(u >= 0 && u <= 1)) continue;
        DVec3 uo = p00 + (p10 - p00) * u;
        DVec3 ud = p01 + (p11 - p01) * u - uo;
        DVec3 deltao = uo - o;
        DVec3 perp = DCross(d, ud);
        double p2 = DDot(perp, perp);
        if (!(p2 > 0)) continue;
        // o + t d = uo + v ud: t = det[deltao, ud, perp] / p2, v = det[deltao, d, perp] / p2.
        double v1 = DDot(DCross(deltao, d), perp);
        double t1 = DDot(DCross(deltao, ud), perp);
        if (!(v1 >= 0 && v1 <= p2)) continue;
        double t = t1 / p2;
        if (!(t > eps && t < tBest)) continue;
        tBest = t;
        *uHit = Float(u);
        *vHit = Float(v1 / p2);
        found = true;
    }
    if (!found) return false;
    *tHit = Float(tBest);
    return *tHit < tMax && *tHit > 0;
}

// The patch's (u, v) of a point on (or near) it: Newton iterations on the tangent-plane
// projection of p(u, v) - p, from the patch center. For light pdfs and bump mapping, which get a
// point, not the hit's (u, v).
LU_INLINE Vec2f InvertBilinearPatch(const PatchCorners &c, const Vec3f &p) {
    Float u = 0.5f, v = 0.5f;
    for (int it = 0; it < 8; ++it) {
        Vec3f r = PatchPoint(c, u, v) - p;
        Vec3f du = PatchDpdu(c, v), dvv = PatchDpdv(c, u);
        // Least squares [du dv] (delta) = -r: normal equations.
        Float a = Dot(du, du), b = Dot(du, dvv), d = Dot(dvv, dvv);
        Float det = a * d - b * b;
        if (!(std::abs(det) > 0)) break;
        Float ru = Dot(du, r), rv = Dot(dvv, r);
        Float dU = (d * ru - b * rv) / det, dV = (a * rv - b * ru) / det;
        u = Clamp(u - dU, Float(0), Float(1));
        v = Clamp(v - dV, Float(0), Float(1));
        if (std::abs(dU) + std::abs(dV) < 1e-7f) break;
    }
    return Vec2f(u, v);
}

// |dp/du x dp/dv|: the area element at (u, v).
LU_INLINE Float PatchAreaElement(const PatchCorners &c, Float u, Float v) {
    return Length(Cross(PatchDpdu(c, v), PatchDpdv(c, u)));
}

// The patch's area by 4 x 4 Gauss-Legendre quadrature of the area element (exact for
// parallelograms; pbrt-v4 approximates a curved patch's area by 3 x 3 quads).
LU_INLINE Float BilinearPatchArea(const PatchCorners &c) {
    constexpr Float x[4] = {0.0694318442f, 0.3300094782f, 0.6699905218f, 0.9305681558f};
    constexpr Float w[4] = {0.1739274226f, 0.3260725774f, 0.3260725774f, 0.1739274226f};
    Float a = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) a += w[i] * w[j] * PatchAreaElement(c, x[i], x[j]);
    return a;
}

// pbrt-v4's approximately uniform area sampling of a patch that is not a rectangle: (u, v) from
// the bilinear density with the area elements at the corners as weights (SampleBilinear), the
// area pdf that density divided by the area element there.
LU_INLINE void PatchCornerWeights(const PatchCorners &c, Float w[4]) {
    w[0] = Length(Cross(c.p10 - c.p00, c.p01 - c.p00));
    w[1] = Length(Cross(c.p10 - c.p00, c.p11 - c.p10));
    w[2] = Length(Cross(c.p01 - c.p00, c.p11 - c.p01));
    w[3] = Length(Cross(c.p11 - c.p10, c.p11 - c.p01));
}
// Samples the bilinear density with corner weights w = {f(0,0), f(1,0), f(0,1), f(1,1)}: y from
// the marginal, then x from the conditional (both linear); BilinearPDF is its density.
LU_INLINE Vec2f SampleBilinear(Vec2f u, const Float w[4]) {
    Vec2f p;
    p.y = SampleLinear(u.y, w[0] + w[1], w[2] + w[3]);
    p.x = SampleLinear(u.x, Lerp(p.y, w[0], w[2]), Lerp(p.y, w[1], w[3]));
    return p;
}
LU_INLINE Float BilinearPDF(Vec2f p, const Float w[4]) {
    if (p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1) return 0;
    Float sum = w[0] + w[1] + w[2] + w[3];
    if (sum == 0) return 1;
    return 4 * ((1 - p.x) * (1 - p.y) * w[0] + p.x * (1 - p.y) * w[1] + (1 - p.x) * p.y * w[2] + p.x * p.y * w[3]) / sum;
}
// Area pdf of that sampling at (u, v).
LU_INLINE Float PatchAreaPDF(const PatchCorners &c, Vec2f uv) {
    Float w[4];
    PatchCornerWeights(c, w);
    Float dA = PatchAreaElement(c, uv.x, uv.y);
    return dA > 0 ? BilinearPDF(uv, w) / dA : 0;
}

}  // namespace lu
