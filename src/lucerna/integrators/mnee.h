// Lucerna: manifold next-event estimation (Hanika, Droske, Fascione 2015, "Manifold Next Event
// Estimation"). From a non-specular vertex x0 and a light point y whose straight connection is
// blocked only by smooth refractive surfaces, the chain x1..xk through those surfaces that obeys
// Snell's law at every vertex is found by Newton iteration on the half-vector constraints
//     C_i = (h_i . s_i, h_i . t_i) = 0,   h_i = normalize(wo_i + eta'_i wn_i),
// (wo_i towards x_{i-1}, wn_i towards x_{i+1}, (s_i, t_i) the shading tangent frame) with
// re-projection onto the surfaces by ray casting from x0, and the estimate is weighted by the
// generalized geometry term from the implicit function theorem: dX/dy = -A^-1 B with A = dC/dX
// (block tridiagonal) and B = dC/dy. Thin dielectric sheets bend no ray: they are crossed straight
// (pass-through) and only their transmittance enters. See docs/regularization.md for how MNEE is
// combined with BSDF sampling and the regularized connection.
// Backends supply a Tracer with  bool Intersect(const Ray &, HitRecord *) const.
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/geometry/shapes.h"
#include "lucerna/lights/lights.h"
#include "lucerna/materials/bsdf.h"

