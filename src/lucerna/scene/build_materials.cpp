// Lucerna scene builder: image loading and materials, after pbrt-v4's materials.cpp Create()
// functions (textures: build_textures.cpp).
#include <cmath>
#include <filesystem>

#include "lucerna/image/image.h"
#include "lucerna/scene/build_internal.h"
#include "lucerna/scene/measured_file.h"

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
    if (img.hasChromaticities) {  // pbrt-v4's ReadEXR: RGBColorSpace::Lookup, else a warning and sRGB
        const auto &c = img.chromaticities;
        std::optional<ColorSpaceId> cs = LookupColorSpace({c[0], c[1]}, {c[2], c[3]}, {c[4], c[5]}, {c[6], c[7]});
        if (cs) li.colorSpace = uint8_t(*cs);
        else
            ctx.diag.Warning(loc, Quoted(path) + ": no supported color space matches the file's chromaticities; using sRGB");
    }
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
    d.colorSpace = img.colorSpace;
    uint32_t index = uint32_t(ctx.scene.images.size());
    ctx.scene.images.push_back(d);
    ctx.imageDataCache[key] = index;
    return index;
}

// ---- Materials ----

namespace {

bool IsUnsupportedMaterialType(const std::string &t) {
    static const char *names[] = {"subsurface"};
    for (const char *n : names)
        if (t == n) return true;
    return false;
}

// "eta" of dielectrics and coated diffuse ("interface.eta" of the coated conductor): a float
// (GetFloatArray(name)[0]) or a spectrum.
// A float or spectrum eta into m.eta; a float texture ("texture" parameter) into m.etaTexture.
void ReadEta(BuildContext &ctx, const ParameterDictionary &p, Material &m, const std::string &name = "eta") {
    if (p.TypeOf(name) == "float") {
        std::vector<double> v = p.GetFloatArray(name);
        m.eta = Spectrum::Const(Float(v.empty() ? 1.5 : v[0]));
    } else if (p.TypeOf(name) == "texture") {
        m.etaTexture = GetFloatTextureNode(ctx, p, name, 1.5f);
    } else if (std::optional<Spectrum> s = GetSpectrum(ctx, p, name, SpectrumType::Unbounded)) {
        m.eta = *s;
    } else {
        m.eta = Spectrum::Const(1.5f);
    }
}

// PREFIXuroughness / PREFIXvroughness, else PREFIXroughness (default 0).
void ReadRoughness(BuildContext &ctx, const ParameterDictionary &p, FloatTexture *uRough, FloatTexture *vRough,
                   const std::string &prefix = "") {
    std::optional<FloatTexture> u = GetFloatTextureOrNull(ctx, p, prefix + "uroughness");
    std::optional<FloatTexture> v = GetFloatTextureOrNull(ctx, p, prefix + "vroughness");
    *uRough = u ? *u : GetFloatTexture(ctx, p, prefix + "roughness", 0);
    *vRough = v ? *v : GetFloatTexture(ctx, p, prefix + "roughness", 0);
}
void ReadRoughness(BuildContext &ctx, const ParameterDictionary &p, Material &m) {
    ReadRoughness(ctx, p, &m.uRoughness, &m.vRoughness);
    m.remapRoughness = p.GetOneBool("remaproughness", true);
}

// A conductor's complex index: "reflectance", or ETANAME / KNAME (default copper).
void ReadConductorIndex(BuildContext &ctx, const ParameterDictionary &p, Material &m, const std::string &etaName,
                        const std::string &kName, const std::string &type, const FileLoc &loc) {
    std::optional<SpectrumTexture> eta = GetSpectrumTextureOrNull(ctx, p, etaName, SpectrumType::Unbounded);
    std::optional<SpectrumTexture> k = GetSpectrumTextureOrNull(ctx, p, kName, SpectrumType::Unbounded);
    std::optional<SpectrumTexture> refl = GetSpectrumTextureOrNull(ctx, p, "reflectance", SpectrumType::Albedo);
    if (refl && (eta || k))
        Fail(loc, "for the " + type + " material, \"reflectance\" and " + Quoted(etaName) + "/" + Quoted(kName) +
                      " can't both be provided");
    if (refl) {
        m.useReflectance = true;
        m.reflectance = *refl;
    } else {
        m.conductorEta = eta ? *eta : ConstantSpectrumTexture(NamedOrFileSpectrum(ctx, "metal-Cu-eta", loc), SpectrumType::Unbounded);
        m.conductorK = k ? *k : ConstantSpectrumTexture(NamedOrFileSpectrum(ctx, "metal-Cu-k", loc), SpectrumType::Unbounded);
    }
}

uint32_t CreateNamedMaterial(BuildContext &ctx, const std::string &name, const SceneEntity &e);

// pbrt-v4's HairMaterial::Create: the absorption from the first of "sigma_a", "reflectance" (or
// "color"), "eumelanin"/"pheomelanin" given (the others are warned about and ignored, as pbrt-v4
// does); none of them: eumelanin 1.3. A missing one of the two melanins is 0.
void ReadHair(BuildContext &ctx, const ParameterDictionary &p, Material &m, const FileLoc &loc, const std::string &owner) {
    std::optional<SpectrumTexture> sigmaA = GetSpectrumTextureOrNull(ctx, p, "sigma_a", SpectrumType::Unbounded);
    std::optional<SpectrumTexture> refl = GetSpectrumTextureOrNull(ctx, p, "reflectance", SpectrumType::Albedo);
    const char *reflName = "reflectance";
    if (!refl) {
        refl = GetSpectrumTextureOrNull(ctx, p, "color", SpectrumType::Albedo);
        reflName = "color";
    }
    std::optional<FloatTexture> eu = GetFloatTextureOrNull(ctx, p, "eumelanin");
    std::optional<FloatTexture> pheo = GetFloatTextureOrNull(ctx, p, "pheomelanin");
    auto ignore = [&](bool given, const std::string &name, const std::string &winner) {
        if (given)
            ctx.diag.Warning(ParamLoc(p, name, loc), owner + ": ignoring " + Quoted(name) + " since " + Quoted(winner) +
                                                         " was provided");
    };
    if (sigmaA) {
        m.hairColor = HairColor::SigmaA;
        m.hairSigmaA = *sigmaA;
        ignore(bool(refl), reflName, "sigma_a");
        ignore(bool(eu), "eumelanin", "sigma_a");
        ignore(bool(pheo), "pheomelanin", "sigma_a");
    } else if (refl) {
        m.hairColor = HairColor::Reflectance;
        m.reflectance = *refl;
        ignore(bool(eu), "eumelanin", reflName);
        ignore(bool(pheo), "pheomelanin", reflName);
    } else {
        // pbrt-v4's default is the constant sigma_a of eumelanin 1.3, pheomelanin 0: the same.
        m.hairColor = HairColor::Melanin;
        bool none = !eu && !pheo;
        m.eumelanin = eu ? *eu : GetFloatTexture(ctx, p, "eumelanin", none ? 1.3f : 0.f);
        m.pheomelanin = pheo ? *pheo : GetFloatTexture(ctx, p, "pheomelanin", 0.f);
    }
    m.hairEta = GetFloatTexture(ctx, p, "eta", 1.55f);
    m.betaM = GetFloatTexture(ctx, p, "beta_m", 0.3f);
    m.betaN = GetFloatTexture(ctx, p, "beta_n", 0.3f);
    m.hairAlpha = GetFloatTexture(ctx, p, "alpha", 2.f);
}

// pbrt-v4's MeasuredMaterial::Create: "filename", an RGL tensor file (Dupuy & Jakob 2018), read
// once per path; a missing, malformed or truncated file is an error at the parameter.
void ReadMeasured(BuildContext &ctx, const ParameterDictionary &p, Material &m, const FileLoc &loc,
                  const std::string &owner) {
    std::string filename = p.GetOneString("filename", "");
    FileLoc at = ParamLoc(p, "filename", loc);
    if (filename.empty()) Fail(at, owner + ": the measured material needs a \"string filename\" (an RGL .bsdf file)");
    std::string path = ResolveScenePath(ctx, "", filename);
    if (auto it = ctx.measuredCache.find(path); it != ctx.measuredCache.end()) {
        m.measured = it->second;
        return;
    }
    ctx.scene.inputFiles.push_back(path);
    try {
        m.measured = BuildMeasuredBRDF(ReadTensorFile(path), path, ctx.scene.measuredData);
    } catch (const MeasuredFileError &e) {
        Fail(at, owner + ": " + e.what());
    }
    ctx.measuredCache[path] = m.measured;
}

// A mix's child: a named material, built now if it is not yet (MakeNamedMaterial order does
// not matter); not "interface" (pbrt-v4 refuses it), not the mix itself.
uint32_t MixChild(BuildContext &ctx, const std::string &name, const FileLoc &at, const std::string &owner) {
    auto built = ctx.namedMaterials.find(name);
    uint32_t index;
    if (built != ctx.namedMaterials.end()) {
        index = built->second;
    } else {
        auto it = ctx.desc.namedMaterials.find(name);
        if (it == ctx.desc.namedMaterials.end()) Fail(at, owner + ": named material " + Quoted(name) + " not found");
        if (ctx.namedMaterialsBuilding.count(name))
            Fail(at, owner + ": named material " + Quoted(name) + " contains itself (a cycle of mix materials)");
        index = CreateNamedMaterial(ctx, name, it->second);
    }
    if (index == NoIndex)
        Fail(at, owner + ": " + Quoted(name) + ": an \"interface\" material cannot be used as an element of the \"mix\" material");
    return index;
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
        ReadConductorIndex(ctx, p, m, "eta", "k", "conductor", loc);
        ReadRoughness(ctx, p, m);
    } else if (type == "coatedconductor") {
        m.kind = MaterialKind::CoatedConductor;
        ReadRoughness(ctx, p, &m.uRoughness, &m.vRoughness, "interface.");
        m.thickness = GetFloatTexture(ctx, p, "thickness", 0.01f);
        ReadEta(ctx, p, m, "interface.eta");
        ReadRoughness(ctx, p, &m.conductorURoughness, &m.conductorVRoughness, "conductor.");
        ReadConductorIndex(ctx, p, m, "conductor.eta", "conductor.k", "coated conductor", loc);
        m.maxDepth = p.GetOneInt("maxdepth", 10);
        m.nSamples = p.GetOneInt("nsamples", 1);
        m.g = GetFloatTexture(ctx, p, "g", 0);
        m.albedo = GetSpectrumTexture(ctx, p, "albedo", SpectrumType::Albedo, Spectrum::Const(0));
        m.remapRoughness = p.GetOneBool("remaproughness", true);
    } else if (type == "diffusetransmission") {
        m.kind = MaterialKind::DiffuseTransmission;
        m.reflectance = GetSpectrumTexture(ctx, p, "reflectance", SpectrumType::Albedo, Spectrum::Const(0.25f));
        m.transmittance = GetSpectrumTexture(ctx, p, "transmittance", SpectrumType::Albedo, Spectrum::Const(0.25f));
        m.scale = Float(p.GetOneFloat("scale", 1));
    } else if (type == "mix") {
        m.kind = MaterialKind::Mix;
        std::vector<std::string> names = p.GetStringArray("materials");
        FileLoc at = ParamLoc(p, "materials", loc);
        if (names.size() != 2)
            Fail(at, owner + ": must provide two values for \"string materials\" for the mix material (got " +
                         std::to_string(names.size()) + ")");
        for (int i = 0; i < 2; ++i) m.mixMaterials[i] = MixChild(ctx, names[i], at, owner);
        m.amount = GetFloatTexture(ctx, p, "amount", 0.5f);
    } else if (type == "dielectric") {
        m.kind = MaterialKind::Dielectric;
        ReadEta(ctx, p, m);
        ReadRoughness(ctx, p, m);
    } else if (type == "thindielectric") {
        m.kind = MaterialKind::ThinDielectric;
        ReadEta(ctx, p, m);
    } else if (type == "measured") {
        m.kind = MaterialKind::Measured;
        ReadMeasured(ctx, p, m, loc, owner);
    } else if (type == "coateddiffuse") {
        m.kind = MaterialKind::CoatedDiffuse;
        m.reflectance = GetSpectrumTexture(ctx, p, "reflectance", SpectrumType::Albedo, Spectrum::Const(0.5f));
        ReadRoughness(ctx, p, m);
        m.thickness = GetFloatTexture(ctx, p, "thickness", 0.01f);
        ReadEta(ctx, p, m);
        m.maxDepth = p.GetOneInt("maxdepth", 10);
        m.nSamples = p.GetOneInt("nsamples", 1);
        m.g = GetFloatTexture(ctx, p, "g", 0);
        m.albedo = GetSpectrumTexture(ctx, p, "albedo", SpectrumType::Albedo, Spectrum::Const(0));
    } else if (type == "hair") {
        m.kind = MaterialKind::Hair;
        ReadHair(ctx, p, m, loc, owner);
    } else {
        Fail(loc, "unknown material type " + Quoted(type));
    }
    // pbrt-v4 reads "displacement" and "normalmap" for every material and the mix and hair
    // ignore them: here they are reported unused.
    if (m.kind != MaterialKind::Mix && m.kind != MaterialKind::Hair) {
        if (p.Has("displacement")) m.displacement = GetFloatTextureNode(ctx, p, "displacement", 0);
        std::string normalMap = p.GetOneString("normalmap", "");
        if (!normalMap.empty()) {
            FileLoc at = ParamLoc(p, "normalmap", loc);
            // Linear encoding, as pbrt-v4 (ColorEncoding::Linear): 8-bit PNG values / 255.
            LoadedImage img = LoadImage(ctx, ResolveScenePath(ctx, "", normalMap), true, at);
            if (img.channels < 3) Fail(at, Quoted(normalMap) + ": normal map image must contain R, G, and B channels");
            m.normalMap = AddImageData(ctx, img, WrapMode::Repeat);
        }
    }
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

namespace {

uint32_t CreateNamedMaterial(BuildContext &ctx, const std::string &name, const SceneEntity &e) {
    std::string type = e.params.GetOneString("type", "");
    if (!e.params.Has("type"))
        Fail(e.loc, "named material " + Quoted(name) + ": \"string type\" not provided in its parameters");
    ctx.namedMaterialTypes[name] = type;
    ctx.namedMaterialsBuilding.insert(name);
    // An unsupported material is collected and replaced by the default one, so that the
    // shapes using it are still checked.
    uint32_t m = NoIndex;
    if (!ctx.Collect([&] { m = CreateMaterial(ctx, type, e.params, e.loc, "MakeNamedMaterial " + Quoted(name)); }))
        m = DefaultMaterial(ctx);
    ctx.namedMaterialsBuilding.erase(name);
    ctx.namedMaterials[name] = m;
    return m;
}

}  // namespace

void BuildMaterials(BuildContext &ctx) {
    // Named materials first (pbrt-v4's CreateMaterials order; a mix builds its children first),
    // then the anonymous ones.
    for (const auto &named : ctx.desc.namedMaterials)
        if (!ctx.namedMaterials.count(named.first)) CreateNamedMaterial(ctx, named.first, named.second);
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
