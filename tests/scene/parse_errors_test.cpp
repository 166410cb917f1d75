// One test per class of bad input: the exact message and its line (and column) for the scene
// reader and the PLY reader, plus the replay of the fuzzers' regression inputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "lucerna/scene/builder.h"
#include "lucerna/scene/parser.h"
#include "lucerna/scene/ply.h"
#include "support/test_support.h"

namespace lu {

static void WriteFile(const std::string &path, const std::string &text) {
    std::ofstream(path, std::ios::binary) << text;
}

// Parses text (as file "e.pbrt") and returns the SceneError it must throw.
static SceneError ErrorOf(const std::string &text) {
    Diagnostics diag;
    diag.quiet = true;
    try {
        ParseSceneString(text, "e.pbrt", diag);
    } catch (SceneError &e) {
        return e;
    }
    ADD_FAILURE() << "no error";
    return SceneError(FileLoc{}, "");
}

static SceneError FileErrorOf(const std::string &path) {
    Diagnostics diag;
    diag.quiet = true;
    try {
        ParseSceneFile(path, diag);
    } catch (SceneError &e) {
        return e;
    }
    ADD_FAILURE() << "no error";
    return SceneError(FileLoc{}, "");
}

static SceneError PlyErrorOf(const std::string &path) {
    FileLoc from{std::make_shared<const std::string>("scene.pbrt"), 12, 5, nullptr};
    try {
        ReadPlyMesh(path, from);
    } catch (SceneError &e) {
        EXPECT_EQ(e.Loc().line, 12);
        EXPECT_EQ(e.Loc().col, 5);
        EXPECT_EQ(*e.Loc().file, "scene.pbrt");
        return e;
    }
    ADD_FAILURE() << "no error";
    return SceneError(FileLoc{}, "");
}

static const std::string PlyHead =
    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

static std::string PlyBody(int index2, float y0 = 0) {
    std::string b;
    float v[9] = {0, y0, 0, 1, 0, 0, 0, 1, 0};
    b.append((const char *)v, sizeof(v));
    int idx[3] = {0, 1, index2};
    b.push_back(3);
    b.append((const char *)idx, sizeof(idx));
    return b;
}

// ---- the scene reader ----

TEST(ParseErrors, UnterminatedString) {
    SceneError e = ErrorOf("WorldBegin\nMaterial \"diffuse\n");
    EXPECT_EQ(e.Message(), "unterminated string: missing closing '\"'");
    EXPECT_EQ(e.Loc().line, 2);
    EXPECT_EQ(e.Loc().col, 10);
    EXPECT_EQ(e.Format(), "e.pbrt:2:10: error: unterminated string: missing closing '\"'\n"
                          "Material \"diffuse\n"
                          "         ^");
}

TEST(ParseErrors, UnterminatedBracket) {
    SceneError e = ErrorOf("WorldBegin\nShape \"trianglemesh\"\n  \"point3 P\" [ 0 0 0\n  1 0 0\n");
    EXPECT_EQ(e.Message(), "unterminated '[': missing ']' before the end of the file");
    EXPECT_EQ(e.Loc().line, 3);
    EXPECT_EQ(e.Loc().col, 14);
    // A directive inside an open list hints at the missing ']'.
    SceneError d = ErrorOf("WorldBegin\nShape \"sphere\" \"float radius\" [ 1\nShape \"sphere\"\n");
    EXPECT_EQ(d.Message(),
              "parameter \"float radius\": expected a number, but got \"Shape\" (missing ']' for the '[' at line 2?) "
              "(at line 3, column 1)");
    EXPECT_EQ(d.Loc().line, 2);
}

TEST(ParseErrors, UnknownDirective) {
    SceneError e = ErrorOf("WorldBegin\n\n  Frobnicate \"x\"\n");
    EXPECT_EQ(e.Message(), "unknown directive \"Frobnicate\"");
    EXPECT_EQ(e.Loc().line, 3);
    EXPECT_EQ(e.Loc().col, 3);
    SceneError s = ErrorOf("WorldBegin\n\"float radius\" 1\n");
    EXPECT_EQ(s.Message(), "unexpected string \"float radius\" where a directive was expected");
    EXPECT_EQ(s.Loc().line, 2);
}

TEST(ParseErrors, WrongParameterType) {
    SceneError e = ErrorOf("WorldBegin\nShape \"sphere\"\n    \"float radius\" \"big\"\n");
    EXPECT_EQ(e.Message(), "parameter \"float radius\": expected a number, but got the string \"big\"");
    EXPECT_EQ(e.Loc().line, 3);
    EXPECT_EQ(e.Loc().col, 5);
    SceneError t = ErrorOf("WorldBegin\nShape \"sphere\" \"real radius\" 1\n");
    EXPECT_EQ(t.Message(), "unknown parameter type \"real\" in \"real radius\"");
    EXPECT_EQ(t.Loc().line, 2);
}

TEST(ParseErrors, NonNumericValue) {
    SceneError e = ErrorOf("WorldBegin\nShape \"sphere\" \"float radius\" [ 1,5 ]\n");
    EXPECT_EQ(e.Message(), "parameter \"float radius\": expected a number, but got \"1,5\"");
    EXPECT_EQ(e.Loc().line, 2);
    SceneError t = ErrorOf("Translate 1 two 3\n");
    EXPECT_EQ(t.Message(), "\"Translate\" needs 3 numbers: \"two\" is not a number");
    EXPECT_EQ(t.Loc().line, 1);
    EXPECT_EQ(t.Loc().col, 13);
}

TEST(ParseErrors, NaNCoordinate) {
    SceneError e = ErrorOf("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 nan 0 0 1 0 ]\n");
    EXPECT_EQ(e.Message(), "parameter \"point3 P\": non-finite number \"nan\"");
    EXPECT_EQ(e.Loc().line, 2);
    SceneError t = ErrorOf("LookAt 0 0 0 0 0 1 0 inf 0\n");
    EXPECT_EQ(t.Message(), "\"LookAt\" needs 9 numbers: non-finite number \"inf\"");
    // In a PLY file.
    std::string dir = test::TempDir("err_nan");
    WriteFile(dir + "/nan.ply", PlyHead + PlyBody(2, std::nanf("")));
    EXPECT_EQ(PlyErrorOf(dir + "/nan.ply").Message(),
              "PLY file \"" + dir + "/nan.ply\": vertex 0 has a non-finite coordinate");
}

TEST(ParseErrors, MissingPly) {
    std::string path = test::TempDir("err_missing_ply") + "/missing.ply";
    EXPECT_EQ(PlyErrorOf(path).Message(), "PLY file \"" + path + "\": cannot open: No such file or directory");
}

TEST(ParseErrors, TruncatedPly) {
    std::string dir = test::TempDir("err_trunc");
    std::string body = PlyBody(2);
    WriteFile(dir + "/t.ply", PlyHead + body.substr(0, body.size() - 3));
    EXPECT_EQ(PlyErrorOf(dir + "/t.ply").Message(),
              "PLY file \"" + dir + "/t.ply\": truncated: the file ends inside element \"face\" (record 1 of 1)");
    // A count that the file cannot hold is caught before anything is allocated.
    std::string big = PlyHead;
    big.replace(big.find("vertex 3"), 8, "vertex 3000000000");
    WriteFile(dir + "/big.ply", big + body);
    EXPECT_EQ(PlyErrorOf(dir + "/big.ply").Message(),
              "PLY file \"" + dir + "/big.ply\": element \"vertex\" declares 3000000000 records, more than the 49 "
              "bytes of data after the header can hold");
}

TEST(ParseErrors, CorruptPly) {
    std::string dir = test::TempDir("err_corrupt");
    WriteFile(dir + "/a.ply", "PLY\nformat ascii 1.0\n");
    EXPECT_EQ(PlyErrorOf(dir + "/a.ply").Message(),
              "PLY file \"" + dir + "/a.ply\": not a PLY file (the first line is not \"ply\")");
    std::string head = PlyHead;
    head.replace(head.find("element face"), 7, "elemnt ");
    WriteFile(dir + "/b.ply", head + PlyBody(2));
    EXPECT_EQ(PlyErrorOf(dir + "/b.ply").Message(),
              "PLY file \"" + dir + "/b.ply\": corrupt header at line 7: unknown keyword \"elemnt\"");
    head = PlyHead;
    head.replace(head.find("uchar int"), 9, "uchar intt");
    WriteFile(dir + "/c.ply", head + PlyBody(2));
    EXPECT_EQ(PlyErrorOf(dir + "/c.ply").Message(),
              "PLY file \"" + dir + "/c.ply\": corrupt header at line 8: unknown type \"intt\"");
}

TEST(ParseErrors, PlyIndexOutOfRange) {
    std::string dir = test::TempDir("err_index");
    WriteFile(dir + "/i.ply", PlyHead + PlyBody(3));
    EXPECT_EQ(PlyErrorOf(dir + "/i.ply").Message(),
              "PLY file \"" + dir + "/i.ply\": face 0: vertex index 3 is out of range (the file has 3 vertices)");
    WriteFile(dir + "/n.ply", PlyHead + PlyBody(-1));
    EXPECT_EQ(PlyErrorOf(dir + "/n.ply").Message(),
              "PLY file \"" + dir + "/n.ply\": face 0: vertex index -1 is out of range (the file has 3 vertices)");
}

TEST(ParseErrors, MissingInclude) {
    std::string dir = test::TempDir("err_include");
    WriteFile(dir + "/main.pbrt", "Film \"rgb\"\n\nInclude \"nope.pbrt\"\n");
    SceneError e = FileErrorOf(dir + "/main.pbrt");
    EXPECT_EQ(e.Message(), "cannot open included file \"nope.pbrt\" (looked for \"" + dir + "/nope.pbrt\")");
    EXPECT_EQ(*e.Loc().file, dir + "/main.pbrt");
    EXPECT_EQ(e.Loc().line, 3);
    EXPECT_EQ(e.Loc().col, 1);
    // The missing main file itself.
    SceneError m = FileErrorOf(dir + "/absent.pbrt");
    EXPECT_EQ(m.Message(), "cannot read scene file \"" + dir + "/absent.pbrt\": No such file or directory");
}

TEST(ParseErrors, IncludeCycle) {
    std::string dir = test::TempDir("err_cycle");
    WriteFile(dir + "/a.pbrt", "Include \"b.pbrt\"\n");
    WriteFile(dir + "/b.pbrt", "# b\nInclude \"a.pbrt\"\n");
    SceneError e = FileErrorOf(dir + "/a.pbrt");
    EXPECT_EQ(e.Message(), "Include cycle: " + dir + "/a.pbrt -> " + dir + "/b.pbrt -> " + dir + "/a.pbrt");
    EXPECT_EQ(*e.Loc().file, dir + "/b.pbrt");
    EXPECT_EQ(e.Loc().line, 2);
    // The diagnostic shows the line of the included file.
    EXPECT_NE(e.Format().find("\nInclude \"a.pbrt\"\n^"), std::string::npos) << e.Format();
    WriteFile(dir + "/self.pbrt", "WorldBegin\nImport \"self.pbrt\"\n");
    EXPECT_EQ(FileErrorOf(dir + "/self.pbrt").Message(),
              "Import cycle: " + dir + "/self.pbrt -> " + dir + "/self.pbrt");
}

TEST(ParseErrors, IncludeChainsPrecedeTheMessage) {
    // a.pbrt includes b.pbrt (line 2), which imports c.pbrt (line 3), which has the error.
    std::string dir = test::TempDir("err_chain");
    WriteFile(dir + "/a.pbrt", "WorldBegin\nInclude \"b.pbrt\"\n");
    WriteFile(dir + "/b.pbrt", "# b\n\n  Import \"c.pbrt\"\n");
    WriteFile(dir + "/c.pbrt", "Shape \"sphere\" \"float radius\" \"x\"\n");
    SceneError e = FileErrorOf(dir + "/a.pbrt");
    EXPECT_EQ(e.Format(), "In file included from " + dir + "/b.pbrt:3:3,\n"
                          "                 from " + dir + "/a.pbrt:2:1:\n" +
                          dir + "/c.pbrt:1:16: error: parameter \"float radius\": expected a number, but got the string \"x\"\n"
                          "Shape \"sphere\" \"float radius\" \"x\"\n"
                          "               ^");
    // what() stays one line.
    EXPECT_EQ(std::string(e.what()), dir + "/c.pbrt:1:16: error: " + e.Message());
    // An error at the Include directive itself names the files above it.
    WriteFile(dir + "/c.pbrt", "Include \"missing.pbrt\"\n");
    EXPECT_EQ(FileErrorOf(dir + "/a.pbrt").Format().substr(0, 200).find("In file included from " + dir + "/b.pbrt:3:3,\n"),
              0u);
    // Warnings too, and the locations kept in the description.
    WriteFile(dir + "/c.pbrt", "\nScale 0 1 1\nShape \"sphere\"\n");
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription d = ParseSceneFile(dir + "/a.pbrt", diag);
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_EQ(diag.warnings[0], "In file included from " + dir + "/b.pbrt:3:3,\n"
                                "                 from " + dir + "/a.pbrt:2:1:\n" +
                                dir + "/c.pbrt:3:1: warning: the transformation of this Shape is not invertible");
    ASSERT_EQ(d.shapes.size(), 1u);
    ASSERT_TRUE(d.shapes[0].loc.includedFrom);
    EXPECT_EQ(d.shapes[0].loc.includedFrom->ToString(), dir + "/b.pbrt:3:3");
    // Errors found after parsing, by the scene builder.
    WriteFile(dir + "/c.pbrt", "Shape \"frobnicate\"\n");
    try {
        LoadScene(dir + "/a.pbrt", diag, BuildOptions{});
        ADD_FAILURE() << "no error";
    } catch (SceneError &b) {
        EXPECT_EQ(b.Format().find("In file included from " + dir + "/b.pbrt:3:3,\n                 from " + dir +
                                  "/a.pbrt:2:1:\n" + dir + "/c.pbrt:1:1: error: "),
                  0u)
            << b.Format();
    }
    // Locations in the main file have none.
    WriteFile(dir + "/one.pbrt", "WorldBegin\nShape \"sphere\"\n");
    SceneDescription m = ParseSceneFile(dir + "/one.pbrt", diag);
    EXPECT_FALSE(m.shapes[0].loc.includedFrom);
    EXPECT_EQ(m.shapes[0].loc.IncludeChain(), "");
}

TEST(ParseErrors, UnmatchedAttributeEnd) {
    SceneError e = ErrorOf("WorldBegin\nAttributeBegin\nAttributeEnd\nAttributeEnd\n");
    EXPECT_EQ(e.Message(), "unmatched \"AttributeEnd\"");
    EXPECT_EQ(e.Loc().line, 4);
    SceneError open = ErrorOf("WorldBegin\nAttributeBegin\nShape \"sphere\"\n");
    EXPECT_EQ(open.Message(), "AttributeBegin without a matching AttributeEnd");
    EXPECT_EQ(open.Loc().line, 2);
    SceneError obj = ErrorOf("WorldBegin\nObjectEnd\n");
    EXPECT_EQ(obj.Message(), "unmatched \"ObjectEnd\"");
    SceneError mixed = ErrorOf("WorldBegin\nObjectBegin \"o\"\nAttributeEnd\n");
    EXPECT_EQ(mixed.Message(), "\"AttributeEnd\" closes the ObjectBegin at line 2 of e.pbrt");
}

TEST(ParseErrors, EmptyFile) {
    for (const char *text : {"", "\n\n", "# nothing but a comment\n"}) {
        Diagnostics diag;
        diag.quiet = true;
        SceneDescription d = ParseSceneString(text, "empty.pbrt", diag);
        EXPECT_TRUE(d.shapes.empty());
        EXPECT_TRUE(d.lights.empty());
        EXPECT_EQ(d.camera.name, "");
        EXPECT_TRUE(diag.warnings.empty());
    }
}

TEST(ParseErrors, BinaryGarbage) {
    std::string garbage("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
    SceneError e = ErrorOf(garbage);
    EXPECT_EQ(e.Message(), "unexpected byte 0x89 outside a string or comment (is this a binary file?)");
    EXPECT_EQ(e.Loc().line, 1);
    EXPECT_EQ(e.Loc().col, 1);
    SceneError nul = ErrorOf(std::string("WorldBegin\nShape\0", 17));
    EXPECT_EQ(nul.Message(), "unexpected byte 0x00 outside a string or comment (is this a binary file?)");
    EXPECT_EQ(nul.Loc().line, 2);
    EXPECT_EQ(nul.Loc().col, 6);
    EXPECT_EQ(nul.Format().substr(nul.Format().find('\n')), "\nShape?\n     ^");
}

TEST(ParseErrors, HugeToken) {
    SceneError e = ErrorOf("WorldBegin\nShape \"sphere\" \"float radius\" " + std::string(100000, '9') + "\n");
    EXPECT_EQ(e.Message(), "token too long (more than 1024 characters)");
    EXPECT_EQ(e.Loc().line, 2);
    EXPECT_EQ(e.Loc().col, 31);
    SceneError s = ErrorOf("WorldBegin\nShape \"" + std::string(70000, 's') + "\"\n");
    EXPECT_EQ(s.Message(), "string too long (more than 65536 characters)");
}

// ---- further classes ----

TEST(ParseErrors, UnknownNamedMaterialIsReportedAtNamedMaterial) {
    SceneError e = ErrorOf("WorldBegin\nNamedMaterial \"gold\"\nShape \"sphere\"\n");
    EXPECT_EQ(e.Message(), "named material \"gold\" is not defined (no MakeNamedMaterial \"gold\")");
    EXPECT_EQ(e.Loc().line, 2);
    // Not used by any shape: no error (as pbrt-v4).
    Diagnostics diag;
    diag.quiet = true;
    EXPECT_NO_THROW(ParseSceneString("WorldBegin\nNamedMaterial \"gold\"\n", "e.pbrt", diag));
}

TEST(ParseErrors, DirectivesInTheWrongBlock) {
    EXPECT_EQ(ErrorOf("Shape \"sphere\"\n").Message(), "\"Shape\" is not allowed before WorldBegin");
    EXPECT_EQ(ErrorOf("WorldBegin\nCamera \"perspective\"\n").Message(), "\"Camera\" is not allowed after WorldBegin");
    EXPECT_EQ(ErrorOf("WorldBegin\nWorldBegin\n").Message(), "\"WorldBegin\" is not allowed after WorldBegin");
    EXPECT_EQ(ErrorOf("Import \"x.pbrt\"\n").Message(), "\"Import\" is not allowed before WorldBegin");
}

TEST(ParseErrors, MiscellaneousDirectiveErrors) {
    EXPECT_EQ(ErrorOf("WorldBegin\nObjectInstance \"none\"\n").Message(),
              "object \"none\" is not defined (no ObjectBegin \"none\")");
    EXPECT_EQ(ErrorOf("Attribute \"camera\" \"float x\" 1\n").Message(),
              "unknown Attribute target \"camera\": must be \"shape\", \"light\", \"material\", \"medium\" or \"texture\"");
    EXPECT_EQ(ErrorOf("WorldBegin\nMakeNamedMaterial \"m\" \"float eta\" 1\n").Message(),
              "named material \"m\" has no \"string type\" parameter");
    EXPECT_EQ(ErrorOf("WorldBegin\nTexture \"t\" \"color\" \"constant\"\n").Message(),
              "texture type \"color\" is unknown: must be \"float\" or \"spectrum\"");
    EXPECT_EQ(ErrorOf("Rotate 10 0 0 0\n").Message(), "\"Rotate\" needs a nonzero rotation axis");
    EXPECT_EQ(ErrorOf("LookAt 0 0 0 0 0 1 0 0 1\n").Message(),
              "\"LookAt\": the up vector is parallel to the viewing direction");
    EXPECT_EQ(ErrorOf("Scale 0 0 0\nCamera \"perspective\"\n").Message(),
              "the camera transformation (the CTM at \"Camera\") is not invertible");
    EXPECT_EQ(ErrorOf("Scale 1e30 1 1\nScale 1e30 1 1\n").Message(),
              "\"Scale\" makes the transformation overflow");
    EXPECT_EQ(ErrorOf("Translate 1 2\n").Message(), "unexpected end of file: \"Translate\" needs 3 numbers");
    EXPECT_EQ(ErrorOf("ColorSpace \"adobe\"\n").Message(),
              "unknown color space \"adobe\" (known: srgb, rec2020, aces2065-1, dci-p3)");
    EXPECT_EQ(ErrorOf("Transform [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 ]\n").Message(),
              "\"Transform\" needs exactly 16 numbers; expected ']' but got \"1\"");
}

TEST(ParseErrors, ColorSpaceIsGraphicsState) {
    // ColorSpace sets the graphics state's color space: parameters and entities written after it
    // carry it, AttributeEnd restores the enclosing one, Attribute values keep theirs.
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription d = ParseSceneString(
        "ColorSpace \"rec2020\"\nFilm \"rgb\"\nColorSpace \"srgb\"\nWorldBegin\n"
        "AttributeBegin\nColorSpace \"aces2065-1\"\nAttribute \"shape\" \"rgb x\" [ 1 1 1 ]\nColorSpace \"dci-p3\"\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\nShape \"sphere\"\nAttributeEnd\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n",
        "cs.pbrt", diag);
    EXPECT_EQ(d.film.colorSpace, uint8_t(ColorSpaceId::Rec2020));
    ASSERT_EQ(d.materials.size(), 2u);
    EXPECT_EQ(d.materials[0].colorSpace, uint8_t(ColorSpaceId::DCI_P3));
    EXPECT_EQ(d.materials[0].params.All()[0].colorSpace, uint8_t(ColorSpaceId::DCI_P3));
    EXPECT_EQ(d.materials[1].colorSpace, uint8_t(ColorSpaceId::SRGB));  // restored by AttributeEnd
    ASSERT_EQ(d.shapes.size(), 1u);
    const ParsedParameter *x = d.shapes[0].params.Find("x");
    ASSERT_NE(x, nullptr);
    EXPECT_EQ(x->colorSpace, uint8_t(ColorSpaceId::ACES2065_1));  // as at the Attribute directive
    EXPECT_EQ(d.shapes[0].colorSpace, uint8_t(ColorSpaceId::DCI_P3));
}

TEST(ParseErrors, SingularShapeTransformWarns) {
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription d = ParseSceneString("WorldBegin\nScale 0 1 1\nShape \"sphere\"\n", "e.pbrt", diag);
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_EQ(diag.warnings[0], "e.pbrt:3:1: warning: the transformation of this Shape is not invertible");
    EXPECT_TRUE(std::isnan(d.shapes[0].renderFromObject.mInv.m[0][0]));
}

TEST(ParseErrors, AllocationIsBounded) {
    // Attribute defaults are copied into every entity: the copies count against the budget
    // (one unit per value and per parameter: 101 per shape here).
    std::string text = "WorldBegin\nAttribute \"shape\" \"float x\" [";
    for (int i = 0; i < 100; ++i) text += " 1";
    text += " ]\n";
    for (int i = 0; i < 20; ++i) text += "Shape \"sphere\"\n";
    Diagnostics diag;
    diag.quiet = true;
    ParseOptions opt;
    opt.maxTotalValues = 1000;
    try {
        ParseSceneString(text, "e.pbrt", diag, opt);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Message(), "the scene has more than 1000 parameter values; refusing to read further");
        EXPECT_EQ(e.Loc().line, 11);  // the 9th shape: 101 + 9 * 101 > 1000
    }
    // Nesting depth is bounded too.
    opt.maxTotalValues = size_t(1) << 28;
    opt.maxAttributeDepth = 8;
    std::string nested = "WorldBegin\n";
    for (int i = 0; i < 9; ++i) nested += "AttributeBegin\n";
    try {
        ParseSceneString(nested, "e.pbrt", diag, opt);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Message(), "\"AttributeBegin\" nested more than 8 deep");
        EXPECT_EQ(e.Loc().line, 10);
    }
}

