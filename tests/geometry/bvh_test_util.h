// Lucerna tests: generated scenes, ray sets and an Embree reference for the BVH tests
// (tests/geometry/bvh_test.cpp and the CPU/GPU agreement tests in tests/gpu). Header-only; the
// reference is the CPU backend's EmbreeScene.
#pragma once

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"
#include "lucerna/accel/bvh_build.h"
#include "lucerna/backend/cpu/embree_scene.h"
#include "lucerna/geometry/bvh_traverse.h"
#include "lucerna/geometry/shapes.h"
#include "lucerna/scene/builder.h"
#include "support/test_transforms.h"

namespace lu::test {

// ---- Deterministic random numbers (PCG32, O'Neill 2014) ----

struct Pcg32 {
    uint64_t state = 0x853c49e6748fea9bULL, inc = 0xda3e39cb94b95bdbULL;
    explicit Pcg32(uint64_t seed, uint64_t seq = 1) {
        state = 0;
        inc = (seq << 1u) | 1u;
        Next();
        state += seed;
        Next();
    }
    uint32_t Next() {
        uint64_t old = state;
        state = old * 6364136223846793005ULL + inc;
        uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
    }
    Float Uniform() { return Float(Next() >> 8) * 0x1p-24f; }
    Vec3f InBox(const Bounds3f &b) {
        Vec3f d = b.Diagonal();
        Float x = Uniform(), y = Uniform(), z = Uniform();
        return b.pMin + Vec3f(x * d.x, y * d.y, z * d.z);
    }
    Vec3f Direction() {
        Float z = 1 - 2 * Uniform();
        Float r = std::sqrt(Max(Float(0), 1 - z * z)), phi = 2 * Pi * Uniform();
        return Vec3f(r * std::cos(phi), r * std::sin(phi), z);
    }
};

// ---- A scene owning its arrays ----

// A HostScene filled shape by shape (bounds kept up to date); View() is HostScene's.
struct OwnedScene : HostScene {
    void AddMesh(const std::vector<Vec3f> &p, const std::vector<uint32_t> &idx) {
        TriangleMesh m;
        m.firstVertex = uint32_t(positions.size());
        m.vertexCount = uint32_t(p.size());
        m.firstIndex = uint32_t(indices.size());
        m.triangleCount = uint32_t(idx.size() / 3);
        positions.insert(positions.end(), p.begin(), p.end());
        indices.insert(indices.end(), idx.begin(), idx.end());
        for (const Vec3f &v : p) bounds.Expand(v);
        Shape s;
        s.kind = ShapeKind::Triangles;
        s.index = uint32_t(triangleMeshes.size());
        s.primitiveCount = m.triangleCount;
        triangleMeshes.push_back(m);
        shapes.push_back(s);
    }
    // A partial sphere when zmin > -radius, zmax < radius or phimax (degrees) < 360.
    void AddSphere(const Transform &renderFromObject, Float radius, Float zmin = -Infinity, Float zmax = Infinity,
                   Float phimax = 360) {
        Sphere sp;
        sp.renderFromObject = renderFromObject;
        sp.radius = radius;
        SetSphereClip(sp, zmin, zmax, phimax);
        Shape s;
        s.kind = ShapeKind::Sphere;
        s.index = uint32_t(spheres.size());
        spheres.push_back(sp);
        shapes.push_back(s);
        bounds.Expand(PrimitiveBounds(View(), uint32_t(shapes.size() - 1), 0));
    }
    void AddDisk(const Transform &renderFromObject, Float height, Float radius, Float innerRadius, Float phimax = 360) {
        Shape s;
        s.kind = ShapeKind::Disk;
        s.index = uint32_t(disks.size());
        disks.push_back(Disk{renderFromObject, height, radius, innerRadius, PhiMaxRadians(phimax)});
        shapes.push_back(s);
        bounds.Expand(PrimitiveBounds(View(), uint32_t(shapes.size() - 1), 0));
    }
    void AddCylinder(const Transform &renderFromObject, Float radius, Float zmin, Float zmax, Float phimax = 360) {
        Shape s;
        s.kind = ShapeKind::Cylinder;
        s.index = uint32_t(cylinders.size());
        cylinders.push_back(Cylinder{renderFromObject, radius, zmin, zmax, PhiMaxRadians(phimax)});
        shapes.push_back(s);
        bounds.Expand(PrimitiveBounds(View(), uint32_t(shapes.size() - 1), 0));
    }
};

// ---- Generated geometry ----

// Random triangles of random sizes (up to `maxSize`) in the unit cube.
inline void AddTriangleSoup(OwnedScene &s, int count, Float maxSize, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<Vec3f> p;
    std::vector<uint32_t> idx;
    for (int i = 0; i < count; ++i) {
        Vec3f c(rng.Uniform(), rng.Uniform(), rng.Uniform());
        Float size = maxSize * (0.05f + rng.Uniform());
        for (int k = 0; k < 3; ++k) {
            p.push_back(c + rng.Direction() * size);
            idx.push_back(uint32_t(p.size() - 1));
        }
    }
    s.AddMesh(p, idx);
}

// A closed UV sphere mesh (shared vertices, so rays hit shared edges and poles).
inline void AddSphereMesh(OwnedScene &s, Vec3f center, Float radius, int nu, int nv) {
    std::vector<Vec3f> p;
    std::vector<uint32_t> idx;
    for (int j = 0; j <= nv; ++j) {
        Float theta = Pi * j / nv;
        for (int i = 0; i < nu; ++i) {
            Float phi = 2 * Pi * i / nu;
            p.push_back(center + Vec3f(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                       std::cos(theta)) * radius);
        }
    }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            uint32_t a = j * nu + i, b = j * nu + (i + 1) % nu, c = (j + 1) * nu + i, d = (j + 1) * nu + (i + 1) % nu;
            if (j > 0) idx.insert(idx.end(), {a, c, b});
            if (j < nv - 1) idx.insert(idx.end(), {b, c, d});
        }
    s.AddMesh(p, idx);
}

