// Lucerna scene builder internals: the state shared by builder.cpp and build_*.cpp while one
// SceneDescription is interpreted (host only; not part of the public API).
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "lucerna/scene/builder.h"

namespace lu::build {

// ---- Errors ----

[[noreturn]] inline void Fail(const FileLoc &loc, const std::string &message) { throw SceneError(loc, message); }
// An unsupported feature: the builder collects these (BuildContext::Collect) and goes on, so that
// one error lists every unsupported feature of the scene.
class UnsupportedError : public SceneError {
  public:
    using SceneError::SceneError;
};
// Unsupported feature that would change the picture: an error naming it.
[[noreturn]] inline void FailUnsupported(const FileLoc &loc, const std::string &feature, const std::string &why = "") {
    throw UnsupportedError(loc, feature + " is not supported" + (why.empty() ? std::string() : " (" + why + ")"));
}
// Location of a parameter (without marking it used), or `fallback` when absent.
inline FileLoc ParamLoc(const ParameterDictionary &params, const std::string &name, const FileLoc &fallback) {
    for (const ParsedParameter &p : params.All())
        if (p.name == name) return p.loc;
    return fallback;
}
inline std::string Quoted(const std::string &s) { return "\"" + s + "\""; }

// ---- Transforms (host) ----

inline Transform MakeTransform(const Matrix4 &m) {
    Matrix4 inv;
    if (!Inverse(m, &inv)) inv = Matrix4();
    return Transform(m, inv);
}
inline Transform TranslateTransform(const Vec3f &d) {
    Matrix4 m;
    m.m[0][3] = d.x; m.m[1][3] = d.y; m.m[2][3] = d.z;
    Matrix4 mi;
    mi.m[0][3] = -d.x; mi.m[1][3] = -d.y; mi.m[2][3] = -d.z;
    return Transform(m, mi);
}
// The transform whose upper 3x3 has columns x, y, z (maps local axes to these vectors).
inline Transform FromColumns(const Vec3f &x, const Vec3f &y, const Vec3f &z) {
    Matrix4 m;
    for (int r = 0; r < 3; ++r) { m.m[r][0] = x[r]; m.m[r][1] = y[r]; m.m[r][2] = z[r]; }
    return MakeTransform(m);
}
// True when the transform scales lengths (pbrt-v4's Transform::HasScale, tolerance 1e-3).
inline bool HasScale(const Transform &t) {
    for (int i = 0; i < 3; ++i) {
        Vec3f e(i == 0, i == 1, i == 2);
        Float l2 = LengthSquared(t.ApplyVector(e));
        if (l2 < 0.999f || l2 > 1.001f) return true;
    }
    return false;
}

// ---- Per-build state ----

struct ImageKey {
    std::string path;
    bool linear = false;
    bool operator<(const ImageKey &o) const { return std::tie(path, linear) < std::tie(o.path, o.linear); }
};
struct LoadedImage {
    uint32_t width = 0, height = 0, channels = 0;
    uint64_t offset = 0;
    uint8_t colorSpace = 0;  // ColorSpaceId of the file's RGB: EXR chromaticities, else sRGB (pbrt-v4)
};

struct AreaLightParams {
    Spectrum L;
    Float scale = 1;      // "scale" / SpectrumToPhotometric(L)
    Float power = -1;     // "power" (<= 0: none)
    bool twoSided = false;
    uint32_t image = NoIndex;   // "filename": the RGB image in scene.images (Light::image)
    double imageLuminance = 1;  // the image's mean luminance (the power normalization's k_e factor)
};

struct BuildContext {
    const SceneDescription &desc;
    Diagnostics &diag;
    const BuildOptions &opts;
    HostScene &scene;

    BuildContext(const SceneDescription &d, Diagnostics &g, const BuildOptions &o, HostScene &s)
        : desc(d), diag(g), opts(o), scene(s) {}

    // What the Option directives set (pbrt-v4's BasicPBRTOptions that the scene may change).
    struct {
        bool disablePixelJitter = false, disableWavelengthJitter = false;
        int seed = 0;   // the default of every sampler's "seed" (pbrt-v4's Options->seed)
    } sceneOptions;