namespace lu {

constexpr int MaxMneeVertices = 4;       // refractive vertices solved for
constexpr int MaxMneeSurfaces = 10;      // surfaces crossed by one segment walk (pass-through + interfaces)
constexpr int MaxMneeIterations = 24;
constexpr Float MneeTolerance = 2e-5f;   // |C|_max at convergence (sine of the angle from Snell's law)

// One vertex of a specular chain with the local geometry the constraints need.
struct MneeVertex {
    Vec3f p;
    Vec3f n;           // shading normal (unit): the refraction's normal
    Vec3f ng;          // geometric normal, for ray offsets
    Vec3f ps, pt;      // orthonormal basis of the geometric tangent plane: the vertex's coordinates
    Vec3f s, t;        // orthonormal basis of the shading tangent plane: the constraint's frame
    Vec3f dnda, dndb;  // derivatives of n along ps and pt
    Float etap = 1;    // relative index across the surface, travelling from x_{i-1} to x_{i+1}
    uint32_t shape = 0xffffffffu;
};

// A solved (or seeded) chain between x0 and y.
struct MneeChain {
    int k = 0;                        // refractive vertices
    MneeVertex v[MaxMneeVertices];
    Vec3f x0, n0;                     // start and its geometric normal
    Vec3f y, nY;                      // light point and its geometric normal (area lights)
    uint32_t shapeHash = 0;           // the refractive surfaces in order (see MneeShapeHash)
    int iterations = 0;
};

// Order-dependent hash of the refractive surfaces of a chain; paths compare it with their own.
LU_INLINE uint32_t MneeShapeHash(uint32_t hash, uint32_t shape) { return (hash ^ (shape + 0x9e3779b9u)) * 16777619u; }

// The transport weight of a solved chain: product of the refraction weights (T / eta'^2 in
// radiance mode) and the pass-through transmittances, and the product of the probabilities with
// which BSDF sampling picks those lobes (the implicit technique's share of the same path).
struct MneeThroughput {
    SampledSpectrum weight{1};
    Float lobePdf = 1;
    int passThrough = 0;   // thin sheets crossed (vertices of the path, as the refractive ones)
};

// ---- Local geometry ----

// Tangent basis (a, b) of unit normal n.
LU_INLINE void MneeBasis(const Vec3f &n, Vec3f *a, Vec3f *b) { CoordinateSystem(n, a, b); }

// What the walk along a segment found.
enum class MneeSurfaceKind : uint8_t { None, Refractive, Blocking };

// Classifies the surface at hit: pass-through surfaces (interfaces, smooth thin dielectrics)
// multiply *through (when given) and return None; a smooth dielectric is Refractive (its vertex
// filled for travel along dir); anything else Blocking, and so is a dispersive index (MNEE handles
// only chains that keep every wavelength of the path).
LU_INLINE MneeSurfaceKind ClassifyMneeSurface(const SceneView &scene, const HitRecord &hit, const Ray &ray,
                                              const SampledWavelengths &lambda, MneeVertex *vtx,
                                              MneeThroughput *through, SurfaceInteraction *siOut) {
    SurfaceInteraction si = ComputeInteraction(scene, hit, ray);
    // The solver needs positions to float precision of the ray, not of the barycentrics (which
    // carry the triangle's size into the error): intersect the triangle's plane once more.
    const Shape &shape = scene.shapes[hit.shape];
    if (shape.kind == ShapeKind::Triangles && hit.instance == NoIndex) {
        uint32_t tv[3];
        TriangleVertices(scene, scene.triangleMeshes[shape.index], hit.primitive, tv);
        Vec3f p0 = scene.positions[tv[0]];
        Vec3f N = Cross(scene.positions[tv[1]] - p0, scene.positions[tv[2]] - p0);
        Float den = Dot(ray.d, N);
        if (den != 0) {
            Float t = Dot(p0 - ray.o, N) / den;
            if (t > 0 && t < Infinity) si.p = ray.o + ray.d * t;
        }
    }
    *siOut = si;
    if (si.material == NoIndex) return MneeSurfaceKind::None;
    // Instanced shapes (object space geometry) are not chain vertices: the solver reads the
    // render-space mesh (ShadingNormalDerivative); they block, as in every query of the walk.
    if (hit.instance != NoIndex) return MneeSurfaceKind::Blocking;
    // Cylinders, curved bilinear patches and curves are not chain vertices either (the solver is
    // tested on spheres and meshes).
    if (shape.kind == ShapeKind::Cylinder || shape.kind == ShapeKind::BilinearPatches || shape.kind == ShapeKind::Curves)
        return MneeSurfaceKind::Blocking;
    // Nor cut-outs: the solver moves vertices over the surface, holes included.
    if (shape.alpha != NoIndex) return MneeSurfaceKind::Blocking;
    const Material &mat = ResolveMixMaterial(scene.materials[si.material], si, scene);   // a mix: its pick at si
    if (mat.kind != MaterialKind::Dielectric && mat.kind != MaterialKind::ThinDielectric) return MneeSurfaceKind::Blocking;
    // The solver uses the interpolated normal and one index per surface; a normal- or
    // bump-mapped surface or a textured index is not a chain vertex.
    if (mat.normalMap != NoIndex || mat.displacement != NoIndex || mat.etaTexture != NoIndex)
        return MneeSurfaceKind::Blocking;
    // A dispersive index ends the secondary wavelengths at the vertex: not for MNEE (decided by
    // the material alone, so that the emitter-hit weight decides as the light sample did).
    if (!mat.eta.IsConstant()) return MneeSurfaceKind::Blocking;
    SampledWavelengths lw = lambda;
    BSDF bsdf;
    if (!MakeBSDF(mat, si, lw, scene, &bsdf)) return MneeSurfaceKind::None;
    if (!bsdf.IsSpecular()) return MneeSurfaceKind::Blocking;
    SpecularLobe lobes[2];
    int n = bsdf.SpecularLobes(si.wo, lobes);
    int tl = -1;
    for (int i = 0; i < n; ++i)
        if (lobes[i].flags & BxDF_Transmission) tl = i;
    // Total internal reflection along a physical direction (through: the chain is evaluated)
    // blocks; along a seed or trial direction only the index across the surface is needed.
    if (tl < 0 && (through || bsdf.kind != BxDFKind::Dielectric)) return MneeSurfaceKind::Blocking;
    if (bsdf.kind == BxDFKind::ThinDielectric) {
        if (through) {
            through->weight *= lobes[tl].weight;
            through->lobePdf *= lobes[tl].pdf;
            ++through->passThrough;
        }
        return MneeSurfaceKind::None;
    }
    if (bsdf.kind != BxDFKind::Dielectric) return MneeSurfaceKind::Blocking;
    if (through) {   // (tl >= 0 here) the chain's direction decides the lobe's weight
        through->weight *= lobes[tl].weight;
        through->lobePdf *= lobes[tl].pdf;
    }
    vtx->p = si.p;
    vtx->n = si.ns;
    vtx->ng = si.n;
    MneeBasis(si.n, &vtx->ps, &vtx->pt);
    Frame f = Frame::FromXZ(si.dpdu, si.ns);
    vtx->s = f.x;
    vtx->t = f.y;
    vtx->dnda = ShadingNormalDerivative(scene, hit, si, vtx->ps);
    vtx->dndb = ShadingNormalDerivative(scene, hit, si, vtx->pt);
    vtx->etap = tl >= 0 ? lobes[tl].eta
                        : (Dot(si.wo, si.ns) > 0 ? bsdf.dielectric.eta : 1 / bsdf.dielectric.eta);
    vtx->shape = hit.shape;
    return MneeSurfaceKind::Refractive;
}

// Walks from `from` (normal nFrom) towards `target` through pass-through surfaces, for at most
// reach x the distance (reach = 0: without bound; the ray aims at target from its offset origin,
// so that it meets a surface at target exactly). Returns the first refractive surface (filled
// into *vtx) or Blocking, or None when the way is free.
template <typename Tracer>
LU_HD MneeSurfaceKind WalkMneeSegment(const SceneView &scene, const Tracer &tracer, Vec3f from, Vec3f nFrom,
                                      Vec3f target, Float reach, const SampledWavelengths &lambda, MneeVertex *vtx,
                                      MneeThroughput *through) {
    Vec3f o = OffsetRayOrigin(from, nFrom, target - from);
    Vec3f dir = target - o;
    Float len = Length(dir);
    if (!(len > 0)) return MneeSurfaceKind::None;
    dir = dir / len;
    Float tMax = reach > 0 ? reach * len : Infinity, travelled = 0;
    for (int i = 0; i < MaxMneeSurfaces; ++i) {
        Ray ray;
        ray.o = o;
        ray.d = dir;
        ray.tMax = tMax == Infinity ? Infinity : tMax - travelled;
        if (!(ray.tMax > 0)) return MneeSurfaceKind::None;
        HitRecord hit;
        if (!tracer.Intersect(ray, &hit)) return MneeSurfaceKind::None;
        SurfaceInteraction si;
        MneeSurfaceKind k = ClassifyMneeSurface(scene, hit, ray, lambda, vtx, through, &si);
        if (k != MneeSurfaceKind::None) return k;
        o = OffsetRayOrigin(si.p, si.n, dir);
        travelled = Dot(o - ray.o, dir) + travelled;
    }
    return MneeSurfaceKind::Blocking;
}

// ---- Constraints and their derivatives ----

// The constraint of vertex i with neighbours a (towards x0) and b (towards y).
struct MneeConstraintState {
    Vec3f wo, wn, hh;
    Float lo, ln, lh;
};
LU_INLINE bool MneeConstraint(const MneeVertex &v, Vec3f a, Vec3f b, MneeConstraintState *c, Float C[2]) {
    c->wo = a - v.p;
    c->lo = Length(c->wo);
    c->wn = b - v.p;
    c->ln = Length(c->wn);
    if (!(c->lo > 0) || !(c->ln > 0)) return false;
    c->wo = c->wo / c->lo;
    c->wn = c->wn / c->ln;
    Vec3f h = c->wo + c->wn * v.etap;
    c->lh = Length(h);
    if (!(c->lh > 0)) return false;
    c->hh = h / c->lh;
    C[0] = Dot(c->hh, v.s);
    C[1] = Dot(c->hh, v.t);
    return true;
}
// dC for a change dh of the unnormalized half vector (own = the vertex itself moves along e).
LU_INLINE void MneeDC(const MneeVertex &v, const MneeConstraintState &c, Vec3f dh, const Vec3f *dn, Float out[2]) {
    Vec3f dhh = (dh - c.hh * Dot(c.hh, dh)) / c.lh;
    out[0] = Dot(dhh, v.s);
    out[1] = Dot(dhh, v.t);
    if (dn) {   // the frame turns with the normal: h . ds = -(h . n)(s . dn) + O(|C|)
        Float hn = Dot(c.hh, v.n);
        out[0] -= hn * Dot(v.s, *dn);
        out[1] -= hn * Dot(v.t, *dn);
    }
}
// Change of a unit vector w = (q - p)/l when q moves by e.
LU_INLINE Vec3f MneeDUnit(const Vec3f &w, Float l, const Vec3f &e) { return (e - w * Dot(w, e)) / l; }

// Dense solve of M X = R (n x n, nr right-hand sides, row-major, n <= 2 MaxMneeVertices) by
// Gaussian elimination with partial pivoting. False when singular.
LU_INLINE bool MneeSolveLinear(Float *M, Float *R, int n, int nr) {
    for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r)
            if (std::abs(M[r * n + c]) > std::abs(M[piv * n + c])) piv = r;
        if (!(std::abs(M[piv * n + c]) > 1e-12f)) return false;
        if (piv != c) {
            for (int j = 0; j < n; ++j) { Float t = M[c * n + j]; M[c * n + j] = M[piv * n + j]; M[piv * n + j] = t; }
            for (int j = 0; j < nr; ++j) { Float t = R[c * nr + j]; R[c * nr + j] = R[piv * nr + j]; R[piv * nr + j] = t; }
        }
        for (int r = 0; r < n; ++r) {
            if (r == c) continue;
            Float f = M[r * n + c] / M[c * n + c];
            if (f == 0) continue;
            for (int j = c; j < n; ++j) M[r * n + j] -= f * M[c * n + j];
            for (int j = 0; j < nr; ++j) R[r * nr + j] -= f * R[c * nr + j];
        }
    }
    for (int r = 0; r < n; ++r) {
        Float d = M[r * n + r];
        for (int j = 0; j < nr; ++j) R[r * nr + j] /= d;
    }
    return true;
}