// A height-field grid of n x n quads over [x0, x1] x [y0, y1] (z up), shared vertices.
inline void AddGrid(OwnedScene &s, int n, Float x0, Float x1, Float y0, Float y1, Float z, Float bump, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<Vec3f> p;
    std::vector<uint32_t> idx;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            p.push_back(Vec3f(x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n, z + bump * rng.Uniform()));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            idx.insert(idx.end(), {a, b, d, a, d, c});
        }
    s.AddMesh(p, idx);
}

// Long thin parallel strips along the (1,1,1) diagonal: their boxes all overlap, the case
// spatial splits are for.
inline void AddSlivers(OwnedScene &s, int count, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<Vec3f> p;
    std::vector<uint32_t> idx;
    for (int i = 0; i < count; ++i) {
        Vec3f off = Vec3f(rng.Uniform() - 0.5f, rng.Uniform() - 0.5f, rng.Uniform() - 0.5f) * 0.6f;
        Vec3f a = off, b = Vec3f(1, 1, 1) + off, c = a + rng.Direction() * 0.01f;
        p.insert(p.end(), {a, b, c});
        uint32_t k = uint32_t(p.size()) - 3;
        idx.insert(idx.end(), {k, k + 1, k + 2});
    }
    s.AddMesh(p, idx);
}

// Spheres, disks and cylinders with rotations, non-uniform scales, an annulus and partial ones
// (cut spheres, a disk sector, a cylinder cut in phi).
inline void AddAnalyticShapes(OwnedScene &s) {
    s.AddSphere(Translate(Vec3f(0.25f, 0.7f, 0.75f)) * Rotate(40, Vec3f(1, 0, 1)), 0.1f, -0.04f, 0.08f, 250);
    s.AddSphere(Translate(Vec3f(0.8f, 0.25f, 0.3f)), 0.09f, -0.09f, 0.02f);
    s.AddDisk(Translate(Vec3f(0.75f, 0.8f, 0.35f)) * Rotate(-35, Vec3f(1, 0.2f, 0)), 0.02f, 0.12f, 0.03f, 200);
    s.AddCylinder(Translate(Vec3f(0.4f, 0.25f, 0.6f)) * Rotate(70, Vec3f(0.3f, 1, 0)), 0.07f, -0.15f, 0.1f);
    s.AddCylinder(Translate(Vec3f(0.6f, 0.4f, 0.15f)) * Rotate(20, Vec3f(1, 0, 0)) * Scale(1, 1.5f, 1), 0.1f, 0, 0.12f, 290);
    s.AddSphere(Translate(Vec3f(0.3f, 0.3f, 0.4f)), 0.12f);
    s.AddSphere(Translate(Vec3f(0.7f, 0.6f, 0.5f)) * Rotate(30, Vec3f(1, 1, 0)) * Scale(1, 0.5f, 2), 0.08f);
    s.AddSphere(Translate(Vec3f(0.5f, 0.8f, 0.2f)), 0.03f);
    s.AddDisk(Translate(Vec3f(0.5f, 0.5f, 0.9f)) * Rotate(25, Vec3f(0, 1, 0.3f)), 0.0f, 0.25f, 0.1f);
    s.AddDisk(Translate(Vec3f(0.2f, 0.7f, 0.6f)) * Rotate(90, Vec3f(1, 0, 0)), 0.05f, 0.15f, 0.0f);
}

