// Lucerna scene reader: the graphics state of a pbrt-v4 scene and the SceneDescription it produces,
// after pbrt-v4's BasicSceneBuilder (scene.cpp), with every bad input a SceneError at its
// file:line:col instead of an exit. Also ParseSceneFile/ParseSceneString: the parser driving it.
#include "lucerna/scene/description_builder.h"

#include <cmath>
#include <limits>

#include "lucerna/spectra/registry.h"

namespace lu {

SceneDescriptionBuilder::SceneDescriptionBuilder(Diagnostics &diag, const ParseOptions &options,
                                                 ValueBudget &budget, const std::string &mainFile)
    : diag_(diag), opt_(options), budget_(budget) {
    desc_.baseDirectory = DirectoryOf(mainFile);
    desc_.filename = mainFile;
}

// ---- helpers ----

void SceneDescriptionBuilder::Enter(Block block, const char *directive, const FileLoc &loc) {
    sawDirective_ = true;
    if (block == Block::World && !inWorld_)
        throw SceneError(loc, "\"" + std::string(directive) + "\" is not allowed before WorldBegin");
    if (block == Block::Options && inWorld_)
        throw SceneError(loc, "\"" + std::string(directive) + "\" is not allowed after WorldBegin");
}

void SceneDescriptionBuilder::NoteParams(ParamList &params) {
    for (ParsedParameter &p : params) p.colorSpace = state_.colorSpace;
}

void SceneDescriptionBuilder::ApplyTransform(const char *directive, const FileLoc &loc, const DMatrix &m,
                                             bool replace) {
    DMatrix r[2] = {state_.ctm[0], state_.ctm[1]};
    for (int i = 0; i < 2; ++i)
        if (i == 0 ? state_.activeStart : state_.activeEnd) r[i] = replace ? m : Mul(state_.ctm[i], m);
    if (!FitsFloat(r[0]) || !FitsFloat(r[1]))
        throw SceneError(loc, "\"" + std::string(directive) + "\" makes the transformation overflow");
    state_.ctm[0] = r[0];
    state_.ctm[1] = r[1];
}

lu::Transform SceneDescriptionBuilder::CurrentTransform(const FileLoc &loc, const char *what) {
    if (!(state_.ctm[0] == state_.ctm[1]) && !warnedMotion_) {
        warnedMotion_ = true;
        diag_.Unsupported(loc, "motion blur (ActiveTransform)", "the start-time transform is used");
    }
    const DMatrix &m = state_.ctm[0];
    DMatrix inv;
    lu::Transform t;
    t.m = ToMatrix4(m);
    if (Invert(m, &inv) && FitsFloat(inv)) {
        t.mInv = ToMatrix4(inv);
    } else {
        diag_.Warning(loc, std::string("the transformation of this ") + what + " is not invertible");
        for (auto &row : t.mInv.m)
            for (Float &x : row) x = std::numeric_limits<Float>::quiet_NaN();
    }
    return t;
}

ParameterDictionary SceneDescriptionBuilder::MakeDict(ParamList params, const Attributes &attributes,
                                                      const FileLoc &loc) {
    if (!attributes) return ParameterDictionary(std::move(params));
    // Attribute defaults come first (oldest first) so that later ones and the entity's own
    // parameters win; they may be unused without a warning (pbrt-v4's mayBeUnused).
    budget_.Spend(attributes->cost, loc);
    std::vector<const AttributeNode *> chain;
    for (const AttributeNode *n = attributes.get(); n; n = n->prev.get()) chain.push_back(n);
    ParamList all;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it)
        for (const ParsedParameter &a : (*it)->params) {
            all.push_back(a);
            all.back().lookedUp = true;
        }
    for (ParsedParameter &p : params) all.push_back(std::move(p));
    return ParameterDictionary(std::move(all));
}

void SceneDescriptionBuilder::Push(char kind, const char *directive, const FileLoc &loc) {
    if ((int)pushed_.size() >= opt_.maxAttributeDepth)
        throw SceneError(loc, "\"" + std::string(directive) + "\" nested more than " +
                                  std::to_string(opt_.maxAttributeDepth) + " deep");
    pushed_.push_back(PushedState{kind, loc, state_});
}

