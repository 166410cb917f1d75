// Tests of the PLY reader: ASCII and binary (little/big endian) files written by the test, with
// quads, normals, texture coordinates, extra properties and elements, and polygon handling.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "lucerna/scene/ply.h"
#include "support/test_support.h"

namespace lu {

// Builds PLY files byte by byte.
struct PlyBuilder {
    std::string bytes;
    bool bigEndian = false;
    explicit PlyBuilder(const std::string &header, bool be = false) : bytes(header), bigEndian(be) {}
    template <typename T>
    PlyBuilder &Put(T v) {
        char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        if (bigEndian)
            for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
        bytes.append(b, sizeof(T));
        return *this;
    }
};

static std::string WritePly(const std::string &name, const std::string &bytes) {
    std::string path = test::TempDir("ply_" + name) + "/" + name + ".ply";
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

static const FileLoc From{std::make_shared<const std::string>("scene.pbrt"), 7, 5, nullptr};

TEST(Ply, AsciiQuadWithNormalsAndUV) {
    std::string text =
        "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 5\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float u\n"
        "property float v\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n2 2 2 0 1 0 .5 .5\n"
        "4 0 1 2 3\n3 1 4 2\n";
    PlyMesh m = ReadPlyMesh(WritePly("ascii", text), From);
    ASSERT_EQ(m.P.size(), 5u);
    EXPECT_EQ(m.P[2], Vec3f(1, 1, 0));
    ASSERT_EQ(m.N.size(), 5u);
    EXPECT_EQ(m.N[4], Vec3f(0, 1, 0));
    ASSERT_EQ(m.uv.size(), 5u);
    EXPECT_EQ(m.uv[4].x, 0.5f);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 1, 4, 2}));
    EXPECT_EQ(m.quadCount, 1u);
    EXPECT_TRUE(m.faceIndices.empty());
}

// A binary mesh with extra properties, an extra element with a list between vertex and face,
// "s t" texture coordinates, doubles, a uint index list and face_indices.
static std::string BinaryMesh(bool be) {
    PlyBuilder b(std::string("ply\nformat ") + (be ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\nelement vertex 4\nproperty double x\nproperty float y\nproperty float z\n"
                     "property uchar red\nproperty float s\nproperty float t\n"
                     "element edge 1\nproperty list uchar int vertex_pair\nproperty short crease\n"
                     "element face 2\nproperty list ushort uint vertex_indices\nproperty int face_indices\n"
                     "end_header\n",
                 be);
    const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int i = 0; i < 4; ++i)
        b.Put<double>(xyz[i][0]).Put<float>(xyz[i][1]).Put<float>(xyz[i][2]).Put<uint8_t>(255).Put<float>(0.25f * i).Put<float>(1);
    b.Put<uint8_t>(2).Put<int32_t>(0).Put<int32_t>(1).Put<int16_t>(-1);
    b.Put<uint16_t>(3).Put<uint32_t>(0).Put<uint32_t>(1).Put<uint32_t>(2).Put<int32_t>(10);
    b.Put<uint16_t>(3).Put<uint32_t>(0).Put<uint32_t>(2).Put<uint32_t>(3).Put<int32_t>(11);
    return b.bytes;
}

TEST(Ply, BinaryLittleAndBigEndian) {
    for (bool be : {false, true}) {
        SCOPED_TRACE(be ? "big endian" : "little endian");
        PlyMesh m = ReadPlyMesh(WritePly(be ? "be" : "le", BinaryMesh(be)), From);
        ASSERT_EQ(m.P.size(), 4u);
        EXPECT_EQ(m.P[2], Vec3f(1, 1, 0));
        EXPECT_TRUE(m.N.empty());
        ASSERT_EQ(m.uv.size(), 4u);
        EXPECT_EQ(m.uv[3].x, 0.75f);
        EXPECT_EQ(m.uv[3].y, 1.0f);
        EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
        EXPECT_EQ(m.faceIndices, (std::vector<int>{10, 11}));
    }
}

TEST(Ply, VertexIndexNameTextureUVAndCrLfHeader) {
    PlyBuilder b("ply\r\nformat binary_little_endian 1.0\r\nelement vertex 3\r\nproperty float x\r\n"
                 "property float y\r\nproperty float z\r\nproperty float texture_u\r\nproperty float texture_v\r\n"
                 "element face 1\r\nproperty list uint8 int32 vertex_index\r\nend_header\n");
    for (int i = 0; i < 3; ++i) b.Put<float>(i).Put<float>(0).Put<float>(0).Put<float>(i).Put<float>(-i);
    b.Put<uint8_t>(3).Put<int32_t>(2).Put<int32_t>(1).Put<int32_t>(0);
    PlyMesh m = ReadPlyMeshFromMemory(b.bytes, "mem.ply", From);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{2, 1, 0}));
    ASSERT_EQ(m.uv.size(), 3u);
    EXPECT_EQ(m.uv[2].y, -2.0f);
}

TEST(Ply, PolygonsAreFannedAndDegenerateFacesSkipped) {
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0.5 2 0\n0 1 0\n5 0 1 2 3 4\n2 0 1\n";
    Diagnostics diag;
    diag.quiet = true;
    PlyMesh m = ReadPlyMeshFromMemory(text, "poly.ply", From, &diag);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
    EXPECT_EQ(m.polygonCount, 1u);
    ASSERT_EQ(diag.warnings.size(), 2u);
    EXPECT_EQ(diag.warnings[0], "scene.pbrt:7:5: warning: PLY file \"poly.ply\": skipped 1 faces with fewer than 3 vertices");
    EXPECT_EQ(diag.warnings[1],
              "scene.pbrt:7:5: warning: PLY file \"poly.ply\": 1 faces with more than 4 vertices were triangulated as fans");
}

TEST(Ply, ErrorsNameTheFileAndTheReferencingLocation) {
    auto message = [](const std::string &bytes) {
        try {
            ReadPlyMeshFromMemory(bytes, "m.ply", From);
        } catch (SceneError &e) {
            EXPECT_EQ(e.Loc().line, 7);
            return e.Message();
        }
        return std::string("no error");
    };
    const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n";
    EXPECT_EQ(message(head + "property list uchar float vertex_indices\nend_header\n" + std::string(25, '\0')),
              "PLY file \"m.ply\": the face property \"vertex_indices\" has a non-integer type");
    EXPECT_EQ(message(std::string("\x1f\x8b\x08\0", 4)),
              "PLY file \"m.ply\": the file is gzip-compressed, which is not supported; decompress it first (gunzip)");
    EXPECT_EQ(message(head + "property list uchar int vertex_indices\n"),
              "PLY file \"m.ply\": corrupt header: no \"end_header\" line before the end of the file");
    EXPECT_EQ(message("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n"),
              "PLY file \"m.ply\": no \"element face\"");
    EXPECT_EQ(message("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nelement face 0\n"
                      "property list uchar int vertex_indices\nend_header\n0\n"),
              "PLY file \"m.ply\": the vertex element has no x, y and z properties");
    EXPECT_EQ(message(head + "property list char int vertex_indices\nend_header\n" + std::string(12, '\0') + "\xff"),
              "PLY file \"m.ply\": corrupt data: negative list length in element \"face\"");
    EXPECT_EQ(message("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 zero 0\n"),
              "PLY file \"m.ply\": corrupt data: \"zero\" is not a number (element \"vertex\", record 1)");
    EXPECT_EQ(message("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 1e39 0\n"),
              "PLY file \"m.ply\": vertex 0 has a non-finite coordinate");
}

}  // namespace lu
