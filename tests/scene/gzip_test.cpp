// Tests of gzip-compressed inputs: Gunzip against zlib's own compressor (one and several members,
// the output bound), corrupt and truncated data, and compressed scene files, Include/Import and
// PLY meshes read through the parser and builder, told by their magic bytes rather than their name.
#include <gtest/gtest.h>

#include <zlib.h>

#include <fstream>

#include "lucerna/scene/builder.h"
#include "lucerna/scene/gzip.h"
#include "lucerna/scene/parser.h"
#include "lucerna/scene/ply.h"
#include "support/test_support.h"

namespace lu {
namespace {

// gzip-format bytes of `data` (zlib's deflate with the gzip wrapper: windowBits 16 + 15).
std::string Gzip(const std::string &data) {
    z_stream zs{};
    EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, 16 + 15, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::string out(deflateBound(&zs, data.size()) + 64, '\0');
    zs.next_in = (Bytef *)data.data();
    zs.avail_in = uInt(data.size());
    zs.next_out = (Bytef *)out.data();
    zs.avail_out = uInt(out.size());
    EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
    out.resize(zs.total_out);
    deflateEnd(&zs);
    return out;
}

void WriteFile(const std::string &path, const std::string &bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

std::string Message(const std::string &why) { return why.empty() ? "(no error)" : why; }

// A scene text long enough that the deflate stream has some size.
std::string Text(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += "# line " + std::to_string(i) + " of a compressed scene file\n";
    return s;
}

TEST(Gzip, RoundTripsZlibOutput) {
    const std::string data = Text(2000) + std::string("\0\x01\xff binary too", 14);
    std::string gz = Gzip(data);
    ASSERT_TRUE(IsGzip(gz));
    EXPECT_FALSE(IsGzip(data));
    EXPECT_LT(gz.size(), data.size() / 5);
    std::string out;
    EXPECT_EQ(Message(Gunzip(gz, &out, 1 << 20)), "(no error)");
    EXPECT_EQ(out, data);
    // Two members back to back (gzip -c a b > c) decompress to the concatenation.
    EXPECT_EQ(Message(Gunzip(gz + Gzip("tail\n"), &out, 1 << 20)), "(no error)");
    EXPECT_EQ(out, data + "tail\n");
    // An empty member.
    EXPECT_EQ(Message(Gunzip(Gzip(""), &out, 16)), "(no error)");
    EXPECT_EQ(out, "");
}

TEST(Gzip, OutputIsBounded) {
    // 8 MB of zeros compress to about 8 kB: the bound stops a "gzip bomb".
    std::string gz = Gzip(std::string(8 << 20, '\0'));
    EXPECT_LT(gz.size(), 20000u);
    std::string out;
    EXPECT_EQ(Gunzip(gz, &out, 1 << 20), "the decompressed data exceed 1048576 bytes");
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(Message(Gunzip(gz, &out, 8 << 20)), "(no error)");
    EXPECT_EQ(out.size(), size_t(8 << 20));
}

TEST(Gzip, CorruptAndTruncatedDataAreErrors) {
    const std::string gz = Gzip(Text(500));
    std::string out;
    // Cut anywhere after the header: truncated.
    for (size_t keep : {size_t(12), gz.size() / 2, gz.size() - 1}) {
        SCOPED_TRACE(keep);
        EXPECT_EQ(Gunzip(gz.substr(0, keep), &out, 1 << 20),
                  "truncated gzip data (the compressed stream ends after " + std::to_string(keep) +
                      " bytes, before its end marker)");
    }
    // A wrong CRC-32 in the trailer (the 8 last bytes: CRC, length).
    std::string crc = gz;
    crc[crc.size() - 8] ^= 0x5a;
    const std::string of = " of " + std::to_string(gz.size()) + " bytes): ";
    EXPECT_EQ(Gunzip(crc, &out, 1 << 20),
              "corrupt gzip data (detected after " + std::to_string(gz.size() - 4) + of + "incorrect data check");
    // A wrong length in the trailer.
    std::string len = gz;
    len[len.size() - 1] ^= 0x01;
    EXPECT_EQ(Gunzip(len, &out, 1 << 20),
              "corrupt gzip data (detected after " + std::to_string(gz.size()) + of + "incorrect length check");
    // An unknown compression method in the header (byte 2), seen once zlib has read 4 bytes.
    std::string method = gz;
    method[2] = 7;
    EXPECT_EQ(Gunzip(method, &out, 1 << 20), "corrupt gzip data (detected after 4" + of + "unknown compression method");
    // Deflate data that make no sense: an invalid block type right after the 10-byte header.
    std::string block = gz;
    block[10] = char(0x07);  // BFINAL 1, BTYPE 11 (reserved)
    EXPECT_EQ(Gunzip(block, &out, 1 << 20), "corrupt gzip data (detected after 11" + of + "invalid block type");
    // Bytes after the last member that are not another member.
    EXPECT_EQ(Gunzip(gz + "junk", &out, 1 << 20),
              "corrupt gzip data: 4 unexpected bytes after the end of the compressed stream (at byte " +
                  std::to_string(gz.size()) + ")");
    EXPECT_TRUE(out.empty());
}

TEST(Gzip, CompressedScenesIncludesAndImportsParse) {
    std::string dir = test::TempDir("gzip_scene");
    WriteFile(dir + "/cam.pbrt.gz", Gzip("Camera \"perspective\" \"float fov\" 30\n"));
    WriteFile(dir + "/geo.pbrt.gz", Gzip("\n\nShape \"sphere\" \"float radius\" 2\n"));
    // Told by the magic bytes, not the name: compressed without ".gz", and plain text named ".gz".
    WriteFile(dir + "/light.pbrt", Gzip("LightSource \"point\"\n"));
    WriteFile(dir + "/plain.pbrt.gz", "Shape \"disk\"\n");
    const std::string main = "Include \"cam.pbrt.gz\"\nWorldBegin\nImport \"geo.pbrt.gz\"\nInclude \"light.pbrt\"\n"
                             "Include \"plain.pbrt.gz\"\n";
    WriteFile(dir + "/main.pbrt", main);
    WriteFile(dir + "/main.pbrt.gz", Gzip(main));
    for (const char *top : {"/main.pbrt", "/main.pbrt.gz"}) {
        SCOPED_TRACE(top);
        Diagnostics diag;
        diag.quiet = true;
        SceneDescription d = ParseSceneFile(dir + top, diag);
        EXPECT_EQ(d.camera.name, "perspective");
        EXPECT_EQ(d.camera.params.GetOneFloat("fov", 90), 30);
        ASSERT_EQ(d.shapes.size(), 2u);
        EXPECT_EQ(d.shapes[0].name, "sphere");
        EXPECT_EQ(d.shapes[0].loc.ToString(), dir + "/geo.pbrt.gz:3:1");
        EXPECT_EQ(d.shapes[1].name, "disk");
        ASSERT_EQ(d.lights.size(), 1u);
        EXPECT_TRUE(diag.warnings.empty());
    }
}

TEST(Gzip, CorruptCompressedScenesAreLocatedErrors) {
    std::string dir = test::TempDir("gzip_corrupt");
    std::string gz = Gzip(Text(300) + "WorldBegin\n");
    WriteFile(dir + "/cut.pbrt.gz", gz.substr(0, gz.size() / 2));
    WriteFile(dir + "/main.pbrt", "WorldBegin\n\n  Include \"cut.pbrt.gz\"\n");
    Diagnostics diag;
    diag.quiet = true;
    try {
        ParseSceneFile(dir + "/main.pbrt", diag);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Format(), dir + "/main.pbrt:3:3: error: cannot read included file \"" + dir +
                                  "/cut.pbrt.gz\": truncated gzip data (the compressed stream ends after " +
                                  std::to_string(gz.size() / 2) + " bytes, before its end marker)\n" +
                                  "  Include \"cut.pbrt.gz\"\n  ^");
    }
    // The main file itself: located at the file.
    std::string bad = gz;
    bad[bad.size() - 8] ^= 1;
    WriteFile(dir + "/crc.pbrt.gz", bad);
    try {
        ParseSceneFile(dir + "/crc.pbrt.gz", diag);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Format(), dir + "/crc.pbrt.gz: error: corrupt gzip data (detected after " +
                                  std::to_string(gz.size() - 4) + " of " + std::to_string(gz.size()) +
                                  " bytes): incorrect data check");
    }
}

TEST(Gzip, ErrorsInCompressedFilesShowTheDecompressedLine) {
    // The parser's errors (in memory) and the builder's (read back from the file afterwards).
    std::string dir = test::TempDir("gzip_lines");
    WriteFile(dir + "/syntax.pbrt.gz", Gzip("WorldBegin\nShape \"sphere\" \"float radius\" [ x ]\n"));
    WriteFile(dir + "/build.pbrt.gz", Gzip("WorldBegin\n\n   Shape \"frobnicate\"\n"));
    Diagnostics diag;
    diag.quiet = true;
    try {
        ParseSceneFile(dir + "/syntax.pbrt.gz", diag);
        FAIL();
    } catch (SceneError &e) {
        // At the parameter: "float radius" is column 16.
        EXPECT_EQ(e.Format().substr(e.Format().find('\n')),
                  "\nShape \"sphere\" \"float radius\" [ x ]\n               ^");
    }
    try {
        LoadScene(dir + "/build.pbrt.gz", diag, BuildOptions{});
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Loc().line, 3);
        EXPECT_EQ(e.Format().substr(e.Format().find('\n')), "\n   Shape \"frobnicate\"\n   ^") << e.Format();
    }
}

