// Tests of parameter lists: every pbrt-v4 parameter type as parsed, the typed getters of
// ParameterDictionary (type checks at the parameter's loc, lookedUp marking) and ReportUnused.
#include <gtest/gtest.h>

#include "lucerna/scene/parser.h"

namespace lu {

// Parses `Shape "test" <params>` in a world block and returns the shape's dictionary.
static ParameterDictionary ShapeParams(const std::string &params) {
    Diagnostics diag;
    diag.quiet = true;
    SceneDescription d = ParseSceneString("WorldBegin\nShape \"test\" " + params + "\n", "p.pbrt", diag);
    EXPECT_EQ(d.shapes.size(), 1u);
    return d.shapes.empty() ? ParameterDictionary() : d.shapes[0].params;
}

static SceneError ParamError(const std::string &params) {
    Diagnostics diag;
    diag.quiet = true;
    try {
        ParseSceneString("WorldBegin\nShape \"test\" " + params + "\n", "p.pbrt", diag);
    } catch (SceneError &e) {
        return e;
    }
    ADD_FAILURE() << "no error for " << params;
    return SceneError(FileLoc{}, "");
}

TEST(Params, Numbers) {
    ParameterDictionary p = ShapeParams(
        "\"integer n\" [ -3 ] \"integer idx\" [0 1 2] \"float r\" 2.5 \"float f\" [ 1e-3 -.5 +4 0x1p3 ]");
    EXPECT_EQ(p.GetOneInt("n", 0), -3);
    EXPECT_EQ(p.GetIntArray("idx"), (std::vector<int>{0, 1, 2}));
    EXPECT_DOUBLE_EQ(p.GetOneFloat("r", 0), 2.5);
    EXPECT_EQ(p.GetFloatArray("f"), (std::vector<double>{1e-3, -0.5, 4, 8}));
    EXPECT_EQ(p.GetOneInt("missing", 7), 7);
    EXPECT_DOUBLE_EQ(p.GetOneFloat("missing", 1.5), 1.5);
    EXPECT_TRUE(p.GetFloatArray("missing").empty());
}

TEST(Params, Vectors) {
    ParameterDictionary p = ShapeParams(
        "\"point2 uv\" [0 1 2 3] \"vector2 d\" [1 2] \"point3 P\" [1 2 3 4 5 6] \"point from\" [7 8 9] "
        "\"vector3 v\" [0 0 1] \"vector up\" [0 1 0] \"normal N\" [0 0 1] \"normal3 N2\" [1 0 0]");
    auto uv = p.GetPoint2fArray("uv");
    ASSERT_EQ(uv.size(), 2u);
    EXPECT_EQ(uv[1].x, 2);
    EXPECT_EQ(uv[1].y, 3);
    auto P = p.GetPoint3fArray("P");
    ASSERT_EQ(P.size(), 2u);
    EXPECT_EQ(P[1], Vec3f(4, 5, 6));
    EXPECT_EQ(*p.GetOnePoint3f("from"), Vec3f(7, 8, 9));
    EXPECT_EQ(*p.GetOneVector3f("v"), Vec3f(0, 0, 1));
    EXPECT_EQ(p.GetVector3fArray("up")[0], Vec3f(0, 1, 0));
    EXPECT_EQ(p.GetNormal3fArray("N")[0], Vec3f(0, 0, 1));
    EXPECT_EQ(p.GetNormal3fArray("N2")[0], Vec3f(1, 0, 0));
    EXPECT_FALSE(p.GetOnePoint3f("nothing").has_value());
    EXPECT_EQ(p.TypeOf("d"), "vector2");
    EXPECT_EQ(p.Find("d")->numbers, (std::vector<double>{1, 2}));
}

TEST(Params, BoolsAndStrings) {
    ParameterDictionary p = ShapeParams(
        "\"bool a\" true \"bool b\" [ false ] \"bool c\" \"true\" \"bool d\" [\"false\"] "
        "\"string s\" \"x y\" \"string list\" [\"a\" \"b\"] \"texture tex\" \"checks\"");
    EXPECT_TRUE(p.GetOneBool("a", false));
    EXPECT_FALSE(p.GetOneBool("b", true));
    EXPECT_TRUE(p.GetOneBool("c", false));
    EXPECT_FALSE(p.GetOneBool("d", true));
    EXPECT_EQ(p.GetOneString("s", ""), "x y");
    EXPECT_EQ(p.GetStringArray("list"), (std::vector<std::string>{"a", "b"}));
    const ParsedParameter *tex = p.Find("tex");
    ASSERT_TRUE(tex);
    EXPECT_EQ(tex->type, "texture");
    EXPECT_EQ(tex->strings, std::vector<std::string>{"checks"});
}

TEST(Params, Spectra) {
    ParameterDictionary p = ShapeParams(
        "\"rgb Kd\" [0.1 0.2 0.3] \"spectrum eta\" [300 1.5 800 1.4] \"spectrum k\" \"metal-Cu-k\" "
        "\"blackbody L\" 6500");
    const ParsedParameter *kd = p.Find("Kd");
    ASSERT_TRUE(kd);
    EXPECT_EQ(kd->numbers, (std::vector<double>{0.1, 0.2, 0.3}));
    EXPECT_EQ(p.Find("eta")->numbers.size(), 4u);
    EXPECT_EQ(p.Find("k")->strings, std::vector<std::string>{"metal-Cu-k"});
    EXPECT_EQ(p.Find("L")->numbers, std::vector<double>{6500});
    EXPECT_EQ(p.TypeOf("L"), "blackbody");
}

TEST(Params, LastDefinitionWins) {
    ParameterDictionary p = ShapeParams("\"float r\" 1 \"float r\" 2");
    EXPECT_EQ(p.GetOneFloat("r", 0), 2);
}

TEST(Params, GetterTypeMismatchIsAnErrorAtTheParameter) {
    ParameterDictionary p = ShapeParams("\n  \"integer radius\" 2");
    try {
        p.GetOneFloat("radius", 1);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Message(), "parameter \"integer radius\" has the wrong type: expected \"float radius\"");
        EXPECT_EQ(e.Loc().line, 3);
        EXPECT_EQ(e.Loc().col, 3);
    }
    ParameterDictionary q = ShapeParams("\"float r\" [1 2]");
    try {
        q.GetOneFloat("r", 1);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Message(), "parameter \"float r\" needs 1 value, but 2 were given");
    }
    ParameterDictionary v = ShapeParams("\"point3 from\" [1 2 3 4 5 6]");
    EXPECT_THROW(v.GetOnePoint3f("from"), SceneError);
}

