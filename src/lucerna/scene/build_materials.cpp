// Lucerna scene builder: image loading and materials, after pbrt-v4's materials.cpp Create()
// functions (textures: build_textures.cpp).
#include <cmath>
#include <filesystem>

#include "lucerna/image/image.h"
#include "lucerna/scene/build_internal.h"

namespace lu::build {

std::string ResolvePath(const std::string &baseDirectory, const std::string &filename) {
    std::filesystem::path p(filename);
    if (p.is_absolute() || baseDirectory.empty()) return filename;
    return (std::filesystem::path(baseDirectory) / p).lexically_normal().string();
}

std::string ResolveScenePath(BuildContext &ctx, const std::string &entityDirectory, const std::string &filename) {
    std::string main = ResolvePath(ctx.desc.baseDirectory, filename);
    std::error_code ec;
    if (entityDirectory.empty() || entityDirectory == ctx.desc.baseDirectory || std::filesystem::exists(main, ec)) return main;
    std::string local = ResolvePath(entityDirectory, filename);
    return std::filesystem::exists(local, ec) ? local : main;
}

// ---- Images ----

LoadedImage LoadImage(BuildContext &ctx, const std::string &path, bool pngIsLinear, const FileLoc &loc) {
    ImageKey key{path, pngIsLinear};
    if (auto it = ctx.imageCache.find(key); it != ctx.imageCache.end()) return it->second;
    ctx.scene.inputFiles.push_back(path);
    Image img;
    try {
        img = ReadImage(path, pngIsLinear);
    } catch (const std::exception &e) {
        Fail(loc, e.what());
    }
    if (img.width <= 0 || img.height <= 0 || img.channels <= 0) Fail(loc, Quoted(path) + ": empty image");
    if (img.channels == 2) Fail(loc, Quoted(path) + ": two-channel images are not supported (need Y, RGB or RGBA)");
    if (CountNonFinite(img) > 0) Fail(loc, Quoted(path) + ": image has infinite or not-a-number pixel values");
    LoadedImage li;
    li.width = uint32_t(img.width);
    li.height = uint32_t(img.height);
    li.channels = img.channels == 1 ? 1 : 3;  // RGBA: alpha is not used
    li.offset = ctx.scene.texels.size();
    ctx.scene.texels.reserve(ctx.scene.texels.size() + size_t(img.width) * img.height * li.channels);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (uint32_t c = 0; c < li.channels; ++c) ctx.scene.texels.push_back(Float(img.At(x, y, int(c))));
    ctx.imageCache[key] = li;
    return li;
}

uint32_t AddImageData(BuildContext &ctx, const LoadedImage &img, WrapMode wrap) {
    auto key = std::make_tuple(img.offset, int(wrap));
    if (auto it = ctx.imageDataCache.find(key); it != ctx.imageDataCache.end()) return it->second;
    ImageData d;
    d.width = img.width;
    d.height = img.height;
    d.channels = img.channels;
    d.offset = img.offset;
    d.wrap = wrap;
    uint32_t index = uint32_t(ctx.scene.images.size());
    ctx.scene.images.push_back(d);
    ctx.imageDataCache[key] = index;
    return index;
}

// ---- Materials ----

namespace {

bool IsUnsupportedMaterialType(const std::string &t) {
    static const char *names[] = {"coatedconductor", "diffusetransmission", "measured", "hair", "subsurface", "mix"};
    for (const char *n : names)
        if (t == n) return true;
    return false;
}

// "eta" of dielectrics and coated diffuse: a float (GetFloatArray("eta")[0]) or a spectrum.
Spectrum ReadEta(BuildContext &ctx, const ParameterDictionary &p) {
    if (p.TypeOf("eta") == "float") {
        std::vector<double> v = p.GetFloatArray("eta");
        return Spectrum::Const(Float(v.empty() ? 1.5 : v[0]));
    }
    if (p.TypeOf("eta") == "texture") FailUnsupported(ParamLoc(p, "eta", {}), "textured \"eta\"");
    if (std::optional<Spectrum> s = GetSpectrum(ctx, p, "eta", SpectrumType::Unbounded)) return *s;
    return Spectrum::Const(1.5f);
}

void ReadRoughness(BuildContext &ctx, const ParameterDictionary &p, Material &m) {
    std::optional<FloatTexture> u = GetFloatTextureOrNull(ctx, p, "uroughness");
    std::optional<FloatTexture> v = GetFloatTextureOrNull(ctx, p, "vroughness");
    m.uRoughness = u ? *u : GetFloatTexture(ctx, p, "roughness", 0);
    m.vRoughness = v ? *v : GetFloatTexture(ctx, p, "roughness", 0);
    m.remapRoughness = p.GetOneBool("remaproughness", true);
}

Spectrum NamedOrFail(BuildContext &ctx, const std::string &name, const FileLoc &loc) {
    return NamedOrFileSpectrum(ctx, name, loc);
}

// pbrt-v4's Material::Create: the material's index in scene.materials, or NoIndex for
// "interface" / "none" / "".
uint32_t CreateMaterial(BuildContext &ctx, const std::string &type, const ParameterDictionary &p, const FileLoc &loc,
                        const std::string &owner) {
    ctx.scene.stats.materialsByType[type.empty() ? std::string("interface") : type]++;
    if (type == "interface" || type == "none" || type.empty()) {
        p.ReportUnused(ctx.diag, owner);
        return NoIndex;
    }
    if (IsUnsupportedMaterialType(type)) FailUnsupported(loc, "Material type " + Quoted(type));
    Material m;
    if (type == "diffuse") {
        m.kind = MaterialKind::Diffuse;
        m.reflectance = GetSpectrumTexture(ctx, p, "reflectance", SpectrumType::Albedo, Spectrum::Const(0.5f));
    } else if (type == "conductor") {
        m.kind = MaterialKind::Conductor;
        std::optional<SpectrumTexture> eta = GetSpectrumTextureOrNull(ctx, p, "eta", SpectrumType::Unbounded);
        std::optional<SpectrumTexture> k = GetSpectrumTextureOrNull(ctx, p, "k", SpectrumType::Unbounded);
        std::optional<SpectrumTexture> refl = GetSpectrumTextureOrNull(ctx, p, "reflectance", SpectrumType::Albedo);
        if (refl && (eta || k))
            Fail(loc, "for the conductor material, \"reflectance\" and \"eta\"/\"k\" can't both be provided");
        if (refl) {
            m.useReflectance = true;
            m.reflectance = *refl;
        } else {
            m.conductorEta = eta ? *eta : ConstantSpectrumTexture(NamedOrFail(ctx, "metal-Cu-eta", loc), SpectrumType::Unbounded);
            m.conductorK = k ? *k : ConstantSpectrumTexture(NamedOrFail(ctx, "metal-Cu-k", loc), SpectrumType::Unbounded);
        }
        ReadRoughness(ctx, p, m);
    } else if (type == "dielectric") {
        m.kind = MaterialKind::Dielectric;
        m.eta = ReadEta(ctx, p);
        ReadRoughness(ctx, p, m);
    } else if (type == "thindielectric") {
        m.kind = MaterialKind::ThinDielectric;
        m.eta = ReadEta(ctx, p);
    } else if (type == "coateddiffuse") {
        m.kind = MaterialKind::CoatedDiffuse;
        m.reflectance = GetSpectrumTexture(ctx, p, "reflectance", SpectrumType::Albedo, Spectrum::Const(0.5f));
        ReadRoughness(ctx, p, m);
        m.thickness = GetFloatTexture(ctx, p, "thickness", 0.01f);
        m.eta = ReadEta(ctx, p);
        m.maxDepth = p.GetOneInt("maxdepth", 10);
        m.nSamples = p.GetOneInt("nsamples", 1);
        m.g = GetFloatTexture(ctx, p, "g", 0);
        m.albedo = GetSpectrumTexture(ctx, p, "albedo", SpectrumType::Albedo, Spectrum::Const(0));
    } else {
        Fail(loc, "unknown material type " + Quoted(type));
    }
    // Bump and normal mapping change the shading normal: refuse rather than ignore.
    if (p.Has("displacement")) FailUnsupported(ParamLoc(p, "displacement", loc), "material \"displacement\" (bump mapping)");
    if (p.Has("normalmap")) FailUnsupported(ParamLoc(p, "normalmap", loc), "material \"normalmap\"");
    CheckMaterialValues(m, ctx.scene.floatTextures, p, loc, owner);
    p.ReportUnused(ctx.diag, owner);
    uint32_t index = uint32_t(ctx.scene.materials.size());
    ctx.scene.materials.push_back(m);
    ctx.scene.SetOrigin(ctx.scene.materialOrigin, index, owner + " at " + loc.ToString());
    return index;
}

}  // namespace

// No Material directive in effect: pbrt-v4's default "diffuse" (reflectance 0.5), created once.
uint32_t DefaultMaterial(BuildContext &ctx) {
    if (ctx.defaultMaterial == NoIndex) {
        Material m;
        m.kind = MaterialKind::Diffuse;
        m.reflectance = ConstantSpectrumTexture(Spectrum::Const(0.5f), SpectrumType::Albedo);
        ctx.defaultMaterial = uint32_t(ctx.scene.materials.size());
        ctx.scene.materials.push_back(m);
        ctx.scene.SetOrigin(ctx.scene.materialOrigin, ctx.defaultMaterial, "the default material (\"diffuse\", reflectance 0.5)");
    }
    return ctx.defaultMaterial;
}

void BuildMaterials(BuildContext &ctx) {
    // Named materials first (pbrt-v4's CreateMaterials order), then the anonymous ones.
    for (const auto &named : ctx.desc.namedMaterials) {
        const std::string &name = named.first;   // (no structured binding: clang 14 cannot capture one)
        const auto &e = named.second;
        std::string type = e.params.GetOneString("type", "");
        if (!e.params.Has("type"))
            Fail(e.loc, "named material " + Quoted(name) + ": \"string type\" not provided in its parameters");
        ctx.namedMaterialTypes[name] = type;
        // An unsupported material is collected and replaced by the default one, so that the
        // shapes using it are still checked.
        uint32_t m = NoIndex;
        if (!ctx.Collect([&] { m = CreateMaterial(ctx, type, e.params, e.loc, "MakeNamedMaterial " + Quoted(name)); }))
            m = DefaultMaterial(ctx);
        ctx.namedMaterials[name] = m;
    }
    for (const SceneEntity &e : ctx.desc.materials) {
        ctx.anonymousMaterialTypes.push_back(e.name);
        uint32_t m = NoIndex;
        if (!ctx.Collect([&] { m = CreateMaterial(ctx, e.name, e.params, e.loc, "Material " + Quoted(e.name)); }))
            m = DefaultMaterial(ctx);
        ctx.anonymousMaterials.push_back(m);
    }
}

uint32_t ResolveShapeMaterial(BuildContext &ctx, const ShapeEntity &shape, std::string *type) {
    if (!shape.materialName.empty()) {
        auto it = ctx.namedMaterials.find(shape.materialName);
        if (it == ctx.namedMaterials.end()) Fail(shape.loc, "named material " + Quoted(shape.materialName) + " is not defined");
        if (type) *type = ctx.namedMaterialTypes[shape.materialName];
        return it->second;
    }
    if (shape.materialIndex >= 0) {
        if (size_t(shape.materialIndex) >= ctx.anonymousMaterials.size()) Fail(shape.loc, "internal: material index out of range");
        if (type) *type = ctx.anonymousMaterialTypes[shape.materialIndex];
        return ctx.anonymousMaterials[shape.materialIndex];
    }
    if (type) *type = "diffuse";
    return DefaultMaterial(ctx);
}

}  // namespace lu::build