void SceneDescriptionBuilder::Pop(const char *directive, const FileLoc &loc) {
    if (pushed_.size() <= pushFloor_) throw SceneError(loc, "unmatched \"" + std::string(directive) + "\"");
    if (pushed_.back().kind != 'a')
        throw SceneError(loc, "\"" + std::string(directive) + "\" closes the ObjectBegin at " +
                                  Where(pushed_.back().loc));
    state_ = std::move(pushed_.back().state);
    pushed_.pop_back();
}

// ---- transformations ----

void SceneDescriptionBuilder::Identity(const FileLoc &loc) {
    Enter(Block::Any, "Identity", loc);
    ApplyTransform("Identity", loc, DMatrix(), true);
}

void SceneDescriptionBuilder::Translate(double dx, double dy, double dz, const FileLoc &loc) {
    Enter(Block::Any, "Translate", loc);
    ApplyTransform("Translate", loc, TranslateM(dx, dy, dz), false);
}

void SceneDescriptionBuilder::Scale(double sx, double sy, double sz, const FileLoc &loc) {
    Enter(Block::Any, "Scale", loc);
    ApplyTransform("Scale", loc, ScaleM(sx, sy, sz), false);
}

void SceneDescriptionBuilder::Rotate(double angleDeg, double ax, double ay, double az, const FileLoc &loc) {
    Enter(Block::Any, "Rotate", loc);
    double len = std::sqrt(ax * ax + ay * ay + az * az);
    if (!(len > 0) || !std::isfinite(len)) throw SceneError(loc, "\"Rotate\" needs a nonzero rotation axis");
    ApplyTransform("Rotate", loc, RotateM(angleDeg, ax / len, ay / len, az / len), false);
}

void SceneDescriptionBuilder::LookAt(const double eye[3], const double look[3], const double up[3],
                                     const FileLoc &loc) {
    Enter(Block::Any, "LookAt", loc);
    DMatrix cameraFromWorld;
    if (const char *why = LookAtM(eye, look, up, &cameraFromWorld))
        throw SceneError(loc, std::string("\"LookAt\": ") + why);
    ApplyTransform("LookAt", loc, cameraFromWorld, false);
}

// The 16 numbers of Transform/ConcatTransform are the matrix in column-major order (translation
// in elements 12-14).
static DMatrix FromColumnMajor(const double v[16]) {
    DMatrix m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m.m[i][j] = v[j * 4 + i];
    return m;
}

void SceneDescriptionBuilder::Transform(const double m[16], const FileLoc &loc) {
    Enter(Block::Any, "Transform", loc);
    ApplyTransform("Transform", loc, FromColumnMajor(m), true);
}

void SceneDescriptionBuilder::ConcatTransform(const double m[16], const FileLoc &loc) {
    Enter(Block::Any, "ConcatTransform", loc);
    ApplyTransform("ConcatTransform", loc, FromColumnMajor(m), false);
}

void SceneDescriptionBuilder::CoordinateSystem(const std::string &name, const FileLoc &loc) {
    Enter(Block::Any, "CoordinateSystem", loc);
    namedCoordinateSystems_[name].m[0] = state_.ctm[0];
    namedCoordinateSystems_[name].m[1] = state_.ctm[1];
}

void SceneDescriptionBuilder::CoordSysTransform(const std::string &name, const FileLoc &loc) {
    Enter(Block::Any, "CoordSysTransform", loc);
    auto it = namedCoordinateSystems_.find(name);
    if (it == namedCoordinateSystems_.end()) {
        diag_.Warning(loc, "unknown coordinate system \"" + name + "\"; the transformation is unchanged");
    } else {
        state_.ctm[0] = it->second.m[0];
        state_.ctm[1] = it->second.m[1];
    }
}

void SceneDescriptionBuilder::ActiveTransformAll(const FileLoc &loc) {
    Enter(Block::Any, "ActiveTransform", loc);
    state_.activeStart = state_.activeEnd = true;
}

