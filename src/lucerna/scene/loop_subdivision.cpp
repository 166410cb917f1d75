// Lucerna (host): Loop subdivision (loop_subdivision.h). The mesh is kept as index arrays: each
// face has its three vertices in order and, for each edge k = (v[k], v[k+1]), the face across it.
// Walking around a vertex goes face to face across the edge that leaves the vertex (NextFace) or
// the one that enters it (PrevFace), as pbrt-v4's SDFace does with pointers.
#include "lucerna/scene/loop_subdivision.h"

#include <cmath>
#include <unordered_map>

namespace lu {

namespace {

constexpr uint32_t None = 0xffffffffu;
inline int Next(int i) { return (i + 1) % 3; }
inline int Prev(int i) { return (i + 2) % 3; }

struct Face {
    uint32_t v[3] = {None, None, None};
    uint32_t f[3] = {None, None, None};   // f[k]: the face across edge (v[k], v[Next(k)])
};

// Loop's even-vertex weight for an interior vertex of this valence, and the limit weight.
double Beta(int valence) { return valence == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * valence); }
double LoopGamma(int valence) { return 1.0 / (valence + 3.0 / (8.0 * Beta(valence))); }

struct SubdivisionMesh {
    std::vector<Vec3f> p;
    std::vector<uint32_t> startFace;   // a face holding the vertex (for a boundary vertex, any)
    std::vector<uint8_t> boundary;
    std::vector<Face> faces;

    int VNum(uint32_t face, uint32_t v) const {
        const Face &f = faces[face];
        return f.v[0] == v ? 0 : f.v[1] == v ? 1 : 2;
    }
    uint32_t NextFace(uint32_t face, uint32_t v) const { return faces[face].f[VNum(face, v)]; }
    uint32_t PrevFace(uint32_t face, uint32_t v) const { return faces[face].f[Prev(VNum(face, v))]; }
    uint32_t NextVert(uint32_t face, uint32_t v) const { return faces[face].v[Next(VNum(face, v))]; }
    uint32_t PrevVert(uint32_t face, uint32_t v) const { return faces[face].v[Prev(VNum(face, v))]; }

    // The number of neighbours: faces around an interior vertex, faces + 1 around a boundary one.
    int Valence(uint32_t v) const {
        uint32_t start = startFace[v], f = start;
        int n = 1;
        if (!boundary[v]) {
            while ((f = NextFace(f, v)) != start) ++n;
            return n;
        }
        while ((f = NextFace(f, v)) != None) ++n;
        f = start;
        while ((f = PrevFace(f, v)) != None) ++n;
        return n + 1;
    }

    // The neighbours in order around the vertex; a boundary vertex's run from one boundary
    // neighbour to the other.
    void OneRing(uint32_t v, std::vector<Vec3f> &ring) const {
        ring.clear();
        uint32_t f = startFace[v];
        if (!boundary[v]) {
            do {
                ring.push_back(p[NextVert(f, v)]);
                f = NextFace(f, v);
            } while (f != startFace[v]);
            return;
        }
        for (uint32_t g; (g = NextFace(f, v)) != None;) f = g;
        ring.push_back(p[NextVert(f, v)]);
        do {
            ring.push_back(p[PrevVert(f, v)]);
            f = PrevFace(f, v);
        } while (f != None);
    }

    Vec3f WeightOneRing(uint32_t v, double beta, std::vector<Vec3f> &ring) const {
        OneRing(v, ring);
        double w = 1 - double(ring.size()) * beta;
        double x = w * p[v].x, y = w * p[v].y, z = w * p[v].z;
        for (const Vec3f &q : ring) {
            x += beta * q.x;
            y += beta * q.y;
            z += beta * q.z;
        }
        return Vec3f(Float(x), Float(y), Float(z));
    }

