// Tests of the parser on its own (pbrt-v4's ParserTarget split): a recording target sees one call
// per directive with the arguments as written, Include/Import bracketed by IncludeBegin/End, and
// no state checks (those belong to the SceneDescriptionBuilder).
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "lucerna/scene/parser.h"
#include "support/test_support.h"

namespace lu {
namespace {

// Writes each call as one line: "Name args... @line:col".
class RecordingTarget final : public ParserTarget {
  public:
    std::vector<std::string> calls;

    void Identity(const FileLoc &loc) override { Add("Identity", loc); }
    void Translate(double x, double y, double z, const FileLoc &loc) override { Add("Translate" + N({x, y, z}), loc); }
    void Scale(double x, double y, double z, const FileLoc &loc) override { Add("Scale" + N({x, y, z}), loc); }
    void Rotate(double a, double x, double y, double z, const FileLoc &loc) override { Add("Rotate" + N({a, x, y, z}), loc); }
    void LookAt(const double e[3], const double l[3], const double u[3], const FileLoc &loc) override {
        Add("LookAt" + N({e[0], e[1], e[2], l[0], l[1], l[2], u[0], u[1], u[2]}), loc);
    }
    void Transform(const double m[16], const FileLoc &loc) override { Add("Transform" + N16(m), loc); }
    void ConcatTransform(const double m[16], const FileLoc &loc) override { Add("ConcatTransform" + N16(m), loc); }
    void CoordinateSystem(const std::string &n, const FileLoc &loc) override { Add("CoordinateSystem " + n, loc); }
    void CoordSysTransform(const std::string &n, const FileLoc &loc) override { Add("CoordSysTransform " + n, loc); }
    void ActiveTransformAll(const FileLoc &loc) override { Add("ActiveTransformAll", loc); }
    void ActiveTransformStartTime(const FileLoc &loc) override { Add("ActiveTransformStartTime", loc); }
    void ActiveTransformEndTime(const FileLoc &loc) override { Add("ActiveTransformEndTime", loc); }
    void TransformTimes(double s, double e, const FileLoc &loc) override { Add("TransformTimes" + N({s, e}), loc); }
    void Option(const std::string &n, const std::string &v, const FileLoc &loc) override { Add("Option " + n + " " + v, loc); }
    void ColorSpace(const std::string &n, const FileLoc &loc) override { Add("ColorSpace " + n, loc); }
    void Camera(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("Camera " + n + P(p), loc); }
    void Film(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("Film " + n + P(p), loc); }
    void Sampler(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("Sampler " + n + P(p), loc); }
    void Integrator(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("Integrator " + n + P(p), loc); }
    void PixelFilter(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("PixelFilter " + n + P(p), loc); }
    void Accelerator(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("Accelerator " + n + P(p), loc); }
    void WorldBegin(const FileLoc &loc) override { Add("WorldBegin", loc); }
    void WorldEnd(const FileLoc &loc) override { Add("WorldEnd", loc); }
    void AttributeBegin(const FileLoc &loc) override { Add("AttributeBegin", loc); }
    void AttributeEnd(const FileLoc &loc) override { Add("AttributeEnd", loc); }
    void TransformBegin(const FileLoc &loc) override { Add("TransformBegin", loc); }
    void TransformEnd(const FileLoc &loc) override { Add("TransformEnd", loc); }
    void Attribute(const std::string &t, ParsedParameterVector p, const FileLoc &loc) override { Add("Attribute " + t + P(p), loc); }
    void ReverseOrientation(const FileLoc &loc) override { Add("ReverseOrientation", loc); }
    void MediumInterface(const std::string &i, const std::string &o, const FileLoc &loc) override {
        Add("MediumInterface '" + i + "' '" + o + "'", loc);
    }
    void MakeNamedMedium(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("MakeNamedMedium " + n + P(p), loc); }
    void Material(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("Material " + n + P(p), loc); }
    void MakeNamedMaterial(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("MakeNamedMaterial " + n + P(p), loc); }
    void NamedMaterial(const std::string &n, const FileLoc &loc) override { Add("NamedMaterial " + n, loc); }
    void Texture(const std::string &n, const std::string &t, const std::string &c, ParsedParameterVector p,
                 const FileLoc &loc) override {
        Add("Texture " + n + " " + t + " " + c + P(p), loc);
    }
    void LightSource(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("LightSource " + n + P(p), loc); }
    void AreaLightSource(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("AreaLightSource " + n + P(p), loc); }
    void Shape(const std::string &n, ParsedParameterVector p, const FileLoc &loc) override { Add("Shape " + n + P(p), loc); }
    void ObjectBegin(const std::string &n, const FileLoc &loc) override { Add("ObjectBegin " + n, loc); }
    void ObjectEnd(const FileLoc &loc) override { Add("ObjectEnd", loc); }
    void ObjectInstance(const std::string &n, const FileLoc &loc) override { Add("ObjectInstance " + n, loc); }
    void IncludeBegin(bool imp, const FileLoc &loc) override { Add(imp ? "ImportBegin" : "IncludeBegin", loc); }
    void IncludeEnd(bool imp, const FileLoc &loc) override { Add(imp ? "ImportEnd" : "IncludeEnd", loc); }
    void EndOfFiles() override { calls.push_back("EndOfFiles"); }