TEST(Gzip, CompressedPlyMeshes) {
    std::string dir = test::TempDir("gzip_ply");
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    WriteFile(dir + "/quad.ply.gz", Gzip(ply));
    WriteFile(dir + "/quad2.ply", Gzip(ply));  // compressed, plain name
    FileLoc from{std::make_shared<const std::string>("scene.pbrt"), 4, 1};
    for (const char *name : {"/quad.ply.gz", "/quad2.ply"}) {
        PlyMesh m = ReadPlyMesh(dir + name, from);
        EXPECT_EQ(m.P.size(), 4u);
        EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    }
    // Through the builder.
    WriteFile(dir + "/scene.pbrt", "Camera \"perspective\"\nWorldBegin\nShape \"plymesh\" \"string filename\" \"quad.ply.gz\"\n");
    Diagnostics diag;
    diag.quiet = true;
    auto scene = LoadScene(dir + "/scene.pbrt", diag, BuildOptions{});
    EXPECT_EQ(scene->indices.size(), 6u);
    // Corrupt: located at the reference, naming the file.
    std::string gz = Gzip(ply);
    gz[gz.size() - 1] ^= 1;  // the length field
    WriteFile(dir + "/bad.ply.gz", gz);
    try {
        ReadPlyMesh(dir + "/bad.ply.gz", from);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Loc().line, 4);
        EXPECT_EQ(e.Message(), "PLY file \"" + dir + "/bad.ply.gz\": corrupt gzip data (detected after " +
                                   std::to_string(gz.size()) + " of " + std::to_string(gz.size()) +
                                   " bytes): incorrect length check");
    }
}

}  // namespace
}  // namespace lu