// Neighbours of vertex i.
LU_INLINE Vec3f MneePrev(const MneeChain &ch, int i) { return i == 0 ? ch.x0 : ch.v[i - 1].p; }
LU_INLINE Vec3f MneeNext(const MneeChain &ch, int i) { return i == ch.k - 1 ? ch.y : ch.v[i + 1].p; }

// All constraints; returns max |C| (Infinity when degenerate).
LU_INLINE Float MneeConstraints(const MneeChain &ch, Float *C, MneeConstraintState *cs) {
    Float m = 0;
    for (int i = 0; i < ch.k; ++i) {
        if (!MneeConstraint(ch.v[i], MneePrev(ch, i), MneeNext(ch, i), &cs[i], C + 2 * i)) return Infinity;
        m = Max(m, Max(std::abs(C[2 * i]), std::abs(C[2 * i + 1])));
    }
    return m;
}

// A = dC/dX (2k x 2k, row-major) in the vertices' (ps, pt) coordinates.
LU_INLINE void MneeJacobian(const MneeChain &ch, const MneeConstraintState *cs, Float *A) {
    int n = 2 * ch.k;
    for (int j = 0; j < n * n; ++j) A[j] = 0;
    for (int i = 0; i < ch.k; ++i) {
        const MneeVertex &v = ch.v[i];
        const MneeConstraintState &c = cs[i];
        Float d[2];
        for (int e = 0; e < 2; ++e) {
            if (i > 0) {   // x_{i-1} moves
                Vec3f dir = e == 0 ? ch.v[i - 1].ps : ch.v[i - 1].pt;
                MneeDC(v, c, MneeDUnit(c.wo, c.lo, dir), nullptr, d);
                A[(2 * i) * n + 2 * (i - 1) + e] = d[0];
                A[(2 * i + 1) * n + 2 * (i - 1) + e] = d[1];
            }
            {   // x_i moves
                Vec3f dir = e == 0 ? v.ps : v.pt;
                Vec3f dn = e == 0 ? v.dnda : v.dndb;
                Vec3f dh = -MneeDUnit(c.wo, c.lo, dir) - MneeDUnit(c.wn, c.ln, dir) * v.etap;
                MneeDC(v, c, dh, &dn, d);
                A[(2 * i) * n + 2 * i + e] = d[0];
                A[(2 * i + 1) * n + 2 * i + e] = d[1];
            }
            if (i < ch.k - 1) {   // x_{i+1} moves
                Vec3f dir = e == 0 ? ch.v[i + 1].ps : ch.v[i + 1].pt;
                MneeDC(v, c, MneeDUnit(c.wn, c.ln, dir) * v.etap, nullptr, d);
                A[(2 * i) * n + 2 * (i + 1) + e] = d[0];
                A[(2 * i + 1) * n + 2 * (i + 1) + e] = d[1];
            }
        }
    }
}

