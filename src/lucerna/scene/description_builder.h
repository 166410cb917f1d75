// Lucerna scene reader: the ParserTarget that owns the graphics state and fills a SceneDescription
// (host only). Follows pbrt-v4's BasicSceneBuilder (scene.cpp): the CTM at start and end time,
// attribute blocks, materials, area lights, object instancing, named coordinate systems, Import.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "lucerna/scene/parser.h"
#include "lucerna/scene/transform_math.h"

namespace lu {

class SceneDescriptionBuilder final : public ParserTarget {
  public:
    // mainFile: the scene's file name (the description's filename; its directory, baseDirectory). The
    // budget counts the copies of attribute defaults and area light parameters the builder makes.
    SceneDescriptionBuilder(Diagnostics &diag, const ParseOptions &options, ValueBudget &budget,
                            const std::string &mainFile);

    // The description; call once, after EndOfFiles.
    SceneDescription TakeDescription() { return std::move(desc_); }

    void Identity(const FileLoc &loc) override;
    void Translate(double dx, double dy, double dz, const FileLoc &loc) override;
    void Scale(double sx, double sy, double sz, const FileLoc &loc) override;
    void Rotate(double angleDeg, double ax, double ay, double az, const FileLoc &loc) override;
    void LookAt(const double eye[3], const double look[3], const double up[3], const FileLoc &loc) override;
    void Transform(const double m[16], const FileLoc &loc) override;
    void ConcatTransform(const double m[16], const FileLoc &loc) override;
    void CoordinateSystem(const std::string &name, const FileLoc &loc) override;
    void CoordSysTransform(const std::string &name, const FileLoc &loc) override;
    void ActiveTransformAll(const FileLoc &loc) override;
    void ActiveTransformStartTime(const FileLoc &loc) override;
    void ActiveTransformEndTime(const FileLoc &loc) override;
    void TransformTimes(double start, double end, const FileLoc &loc) override;

    void Option(const std::string &name, const std::string &value, const FileLoc &loc) override;
    void ColorSpace(const std::string &name, const FileLoc &loc) override;
    void Camera(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void Film(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void Sampler(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void Integrator(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void PixelFilter(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void Accelerator(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void WorldBegin(const FileLoc &loc) override;
    void WorldEnd(const FileLoc &loc) override;

    void AttributeBegin(const FileLoc &loc) override;
    void AttributeEnd(const FileLoc &loc) override;
    void TransformBegin(const FileLoc &loc) override;
    void TransformEnd(const FileLoc &loc) override;
    void Attribute(const std::string &target, ParsedParameterVector params, const FileLoc &loc) override;
    void ReverseOrientation(const FileLoc &loc) override;
    void MediumInterface(const std::string &inside, const std::string &outside, const FileLoc &loc) override;
    void MakeNamedMedium(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;

    void Material(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void MakeNamedMaterial(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void NamedMaterial(const std::string &name, const FileLoc &loc) override;
    void Texture(const std::string &name, const std::string &type, const std::string &texClass,
                 ParsedParameterVector params, const FileLoc &loc) override;
    void LightSource(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void AreaLightSource(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;
    void Shape(const std::string &name, ParsedParameterVector params, const FileLoc &loc) override;

    void ObjectBegin(const std::string &name, const FileLoc &loc) override;
    void ObjectEnd(const FileLoc &loc) override;
    void ObjectInstance(const std::string &name, const FileLoc &loc) override;

    void IncludeBegin(bool isImport, const FileLoc &loc) override;
    void IncludeEnd(bool isImport, const FileLoc &loc) override;
    void FileRead(const std::string &path) override { desc_.inputFiles.push_back(path); }
    void EndOfFiles() override;

  private:
    using ParamList = ParsedParameterVector;

    // Attribute defaults as a chain of the Attribute directives in effect (newest last), so that
    // pushing the graphics state and adding defaults are O(1).
    struct AttributeNode {
        ParamList params;
        std::shared_ptr<const AttributeNode> prev;
        size_t cost = 0;  // budget units of this node and all before it
    };
    using Attributes = std::shared_ptr<const AttributeNode>;

    // pbrt-v4's BasicSceneBuilder::GraphicsState.
    struct GraphicsState {
        DMatrix ctm[2];  // start and end time (pbrt-v4's TransformSet)
        bool activeStart = true, activeEnd = true;
        bool reverseOrientation = false;
        int materialIndex = -1;
        std::string materialName;
        FileLoc materialLoc;
        std::string areaLightName;
        std::shared_ptr<const ParamList> areaLightParams;
        FileLoc areaLightLoc;
        uint8_t areaLightColorSpace = 0;
        std::string insideMedium, outsideMedium;
        uint8_t colorSpace = 0;  // ColorSpaceId set by ColorSpace (pbrt-v4's graphicsState.colorSpace)
        Attributes shapeAttributes, lightAttributes, materialAttributes, mediumAttributes, textureAttributes;
    };

    struct PushedState {
        char kind;  // 'a' AttributeBegin/TransformBegin, 'o' ObjectBegin
        FileLoc loc;
        GraphicsState state;
    };

    struct TransformPair {
        DMatrix m[2];  // start and end time
    };

    // What an Import saved: the importer's graphics state and push floor.
    struct ImportFrame {
        GraphicsState state;
        size_t pushFloor;
    };

    enum class Block { Any, Options, World };
    // Every directive starts here: checks that it is allowed in the current block (pbrt-v4's
    // VERIFY_OPTIONS / VERIFY_WORLD) and notes that the scene has a directive.
    void Enter(Block block, const char *directive, const FileLoc &loc);
    // Stamps every parameter with the color space in effect.
    void NoteParams(ParamList &params);
    void ApplyTransform(const char *directive, const FileLoc &loc, const DMatrix &m, bool replace);
    lu::Transform CurrentTransform(const FileLoc &loc, const char *what);
    ParameterDictionary MakeDict(ParamList params, const Attributes &attributes, const FileLoc &loc);
    void SetOption(SceneEntity &slot, const char *directive, const std::string &name, ParamList params,
                   const FileLoc &loc);
    void Push(char kind, const char *directive, const FileLoc &loc);
    void Pop(const char *directive, const FileLoc &loc);
    static std::string OpenName(const PushedState &p) { return p.kind == 'o' ? "ObjectBegin" : "AttributeBegin"; }
    static std::string Where(const FileLoc &loc) {
        return "line " + std::to_string(loc.line) + (loc.file ? " of " + *loc.file : "");
    }

    Diagnostics &diag_;
    ParseOptions opt_;
    ValueBudget &budget_;
    SceneDescription desc_;
    GraphicsState state_;
    std::vector<PushedState> pushed_;
    size_t pushFloor_ = 0;  // pushes below this belong to an importing file
    std::vector<ImportFrame> imports_;
    bool inWorld_ = false, sawDirective_ = false;
    std::map<std::string, TransformPair> namedCoordinateSystems_;
    std::string activeInstance_;  // name of the ObjectBegin being defined, "" if none
    std::unordered_map<std::string, uint32_t> objectIds_;  // ObjectInstance name -> InstanceUse::object
    std::vector<FileLoc> objectFirstUse_;                  // per object id: its first ObjectInstance
    std::set<std::string> floatTextureNames_, spectrumTextureNames_, mediumNames_;
    std::vector<std::pair<std::string, FileLoc>> namedMaterialUses_;  // (name, NamedMaterial loc) per shape
    bool warnedTransformBegin_ = false, warnedMotion_ = false, warnedTransformTimes_ = false,
         warnedActiveTransform_ = false;
};

}  // namespace lu