void SceneDescriptionBuilder::ActiveTransformStartTime(const FileLoc &loc) {
    Enter(Block::Any, "ActiveTransform", loc);
    if (!warnedActiveTransform_) {
        warnedActiveTransform_ = true;
        diag_.Warning(loc, "ActiveTransform: motion blur is not supported; the start-time transformation is used");
    }
    state_.activeStart = true;
    state_.activeEnd = false;
}

void SceneDescriptionBuilder::ActiveTransformEndTime(const FileLoc &loc) {
    Enter(Block::Any, "ActiveTransform", loc);
    if (!warnedActiveTransform_) {
        warnedActiveTransform_ = true;
        diag_.Warning(loc, "ActiveTransform: motion blur is not supported; the start-time transformation is used");
    }
    state_.activeStart = false;
    state_.activeEnd = true;
}

void SceneDescriptionBuilder::TransformTimes(double /*start*/, double /*end*/, const FileLoc &loc) {
    Enter(Block::Options, "TransformTimes", loc);
    if (!warnedTransformTimes_) {
        warnedTransformTimes_ = true;
        diag_.Warning(loc, "TransformTimes is ignored: motion blur is not supported");
    }
}

// ---- rendering options ----

void SceneDescriptionBuilder::Option(const std::string &name, const std::string &value, const FileLoc &loc) {
    Enter(Block::Any, "Option", loc);
    desc_.options.push_back({name, value, loc});
}

void SceneDescriptionBuilder::ColorSpace(const std::string &name, const FileLoc &loc) {
    Enter(Block::Any, "ColorSpace", loc);
    std::optional<ColorSpaceId> cs = ColorSpaceFromName(name);
    if (!cs) throw SceneError(loc, "unknown color space \"" + name + "\" (known: srgb, rec2020, aces2065-1, dci-p3)");
    state_.colorSpace = uint8_t(*cs);
}

void SceneDescriptionBuilder::Camera(const std::string &name, ParamList params, const FileLoc &loc) {
    Enter(Block::Options, "Camera", loc);
    NoteParams(params);
    DMatrix cameraFromWorld = state_.ctm[0], worldFromCamera;
    if (!Invert(cameraFromWorld, &worldFromCamera) || !FitsFloat(worldFromCamera))
        throw SceneError(loc, "the camera transformation (the CTM at \"Camera\") is not invertible");
    desc_.camera.name = name;
    desc_.camera.loc = loc;
    desc_.camera.params = ParameterDictionary(std::move(params));
    desc_.camera.worldFromCamera = lu::Transform(ToMatrix4(worldFromCamera), ToMatrix4(cameraFromWorld));
    desc_.camera.medium = state_.outsideMedium;
    DMatrix inv1;
    if (!Invert(state_.ctm[1], &inv1)) inv1 = worldFromCamera;
    namedCoordinateSystems_["camera"].m[0] = worldFromCamera;
    namedCoordinateSystems_["camera"].m[1] = inv1;
}

void SceneDescriptionBuilder::SetOption(SceneEntity &slot, const char *directive, const std::string &name,
                                        ParamList params, const FileLoc &loc) {
    Enter(Block::Options, directive, loc);
    NoteParams(params);
    SceneEntity e;
    e.name = name;
    e.loc = loc;
    e.colorSpace = state_.colorSpace;
    e.params = ParameterDictionary(std::move(params));
    slot = std::move(e);
}

void SceneDescriptionBuilder::Film(const std::string &name, ParamList params, const FileLoc &loc) {
    SetOption(desc_.film, "Film", name, std::move(params), loc);
}

void SceneDescriptionBuilder::Sampler(const std::string &name, ParamList params, const FileLoc &loc) {
    SetOption(desc_.sampler, "Sampler", name, std::move(params), loc);
}

void SceneDescriptionBuilder::Integrator(const std::string &name, ParamList params, const FileLoc &loc) {
    SetOption(desc_.integrator, "Integrator", name, std::move(params), loc);
}

void SceneDescriptionBuilder::PixelFilter(const std::string &name, ParamList params, const FileLoc &loc) {
    SetOption(desc_.filter, "PixelFilter", name, std::move(params), loc);
}

void SceneDescriptionBuilder::Accelerator(const std::string &name, ParamList params, const FileLoc &loc) {
    SetOption(desc_.accelerator, "Accelerator", name, std::move(params), loc);
}

