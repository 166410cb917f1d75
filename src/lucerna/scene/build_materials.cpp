// Lucerna scene builder: textures and materials, after pbrt-v4's textures.cpp / materials.cpp
// Create() functions and TextureParameterDictionary (paramdict.cpp).
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

// ---- Textures ----

namespace {

// The pbrt-v4 texture types Lucerna does not evaluate.
bool IsUnsupportedTextureType(const std::string &t) {
    static const char *names[] = {"scale", "mix", "directionmix", "bilerp", "dots", "fbm", "marble",
                                  "wrinkled", "windy", "ptex"};
    for (const char *n : names)
        if (t == n) return true;
    return false;
}

std::string Owner(const TextureEntity &te) { return "Texture " + Quoted(te.textureName) + " (" + Quoted(te.name) + ")"; }

UVMapping ReadMapping(const TextureEntity &te) {
    const ParameterDictionary &p = te.params;
    std::string type = p.GetOneString("mapping", "uv");
    if (type == "spherical" || type == "cylindrical" || type == "planar")
        FailUnsupported(ParamLoc(p, "mapping", te.loc), "texture mapping " + Quoted(type));
    if (type != "uv") Fail(ParamLoc(p, "mapping", te.loc), "unknown 2D texture mapping " + Quoted(type));
    UVMapping m;
    m.su = Float(p.GetOneFloat("uscale", 1));
    m.sv = Float(p.GetOneFloat("vscale", 1));
    m.du = Float(p.GetOneFloat("udelta", 0));
    m.dv = Float(p.GetOneFloat("vdelta", 0));
    return m;
}

struct ImageTexParams {
    uint32_t image = NoIndex;
    Float scale = 1;
    bool invert = false;
};

// pbrt-v4's FloatImageTexture / SpectrumImageTexture::Create parameters.
ImageTexParams ReadImageTexture(BuildContext &ctx, const TextureEntity &te) {
    const ParameterDictionary &p = te.params;
    if (auto it = ctx.textureImages.find(&te); it != ctx.textureImages.end()) {
        // Already interpreted (spectrum textures are built once per spectrum type).
        ImageTexParams r;
        r.image = it->second;
        r.scale = Float(p.GetOneFloat("scale", 1));
        r.invert = p.GetOneBool("invert", false);
        return r;
    }
    // Filtering: Lucerna looks textures up bilinearly without MIP-mapping.
    std::string filter = p.GetOneString("filter", "bilinear");
    (void)p.GetOneFloat("maxanisotropy", 8);
    if (filter != "bilinear" && filter != "point" && filter != "trilinear" && filter != "ewa")
        Fail(ParamLoc(p, "filter", te.loc), Quoted(filter) + ": unknown texture filter function");
    if (filter != "bilinear")
        ctx.diag.Unsupported(ParamLoc(p, "filter", te.loc), "texture filter " + Quoted(filter), "using bilinear lookups");
    std::string wrapString = p.GetOneString("wrap", "repeat");
    WrapMode wrap;
    if (wrapString == "repeat") wrap = WrapMode::Repeat;
    else if (wrapString == "clamp") wrap = WrapMode::Clamp;
    else if (wrapString == "black") wrap = WrapMode::Black;
    else if (wrapString == "octahedralsphere")
        FailUnsupported(ParamLoc(p, "wrap", te.loc), "texture wrap mode \"octahedralsphere\"");
    else
        Fail(ParamLoc(p, "wrap", te.loc), Quoted(wrapString) + ": unknown wrap mode");
    ImageTexParams r;
    r.scale = Float(p.GetOneFloat("scale", 1));
    r.invert = p.GetOneBool("invert", false);
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty()) Fail(te.loc, "\"string filename\" not provided for image texture " + Quoted(te.textureName));
    std::string path = ResolveScenePath(ctx, te.baseDirectory, filename);
    std::string ext = std::filesystem::path(filename).extension().string();
    for (char &c : ext) c = char(std::tolower((unsigned char)c));
    bool isPNG = ext == ".png";
    std::string encoding = p.GetOneString("encoding", isPNG ? "sRGB" : "linear");
    bool linear;
    if (encoding == "sRGB") linear = false;
    else if (encoding == "linear") linear = true;
    else if (encoding.rfind("gamma ", 0) == 0)
        FailUnsupported(ParamLoc(p, "encoding", te.loc), "texture encoding " + Quoted(encoding));
    else
        Fail(ParamLoc(p, "encoding", te.loc), Quoted(encoding) + ": unknown color encoding");
    if (!isPNG && !linear)
        ctx.diag.Warning(ParamLoc(p, "encoding", te.loc), "\"encoding\" only applies to 8-bit (PNG) images; " +
                                                              Quoted(filename) + " is read as linear");
    LoadedImage img = LoadImage(ctx, path, linear || !isPNG, te.loc);
    r.image = AddImageData(ctx, img, wrap);
    ctx.textureImages[&te] = r.image;
    return r;
}