    Vec3f WeightBoundary(uint32_t v, Float beta, std::vector<Vec3f> &ring) const {
        OneRing(v, ring);
        return (1 - 2 * beta) * p[v] + beta * ring.front() + beta * ring.back();
    }
};

// Links faces across shared edges and classifies the vertices; false (with *error) on a mesh
// that is not a consistently oriented manifold.
bool BuildTopology(SubdivisionMesh &m, std::string *error) {
    struct EdgeUse {
        uint32_t face;
        int edge;
        int uses;
    };
    std::unordered_map<uint64_t, EdgeUse> edges;
    edges.reserve(m.faces.size() * 2);
    std::vector<uint32_t> incident(m.p.size(), 0);
    for (uint32_t i = 0; i < m.faces.size(); ++i) {
        Face &f = m.faces[i];
        for (int k = 0; k < 3; ++k) {
            uint32_t a = f.v[k], b = f.v[Next(k)];
            ++incident[a];
            m.startFace[a] = i;
            uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
            auto [it, added] = edges.try_emplace(key, EdgeUse{i, k, 1});
            if (added) continue;
            EdgeUse &e = it->second;
            auto edgeName = [&] { return "the edge between vertices " + std::to_string(a) + " and " + std::to_string(b); };
            if (e.uses >= 2) {
                *error = edgeName() + " is shared by more than two faces (the mesh is not a manifold)";
                return false;
            }
            Face &g = m.faces[e.face];
            if (g.v[e.edge] == a) {
                *error = "faces " + std::to_string(e.face) + " and " + std::to_string(i) + " traverse " + edgeName() +
                         " in the same direction (the faces are not consistently oriented)";
                return false;
            }
            g.f[e.edge] = i;
            f.f[k] = e.face;
            e.uses = 2;
        }
    }
    for (uint32_t v = 0; v < m.p.size(); ++v) {
        // Walk the fan from the start face: it closes (interior) or ends at a boundary edge.
        uint32_t f = m.startFace[v];
        uint32_t reached = 1;
        while ((f = m.NextFace(f, v)) != None && f != m.startFace[v]) ++reached;
        m.boundary[v] = f == None;
        if (m.boundary[v]) {
            f = m.startFace[v];
            while ((f = m.PrevFace(f, v)) != None) ++reached;
        }
        if (reached != incident[v]) {
            *error = "the faces around vertex " + std::to_string(v) + " form more than one fan (the mesh is not a manifold there)";
            return false;
        }
    }
    return true;
}

void Refine(SubdivisionMesh &m) {
    const uint32_t nv = uint32_t(m.p.size()), nf = uint32_t(m.faces.size());
    SubdivisionMesh r;
    r.faces.resize(size_t(nf) * 4);
    r.p.resize(nv);
    r.startFace.resize(nv);
    r.boundary = m.boundary;
    std::vector<Vec3f> ring;
    // Even vertices: the old ones, moved.
    for (uint32_t v = 0; v < nv; ++v) {
        r.p[v] = m.boundary[v] ? m.WeightBoundary(v, Float(1) / 8, ring) : m.WeightOneRing(v, Beta(m.Valence(v)), ring);
        r.startFace[v] = 4 * m.startFace[v] + uint32_t(m.VNum(m.startFace[v], v));
    }
    // Odd vertices: one per edge, made by the lower-numbered face that holds it.
    std::vector<uint32_t> edgeVert(size_t(nf) * 3, None);
    for (uint32_t i = 0; i < nf; ++i) {
        const Face &f = m.faces[i];
        for (int k = 0; k < 3; ++k) {
            uint32_t a = f.v[k], b = f.v[Next(k)], n = f.f[k];
            int j = 0;
            if (n != None) j = Prev(m.VNum(n, a));   // the neighbour's edge (b, a) ends at a
            if (n != None && n < i) {
                edgeVert[size_t(i) * 3 + k] = edgeVert[size_t(n) * 3 + j];
                continue;
            }
            Vec3f q = n == None ? Float(0.5) * (m.p[a] + m.p[b])
                                : Float(3.0 / 8.0) * (m.p[a] + m.p[b]) +
                                      Float(1.0 / 8.0) * (m.p[f.v[Prev(k)]] + m.p[m.faces[n].v[Prev(j)]]);
            edgeVert[size_t(i) * 3 + k] = uint32_t(r.p.size());
            r.p.push_back(q);
            r.startFace.push_back(4 * i + 3);
            r.boundary.push_back(n == None);
        }
    }
    // The four children of each face: child j at corner v[j], child 3 in the middle.
    for (uint32_t i = 0; i < nf; ++i) {
        const Face &f = m.faces[i];
        Face *c = &r.faces[size_t(i) * 4];
        for (int j = 0; j < 3; ++j) {
            c[3].f[j] = 4 * i + uint32_t(Next(j));
            c[j].f[Next(j)] = 4 * i + 3;
            uint32_t g = f.f[j];
            c[j].f[j] = g != None ? 4 * g + uint32_t(m.VNum(g, f.v[j])) : None;
            g = f.f[Prev(j)];
            c[j].f[Prev(j)] = g != None ? 4 * g + uint32_t(m.VNum(g, f.v[j])) : None;

            uint32_t odd = edgeVert[size_t(i) * 3 + j];
            c[j].v[j] = f.v[j];
            c[j].v[Next(j)] = odd;
            c[Next(j)].v[j] = odd;
            c[3].v[j] = odd;
        }
    }
    m = std::move(r);
}

}  // namespace