void SceneDescriptionBuilder::WorldBegin(const FileLoc &loc) {
    Enter(Block::Options, "WorldBegin", loc);
    if (!pushed_.empty())
        throw SceneError(loc, "\"WorldBegin\" inside the " + OpenName(pushed_.back()) + " at " +
                                  Where(pushed_.back().loc));
    inWorld_ = true;
    state_.ctm[0] = state_.ctm[1] = DMatrix();
    state_.activeStart = state_.activeEnd = true;
    namedCoordinateSystems_["world"].m[0] = DMatrix();
    namedCoordinateSystems_["world"].m[1] = DMatrix();
}

void SceneDescriptionBuilder::WorldEnd(const FileLoc &loc) {
    Enter(Block::Any, "WorldEnd", loc);
    diag_.Warning(loc, "\"WorldEnd\" is pbrt-v3 syntax; ignored");
}

// ---- graphics state ----

void SceneDescriptionBuilder::AttributeBegin(const FileLoc &loc) {
    Enter(Block::Any, "AttributeBegin", loc);
    Push('a', "AttributeBegin", loc);
}

void SceneDescriptionBuilder::AttributeEnd(const FileLoc &loc) {
    Enter(Block::Any, "AttributeEnd", loc);
    Pop("AttributeEnd", loc);
}

void SceneDescriptionBuilder::TransformBegin(const FileLoc &loc) {
    Enter(Block::Any, "TransformBegin", loc);
    if (!warnedTransformBegin_) {
        warnedTransformBegin_ = true;
        diag_.Warning(loc, "TransformBegin/End are deprecated and should be replaced with AttributeBegin/End");
    }
    Push('a', "TransformBegin", loc);
}

void SceneDescriptionBuilder::TransformEnd(const FileLoc &loc) {
    Enter(Block::Any, "TransformEnd", loc);
    Pop("TransformEnd", loc);
}

void SceneDescriptionBuilder::Attribute(const std::string &target, ParamList params, const FileLoc &loc) {
    Enter(Block::Any, "Attribute", loc);
    NoteParams(params);
    Attributes *slot = target == "shape"      ? &state_.shapeAttributes
                       : target == "light"    ? &state_.lightAttributes
                       : target == "material" ? &state_.materialAttributes
                       : target == "medium"   ? &state_.mediumAttributes
                       : target == "texture"  ? &state_.textureAttributes
                                              : nullptr;
    if (!slot)
        throw SceneError(loc, "unknown Attribute target \"" + target +
                                  "\": must be \"shape\", \"light\", \"material\", \"medium\" or \"texture\"");
    if (!params.empty()) {
        auto node = std::make_shared<AttributeNode>();
        node->cost = ValueBudget::Cost(params) + (*slot ? (*slot)->cost : 0);
        node->params = std::move(params);
        node->prev = *slot;
        *slot = std::move(node);
    }
}

void SceneDescriptionBuilder::ReverseOrientation(const FileLoc &loc) {
    Enter(Block::World, "ReverseOrientation", loc);
    state_.reverseOrientation = !state_.reverseOrientation;
}

void SceneDescriptionBuilder::MediumInterface(const std::string &inside, const std::string &outside,
                                              const FileLoc &loc) {
    Enter(Block::Any, "MediumInterface", loc);
    state_.insideMedium = inside;
    state_.outsideMedium = outside;
}

void SceneDescriptionBuilder::MakeNamedMedium(const std::string &name, ParamList params, const FileLoc &loc) {
    Enter(Block::Any, "MakeNamedMedium", loc);
    NoteParams(params);
    if (!mediumNames_.insert(name).second) throw SceneError(loc, "named medium \"" + name + "\" is already defined");
    MediumEntity e;
    e.name = name;
    e.loc = loc;
    e.colorSpace = state_.colorSpace;
    e.params = MakeDict(std::move(params), state_.mediumAttributes, loc);
    e.renderFromObject = CurrentTransform(loc, "MakeNamedMedium");
    desc_.media.push_back(std::move(e));
}

// ---- materials and textures ----