    // Unsupported features met so far (each location and message once), in scene order.
    std::vector<SceneError> unsupportedErrors;
    // Runs f; an UnsupportedError it throws is recorded and false returned (the caller skips the
    // entity); any other error propagates.
    template <typename F>
    bool Collect(F &&f) {
        try {
            f();
            return true;
        } catch (const UnsupportedError &e) {
            for (const SceneError &seen : unsupportedErrors)
                if (seen.Message() == e.Message() && seen.Loc().ToString() == e.Loc().ToString()) return false;
            unsupportedErrors.push_back(e);
            return false;
        }
    }

    // Textures by name (the last definition wins is not allowed: redefinitions are errors).
    std::map<std::string, const TextureEntity *> floatTextures, spectrumTextures;
    std::map<ImageKey, LoadedImage> imageCache;
    std::map<std::tuple<uint64_t, int>, uint32_t> imageDataCache;
    std::map<std::string, MeasuredBRDFData> measuredCache;  // measured BRDF file -> its tables in measuredData  // (texel offset, wrap) -> images index
    // Built textures, memoized per name (and spectrum type): each entity is interpreted once.
    std::map<std::string, FloatTexture> floatTextureCache;
    std::map<std::pair<std::string, int>, SpectrumTexture> spectrumTextureCache;
    std::set<std::string> texturesBuilding;  // cycle detection
    // Named textures as children of other textures: their index in scene.floatTextures /
    // spectrumTextures (stored once per name and spectrum type).
    std::map<std::string, uint32_t> floatTextureNodes;
    std::map<std::pair<std::string, int>, uint32_t> spectrumTextureNodes;
    std::map<std::string, LoadedImage> textureImageCache;  // file, encoding, channel reduction -> texels

    // Materials: desc.materials[i] -> scene.materials index (NoIndex: interface).
    std::vector<uint32_t> anonymousMaterials;
    std::vector<std::string> anonymousMaterialTypes;
    std::map<std::string, uint32_t> namedMaterials;
    std::map<std::string, std::string> namedMaterialTypes;
    std::set<std::string> namedMaterialsBuilding;  // a mix's children are built first (cycle detection)
    uint32_t defaultMaterial = NoIndex;  // diffuse 0.5, created on first use

    // Media by name -> scene.media index.
    std::map<std::string, uint32_t> media;

    // Area light entities already interpreted (ReportUnused once each).
    std::map<int, AreaLightParams> areaLights;

    // Goniometric / IES profile tables already built: file path -> scene.images index and the
    // profile's description for `lucerna info` (build_lights.cpp).
    std::map<std::string, std::pair<uint32_t, std::string>> profileTables;