  private:
    void Add(const std::string &s, const FileLoc &loc) {
        std::string file = loc.Filename();
        file = file.substr(file.find_last_of('/') + 1);
        calls.push_back(s + " @" + file + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.col));
    }
    static std::string Num(double x) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", x);
        return buf;
    }
    static std::string N(std::initializer_list<double> v) {
        std::string s;
        for (double x : v) s += " " + Num(x);
        return s;
    }
    static std::string N16(const double m[16]) {
        std::string s;
        for (int i = 0; i < 16; ++i) s += " " + Num(m[i]);
        return s;
    }
    static std::string P(const ParsedParameterVector &ps) {
        std::string s;
        for (const ParsedParameter &p : ps) {
            s += " [" + p.type + " " + p.name + ":";
            for (double x : p.numbers) s += " " + Num(x);
            for (const std::string &t : p.strings) s += " '" + t + "'";
            for (bool b : p.bools) s += b ? " true" : " false";
            s += "]";
        }
        return s;
    }
};

std::vector<std::string> Record(const std::string &text) {
    RecordingTarget t;
    ValueBudget budget(1000);
    ParseString(t, text, "r.pbrt", ParseOptions{}, budget);
    return t.calls;
}

TEST(ParserTarget, OneCallPerDirectiveWithItsArgumentsAsWritten) {
    std::vector<std::string> calls = Record(
        "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
        "  Option \"disablepixeljitter\" true\nColorSpace \"srgb\"\nActiveTransform EndTime\n"
        "Transform [ 1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1 ]\nWorldBegin\n"
        "Attribute \"shape\" \"float radius\" [ 2 ]\nMediumInterface \"fog\"\n"
        "Texture \"t\" \"float\" \"constant\" \"float value\" .5\n"
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"bool alpha\" \"true\" \"string name\" \"a b\"\n"
        "ObjectBegin \"o\"\nObjectEnd\nObjectInstance \"o\"\n");
    const std::vector<std::string> expected = {
        "LookAt 0 0 -5 0 0 0 0 1 0 @r.pbrt:1:1",
        "Camera perspective [float fov: 45] @r.pbrt:2:1",
        "Option disablepixeljitter true @r.pbrt:3:3",
        "ColorSpace srgb @r.pbrt:4:1",
        "ActiveTransformEndTime @r.pbrt:5:1",
        // Column-major, as written: the target transposes.
        "Transform 1 0 0 0 0 1 0 0 0 0 1 0 5 6 7 1 @r.pbrt:6:1",
        "WorldBegin @r.pbrt:7:1",
        "Attribute shape [float radius: 2] @r.pbrt:8:1",
        "MediumInterface 'fog' 'fog' @r.pbrt:9:1",
        "Texture t float constant [float value: 0.5] @r.pbrt:10:1",
        "Shape trianglemesh [point3 P: 0 0 0 1 0 0 0 1 0] [bool alpha: true] [string name: 'a b'] @r.pbrt:11:1",
        "ObjectBegin o @r.pbrt:12:1",
        "ObjectEnd @r.pbrt:13:1",
        "ObjectInstance o @r.pbrt:14:1",
        "EndOfFiles"};
    EXPECT_EQ(calls, expected);
}

TEST(ParserTarget, TheParserChecksSyntaxButNotState) {
    // Out of block, unbalanced, undefined: all the target's business.
    std::vector<std::string> calls =
        Record("Shape \"sphere\"\nAttributeEnd\nObjectInstance \"none\"\nWorldBegin\nCamera \"x\"\nWorldBegin\n");
    ASSERT_EQ(calls.size(), 7u);
    EXPECT_EQ(calls[0], "Shape sphere @r.pbrt:1:1");
    EXPECT_EQ(calls[4], "Camera x @r.pbrt:5:1");
    // Syntax is the parser's: the target sees nothing after the bad directive.
    RecordingTarget t;
    ValueBudget budget(1000);
    try {
        ParseString(t, "WorldBegin\nShape \"sphere\" \"float radius\" [ 1 \"two\" ]\nShape \"disk\"\n", "r.pbrt",
                    ParseOptions{}, budget);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Message(), "parameter \"float radius\": expected a number, but got the string \"two\"");
        EXPECT_EQ(e.SourceLine(), "Shape \"sphere\" \"float radius\" [ 1 \"two\" ]");
    }
    EXPECT_EQ(t.calls, std::vector<std::string>{"WorldBegin @r.pbrt:1:1"});
}

