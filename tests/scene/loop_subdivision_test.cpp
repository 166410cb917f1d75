// Tests of Loop subdivision (scene/loop_subdivision.*) and of `Shape "loopsubdiv"`: the limit
// position of a control vertex, computed by hand, does not depend on the number of levels (the
// refinement rules and the topology updates must all be right for that); planar meshes stay
// planar with one normal orientation, interior and boundary rules alike; the counts follow
// V + E, 4F; the normals' orientation against the winding (pbrt-v4's); meshes that are not
// consistently oriented manifolds are refused by name, with the shape's line.
#include <gtest/gtest.h>

#include <cmath>

#include "lucerna/scene/builder.h"
#include "lucerna/scene/loop_subdivision.h"

namespace lu {
namespace {

// An octahedron with outward (counter-clockwise seen from outside) faces.
const std::vector<Vec3f> kOctP = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const std::vector<uint32_t> kOctI = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};

// A flat 3x3-quad grid in z = 0, each quad split along its diagonal: boundary vertices of valence
// 2, 3 and 4, interior vertices of valence 6.
void Grid(std::vector<Vec3f> *P, std::vector<uint32_t> *I) {
    const int n = 3;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) P->push_back(Vec3f(Float(x), Float(y) * 1.3f, 0));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            I->insert(I->end(), {a, b, d, a, d, c});
        }
}

LoopSubdivisionMesh Subdivide(const std::vector<Vec3f> &P, const std::vector<uint32_t> &I, int levels) {
    LoopSubdivisionMesh m;
    std::string error;
    EXPECT_TRUE(LoopSubdivide(P, I, levels, &m, &error)) << error;
    return m;
}

TEST(LoopSubdivision, LimitOfAControlVertexIsTheSameAtEveryLevel) {
    // Valence 4: Loop's limit weight gamma(4) = 1 / (4 + 3 / (8 beta(4))) = 1/8, so the limit of
    // (1, 0, 0) is 1/2 (1, 0, 0) + 1/8 (the four neighbours, which sum to 0) = (1/2, 0, 0).
    for (int levels = 0; levels <= 4; ++levels) {
        LoopSubdivisionMesh m = Subdivide(kOctP, kOctI, levels);
        // The control vertices keep their indices (0..5) through the refinement.
        for (int axis = 0; axis < 3; ++axis) {
            const Vec3f &p = m.P[uint32_t(2 * axis)];
            Float c[3] = {p.x, p.y, p.z};
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], k == axis ? 0.5f : 0.0f, 2e-6f) << "levels " << levels;
        }
    }
}

TEST(LoopSubdivision, CountsFollowVerticesPlusEdgesAndFourFacesPerFace) {
    uint64_t v = 6, e = 12, f = 8;
    for (int levels = 0; levels <= 3; ++levels) {
        LoopSubdivisionMesh m = Subdivide(kOctP, kOctI, levels);
        EXPECT_EQ(m.P.size(), v);
        EXPECT_EQ(m.N.size(), v);
        EXPECT_EQ(m.indices.size(), 3 * f);
        EXPECT_EQ(LoopSubdividedTriangleCount(8, levels), f);
        v += e;
        e = 2 * e + 3 * f;
        f *= 4;
    }
    EXPECT_EQ(LoopSubdividedTriangleCount(1, 40), UINT64_MAX);
}

TEST(LoopSubdivision, ClosedSurfaceIsSymmetricAndItsNormalsAreRadial) {
    LoopSubdivisionMesh m = Subdivide(kOctP, kOctI, 3);
    // Every vertex of the limit surface of the symmetric octahedron lies between the limit of a
    // control vertex (distance 1/2) and that of a face centre; normals at the control vertices
    // point along their position. pbrt-v4's limit normal (cross(S, T) over the one-ring in its
    // walking order) points INTO a mesh wound counter-clockwise seen from outside.
    for (size_t i = 0; i < m.P.size(); ++i) {
        Float r = Length(m.P[i]);
        EXPECT_GT(r, 0.3f);
        EXPECT_LE(r, 0.5f + 1e-5f);
        Float c = Dot(Normalize(m.N[i]), m.P[i] / r);
        EXPECT_LT(c, -0.8f) << "vertex " << i;
        if (i < 6) {
            EXPECT_NEAR(c, -1.0f, 1e-5f);
        }
    }
}