// The fuzzers' minimized crashers stay here as regression inputs, each replayed with the fuzzers'
// options (no file access, the fuzzer's value budget) and its outcome asserted: the SceneError it
// must throw (message and location) or success. A new input in fuzz/regressions needs an entry.
TEST(ParseErrors, FuzzRegressionsGiveTheirExpectedOutcome) {
    struct Expected {
        const char *file;
        const char *message;  // nullptr: parses (or reads) without error
        int line = 0, col = 0;  // of a scene error (PLY errors are at the plymesh reference)
    };
    const Expected expected[] = {
        // The bound on the parameter values that attribute defaults copy into each shape.
        {"scene-attribute-amplification.pbrt",
         "the scene has more than 1048576 parameter values; refusing to read further", 525, 1},
        {"scene-binary.pbrt", "unknown directive \"D\"", 1, 1},
        // The bound on AttributeBegin nesting (4096; the file nests 5000 deep).
        {"scene-deep-attributes.pbrt", "\"AttributeBegin\" nested more than 4096 deep", 4098, 1},
        {"scene-escapes.pbrt", "unknown escape sequence '\\q' in string", 2, 54},
        {"scene-numbers.pbrt", "parameter \"float a\": number \"0x1p99999\" is out of range", 2, 11},
        {"scene-overflow.pbrt", "\"Scale\" makes the transformation overflow", 2, 1},
        {"scene-singular.pbrt", "\"LookAt\": the eye and look-at points are the same", 5, 1},
        {"ply-ascii-huge-listcount.ply",
         "PLY file \"ply-ascii-huge-listcount.ply\": truncated: the file ends inside element \"face\" (record 1 of 1)"},
        {"ply-ascii-inf-index.ply",
         "PLY file \"ply-ascii-inf-index.ply\": face 0: vertex index 1e+300 is out of range (the file has 3 vertices)"},
        {"ply-huge-count.ply",
         "PLY file \"ply-huge-count.ply\": element \"vertex\" declares 4000000000 records, more than the 64 bytes of "
         "data after the header can hold"},
        {"ply-huge-list.ply",
         "PLY file \"ply-huge-list.ply\": truncated: the file ends inside element \"face\" (record 1 of 1)"},
        {"ply-no-props-huge.ply", nullptr},  // 10^12 records of no properties: read, nothing allocated
    };
    std::string dir = test::SourcePath("fuzz/regressions");
    ASSERT_TRUE(std::filesystem::is_directory(dir)) << "missing " << dir;
    std::set<std::string> files;
    for (const auto &entry : std::filesystem::directory_iterator(dir)) files.insert(entry.path().filename().string());
    for (const Expected &x : expected) EXPECT_EQ(files.count(x.file), 1u) << x.file << " is listed but not in " << dir;
    const FileLoc from{std::make_shared<const std::string>("scene.pbrt"), 7, 5, nullptr};  // a plymesh reference
    for (const std::string &name : files) {
        SCOPED_TRACE(name);
        const Expected *x = nullptr;
        for (const Expected &e : expected)
            if (name == e.file) x = &e;
        if (!x) {
            ADD_FAILURE() << name << " has no expected outcome in this test";
            continue;
        }
        std::string path = dir + "/" + name, data;
        {
            std::ifstream in(path, std::ios::binary);
            data.assign(std::istreambuf_iterator<char>(in), {});
        }
        Diagnostics diag;
        diag.quiet = true;
        bool ply = name.size() > 4 && name.substr(name.size() - 4) == ".ply";
        try {
            if (ply) {
                ReadPlyMeshFromMemory(data, name, from, &diag);
            } else {
                ParseOptions opt;  // as fuzz/fuzz_scene.cpp
                opt.allowFileAccess = false;
                opt.maxTotalValues = size_t(1) << 20;
                ParseSceneString(data, name, diag, opt);
            }
            std::printf("[ fuzz ] %s: ok\n", name.c_str());
            EXPECT_EQ(x->message, nullptr) << "no error";
        } catch (SceneError &e) {
            std::printf("[ fuzz ] %s: %s\n", name.c_str(), e.Format().substr(0, e.Format().find('\n')).c_str());
            ASSERT_NE(x->message, nullptr) << e.Format();
            EXPECT_EQ(e.Message(), x->message);
            // Located: the reference for a PLY file, the input's own line:col for a scene.
            ASSERT_TRUE(e.Loc().file);
            if (ply) {
                EXPECT_EQ(e.Loc().ToString(), "scene.pbrt:7:5");
            } else {
                EXPECT_EQ(*e.Loc().file, name);
                EXPECT_EQ(e.Loc().line, x->line);
                EXPECT_EQ(e.Loc().col, x->col);
            }
        }
    }
}

}  // namespace lu