uint64_t LoopSubdividedTriangleCount(uint64_t faces, int levels) {
    uint64_t n = faces;
    for (int i = 0; i < levels && n > 0; ++i) {
        if (n > UINT64_MAX / 4) return UINT64_MAX;
        n *= 4;
    }
    return n;
}

bool LoopSubdivide(const std::vector<Vec3f> &P, const std::vector<uint32_t> &indices, int levels,
                   LoopSubdivisionMesh *out, std::string *error) {
    *out = LoopSubdivisionMesh{};
    // Faces that repeat a vertex dropped; only the vertices the others use, in their order.
    auto degenerate = [&](size_t i) {
        uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
        return a == b || b == c || a == c;
    };
    std::vector<uint32_t> remap(P.size(), None);
    for (size_t i = 0; i + 2 < indices.size(); i += 3)
        if (!degenerate(i))
            for (int k = 0; k < 3; ++k) remap[indices[i + k]] = 0;
    SubdivisionMesh m;
    for (size_t v = 0; v < P.size(); ++v)
        if (remap[v] == 0) {
            remap[v] = uint32_t(m.p.size());
            m.p.push_back(P[v]);
        }
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        if (degenerate(i)) {
            ++out->droppedFaces;
            continue;
        }
        Face f;
        for (int k = 0; k < 3; ++k) f.v[k] = remap[indices[i + k]];
        m.faces.push_back(f);
    }
    if (m.faces.empty()) {
        *error = "no face with three distinct vertices";
        return false;
    }
    m.startFace.assign(m.p.size(), None);
    m.boundary.assign(m.p.size(), 0);
    if (!BuildTopology(m, error)) return false;

    for (int level = 0; level < levels; ++level) Refine(m);

    // Limit positions, then the limit tangents from the moved one-rings (pbrt-v4's order).
    std::vector<Vec3f> ring;
    std::vector<Vec3f> limit(m.p.size());
    for (uint32_t v = 0; v < m.p.size(); ++v)
        limit[v] = m.boundary[v] ? m.WeightBoundary(v, Float(1) / 5, ring) : m.WeightOneRing(v, LoopGamma(m.Valence(v)), ring);
    m.p = limit;
    out->N.resize(m.p.size());
    for (uint32_t v = 0; v < m.p.size(); ++v) {
        m.OneRing(v, ring);
        const int n = int(ring.size());
        const Vec3f p = m.p[v];
        Vec3f S(0, 0, 0), T(0, 0, 0);
        if (!m.boundary[v]) {
            for (int j = 0; j < n; ++j) {
                double phi = 2 * Pi * double(j) / double(n);
                S += Float(std::cos(phi)) * ring[j];
                T += Float(std::sin(phi)) * ring[j];
            }
        } else {
            S = ring[n - 1] - ring[0];
            if (n == 2) T = ring[0] + ring[1] - 2 * p;
            else if (n == 3) T = ring[1] - p;
            else if (n == 4) T = -1 * ring[0] + 2 * ring[1] + 2 * ring[2] - ring[3] - 2 * p;
            else {
                double theta = Pi / double(n - 1);
                T = Float(std::sin(theta)) * (ring[0] + ring[n - 1]);
                for (int k = 1; k < n - 1; ++k) T += Float((2 * std::cos(theta) - 2) * std::sin(k * theta)) * ring[k];
                T = -T;
            }
        }
        out->N[v] = Cross(S, T);
    }
    out->P = std::move(m.p);
    out->indices.reserve(m.faces.size() * 3);
    for (const Face &f : m.faces) out->indices.insert(out->indices.end(), f.v, f.v + 3);

    // A limit normal of zero length (a degenerate control mesh) would make the shading normal
    // NaN: such vertices take the area-weighted normal of their triangles instead.
    std::vector<Vec3f> faceSum;
    for (uint32_t v = 0; v < out->N.size(); ++v) {
        const Vec3f &nv = out->N[v];
        if (LengthSquared(nv) > 0 && std::isfinite(nv.x + nv.y + nv.z)) continue;
        if (faceSum.empty()) {
            faceSum.assign(out->P.size(), Vec3f(0, 0, 0));
            for (size_t i = 0; i < out->indices.size(); i += 3) {
                uint32_t a = out->indices[i], b = out->indices[i + 1], c = out->indices[i + 2];
                Vec3f fn = Cross(out->P[b] - out->P[a], out->P[c] - out->P[a]);
                faceSum[a] += fn;
                faceSum[b] += fn;
                faceSum[c] += fn;
            }
        }
        out->N[v] = faceSum[v];
    }
    return true;
}

}  // namespace lu