// ---- Seed, solve, evaluate ----

// The seed chain: the refractive surfaces the straight segment x0 -> y crosses. False when the
// segment meets a blocking surface or more than MaxMneeVertices refractive ones.
template <typename Tracer>
LU_HD bool SeedMneeChain(const SceneView &scene, const Tracer &tracer, Vec3f x0, Vec3f n0, Vec3f y, Vec3f nY,
                         const SampledWavelengths &lambda, MneeChain *ch) {
    ch->k = 0;
    ch->x0 = x0;
    ch->n0 = n0;
    ch->y = y;
    ch->nY = nY;
    ch->shapeHash = 0;
    ch->iterations = 0;
    Vec3f from = x0, nFrom = n0;
    for (;;) {
        MneeVertex vtx;
        MneeSurfaceKind k = WalkMneeSegment(scene, tracer, from, nFrom, y, 1 - 1e-4f, lambda, &vtx, nullptr);
        if (k == MneeSurfaceKind::None) return true;
        if (k == MneeSurfaceKind::Blocking || ch->k == MaxMneeVertices) return false;
        ch->v[ch->k++] = vtx;
        ch->shapeHash = MneeShapeHash(ch->shapeHash, vtx.shape);
        from = vtx.p;
        nFrom = vtx.ng;
    }
}