void SceneDescriptionBuilder::Material(const std::string &name, ParamList params, const FileLoc &loc) {
    Enter(Block::World, "Material", loc);
    NoteParams(params);
    SceneEntity e;
    e.name = name;
    e.loc = loc;
    e.colorSpace = state_.colorSpace;
    e.params = MakeDict(std::move(params), state_.materialAttributes, loc);
    desc_.materials.push_back(std::move(e));
    state_.materialIndex = int(desc_.materials.size()) - 1;
    state_.materialName.clear();
}

void SceneDescriptionBuilder::MakeNamedMaterial(const std::string &name, ParamList params, const FileLoc &loc) {
    Enter(Block::World, "MakeNamedMaterial", loc);
    NoteParams(params);
    if (desc_.namedMaterials.count(name)) throw SceneError(loc, "named material \"" + name + "\" is already defined");
    SceneEntity e;
    e.loc = loc;
    e.colorSpace = state_.colorSpace;
    e.params = MakeDict(std::move(params), state_.materialAttributes, loc);
    const ParsedParameter *type = nullptr;  // the last one: the material's own wins over defaults
    for (const ParsedParameter &p : e.params.All())
        if (p.name == "type") type = &p;
    if (!type) throw SceneError(loc, "named material \"" + name + "\" has no \"string type\" parameter");
    if (type->type != "string" || type->strings.size() != 1)
        throw SceneError(type->loc, "named material \"" + name +
                                        "\": \"type\" must be one string, like \"string type\" \"diffuse\"");
    type->lookedUp = true;
    e.name = type->strings[0];
    desc_.namedMaterials.emplace(name, std::move(e));
}

void SceneDescriptionBuilder::NamedMaterial(const std::string &name, const FileLoc &loc) {
    Enter(Block::World, "NamedMaterial", loc);
    state_.materialName = name;
    state_.materialIndex = -1;
    state_.materialLoc = loc;
}

void SceneDescriptionBuilder::Texture(const std::string &name, const std::string &type, const std::string &texClass,
                                      ParamList params, const FileLoc &loc) {
    Enter(Block::World, "Texture", loc);
    NoteParams(params);
    if (type != "float" && type != "spectrum")
        throw SceneError(loc, "texture type \"" + type + "\" is unknown: must be \"float\" or \"spectrum\"");
    auto &names = type == "float" ? floatTextureNames_ : spectrumTextureNames_;
    if (!names.insert(name).second) throw SceneError(loc, type + " texture \"" + name + "\" is already defined");
    TextureEntity e;
    e.textureName = name;
    e.valueType = type;
    e.name = texClass;
    e.loc = loc;
    e.colorSpace = state_.colorSpace;
    e.params = MakeDict(std::move(params), state_.textureAttributes, loc);
    e.renderFromObject = CurrentTransform(loc, "Texture");
    e.baseDirectory = DirectoryOf(loc.Filename());
    (type == "float" ? desc_.floatTextures : desc_.spectrumTextures).push_back(std::move(e));
}

// ---- lights and shapes ----

void SceneDescriptionBuilder::LightSource(const std::string &name, ParamList params, const FileLoc &loc) {
    Enter(Block::World, "LightSource", loc);
    NoteParams(params);
    LightEntity e;
    e.name = name;
    e.loc = loc;
    e.colorSpace = state_.colorSpace;
    e.params = MakeDict(std::move(params), state_.lightAttributes, loc);
    e.renderFromObject = CurrentTransform(loc, "LightSource");
    e.outsideMedium = state_.outsideMedium;
    desc_.lights.push_back(std::move(e));
}

void SceneDescriptionBuilder::AreaLightSource(const std::string &name, ParamList params, const FileLoc &loc) {
    Enter(Block::World, "AreaLightSource", loc);
    NoteParams(params);
    state_.areaLightName = name;
    state_.areaLightLoc = loc;
    state_.areaLightColorSpace = state_.colorSpace;
    // The light attribute defaults in effect now apply (as pbrt-v4's AreaLightSource).
    state_.areaLightParams =
        std::make_shared<ParamList>(MakeDict(std::move(params), state_.lightAttributes, loc).All());
}