TEST(Params, ParseErrorsForBadValues) {
    SceneError a = ParamError("\"float radius\" \"one\"");
    EXPECT_EQ(a.Message(), "parameter \"float radius\": expected a number, but got the string \"one\"");
    EXPECT_EQ(a.Loc().line, 2);
    EXPECT_EQ(a.Loc().col, 14);
    EXPECT_EQ(ParamError("\"rgb Kd\" [0.5 0.5]").Message(), "parameter \"rgb Kd\" needs 3 values, but 2 were given");
    EXPECT_EQ(ParamError("\"point3 P\" [0 0 0 1]").Message(),
              "parameter \"point3 P\" needs a multiple of 3 values, but 4 were given");
    EXPECT_EQ(ParamError("\"integer n\" 1.5").Message(), "parameter \"integer n\": expected an integer, but got \"1.5\"");
    EXPECT_EQ(ParamError("\"integer n\" 3000000000").Message(),
              "parameter \"integer n\": expected an integer, but got \"3000000000\"");
    EXPECT_EQ(ParamError("\"bool b\" 1").Message(), "parameter \"bool b\": expected true or false, but got \"1\"");
    EXPECT_EQ(ParamError("\"string s\" 1").Message(), "parameter \"string s\": expected a quoted string, but got \"1\"");
    EXPECT_EQ(ParamError("\"float f\" []").Message(), "parameter \"float f\" has no values");
    EXPECT_EQ(ParamError("\"spectrum s\" [300 1 400]").Message(),
              "parameter \"spectrum s\" needs (wavelength, value) pairs, but 3 values were given");
    EXPECT_EQ(ParamError("\"blackbody L\" [5500 125]").Message(),
              "parameter \"blackbody L\" needs 1 value, but 2 were given");
    EXPECT_EQ(ParamError("\"texture t\" [\"a\" \"b\"]").Message(),
              "parameter \"texture t\" needs 1 value, but 2 were given");
    EXPECT_EQ(ParamError("\"color Kd\" [1 1 1]").Message(),
              "unknown parameter type \"color\" in \"color Kd\" (pbrt-v3 syntax: use \"rgb\")");
    EXPECT_EQ(ParamError("\"float\" 1").Message(),
              "bad parameter declaration \"float\": expected \"type name\", like \"float radius\"");
    EXPECT_EQ(ParamError("\"float r\" 1e39").Message(), "parameter \"float r\": number \"1e39\" is out of range");
    EXPECT_EQ(ParamError("\"float r\" inf").Message(), "parameter \"float r\": non-finite number \"inf\"");
}

TEST(Params, ValueErrorOnAnotherLineNamesItsPosition) {
    SceneError e = ParamError("\"point3 P\" [ 0 0 0\n   1 x 0 ]");
    EXPECT_EQ(e.Message(), "parameter \"point3 P\": expected a number, but got \"x\" (at line 3, column 6)");
    EXPECT_EQ(e.Loc().line, 2);
}

TEST(Params, LookedUpAndReportUnused) {
    ParameterDictionary p = ShapeParams("\"float radius\" 1 \"float zmin\" -1 \"string unused\" \"x\"");
    p.GetOneFloat("radius", 0);
    p.GetOneFloat("zmin", 0);
    EXPECT_TRUE(p.All()[0].lookedUp);
    EXPECT_FALSE(p.All()[2].lookedUp);
    Diagnostics diag;
    diag.quiet = true;
    p.ReportUnused(diag, "Shape \"test\"");
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_EQ(diag.warnings[0], "p.pbrt:2:47: warning: parameter \"string unused\" is not used by Shape \"test\"");
    // TypeOf does not mark; Find does.
    ParameterDictionary q = ShapeParams("\"rgb L\" [1 1 1]");
    EXPECT_EQ(q.TypeOf("L"), "rgb");
    EXPECT_FALSE(q.All()[0].lookedUp);
    q.Find("L");
    EXPECT_TRUE(q.All()[0].lookedUp);
}

TEST(Params, ShadowedParameterIsNotReported) {
    ParameterDictionary p = ShapeParams("\"float r\" 1 \"float r\" 2");
    p.GetOneFloat("r", 0);
    Diagnostics diag;
    diag.quiet = true;
    p.ReportUnused(diag, "Shape");
    EXPECT_TRUE(diag.warnings.empty());
}

}  // namespace lu
