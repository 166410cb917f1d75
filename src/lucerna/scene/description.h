// Lucerna scene reader: the parsed pbrt-v4 scene, before interpretation (host only).
// The parser (parser.cpp) drives a SceneDescriptionBuilder (description_builder.cpp) that fills a
// SceneDescription with entities that keep their parameters and source locations; the scene
// builder (builder.cpp) interprets them into SceneData.
// Modeled on pbrt-v4's BasicScene entities.
#pragma once

#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lucerna/scene/error.h"
#include "lucerna/spectrum/color_space.h"
#include "lucerna/util/vecmath.h"

namespace lu {

// One "type name" [values] parameter as written in the file.
struct ParsedParameter {
    std::string type;   // as written: "float", "integer", "point3", "rgb", "spectrum", "texture", ...
    std::string name;
    FileLoc loc;
    std::vector<double> numbers;      // numeric values (also blackbody temperature, spectrum pairs)
    std::vector<std::string> strings; // string, texture, named spectrum or spectrum file name
    std::vector<bool> bools;
    mutable bool lookedUp = false;    // set by every Get*; unread parameters are reported
    // The ColorSpace in effect where the parameter was written (a ColorSpaceId), for "rgb"
    // values (pbrt-v4's ParsedParameter::colorSpace: Attribute values keep theirs).
    uint8_t colorSpace = 0;
};

// Typed access to an entity's parameters. Every getter marks the parameter used; a parameter of
// the right name but wrong type, or with the wrong number of values, is a SceneError at its loc.
class ParameterDictionary {
  public:
    ParameterDictionary() = default;
    explicit ParameterDictionary(std::vector<ParsedParameter> params) : params_(std::move(params)) {}

    double GetOneFloat(const std::string &name, double def) const;
    int GetOneInt(const std::string &name, int def) const;
    bool GetOneBool(const std::string &name, bool def) const;
    std::string GetOneString(const std::string &name, const std::string &def) const;
    std::optional<Vec3f> GetOnePoint3f(const std::string &name) const;
    std::optional<Vec3f> GetOneVector3f(const std::string &name) const;

    std::vector<double> GetFloatArray(const std::string &name) const;
    std::vector<int> GetIntArray(const std::string &name) const;
    std::vector<std::string> GetStringArray(const std::string &name) const;
    std::vector<Vec3f> GetPoint3fArray(const std::string &name) const;   // "point3"/"point"
    std::vector<Vec3f> GetNormal3fArray(const std::string &name) const;  // "normal"/"normal3"
    std::vector<Vec3f> GetVector3fArray(const std::string &name) const;
    std::vector<Vec2f> GetPoint2fArray(const std::string &name) const;   // "point2"

    // The raw parameter (any type) or nullptr; marks it used. Spectra ("rgb", "spectrum",
    // "blackbody") and "texture" references are interpreted by the builder from this.
    const ParsedParameter *Find(const std::string &name) const;
    // The type of a parameter if present ("" otherwise), without marking it used.
    std::string TypeOf(const std::string &name) const;
    bool Has(const std::string &name) const { return !TypeOf(name).empty(); }

    // Warnings "parameter \"type name\" is not used by NAME" for every unread parameter.
    void ReportUnused(Diagnostics &diag, const std::string &owner) const;

    const std::vector<ParsedParameter> &All() const { return params_; }