void SceneDescriptionBuilder::Shape(const std::string &name, ParamList params, const FileLoc &loc) {
    Enter(Block::World, "Shape", loc);
    NoteParams(params);
    ShapeEntity e;
    e.name = name;
    e.loc = loc;
    e.colorSpace = state_.colorSpace;
    e.params = MakeDict(std::move(params), state_.shapeAttributes, loc);
    e.renderFromObject = CurrentTransform(loc, "Shape");
    e.reverseOrientation = state_.reverseOrientation;
    e.materialIndex = state_.materialIndex;
    e.materialName = state_.materialName;
    e.insideMedium = state_.insideMedium;
    e.outsideMedium = state_.outsideMedium;
    e.baseDirectory = DirectoryOf(loc.Filename());
    if (!state_.areaLightName.empty()) {
        SceneEntity light;
        light.name = state_.areaLightName;
        light.loc = state_.areaLightLoc;
        light.colorSpace = state_.areaLightColorSpace;
        ParamList lp = state_.areaLightParams ? *state_.areaLightParams : ParamList();
        budget_.Spend(ValueBudget::Cost(lp), loc);
        light.params = ParameterDictionary(std::move(lp));
        desc_.areaLights.push_back(std::move(light));
        e.areaLightIndex = int(desc_.areaLights.size()) - 1;
        if (!activeInstance_.empty()) diag_.Warning(loc, "area lights are not supported with object instancing");
    }
    if (!e.materialName.empty()) namedMaterialUses_.emplace_back(e.materialName, state_.materialLoc);
    if (!activeInstance_.empty()) desc_.instanceDefinitions[activeInstance_].shapes.push_back(std::move(e));
    else desc_.shapes.push_back(std::move(e));
}

// ---- object instancing ----

void SceneDescriptionBuilder::ObjectBegin(const std::string &name, const FileLoc &loc) {
    Enter(Block::World, "ObjectBegin", loc);
    if (!activeInstance_.empty())
        throw SceneError(loc, "\"ObjectBegin\" inside the definition of object \"" + activeInstance_ + "\"");
    if (desc_.instanceDefinitions.count(name)) throw SceneError(loc, "object \"" + name + "\" is already defined");
    Push('o', "ObjectBegin", loc);
    activeInstance_ = name;
    InstanceDefinition &def = desc_.instanceDefinitions[name];
    def.name = name;
    def.loc = loc;
}

void SceneDescriptionBuilder::ObjectEnd(const FileLoc &loc) {
    Enter(Block::World, "ObjectEnd", loc);
    if (activeInstance_.empty() || pushed_.size() <= pushFloor_) throw SceneError(loc, "unmatched \"ObjectEnd\"");
    if (pushed_.back().kind != 'o')
        throw SceneError(loc, "\"ObjectEnd\" closes the AttributeBegin at " + Where(pushed_.back().loc));
    state_ = std::move(pushed_.back().state);
    pushed_.pop_back();
    activeInstance_.clear();
}

void SceneDescriptionBuilder::ObjectInstance(const std::string &name, const FileLoc &loc) {
    Enter(Block::World, "ObjectInstance", loc);
    if (!activeInstance_.empty())
        throw SceneError(loc, "\"ObjectInstance\" inside the definition of object \"" + activeInstance_ + "\"");
    InstanceUse use;
    auto [it, added] = objectIds_.try_emplace(name, uint32_t(desc_.objectNames.size()));
    if (added) {
        desc_.objectNames.push_back(name);
        objectFirstUse_.push_back(loc);
    }
    use.object = it->second;
    // The file: the same as the previous use's almost always.
    if (desc_.instanceFiles.empty() || desc_.instanceFiles.back().file != loc.file ||
        desc_.instanceFiles.back().includedFrom != loc.includedFrom) {
        FileLoc f = loc;
        f.line = f.col = 0;
        desc_.instanceFiles.push_back(std::move(f));
    }
    use.file = uint32_t(desc_.instanceFiles.size() - 1);
    use.line = loc.line;
    use.col = loc.col;
    lu::Transform t = CurrentTransform(loc, "ObjectInstance");
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            use.m[i][j] = t.m.m[i][j];
            use.mInv[i][j] = t.mInv.m[i][j];
        }
    bool affine = true;
    for (int j = 0; j < 4; ++j) {
        Float e = j == 3 ? 1 : 0;
        affine = affine && t.m.m[3][j] == e && t.mInv.m[3][j] == e;
    }
    if (!affine) {
        use.projective = uint32_t(desc_.projectiveInstanceTransforms.size());
        desc_.projectiveInstanceTransforms.push_back(t);
    }
    desc_.instances.push_back(use);
}