// Re-projects proposed positions onto the surfaces by casting rays from x0 through the chain;
// each ray must first meet the vertex's own surface. The directions of travel stay on the same
// side of every surface, so each vertex keeps its relative index.
template <typename Tracer>
LU_HD bool ProjectMneeChain(const SceneView &scene, const Tracer &tracer, const SampledWavelengths &lambda,
                            const Vec3f *proposed, MneeChain *ch) {
    Vec3f from = ch->x0, nFrom = ch->n0;
    for (int i = 0; i < ch->k; ++i) {
        MneeVertex vtx;
        if (WalkMneeSegment(scene, tracer, from, nFrom, proposed[i], 0, lambda, &vtx, nullptr) !=
                MneeSurfaceKind::Refractive ||
            vtx.shape != ch->v[i].shape)
            return false;
        ch->v[i] = vtx;
        from = vtx.p;
        nFrom = vtx.ng;
    }
    return true;
}

// Newton's method on the constraints from the seed chain. True when the chain satisfies Snell's
// law at every vertex within MneeTolerance (a chain of pass-through surfaces only, k = 0, needs
// no solve). Deterministic in (x0, y): the emitter-hit weight re-runs it to decide whether MNEE
// would have found a path.
template <typename Tracer>
LU_HD bool SolveMneeChain(const SceneView &scene, const Tracer &tracer, const SampledWavelengths &lambda,
                          MneeChain *ch) {
    if (ch->k == 0) return true;
    constexpr int N = 2 * MaxMneeVertices;
    Float C[N], A[N * N], step[N];
    MneeConstraintState cs[MaxMneeVertices];
    Float err = MneeConstraints(*ch, C, cs);
    int n = 2 * ch->k;
    for (int it = 0; it < MaxMneeIterations; ++it) {
        ch->iterations = it;
        if (err < MneeTolerance) return true;
        if (err == Infinity) return false;
        MneeJacobian(*ch, cs, A);
        for (int j = 0; j < n; ++j) step[j] = C[j];
        if (!MneeSolveLinear(A, step, n, 1)) return false;
        bool accepted = false;
        Float lambdaStep = 1;
        for (int tries = 0; tries < 8 && !accepted; ++tries, lambdaStep *= 0.5f) {
            Vec3f proposed[MaxMneeVertices];
            for (int i = 0; i < ch->k; ++i)
                proposed[i] = ch->v[i].p - (ch->v[i].ps * step[2 * i] + ch->v[i].pt * step[2 * i + 1]) * lambdaStep;
            MneeChain trial = *ch;
            if (!ProjectMneeChain(scene, tracer, lambda, proposed, &trial)) continue;
            Float Ct[N];
            MneeConstraintState cst[MaxMneeVertices];
            Float errT = MneeConstraints(trial, Ct, cst);
            if (!(errT < err)) continue;
            *ch = trial;
            err = errT;
            for (int j = 0; j < n; ++j) C[j] = Ct[j];
            for (int i = 0; i < ch->k; ++i) cs[i] = cst[i];
            accepted = true;
        }
        if (!accepted) return false;
    }
    ch->iterations = MaxMneeIterations;
    return err < MneeTolerance;
}