TEST(LoopSubdivision, PlanarMeshStaysPlanarWithOneNormalOrientation) {
    std::vector<Vec3f> P;
    std::vector<uint32_t> I;
    Grid(&P, &I);
    for (int levels = 0; levels <= 3; ++levels) {
        LoopSubdivisionMesh m = Subdivide(P, I, levels);
        for (size_t i = 0; i < m.P.size(); ++i) {
            EXPECT_NEAR(m.P[i].z, 0.0f, 1e-6f);
            Vec3f n = Normalize(m.N[i]);
            // Interior (valence 6) and boundary (valence 2, 3, 4) rules alike: -z, as the
            // octahedron's (the grid is wound counter-clockwise seen from +z).
            EXPECT_NEAR(n.z, -1.0f, 1e-4f) << "levels " << levels << " vertex " << i << " at " << m.P[i].x << ","
                                           << m.P[i].y;
        }
    }
}

TEST(LoopSubdivision, BoundaryFollowsTheCubicBSplineWithPbrtsLimitWeight) {
    // The boundary is refined as a cubic B-spline (even 3/4 v + 1/8 (both boundary neighbours)),
    // whose limit mask is (1/6, 2/3, 1/6). pbrt-v4 (and so Lucerna) moves boundary vertices to
    // (1 - 2/5) v + 1/5 (neighbours): exact for 0 levels of the corner (0, 0) of the grid,
    // (0.2, 0.26), and tending to the true limit (1/6, 1.3/6) as the levels add up.
    std::vector<Vec3f> P;
    std::vector<uint32_t> I;
    Grid(&P, &I);
    LoopSubdivisionMesh m = Subdivide(P, I, 0);
    EXPECT_NEAR(m.P[0].x, 0.2f, 1e-6f);
    EXPECT_NEAR(m.P[0].y, 0.26f, 1e-6f);
    Float previous = 1;
    for (int levels = 1; levels <= 5; ++levels) {
        m = Subdivide(P, I, levels);
        Float error = std::hypot(m.P[0].x - 1.0f / 6, m.P[0].y - 1.3f / 6);
        EXPECT_LT(error, 0.5f * previous) << "levels " << levels;
        EXPECT_NEAR(m.P[0].z, 0.0f, 1e-7f);
        previous = error;
    }
    EXPECT_LT(previous, 1e-3f);
}