// ---- Ray sets ----

// Camera-like bundles: `cameras` pinholes around (and one inside) the scene looking at its
// center, each shooting res x res rays through a 60 degree field of view.
inline std::vector<Ray> CoherentRays(const Bounds3f &b, int cameras, int res, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<Ray> rays;
    Vec3f center = b.Center();
    Float radius = 0.5f * Length(b.Diagonal());
    for (int c = 0; c < cameras; ++c) {
        Vec3f eye = c == 0 ? center + (rng.InBox(b) - center) * 0.3f : center + rng.Direction() * (1.5f * radius);
        Vec3f target = center + (rng.InBox(b) - center) * 0.2f;
        Frame f = Frame::FromZ(Normalize(target - eye));
        Float tanHalf = std::tan(Radians(30));
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) {
                Float u = (2 * (x + 0.5f) / res - 1) * tanHalf, v = (2 * (y + 0.5f) / res - 1) * tanHalf;
                Ray r;
                r.o = eye;
                r.d = Normalize(f.FromLocal(Vec3f(u, v, 1)));
                rays.push_back(r);
            }
    }
    return rays;
}

// Random origins in the (slightly enlarged) bounds and uniform directions; every 16th ray is
// axis-aligned or has a zero direction component (slab-test edge cases).
inline std::vector<Ray> IncoherentRays(const Bounds3f &b, int count, uint64_t seed) {
    Pcg32 rng(seed);
    Bounds3f big = b;
    Vec3f pad = b.Diagonal() * 0.05f;
    big.pMin = big.pMin - pad;
    big.pMax = big.pMax + pad;
    std::vector<Ray> rays(count);
    for (int i = 0; i < count; ++i) {
        Ray &r = rays[i];
        r.o = rng.InBox(big);
        r.d = rng.Direction();
        if (i % 16 == 0) {
            int axis = int(rng.Next() % 3);
            r.d[axis] = 0;
            if (i % 32 == 0) r.d[(axis + 1) % 3] = 0;
            if (LengthSquared(r.d) == 0) r.d[axis] = 1;
            r.d = Normalize(r.d);
        }
    }
    return rays;
}

// Segments between random points (unnormalized directions, tMax = 1): shadow-ray queries.
inline std::vector<Ray> SegmentRays(const Bounds3f &b, int count, uint64_t seed) {
    Pcg32 rng(seed);
    std::vector<Ray> rays(count);
    for (int i = 0; i < count; ++i) {
        Vec3f p0 = rng.InBox(b), p1 = rng.InBox(b);
        rays[i].o = p0;
        rays[i].d = p1 - p0;
        rays[i].tMax = 1;
    }
    return rays;
}

// ---- Embree reference: the CPU backend's own EmbreeScene (Embree's triangles, user geometry for
// spheres and disks), behind the names the BVH tests use ----

class EmbreeReference {
  public:
    explicit EmbreeReference(const SceneView &scene) : scene_(scene), embree_(scene_) {}
    HitRecord Closest(const Ray &ray) const {
        HitRecord h;
        if (!embree_.Intersect(ray, &h)) h = HitRecord();
        return h;
    }
    bool Occluded(const Ray &ray) const { return embree_.Occluded(ray); }

  private:
    SceneView scene_;   // EmbreeScene keeps a pointer to the view
    EmbreeScene embree_;
};

// ---- Comparing hit lists ----