// |det| of the 2x2 map from (e0, e1)-coordinates to the unit direction w = normalize(q - p) when q
// moves by dq0, dq1 (l = |q - p|): the solid angle per unit area of those coordinates.
LU_INLINE Float MneeSolidAngleDet(const Vec3f &w, Float l, const Vec3f &dq0, const Vec3f &dq1) {
    Vec3f a, b;
    CoordinateSystem(w, &a, &b);
    Vec3f d0 = MneeDUnit(w, l, dq0), d1 = MneeDUnit(w, l, dq1);
    return std::abs(Dot(a, d0) * Dot(b, d1) - Dot(a, d1) * Dot(b, d0));
}

// Generalized geometry terms of a solved chain. atX0 = true: |d omega_0 / dA_y|, the solid angle
// at x0 (of the direction to x1) per unit area of the light surface at y (area lights). false:
// |d omega_y / dA_x0|, the solid angle at y (of the direction to x_k) per unit area at x0 (point
// lights). Without refractive vertices they are |cos theta_y| / d^2 and |cos theta_0| / d^2.
LU_INLINE Float MneeGeometry(const MneeChain &ch, bool atX0) {
    Vec3f ya(0, 0, 0), yb(0, 0, 0), xa(0, 0, 0), xb(0, 0, 0);
    if (atX0) MneeBasis(ch.nY, &ya, &yb);   // point lights have no surface at y
    else MneeBasis(ch.n0, &xa, &xb);
    if (ch.k == 0) {
        Vec3f w = atX0 ? ch.y - ch.x0 : ch.x0 - ch.y;
        Float l = Length(w);
        if (!(l > 0)) return 0;
        return atX0 ? MneeSolidAngleDet(w / l, l, ya, yb) : MneeSolidAngleDet(w / l, l, xa, xb);
    }
    constexpr int N = 2 * MaxMneeVertices;
    Float C[N], A[N * N], B[N * 2];
    MneeConstraintState cs[MaxMneeVertices];
    if (MneeConstraints(ch, C, cs) == Infinity) return 0;
    MneeJacobian(ch, cs, A);
    int n = 2 * ch.k;
    for (int j = 0; j < 2 * n; ++j) B[j] = 0;
    // B = dC/d(endpoint): only the constraint next to the endpoint depends on it; solve A T = -B.
    int i = atX0 ? ch.k - 1 : 0;
    const MneeVertex &v = ch.v[i];
    for (int e = 0; e < 2; ++e) {
        Float d[2];
        if (atX0) MneeDC(v, cs[i], MneeDUnit(cs[i].wn, cs[i].ln, e == 0 ? ya : yb) * v.etap, nullptr, d);
        else MneeDC(v, cs[i], MneeDUnit(cs[i].wo, cs[i].lo, e == 0 ? xa : xb), nullptr, d);
        B[(2 * i) * 2 + e] = -d[0];
        B[(2 * i + 1) * 2 + e] = -d[1];
    }
    if (!MneeSolveLinear(A, B, n, 2)) return 0;
    // The vertex next to the other endpoint moves by T's block of rows.
    int j = atX0 ? 0 : ch.k - 1;
    const MneeVertex &u = ch.v[j];
    Vec3f dq0 = u.ps * B[(2 * j) * 2 + 0] + u.pt * B[(2 * j + 1) * 2 + 0];
    Vec3f dq1 = u.ps * B[(2 * j) * 2 + 1] + u.pt * B[(2 * j + 1) * 2 + 1];
    Vec3f from = atX0 ? ch.x0 : ch.y;
    Vec3f w = u.p - from;
    Float l = Length(w);
    if (!(l > 0)) return 0;
    return MneeSolidAngleDet(w / l, l, dq0, dq1);
}