const TextureEntity *FindTexture(const std::map<std::string, const TextureEntity *> &m, const std::string &name) {
    auto it = m.find(name);
    return it == m.end() ? nullptr : it->second;
}

FloatTexture BuildFloatTexture(BuildContext &ctx, const TextureEntity &te);
SpectrumTexture BuildSpectrumTexture(BuildContext &ctx, const TextureEntity &te, SpectrumType type);

FloatTexture FloatTextureByName(BuildContext &ctx, const std::string &texName, const ParsedParameter &p) {
    const TextureEntity *te = FindTexture(ctx.floatTextures, texName);
    if (!te) Fail(p.loc, "couldn't find float texture named " + Quoted(texName) + " for parameter " + Quoted(p.name));
    return BuildFloatTexture(ctx, *te);
}

SpectrumTexture SpectrumTextureByName(BuildContext &ctx, const std::string &texName, const ParsedParameter &p,
                                      SpectrumType type) {
    const TextureEntity *te = FindTexture(ctx.spectrumTextures, texName);
    if (!te) Fail(p.loc, "couldn't find spectrum texture named " + Quoted(texName) + " for parameter " + Quoted(p.name));
    return BuildSpectrumTexture(ctx, *te, type);
}

const ParsedParameter &TextureReference(const ParameterDictionary &params, const std::string &name) {
    const ParsedParameter *p = params.Find(name);
    if (p->strings.size() != 1) Fail(p->loc, "parameter \"texture " + name + "\" needs exactly one texture name");
    return *p;
}

}  // namespace

// pbrt-v4's TextureParameterDictionary::GetFloatTextureOrNull.
static std::optional<FloatTexture> GetFloatTextureOrNull(BuildContext &ctx, const ParameterDictionary &params,
                                                         const std::string &name) {
    std::string t = params.TypeOf(name);
    if (t.empty()) return std::nullopt;
    if (t == "float") {
        FloatTexture ft;
        ft.kind = TextureKind::Constant;
        ft.value = Float(params.GetOneFloat(name, 0));
        return ft;
    }
    if (t == "texture") {
        const ParsedParameter &p = TextureReference(params, name);
        return FloatTextureByName(ctx, p.strings[0], p);
    }
    Fail(ParamLoc(params, name, {}), "parameter " + Quoted(t + " " + name) + " has the wrong type: expected \"float\" or \"texture\"");
}

static FloatTexture GetFloatTexture(BuildContext &ctx, const ParameterDictionary &params, const std::string &name, Float def) {
    if (auto t = GetFloatTextureOrNull(ctx, params, name)) return *t;
    FloatTexture ft;
    ft.kind = TextureKind::Constant;
    ft.value = def;
    return ft;
}

static SpectrumTexture ConstantSpectrumTexture(const Spectrum &s, SpectrumType type) {
    SpectrumTexture st;
    st.kind = TextureKind::Constant;
    st.value = s;
    st.unbounded = type != SpectrumType::Albedo;
    return st;
}

// pbrt-v4's TextureParameterDictionary::GetSpectrumTextureOrNull.
static std::optional<SpectrumTexture> GetSpectrumTextureOrNull(BuildContext &ctx, const ParameterDictionary &params,
                                                               const std::string &name, SpectrumType type) {
    std::string t = params.TypeOf(name);
    if (t.empty()) return std::nullopt;
    if (t == "texture") {
        const ParsedParameter &p = TextureReference(params, name);
        return SpectrumTextureByName(ctx, p.strings[0], p, type);
    }
    std::optional<Spectrum> s = GetSpectrum(ctx, params, name, type);
    if (!s) return std::nullopt;
    return ConstantSpectrumTexture(*s, type);
}