  private:
    const ParsedParameter *Lookup(const std::string &name, std::initializer_list<const char *> types,
                                  const char *expected) const;
    std::vector<ParsedParameter> params_;
};

// A directive with a type name and parameters, e.g. Camera "perspective" ...
struct SceneEntity {
    std::string name;           // "perspective", "diffuse", "trianglemesh", ...
    FileLoc loc;
    ParameterDictionary params;
    uint8_t colorSpace = 0;     // the ColorSpace in effect at the directive (a ColorSpaceId)
};

struct TransformedEntity : SceneEntity {
    Transform renderFromObject;
};

struct CameraEntity : SceneEntity {
    Transform worldFromCamera;  // inverse of the CTM at the Camera directive
    // Lucerna renders in world space: renderFromWorld is the identity.
    std::string medium;         // the outside medium at the Camera directive ("" none)
};

// MakeNamedMedium "name" "string type" ...: name in `name`, parameters (with "type") in params.
struct MediumEntity : TransformedEntity {};

struct ShapeEntity : TransformedEntity {
    bool reverseOrientation = false;
    // Material: index into SceneDescription::materials, or a named material.
    int materialIndex = -1;
    std::string materialName;           // NamedMaterial in effect ("" if materialIndex used)
    int areaLightIndex = -1;            // index into SceneDescription::areaLights, -1 none
    std::string insideMedium, outsideMedium;  // MediumInterface in effect ("" none)
    std::string baseDirectory;          // directory of the file that declared the shape (for plymesh)
};

struct LightEntity : TransformedEntity {
    std::string outsideMedium;
};

struct TextureEntity : TransformedEntity {
    std::string textureName;   // the name given in Texture "name" ...
    std::string valueType;     // "float" or "spectrum"
    std::string baseDirectory; // for image file names
};

struct InstanceDefinition {
    std::string name;
    FileLoc loc;
    std::vector<ShapeEntity> shapes;   // renderFromObject relative to the instance's world
};

// One ObjectInstance directive, kept small (116 bytes, not 200: scenes place millions of them): the object
// by index, the file location as (file, line, col) and an affine render-from-instance transform
// with its inverse as their top three rows. A transform whose bottom rows are not exactly
// (0 0 0 1) lives in SceneDescription::projectiveInstanceTransforms. Read it through the
// SceneDescription accessors below.
struct InstanceUse {
    uint32_t object = 0;                 // index into SceneDescription::objectNames
    uint32_t projective = 0xffffffffu;   // index into projectiveInstanceTransforms, or none
    Float m[3][4], mInv[3][4];           // top rows of renderFromInstance and its inverse
    uint32_t file = 0;                   // index into SceneDescription::instanceFiles
    int32_t line = 0, col = 0;
};
static_assert(sizeof(InstanceUse) == 116, "InstanceUse: keep it small (docs/benchmarks.md, instancing)");

struct SceneDescription {
    // Rendering options (pre-WorldBegin); name == "" when absent (defaults apply).
    CameraEntity camera;
    SceneEntity film, sampler, integrator, filter, accelerator;
    // Option directives, as written: the name (dequoted) and the value token (raw, quotes kept).
    struct OptionEntry {
        std::string name, value;
        FileLoc loc;
    };
    std::vector<OptionEntry> options;

    // World.
    std::vector<SceneEntity> materials;                // anonymous Material directives
    std::map<std::string, SceneEntity> namedMaterials; // MakeNamedMaterial (params include "string type")
    std::vector<TextureEntity> floatTextures, spectrumTextures;
    std::vector<LightEntity> lights;
    std::vector<SceneEntity> areaLights;               // AreaLightSource entities
    std::vector<ShapeEntity> shapes;
    std::map<std::string, InstanceDefinition> instanceDefinitions;
    // ObjectInstance uses in file order (a deque: no reallocation copies while millions arrive).
    std::deque<InstanceUse> instances;
    std::vector<std::string> objectNames;              // InstanceUse::object -> object name
    std::vector<FileLoc> instanceFiles;                // InstanceUse::file -> its file (line, col 0)
    std::vector<Transform> projectiveInstanceTransforms;
    std::vector<MediumEntity> media;                   // MakeNamedMedium, in file order
    std::string baseDirectory;                         // directory of the main file
    std::string filename;                              // the main file (whole-scene diagnostics)
    std::vector<std::string> inputFiles;               // every file read: the main file, then each Include/Import

    const std::string &ObjectName(const InstanceUse &use) const { return objectNames[use.object]; }
    FileLoc Loc(const InstanceUse &use) const;
    Transform RenderFromInstance(const InstanceUse &use) const;
};

// Parses a pbrt-v4 scene file (following Include/Import). Throws SceneError on bad input.
// Directives outside the supported subset that change the picture are errors; others are
// recorded in diag as warnings/unsupported.
SceneDescription ParseSceneFile(const std::string &filename, Diagnostics &diag);
SceneDescription ParseSceneString(const std::string &text, const std::string &filename, Diagnostics &diag);

}  // namespace lu
