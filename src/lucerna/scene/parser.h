// Lucerna scene reader: the pbrt-v4 text-format parser (host only). As pbrt-v4's parser.h, it only
// tokenizes and parses: each directive goes to a ParserTarget, such as the SceneDescriptionBuilder
// (description_builder.h), which owns the graphics state. Scene files may be gzip-compressed.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "lucerna/scene/description.h"

namespace lu {

struct ParseOptions {
    // Include/Import may open files. Off: they are SceneErrors (the fuzzer uses this).
    bool allowFileAccess = true;
    // Bounds on what hostile input can make the reader allocate.
    int maxIncludeDepth = 32;
    int maxAttributeDepth = 4096;
    size_t maxTotalValues = size_t(1) << 28;  // parameter values stored, copies included
};

// The parameter values a scene may make the reader store, shared by the parser (values as
// written) and its target (copies of attribute defaults and area light parameters). One unit per
// value and one per parameter.
class ValueBudget {
  public:
    explicit ValueBudget(size_t limit) : limit_(limit) {}
    // Throws SceneError at loc once more than the limit has been spent in all.
    void Spend(size_t n, const FileLoc &loc);
    bool Exceeds(size_t more) const { return used_ + more > limit_; }
    static size_t Cost(const ParsedParameter &p) { return 1 + p.numbers.size() + p.strings.size() + p.bools.size(); }
    static size_t Cost(const std::vector<ParsedParameter> &ps);

  private:
    size_t used_ = 0, limit_;
};

using ParsedParameterVector = std::vector<ParsedParameter>;

// The receiver of the parsed directives, in file order (pbrt-v4's ParserTarget). Each call gets the
// directive's location (its first token) and its arguments, checked for syntax only: argument counts
// and kinds, parameter declarations and value counts. Whatever depends on state (the block, names,
// transformations) is the target's to check; it reports bad input by throwing SceneError.
class ParserTarget {
  public:
    virtual ~ParserTarget() = default;

    // ---- transformations (numbers as written, in double precision) ----
    virtual void Identity(const FileLoc &loc) = 0;
    virtual void Translate(double dx, double dy, double dz, const FileLoc &loc) = 0;
    virtual void Scale(double sx, double sy, double sz, const FileLoc &loc) = 0;
    virtual void Rotate(double angleDeg, double ax, double ay, double az, const FileLoc &loc) = 0;
    virtual void LookAt(const double eye[3], const double look[3], const double up[3], const FileLoc &loc) = 0;
    // The 16 numbers as written: the matrix in column-major order.
    virtual void Transform(const double m[16], const FileLoc &loc) = 0;
    virtual void ConcatTransform(const double m[16], const FileLoc &loc) = 0;
    virtual void CoordinateSystem(const std::string &name, const FileLoc &loc) = 0;
    virtual void CoordSysTransform(const std::string &name, const FileLoc &loc) = 0;
    virtual void ActiveTransformAll(const FileLoc &loc) = 0;
    virtual void ActiveTransformStartTime(const FileLoc &loc) = 0;
    virtual void ActiveTransformEndTime(const FileLoc &loc) = 0;
    virtual void TransformTimes(double start, double end, const FileLoc &loc) = 0;

    // ---- rendering options ----
    // value: the value token as written (a quoted string keeps its quotes).
    virtual void Option(const std::string &name, const std::string &value, const FileLoc &loc) = 0;
    virtual void ColorSpace(const std::string &name, const FileLoc &loc) = 0;
    virtual void Camera(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void Film(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void Sampler(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void Integrator(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void PixelFilter(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void Accelerator(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void WorldBegin(const FileLoc &loc) = 0;
    virtual void WorldEnd(const FileLoc &loc) = 0;  // pbrt-v3 syntax

    // ---- graphics state ----
    virtual void AttributeBegin(const FileLoc &loc) = 0;
    virtual void AttributeEnd(const FileLoc &loc) = 0;
    virtual void TransformBegin(const FileLoc &loc) = 0;  // deprecated forms of AttributeBegin/End
    virtual void TransformEnd(const FileLoc &loc) = 0;
    virtual void Attribute(const std::string &target, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void ReverseOrientation(const FileLoc &loc) = 0;
    virtual void MediumInterface(const std::string &inside, const std::string &outside, const FileLoc &loc) = 0;
    virtual void MakeNamedMedium(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;

    // ---- materials, textures, lights, shapes ----
    virtual void Material(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void MakeNamedMaterial(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void NamedMaterial(const std::string &name, const FileLoc &loc) = 0;
    virtual void Texture(const std::string &name, const std::string &type, const std::string &texClass,
                         ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void LightSource(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void AreaLightSource(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;
    virtual void Shape(const std::string &name, ParsedParameterVector params, const FileLoc &loc) = 0;

    // ---- object instancing ----
    virtual void ObjectBegin(const std::string &name, const FileLoc &loc) = 0;
    virtual void ObjectEnd(const FileLoc &loc) = 0;
    virtual void ObjectInstance(const std::string &name, const FileLoc &loc) = 0;

    // ---- files ----
    // Include/Import "name" at loc: IncludeBegin comes before the file is opened (a target may
    // refuse it), IncludeEnd after its last directive. The parser opens and reads the file.
    virtual void IncludeBegin(bool isImport, const FileLoc &loc) = 0;
    virtual void IncludeEnd(bool isImport, const FileLoc &loc) = 0;
    // Each file the parser has read (the main file, then each Include/Import), before its directives.
    virtual void FileRead(const std::string & /*path*/) {}
    // After the last directive of the main file.
    virtual void EndOfFiles() = 0;
};

// Parses a scene file and everything it includes (each gzip-compressed or not: told by its first
// bytes, whatever its name), calling target for each directive and then target.EndOfFiles(). Throws SceneError.
void ParseFile(ParserTarget &target, const std::string &filename, const ParseOptions &options, ValueBudget &budget);
// The same for scene text in memory; filename is what FileLocs report and what Include resolves against.
void ParseString(ParserTarget &target, const std::string &text, const std::string &filename,
                 const ParseOptions &options, ValueBudget &budget);

// The parser driving a SceneDescriptionBuilder (defined in description_builder.cpp).
// ParseSceneFile / ParseSceneString without options (description.h) use the default ParseOptions.
SceneDescription ParseSceneFile(const std::string &filename, Diagnostics &diag, const ParseOptions &options);
SceneDescription ParseSceneString(const std::string &text, const std::string &filename, Diagnostics &diag,
                                  const ParseOptions &options);

// The directory part of a path ("" for a bare file name), and `path` resolved against `dir`
// (absolute paths are returned unchanged).
std::string DirectoryOf(const std::string &path);
std::string ResolvePath(const std::string &dir, const std::string &path);

}  // namespace lu
