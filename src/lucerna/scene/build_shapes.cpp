// Lucerna scene builder: shapes (trianglemesh, plymesh, bilinearmesh, loopsubdiv, sphere, disk, cylinder, curve), their area
// lights and object instances (prototypes in object space plus instance records, or flattened), after pbrt-v4's shapes.cpp Create() functions,
// TriangleMesh (util/mesh.cpp) and BasicScene::CreateLights / CreateAggregate (scene.cpp).
#include <cmath>

#include "lucerna/geometry/shapes.h"
#include "lucerna/scene/build_internal.h"
#include "lucerna/scene/loop_subdivision.h"
#include "lucerna/scene/ply.h"

namespace lu::build {

namespace {

// Raw (object-space) triangle geometry of one shape before it is placed in the scene.
struct MeshData {
    std::vector<Vec3f> P, N;
    std::vector<Vec2f> uv;
    std::vector<uint32_t> indices;
    // Area used by the "power" normalization of each triangle's light; empty: the triangle's
    // own render-space area (bilinear patches use the patch area, as pbrt-v4 has one light per patch).
    std::vector<Float> powerArea;
};

// What a Shape directive becomes, and where it goes.
struct Placement {
    const ShapeEntity *shape = nullptr;
    Transform renderFromObject;
    // renderFromObject has no inverse (a zero scale: the parser filled mInv with NaN). Analytic
    // shapes intersect in object space and are dropped; meshes lose their per-vertex normals.
    bool singular = false;
    bool firstUse = true;  // the first placement of this Shape directive (warnings are given once)
    std::string where;     // "" at top level; " (object instance \"name\" used at FILE:LINE:COL)"
    bool reverseOrientation = false;
    bool analyticSwapsHandedness = false;  // handedness of the shape's own transform (instances: not the instance's)
    uint32_t material = NoIndex;
    const AreaLightParams *areaLight = nullptr;
};

bool IsFiniteMatrix(const Matrix4 &m) {
    for (const auto &row : m.m)
        for (Float x : row)
            if (!std::isfinite(x)) return false;
    return true;
}

// A warning about one Shape directive, given once (an instance used many times would repeat it).
void ShapeWarning(BuildContext &ctx, const Placement &pl, const std::string &message) {
    if (pl.firstUse) ctx.diag.Warning(pl.shape->loc, message + pl.where);
}

void ExpandBounds(Bounds3f &b, const Transform &t, const Vec3f &pMin, const Vec3f &pMax) {
    for (int i = 0; i < 8; ++i) {
        Vec3f p((i & 1) ? pMax.x : pMin.x, (i & 2) ? pMax.y : pMin.y, (i & 4) ? pMax.z : pMin.z);
        b.Expand(t.ApplyPoint(p));
    }
}

uint32_t AddAreaLights(BuildContext &ctx, const Placement &pl, uint32_t shapeIndex, const std::vector<Float> &areas) {
    HostScene &s = ctx.scene;
    uint32_t first = uint32_t(s.lights.size());
    const std::string origin =
        "AreaLightSource \"diffuse\" on Shape " + Quoted(pl.shape->name) + " at " + pl.shape->loc.ToString() + pl.where;
    for (size_t i = 0; i < areas.size(); ++i) {
        Light l;
        l.kind = LightKind::DiffuseArea;
        l.spectrum = pl.areaLight->L;
        l.scale = AreaLightPrimitiveScale(*pl.areaLight, areas[i]);
        l.renderFromLight = pl.renderFromObject;
        l.shape = shapeIndex;
        l.primitive = uint32_t(i);
        l.twoSided = pl.areaLight->twoSided;
        l.image = pl.areaLight->image;
        s.SetOrigin(s.lightOrigin, s.lights.size(), origin);
        s.lights.push_back(l);
    }
    s.stats.lightsByType[pl.areaLight->image != NoIndex ? "diffuse area (image)" : "diffuse area"] += int(areas.size());
    return first;
}

// Adds a triangle mesh in render space: vertices by renderFromObject, normals by its inverse
// transpose and negated for ReverseOrientation (pbrt-v4's TriangleMesh constructor).
// A mesh that keeps no area in render space (every triangle degenerate, e.g. under "Scale 0 0 0"
// or a mesh lying in a plane the transformation collapses to a line) is dropped with a warning.
void AddTriangles(BuildContext &ctx, const Placement &pl, MeshData &mesh) {
    HostScene &s = ctx.scene;
    const Transform &t = pl.renderFromObject;
    const std::string &name = pl.shape->name;
    // ---- Render-space geometry: finite positions and normals, some area ----
    std::vector<Vec3f> P(mesh.P.size());
    for (size_t i = 0; i < P.size(); ++i) {
        P[i] = t.ApplyPoint(mesh.P[i]);
        if (!IsFinite(P[i].x) || !IsFinite(P[i].y) || !IsFinite(P[i].z))
            Fail(pl.shape->loc, name + ": vertex " + std::to_string(i) + " is not finite after the transformation" + pl.where);
    }
    uint32_t triangleCount = uint32_t(mesh.indices.size() / 3);
    std::vector<Float> areas(triangleCount);
    bool hasArea = false;
    for (uint32_t i = 0; i < triangleCount; ++i) {
        const Vec3f &p0 = P[mesh.indices[3 * i]], &p1 = P[mesh.indices[3 * i + 1]], &p2 = P[mesh.indices[3 * i + 2]];
        areas[i] = 0.5f * Length(Cross(p1 - p0, p2 - p0));
        hasArea = hasArea || areas[i] > 0;
    }
    if (!hasArea) {
        ShapeWarning(ctx, pl, name + " has zero area" +
                                  std::string(pl.singular ? " under its singular (non-invertible) transformation" : "") +
                                  "; it is not rendered" + std::string(pl.areaLight ? " and emits no light" : ""));
        return;
    }
    std::vector<Vec3f> N(mesh.N.size());
    bool finiteNormals = !pl.singular;
    for (size_t i = 0; i < N.size() && finiteNormals; ++i) {
        N[i] = t.ApplyNormal(mesh.N[i]);
        finiteNormals = IsFinite(N[i].x) && IsFinite(N[i].y) && IsFinite(N[i].z);
    }
    if (!N.empty() && !finiteNormals) {
        ShapeWarning(ctx, pl, name + ": the transformation is not invertible; the per-vertex normals \"N\" are "
                                     "discarded (the geometric normal is used)");
        N.clear();
    }

    TriangleMesh tm;
    tm.firstVertex = uint32_t(s.positions.size());
    tm.vertexCount = uint32_t(mesh.P.size());
    tm.firstIndex = uint32_t(s.indices.size());
    tm.triangleCount = triangleCount;
    tm.flipNormals = pl.reverseOrientation != t.SwapsHandedness();
    for (const Vec3f &q : P) {
        s.positions.push_back(q);
        s.bounds.Expand(q);
    }
    if (!N.empty()) {
        tm.normalOffset = uint32_t(s.normals.size());
        for (const Vec3f &m : N) s.normals.push_back(pl.reverseOrientation ? -m : m);
    }
    if (!mesh.uv.empty()) {
        tm.uvOffset = uint32_t(s.uvs.size());
        s.uvs.insert(s.uvs.end(), mesh.uv.begin(), mesh.uv.end());
    }
    s.indices.insert(s.indices.end(), mesh.indices.begin(), mesh.indices.end());

    Shape shape;
    shape.kind = ShapeKind::Triangles;
    shape.index = uint32_t(s.triangleMeshes.size());
    shape.material = pl.material;
    shape.primitiveCount = tm.triangleCount;
    uint32_t shapeIndex = uint32_t(s.shapes.size());
    if (pl.areaLight) {
        // Degenerate triangles get lights of zero power, which the light CDF never picks.
        if (!mesh.powerArea.empty()) areas = mesh.powerArea;
        shape.areaLight = AddAreaLights(ctx, pl, shapeIndex, areas);
    }
    s.triangleMeshes.push_back(tm);
    s.shapes.push_back(shape);
    s.stats.triangles += tm.triangleCount;
}

// pbrt-v4's Triangle::CreateMesh checks on P / indices / uv / N / S.
void CheckMesh(BuildContext &ctx, const ShapeEntity &sh, MeshData &m, const char *what) {
    if (m.P.empty()) Fail(sh.loc, std::string(what) + ": vertex positions \"P\" must be provided");
    if (m.indices.empty()) {
        if (m.P.size() == 3) m.indices = {0, 1, 2};
        else Fail(sh.loc, std::string(what) + ": vertex indices \"indices\" must be provided");
    } else if (m.indices.size() % 3 != 0) {
        ctx.diag.Warning(sh.loc, std::string(what) + ": number of vertex indices " + std::to_string(m.indices.size()) +
                                     " is not a multiple of 3; discarding " + std::to_string(m.indices.size() % 3) + " excess");
        m.indices.resize(m.indices.size() - m.indices.size() % 3);
    }
    for (uint32_t i : m.indices)
        if (i >= m.P.size())
            Fail(sh.loc, std::string(what) + " has out-of-bounds vertex index " + std::to_string(i) + " (" +
                             std::to_string(m.P.size()) + " \"P\" values were given)");
    if (!m.uv.empty() && m.uv.size() != m.P.size()) {
        ctx.diag.Warning(sh.loc, std::string(what) + ": number of \"uv\"s must match \"P\"s; discarding uvs");
        m.uv.clear();
    }
    if (!m.N.empty() && m.N.size() != m.P.size()) {
        ctx.diag.Warning(sh.loc, std::string(what) + ": number of \"N\"s must match \"P\"s; discarding \"N\"s");
        m.N.clear();
    }
}

std::vector<uint32_t> ToIndices(BuildContext &, const ShapeEntity &sh, const std::vector<int> &v) {
    std::vector<uint32_t> r;
    r.reserve(v.size());
    for (int i : v) {
        if (i < 0) Fail(ParamLoc(sh.params, "indices", sh.loc), "negative vertex index " + std::to_string(i));
        r.push_back(uint32_t(i));
    }
    return r;
}

void BuildTriangleMesh(BuildContext &ctx, const Placement &pl) {
    const ShapeEntity &sh = *pl.shape;
    const ParameterDictionary &p = sh.params;
    MeshData m;
    m.indices = ToIndices(ctx, sh, p.GetIntArray("indices"));
    m.P = p.GetPoint3fArray("P");
    m.uv = p.GetPoint2fArray("uv");
    m.N = p.GetNormal3fArray("N");
    std::vector<Vec3f> S = p.GetVector3fArray("S");
    (void)p.GetIntArray("faceIndices");  // only used by ptex textures
    CheckMesh(ctx, sh, m, "trianglemesh");
    if (!S.empty())
        ctx.diag.Unsupported(ParamLoc(p, "S", sh.loc), "trianglemesh per-vertex tangents \"S\"",
                             "the shading frame's tangent comes from the uv parameterization");
    AddTriangles(ctx, pl, m);
}

void BuildPlyMesh(BuildContext &ctx, const Placement &pl) {
    const ShapeEntity &sh = *pl.shape;
    const ParameterDictionary &p = sh.params;
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty()) Fail(sh.loc, "plymesh: \"string filename\" must be provided");
    if (p.Has("displacement")) {
        (void)p.Find("displacement");
        (void)p.GetOneFloat("edgelength", 1);
        ctx.diag.Unsupported(ParamLoc(p, "displacement", sh.loc), "plymesh \"displacement\"", "the mesh is not displaced");
    }
    std::string path = ResolveScenePath(ctx, sh.baseDirectory, filename);
    ctx.scene.inputFiles.push_back(path);
    PlyMesh ply = ReadPlyMesh(path, sh.loc, &ctx.diag);
    MeshData m;
    m.P = std::move(ply.P);
    m.N = std::move(ply.N);
    m.uv = std::move(ply.uv);
    m.indices = std::move(ply.indices);
    if (ply.quadCount > 0)
        ctx.diag.Warning(sh.loc, "plymesh " + Quoted(filename) + ": " + std::to_string(ply.quadCount) +
                                     " quads rendered as triangle pairs (pbrt-v4 renders them as bilinear patches)");
    if (m.indices.empty()) Fail(sh.loc, "plymesh " + Quoted(filename) + ": no faces");
    CheckMesh(ctx, sh, m, "plymesh");
    AddTriangles(ctx, pl, m);
}

// Adds curved bilinear patches natively (geometry/bilinear_patch.h): render-space corners, each
// patch its own four vertices; normals by the inverse transpose and negated for
// ReverseOrientation, as the triangle meshes'. vi: four object-space vertex indices per patch.
void AddBilinearPatches(BuildContext &ctx, const Placement &pl, const std::vector<Vec3f> &P, const std::vector<Vec3f> &N,
                        const std::vector<Vec2f> &uv, const std::vector<uint32_t> &vi) {
    HostScene &s = ctx.scene;
    const Transform &t = pl.renderFromObject;
    const uint32_t patchCount = uint32_t(vi.size() / 4);
    if (patchCount == 0) return;
    BilinearMesh bm;
    bm.firstVertex = uint32_t(s.positions.size());
    bm.vertexCount = 4 * patchCount;
    bm.firstIndex = uint32_t(s.indices.size());
    bm.patchCount = patchCount;
    bm.flipNormals = pl.reverseOrientation != t.SwapsHandedness();
    bool useNormals = !N.empty() && !pl.singular;
    for (uint32_t k = 0; k < vi.size() && useNormals; ++k) {
        Vec3f n = t.ApplyNormal(N[vi[k]]);
        useNormals = IsFinite(n.x) && IsFinite(n.y) && IsFinite(n.z);
    }
    if (!N.empty() && !useNormals)
        ShapeWarning(ctx, pl, "bilinearmesh: the transformation is not invertible; the per-vertex normals \"N\" are "
                              "discarded (the geometric normal is used)");
    if (useNormals) bm.normalOffset = uint32_t(s.normals.size());
    if (!uv.empty()) bm.uvOffset = uint32_t(s.uvs.size());
    std::vector<Float> areas(patchCount);
    for (uint32_t q = 0; q < patchCount; ++q) {
        PatchCorners c;
        Vec3f *corner[4] = {&c.p00, &c.p10, &c.p01, &c.p11};
        for (int k = 0; k < 4; ++k) {
            uint32_t v = vi[4 * q + k];
            Vec3f p = t.ApplyPoint(P[v]);
            if (!IsFinite(p.x) || !IsFinite(p.y) || !IsFinite(p.z))
                Fail(pl.shape->loc, "bilinearmesh: vertex " + std::to_string(v) + " is not finite after the transformation" + pl.where);
            *corner[k] = p;
            s.positions.push_back(p);
            s.bounds.Expand(p);
            s.indices.push_back(4 * q + uint32_t(k));
            if (useNormals) {
                Vec3f n = t.ApplyNormal(N[v]);
                s.normals.push_back(pl.reverseOrientation ? -n : n);
            }
            if (!uv.empty()) s.uvs.push_back(uv[v]);
        }
        areas[q] = BilinearPatchArea(c);
    }
    Shape shape;
    shape.kind = ShapeKind::BilinearPatches;
    shape.index = uint32_t(s.bilinearMeshes.size());
    shape.material = pl.material;
    shape.primitiveCount = patchCount;
    uint32_t shapeIndex = uint32_t(s.shapes.size());
    if (pl.areaLight) shape.areaLight = AddAreaLights(ctx, pl, shapeIndex, areas);
    s.bilinearMeshes.push_back(bm);
    s.shapes.push_back(shape);
    s.stats.bilinearPatches += patchCount;
}

// Whether four values of a patch's corners are an affine function of (u, v) (p00 + p11 =
// p10 + p01, to rounding): then the bilinear interpolation over the patch is the linear one over
// each of its two triangles.
template <typename V>
bool AffineCorners(const V &a00, const V &a10, const V &a01, const V &a11, Float scale) {
    V d = (a00 + a11) - (a10 + a01);
    Float dd = 0, ss = 0;
    const Float *pd = &d.x, *p00 = &a00.x, *p11 = &a11.x;
    for (size_t i = 0; i < sizeof(V) / sizeof(Float); ++i) {
        dd = Max(dd, std::abs(pd[i]));
        ss = Max(ss, Max(std::abs(p00[i] - p11[i]), std::abs(p00[i])));
    }
    return dd <= scale * ss;
}

// pbrt-v4's bilinear patches (vertices p00, p10, p01, p11). A patch whose corners make a
// parallelogram, with affine uv and normals, is exactly the two triangles (p00, p10, p11) and
// (p00, p11, p01) (with the patch's (u, v) as uv when there is no "uv"), and is rendered as them
// (Embree's triangles are faster than the patch test); any other patch is a native bilinear
// patch. Both kinds of one Shape become two shapes.
void BuildBilinearMesh(BuildContext &ctx, const Placement &pl) {
    const ShapeEntity &sh = *pl.shape;
    const ParameterDictionary &p = sh.params;
    std::vector<uint32_t> vi = ToIndices(ctx, sh, p.GetIntArray("indices"));
    std::vector<Vec3f> P = p.GetPoint3fArray("P");
    std::vector<Vec2f> uv = p.GetPoint2fArray("uv");
    std::vector<Vec3f> N = p.GetNormal3fArray("N");
    (void)p.GetIntArray("faceIndices");
    if (p.Has("emissionfilename"))
        FailUnsupported(ParamLoc(p, "emissionfilename", sh.loc), "bilinearmesh \"emissionfilename\" (textured emission)");
    if (P.empty()) Fail(sh.loc, "bilinearmesh: vertex positions \"P\" must be provided");
    if (vi.empty()) {
        if (P.size() == 4) vi = {0, 1, 2, 3};
        else Fail(sh.loc, "bilinearmesh: vertex indices \"indices\" must be provided");
    } else if (vi.size() % 4 != 0) {
        ctx.diag.Warning(sh.loc, "bilinearmesh: number of vertex indices is not a multiple of 4; discarding excess");
        vi.resize(vi.size() - vi.size() % 4);
    }
    for (uint32_t i : vi)
        if (i >= P.size()) Fail(sh.loc, "bilinearmesh has out-of-bounds vertex index " + std::to_string(i));
    if (!uv.empty() && uv.size() != P.size()) {
        ctx.diag.Warning(sh.loc, "bilinearmesh: number of \"uv\"s must match \"P\"s; discarding uvs");
        uv.clear();
    }
    if (!N.empty() && N.size() != P.size()) {
        ctx.diag.Warning(sh.loc, "bilinearmesh: number of \"N\"s must match \"P\"s; discarding \"N\"s");
        N.clear();
    }
    MeshData m;
    std::vector<uint32_t> curved;   // the native patches' vertex indices
    static const Vec2f patchUV[4] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    for (size_t q = 0; q < vi.size(); q += 4) {
        const uint32_t *v = &vi[q];
        Vec3f w[4];
        for (int k = 0; k < 4; ++k) w[k] = pl.renderFromObject.ApplyPoint(P[v[k]]);
        bool flat = AffineCorners(w[0], w[1], w[2], w[3], Float(1e-5)) &&
                    (uv.empty() || AffineCorners(uv[v[0]], uv[v[1]], uv[v[2]], uv[v[3]], Float(1e-5))) &&
                    (N.empty() || AffineCorners(N[v[0]], N[v[1]], N[v[2]], N[v[3]], Float(1e-5)));
        if (!flat) {
            curved.insert(curved.end(), v, v + 4);
            continue;
        }
        uint32_t base = uint32_t(m.P.size());
        for (int k = 0; k < 4; ++k) {
            m.P.push_back(P[v[k]]);
            if (!N.empty()) m.N.push_back(N[v[k]]);
            m.uv.push_back(uv.empty() ? patchUV[k] : uv[v[k]]);
        }
        const uint32_t tri[6] = {0, 1, 3, 0, 3, 2};
        for (uint32_t k : tri) m.indices.push_back(base + k);
        // Render-space patch area (pbrt-v4 normalizes "power" per patch).
        Float a0 = 0.5f * Length(Cross(w[1] - w[0], w[3] - w[0]));
        Float a1 = 0.5f * Length(Cross(w[3] - w[0], w[2] - w[0]));
        m.powerArea.push_back(a0 + a1);
        m.powerArea.push_back(a0 + a1);
    }
    if (!pl.areaLight) m.powerArea.clear();
    if (!m.indices.empty()) AddTriangles(ctx, pl, m);
    AddBilinearPatches(ctx, pl, P, N, uv, curved);
}

// Adds the render-space box of an analytic shape's object-space box to the scene bounds; a
// projective "Transform" that sends a corner to infinity is an error (the box goes to Embree).
void AddBounds(BuildContext &ctx, const Placement &pl, const Vec3f &pMin, const Vec3f &pMax) {
    for (int i = 0; i < 8; ++i) {
        Vec3f p((i & 1) ? pMax.x : pMin.x, (i & 2) ? pMax.y : pMin.y, (i & 4) ? pMax.z : pMin.z);
        Vec3f q = pl.renderFromObject.ApplyPoint(p);
        if (!IsFinite(q.x) || !IsFinite(q.y) || !IsFinite(q.z))
            Fail(pl.shape->loc, pl.shape->name + ": the transformation sends the shape to infinity" + pl.where);
    }
    ExpandBounds(ctx.scene.bounds, pl.renderFromObject, pMin, pMax);
}

// Spheres and disks are intersected in object space through the inverse transformation; under a
// singular one they are flat (or a point, a segment) and pbrt-v4 cannot intersect them either.
void DropSingular(BuildContext &ctx, const Placement &pl) {
    ShapeWarning(ctx, pl, pl.shape->name + ": the transformation is singular (not invertible), so the shape is flat or "
                                           "degenerate; it is not rendered" +
                              std::string(pl.areaLight ? " and its area light is dropped" : ""));
}

// A quadric cut down to no area (zmin = zmax, phimax = 0) is never hit; pbrt-v4 keeps it.
void DropEmpty(BuildContext &ctx, const Placement &pl) {
    ShapeWarning(ctx, pl, pl.shape->name + ": the shape has no area (\"zmin\" = \"zmax\" or \"phimax\" 0); it is not rendered" +
                              std::string(pl.areaLight ? " and its area light is dropped" : ""));
}

// The area light of an analytic shape: pbrt-v4 takes its power and sampling from the object-space
// area (transform scale ignored).
uint32_t AddQuadricAreaLight(BuildContext &ctx, const Placement &pl, uint32_t shapeIndex, Float objectArea) {
    if (HasScale(pl.renderFromObject))
        ctx.diag.Warning(pl.shape->loc, "scaling detected in the area light's transformation: pbrt-v4 assumes none "
                                        "(its power and sampling use the object-space radius)");
    return AddAreaLights(ctx, pl, shapeIndex, {objectArea});
}

void AddQuadricShape(BuildContext &ctx, const Placement &pl, ShapeKind kind, uint32_t index, Float objectArea) {
    HostScene &s = ctx.scene;
    Shape shape;
    shape.kind = kind;
    shape.index = index;
    shape.material = pl.material;
    uint32_t shapeIndex = uint32_t(s.shapes.size());
    if (pl.areaLight) shape.areaLight = AddQuadricAreaLight(ctx, pl, shapeIndex, objectArea);
    s.shapes.push_back(shape);
}

// pbrt-v4's Sphere::Create: radius, zmin, zmax (clamped to [-radius, radius]), phimax (degrees,
// clamped to [0, 360]); a partial sphere is cut to zmin <= z <= zmax, phi <= phimax.
void BuildSphere(BuildContext &ctx, const Placement &pl) {
    const ShapeEntity &sh = *pl.shape;
    const ParameterDictionary &p = sh.params;
    Float radius = Float(p.GetOneFloat("radius", 1));
    Float zmin = Float(p.GetOneFloat("zmin", -radius)), zmax = Float(p.GetOneFloat("zmax", radius));
    Float phimax = Float(p.GetOneFloat("phimax", 360));
    if (!(radius > 0)) Fail(ParamLoc(p, "radius", sh.loc), "sphere radius must be positive");
    if (pl.singular) return DropSingular(ctx, pl);
    Sphere sp;
    sp.renderFromObject = pl.renderFromObject;
    sp.radius = radius;
    SetSphereClip(sp, zmin, zmax, phimax);
    sp.flipNormals = pl.reverseOrientation != pl.analyticSwapsHandedness;
    if (!(SphereArea(sp) > 0)) return DropEmpty(ctx, pl);
    // pbrt-v4's Sphere::Bounds: the z range's slab of the sphere's box.
    AddBounds(ctx, pl, Vec3f(-radius, -radius, sp.zMin), Vec3f(radius, radius, sp.zMax));
    AddQuadricShape(ctx, pl, ShapeKind::Sphere, uint32_t(ctx.scene.spheres.size()), SphereArea(sp));
    ctx.scene.spheres.push_back(sp);
}

// pbrt-v4's Disk::Create: height, radius, innerradius, phimax (degrees, clamped to [0, 360]).
void BuildDisk(BuildContext &ctx, const Placement &pl) {
    const ShapeEntity &sh = *pl.shape;
    const ParameterDictionary &p = sh.params;
    Float height = Float(p.GetOneFloat("height", 0));
    Float radius = Float(p.GetOneFloat("radius", 1));
    Float inner = Float(p.GetOneFloat("innerradius", 0));
    Float phimax = Float(p.GetOneFloat("phimax", 360));
    if (!(radius > 0) || inner < 0 || inner >= radius)
        Fail(sh.loc, "disk needs 0 <= innerradius < radius");
    if (pl.singular) return DropSingular(ctx, pl);
    Disk d;
    d.renderFromObject = pl.renderFromObject;
    d.height = height;
    d.radius = radius;
    d.innerRadius = inner;
    d.phiMax = PhiMaxRadians(phimax);
    d.flipNormals = pl.reverseOrientation != pl.analyticSwapsHandedness;
    if (!(DiskArea(d) > 0)) return DropEmpty(ctx, pl);
    AddBounds(ctx, pl, Vec3f(-radius, -radius, height), Vec3f(radius, radius, height));
    AddQuadricShape(ctx, pl, ShapeKind::Disk, uint32_t(ctx.scene.disks.size()), DiskArea(d));
    ctx.scene.disks.push_back(d);
}

// pbrt-v4's Cylinder::Create: radius (1), zmin (-1), zmax (1) (ordered), phimax (360, clamped to
// [0, 360]); the open tube, no caps.
void BuildCylinder(BuildContext &ctx, const Placement &pl) {
    const ShapeEntity &sh = *pl.shape;
    const ParameterDictionary &p = sh.params;
    Float radius = Float(p.GetOneFloat("radius", 1));
    Float zmin = Float(p.GetOneFloat("zmin", -1)), zmax = Float(p.GetOneFloat("zmax", 1));
    Float phimax = Float(p.GetOneFloat("phimax", 360));
    if (!(radius > 0)) Fail(ParamLoc(p, "radius", sh.loc), "cylinder radius must be positive");
    if (pl.singular) return DropSingular(ctx, pl);
    Cylinder c;
    c.renderFromObject = pl.renderFromObject;
    c.radius = radius;
    c.zMin = Min(zmin, zmax);
    c.zMax = Max(zmin, zmax);
    c.phiMax = PhiMaxRadians(phimax);
    c.flipNormals = pl.reverseOrientation != pl.analyticSwapsHandedness;
    if (!(CylinderArea(c) > 0)) return DropEmpty(ctx, pl);
    AddBounds(ctx, pl, Vec3f(-radius, -radius, c.zMin), Vec3f(radius, radius, c.zMax));
    AddQuadricShape(ctx, pl, ShapeKind::Cylinder, uint32_t(ctx.scene.cylinders.size()), CylinderArea(c));
    ctx.scene.cylinders.push_back(c);
}

// pbrt-v4's Curve::Create: "P" control points of a "bezier" (degree + 1 + n degree of them) or
// uniform "bspline" (at least degree + 1) curve of "degree" 2 or 3, each segment turned into a
// cubic Bezier segment; widths "width0" to "width1" ("width", default 1) spread linearly over
// the segments; "type" flat, cylinder or ribbon ("N": a normal per segment end, ribbons only);
// each segment split into 2^"splitdepth" (default 3) primitives. pbrt-v4 reports bad counts and
// an unknown type and renders on without the shape; here they are located errors.
void BuildCurve(BuildContext &ctx, const Placement &pl) {
    const ShapeEntity &sh = *pl.shape;
    const ParameterDictionary &p = sh.params;
    Float width = Float(p.GetOneFloat("width", 1));
    Float width0 = Float(p.GetOneFloat("width0", width)), width1 = Float(p.GetOneFloat("width1", width));
    int degree = p.GetOneInt("degree", 3);
    std::string basis = p.GetOneString("basis", "bezier");
    std::string typeName = p.GetOneString("type", "flat");
    int splitDepth = p.GetOneInt("splitdepth", 3);
    std::vector<Vec3f> cp = p.GetPoint3fArray("P");
    std::vector<Vec3f> N = p.GetNormal3fArray("N");
    if (pl.areaLight)
        FailUnsupported(sh.loc, "AreaLightSource on a \"curve\" shape (pbrt-v4 cannot sample curves either: its "
                                "Curve::Sample is not implemented)");
    if (degree != 2 && degree != 3) Fail(ParamLoc(p, "degree", sh.loc), "curve: \"degree\" must be 2 or 3");
    if (basis != "bezier" && basis != "bspline")
        Fail(ParamLoc(p, "basis", sh.loc), "curve: unknown \"basis\" " + Quoted(basis) + " (bezier or bspline)");
    CurveType type;
    if (typeName == "flat") type = CurveType::Flat;
    else if (typeName == "cylinder") type = CurveType::Cylinder;
    else if (typeName == "ribbon") type = CurveType::Ribbon;
    else Fail(ParamLoc(p, "type", sh.loc), "curve: unknown \"type\" " + Quoted(typeName) + " (flat, cylinder or ribbon)");
    if (!(width0 >= 0) || !(width1 >= 0) || !IsFinite(width0) || !IsFinite(width1))
        Fail(sh.loc, "curve: widths must be finite and not negative");
    if (splitDepth < 0 || splitDepth > 10)
        Fail(ParamLoc(p, "splitdepth", sh.loc), "curve: \"splitdepth\" must be in [0, 10] (2^splitdepth primitives per segment)");
    const size_t n = cp.size();
    size_t nSegments = 0;
    if (basis == "bezier") {
        if (n < size_t(degree) + 1 || (n - 1 - size_t(degree)) % size_t(degree) != 0)
            Fail(ParamLoc(p, "P", sh.loc), "curve: " + std::to_string(n) + " control points; a degree " +
                                               std::to_string(degree) + " Bezier curve needs " + std::to_string(degree + 1) +
                                               " + k * " + std::to_string(degree) + " of them (k >= 0)");
        nSegments = (n - 1) / size_t(degree);
    } else {
        if (n < size_t(degree) + 1)
            Fail(ParamLoc(p, "P", sh.loc), "curve: " + std::to_string(n) + " control points; a degree " +
                                               std::to_string(degree) + " b-spline needs at least " + std::to_string(degree + 1));
        nSegments = n - size_t(degree);
    }
    if (!N.empty() && type != CurveType::Ribbon) {
        ctx.diag.Warning(ParamLoc(p, "N", sh.loc), "curve: normals \"N\" are only used by \"ribbon\" curves; discarded");
        N.clear();
    } else if (type == CurveType::Ribbon && N.size() != nSegments + 1) {
        Fail(ParamLoc(p, "N", sh.loc), "curve: a ribbon curve of " + std::to_string(nSegments) + " segments needs " +
                                           std::to_string(nSegments + 1) + " normals \"N\" (one per segment end), not " +
                                           std::to_string(N.size()));
    }
    if (pl.singular) return DropSingular(ctx, pl);
    uint64_t primitives = uint64_t(nSegments) << splitDepth;
    if (primitives > (uint64_t(1) << 31))
        Fail(sh.loc, "curve: " + std::to_string(primitives) + " primitives (segments x 2^splitdepth) are too many");
    HostScene &s = ctx.scene;
    CurveSet cs;
    cs.renderFromObject = pl.renderFromObject;
    cs.firstSegment = uint32_t(s.curveSegments.size());
    cs.segmentCount = uint32_t(nSegments);
    cs.type = type;
    cs.splitDepth = uint8_t(splitDepth);
    cs.flipNormals = pl.reverseOrientation != pl.analyticSwapsHandedness;
    auto lerp3 = [](Float t, const Vec3f &a, const Vec3f &b) { return a + (b - a) * t; };
    for (size_t seg = 0; seg < nSegments; ++seg) {
        CurveSegment cs4;
        Vec3f *q = cs4.cp;
        if (basis == "bezier") {
            const Vec3f *c = &cp[seg * size_t(degree)];
            if (degree == 3) {
                for (int i = 0; i < 4; ++i) q[i] = c[i];
            } else {   // pbrt-v4's ElevateQuadraticBezierToCubic
                q[0] = c[0];
                q[1] = lerp3(Float(2) / 3, c[0], c[1]);
                q[2] = lerp3(Float(1) / 3, c[1], c[2]);
                q[3] = c[2];
            }
        } else {
            const Vec3f *c = &cp[seg];
            if (degree == 3) {   // pbrt-v4's CubicBSplineToBezier
                q[0] = (c[0] + c[1] * 4 + c[2]) / Float(6);
                q[1] = (c[1] * 2 + c[2]) / Float(3);
                q[2] = (c[1] + c[2] * 2) / Float(3);
                q[3] = (c[1] + c[2] * 4 + c[3]) / Float(6);
            } else {             // QuadraticBSplineToBezier, then elevated
                Vec3f b0 = (c[0] + c[1]) / Float(2), b1 = c[1], b2 = (c[1] + c[2]) / Float(2);
                q[0] = b0;
                q[1] = lerp3(Float(2) / 3, b0, b1);
                q[2] = lerp3(Float(1) / 3, b1, b2);
                q[3] = b2;
            }
        }
        cs4.width[0] = Lerp(Float(seg) / Float(nSegments), width0, width1);
        cs4.width[1] = Lerp(Float(seg + 1) / Float(nSegments), width0, width1);
        if (type == CurveType::Ribbon) {
            for (int e = 0; e < 2; ++e) {
                Vec3f nn = N[seg + size_t(e)];
                if (!(LengthSquared(nn) > 0)) Fail(ParamLoc(p, "N", sh.loc), "curve: a ribbon normal \"N\" is zero");
                cs4.n[e] = Normalize(nn);
            }
        }
        s.curveSegments.push_back(cs4);
    }
    Shape shape;
    shape.kind = ShapeKind::Curves;
    shape.index = uint32_t(s.curveSets.size());
    shape.material = pl.material;
    shape.primitiveCount = uint32_t(primitives);
    s.curveSets.push_back(cs);
    s.shapes.push_back(shape);
    s.stats.curveSegments += nSegments;
    // Scene bounds: every piece's box.
    SceneView view = s.View();
    const Shape &added = s.shapes.back();
    for (uint32_t prim = 0; prim < added.primitiveCount; ++prim) {
        Bounds3f b = PatchOrCurveBounds(view, added, prim);
        if (!IsFinite(b.pMin.x) || !IsFinite(b.pMin.y) || !IsFinite(b.pMin.z) || !IsFinite(b.pMax.x) ||
            !IsFinite(b.pMax.y) || !IsFinite(b.pMax.z))
            Fail(sh.loc, "curve: the transformation sends the shape to infinity" + pl.where);
        s.bounds.Expand(b.pMin);
        s.bounds.Expand(b.pMax);
    }
}

// A finite transformation is required (an instance's product of two can overflow); a singular one
// sets pl.singular.
void CheckTransform(Placement &pl, const FileLoc &loc) {
    if (!IsFiniteMatrix(pl.renderFromObject.m))
        Fail(loc, "the transformation of this " + Quoted(pl.shape->name) + " shape is not finite" + pl.where);
    pl.singular = !IsFiniteMatrix(pl.renderFromObject.mInv);
}

// pbrt-v4's MediumInterface of a shape: a transition only when inside and outside differ.
void SetMedia(BuildContext &ctx, const ShapeEntity &sh, size_t firstShape) {
    uint32_t inside = ResolveMedium(ctx, sh.insideMedium, sh.loc), outside = ResolveMedium(ctx, sh.outsideMedium, sh.loc);
    if (inside == outside) return;
    for (size_t i = firstShape; i < ctx.scene.shapes.size(); ++i) {
        Shape &s = ctx.scene.shapes[i];
        s.mediumTransition = true;
        s.insideMedium = inside;
        s.outsideMedium = outside;
    }
}

// pbrt-v4's "loopsubdiv": the control mesh refined "levels" times and moved to the limit surface
// (scene/loop_subdivision.h), then rendered as a triangle mesh with the limit normals.
void BuildLoopSubdiv(BuildContext &ctx, const Placement &pl) {
    const ShapeEntity &sh = *pl.shape;
    const ParameterDictionary &p = sh.params;
    int levels = p.GetOneInt("levels", 3);
    MeshData control;
    control.indices = ToIndices(ctx, sh, p.GetIntArray("indices"));
    control.P = p.GetPoint3fArray("P");
    CheckMesh(ctx, sh, control, "loopsubdiv");
    const uint64_t maxTriangles = ctx.opts.maxSubdivisionTriangles;
    uint64_t triangles = LoopSubdividedTriangleCount(control.indices.size() / 3, levels);
    if (triangles > maxTriangles)
        Fail(ParamLoc(p, "levels", sh.loc), "loopsubdiv: " + std::to_string(levels) + " levels would make " +
                                                (triangles == UINT64_MAX ? std::string("more than 2^64") : std::to_string(triangles)) +
                                                " triangles (at most " + std::to_string(maxTriangles) + "); use fewer \"levels\"");
    LoopSubdivisionMesh sub;
    std::string error;
    if (!LoopSubdivide(control.P, control.indices, levels, &sub, &error)) Fail(sh.loc, "loopsubdiv: " + error);
    if (sub.droppedFaces > 0)
        ctx.diag.Warning(sh.loc, "loopsubdiv: " + std::to_string(sub.droppedFaces) +
                                     " faces that repeat a vertex are left out of the control mesh");
    MeshData m;
    m.P = std::move(sub.P);
    m.N = std::move(sub.N);
    m.indices = std::move(sub.indices);
    AddTriangles(ctx, pl, m);
}

// Builds one Shape directive at its placement; returns false for unknown names (reported by caller).
void BuildOne(BuildContext &ctx, const Placement &pl, bool reportUnused) {
    const ShapeEntity &sh = *pl.shape;
    const std::string &name = sh.name;
    const ParameterDictionary &p = sh.params;
    // pbrt-v4's getAlphaTexture: a "texture alpha", or a constant "float alpha" below 1.
    uint32_t alpha = NoIndex;
    if (p.TypeOf("alpha") == "texture" || (p.Has("alpha") && p.GetOneFloat("alpha", 1) < 1))
        alpha = GetFloatTextureNode(ctx, p, "alpha", 1);
    if (alpha != NoIndex && pl.areaLight) {
        // pbrt-v4 turns an emitter with a constant alpha of 0 into an invisible light sampled as a
        // delta-position light (no MIS); Lucerna's techniques have no such light type yet.
        const FloatTexture &a = ctx.scene.floatTextures[alpha];
        if (a.kind == TextureKind::Constant && a.value == 0)
            FailUnsupported(ParamLoc(p, "alpha", sh.loc), "area light with a constant \"alpha\" of 0 (an invisible emitter)");
    }
    const size_t firstShape = ctx.scene.shapes.size();
    if (name == "trianglemesh") BuildTriangleMesh(ctx, pl);
    else if (name == "plymesh") BuildPlyMesh(ctx, pl);
    else if (name == "bilinearmesh") BuildBilinearMesh(ctx, pl);
    else if (name == "sphere") BuildSphere(ctx, pl);
    else if (name == "disk") BuildDisk(ctx, pl);
    else if (name == "loopsubdiv") BuildLoopSubdiv(ctx, pl);
    else if (name == "cylinder") BuildCylinder(ctx, pl);
    else if (name == "curve") BuildCurve(ctx, pl);
    else
        Fail(sh.loc, "unknown shape type " + Quoted(name));
    for (size_t i = firstShape; i < ctx.scene.shapes.size(); ++i) ctx.scene.shapes[i].alpha = alpha;
    ctx.scene.stats.shapesByType[name]++;
    if (reportUnused) p.ReportUnused(ctx.diag, "Shape " + Quoted(name));
}

}  // namespace

