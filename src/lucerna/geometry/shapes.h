// Lucerna: ray-shape intersection and hit reconstruction for triangles, spheres, disks and
// cylinders, partial ones included (host and device). Conventions follow pbrt-v4's
// Triangle/Sphere/Disk/Cylinder: the geometric normal is
// flipped by ReverseOrientation XOR handedness swap, and for meshes with shading normals it is
// made to face the shading normal (pbrt-v4's "orientation is authoritative").
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"
#include "lucerna/geometry/bilinear_patch.h"
#include "lucerna/geometry/curve.h"

namespace lu {

// Watertight ray-triangle intersection (Woop, Benthin, Wald 2013). On a hit in (0, tMax) returns
// t and the barycentrics b1, b2 of p1 and p2.
LU_INLINE bool IntersectTriangle(const Vec3f &p0, const Vec3f &p1, const Vec3f &p2, const Ray &ray, Float tMax,
                                 Float *tOut, Float *b1Out, Float *b2Out) {
    Vec3f ad = Abs(ray.d);
    int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
    int kx = kz + 1 == 3 ? 0 : kz + 1;
    int ky = kx + 1 == 3 ? 0 : kx + 1;
    Vec3f d(ray.d[kx], ray.d[ky], ray.d[kz]);
    Vec3f a = p0 - ray.o, b = p1 - ray.o, c = p2 - ray.o;
    a = Vec3f(a[kx], a[ky], a[kz]);
    b = Vec3f(b[kx], b[ky], b[kz]);
    c = Vec3f(c[kx], c[ky], c[kz]);
    Float sz = 1 / d.z, sx = -d.x * sz, sy = -d.y * sz;
    a.x += sx * a.z; a.y += sy * a.z;
    b.x += sx * b.z; b.y += sy * b.z;
    c.x += sx * c.z; c.y += sy * c.z;
    Float e0 = b.x * c.y - b.y * c.x;
    Float e1 = c.x * a.y - c.y * a.x;
    Float e2 = a.x * b.y - a.y * b.x;
    if (e0 == 0 || e1 == 0 || e2 == 0) {  // fall back to double on edges
        e0 = Float(double(b.x) * c.y - double(b.y) * c.x);
        e1 = Float(double(c.x) * a.y - double(c.y) * a.x);
        e2 = Float(double(a.x) * b.y - double(a.y) * b.x);
    }
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return false;
    Float det = e0 + e1 + e2;
    if (det == 0) return false;
    a.z *= sz; b.z *= sz; c.z *= sz;
    Float tScaled = e0 * a.z + e1 * b.z + e2 * c.z;
    if (det < 0 && (tScaled >= 0 || tScaled < tMax * det)) return false;
    if (det > 0 && (tScaled <= 0 || tScaled > tMax * det)) return false;
    Float invDet = 1 / det;
    Float t = tScaled * invDet;
    if (!(t > 0 && t < tMax)) return false;
    *tOut = t;
    *b1Out = e1 * invDet;
    *b2Out = e2 * invDet;
    return true;
}

// ---- Quadrics (pbrt-v4's Sphere, Disk and Cylinder) ----

// Object-space areas, as pbrt-v4's Area(): phiMax r (zMax - zMin), phiMax (r^2 - ri^2) / 2 and
// (zMax - zMin) r phiMax.
LU_INLINE Float SphereArea(const Sphere &sp) {
    return sp.phiMax * sp.radius * (Min(sp.zMax, sp.radius) - Max(sp.zMin, -sp.radius));
}
LU_INLINE Float DiskArea(const Disk &dk) { return Float(0.5) * dk.phiMax * (Sqr(dk.radius) - Sqr(dk.innerRadius)); }
LU_INLINE Float CylinderArea(const Cylinder &cy) { return (cy.zMax - cy.zMin) * cy.radius * cy.phiMax; }

// phi = atan2(y, x) in [0, 2 pi).
LU_INLINE Float PhiOf(Float x, Float y) {
    Float phi = std::atan2(y, x);
    return phi < 0 ? phi + 2 * Pi : phi;
}

// pbrt-v4's clip test of a partial sphere at an object-space point on it (true: cut away).
LU_INLINE bool SphereClipped(const Sphere &sp, double x, double y, double z) {
    if ((sp.zMin > -sp.radius && z < sp.zMin) || (sp.zMax < sp.radius && z > sp.zMax)) return true;
    if (sp.phiMax >= 2 * Pi) return false;
    if (x == 0 && y == 0) x = 1e-5 * sp.radius;   // pbrt-v4's phi at the poles
    return PhiOf(Float(x), Float(y)) > sp.phiMax;
}

// Sphere of radius r at the object origin. The ray is transformed to object space (t is
// preserved because the direction is not renormalized). Solved in double for robustness. A
// partial sphere's near root, when cut away, gives way to the far one (pbrt-v4).
// farSide: the far root only, when the near one is the hit found without it (the ray continued
// after an alpha-ignored near hit, geometry/alpha.h); false when the hit found was the far one.
LU_INLINE bool IntersectSphere(const Sphere &s, const Ray &ray, Float tMax, Float *tHit, bool farSide = false) {
    Vec3f o = s.renderFromObject.Inverted().ApplyPoint(ray.o);
    Vec3f d = s.renderFromObject.Inverted().ApplyVector(ray.d);
    double a = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    double b = 2 * (double(d.x) * o.x + double(d.y) * o.y + double(d.z) * o.z);
    // c = |o|^2 - r^2, with the "robust quadratic" discriminant of pbrt-v4 (Hearn-Baker).
    double c = double(o.x) * o.x + double(o.y) * o.y + double(o.z) * o.z - double(s.radius) * s.radius;
    double fx = o.x - b / (2 * a) * d.x, fy = o.y - b / (2 * a) * d.y, fz = o.z - b / (2 * a) * d.z;
    double len = std::sqrt(fx * fx + fy * fy + fz * fz);
    double disc = 4 * a * (double(s.radius) + len) * (double(s.radius) - len);
    if (disc < 0) return false;
    double root = std::sqrt(disc);
    double q = b < 0 ? -0.5 * (b - root) : -0.5 * (b + root);
    double t0 = q / a, t1 = c / q;
    if (t0 > t1) { double t = t0; t0 = t1; t1 = t; }
    // Reject hits too close to the origin relative to the sphere size (self-intersection guard).
    double eps = 1e-6 * double(s.radius) / std::sqrt(a);
    // A root is a hit when in (eps, tMax) and not on a cut-away part of a partial sphere.
    auto isHit = [&](double t) {
        if (!(t > eps && t < tMax)) return false;
        if (!IsPartial(s)) return true;
        double px = o.x + t * d.x, py = o.y + t * d.y, pz = o.z + t * d.z;
        double k = s.radius / std::sqrt(px * px + py * py + pz * pz);   // onto the surface
        return !SphereClipped(s, px * k, py * k, pz * k);
    };
    bool nearHit = isHit(t0);
    if (farSide && !nearHit) return false;   // the hit found without farSide was already the far root
    double t = nearHit && !farSide ? t0 : t1;
    if (t == t1 && !isHit(t1)) return false;
    *tHit = Float(t);
    return true;
}

// Disk at z = height in object space between the inner radius and the radius, phi <= phiMax.
LU_INLINE bool IntersectDisk(const Disk &dk, const Ray &ray, Float tMax, Float *tHit) {
    Vec3f o = dk.renderFromObject.Inverted().ApplyPoint(ray.o);
    Vec3f d = dk.renderFromObject.Inverted().ApplyVector(ray.d);
    if (d.z == 0) return false;
    Float t = (dk.height - o.z) / d.z;
    if (!(t > 0 && t < tMax)) return false;
    Float px = o.x + t * d.x, py = o.y + t * d.y;
    Float r2 = px * px + py * py;
    if (r2 > dk.radius * dk.radius || r2 < dk.innerRadius * dk.innerRadius) return false;
    if (dk.phiMax < 2 * Pi && PhiOf(px, py) > dk.phiMax) return false;
    *tHit = t;
    return true;
}

// Cylinder x^2 + y^2 = r^2, zMin <= z <= zMax, phi <= phiMax in object space (pbrt-v4's
// Cylinder::BasicIntersect, in double as the sphere): the near root, else the far one. farSide:
// as the sphere's.
LU_INLINE bool IntersectCylinder(const Cylinder &cy, const Ray &ray, Float tMax, Float *tHit, bool farSide = false) {
    Vec3f o = cy.renderFromObject.Inverted().ApplyPoint(ray.o);
    Vec3f d = cy.renderFromObject.Inverted().ApplyVector(ray.d);
    double a = double(d.x) * d.x + double(d.y) * d.y;
    if (!(a > 0)) return false;   // parallel to the axis
    double b = 2 * (double(d.x) * o.x + double(d.y) * o.y);
    double c = double(o.x) * o.x + double(o.y) * o.y - double(cy.radius) * cy.radius;
    double fx = o.x - b / (2 * a) * d.x, fy = o.y - b / (2 * a) * d.y;
    double len = std::sqrt(fx * fx + fy * fy);
    double disc = 4 * a * (double(cy.radius) + len) * (double(cy.radius) - len);
    if (disc < 0) return false;
    double root = std::sqrt(disc);
    double q = b < 0 ? -0.5 * (b - root) : -0.5 * (b + root);
    if (q == 0) return false;
    double t0 = q / a, t1 = c / q;
    if (t0 > t1) { double t = t0; t0 = t1; t1 = t; }
    double eps = 1e-6 * double(cy.radius) / std::sqrt(a);   // as the sphere's, in radial distance
    auto isHit = [&](double t) {
        if (!(t > eps && t < tMax)) return false;
        double px = o.x + t * d.x, py = o.y + t * d.y, pz = o.z + t * d.z;
        return !(pz < cy.zMin || pz > cy.zMax || (cy.phiMax < 2 * Pi && PhiOf(Float(px), Float(py)) > cy.phiMax));
    };
    bool nearHit = isHit(t0);
    if (farSide && !nearHit) return false;   // the hit found without farSide was already the far root
    double t = nearHit && !farSide ? t0 : t1;
    if (t == t1 && !isHit(t1)) return false;
    *tHit = Float(t);
    return true;
}

// Intersects one analytic shape (sphere, disk, cylinder) in (0, tMax); false for triangles.
LU_INLINE bool IntersectQuadric(const SceneView &s, const Shape &shape, const Ray &ray, Float tMax, Float *tHit) {
    switch (shape.kind) {
    case ShapeKind::Sphere: return IntersectSphere(s.spheres[shape.index], ray, tMax, tHit);
    case ShapeKind::Disk: return IntersectDisk(s.disks[shape.index], ray, tMax, tHit);
    case ShapeKind::Cylinder: return IntersectCylinder(s.cylinders[shape.index], ray, tMax, tHit);
    case ShapeKind::Triangles:
    case ShapeKind::BilinearPatches:
    case ShapeKind::Curves: break;
    }
    return false;
}

// Quadrics: one primitive per shape, hits carry t only (their far side matters to alpha).
LU_INLINE bool IsQuadric(ShapeKind k) {
    return k == ShapeKind::Sphere || k == ShapeKind::Disk || k == ShapeKind::Cylinder;
}

// Intersects primitive prim of a bilinear patch mesh or a curve set in (0, tMax): t and the
// primitive's (u, v) in (b1, b2), which ComputeInteraction reads back. ray is in the space the
// shape is stored in (a prototype's object space for instanced shapes).
LU_INLINE bool IntersectPatchOrCurve(const SceneView &s, const Shape &shape, uint32_t prim, const Ray &ray, Float tMax,
                                     Float *t, Float *b1, Float *b2) {
    if (shape.kind == ShapeKind::BilinearPatches) {
        const BilinearMesh &m = s.bilinearMeshes[shape.index];
        uint32_t v[4];
        PatchVertices(m, s, prim, v);
        return IntersectBilinearPatch(PatchPositions(s, v), ray, tMax, t, b1, b2);
    }
    if (shape.kind == ShapeKind::Curves) return IntersectCurve(s, s.curveSets[shape.index], prim, ray, tMax, t, b1, b2);
    return false;
}

// pbrt-v4's (u, v) of a (partial) sphere at an object-space point on it: u = phi / phiMax,
// v = (theta - thetaZMin) / (thetaZMax - thetaZMin) (1 - theta / pi on the full sphere).
LU_INLINE Vec2f SphereUV(const Sphere &sp, Vec3f pObj) {
    if (pObj.x == 0 && pObj.y == 0) pObj.x = 1e-5f * sp.radius;
    Float theta = SafeACos(pObj.z / sp.radius);
    return Vec2f(PhiOf(pObj.x, pObj.y) / sp.phiMax, (theta - sp.thetaZMin) / (sp.thetaZMax - sp.thetaZMin));
}

// Vertex access for triangle `prim` of mesh m.
LU_INLINE void TriangleVertices(const SceneView &s, const TriangleMesh &m, uint32_t prim, uint32_t v[3]) {
    const uint32_t *idx = s.indices.ptr + m.firstIndex + 3 * prim;
    v[0] = m.firstVertex + idx[0];
    v[1] = m.firstVertex + idx[1];
    v[2] = m.firstVertex + idx[2];
}

// A triangle's vertex positions and (when the mesh has them) vertex normals in render space: a
// prototype's through the instance it is seen in (normals by the inverse transpose), else as stored.
LU_INLINE void TriangleRenderPositions(const SceneView &s, const uint32_t v[3], const Instance *inst, Vec3f p[3]) {
    for (int i = 0; i < 3; ++i) p[i] = inst ? InstancePoint(inst->renderFromInstance, s.positions[v[i]]) : s.positions[v[i]];
}
LU_INLINE void TriangleRenderNormals(const SceneView &s, const TriangleMesh &m, const uint32_t v[3], const Instance *inst,
                                     Vec3f n[3]) {
    for (int i = 0; i < 3; ++i) {
        n[i] = s.normals[m.normalOffset + (v[i] - m.firstVertex)];
        if (inst) n[i] = InstanceNormal(inst->instanceFromRender, n[i]);
    }
}
LU_INLINE const Instance *InstanceOf(const SceneView &s, uint32_t instance) {
    return instance != NoIndex ? &s.instances[instance] : nullptr;
}

// A bilinear patch's corners (p00, p10, p01, p11) in render space: a prototype's through its instance.
LU_INLINE PatchCorners PatchRenderCorners(const SceneView &s, const uint32_t v[4], const Instance *inst) {
    PatchCorners c = PatchPositions(s, v);
    if (inst) {
        c.p00 = InstancePoint(inst->renderFromInstance, c.p00);
        c.p10 = InstancePoint(inst->renderFromInstance, c.p10);
        c.p01 = InstancePoint(inst->renderFromInstance, c.p01);
        c.p11 = InstancePoint(inst->renderFromInstance, c.p11);
    }
    return c;
}

// The texture (s, t) of a patch at (u, v) and dp/ds, dp/dt: pbrt-v4's BilinearPatch with "uv"
// (the (u, v) partials re-expressed in the texture coordinates, dp/dt turned to keep the
// orientation of dp/du x dp/dv); without "uv", (s, t) = (u, v).
LU_INLINE Vec2f PatchTextureFrame(const SceneView &s, const BilinearMesh &m, const uint32_t v[4], const PatchCorners &c,
                                  Float u, Float w, Vec3f *dpds, Vec3f *dpdt) {
    Vec3f dpdu = PatchDpdu(c, w), dpdv = PatchDpdv(c, u);
    *dpds = dpdu;
    *dpdt = dpdv;
    if (m.uvOffset == NoIndex) return Vec2f(u, w);
    Vec2f t[4];
    for (int k = 0; k < 4; ++k) t[k] = s.uvs[m.uvOffset + (v[k] - m.firstVertex)];
    Vec2f uv((t[0].x * (1 - u) + t[1].x * u) * (1 - w) + (t[2].x * (1 - u) + t[3].x * u) * w,
             (t[0].y * (1 - u) + t[1].y * u) * (1 - w) + (t[2].y * (1 - u) + t[3].y * u) * w);
    Vec2f dUVdu((t[1].x - t[0].x) * (1 - w) + (t[3].x - t[2].x) * w, (t[1].y - t[0].y) * (1 - w) + (t[3].y - t[2].y) * w);
    Vec2f dUVdv((t[2].x - t[0].x) * (1 - u) + (t[3].x - t[1].x) * u, (t[2].y - t[0].y) * (1 - u) + (t[3].y - t[1].y) * u);
    Float det = dUVdu.x * dUVdv.y - dUVdu.y * dUVdv.x;
    if (std::abs(det) > 1e-12f) {
        Vec3f ps = (dpdu * dUVdv.y - dpdv * dUVdu.y) / det;
        Vec3f pt = (dpdv * dUVdu.x - dpdu * dUVdv.x) / det;
        if (LengthSquared(Cross(ps, pt)) > 0) {
            if (Dot(Cross(ps, pt), Cross(dpdu, dpdv)) < 0) pt = -pt;
            *dpds = ps;
            *dpdt = pt;
        }
    }
    return uv;
}

// The interpolated vertex normal of a patch (render space, unnormalized).
LU_INLINE Vec3f PatchShadingNormal(const SceneView &s, const BilinearMesh &m, const uint32_t v[4], const Instance *inst,
                                   Float u, Float w) {
    Vec3f n[4];
    for (int k = 0; k < 4; ++k) {
        n[k] = s.normals[m.normalOffset + (v[k] - m.firstVertex)];
        if (inst) n[k] = InstanceNormal(inst->instanceFromRender, n[k]);
    }
    return (n[0] * (1 - u) + n[1] * u) * (1 - w) + (n[2] * (1 - u) + n[3] * u) * w;
}

// Builds the SurfaceInteraction for a hit found by any backend. A hit on an instance's shape
// (hit.instance set; the shape is a prototype's, in object space) is reconstructed in render
// space as the flattened copy would be: triangle vertices and shading normals mapped first,
// analytic shapes through the product transform; the ray and t are the render-space ones.
LU_INLINE SurfaceInteraction ComputeInteraction(const SceneView &s, const HitRecord &hit, const Ray &ray) {
    SurfaceInteraction si;
    const Shape &shape = s.shapes[hit.shape];
    const Instance *inst = InstanceOf(s, hit.instance);
    si.shape = hit.shape;
    si.primitive = hit.primitive;
    si.instance = hit.instance;
    si.material = shape.material;
    si.areaLight = shape.areaLight == NoIndex ? NoIndex : shape.areaLight + hit.primitive;
    si.wo = -Normalize(ray.d);
    switch (shape.kind) {
    case ShapeKind::Triangles: {
        const TriangleMesh &m = s.triangleMeshes[shape.index];
        uint32_t v[3];
        TriangleVertices(s, m, hit.primitive, v);
        Vec3f pv[3];
        TriangleRenderPositions(s, v, inst, pv);
        Vec3f p0 = pv[0], p1 = pv[1], p2 = pv[2];
        Float b1 = hit.b1, b2 = hit.b2, b0 = 1 - b1 - b2;
        si.p = p0 * b0 + p1 * b1 + p2 * b2;
        Vec2f uv0(0, 0), uv1(1, 0), uv2(1, 1);
        if (m.uvOffset != NoIndex) {
            uv0 = s.uvs[m.uvOffset + (v[0] - m.firstVertex)];
            uv1 = s.uvs[m.uvOffset + (v[1] - m.firstVertex)];
            uv2 = s.uvs[m.uvOffset + (v[2] - m.firstVertex)];
        }
        si.uv = Vec2f(b0 * uv0.x + b1 * uv1.x + b2 * uv2.x, b0 * uv0.y + b1 * uv1.y + b2 * uv2.y);
        // dpdu from the uv parameterization (pbrt-v4 Triangle), falling back to an edge.
        Vec2f duv02 = uv0 - uv2, duv12 = uv1 - uv2;
        Vec3f dp02 = p0 - p2, dp12 = p1 - p2;
        Float det = duv02.x * duv12.y - duv02.y * duv12.x;
        Vec3f n = Cross(dp02, dp12);
        Float nl = Length(n);
        n = nl > 0 ? n / nl : Vec3f(0, 0, 1);
        if (std::abs(det) > 1e-9f) si.dpdu = (dp02 * duv12.y - dp12 * duv02.y) / det;
        else si.dpdu = dp02;
        if (m.flipNormals != (inst && inst->swapsHandedness)) n = -n;
        si.n = n;
        si.ns = n;
        if (m.normalOffset != NoIndex) {
            Vec3f nv[3];
            TriangleRenderNormals(s, m, v, inst, nv);
            Vec3f n0 = nv[0], n1 = nv[1], n2 = nv[2];
            Vec3f ns = n0 * b0 + n1 * b1 + n2 * b2;
            Float l2 = LengthSquared(ns);
            if (l2 > 0) {
                ns = ns / std::sqrt(l2);
                si.ns = ns;
                si.n = FaceForward(n, ns);
            }
        }
        break;
    }
    case ShapeKind::Sphere: {
        Sphere sp = s.spheres[shape.index];
        if (inst) sp.renderFromObject = InstanceTransform(*inst) * sp.renderFromObject;
        Vec3f pRender = ray(hit.t);
        Vec3f pObj = sp.renderFromObject.Inverted().ApplyPoint(pRender);
        pObj = pObj * (sp.radius / Length(pObj));  // reproject onto the surface
        si.p = sp.renderFromObject.ApplyPoint(pObj);
        si.uv = SphereUV(sp, pObj);
        Vec3f dpduObj(-sp.phiMax * pObj.y, sp.phiMax * pObj.x, 0);
        if (dpduObj.x == 0 && dpduObj.y == 0) dpduObj = Vec3f(1, 0, 0);
        si.dpdu = sp.renderFromObject.ApplyVector(dpduObj);
        Vec3f n = Normalize(sp.renderFromObject.ApplyNormal(pObj));
        if (sp.flipNormals) n = -n;
        si.n = si.ns = n;
        break;
    }
    case ShapeKind::Disk: {
        Disk dk = s.disks[shape.index];
        if (inst) dk.renderFromObject = InstanceTransform(*inst) * dk.renderFromObject;
        Vec3f pObj = dk.renderFromObject.Inverted().ApplyPoint(ray(hit.t));
        pObj.z = dk.height;
        si.p = dk.renderFromObject.ApplyPoint(pObj);
        Float dist = std::sqrt(pObj.x * pObj.x + pObj.y * pObj.y);
        Float rr = dk.radius - dk.innerRadius;
        si.uv = Vec2f(PhiOf(pObj.x, pObj.y) / dk.phiMax, rr > 0 ? (dk.radius - dist) / rr : 0);
        Vec3f dpduObj(-dk.phiMax * pObj.y, dk.phiMax * pObj.x, 0);
        if (dpduObj.x == 0 && dpduObj.y == 0) dpduObj = Vec3f(1, 0, 0);
        si.dpdu = dk.renderFromObject.ApplyVector(dpduObj);
        Vec3f n = Normalize(dk.renderFromObject.ApplyNormal(Vec3f(0, 0, 1)));
        if (dk.flipNormals) n = -n;
        si.n = si.ns = n;
        break;
    }
    case ShapeKind::Cylinder: {
        Cylinder cy = s.cylinders[shape.index];
        if (inst) cy.renderFromObject = InstanceTransform(*inst) * cy.renderFromObject;
        Vec3f pObj = cy.renderFromObject.Inverted().ApplyPoint(ray(hit.t));
        Float hitRad = std::sqrt(pObj.x * pObj.x + pObj.y * pObj.y);
        if (hitRad > 0) { pObj.x *= cy.radius / hitRad; pObj.y *= cy.radius / hitRad; }   // onto the surface
        si.p = cy.renderFromObject.ApplyPoint(pObj);
        Float h = cy.zMax - cy.zMin;
        si.uv = Vec2f(PhiOf(pObj.x, pObj.y) / cy.phiMax, h > 0 ? (pObj.z - cy.zMin) / h : 0);
        si.dpdu = cy.renderFromObject.ApplyVector(Vec3f(-cy.phiMax * pObj.y, cy.phiMax * pObj.x, 0));
        // pbrt-v4's Normalize(Cross(dpdu, dpdv)): outwards.
        Vec3f n = Normalize(cy.renderFromObject.ApplyNormal(Vec3f(pObj.x, pObj.y, 0)));
        if (cy.flipNormals) n = -n;
        si.n = si.ns = n;
        break;
    }
    case ShapeKind::BilinearPatches: {
        // pbrt-v4's BilinearPatch::InteractionFromIntersection; (u, v) from the hit.
        const BilinearMesh &m = s.bilinearMeshes[shape.index];
        uint32_t v[4];
        PatchVertices(m, s, hit.primitive, v);
        PatchCorners c = PatchRenderCorners(s, v, inst);
        Float u = hit.b1, w = hit.b2;
        si.p = PatchPoint(c, u, w);
        Vec3f dpds, dpdt;
        si.uv = PatchTextureFrame(s, m, v, c, u, w, &dpds, &dpdt);
        si.dpdu = dpds;
        Vec3f n = Cross(PatchDpdu(c, w), PatchDpdv(c, u));
        Float nl = Length(n);
        n = nl > 0 ? n / nl : Vec3f(0, 0, 1);
        if (m.flipNormals != (inst && inst->swapsHandedness)) n = -n;
        si.n = si.ns = n;
        if (m.normalOffset != NoIndex) {
            Vec3f ns = PatchShadingNormal(s, m, v, inst, u, w);
            Float l2 = LengthSquared(ns);
            if (l2 > 0) {
                si.ns = ns / std::sqrt(l2);
                si.n = FaceForward(n, si.ns);
            }
        }
        break;
    }
    case ShapeKind::Curves: {
        // pbrt-v4's Curve: the point at the curve's depth along the ray, (u, v) from the hit.
        CurveSet cs = s.curveSets[shape.index];
        if (inst) cs.renderFromObject = InstanceTransform(*inst) * cs.renderFromObject;
        const CurveSegment &seg = CurvePrimitiveSegment(s, cs, hit.primitive);
        Vec3f dpdu, dpdv;
        CurveFrame(cs, seg, hit.b1, hit.b2, cs.renderFromObject.Inverted().ApplyVector(ray.d), &dpdu, &dpdv);
        si.p = ray(hit.t);
        si.uv = Vec2f(hit.b1, hit.b2);
        si.dpdu = cs.renderFromObject.ApplyVector(dpdu);
        Vec3f n = cs.renderFromObject.ApplyNormal(Cross(dpdu, dpdv));
        Float nl = Length(n);
        n = nl > 0 ? n / nl : -Normalize(ray.d);
        if (cs.flipNormals) n = -n;
        si.n = si.ns = n;
        break;
    }
    }
    return si;
}

// Derivative of the unit shading normal along the tangent direction d (in the geometric plane):
// a sphere's d/R (sign by orientation), a cylinder's d across the axis / R, a mesh's interpolated vertex normal (its normalization
// included), zero otherwise. MNEE's chain derivatives and bump mapping's dndu/dndv use it.
LU_INLINE Vec3f ShadingNormalDerivative(const SceneView &scene, const HitRecord &hit, const SurfaceInteraction &si,
                                        const Vec3f &d) {
    const Shape &shape = scene.shapes[hit.shape];
    const Instance *inst = InstanceOf(scene, hit.instance);
    if (shape.kind == ShapeKind::Sphere) {
        Sphere sp = scene.spheres[shape.index];
        if (inst) sp.renderFromObject = InstanceTransform(*inst) * sp.renderFromObject;
        Float R = sp.radius * Length(sp.renderFromObject.ApplyVector(Vec3f(1, 0, 0)));
        Vec3f dn = d / R;
        return sp.flipNormals ? -dn : dn;
    }
    if (shape.kind == ShapeKind::Cylinder) {
        // n = (x, y, 0) / R: d's component along the axis leaves it unchanged.
        Cylinder cy = scene.cylinders[shape.index];
        if (inst) cy.renderFromObject = InstanceTransform(*inst) * cy.renderFromObject;
        Float R = cy.radius * Length(cy.renderFromObject.ApplyVector(Vec3f(1, 0, 0)));
        Vec3f axis = Normalize(cy.renderFromObject.ApplyVector(Vec3f(0, 0, 1)));
        Vec3f dn = (d - axis * Dot(axis, d)) / R;
        return cy.flipNormals ? -dn : dn;
    }
    if (shape.kind != ShapeKind::Triangles) return Vec3f(0, 0, 0);
    const TriangleMesh &m = scene.triangleMeshes[shape.index];
    if (m.normalOffset == NoIndex) return Vec3f(0, 0, 0);
    uint32_t v[3];
    TriangleVertices(scene, m, hit.primitive, v);
    Vec3f pv[3], nv[3];
    TriangleRenderPositions(scene, v, inst, pv);
    TriangleRenderNormals(scene, m, v, inst, nv);
    Vec3f e1 = pv[1] - pv[0], e2 = pv[2] - pv[0];
    Vec3f n0 = nv[0], n1 = nv[1], n2 = nv[2];
    // d = db1 e1 + db2 e2 (d lies in the triangle's plane): normal equations.
    Float g11 = Dot(e1, e1), g12 = Dot(e1, e2), g22 = Dot(e2, e2), det = g11 * g22 - g12 * g12;
    if (!(std::abs(det) > 0)) return Vec3f(0, 0, 0);
    Float r1 = Dot(e1, d), r2 = Dot(e2, d);
    Float db1 = (g22 * r1 - g12 * r2) / det, db2 = (g11 * r2 - g12 * r1) / det;
    Float b1 = hit.b1, b2 = hit.b2;
    Vec3f N = n0 * (1 - b1 - b2) + n1 * b1 + n2 * b2;
    Float len = Length(N);
    if (!(len > 0)) return Vec3f(0, 0, 0);
    Vec3f dN = (n1 - n0) * db1 + (n2 - n0) * db2;
    return (dN - si.ns * Dot(si.ns, dN)) / len;
}

// Barycentrics (b1, b2) of point p (in or near the triangle's plane) in triangle p0 p1 p2.
LU_INLINE void TriangleBarycentrics(const Vec3f &p0, const Vec3f &p1, const Vec3f &p2, const Vec3f &p, Float *b1,
                                    Float *b2) {
    Vec3f e1 = p1 - p0, e2 = p2 - p0, w = p - p0;
    Float g11 = Dot(e1, e1), g12 = Dot(e1, e2), g22 = Dot(e2, e2), det = g11 * g22 - g12 * g12;
    Float r1 = Dot(w, e1), r2 = Dot(w, e2);
    *b1 = det != 0 ? (g22 * r1 - g12 * r2) / det : 0;
    *b2 = det != 0 ? (g11 * r2 - g12 * r1) / det : 0;
}

// pbrt-v4's shading tangents of a mesh with vertex normals ns (triangles, bilinear patches):
// ts = ns x dpdu, ss = ts x ns; any frame around ns when dpdu is along it.
LU_INLINE void ShadingTangentsAround(const Vec3f &ns, ShadingDerivatives *d) {
    Vec3f ts = Cross(ns, d->dpdu);
    if (LengthSquared(ts) > 0) {
        d->dpdu = Cross(ts, ns);
        d->dpdv = ts;
    } else {
        CoordinateSystem(ns, &d->dpdu, &d->dpdv);
    }
}

// pbrt-v4's shading dpdu, dpdv (Triangle, Sphere, Disk, Cylinder InteractionFromIntersection) at the hit si
// and the derivatives of the unit shading normal along them (ShadingNormalDerivative; pbrt-v4
// differentiates a mesh's unnormalized interpolated normal and does not flip a reversed
// sphere's, which agree to first order in the displacement for unit vertex normals). Computed
// from si alone (a triangle's barycentrics from si.p), so that hits need not carry them.
LU_INLINE ShadingDerivatives ComputeShadingDerivatives(const SceneView &s, const SurfaceInteraction &si) {
    ShadingDerivatives d;
    const Shape &shape = s.shapes[si.shape];
    const Instance *inst = InstanceOf(s, si.instance);
    HitRecord hit;
    hit.shape = si.shape;
    hit.primitive = si.primitive;
    hit.instance = si.instance;
    switch (shape.kind) {
    case ShapeKind::Triangles: {
        const TriangleMesh &m = s.triangleMeshes[shape.index];
        uint32_t v[3];
        TriangleVertices(s, m, si.primitive, v);
        Vec3f pv[3];
        TriangleRenderPositions(s, v, inst, pv);
        Vec3f p0 = pv[0], p1 = pv[1], p2 = pv[2];
        Vec2f uv0(0, 0), uv1(1, 0), uv2(1, 1);
        if (m.uvOffset != NoIndex) {
            uv0 = s.uvs[m.uvOffset + (v[0] - m.firstVertex)];
            uv1 = s.uvs[m.uvOffset + (v[1] - m.firstVertex)];
            uv2 = s.uvs[m.uvOffset + (v[2] - m.firstVertex)];
        }
        Vec2f duv02 = uv0 - uv2, duv12 = uv1 - uv2;
        Vec3f dp02 = p0 - p2, dp12 = p1 - p2;
        Float det = duv02.x * duv12.y - duv02.y * duv12.x;
        bool degenerate = std::abs(det) < 1e-9f;
        if (!degenerate) {
            d.dpdu = (dp02 * duv12.y - dp12 * duv02.y) / det;
            d.dpdv = (dp12 * duv02.x - dp02 * duv12.x) / det;
        }
        if (degenerate || LengthSquared(Cross(d.dpdu, d.dpdv)) == 0) {
            Vec3f ng = Cross(p2 - p0, p1 - p0);
            if (LengthSquared(ng) == 0) return d;   // a degenerate triangle: no tangent plane
            CoordinateSystem(Normalize(ng), &d.dpdu, &d.dpdv);
        }
        if (m.normalOffset == NoIndex) return d;   // flat: dndu = dndv = 0
        TriangleBarycentrics(p0, p1, p2, si.p, &hit.b1, &hit.b2);
        d.dndu = ShadingNormalDerivative(s, hit, si, d.dpdu);
        d.dndv = ShadingNormalDerivative(s, hit, si, d.dpdv);
        ShadingTangentsAround(si.ns, &d);
        return d;
    }
    case ShapeKind::Sphere: {
        Sphere sp = s.spheres[shape.index];
        if (inst) sp.renderFromObject = InstanceTransform(*inst) * sp.renderFromObject;
        Vec3f pObj = sp.renderFromObject.Inverted().ApplyPoint(si.p);
        Float r = sp.radius, zRadius = std::sqrt(pObj.x * pObj.x + pObj.y * pObj.y);
        Float cosPhi = zRadius > 0 ? pObj.x / zRadius : 1, sinPhi = zRadius > 0 ? pObj.y / zRadius : 0;
        Float sinTheta = SafeSqrt(1 - Sqr(Clamp(pObj.z / r, Float(-1), Float(1))));
        Vec3f dpduObj(-sp.phiMax * pObj.y, sp.phiMax * pObj.x, 0);
        if (dpduObj.x == 0 && dpduObj.y == 0) dpduObj = Vec3f(1, 0, 0);
        // dp/dv = (thetaZMax - thetaZMin) (z cos phi, z sin phi, -r sin theta) (-pi on the full sphere).
        Vec3f dpdvObj = Vec3f(pObj.z * cosPhi, pObj.z * sinPhi, -r * sinTheta) * (sp.thetaZMax - sp.thetaZMin);
        d.dpdu = sp.renderFromObject.ApplyVector(dpduObj);
        d.dpdv = sp.renderFromObject.ApplyVector(dpdvObj);
        d.dndu = ShadingNormalDerivative(s, hit, si, d.dpdu);
        d.dndv = ShadingNormalDerivative(s, hit, si, d.dpdv);
        return d;
    }
    case ShapeKind::Disk: {
        Disk dk = s.disks[shape.index];
        if (inst) dk.renderFromObject = InstanceTransform(*inst) * dk.renderFromObject;
        Vec3f pObj = dk.renderFromObject.Inverted().ApplyPoint(si.p);
        Float rHit = std::sqrt(pObj.x * pObj.x + pObj.y * pObj.y);
        Vec3f dpduObj(-dk.phiMax * pObj.y, dk.phiMax * pObj.x, 0);
        if (dpduObj.x == 0 && dpduObj.y == 0) dpduObj = Vec3f(1, 0, 0);
        Vec3f radial = rHit > 0 ? Vec3f(pObj.x / rHit, pObj.y / rHit, 0) : Vec3f(1, 0, 0);
        d.dpdu = dk.renderFromObject.ApplyVector(dpduObj);
        d.dpdv = dk.renderFromObject.ApplyVector(radial * (dk.innerRadius - dk.radius));
        return d;   // flat: dndu = dndv = 0
    }
    case ShapeKind::Cylinder: {
        Cylinder cy = s.cylinders[shape.index];
        if (inst) cy.renderFromObject = InstanceTransform(*inst) * cy.renderFromObject;
        Vec3f pObj = cy.renderFromObject.Inverted().ApplyPoint(si.p);
        d.dpdu = cy.renderFromObject.ApplyVector(Vec3f(-cy.phiMax * pObj.y, cy.phiMax * pObj.x, 0));
        d.dpdv = cy.renderFromObject.ApplyVector(Vec3f(0, 0, cy.zMax - cy.zMin));
        d.dndu = ShadingNormalDerivative(s, hit, si, d.dpdu);   // dpdu / R (pbrt-v4's Weingarten equations)
        return d;                                               // dndv = 0
    }
    case ShapeKind::BilinearPatches: {
        const BilinearMesh &m = s.bilinearMeshes[shape.index];
        uint32_t v[4];
        PatchVertices(m, s, si.primitive, v);
        PatchCorners c = PatchRenderCorners(s, v, inst);
        Vec2f uv = InvertBilinearPatch(c, si.p);
        PatchTextureFrame(s, m, v, c, uv.x, uv.y, &d.dpdu, &d.dpdv);
        if (m.normalOffset == NoIndex) return d;   // dndu = dndv = 0, as the patch's own normal (pbrt-v4)
        // The unit shading normal's derivatives along dp/ds, dp/dt, through (u, v).
        Vec3f N = PatchShadingNormal(s, m, v, inst, uv.x, uv.y);
        Float len = Length(N);
        if (!(len > 0)) return d;
        constexpr Float h = 1e-3f;
        Float u0 = Min(uv.x, 1 - h), v0 = Min(uv.y, 1 - h);
        Vec3f dNdu = (PatchShadingNormal(s, m, v, inst, u0 + h, uv.y) - PatchShadingNormal(s, m, v, inst, u0, uv.y)) / h;
        Vec3f dNdv = (PatchShadingNormal(s, m, v, inst, uv.x, v0 + h) - PatchShadingNormal(s, m, v, inst, uv.x, v0)) / h;
        // d = a dpdu + b dpdv in the patch's tangent plane: dN along d = a dNdu + b dNdv.
        Vec3f pu = PatchDpdu(c, uv.y), pv = PatchDpdv(c, uv.x);
        Float g11 = Dot(pu, pu), g12 = Dot(pu, pv), g22 = Dot(pv, pv), det = g11 * g22 - g12 * g12;
        auto along = [&](const Vec3f &dir) {
            if (!(std::abs(det) > 0)) return Vec3f(0, 0, 0);
            Float r1 = Dot(pu, dir), r2 = Dot(pv, dir);
            Float a = (g22 * r1 - g12 * r2) / det, b = (g11 * r2 - g12 * r1) / det;
            Vec3f dN = dNdu * a + dNdv * b;
            return (dN - si.ns * Dot(si.ns, dN)) / len;
        };
        d.dndu = along(d.dpdu);
        d.dndv = along(d.dpdv);
        ShadingTangentsAround(si.ns, &d);
        return d;
    }
    case ShapeKind::Curves: {
        // pbrt-v4's curve partials; its dndu, dndv are zero.
        CurveSet cs = s.curveSets[shape.index];
        if (inst) cs.renderFromObject = InstanceTransform(*inst) * cs.renderFromObject;
        const CurveSegment &seg = CurvePrimitiveSegment(s, cs, si.primitive);
        Vec3f dpdu, dpdv;
        CurveFrame(cs, seg, si.uv.x, si.uv.y, cs.renderFromObject.Inverted().ApplyVector(-si.wo), &dpdu, &dpdv);
        d.dpdu = cs.renderFromObject.ApplyVector(dpdu);
        d.dpdv = cs.renderFromObject.ApplyVector(dpdv);
        return d;
    }
    }
    return d;
}

// Box of primitive prim of a bilinear patch mesh (its corners: the patch is in their convex
// hull) or of a curve set (the piece's object-space box, transformed), in the shape's space.
LU_INLINE Bounds3f PatchOrCurveBounds(const SceneView &s, const Shape &shape, uint32_t prim) {
    Bounds3f b;
    if (shape.kind == ShapeKind::BilinearPatches) {
        uint32_t v[4];
        PatchVertices(s.bilinearMeshes[shape.index], s, prim, v);
        for (int k = 0; k < 4; ++k) b.Expand(s.positions[v[k]]);
    } else if (shape.kind == ShapeKind::Curves) {
        const CurveSet &cs = s.curveSets[shape.index];
        Bounds3f o = CurvePieceObjectBounds(s, cs, prim);
        for (int i = 0; i < 8; ++i)
            b.Expand(cs.renderFromObject.ApplyPoint(Vec3f((i & 1) ? o.pMax.x : o.pMin.x, (i & 2) ? o.pMax.y : o.pMin.y,
                                                          (i & 4) ? o.pMax.z : o.pMin.z)));
    }
    return b;
}

// Surface area of one primitive (for light power and area sampling).
LU_INLINE Float PrimitiveArea(const SceneView &s, const Shape &shape, uint32_t prim) {
    switch (shape.kind) {
    case ShapeKind::Triangles: {
        const TriangleMesh &m = s.triangleMeshes[shape.index];
        uint32_t v[3];
        TriangleVertices(s, m, prim, v);
        return 0.5f * Length(Cross(s.positions[v[1]] - s.positions[v[0]], s.positions[v[2]] - s.positions[v[0]]));
    }
    case ShapeKind::Sphere: {
        // Exact for similarity transforms (uniform scale).
        const Sphere &sp = s.spheres[shape.index];
        Float sc = Length(sp.renderFromObject.ApplyVector(Vec3f(1, 0, 0)));
        return SphereArea(sp) * Sqr(sc);
    }
    case ShapeKind::Disk: {
        const Disk &dk = s.disks[shape.index];
        Float sc = Length(dk.renderFromObject.ApplyVector(Vec3f(1, 0, 0)));
        return DiskArea(dk) * Sqr(sc);
    }
    case ShapeKind::Cylinder: {
        const Cylinder &cy = s.cylinders[shape.index];
        Float sc = Length(cy.renderFromObject.ApplyVector(Vec3f(1, 0, 0)));
        return CylinderArea(cy) * Sqr(sc);
    }
    case ShapeKind::BilinearPatches: {
        uint32_t v[4];
        PatchVertices(s.bilinearMeshes[shape.index], s, prim, v);
        return BilinearPatchArea(PatchPositions(s, v));
    }
    case ShapeKind::Curves: return 0;   // not an emitter (scene/build_shapes.cpp refuses curve area lights)
    }
    return 0;
}

}  // namespace lu