struct HitComparison {
    size_t rays = 0, hits = 0;
    size_t hitMiss = 0;      // one side hits, the other misses
    size_t otherPrim = 0;    // both hit at the same distance but different primitives, and not a tie
    size_t ties = 0;         // different primitives that both lie at that distance (shared edges,
                             // coplanar overlaps): either answer is right; not a disagreement
    size_t distance = 0;     // both hit, distances differ beyond the tolerance
    size_t Disagreements() const { return hitMiss + otherPrim + distance; }
    std::string Summary() const {
        char buf[240];
        std::snprintf(buf, sizeof(buf),
                      "%zu rays, %zu hits: %zu hit/miss, %zu other-primitive, %zu distance (%zu ties)", rays, hits,
                      hitMiss, otherPrim, distance, ties);
        return buf;
    }
};

// Distance at which the ray meets one given primitive (Infinity if it misses), by the shared routines.
inline Float PrimitiveDistance(const SceneView &scene, uint32_t shapeId, uint32_t prim, const Ray &ray) {
    const Shape &shape = scene.shapes[shapeId];
    Float t = Infinity, b1, b2;
    bool hit = false;
    if (shape.kind == ShapeKind::Triangles) {
        uint32_t v[3];
        TriangleVertices(scene, scene.triangleMeshes[shape.index], prim, v);
        hit = IntersectTriangle(scene.positions[v[0]], scene.positions[v[1]], scene.positions[v[2]], ray, Infinity, &t,
                                &b1, &b2);
    } else {
        hit = IntersectQuadric(scene, shape, ray, Infinity, &t);
    }
    return hit ? t : Infinity;
}

// Distances agree when |ta - tb| <= relTol * max(ta, tb) + absTol / |d|: absTol (render-space
// length, e.g. 1e-5 of the scene diagonal) covers rounding of hits very close to the origin.
// Different primitives at an agreeing distance are a tie if the shared routines find both of
// them at that distance (checked with `scene`).
inline HitComparison CompareHits(const std::vector<HitRecord> &a, const std::vector<HitRecord> &b,
                                 const std::vector<Ray> &rays, const SceneView &scene, Float relTol, Float absTol) {
    HitComparison c;
    c.rays = a.size();
    auto close = [&](Float ta, Float tb, const Ray &r) {
        return std::abs(ta - tb) <= relTol * Max(std::abs(ta), std::abs(tb)) + absTol / Length(r.d);
    };
    for (size_t i = 0; i < a.size(); ++i) {
        if (a[i].Hit()) c.hits++;
        if (a[i].Hit() != b[i].Hit()) {
            c.hitMiss++;
            continue;
        }
        if (!a[i].Hit()) continue;
        if (!close(a[i].t, b[i].t, rays[i])) {
            c.distance++;
        } else if (a[i].shape != b[i].shape || a[i].primitive != b[i].primitive) {
            Float ta = PrimitiveDistance(scene, b[i].shape, b[i].primitive, rays[i]);
            Float tb = PrimitiveDistance(scene, a[i].shape, a[i].primitive, rays[i]);
            if (close(ta, a[i].t, rays[i]) && close(tb, b[i].t, rays[i])) c.ties++;
            else c.otherPrim++;
        }
    }
    return c;
}

inline std::vector<HitRecord> TraceClosestCpu(const GpuBVH &bvh, const SceneView &scene, const std::vector<Ray> &rays) {
    std::vector<HitRecord> hits(rays.size());
    BVHView view = bvh.View();
    for (size_t i = 0; i < rays.size(); ++i) IntersectClosest(view, scene, rays[i], &hits[i]);
    return hits;
}

inline std::vector<uint8_t> TraceAnyCpu(const GpuBVH &bvh, const SceneView &scene, const std::vector<Ray> &rays) {
    std::vector<uint8_t> occ(rays.size());
    BVHView view = bvh.View();
    for (size_t i = 0; i < rays.size(); ++i) occ[i] = IntersectAny(view, scene, rays[i]) ? 1 : 0;
    return occ;
}

inline std::string StatsSummary(const BVHStats &s) {
    char buf[300];
    std::snprintf(buf, sizeof(buf),
                  "%u prims, %u refs (x%.3f), %u inner nodes, %u leaves (max %u prims), depth %u, SAH %.2f, build %.1f ms",
                  s.primitives, s.references, s.primitives ? double(s.references) / s.primitives : 0.0, s.innerNodes,
                  s.leaves, s.maxLeafSize, s.maxDepth, s.sahCost, s.buildSeconds * 1e3);
    return buf;
}

}  // namespace lu::test