TEST(ParserTarget, IncludeAndImportAreBracketed) {
    std::string dir = test::TempDir("target_include");
    std::ofstream(dir + "/main.pbrt") << "Include \"a.pbrt\"\nWorldBegin\nImport \"b.pbrt\"\n";
    std::ofstream(dir + "/a.pbrt") << "Film \"rgb\"\n";
    std::ofstream(dir + "/b.pbrt") << "\n  Shape \"sphere\"\n";
    RecordingTarget t;
    ValueBudget budget(1000);
    ParseFile(t, dir + "/main.pbrt", ParseOptions{}, budget);
    const std::vector<std::string> expected = {
        "IncludeBegin @main.pbrt:1:1", "Film rgb @a.pbrt:1:1",      "IncludeEnd @main.pbrt:1:1",
        "WorldBegin @main.pbrt:2:1",   "ImportBegin @main.pbrt:3:1", "Shape sphere @b.pbrt:2:3",
        "ImportEnd @main.pbrt:3:1",    "EndOfFiles"};
    EXPECT_EQ(t.calls, expected);
}

// An error the target throws gets the source line from the parser (the text is in memory).
class ThrowingTarget final : public ParserTarget {
  public:
    void Identity(const FileLoc &) override {}
    void Translate(double, double, double, const FileLoc &loc) override { throw SceneError(loc, "no translation"); }
    void Scale(double, double, double, const FileLoc &) override {}
    void Rotate(double, double, double, double, const FileLoc &) override {}
    void LookAt(const double[3], const double[3], const double[3], const FileLoc &) override {}
    void Transform(const double[16], const FileLoc &) override {}
    void ConcatTransform(const double[16], const FileLoc &) override {}
    void CoordinateSystem(const std::string &, const FileLoc &) override {}
    void CoordSysTransform(const std::string &, const FileLoc &) override {}
    void ActiveTransformAll(const FileLoc &) override {}
    void ActiveTransformStartTime(const FileLoc &) override {}
    void ActiveTransformEndTime(const FileLoc &) override {}
    void TransformTimes(double, double, const FileLoc &) override {}
    void Option(const std::string &, const std::string &, const FileLoc &) override {}
    void ColorSpace(const std::string &, const FileLoc &) override {}
    void Camera(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void Film(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void Sampler(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void Integrator(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void PixelFilter(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void Accelerator(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void WorldBegin(const FileLoc &) override {}
    void WorldEnd(const FileLoc &) override {}
    void AttributeBegin(const FileLoc &) override {}
    void AttributeEnd(const FileLoc &) override {}
    void TransformBegin(const FileLoc &) override {}
    void TransformEnd(const FileLoc &) override {}
    void Attribute(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void ReverseOrientation(const FileLoc &) override {}
    void MediumInterface(const std::string &, const std::string &, const FileLoc &) override {}
    void MakeNamedMedium(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void Material(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void MakeNamedMaterial(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void NamedMaterial(const std::string &, const FileLoc &) override {}
    void Texture(const std::string &, const std::string &, const std::string &, ParsedParameterVector,
                 const FileLoc &) override {}
    void LightSource(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void AreaLightSource(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void Shape(const std::string &, ParsedParameterVector, const FileLoc &) override {}
    void ObjectBegin(const std::string &, const FileLoc &) override {}
    void ObjectEnd(const FileLoc &) override {}
    void ObjectInstance(const std::string &, const FileLoc &) override {}
    void IncludeBegin(bool, const FileLoc &) override {}
    void IncludeEnd(bool, const FileLoc &) override {}
    void EndOfFiles() override {}
};

TEST(ParserTarget, TargetErrorsGetTheSourceLine) {
    ThrowingTarget t;
    ValueBudget budget(1000);
    try {
        ParseString(t, "Scale 1 1 1\n  Translate 1 2\n    3\n", "r.pbrt", ParseOptions{}, budget);
        FAIL();
    } catch (SceneError &e) {
        EXPECT_EQ(e.Format(), "r.pbrt:2:3: error: no translation\n  Translate 1 2\n  ^");
    }
}

}  // namespace
}  // namespace lu