static SpectrumTexture GetSpectrumTexture(BuildContext &ctx, const ParameterDictionary &params, const std::string &name,
                                          SpectrumType type, const Spectrum &def) {
    if (auto t = GetSpectrumTextureOrNull(ctx, params, name, type)) return *t;
    return ConstantSpectrumTexture(def, type);
}

namespace {

FloatTexture BuildFloatTexture(BuildContext &ctx, const TextureEntity &te) {
    if (auto it = ctx.floatTextureCache.find(te.textureName); it != ctx.floatTextureCache.end()) return it->second;
    std::string key = "float:" + te.textureName;
    if (ctx.texturesBuilding.count(key)) Fail(te.loc, "texture " + Quoted(te.textureName) + " refers to itself");
    ctx.texturesBuilding.insert(key);
    const ParameterDictionary &p = te.params;
    FloatTexture ft;
    if (te.name == "constant") {
        ft.kind = TextureKind::Constant;
        ft.value = Float(p.GetOneFloat("value", 1));
    } else if (te.name == "imagemap") {
        ft.kind = TextureKind::ImageMap;
        ft.mapping = ReadMapping(te);
        ImageTexParams ip = ReadImageTexture(ctx, te);
        ft.image = ip.image;
        ft.scale = ip.scale;
        ft.invert = ip.invert;
    } else if (te.name == "checkerboard") {
        int dim = p.GetOneInt("dimension", 2);
        if (dim == 3) FailUnsupported(ParamLoc(p, "dimension", te.loc), "3D checkerboard texture");
        if (dim != 2) Fail(ParamLoc(p, "dimension", te.loc), std::to_string(dim) + " dimensional checkerboard texture not supported");
        ft.kind = TextureKind::Checkerboard;
        ft.mapping = ReadMapping(te);
        FloatTexture t1 = GetFloatTexture(ctx, p, "tex1", 1), t2 = GetFloatTexture(ctx, p, "tex2", 0);
        if (t1.kind != TextureKind::Constant || t2.kind != TextureKind::Constant)
            FailUnsupported(te.loc, "checkerboard texture with non-constant \"tex1\"/\"tex2\"");
        ft.tex1 = t1.value;
        ft.tex2 = t2.value;
    } else if (IsUnsupportedTextureType(te.name)) {
        FailUnsupported(te.loc, "Texture type " + Quoted(te.name));
    } else {
        Fail(te.loc, "unknown texture type " + Quoted(te.name));
    }
    p.ReportUnused(ctx.diag, Owner(te));
    ctx.texturesBuilding.erase(key);
    ctx.floatTextureCache[te.textureName] = ft;
    return ft;
}

SpectrumTexture BuildSpectrumTexture(BuildContext &ctx, const TextureEntity &te, SpectrumType type) {
    auto ckey = std::make_pair(te.textureName, int(type));
    if (auto it = ctx.spectrumTextureCache.find(ckey); it != ctx.spectrumTextureCache.end()) return it->second;
    std::string key = "spectrum:" + te.textureName;
    if (ctx.texturesBuilding.count(key)) Fail(te.loc, "texture " + Quoted(te.textureName) + " refers to itself");
    ctx.texturesBuilding.insert(key);
    const ParameterDictionary &p = te.params;
    SpectrumTexture st;
    st.unbounded = type != SpectrumType::Albedo;
    if (te.name == "constant") {
        st = GetSpectrumTexture(ctx, p, "value", type, Spectrum::Const(1));
        if (st.kind != TextureKind::Constant) FailUnsupported(te.loc, "constant texture whose \"value\" is a texture");
    } else if (te.name == "imagemap") {
        st.kind = TextureKind::ImageMap;
        st.mapping = ReadMapping(te);
        ImageTexParams ip = ReadImageTexture(ctx, te);
        st.image = ip.image;
        st.scale = ip.scale;
        st.invert = ip.invert;
    } else if (te.name == "checkerboard") {
        int dim = p.GetOneInt("dimension", 2);
        if (dim == 3) FailUnsupported(ParamLoc(p, "dimension", te.loc), "3D checkerboard texture");
        if (dim != 2) Fail(ParamLoc(p, "dimension", te.loc), std::to_string(dim) + " dimensional checkerboard texture not supported");
        st.kind = TextureKind::Checkerboard;
        st.mapping = ReadMapping(te);
        SpectrumTexture t1 = GetSpectrumTexture(ctx, p, "tex1", type, Spectrum::Const(1));
        SpectrumTexture t2 = GetSpectrumTexture(ctx, p, "tex2", type, Spectrum::Const(0));
        if (t1.kind != TextureKind::Constant || t2.kind != TextureKind::Constant)
            FailUnsupported(te.loc, "checkerboard texture with non-constant \"tex1\"/\"tex2\"");
        st.tex1 = t1.value;
        st.tex2 = t2.value;
    } else if (IsUnsupportedTextureType(te.name)) {
        FailUnsupported(te.loc, "Texture type " + Quoted(te.name));
    } else {
        Fail(te.loc, "unknown texture type " + Quoted(te.name));
    }
    // Parameters are read once per spectrum type; report unused after the first.
    bool first = true;
    for (auto &[k, v] : ctx.spectrumTextureCache)
        if (k.first == te.textureName) first = false;
    if (first) p.ReportUnused(ctx.diag, Owner(te));
    ctx.texturesBuilding.erase(key);
    ctx.spectrumTextureCache[ckey] = st;
    return st;
}

}  // namespace