    SpectrumRegistry &Registry() { return scene.spectra; }
};

// ---- build_spectra.cpp ----

// The color space's standard illuminant (D65) as a Spectrum.
// The illuminant of color space cs (a ColorSpaceId), as a tabulated spectrum (pbrt-v4's
// colorSpace->illuminant, the default emission of lights).
Spectrum IlluminantSpectrum(BuildContext &ctx, uint8_t cs);
// A spectrum-valued parameter ("rgb", "spectrum" (pairs, named or file), "blackbody") as pbrt-v4's
// ParameterDictionary::GetOneSpectrum; nullopt when absent. Other types of that name are errors.
std::optional<Spectrum> GetSpectrum(BuildContext &ctx, const ParameterDictionary &params, const std::string &name,
                                    SpectrumType type);
// A named spectrum or a spectrum file (relative to the scene directory); SceneError at loc if neither.
Spectrum NamedOrFileSpectrum(BuildContext &ctx, const std::string &name, const FileLoc &loc);

// ---- build_textures.cpp ----

// Interprets every Texture directive (pbrt-v4 creates unused ones too, so their errors surface).
void IndexTextures(BuildContext &ctx);
// pbrt-v4's TextureParameterDictionary: a "float" / "texture" parameter as a float texture
// (nullopt when absent), and a spectrum ("rgb", "spectrum", "blackbody") / "texture" parameter as
// a spectrum texture of the given type. Texture references are built on first use.
std::optional<FloatTexture> GetFloatTextureOrNull(BuildContext &ctx, const ParameterDictionary &params,
                                                  const std::string &name);
FloatTexture GetFloatTexture(BuildContext &ctx, const ParameterDictionary &params, const std::string &name, Float def);
// The same parameter as a floatTextures index (a named texture stored once), for materials that
// keep a texture by index (displacement, textured eta).
uint32_t GetFloatTextureNode(BuildContext &ctx, const ParameterDictionary &params, const std::string &name, Float def);
std::optional<SpectrumTexture> GetSpectrumTextureOrNull(BuildContext &ctx, const ParameterDictionary &params,
                                                        const std::string &name, SpectrumType type);
SpectrumTexture GetSpectrumTexture(BuildContext &ctx, const ParameterDictionary &params, const std::string &name,
                                   SpectrumType type, const Spectrum &def);
SpectrumTexture ConstantSpectrumTexture(const Spectrum &s, SpectrumType type);

// ---- build_materials.cpp ----

void BuildMaterials(BuildContext &ctx);
// Material of a shape: scene.materials index or NoIndex (interface); *type gets the pbrt type name.
uint32_t ResolveShapeMaterial(BuildContext &ctx, const ShapeEntity &shape, std::string *type);
// pbrt-v4's default material (diffuse, reflectance 0.5), created on first use.
uint32_t DefaultMaterial(BuildContext &ctx);
// Loads an image file into scene.texels (cached); SceneError at loc on failure.
LoadedImage LoadImage(BuildContext &ctx, const std::string &path, bool pngIsLinear, const FileLoc &loc);
uint32_t AddImageData(BuildContext &ctx, const LoadedImage &img, WrapMode wrap);
std::string ResolvePath(const std::string &baseDirectory, const std::string &filename);
// pbrt-v4 resolves relative file names against the main scene file's directory; when the file
// is not there, the directory of the file that named it (Include) is tried.
std::string ResolveScenePath(BuildContext &ctx, const std::string &entityDirectory, const std::string &filename);

// ---- build_values.cpp ----

// SceneError at the offending parameter of `p` for values that would render NaN, infinity or
// negative radiance (negative roughness or thickness, eta <= 0, |g| > 1, nsamples < 1).
void CheckMaterialValues(const Material &m, const std::vector<FloatTexture> &nodes, const ParameterDictionary &p,
                         const FileLoc &loc, const std::string &owner);

// ---- build_media.cpp ----

// MakeNamedMedium entities -> scene.media (and the camera's medium).
void BuildMedia(BuildContext &ctx);
// A MediumInterface name -> scene.media index (NoIndex for ""); SceneError at loc if undefined.
uint32_t ResolveMedium(BuildContext &ctx, const std::string &name, const FileLoc &loc);

// ---- build_shapes.cpp ----

void BuildShapes(BuildContext &ctx);

// ---- build_lights.cpp ----

void BuildLights(BuildContext &ctx);
// build_collimated.cpp: LightSource "collimated" (a Lucerna extension) into l.
// *description: the beam's line for `lucerna info` (aperture, profile, spectrum, power).
void BuildCollimated(BuildContext &ctx, const LightEntity &e, Light &l, std::string *description);
// Scene bounding sphere for distant / infinite lights and the power-proportional light CDF
// (after all geometry exists).
void FinishLights(BuildContext &ctx);
// pbrt-v4's DiffuseAreaLight::Create, split in two: the parameters (parsed once per
// AreaLightSource), and the per-primitive scale (the "power" normalization uses the area of
// each emitting primitive, as pbrt-v4 creates one light per primitive).
const AreaLightParams &ParseAreaLight(BuildContext &ctx, int areaLightIndex);
Float AreaLightPrimitiveScale(const AreaLightParams &p, Float area);

}  // namespace lu::build