void BuildShapes(BuildContext &ctx) {
    const SceneDescription &desc = ctx.desc;
    // ---- Top-level shapes ----
    for (const ShapeEntity &sh : desc.shapes) ctx.Collect([&] {
        size_t firstShape = ctx.scene.shapes.size();
        Placement pl;
        pl.shape = &sh;
        pl.renderFromObject = sh.renderFromObject;
        pl.reverseOrientation = sh.reverseOrientation;
        pl.analyticSwapsHandedness = sh.renderFromObject.SwapsHandedness();
        CheckTransform(pl, sh.loc);
        std::string materialType;
        pl.material = ResolveShapeMaterial(ctx, sh, &materialType);
        if (sh.areaLightIndex >= 0) {
            if (size_t(sh.areaLightIndex) >= desc.areaLights.size()) Fail(sh.loc, "internal: area light index out of range");
            if (pl.material == NoIndex) {
                ctx.diag.Warning(sh.loc, "ignoring area light specification for shape with \"interface\" material");
            } else {
                pl.areaLight = &ParseAreaLight(ctx, sh.areaLightIndex);
                ctx.scene.stats.areaLightShapes++;
            }
        }
        BuildOne(ctx, pl, true);
        SetMedia(ctx, sh, firstShape);
    });

    // ---- Object instances ----
    // Rule: an object used at least twice is kept once, in object space (a prototype), and each
    // of its uses becomes an Instance record (104 bytes). Objects used once, and uses whose
    // transformation is projective or singular, are flattened into render-space copies as before.
    ctx.scene.stats.instanceDefinitions = int(desc.instanceDefinitions.size());
    std::vector<const InstanceDefinition *> defs(desc.objectNames.size(), nullptr);
    for (size_t i = 0; i < desc.objectNames.size(); ++i) {
        auto it = desc.instanceDefinitions.find(desc.objectNames[i]);
        if (it != desc.instanceDefinitions.end()) defs[i] = &it->second;
    }
    auto instanceable = [&](const InstanceUse &use) {
        if (use.projective != 0xffffffffu) return false;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j)
                if (!std::isfinite(use.m[i][j]) || !std::isfinite(use.mInv[i][j])) return false;
        return true;
    };
    std::vector<uint32_t> instanceableUses(defs.size(), 0);
    for (const InstanceUse &use : desc.instances)
        if (instanceable(use)) instanceableUses[use.object]++;
    auto instanced = [&](const InstanceUse &use) { return instanceableUses[use.object] >= 2 && instanceable(use); };

    // Flattened copies (render space), in file order.
    std::set<const ShapeEntity *> reported;
    for (const InstanceUse &use : desc.instances) {
        const FileLoc useLoc = desc.Loc(use);
        const std::string &name = desc.ObjectName(use);
        if (!defs[use.object]) Fail(useLoc, "object instance " + Quoted(name) + " is not defined");
        ctx.scene.stats.instanceUses++;
        if (instanced(use)) continue;
        const Transform renderFromInstance = desc.RenderFromInstance(use);
        for (const ShapeEntity &sh : defs[use.object]->shapes) ctx.Collect([&] {
            size_t firstShape = ctx.scene.shapes.size();
            Placement pl;
            pl.shape = &sh;
            pl.renderFromObject = renderFromInstance * sh.renderFromObject;
            pl.firstUse = reported.insert(&sh).second;
            pl.where = " (object instance " + Quoted(name) + " used at " + useLoc.ToString() + ")";
            CheckTransform(pl, useLoc);
            pl.reverseOrientation = sh.reverseOrientation;
            // pbrt-v4 orients analytic shapes in instance space, then transforms the normal.
            pl.analyticSwapsHandedness = sh.renderFromObject.SwapsHandedness();
            pl.material = ResolveShapeMaterial(ctx, sh, nullptr);
            // Area lights inside instances do not emit (pbrt-v4; the parser warns).
            BuildOne(ctx, pl, pl.firstUse);
            SetMedia(ctx, sh, firstShape);
        });
    }

    // Prototypes: after every render-space shape (TopLevelShapeCount), in object order.
    HostScene &hs = ctx.scene;
    std::vector<uint32_t> prototypeOf(defs.size(), NoIndex);
    std::vector<uint64_t> prototypeTriangles;   // per prototype
    for (size_t o = 0; o < defs.size(); ++o) {
        if (instanceableUses[o] < 2 || !defs[o]) continue;
        const Bounds3f sceneBounds = hs.bounds;
        hs.bounds = Bounds3f();   // the shape builders expand it: here with object-space geometry
        Prototype proto;
        proto.firstShape = uint32_t(hs.shapes.size());
        const uint64_t trianglesBefore = hs.stats.triangles;
        for (const ShapeEntity &sh : defs[o]->shapes) ctx.Collect([&] {
            size_t firstShape = hs.shapes.size();
            Placement pl;
            pl.shape = &sh;
            pl.renderFromObject = sh.renderFromObject;
            pl.firstUse = reported.insert(&sh).second;
            pl.where = " (in object " + Quoted(defs[o]->name) + ")";
            CheckTransform(pl, sh.loc);
            pl.reverseOrientation = sh.reverseOrientation;
            pl.analyticSwapsHandedness = sh.renderFromObject.SwapsHandedness();
            pl.material = ResolveShapeMaterial(ctx, sh, nullptr);
            BuildOne(ctx, pl, pl.firstUse);
            SetMedia(ctx, sh, firstShape);
        });
        proto.shapeCount = uint32_t(hs.shapes.size()) - proto.firstShape;
        proto.bounds = hs.bounds;
        hs.bounds = sceneBounds;
        prototypeTriangles.push_back(hs.stats.triangles - trianglesBefore);   // counted per instance below
        hs.stats.triangles = trianglesBefore;
        if (proto.shapeCount == 0) {   // everything dropped (warned): its uses render nothing
            prototypeTriangles.pop_back();
            continue;
        }
        prototypeOf[o] = uint32_t(hs.prototypes.size());
        hs.prototypes.push_back(proto);
    }
    hs.stats.prototypes = int(hs.prototypes.size());

    // Instances, in file order.
    size_t count = 0;
    for (const InstanceUse &use : desc.instances) count += instanced(use) && prototypeOf[use.object] != NoIndex;
    hs.instances.reserve(count);
    for (const InstanceUse &use : desc.instances) {
        if (!instanced(use)) continue;
        hs.stats.instancedUses++;
        uint32_t p = prototypeOf[use.object];
        if (p == NoIndex) continue;
        Instance in;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) {
                in.renderFromInstance[i][j] = use.m[i][j];
                in.instanceFromRender[i][j] = use.mInv[i][j];
            }
        in.prototype = p;
        const Transform t = InstanceTransform(in);
        in.swapsHandedness = t.SwapsHandedness() ? 1 : 0;
        const Bounds3f &ob = hs.prototypes[p].bounds;
        for (int c = 0; c < 8; ++c) {
            Vec3f q = t.ApplyPoint(Vec3f(c & 1 ? ob.pMax.x : ob.pMin.x, c & 2 ? ob.pMax.y : ob.pMin.y,
                                         c & 4 ? ob.pMax.z : ob.pMin.z));
            if (!IsFinite(q.x) || !IsFinite(q.y) || !IsFinite(q.z))
                Fail(desc.Loc(use), "the transformation of object instance " + Quoted(desc.ObjectName(use)) +
                                        " sends it to infinity");
            hs.bounds.Expand(q);
        }
        hs.instances.push_back(in);
        hs.stats.triangles += prototypeTriangles[p];
    }
}

}  // namespace lu::build