void IndexTextures(BuildContext &ctx) {
    for (const TextureEntity &te : ctx.desc.floatTextures) {
        if (ctx.floatTextures.count(te.textureName)) Fail(te.loc, "redefining texture " + Quoted(te.textureName));
        ctx.floatTextures[te.textureName] = &te;
    }
    for (const TextureEntity &te : ctx.desc.spectrumTextures) {
        if (ctx.spectrumTextures.count(te.textureName)) Fail(te.loc, "redefining texture " + Quoted(te.textureName));
        ctx.spectrumTextures[te.textureName] = &te;
    }
    ctx.scene.stats.floatTextures = int(ctx.desc.floatTextures.size());
    ctx.scene.stats.spectrumTextures = int(ctx.desc.spectrumTextures.size());
    // pbrt-v4 creates every texture, used or not (spectrum textures in each spectrum type), so
    // errors in unused ones surface too.
    for (const TextureEntity &te : ctx.desc.floatTextures) BuildFloatTexture(ctx, te);
    for (const TextureEntity &te : ctx.desc.spectrumTextures) {
        BuildSpectrumTexture(ctx, te, SpectrumType::Albedo);
        BuildSpectrumTexture(ctx, te, SpectrumType::Unbounded);
    }
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
    p.ReportUnused(ctx.diag, owner);
    uint32_t index = uint32_t(ctx.scene.materials.size());
    ctx.scene.materials.push_back(m);
    return index;
}

}  // namespace

void BuildMaterials(BuildContext &ctx) {
    // Named materials first (pbrt-v4's CreateMaterials order), then the anonymous ones.
    for (const auto &[name, e] : ctx.desc.namedMaterials) {
        std::string type = e.params.GetOneString("type", "");
        if (!e.params.Has("type"))
            Fail(e.loc, "named material " + Quoted(name) + ": \"string type\" not provided in its parameters");
        ctx.namedMaterialTypes[name] = type;
        ctx.namedMaterials[name] = CreateMaterial(ctx, type, e.params, e.loc, "MakeNamedMaterial " + Quoted(name));
    }
    for (const SceneEntity &e : ctx.desc.materials) {
        ctx.anonymousMaterialTypes.push_back(e.name);
        ctx.anonymousMaterials.push_back(CreateMaterial(ctx, e.name, e.params, e.loc, "Material " + Quoted(e.name)));
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
    // No Material directive in effect: pbrt-v4's default "diffuse" (reflectance 0.5).
    if (ctx.defaultMaterial == NoIndex) {
        Material m;
        m.kind = MaterialKind::Diffuse;
        m.reflectance = ConstantSpectrumTexture(Spectrum::Const(0.5f), SpectrumType::Albedo);
        ctx.defaultMaterial = uint32_t(ctx.scene.materials.size());
        ctx.scene.materials.push_back(m);
    }
    if (type) *type = "diffuse";
    return ctx.defaultMaterial;
}

}  // namespace lu::build