TEST(LoopSubdivision, RefusesMeshesThatAreNotOrientedManifolds) {
    LoopSubdivisionMesh m;
    std::string error;
    // Three faces on one edge.
    EXPECT_FALSE(LoopSubdivide({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {0, 1, 2, 1, 0, 3, 0, 1, 4}, 1, &m, &error));
    EXPECT_NE(error.find("more than two faces"), std::string::npos) << error;
    // Two faces traversing their shared edge the same way.
    EXPECT_FALSE(LoopSubdivide({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}}, {0, 1, 2, 0, 1, 3}, 1, &m, &error));
    EXPECT_NE(error.find("consistently oriented"), std::string::npos) << error;
    // Two triangles touching at one vertex only (a bow tie).
    EXPECT_FALSE(LoopSubdivide({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {0, 1, 2, 0, 3, 4}, 1, &m, &error));
    EXPECT_NE(error.find("more than one fan"), std::string::npos) << error;
    // Nothing but degenerate faces.
    EXPECT_FALSE(LoopSubdivide({{0, 0, 0}, {1, 0, 0}}, {0, 1, 1}, 1, &m, &error));
    // A degenerate face among good ones is dropped; unused vertices are left out.
    std::vector<Vec3f> P = kOctP;
    P.push_back(Vec3f(5, 5, 5));
    std::vector<uint32_t> I = kOctI;
    I.insert(I.end(), {0, 0, 1});
    ASSERT_TRUE(LoopSubdivide(P, I, 1, &m, &error)) << error;
    EXPECT_EQ(m.droppedFaces, 1u);
    EXPECT_EQ(m.indices.size(), 3u * 32);
    for (const Vec3f &p : m.P) EXPECT_LT(Length(p), 1.0f);
}

// ---- Shape "loopsubdiv" in the builder ----

const char *kHeader =
    "Film \"rgb\" \"integer xresolution\" [ 32 ] \"integer yresolution\" [ 16 ]\n"
    "Camera \"perspective\" \"float fov\" [ 45 ]\n"
    "WorldBegin\n";

std::string OctahedronShape(const std::string &extra) {
    return "Shape \"loopsubdiv\" " + extra +
           " \"point3 P\" [1 0 0 -1 0 0 0 1 0 0 -1 0 0 0 1 0 0 -1]"
           " \"integer indices\" [0 2 4 2 1 4 1 3 4 3 0 4 2 0 5 1 2 5 3 1 5 0 3 5]\n";
}

std::unique_ptr<HostScene> BuildWorld(const std::string &world, Diagnostics &diag, const BuildOptions &opts = {}) {
    diag.quiet = true;
    SceneDescription desc = ParseSceneString(std::string(kHeader) + world, "test.pbrt", diag);
    return BuildScene(desc, diag, opts);
}

TEST(LoopSubdivShape, BuildsATriangleMeshWithLimitNormals) {
    Diagnostics diag;
    auto scene = BuildWorld("LightSource \"point\" \"point3 from\" [0 0 5]\n" + OctahedronShape(""), diag);   // levels default 3
    SceneView v = scene->View();
    ASSERT_EQ(v.triangleMeshes.size, 1u);
    EXPECT_EQ(v.triangleMeshes[0].triangleCount, 8u * 64);
    ASSERT_NE(v.triangleMeshes[0].normalOffset, NoIndex);
    EXPECT_TRUE(diag.warnings.empty()) << (diag.warnings.empty() ? "" : diag.warnings[0]);
    // The scene's normals are the limit normals (inward, as pbrt-v4's); ReverseOrientation flips them.
    const Vec3f p0 = v.positions[v.triangleMeshes[0].firstVertex];
    const Vec3f n0 = v.normals[v.triangleMeshes[0].normalOffset];
    EXPECT_LT(Dot(n0, p0), 0);
    Diagnostics diag2;
    auto reversed = BuildWorld("ReverseOrientation\n" + OctahedronShape("\"integer levels\" 1"), diag2);
    SceneView r = reversed->View();
    EXPECT_EQ(r.triangleMeshes[0].triangleCount, 32u);
    EXPECT_GT(Dot(r.normals[r.triangleMeshes[0].normalOffset], r.positions[r.triangleMeshes[0].firstVertex]), 0);
}

TEST(LoopSubdivShape, BadMeshesAndTooManyLevelsAreErrorsAtTheShape) {
    auto errorOf = [](const std::string &world, const BuildOptions &opts = {}) -> std::string {
        Diagnostics diag;
        try {
            BuildWorld(world, diag, opts);
        } catch (const SceneError &e) {
            return e.Format();
        }
        ADD_FAILURE() << "no error for " << world;
        return "";
    };
    std::string e = errorOf("\n" + OctahedronShape("\"integer levels\" 12"));
    EXPECT_NE(e.find("test.pbrt:5"), std::string::npos) << e;
    EXPECT_NE(e.find("levels"), std::string::npos) << e;
    BuildOptions small;
    small.maxSubdivisionTriangles = 100;
    e = errorOf(OctahedronShape("\"integer levels\" 2"), small);
    EXPECT_NE(e.find("128 triangles"), std::string::npos) << e;
    e = errorOf("Shape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0 0 -1 0] \"integer indices\" [0 1 2 0 1 3]\n");
    EXPECT_NE(e.find("test.pbrt:4"), std::string::npos) << e;
    EXPECT_NE(e.find("consistently oriented"), std::string::npos) << e;
    e = errorOf("Shape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 7]\n");
    EXPECT_NE(e.find("out-of-bounds"), std::string::npos) << e;
}

}  // namespace
}  // namespace lu