// ---- files ----

void SceneDescriptionBuilder::IncludeBegin(bool isImport, const FileLoc &loc) {
    Enter(isImport ? Block::World : Block::Any, isImport ? "Import" : "Include", loc);
    if (!isImport) return;
    // Import: the imported file sees a copy of the graphics state and cannot change ours; its
    // AttributeBegin/End must balance (pbrt-v4's CopyForImport / MergeImported).
    imports_.push_back(ImportFrame{state_, pushFloor_});
    pushFloor_ = pushed_.size();
}

void SceneDescriptionBuilder::IncludeEnd(bool isImport, const FileLoc &) {
    if (!isImport) return;
    if (pushed_.size() > pushFloor_) {
        const PushedState &open = pushed_.back();
        throw SceneError(open.loc, OpenName(open) + " without a matching " +
                                       (open.kind == 'o' ? "ObjectEnd" : "AttributeEnd") + " in the imported file");
    }
    pushFloor_ = imports_.back().pushFloor;
    state_ = std::move(imports_.back().state);
    imports_.pop_back();
}

void SceneDescriptionBuilder::EndOfFiles() {
    if (!pushed_.empty()) {
        const PushedState &open = pushed_.back();
        throw SceneError(open.loc, OpenName(open) + " without a matching " +
                                       (open.kind == 'o' ? "ObjectEnd" : "AttributeEnd"));
    }
    for (const auto &[name, loc] : namedMaterialUses_)
        if (!desc_.namedMaterials.count(name))
            throw SceneError(loc, "named material \"" + name + "\" is not defined (no MakeNamedMaterial \"" + name + "\")");
    for (size_t i = 0; i < desc_.objectNames.size(); ++i) {
        const std::string &name = desc_.objectNames[i];
        if (!desc_.instanceDefinitions.count(name))
            throw SceneError(objectFirstUse_[i], "object \"" + name + "\" is not defined (no ObjectBegin \"" + name + "\")");
    }
    if (sawDirective_ && !inWorld_) diag_.Warning(FileLoc{}, "the scene has no WorldBegin");
}

// ---- the compact instance uses ----

FileLoc SceneDescription::Loc(const InstanceUse &use) const {
    FileLoc loc = use.file < instanceFiles.size() ? instanceFiles[use.file] : FileLoc{};
    loc.line = use.line;
    loc.col = use.col;
    return loc;
}

Transform SceneDescription::RenderFromInstance(const InstanceUse &use) const {
    if (use.projective != 0xffffffffu) return projectiveInstanceTransforms[use.projective];
    Transform t;   // Matrix4() is the identity: its bottom rows stay (0 0 0 1)
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            t.m.m[i][j] = use.m[i][j];
            t.mInv.m[i][j] = use.mInv[i][j];
        }
    return t;
}

// ---- the parser driving the builder ----

SceneDescription ParseSceneFile(const std::string &filename, Diagnostics &diag, const ParseOptions &options) {
    ValueBudget budget(options.maxTotalValues);
    SceneDescriptionBuilder builder(diag, options, budget, filename);
    ParseFile(builder, filename, options, budget);
    return builder.TakeDescription();
}

SceneDescription ParseSceneString(const std::string &text, const std::string &filename, Diagnostics &diag,
                                  const ParseOptions &options) {
    ValueBudget budget(options.maxTotalValues);
    SceneDescriptionBuilder builder(diag, options, budget, filename);
    ParseString(builder, text, filename, options, budget);
    return builder.TakeDescription();
}

SceneDescription ParseSceneFile(const std::string &filename, Diagnostics &diag) {
    return ParseSceneFile(filename, diag, ParseOptions());
}

SceneDescription ParseSceneString(const std::string &text, const std::string &filename, Diagnostics &diag) {
    return ParseSceneString(text, filename, diag, ParseOptions());
}

}  // namespace lu