// Walks the solved chain once more from x0 to y: every segment must reach its vertex (and the
// last one y) through pass-through surfaces only, every refraction must send the light on to the
// next vertex. Fills the chain's transport weight. False when the chain is not a valid path.
template <typename Tracer>
LU_HD bool EvaluateMneeChain(const SceneView &scene, const Tracer &tracer, const SampledWavelengths &lambda,
                             const MneeChain &ch, MneeThroughput *through) {
    *through = MneeThroughput();
    Vec3f from = ch.x0, nFrom = ch.n0;
    for (int i = 0; i <= ch.k; ++i) {
        Vec3f to = i == ch.k ? ch.y : ch.v[i].p;
        Float l = Distance(to, from);
        MneeVertex vtx;
        MneeSurfaceKind k = WalkMneeSegment(scene, tracer, from, nFrom, to, i == ch.k ? 1 - 1e-4f : 1.01f, lambda, &vtx, through);
        if (i == ch.k) {
            if (k != MneeSurfaceKind::None) return false;
        } else {
            if (k != MneeSurfaceKind::Refractive || vtx.shape != ch.v[i].shape ||
                DistanceSquared(vtx.p, to) > Sqr(1e-3f * l + 1e-6f))
                return false;
            // The refraction at the vertex must continue towards the next vertex.
            Vec3f next = i == ch.k - 1 ? ch.y : ch.v[i + 1].p;
            MneeConstraintState c;
            Float C[2];
            if (!MneeConstraint(vtx, from, next, &c, C) || Max(std::abs(C[0]), std::abs(C[1])) > 10 * MneeTolerance)
                return false;
        }
        from = i == ch.k ? from : ch.v[i].p;
        nFrom = i == ch.k ? nFrom : ch.v[i].ng;
    }
    return through->weight.MaxValue() > 0;
}

// Seed, solve and evaluate in one: the chain from x0 (geometric normal n0) to the light point y
// (normal nY; any for point lights). False when MNEE finds no valid chain.
template <typename Tracer>
LU_HD bool FindMneeChain(const SceneView &scene, const Tracer &tracer, Vec3f x0, Vec3f n0, Vec3f y, Vec3f nY,
                         const SampledWavelengths &lambda, MneeChain *ch, MneeThroughput *through) {
    return SeedMneeChain(scene, tracer, x0, n0, y, nY, lambda, ch) && SolveMneeChain(scene, tracer, lambda, ch) &&
           EvaluateMneeChain(scene, tracer, lambda, *ch, through);
}

// Whether MNEE from x0 to y reproduces a path's chain: same refractive surfaces in the same order
// and its first refractive vertex within tol of the path's (first unused when k = 0).
LU_INLINE bool MneeChainMatches(const MneeChain &ch, int k, uint32_t shapeHash, Vec3f first, Float tol) {
    if (ch.k != k || ch.shapeHash != shapeHash) return false;
    return k == 0 || DistanceSquared(ch.v[0].p, first) <= tol * tol;
}

// Intensity of a point or spot light towards the unit direction w (from the light).
LU_INLINE SampledSpectrum PointLightIntensity(const Light &light, const SceneView &scene, Vec3f w,
                                              const SampledWavelengths &lambda) {
    LightSampleContext ctx;
    ctx.p = light.position + w;   // at unit distance, L = I(w) / 1^2
    ctx.n = ctx.ns = -w;
    LightLiSample ls;
    if (!SampleLi(light, scene, ctx, Vec2f(0.5f, 0.5f), lambda, &ls, false)) return SampledSpectrum(0);
    return ls.L;
}

}  // namespace lu
