// Lucerna: sampling points on emitting shapes as seen from a reference point, with solid-angle
// pdfs (host and device). Follows pbrt-v4's Triangle/Sphere/Disk/Cylinder::Sample(ctx, u) and
// PDF(ctx, wi): spherical-triangle sampling (Arvo 1995) with the bilinear cos-warp, cone sampling
// of spheres, area sampling of disks and cylinders; the spherical-triangle helpers after pbrt-v4's
// sampling.cpp. Partial shapes keep pbrt-v4's pdfs but return only points that exist (pbrt-v4
// samples the whole sphere or disk, cut-away parts included: see SampleSphere, SampleDisk).
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/geometry/shapes.h"
#include "lucerna/sampling/warp.h"

namespace lu {

// Where light is sampled from: p, and the geometric and shading normals of the surface there
// ((0,0,0) when not on a surface).
struct LightSampleContext {
    Vec3f p, n, ns;
};

// A sampled point on a shape: position, oriented geometric normal (pbrt-v4's conventions), uv,
// and the pdf w.r.t. solid angle at the reference point.
struct ShapeSample {
    Vec3f p, n;
    Vec2f uv;
    Float pdf = 0;
};

// ---- Spherical geometry helpers ----

// Angle between unit vectors, accurate near 0 and pi.
LU_INLINE Float AngleBetween(const Vec3f &a, const Vec3f &b) {
    if (Dot(a, b) < 0) return Pi - 2 * SafeASin(Length(a + b) / 2);
    return 2 * SafeASin(Length(b - a) / 2);
}

// v minus its projection on the unit vector w.
LU_INLINE Vec3f GramSchmidt(const Vec3f &v, const Vec3f &w) { return v - w * Dot(v, w); }

// atan2 by Cephes atanf's reduction to |t| <= tan(pi/8) and its polynomial: within 3.3 ulp
// (2.3e-7 relative) of atan2 over 20M random arguments, at a third of the cost of the libm call
// (with its errno wrapper) that every triangle light sample and pdf made.
LU_INLINE Float Atan2Poly(Float y, Float x) {
    Float ax = std::abs(x), ay = std::abs(y);
    bool swap = ay > ax;
    Float num = swap ? ax : ay, den = swap ? ay : ax;
    if (den == 0) return std::copysign(std::signbit(x) ? Pi : Float(0), y);
    Float t = num / den;   // in [0, 1]
    Float base = 0;
    if (t > 0.41421356f) { base = PiOver4; t = (t - 1) / (t + 1); }
    Float z = t * t;
    Float r = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z * t +
              t + base;
    if (swap) r = PiOver2 - r;
    if (x < 0) r = Pi - r;
    return std::copysign(r, y);
}

// Solid angle of the spherical triangle with unit vertices a, b, c (Van Oosterom & Strackee).
LU_INLINE Float SphericalTriangleArea(const Vec3f &a, const Vec3f &b, const Vec3f &c) {
    return std::abs(2 * Atan2Poly(Dot(a, Cross(b, c)), 1 + Dot(a, b) + Dot(a, c) + Dot(b, c)));
}

// Uniform sampling of the solid angle subtended by triangle v from p (Arvo 1995). Returns the
// barycentrics of the sampled point; *pdf = 1 / solid angle, or 0 for degenerate triangles.
// This version takes the unit directions dir[i] = Normalize(v[i] - p) and the solid angle
// area = SphericalTriangleArea(dir) (Van Oosterom & Strackee, accurate for small triangles).
// Arvo's construction needs only cos and sin of the interior angle alpha at a, which come from
// the normals of the planes (a, b) and (a, c) without an arcsine, and of A' = u0 * area.
// The plane normals need no normalization (cos and sin are renormalized together), and
// |n_ab x n_ca| = |det(a, b, c)| |a|. sin and cos of A' come from the half angle (one float
// sincos): 1 - cos A' = 2 sin^2(A'/2) keeps k1 = cos(phi) - cos(alpha) free of cancellation
// for small A'; the rest runs in double as before.
LU_INLINE void SampleSphericalTriangleDirs(const Vec3f &v0, const Vec3f &v1, const Vec3f &v2, const Vec3f dir[3],
                                           Float area, const Vec3f &p, Vec2f u, Float b[3], Float *pdf) {
    *pdf = 0;
    b[0] = b[1] = b[2] = Float(1) / 3;
    const Vec3f &a = dir[0], &bb = dir[1], &c = dir[2];
    Vec3f nab = Cross(a, bb), nca = Cross(c, a);
    if (LengthSquared(nab) == 0 || LengthSquared(nca) == 0 || !(area > 0)) return;
    *pdf = 1 / area;
    // alpha = angle(nab, -nca).
    double cosA = -double(Dot(nab, nca)), sinA = std::abs(double(Dot(nab, c)));
    double norm = std::sqrt(cosA * cosA + sinA * sinA);
    if (!(norm > 0)) return;
    double invNorm = 1 / norm;
    cosA *= invNorm;
    sinA *= invNorm;
    // Sub-triangle area A' = u0 * area determines the point c' on the arc from a to c.
    // phi = A' - alpha (pbrt-v4's A' + pi - alpha, with the pi folded into the signs).
    Float halfAp = 0.5f * (u.x * area);
    Float sh = std::sin(halfAp), ch = std::cos(halfAp);   // one sincosf
    double sinAp = 2 * double(sh) * double(ch), oneMinusCosAp = 2 * double(sh) * double(sh);
    double cosAp = 1 - oneMinusCosAp;
    double sinPhi = sinAp * cosA - cosAp * sinA;
    double cosPhi = cosAp * cosA + sinAp * sinA;
    double k1 = sinAp * sinA - oneMinusCosAp * cosA;   // cos(phi) - cos(alpha)
    double k2 = sinPhi + sinA * double(Dot(a, bb));
    double cosBp = ((k2 * cosPhi - k1 * sinPhi) * cosA - k2) / ((k2 * sinPhi + k1 * cosPhi) * sinA);
    if (cosBp != cosBp) cosBp = 1;  // triangle covering (nearly) a hemisphere
    cosBp = cosBp < -1 ? -1 : (cosBp > 1 ? 1 : cosBp);
    Float sinBp = SafeSqrt(1 - Float(cosBp * cosBp));
    Vec3f cp = a * Float(cosBp) + Normalize(GramSchmidt(c, a)) * sinBp;
    // Uniform in cos along the arc from b to c'.
    Float cosTheta = 1 - u.y * (1 - Dot(cp, bb));
    Float sinTheta = SafeSqrt(1 - cosTheta * cosTheta);
    Vec3f gs = GramSchmidt(cp, bb);
    Float gs2 = LengthSquared(gs);
    Vec3f w = bb * cosTheta + (gs2 > 0 ? gs * (sinTheta / std::sqrt(gs2)) : Vec3f());
    // Barycentrics of the ray (p, w) against the planar triangle (Moller-Trumbore).
    Vec3f e1 = v1 - v0, e2 = v2 - v0;
    Vec3f s1 = Cross(w, e2);
    Float divisor = Dot(s1, e1);
    if (divisor == 0) return;
    Float inv = 1 / divisor;
    Vec3f s = p - v0;
    Float b1 = Clamp(Dot(s, s1) * inv, Float(0), Float(1));
    Float b2 = Clamp(Dot(w, Cross(s, e1)) * inv, Float(0), Float(1));
    Float sum = b1 + b2;
    if (sum > 1) { b1 /= sum; b2 /= sum; }
    b[0] = 1 - b1 - b2; b[1] = b1; b[2] = b2;
}

LU_INLINE void SampleSphericalTriangle(const Vec3f v[3], const Vec3f &p, Vec2f u, Float b[3], Float *pdf) {
    Vec3f dir[3] = {v[0] - p, v[1] - p, v[2] - p};
    if (LengthSquared(dir[0]) == 0 || LengthSquared(dir[1]) == 0 || LengthSquared(dir[2]) == 0) {
        *pdf = 0;
        b[0] = b[1] = b[2] = Float(1) / 3;
        return;
    }
    for (int i = 0; i < 3; ++i) dir[i] = Normalize(dir[i]);
    SampleSphericalTriangleDirs(v[0], v[1], v[2], dir, SphericalTriangleArea(dir[0], dir[1], dir[2]), p, u, b, pdf);
}

// The sample u that SampleSphericalTriangle maps to direction w (unit) from p.
LU_INLINE Vec2f InvertSphericalTriangleSampleDirs(const Vec3f dir[3], const Vec3f &w) {
    const Vec3f &a = dir[0], &b = dir[1], &c = dir[2];
    Vec3f nab = Cross(a, b), nbc = Cross(b, c), nca = Cross(c, a);
    if (LengthSquared(nab) == 0 || LengthSquared(nbc) == 0 || LengthSquared(nca) == 0) return {0.5f, 0.5f};
    nab = Normalize(nab); nbc = Normalize(nbc); nca = Normalize(nca);
    Float alpha = AngleBetween(nab, -nca), beta = AngleBetween(nbc, -nab), gamma = AngleBetween(nca, -nbc);
    // c' is where the great circle through b and w meets the arc a-c.
    Vec3f cp = Cross(Cross(b, w), Cross(c, a));
    if (LengthSquared(cp) == 0) return {0.5f, 0.5f};
    cp = Normalize(cp);
    if (Dot(cp, a + c) < 0) cp = -cp;
    Float u0;
    if (Dot(a, cp) > 0.99999847691f)  // within 0.1 degree of a
        u0 = 0;
    else {
        Vec3f ncpb = Cross(cp, b), nacp = Cross(a, cp);
        if (LengthSquared(ncpb) == 0 || LengthSquared(nacp) == 0) return {0.5f, 0.5f};
        ncpb = Normalize(ncpb); nacp = Normalize(nacp);
        Float apPi = alpha + AngleBetween(nab, ncpb) + AngleBetween(nacp, -ncpb);
        u0 = (apPi - Pi) / (alpha + beta + gamma - Pi);
    }
    Float u1 = (1 - Dot(w, b)) / (1 - Dot(cp, b));
    return {Clamp(u0, Float(0), Float(1)), Clamp(u1, Float(0), Float(1))};
}

LU_INLINE Vec2f InvertSphericalTriangleSample(const Vec3f v[3], const Vec3f &p, const Vec3f &w) {
    Vec3f dir[3] = {Normalize(v[0] - p), Normalize(v[1] - p), Normalize(v[2] - p)};
    return InvertSphericalTriangleSampleDirs(dir, w);
}

// ---- Shapes ----

// pbrt-v4's spherical sampling is used when the triangle's solid angle lies in this range.
constexpr Float MinSphericalSampleArea = 3e-4f, MaxSphericalSampleArea = 6.22f;

// pbrt-v4 samples spheres and disks with the normal flipped by ReverseOrientation only (not by
// a handedness-swapping transform, unlike intersection): recover ReverseOrientation.
LU_INLINE bool ReverseOrientation(bool flipNormals, const Transform &renderFromObject) {
    return flipNormals != renderFromObject.SwapsHandedness();
}

// Area used by the sampling pdfs, as pbrt-v4's Shape::Area(): render-space for triangles,
// object-space (transform scale ignored) for spheres, disks and cylinders.
LU_INLINE Float ShapeArea(const SceneView &s, const Shape &shape, uint32_t prim) {
    switch (shape.kind) {
    case ShapeKind::Triangles: {
        const TriangleMesh &m = s.triangleMeshes[shape.index];
        const uint32_t *idx = s.indices.ptr + m.firstIndex + 3 * prim;
        Vec3f p0 = s.positions[m.firstVertex + idx[0]], p1 = s.positions[m.firstVertex + idx[1]],
              p2 = s.positions[m.firstVertex + idx[2]];
        return 0.5f * Length(Cross(p1 - p0, p2 - p0));
    }
    case ShapeKind::Sphere: return SphereArea(s.spheres[shape.index]);
    case ShapeKind::Disk: return DiskArea(s.disks[shape.index]);
    case ShapeKind::Cylinder: return CylinderArea(s.cylinders[shape.index]);
    case ShapeKind::BilinearPatches: {
        uint32_t v[4];
        PatchVertices(s.bilinearMeshes[shape.index], s, prim, v);
        return BilinearPatchArea(PatchPositions(s, v));
    }
    case ShapeKind::Curves: return 0;   // curves are never emitters
    }
    return 0;
}

struct TriangleData {
    Vec3f p[3];
    uint32_t v[3];  // absolute vertex indices
};

LU_INLINE TriangleData GetTriangle(const SceneView &s, const TriangleMesh &m, uint32_t prim) {
    TriangleData t;
    const uint32_t *idx = s.indices.ptr + m.firstIndex + 3 * prim;
    for (int i = 0; i < 3; ++i) {
        t.v[i] = m.firstVertex + idx[i];
        t.p[i] = s.positions[t.v[i]];
    }
    return t;
}

// The same without copies: references to the positions in the scene arrays. (Copying 12-byte
// vectors to the stack and reloading them as 16-byte vectors right away stalls store forwarding:
// 11% of SampleLi's time.)
struct TriangleRef {
    const Vec3f &p0, &p1, &p2;
    uint32_t v[3];  // absolute vertex indices
};

LU_INLINE TriangleRef GetTriangleRef(const SceneView &s, const TriangleMesh &m, uint32_t prim) {
    const uint32_t *idx = s.indices.ptr + m.firstIndex + 3 * prim;
    uint32_t v0 = m.firstVertex + idx[0], v1 = m.firstVertex + idx[1], v2 = m.firstVertex + idx[2];
    return TriangleRef{s.positions[v0], s.positions[v1], s.positions[v2], {v0, v1, v2}};
}

// Geometric normal and uv at barycentrics b, oriented as pbrt-v4's Triangle (flip, or facing the
// interpolated shading normal when the mesh has normals). uv is skipped when null.
LU_INLINE void TriangleNormalUV(const SceneView &s, const TriangleMesh &m, const TriangleRef &t, const Float b[3],
                                Vec3f *n, Vec2f *uv) {
    Vec3f ng = Normalize(Cross(t.p1 - t.p0, t.p2 - t.p0));
    if (m.flipNormals) ng = -ng;
    if (m.normalOffset != NoIndex) {
        Vec3f ns = s.normals[m.normalOffset + (t.v[0] - m.firstVertex)] * b[0] +
                   s.normals[m.normalOffset + (t.v[1] - m.firstVertex)] * b[1] +
                   s.normals[m.normalOffset + (t.v[2] - m.firstVertex)] * b[2];
        if (LengthSquared(ns) > 0) ng = FaceForward(ng, ns);
    }
    *n = ng;
    if (!uv) return;
    Vec2f uv0(0, 0), uv1(1, 0), uv2(1, 1);
    if (m.uvOffset != NoIndex) {
        uv0 = s.uvs[m.uvOffset + (t.v[0] - m.firstVertex)];
        uv1 = s.uvs[m.uvOffset + (t.v[1] - m.firstVertex)];
        uv2 = s.uvs[m.uvOffset + (t.v[2] - m.firstVertex)];
    }
    *uv = Vec2f(b[0] * uv0.x + b[1] * uv1.x + b[2] * uv2.x, b[0] * uv0.y + b[1] * uv1.y + b[2] * uv2.y);
}

// Bilinear corner weights approximating |cos| at the reference point over the spherical
// triangle (pbrt-v4): (0,0),(1,0) -> vertex 1, (0,1) -> vertex 0, (1,1) -> vertex 2.
// dir[i]: the unit directions from ctx.p to the vertices.
LU_INLINE void TriangleCosWeights(const Vec3f dir[3], const LightSampleContext &ctx, Float w[4]) {
    w[0] = w[1] = Max(Float(0.01), AbsDot(ctx.ns, dir[1]));
    w[2] = Max(Float(0.01), AbsDot(ctx.ns, dir[0]));
    w[3] = Max(Float(0.01), AbsDot(ctx.ns, dir[2]));
}
LU_INLINE void TriangleCosWeights(const TriangleData &t, const LightSampleContext &ctx, Float w[4]) {
    Vec3f dir[3] = {Normalize(t.p[0] - ctx.p), Normalize(t.p[1] - ctx.p), Normalize(t.p[2] - ctx.p)};
    TriangleCosWeights(dir, ctx, w);
}

LU_INLINE void TriangleDirections(const TriangleRef &t, const Vec3f &p, Vec3f dir[3]) {
    dir[0] = Normalize(t.p0 - p);
    dir[1] = Normalize(t.p1 - p);
    dir[2] = Normalize(t.p2 - p);
}

LU_INLINE Float TriangleSolidAngle(const TriangleData &t, const Vec3f &p) {
    return SphericalTriangleArea(Normalize(t.p[0] - p), Normalize(t.p[1] - p), Normalize(t.p[2] - p));
}

// Converts an area pdf at a sampled point to solid angle at ref; 0 if infinite.
LU_INLINE Float AreaToSolidAnglePDF(Float pdfA, const Vec3f &ref, const Vec3f &pLight, const Vec3f &nLight,
                                    const Vec3f &wi) {
    Float cos = AbsDot(nLight, wi);
    Float pdf = pdfA * DistanceSquared(ref, pLight) / cos;
    return IsFinite(pdf) ? pdf : 0;
}

LU_INLINE bool SampleTriangle(const SceneView &s, const Shape &shape, uint32_t prim, const LightSampleContext &ctx,
                              Vec2f u, ShapeSample *ss, bool wantUV = true) {
    const TriangleMesh &m = s.triangleMeshes[shape.index];
    TriangleRef t = GetTriangleRef(s, m, prim);
    Vec3f dir[3];   // shared by the solid angle, the cos weights and the spherical sampling
    TriangleDirections(t, ctx.p, dir);
    Float sa = SphericalTriangleArea(dir[0], dir[1], dir[2]);
    Float b[3];
    Float pdf = 0;   // each branch below sets it (initialized for GCC 12's -Wmaybe-uninitialized)
    bool spherical = sa >= MinSphericalSampleArea && sa <= MaxSphericalSampleArea;
    if (!spherical) {
        SampleUniformTriangle(u, &b[0], &b[1], &b[2]);
    } else {
        pdf = 1;
        if (ctx.ns != Vec3f(0, 0, 0)) {
            Float w[4];
            TriangleCosWeights(dir, ctx, w);
            u = SampleBilinear(u, w);
            pdf *= BilinearPDF(u, w);
        }
        Float triPDF;
        // A finite solid angle means no vertex coincides with ctx.p (else dir would be NaN).
        SampleSphericalTriangleDirs(t.p0, t.p1, t.p2, dir, sa, ctx.p, u, b, &triPDF);
        if (triPDF == 0) return false;
        pdf *= triPDF;
    }
    ss->p = t.p0 * b[0] + t.p1 * b[1] + t.p2 * b[2];
    TriangleNormalUV(s, m, t, b, &ss->n, wantUV ? &ss->uv : nullptr);
    Vec3f d = ss->p - ctx.p;
    if (LengthSquared(d) == 0) return false;
    if (!spherical) {
        Float area = 0.5f * Length(Cross(t.p1 - t.p0, t.p2 - t.p0));
        pdf = AreaToSolidAnglePDF(1 / area, ctx.p, ss->p, ss->n, Normalize(d));
    }
    ss->pdf = pdf;
    return pdf > 0;
}

LU_INLINE Float TrianglePDF(const SceneView &s, const Shape &shape, uint32_t prim, const LightSampleContext &ctx,
                            const Vec3f &wi, const Vec3f &pLight, const Vec3f &nLight) {
    const TriangleMesh &m = s.triangleMeshes[shape.index];
    TriangleRef t = GetTriangleRef(s, m, prim);
    Vec3f dir[3];
    TriangleDirections(t, ctx.p, dir);
    Float sa = SphericalTriangleArea(dir[0], dir[1], dir[2]);
    if (sa < MinSphericalSampleArea || sa > MaxSphericalSampleArea) {
        Float area = 0.5f * Length(Cross(t.p1 - t.p0, t.p2 - t.p0));
        return AreaToSolidAnglePDF(1 / area, ctx.p, pLight, nLight, wi);
    }
    Float pdf = 1 / sa;
    if (ctx.ns != Vec3f(0, 0, 0)) {
        Float w[4];
        TriangleCosWeights(dir, ctx, w);
        pdf *= BilinearPDF(InvertSphericalTriangleSampleDirs(dir, wi), w);
    }
    return pdf;
}

// sin and cos of x in one call where the math library has one (glibc's sincosf gives the same
// bits as sinf and cosf: checked on every third float in [0, 2 pi]).
LU_INLINE void SinCos(Float x, Float *s, Float *c) {
#if defined(__CUDA_ARCH__) || defined(__GLIBC__)
    sincosf(x, s, c);
#else
    *s = std::sin(x);
    *c = std::cos(x);
#endif
}

// t applied to the origin, i.e. t.ApplyPoint(Vec3f(0, 0, 0)) without the multiplications by 0.
LU_INLINE Vec3f TransformOrigin(const Transform &t) {
    Vec3f o(t.m.m[0][3], t.m.m[1][3], t.m.m[2][3]);
    Float w = t.m.m[3][3];
    return w == 1 ? o : o / w;
}

// True when ctx.p is inside (or on) the sphere, after pbrt-v4's offset of the reference point
// towards the center.
LU_INLINE bool InsideSphere(const Sphere &sp, const LightSampleContext &ctx, const Vec3f &pCenter) {
    Vec3f pOrigin = ctx.p;
    if (ctx.n != Vec3f(0, 0, 0)) pOrigin = OffsetRayOrigin(ctx.p, ctx.n, pCenter - ctx.p);
    return DistanceSquared(pOrigin, pCenter) <= Sqr(sp.radius);
}

// Sphere uv and normal at an object-space point on it.
LU_INLINE void SpherePointData(const Sphere &sp, const Vec3f &pObj, Vec3f *n, Vec2f *uv) {
    *n = Normalize(sp.renderFromObject.ApplyNormal(pObj));
    if (ReverseOrientation(sp.flipNormals, sp.renderFromObject)) *n = -*n;
    *uv = SphereUV(sp, pObj);
}

// Inside the sphere: uniform by area (pbrt-v4); on a partial sphere over what is left of it
// (z uniform in [zMin, zMax] and phi in [0, phiMax], Archimedes), where pbrt-v4 samples the
// whole sphere with the partial sphere's pdf. Outside: pbrt-v4's uniform sampling of the cone
// of directions the whole sphere subtends, with its pdf; on a partial sphere the point returned
// is the first one that exists along the sampled direction (the far side seen through the cut),
// and the sample fails where the direction misses the shape, where pbrt-v4 returns the cut-away
// point on the near side. Both keep pbrt-v4's PDF (SpherePDF) and make it the sampled density.
LU_INLINE bool SampleSphere(const Sphere &sp, const LightSampleContext &ctx, Vec2f u, ShapeSample *ss, bool wantUV = true) {
    Vec3f pCenter = TransformOrigin(sp.renderFromObject);
    bool partial = IsPartial(sp);
    if (InsideSphere(sp, ctx, pCenter)) {
        // Uniform area sampling, converted to solid angle.
        Vec3f pObj;
        if (!partial) {
            pObj = SampleUniformSphere(u) * sp.radius;
        } else {
            Float z = Lerp(u.x, sp.zMin, sp.zMax), rz = SafeSqrt(Sqr(sp.radius) - z * z), sinPhi, cosPhi;
            SinCos(u.y * sp.phiMax, &sinPhi, &cosPhi);
            pObj = Vec3f(rz * cosPhi, rz * sinPhi, z);
        }
        SpherePointData(sp, pObj, &ss->n, &ss->uv);
        ss->p = sp.renderFromObject.ApplyPoint(pObj);
        Vec3f d = ss->p - ctx.p;
        if (LengthSquared(d) == 0) return false;
        ss->pdf = AreaToSolidAnglePDF(1 / SphereArea(sp), ctx.p, ss->p, ss->n, Normalize(d));
        return ss->pdf > 0;
    }
    // Uniform sampling of the cone of directions subtended by the sphere.
    Float sinThetaMax = sp.radius / Distance(ctx.p, pCenter);
    Float sin2ThetaMax = sinThetaMax * sinThetaMax;
    Float cosThetaMax = SafeSqrt(1 - sin2ThetaMax);
    Float oneMinusCosThetaMax = 1 - cosThetaMax;
    Float cosTheta = (cosThetaMax - 1) * u.x + 1;
    Float sin2Theta = 1 - cosTheta * cosTheta;
    if (sin2ThetaMax < 0.00068523f /* sin^2(1.5 deg) */) {
        // Taylor expansion for small cones.
        sin2Theta = sin2ThetaMax * u.x;
        cosTheta = std::sqrt(1 - sin2Theta);
        oneMinusCosThetaMax = sin2ThetaMax / 2;
    }
    // Angle alpha from the center to the sampled point, seen from the sphere center.
    Float cosAlpha = sin2Theta / sinThetaMax + cosTheta * SafeSqrt(1 - sin2Theta / Sqr(sinThetaMax));
    Float sinAlpha = SafeSqrt(1 - Sqr(cosAlpha));
    Float phi = u.y * 2 * Pi;
    Float sinPhi, cosPhi;   // SphericalDirection(sinAlpha, cosAlpha, phi) with one sincosf
    SinCos(phi, &sinPhi, &cosPhi);
    Float sinA = Clamp(sinAlpha, Float(-1), Float(1));
    Vec3f w(sinA * cosPhi, sinA * sinPhi, Clamp(cosAlpha, Float(-1), Float(1)));
    Frame frame = Frame::FromZ(Normalize(pCenter - ctx.p));
    Vec3f nOut = frame.FromLocal(-w);
    ss->p = pCenter + nOut * sp.radius;
    Vec3f pObj;
    if (partial) {
        pObj = sp.renderFromObject.Inverted().ApplyPoint(ss->p);
        if (SphereClipped(sp, pObj.x, pObj.y, pObj.z)) {
            // The near point is cut away: the far end of the chord along the sampled direction.
            Vec3f wi = Normalize(ss->p - ctx.p);
            ss->p = ss->p + wi * (2 * Dot(pCenter - ss->p, wi));
            nOut = Normalize(ss->p - pCenter);
            pObj = sp.renderFromObject.Inverted().ApplyPoint(ss->p);
            if (SphereClipped(sp, pObj.x, pObj.y, pObj.z)) return false;
        }
    }
    ss->n = ReverseOrientation(sp.flipNormals, sp.renderFromObject) ? -nOut : nOut;
    if (wantUV) {
        if (!partial) pObj = sp.renderFromObject.Inverted().ApplyPoint(ss->p);
        ss->uv = SphereUV(sp, pObj);
    }
    ss->pdf = 1 / (2 * Pi * oneMinusCosThetaMax);
    return oneMinusCosThetaMax > 0;
}

LU_INLINE Float SpherePDF(const Sphere &sp, const LightSampleContext &ctx, const Vec3f &wi, const Vec3f &pLight,
                          const Vec3f &nLight) {
    Vec3f pCenter = TransformOrigin(sp.renderFromObject);
    if (InsideSphere(sp, ctx, pCenter))
        return AreaToSolidAnglePDF(1 / SphereArea(sp), ctx.p, pLight, nLight, wi);
    Float sin2ThetaMax = Sqr(sp.radius) / DistanceSquared(ctx.p, pCenter);
    Float oneMinusCosThetaMax = 1 - SafeSqrt(1 - sin2ThetaMax);
    if (sin2ThetaMax < 0.00068523f) oneMinusCosThetaMax = sin2ThetaMax / 2;
    return 1 / (2 * Pi * oneMinusCosThetaMax);
}

// pbrt-v4 samples the full disk of the outer radius (the inner hole and, for phimax < 360, the
// cut-away sector included) with pdf 1 / Area(). A full disk does the same here for parity; a
// partial one samples its annular sector uniformly (r^2 uniform in [ri^2, r^2], phi in
// [0, phiMax]), which is the density 1 / Area() that pbrt-v4's PDF assumes.
LU_INLINE bool SampleDisk(const Disk &dk, const LightSampleContext &ctx, Vec2f u, ShapeSample *ss) {
    Vec3f pObj;
    if (dk.phiMax >= 2 * Pi) {
        Vec2f pd = SampleUniformDiskConcentric(u);
        pObj = Vec3f(pd.x * dk.radius, pd.y * dk.radius, dk.height);
    } else {
        Float rr = std::sqrt(Lerp(u.x, Sqr(dk.innerRadius), Sqr(dk.radius))), sinPhi, cosPhi;
        SinCos(u.y * dk.phiMax, &sinPhi, &cosPhi);
        pObj = Vec3f(rr * cosPhi, rr * sinPhi, dk.height);
    }
    ss->p = dk.renderFromObject.ApplyPoint(pObj);
    ss->n = Normalize(dk.renderFromObject.ApplyNormal(Vec3f(0, 0, 1)));
    if (ReverseOrientation(dk.flipNormals, dk.renderFromObject)) ss->n = -ss->n;
    Float dist = std::sqrt(pObj.x * pObj.x + pObj.y * pObj.y);
    Float rr = dk.radius - dk.innerRadius;
    ss->uv = Vec2f(PhiOf(pObj.x, pObj.y) / dk.phiMax, rr > 0 ? (dk.radius - dist) / rr : 0);
    Vec3f d = ss->p - ctx.p;
    if (LengthSquared(d) == 0) return false;
    ss->pdf = AreaToSolidAnglePDF(1 / DiskArea(dk), ctx.p, ss->p, ss->n, Normalize(d));
    return ss->pdf > 0;
}

// pbrt-v4's Cylinder::Sample: uniform by area (z uniform in [zMin, zMax], phi in [0, phiMax]),
// converted to solid angle; the normal flipped by ReverseOrientation only.
LU_INLINE bool SampleCylinder(const Cylinder &cy, const LightSampleContext &ctx, Vec2f u, ShapeSample *ss) {
    Float z = Lerp(u.x, cy.zMin, cy.zMax), phi = u.y * cy.phiMax, sinPhi, cosPhi;
    SinCos(phi, &sinPhi, &cosPhi);
    Vec3f pObj(cy.radius * cosPhi, cy.radius * sinPhi, z);
    ss->p = cy.renderFromObject.ApplyPoint(pObj);
    ss->n = Normalize(cy.renderFromObject.ApplyNormal(Vec3f(pObj.x, pObj.y, 0)));
    if (ReverseOrientation(cy.flipNormals, cy.renderFromObject)) ss->n = -ss->n;
    Float h = cy.zMax - cy.zMin;
    ss->uv = Vec2f(u.y, h > 0 ? (z - cy.zMin) / h : 0);
    Vec3f d = ss->p - ctx.p;
    if (LengthSquared(d) == 0) return false;
    ss->pdf = AreaToSolidAnglePDF(1 / CylinderArea(cy), ctx.p, ss->p, ss->n, Normalize(d));
    return ss->pdf > 0;
}

// pbrt-v4's BilinearPatch::Sample for a patch that is not a rectangle (rectangles and other
// parallelograms are triangle pairs here): (u, v) by SampleBilinear with the corners' area
// elements as weights, area pdf BilinearPDF / |dp/du x dp/dv|, converted to solid angle; the
// normal flipped as the hit's (by the interpolated vertex normal when the mesh has them).
LU_INLINE bool SampleBilinearPatchShape(const SceneView &s, const Shape &shape, uint32_t prim,
                                        const LightSampleContext &ctx, Vec2f u, ShapeSample *ss) {
    const BilinearMesh &m = s.bilinearMeshes[shape.index];
    uint32_t v[4];
    PatchVertices(m, s, prim, v);
    PatchCorners c = PatchPositions(s, v);
    Float w[4];
    PatchCornerWeights(c, w);
    Vec2f uv = SampleBilinear(u, w);
    Vec3f n = Cross(PatchDpdu(c, uv.y), PatchDpdv(c, uv.x));
    Float dA = Length(n);
    if (!(dA > 0)) return false;
    n = n / dA;
    if (m.flipNormals) n = -n;
    if (m.normalOffset != NoIndex) {
        Vec3f ns = PatchShadingNormal(s, m, v, nullptr, uv.x, uv.y);
        if (LengthSquared(ns) > 0) n = FaceForward(n, ns);
    }
    ss->p = PatchPoint(c, uv.x, uv.y);
    ss->n = n;
    Vec3f dpds, dpdt;
    ss->uv = PatchTextureFrame(s, m, v, c, uv.x, uv.y, &dpds, &dpdt);
    Vec3f d = ss->p - ctx.p;
    if (LengthSquared(d) == 0) return false;
    ss->pdf = AreaToSolidAnglePDF(BilinearPDF(uv, w) / dA, ctx.p, ss->p, ss->n, Normalize(d));
    return ss->pdf > 0;
}

LU_INLINE Float BilinearPatchShapePDF(const SceneView &s, const Shape &shape, uint32_t prim,
                                      const LightSampleContext &ctx, const Vec3f &wi, const Vec3f &pLight,
                                      const Vec3f &nLight) {
    uint32_t v[4];
    PatchVertices(s.bilinearMeshes[shape.index], s, prim, v);
    PatchCorners c = PatchPositions(s, v);
    return AreaToSolidAnglePDF(PatchAreaPDF(c, InvertBilinearPatch(c, pLight)), ctx.p, pLight, nLight, wi);
}

// Samples primitive `prim` of `shape` from ctx. Returns false (and no sample) on failure.
// wantUV = false leaves ss->uv unset where computing it costs (the cone-sampled sphere); the
// area lights' emission depends on uv only through an alpha texture or an image (SampleLi asks
// for it then).
LU_INLINE bool SampleShape(const SceneView &s, const Shape &shape, uint32_t prim, const LightSampleContext &ctx,
                           Vec2f u, ShapeSample *ss, bool wantUV = true) {
    switch (shape.kind) {
    case ShapeKind::Triangles: return SampleTriangle(s, shape, prim, ctx, u, ss, wantUV);
    case ShapeKind::Sphere: return SampleSphere(s.spheres[shape.index], ctx, u, ss, wantUV);
    case ShapeKind::Disk: return SampleDisk(s.disks[shape.index], ctx, u, ss);
    case ShapeKind::Cylinder: return SampleCylinder(s.cylinders[shape.index], ctx, u, ss);
    case ShapeKind::BilinearPatches: return SampleBilinearPatchShape(s, shape, prim, ctx, u, ss);
    case ShapeKind::Curves: return false;
    }
    return false;
}

// Solid-angle pdf at ctx.p of SampleShape producing direction wi (unit), which hits the shape
// at pLight with geometric normal nLight.
LU_INLINE Float ShapePDF(const SceneView &s, const Shape &shape, uint32_t prim, const LightSampleContext &ctx,
                         const Vec3f &wi, const Vec3f &pLight, const Vec3f &nLight) {
    switch (shape.kind) {
    case ShapeKind::Triangles: return TrianglePDF(s, shape, prim, ctx, wi, pLight, nLight);
    case ShapeKind::Sphere: return SpherePDF(s.spheres[shape.index], ctx, wi, pLight, nLight);
    case ShapeKind::Disk: return AreaToSolidAnglePDF(1 / DiskArea(s.disks[shape.index]), ctx.p, pLight, nLight, wi);
    case ShapeKind::Cylinder:
        return AreaToSolidAnglePDF(1 / CylinderArea(s.cylinders[shape.index]), ctx.p, pLight, nLight, wi);
    case ShapeKind::BilinearPatches: return BilinearPatchShapePDF(s, shape, prim, ctx, wi, pLight, nLight);
    case ShapeKind::Curves: return 0;
    }
    return 0;
}

}  // namespace lu
