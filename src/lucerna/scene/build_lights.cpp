// Lucerna scene builder: light sources (point, spot, goniometric, projection, distant, infinite,
// diffuse area with a spectrum or an image),
// after pbrt-v4's lights.cpp Create() functions: "scale" divided by SpectrumToPhotometric of the
// emission, "power" / "illuminance" normalizations, IES profiles, the power-proportional light sampler.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "lucerna/lights/equal_area.h"
#include "lucerna/lights/shape_sampling.h"
#include "lucerna/scene/build_internal.h"
#include "lucerna/scene/ies.h"
#include "lucerna/scene/light_build.h"

namespace lu::build {

// ---- Parameter checks ----

namespace {

// "scale": any finite value >= 0 (0 turns the light off). A negative one would emit negative
// radiance, which the film rejects sample by sample: the light would vanish without a word.
Float GetScale(const ParameterDictionary &p, const FileLoc &loc, const std::string &owner) {
    double scale = p.GetOneFloat("scale", 1);
    if (!(scale >= 0)) Fail(ParamLoc(p, "scale", loc), owner + ": \"scale\" must not be negative (got " + FormatNumber(scale) + ")");
    return Float(scale);
}

// "power" / "illuminance": absent (-1) or positive. pbrt-v4 silently ignores a value <= 0 and
// renders the light at its unnormalized "scale"; Lucerna refuses it.
Float GetPhotometric(const ParameterDictionary &p, const std::string &name, const FileLoc &loc, const std::string &owner) {
    if (!p.Has(name)) return -1;
    double v = p.GetOneFloat(name, -1);
    if (!(v > 0))
        Fail(ParamLoc(p, name, loc), owner + ": " + Quoted(name) + " must be positive (got " + FormatNumber(v) +
                                         "; use \"scale\" 0 to turn a light off)");
    return Float(v);
}

bool IsFiniteMatrix(const Matrix4 &m) {
    for (const auto &row : m.m)
        for (Float x : row)
            if (!std::isfinite(x)) return false;
    return true;
}
bool IsFinite3(const Vec3f &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The color space's LuminanceVector: Y of each primary.
void LuminanceVector(Float lum[3], uint32_t colorSpace) {
    const RGBColorSpace &cs = GetRGBColorSpace(ColorSpaceId(colorSpace));
    for (int c = 0; c < 3; ++c) lum[c] = cs.ToXYZ(RGB{Float(c == 0), Float(c == 1), Float(c == 2)})[1];
}

// The RGB image named by string parameter "filename" of an image light (pbrt-v4 refuses images
// without R, G and B; LoadImage refuses NaN and infinite texels), at that parameter's location.
LoadedImage LoadLightImage(BuildContext &ctx, const ParameterDictionary &p, const FileLoc &loc, const std::string &owner) {
    std::string filename = p.GetOneString("filename", "");
    FileLoc at = ParamLoc(p, "filename", loc);
    LoadedImage img = LoadImage(ctx, ResolvePath(ctx.desc.baseDirectory, filename), false, at);
    if (img.channels < 3)
        Fail(at, Quoted(filename) + ": image provided to " + owner + " must have R, G, and B channels");
    return img;
}

}  // namespace

// ---- Area lights ----

const AreaLightParams &ParseAreaLight(BuildContext &ctx, int index) {
    if (auto it = ctx.areaLights.find(index); it != ctx.areaLights.end()) return it->second;
    const SceneEntity &e = ctx.desc.areaLights[size_t(index)];
    if (e.name != "diffuse") Fail(e.loc, "unknown area light type " + Quoted(e.name));
    const ParameterDictionary &p = e.params;
    AreaLightParams a;
    std::optional<Spectrum> L = GetSpectrum(ctx, p, "L", SpectrumType::Illuminant);
    Float scale = GetScale(p, e.loc, "AreaLightSource " + Quoted(e.name));
    a.twoSided = p.GetOneBool("twosided", false);
    a.L = L ? *L : IlluminantSpectrum(ctx, e.colorSpace);
    if (p.Has("filename")) {
        // pbrt-v4: the image's RGB as illuminant spectra; scaled as the color space's illuminant.
        if (L) Fail(ParamLoc(p, "filename", e.loc), "both \"L\" and \"filename\" specified for AreaLightSource \"diffuse\"");
        if (p.GetOneString("filename", "").empty())
            Fail(ParamLoc(p, "filename", e.loc), "AreaLightSource \"diffuse\": \"filename\" is empty");
        LoadedImage img = LoadLightImage(ctx, p, e.loc, "AreaLightSource \"diffuse\"");
        Float lum[3];
        LuminanceVector(lum, img.colorSpace);
        const Float *t = ctx.scene.texels.data() + img.offset;
        double sum = 0;
        for (size_t i = 0; i < size_t(img.width) * img.height; ++i)
            for (int c = 0; c < 3; ++c) sum += double(t[i * img.channels + c]) * lum[c];
        a.imageLuminance = sum / (double(img.width) * img.height);
        a.image = AddImageData(ctx, img, WrapMode::Clamp);
        a.L = IlluminantSpectrum(ctx, img.colorSpace);   // the image file's color space (pbrt-v4)
    }
    // Scale so that the radiance is equivalent to 1 nit.
    Float photometric = ctx.Registry().ToPhotometric(a.L);
    a.scale = photometric > 0 ? scale / photometric : scale;
    a.power = GetPhotometric(p, "power", e.loc, "AreaLightSource " + Quoted(e.name));
    if (a.power > 0 && a.image != NoIndex && !(a.imageLuminance > 0))
        Fail(ParamLoc(p, "power", e.loc), "AreaLightSource \"diffuse\": \"power\" cannot be met: the image's luminance is zero");
    p.ReportUnused(ctx.diag, "AreaLightSource " + Quoted(e.name));
    return ctx.areaLights[index] = a;
}

Float AreaLightPrimitiveScale(const AreaLightParams &a, Float area) {
    Float scale = a.scale;
    if (a.power > 0) {
        // pbrt-v4: k_e = (twoSided ? 2 : 1) * area * pi (the spectrum is already photometrically
        // normalized; an RGB's own luminance is not accounted for), times an image's mean luminance.
        Float k_e = Float((a.twoSided ? 2 : 1) * area * Pi * a.imageLuminance);
        if (k_e > 0) scale *= a.power / k_e;
    }
    return scale;
}

// ---- LightSource ----

namespace {

Float Photometric(BuildContext &ctx, const Spectrum &s) {
    Float v = ctx.Registry().ToPhotometric(s);
    return v > 0 ? v : 1;
}

std::string LightPath(BuildContext &ctx, const std::string &filename) {
    return ResolvePath(ctx.desc.baseDirectory, filename);
}

void BuildInfinite(BuildContext &ctx, const LightEntity &e, Light &l) {
    const ParameterDictionary &p = e.params;
    std::optional<Spectrum> L = GetSpectrum(ctx, p, "L", SpectrumType::Illuminant);
    Float scale = GetScale(p, e.loc, "LightSource \"infinite\"");
    std::vector<Vec3f> portal = p.GetPoint3fArray("portal");
    std::string filename = p.GetOneString("filename", "");
    Float E_v = GetPhotometric(p, "illuminance", e.loc, "LightSource \"infinite\"");
    if (!portal.empty()) FailUnsupported(ParamLoc(p, "portal", e.loc), "infinite light \"portal\"");
    l.renderFromLight = e.renderFromObject;
    if (filename.empty()) {
        // Uniform: "L", or the color space's illuminant.
        l.kind = LightKind::UniformInfinite;
        l.spectrum = L ? *L : IlluminantSpectrum(ctx, e.colorSpace);
        l.scale = scale / Photometric(ctx, l.spectrum);
        if (E_v > 0) l.scale *= E_v / Pi;  // illuminance of uniform emission on an upward-facing patch
        return;
    }
    if (L) Fail(e.loc, "can't specify both emission \"L\" and \"filename\" with an infinite light");
    std::string path = LightPath(ctx, filename);
    LoadedImage img = LoadImage(ctx, path, false, ParamLoc(p, "filename", e.loc));
    if (img.channels < 3)
        Fail(ParamLoc(p, "filename", e.loc), Quoted(filename) + ": image provided to \"infinite\" light must have R, G, and B channels");
    if (img.width != img.height)
        Fail(ParamLoc(p, "filename", e.loc), Quoted(filename) + ": image resolution (" + std::to_string(img.width) + ", " +
                                                 std::to_string(img.height) + ") is non-square; it is unlikely to be an "
                                                                              "equal-area environment map");
    if (!IsFiniteMatrix(e.renderFromObject.mInv))
        Fail(e.loc, "the transformation of this \"infinite\" light is not invertible: its directions are undefined");
    l.kind = LightKind::ImageInfinite;
    l.spectrum = IlluminantSpectrum(ctx, img.colorSpace);  // the image file's color space (pbrt-v4)
    l.scale = scale / Photometric(ctx, l.spectrum);
    const Float *texels = ctx.scene.texels.data() + img.offset;
    if (E_v > 0) {
        // pbrt-v4: upper-hemisphere illuminance of the map (its color space's luminance weights), times 2 pi / N.
        Float lum[3];  // the color space's LuminanceVector: Y of each primary
        const RGBColorSpace &imgSpace = GetRGBColorSpace(ColorSpaceId(img.colorSpace));
        for (int c = 0; c < 3; ++c) lum[c] = imgSpace.ToXYZ(RGB{Float(c == 0), Float(c == 1), Float(c == 2)})[1];
        double illuminance = 0;
        for (uint32_t y = 0; y < img.height; ++y) {
            Float v = (Float(y) + 0.5f) / Float(img.height);
            for (uint32_t x = 0; x < img.width; ++x) {
                Float u = (Float(x) + 0.5f) / Float(img.width);
                Vec3f w = EqualAreaSquareToSphere(Vec2f(u, v));
                if (w.z <= 0) continue;
                const Float *t = texels + (size_t(y) * img.width + x) * img.channels;
                for (int c = 0; c < 3; ++c) illuminance += double(t[c]) * lum[c] * w.z;
            }
        }
        illuminance *= 2 * Pi / (double(img.width) * img.height);
        if (illuminance > 0) l.scale *= Float(E_v / illuminance);
    }
    l.image = AddImageData(ctx, img, WrapMode::Clamp);  // lookups wrap octahedrally (lights/lights.h)
    l.distribution = BuildImageInfiniteDistributions(texels, int(img.width), int(img.height), int(img.channels),
                                                     ctx.scene.distributions2D, ctx.scene.distData);
}

// ---- Goniometric lights and IES profiles ----

// Equal-area vertex tables of IES files: (n+1)^2 samples, cells of about 0.4 degrees.
constexpr int kIESTableResolution = 512;

// pbrt-v4's swapYZ: the goniometric light's image frame has its pole (+z) along the light's +y.
Transform SwapYZ() { return FromColumns(Vec3f(1, 0, 0), Vec3f(0, 0, 1), Vec3f(0, 1, 0)); }

bool IsIESFile(const std::string &filename) {
    std::string ext = std::filesystem::path(filename).extension().string();
    for (char &c : ext) c = char(std::tolower((unsigned char)c));
    return ext == ".ies";
}

// Appends a one-channel n x n table to the scene's texels and returns its images index.
uint32_t AddProfileTable(BuildContext &ctx, const std::vector<float> &values, uint32_t n) {
    LoadedImage li;
    li.width = li.height = n;
    li.channels = 1;
    li.offset = ctx.scene.texels.size();
    ctx.scene.texels.insert(ctx.scene.texels.end(), values.begin(), values.end());
    return AddImageData(ctx, li, WrapMode::Clamp);  // lookups clamp or wrap octahedrally (lights.h)
}

// The profile table of the IES file named by string parameter `param` of e (cached per file and
// tilt); *description: the line for `lucerna info`. "float iestilt" (degrees) applies the file's
// tilt factor at that tilt (docs/lights.md); it is an error for a file without tilt data or
// outside the file's tilt angles.
uint32_t IESProfileTable(BuildContext &ctx, const LightEntity &e, const std::string &param, std::string *description) {
    const ParameterDictionary &p = e.params;
    std::string filename = p.GetOneString(param, "");
    FileLoc loc = ParamLoc(p, param, e.loc);
    if (filename.empty()) Fail(loc, "LightSource " + Quoted(e.name) + ": " + Quoted(param) + " is empty");
    const bool tilted = p.Has("iestilt");
    const double tilt = p.GetOneFloat("iestilt", 0);
    std::string path = LightPath(ctx, filename), key = path;
    if (tilted) {
        char buf[40];
        std::snprintf(buf, sizeof(buf), "\ntilt %.17g", tilt);
        key += buf;
    }
    if (auto it = ctx.profileTables.find(key); it != ctx.profileTables.end()) {
        *description = it->second.second;
        return it->second.first;
    }
    ctx.scene.inputFiles.push_back(path);
    IESProfile prof = ReadIES(path, loc, "the IES file of LightSource " + Quoted(e.name) + " at " + loc.ToString());
    if (!prof.tiltFile.empty()) ctx.scene.inputFiles.push_back(prof.tiltFile);
    if (tilted) {
        FileLoc tiltLoc = ParamLoc(p, "iestilt", e.loc);
        double factor;
        if (prof.tiltAngles.empty())
            Fail(tiltLoc, "LightSource " + Quoted(e.name) + ": \"iestilt\" is meaningless: " + Quoted(filename) +
                              " has TILT=NONE (no tilt data)");
        if (!prof.TiltFactorAt(tilt, &factor))
            Fail(tiltLoc, "LightSource " + Quoted(e.name) + ": \"iestilt\" " + FormatNumber(tilt) + " is outside the tilt angles of " +
                              Quoted(filename) + " (" + FormatNumber(prof.tiltAngles.front()) + "-" +
                              FormatNumber(prof.tiltAngles.back()) + " degrees; LM-63 gives no factor beyond them)");
        prof.SetTilt(tilt);
    }
    std::vector<float> table = IESEqualAreaTable(prof, kIESTableResolution);
    uint32_t index = AddProfileTable(ctx, table, kIESTableResolution + 1);
    *description = Quoted(filename) + ": " + prof.Describe();
    ctx.profileTables[key] = {index, *description};
    return index;
}

// The profile table of an equal-area image as pbrt-v4's GoniometricLight::Create makes it: square,
// RGB averaged per texel (or the one channel Y); no negative values (they would emit negative light).
uint32_t ImageProfileTable(BuildContext &ctx, const LightEntity &e, const std::string &filename, std::string *description) {
    const ParameterDictionary &p = e.params;
    FileLoc loc = ParamLoc(p, "filename", e.loc);
    std::string path = LightPath(ctx, filename);
    if (auto it = ctx.profileTables.find(path); it != ctx.profileTables.end()) {
        *description = it->second.second;
        return it->second.first;
    }
    LoadedImage img = LoadImage(ctx, path, false, loc);
    if (img.width != img.height)
        Fail(loc, Quoted(filename) + ": image resolution (" + std::to_string(img.width) + ", " + std::to_string(img.height) +
                      ") is non-square; it is unlikely to be an equal-area map");
    std::vector<float> table(size_t(img.width) * img.height);
    const Float *t = ctx.scene.texels.data() + img.offset;
    double peak = 0;
    for (size_t i = 0; i < table.size(); ++i) {
        const Float *px = t + i * img.channels;
        float v = img.channels >= 3 ? (px[0] + px[1] + px[2]) / 3 : px[0];
        if (v < 0)
            Fail(loc, Quoted(filename) + ": negative value " + FormatNumber(v) + " at pixel (" + std::to_string(i % img.width) +
                          ", " + std::to_string(i / img.width) + "); a goniometric light cannot emit negative intensity");
        table[i] = v;
        peak = std::max(peak, double(v));
    }
    uint32_t index = AddProfileTable(ctx, table, img.width);
    *description = Quoted(filename) + ": " + std::to_string(img.width) + " x " + std::to_string(img.height) +
                   " equal-area image (" + (img.channels >= 3 ? "RGB averaged" : "Y") + "), peak " + FormatNumber(peak);
    ctx.profileTables[path] = {index, *description};
    return index;
}

// "power" for a light with profile table `profile`: k_e = the integral of the table over the sphere.
void NormalizeProfilePower(BuildContext &ctx, const ParameterDictionary &p, const FileLoc &loc, const std::string &owner,
                           Float phi_v, double k_e, Light &l) {
    (void)ctx;
    if (!(phi_v > 0)) return;
    if (!(k_e > 0)) Fail(ParamLoc(p, "power", loc), owner + ": \"power\" cannot be met: the intensity profile is zero everywhere");
    l.scale *= Float(phi_v / k_e);
}

// LightSource "goniometric" (pbrt-v4's GoniometricLight::Create; "filename" may also be an IES file).
void BuildGoniometric(BuildContext &ctx, const LightEntity &e, Light &l, std::string *description) {
    const ParameterDictionary &p = e.params;
    const std::string owner = "LightSource \"goniometric\"";
    std::optional<Spectrum> I = GetSpectrum(ctx, p, "I", SpectrumType::Illuminant);
    Float scale = GetScale(p, e.loc, owner);
    Float phi_v = GetPhotometric(p, "power", e.loc, owner);
    std::string filename = p.GetOneString("filename", "");
    // pbrt-v4 warns and renders an empty image; Lucerna refuses.
    if (filename.empty())
        Fail(e.loc, owner + ": \"string filename\" must name an equal-area image or an IES file (.ies)");
    if (!IsFiniteMatrix(e.renderFromObject.mInv))
        Fail(e.loc, owner + ": the transformation is not invertible: the light's directions are undefined");
    l.kind = LightKind::Goniometric;
    l.spectrum = I ? *I : IlluminantSpectrum(ctx, e.colorSpace);
    l.scale = scale / Photometric(ctx, l.spectrum);
    if (IsIESFile(filename)) {
        l.profile = IESProfileTable(ctx, e, "filename", description);
        l.profileVertices = true;
    } else {
        l.profile = ImageProfileTable(ctx, e, filename, description);
    }
    NormalizeProfilePower(ctx, p, e.loc, owner, phi_v,
                          ProfileIntegral(ctx.scene.images[l.profile], ctx.scene.texels.data(), l.profileVertices), l);
    l.renderFromLight = e.renderFromObject * SwapYZ();
    l.position = l.renderFromLight.ApplyPoint(Vec3f(0, 0, 0));
}

// LightSource "projection" (pbrt-v4's ProjectionLight::Create): the image "filename" projected from
// the origin down +z through a perspective frustum of "fov" degrees across the image's shorter
// side; +y of the CTM's space is the image's top (pbrt-v4 flips y).
void BuildProjection(BuildContext &ctx, const LightEntity &e, Light &l) {
    const ParameterDictionary &p = e.params;
    const std::string owner = "LightSource \"projection\"";
    Float scale = GetScale(p, e.loc, owner);
    Float phi_v = GetPhotometric(p, "power", e.loc, owner);
    double fov = p.GetOneFloat("fov", 90);
    if (!(fov > 0 && fov < 180))
        Fail(ParamLoc(p, "fov", e.loc), owner + ": \"fov\" must be in (0, 180) degrees (got " + FormatNumber(fov) + ")");
    if (p.GetOneString("filename", "").empty())
        Fail(p.Has("filename") ? ParamLoc(p, "filename", e.loc) : e.loc, "must provide \"filename\" to \"projection\" light source");
    if (!IsFiniteMatrix(e.renderFromObject.mInv))
        Fail(e.loc, owner + ": the transformation is not invertible: the light's directions are undefined");
    LoadedImage img = LoadLightImage(ctx, p, e.loc, "\"projection\" light");
    l.kind = LightKind::Projection;
    l.spectrum = IlluminantSpectrum(ctx, img.colorSpace);  // the image file's color space (pbrt-v4)
    l.scale = scale / Photometric(ctx, l.spectrum);
    l.image = AddImageData(ctx, img, WrapMode::Clamp);
    Float aspect = Float(img.width) / Float(img.height);
    l.projectionScreen = aspect > 1 ? Vec2f(aspect, 1) : Vec2f(1, 1 / aspect);
    l.projectionTan = Float(std::tan(Radians(Float(fov)) / 2));
    if (phi_v > 0) {
        // pbrt-v4: k_e = the image's luminance integrated over the solid angle of its texels.
        Float lum[3];
        LuminanceVector(lum, img.colorSpace);
        const ImageData &im = ctx.scene.images[l.image];
        const Float *t = ctx.scene.texels.data() + img.offset;
        double k_e = 0;
        for (uint32_t y = 0; y < img.height; ++y)
            for (uint32_t x = 0; x < img.width; ++x) {
                const Float *px = t + (size_t(y) * img.width + x) * img.channels;
                k_e += (px[0] * lum[0] + px[1] * lum[1] + px[2] * lum[2]) * ProjectionTexelSolidAngle(l, im, x, y);
            }
        if (!(k_e > 0)) Fail(ParamLoc(p, "power", e.loc), owner + ": \"power\" cannot be met: the image's luminance is zero");
        l.scale *= Float(phi_v / k_e);
    }
    l.renderFromLight = e.renderFromObject * FromColumns(Vec3f(1, 0, 0), Vec3f(0, -1, 0), Vec3f(0, 0, 1));
    l.position = l.renderFromLight.ApplyPoint(Vec3f(0, 0, 0));
}

}  // namespace

void BuildLights(BuildContext &ctx) {
    HostScene &s = ctx.scene;
    for (const LightEntity &e : ctx.desc.lights) ctx.Collect([&] {
        // The light's medium matters only to light paths (pbrt-v4's bdpt); checked, not used.
        (void)ResolveMedium(ctx, e.outsideMedium, e.loc);
        const ParameterDictionary &p = e.params;
        const Transform &ctm = e.renderFromObject;
        const std::string owner = "LightSource " + Quoted(e.name);
        Light l;
        std::string profile;  // the intensity profile's description, for `lucerna info`
        if (e.name == "point") {
            std::optional<Spectrum> I = GetSpectrum(ctx, p, "I", SpectrumType::Illuminant);
            l.kind = LightKind::Point;
            l.spectrum = I ? *I : IlluminantSpectrum(ctx, e.colorSpace);
            l.scale = GetScale(p, e.loc, owner) / Photometric(ctx, l.spectrum);
            Float phi_v = GetPhotometric(p, "power", e.loc, owner);
            Vec3f from = p.GetOnePoint3f("from").value_or(Vec3f(0, 0, 0));
            if (p.Has("iesfile")) {
                // Lucerna's extension: a point light with an IES profile is the goniometric light
                // of that file at "from" (docs/lights.md).
                l.kind = LightKind::Goniometric;
                l.profile = IESProfileTable(ctx, e, "iesfile", &profile);
                l.profileVertices = true;
                NormalizeProfilePower(ctx, p, e.loc, owner, phi_v,
                                      ProfileIntegral(s.images[l.profile], s.texels.data(), true), l);
                if (!IsFiniteMatrix(ctm.mInv))
                    Fail(e.loc, owner + ": the transformation is not invertible: the profile's directions are undefined");
                l.renderFromLight = ctm * TranslateTransform(from) * SwapYZ();
            } else {
                if (phi_v > 0) l.scale *= phi_v / (4 * Pi);
                l.renderFromLight = ctm * TranslateTransform(from);
            }
            l.position = l.renderFromLight.ApplyPoint(Vec3f(0, 0, 0));
        } else if (e.name == "spot") {
            std::optional<Spectrum> I = GetSpectrum(ctx, p, "I", SpectrumType::Illuminant);
            l.kind = LightKind::Spot;
            l.spectrum = I ? *I : IlluminantSpectrum(ctx, e.colorSpace);
            Float scale = GetScale(p, e.loc, owner);
            Float coneAngle = Float(p.GetOneFloat("coneangle", 30));
            Float coneDelta = Float(p.GetOneFloat("conedeltaangle", 5));
            if (!(coneAngle > 0 && coneAngle <= 180))
                Fail(ParamLoc(p, "coneangle", e.loc), "spot light: \"coneangle\" must be in (0, 180] degrees (got " + FormatNumber(coneAngle) + ")");
            if (!(coneDelta >= 0 && coneDelta <= coneAngle))
                Fail(ParamLoc(p, "conedeltaangle", e.loc), "spot light: \"conedeltaangle\" must be in [0, coneangle] (got " +
                                                               FormatNumber(coneDelta) + ")");
            Vec3f from = p.GetOnePoint3f("from").value_or(Vec3f(0, 0, 0));
            Vec3f to = p.GetOnePoint3f("to").value_or(Vec3f(0, 0, 1));
            if (!(LengthSquared(to - from) > 0)) Fail(e.loc, "spot light: \"from\" and \"to\" must differ");
            Frame f = Frame::FromZ(Normalize(to - from));
            l.renderFromLight = ctm * TranslateTransform(from) * FromColumns(f.x, f.y, f.z);
            l.position = l.renderFromLight.ApplyPoint(Vec3f(0, 0, 0));
            l.direction = Normalize(l.renderFromLight.ApplyVector(Vec3f(0, 0, 1)));
            l.cosFalloffEnd = std::cos(Radians(coneAngle));
            l.cosFalloffStart = std::cos(Radians(coneAngle - coneDelta));
            l.scale = scale / Photometric(ctx, l.spectrum);
            Float phi_v = GetPhotometric(p, "power", e.loc, owner);
            if (p.Has("iesfile")) {
                // Lucerna's extension: the IES profile times the cone falloff, nadir along the axis.
                l.profile = IESProfileTable(ctx, e, "iesfile", &profile);
                l.profileVertices = true;
                NormalizeProfilePower(ctx, p, e.loc, owner, phi_v,
                                      ProfileIntegral(s.images[l.profile], s.texels.data(), true, &l), l);
            } else if (phi_v > 0) {
                Float k_e = 2 * Pi * ((1 - l.cosFalloffStart) + (l.cosFalloffStart - l.cosFalloffEnd) / 2);
                if (k_e > 0) l.scale *= phi_v / k_e;
            }
        } else if (e.name == "distant") {
            std::optional<Spectrum> L = GetSpectrum(ctx, p, "L", SpectrumType::Illuminant);
            l.kind = LightKind::Distant;
            l.spectrum = L ? *L : IlluminantSpectrum(ctx, e.colorSpace);
            Float scale = GetScale(p, e.loc, owner);
            Vec3f from = p.GetOnePoint3f("from").value_or(Vec3f(0, 0, 0));
            Vec3f to = p.GetOnePoint3f("to").value_or(Vec3f(0, 0, 1));
            if (!(LengthSquared(from - to) > 0)) Fail(e.loc, "distant light: \"from\" and \"to\" must differ");
            Vec3f w = Normalize(from - to), v1, v2;
            CoordinateSystem(w, &v1, &v2);
            l.renderFromLight = ctm * FromColumns(v1, v2, w);
            l.direction = Normalize(l.renderFromLight.ApplyVector(Vec3f(0, 0, 1)));
            l.scale = scale / Photometric(ctx, l.spectrum);
            Float E_v = GetPhotometric(p, "illuminance", e.loc, owner);
            if (E_v > 0) l.scale *= E_v;
        } else if (e.name == "infinite") {
            BuildInfinite(ctx, e, l);
        } else if (e.name == "collimated") {
            BuildCollimated(ctx, e, l, &profile);
        } else if (e.name == "goniometric") {
            BuildGoniometric(ctx, e, l, &profile);
        } else if (e.name == "projection") {
            BuildProjection(ctx, e, l);
        } else {
            Fail(e.loc, "unknown light type " + Quoted(e.name));
        }
        // A singular or projective CTM can leave a light without a position or direction.
        if ((l.kind == LightKind::Point || l.kind == LightKind::Spot || l.kind == LightKind::Goniometric ||
             l.kind == LightKind::Projection) &&
            !IsFinite3(l.position))
            Fail(e.loc, owner + ": the transformation sends the light's position to infinity");
        if ((l.kind == LightKind::Spot || l.kind == LightKind::Distant) && !IsFinite3(l.direction))
            Fail(e.loc, owner + ": the transformation is singular and collapses the light's direction");
        p.ReportUnused(ctx.diag, owner);
        s.stats.lightsByType[e.name]++;
        if (!profile.empty())
            s.stats.lightProfiles.push_back("light " + std::to_string(s.lights.size()) + ": " + e.name + " " + profile);
        if (l.kind == LightKind::UniformInfinite || l.kind == LightKind::ImageInfinite)
            s.infiniteLights.push_back(uint32_t(s.lights.size()));
        s.SetOrigin(s.lightOrigin, s.lights.size(), owner + " at " + e.loc.ToString());
        s.lights.push_back(l);
    });
}

namespace {

// Largest distance from c to the 8 corners of the object-space box [pMin, pMax] in render space.
Float MaxCornerDistance(const Transform &t, const Vec3f &c, const Vec3f &pMin, const Vec3f &pMax) {
    Float d2 = 0;
    for (int i = 0; i < 8; ++i) {
        Vec3f p((i & 1) ? pMax.x : pMin.x, (i & 2) ? pMax.y : pMin.y, (i & 4) ? pMax.z : pMin.z);
        d2 = Max(d2, DistanceSquared(c, t.ApplyPoint(p)));
    }
    return std::sqrt(d2);
}

// Light::boundCenter/boundRadius: a sphere containing every point SampleLi returns. The
// cone-sampled sphere puts its points at the object-space radius around the center (pbrt-v4
// assumes no scale), the other branches at transformed object points: both are covered.
void LightBoundingSphere(const Light &l, const SceneView &s, Vec3f *center, Float *radius) {
    *radius = -1;
    if (l.kind == LightKind::Point || l.kind == LightKind::Spot || l.kind == LightKind::Goniometric ||
        l.kind == LightKind::Projection) {
        *center = l.position;
        *radius = 0;
        return;
    }
    if (l.kind == LightKind::Collimated) {   // the aperture (beamRadius: a rectangle's half diagonal)
        *center = l.position;
        *radius = l.beamRadius;
        return;
    }
    if (l.kind != LightKind::DiffuseArea || l.shape == NoIndex) return;
    const Shape &shape = s.shapes[l.shape];
    if (shape.kind == ShapeKind::Triangles) {
        TriangleRef t = GetTriangleRef(s, s.triangleMeshes[shape.index], l.primitive);
        *center = (t.p0 + t.p1 + t.p2) / Float(3);
        *radius = std::sqrt(Max(DistanceSquared(*center, t.p0), Max(DistanceSquared(*center, t.p1), DistanceSquared(*center, t.p2))));
    } else if (shape.kind == ShapeKind::Sphere) {
        const Sphere &sp = s.spheres[shape.index];
        Float r = sp.radius;
        *center = sp.renderFromObject.ApplyPoint(Vec3f(0, 0, 0));
        *radius = Max(r, MaxCornerDistance(sp.renderFromObject, *center, Vec3f(-r, -r, -r), Vec3f(r, r, r)));
    } else if (shape.kind == ShapeKind::Disk) {
        const Disk &dk = s.disks[shape.index];
        Float r = dk.radius;
        *center = dk.renderFromObject.ApplyPoint(Vec3f(0, 0, dk.height));
        *radius = MaxCornerDistance(dk.renderFromObject, *center, Vec3f(-r, -r, dk.height), Vec3f(r, r, dk.height));
    } else if (shape.kind == ShapeKind::Cylinder) {
        const Cylinder &cy = s.cylinders[shape.index];
        Float r = cy.radius;
        *center = cy.renderFromObject.ApplyPoint(Vec3f(0, 0, (cy.zMin + cy.zMax) / 2));
        *radius = MaxCornerDistance(cy.renderFromObject, *center, Vec3f(-r, -r, cy.zMin), Vec3f(r, r, cy.zMax));
    } else if (shape.kind == ShapeKind::BilinearPatches) {
        // The patch lies in the convex hull of its corners.
        uint32_t v[4];
        PatchVertices(s.bilinearMeshes[shape.index], s, l.primitive, v);
        PatchCorners c = PatchPositions(s, v);
        *center = (c.p00 + c.p10 + c.p01 + c.p11) / Float(4);
        *radius = std::sqrt(Max(Max(DistanceSquared(*center, c.p00), DistanceSquared(*center, c.p10)),
                                Max(DistanceSquared(*center, c.p01), DistanceSquared(*center, c.p11))));
    }
}

}  // namespace

void FinishLights(BuildContext &ctx) {
    HostScene &s = ctx.scene;
    // pbrt-v4 warns too ("No light sources defined in scene; rendering a black image").
    if (s.lights.empty()) {
        FileLoc file;
        if (!ctx.desc.filename.empty()) file.file = std::make_shared<const std::string>(ctx.desc.filename);
        bool empty = s.shapes.empty() && ctx.desc.shapes.empty() && ctx.desc.instances.empty();
        ctx.diag.Warning(file, empty ? "the scene has no shapes and no light sources; the image will be black"
                                     : "the scene has no light sources; the image will be black");
    }
    // pbrt-v4's Bounds3::BoundingSphere of the scene bounds.
    Vec3f center;
    Float radius = 0;
    if (!s.bounds.Empty()) {
        center = s.bounds.Center();
        radius = Distance(center, s.bounds.pMax);
    }
    SceneView view = s.View();
    for (Light &l : s.lights) {
        if (l.kind == LightKind::Distant || l.kind == LightKind::UniformInfinite || l.kind == LightKind::ImageInfinite ||
            l.kind == LightKind::Collimated) {   // beams: their reach in a medium (BeamRegionInterval)
            l.sceneCenter = center;
            l.sceneRadius = radius;
        }
        LightBoundingSphere(l, view, &l.boundCenter, &l.boundRadius);
    }
    s.lightCdf.clear();
    s.lightCdf = BuildLightCdf(s.View());
    // When every light has zero power the CDF is uniform (pbrt-v4); a degenerate (zero-area)
    // triangle must not be picked then: sampling it gives a NaN pdf. Meshes keep at least one
    // triangle with area (build_shapes.cpp drops the others), so some light remains.
    view = s.View();
    std::vector<double> mass(s.lights.size());
    double total = 0;
    bool changed = false;
    for (size_t i = 0; i < s.lights.size(); ++i) {
        const Light &l = s.lights[i];
        mass[i] = double(s.lightCdf[i + 1]) - double(s.lightCdf[i]);
        if (l.kind == LightKind::DiffuseArea && mass[i] > 0 && !(ShapeArea(view, view.shapes[l.shape], l.primitive) > 0)) {
            mass[i] = 0;
            changed = true;
        }
        total += mass[i];
    }
    if (changed && total > 0) {
        double run = 0;
        for (size_t i = 0; i < s.lights.size(); ++i) {
            run += mass[i];
            s.lightCdf[i + 1] = Float(run / total);
        }
        s.lightCdf.back() = 1;
    }
}

}  // namespace lu::build
