// Lucerna scene builder: rendering options (Film, Camera, PixelFilter, Sampler, Integrator) and
// the build order, after pbrt-v4's BasicScene::SetOptions and the Film / Camera / Filter /
// Sampler / Integrator Create() functions (film.cpp, cameras.cpp, filters.cpp, ...).
#include "lucerna/scene/builder.h"

#include <array>
#include <cctype>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <cmath>

#include "lucerna/scene/camera_build.h"
#include "lucerna/scene/pmj02_build.h"
#include "lucerna/scene/sampler_build.h"
#include "lucerna/scene/build_internal.h"

namespace lu {

template <typename T>
static Span<T> SpanOf(const std::vector<T> &v) {
    return Span<T>{v.data(), uint32_t(v.size())};
}

SceneView HostScene::View() const {
    SceneView v;
    v.positions = SpanOf(positions);
    v.normals = SpanOf(normals);
    v.uvs = SpanOf(uvs);
    v.indices = SpanOf(indices);
    v.triangleMeshes = SpanOf(triangleMeshes);
    v.spheres = SpanOf(spheres);
    v.disks = SpanOf(disks);
    v.cylinders = SpanOf(cylinders);
    v.bilinearMeshes = SpanOf(bilinearMeshes);
    v.curveSets = SpanOf(curveSets);
    v.curveSegments = SpanOf(curveSegments);
    v.shapes = SpanOf(shapes);
    v.prototypes = SpanOf(prototypes);
    v.instances = SpanOf(instances);
    v.materials = SpanOf(materials);
    v.lights = SpanOf(lights);
    v.lightCdf = SpanOf(lightCdf);
    v.infiniteLights = SpanOf(infiniteLights);
    v.images = SpanOf(images);
    v.texels = SpanOf(texels);
    v.floatTextures = SpanOf(floatTextures);
    v.spectrumTextures = SpanOf(spectrumTextures);
    v.distributions2D = SpanOf(distributions2D);
    v.distData = SpanOf(distData);
    v.pmjPoints = SpanOf(pmjPoints);
    v.media = SpanOf(media);
    v.mediumData = SpanOf(mediumData);
    v.measuredData = SpanOf(measuredData);
    v.walkInterfaces = walkInterfaces;
    v.spectra = spectra.Tables();
    // sRGB's table alone unless an image's RGB is in another color space (constant RGB values
    // were converted with their space's table while building).
    RGBToSpectrumTableData t = SRGBToSpectrumTable();
    const uint32_t tableSize = 3 * t.res * t.res * t.res * 3;
    v.rgbToSpecRes = t.res;
    v.rgbToSpecZNodes = Span<Float>{t.zNodes, t.res};
    v.rgbToSpecCoeffs = Span<Float>{t.coeffs, tableSize};
    bool otherSpaces = false;
    for (const ImageData &im : images) otherSpaces |= im.colorSpace != uint8_t(ColorSpaceId::SRGB);
    if (otherSpaces) {
        static const std::vector<Float> all = [&] {
            std::vector<Float> a;
            a.reserve(size_t(tableSize) * NumColorSpaces);
            for (uint32_t i = 0; i < NumColorSpaces; ++i) {
                RGBToSpectrumTableData ti = RGBToSpectrumTable(ColorSpaceId(i));
                a.insert(a.end(), ti.coeffs, ti.coeffs + tableSize);
            }
            return a;
        }();
        v.rgbToSpecCoeffs = SpanOf(all);
    }
    for (uint32_t i = 0; i < NumColorSpaces; ++i) v.illuminantTables[i] = illuminantTables[i];
    for (const Material &m : materials)
        v.transmitters += m.kind == MaterialKind::Dielectric || m.kind == MaterialKind::ThinDielectric;
    for (const Light &l : lights) {
        v.collimatedLights += l.kind == LightKind::Collimated;
        v.deltaLights += IsDeltaLight(l);
    }
    for (const Shape &sh : shapes) v.alphaShapes += sh.alpha != NoIndex;
    v.camera = camera;
    v.camera.lensElements = SpanOf(lensElements);     // the realistic camera's arrays
    v.camera.exitPupilBounds = SpanOf(exitPupilBounds);
    v.film = film;
    v.filter = filter;
    v.bounds = bounds;
    return v;
}

void HostScene::SetOrigin(std::vector<uint32_t> &list, size_t index, const std::string &what) {
    if (origins.empty() || origins.back() != what) origins.push_back(what);   // area lights: one per triangle
    if (list.size() <= index) list.resize(index + 1, NoIndex);
    list[index] = uint32_t(origins.size() - 1);
}

std::string HostScene::OriginOf(const std::vector<uint32_t> &list, uint32_t index) const {
    if (index >= list.size() || list[index] >= origins.size()) return "";
    return origins[list[index]];
}

namespace build {
namespace {

// Marks every parameter used (for directives Lucerna substitutes as a whole).
void MarkAllUsed(const ParameterDictionary &p) {
    for (const ParsedParameter &q : p.All()) q.lookedUp = true;
}

bool OneOf(const std::string &s, std::initializer_list<const char *> names) {
    for (const char *n : names)
        if (s == n) return true;
    return false;
}

// ---- White balance (pbrt-v4's PixelSensor with sensorIllum = D(T), and WhiteBalance()) ----

using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 Mul3(const Mat3 &a, const Mat3 &b) {
    Mat3 r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) r[i][j] += a[i][k] * b[k][j];
    return r;
}

Mat3 Inverse3(const Mat3 &m) {
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    Mat3 r;
    r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    return r;
}

// Chromaticity of pbrt-v4's Spectra::D(T): CIE daylight for CCT >= 4000 K (the CIE xD(T), yD(x)
// formulas), a blackbody below.
std::array<double, 2> DaylightChromaticity(BuildContext &ctx, double T) {
    double cct = T * 1.4388 / 1.4380;
    if (cct < 4000) {
        XYZ xyz = ctx.Registry().ToXYZ(ctx.Registry().Blackbody(Float(cct)));
        double sum = double(xyz[0]) + xyz[1] + xyz[2];
        return {xyz[0] / sum, xyz[1] / sum};
    }
    double x = cct <= 7000 ? -4.607e9 / (cct * cct * cct) + 2.9678e6 / (cct * cct) + 0.09911e3 / cct + 0.244063
                           : -2.0064e9 / (cct * cct * cct) + 1.9018e6 / (cct * cct) + 0.24748e3 / cct + 0.23704;
    return {x, -3 * x * x + 2.870 * x - 0.275};
}

// Bradford chromatic adaptation from white xy `src` to `dst` (pbrt-v4's WhiteBalance).
Mat3 WhiteBalance(std::array<double, 2> src, std::array<double, 2> dst) {
    const Mat3 lmsFromXYZ = {{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
    auto toXYZ = [](std::array<double, 2> xy) { return std::array<double, 3>{xy[0] / xy[1], 1.0, (1 - xy[0] - xy[1]) / xy[1]}; };
    auto apply = [](const Mat3 &m, std::array<double, 3> v) {
        return std::array<double, 3>{m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
                                     m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
                                     m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
    };
    std::array<double, 3> srcLMS = apply(lmsFromXYZ, toXYZ(src)), dstLMS = apply(lmsFromXYZ, toXYZ(dst));
    Mat3 scale{};
    for (int i = 0; i < 3; ++i) scale[i][i] = dstLMS[i] / srcLMS[i];
    return Mul3(Inverse3(lmsFromXYZ), Mul3(scale, lmsFromXYZ));
}

// ---- Film, camera, filter, sampler, integrator ----

Float ExposureTime(BuildContext &ctx) {
    const CameraEntity &c = ctx.desc.camera;
    Float open = Float(c.params.GetOneFloat("shutteropen", 0)), close = Float(c.params.GetOneFloat("shutterclose", 1));
    if (close < open) {
        ctx.diag.Warning(c.loc, "shutter close time < shutter open time; swapping them");
        std::swap(open, close);
    }
    if (!(close - open > 0))
        Fail(c.loc, "the specified camera shutter times imply that the shutter does not open (a black image would result)");
    return close - open;
}

void BuildFilm(BuildContext &ctx, Float exposureTime) {
    const SceneEntity &f = ctx.desc.film;
    HostScene &s = ctx.scene;
    const ParameterDictionary &p = f.params;
    std::string name = f.name.empty() ? "rgb" : f.name;
    if (name == "gbuffer" || name == "spectral") {
        ctx.diag.Unsupported(f.loc, "Film " + Quoted(name), "writing the \"rgb\" film's image (same RGB channels)");
        MarkAllUsed(p);
    } else if (name != "rgb") {
        Fail(f.loc, "unknown film type " + Quoted(name));
    }
    int xres = p.GetOneInt("xresolution", 1280), yres = p.GetOneInt("yresolution", 720);
    if (ctx.opts.resX > 0 && ctx.opts.resY > 0) {
        xres = ctx.opts.resX;
        yres = ctx.opts.resY;
    }
    if (xres <= 0) Fail(ParamLoc(p, "xresolution", f.loc), "film resolution must be positive (xresolution " + std::to_string(xres) + ")");
    if (yres <= 0) Fail(ParamLoc(p, "yresolution", f.loc), "film resolution must be positive (yresolution " + std::to_string(yres) + ")");
    if (int64_t(xres) * yres > (int64_t(1) << 27))
        Fail(ParamLoc(p, "xresolution", f.loc), "film resolution " + std::to_string(xres) + "x" + std::to_string(yres) +
                                                    " is too large (at most 2^27 pixels)");
    s.outputFilename = p.GetOneString("filename", "");
    Float iso = Float(p.GetOneFloat("iso", 100));
    Float whiteBalance = Float(p.GetOneFloat("whitebalance", 0));
    std::string sensor = p.GetOneString("sensor", "cie1931");
    Float maxComponent = Float(p.GetOneFloat("maxcomponentvalue", Infinity));
    (void)p.GetOneBool("savefp16", true);
    Float diagonal = Float(p.GetOneFloat("diagonal", 35));
    if (!(diagonal > 0)) Fail(ParamLoc(p, "diagonal", f.loc), "\"diagonal\" must be positive");
    if (p.Has("cropwindow")) {
        (void)p.GetFloatArray("cropwindow");
        ctx.diag.Unsupported(ParamLoc(p, "cropwindow", f.loc), "Film \"cropwindow\"", "the full image is rendered");
    }
    if (p.Has("pixelbounds")) {
        (void)p.GetIntArray("pixelbounds");
        ctx.diag.Unsupported(ParamLoc(p, "pixelbounds", f.loc), "Film \"pixelbounds\"", "the full image is rendered");
    }
    if (sensor != "cie1931") {
        ctx.diag.Unsupported(ParamLoc(p, "sensor", f.loc), "Film sensor " + Quoted(sensor), "using the CIE 1931 observer");
        // pbrt-v4 white-balances real sensors to 6500 K by default; with the XYZ sensor that is
        // close to the identity, so nothing more is done here.
    }
    if (!(iso > 0)) Fail(ParamLoc(p, "iso", f.loc), "\"iso\" must be positive");
    FilmData &fd = s.film;
    fd.width = xres;
    fd.height = yres;
    fd.imagingRatio = exposureTime * iso / 100;
    fd.maxComponentValue = maxComponent > 0 ? maxComponent : Infinity;
    fd.filterWeightFloor = FilterWeightFloor(s.filter, s.distributions2D);   // the filter is built first
    fd.diagonalMm = diagonal;
    // pbrt-v4's RGBFilm: outputRGBFromSensorRGB = colorSpace->RGBFromXYZ * sensor->XYZFromSensorRGB,
    // colorSpace the one in effect at Film; the cie1931 sensor's XYZFromSensorRGB is the identity,
    // or with "whitebalance" the Bradford adaptation from D(T) to the output space's white.
    s.filmColorSpace = ColorSpaceId(f.colorSpace);
    const RGBColorSpace &cs = GetRGBColorSpace(s.filmColorSpace);
    Mat3 out = cs.rgbFromXYZ;
    if (whiteBalance != 0) {
        if (whiteBalance < 0) Fail(ParamLoc(p, "whitebalance", f.loc), "\"whitebalance\" must be a positive temperature");
        out = Mul3(out, WhiteBalance(DaylightChromaticity(ctx, whiteBalance), cs.w));
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) fd.xyzToOutput[i][j] = Float(out[i][j]);
    p.ReportUnused(ctx.diag, "Film " + Quoted(name));
}

// pbrt-v4's RealisticCamera::Create: "lensfile" (resolved against the scene's directory),
// "aperturediameter" (mm), "focusdistance" (m); only the default circular "aperture".
void BuildRealisticCamera(BuildContext &ctx) {
    const CameraEntity &c = ctx.desc.camera;
    HostScene &s = ctx.scene;
    const ParameterDictionary &p = c.params;
    s.stats.cameraType = "realistic";
    s.stats.cameraPosition = c.worldFromCamera.ApplyPoint(Vec3f(0, 0, 0));
    Vec3f dir = c.worldFromCamera.ApplyVector(Vec3f(0, 0, 1));
    if (LengthSquared(dir) > 0) s.stats.cameraDirection = Normalize(dir);
    std::string aperture = p.GetOneString("aperture", "");
    if (!aperture.empty() && aperture != "circular")
        FailUnsupported(ParamLoc(p, "aperture", c.loc), "Camera \"realistic\" \"aperture\" " + Quoted(aperture),
                        "only the default circular aperture stop is implemented; the pentagon, star, gaussian and "
                        "image apertures are not");
    std::string lensFile = p.GetOneString("lensfile", "");
    Float apertureDiameter = Float(p.GetOneFloat("aperturediameter", 1.0));
    Float focusDistance = Float(p.GetOneFloat("focusdistance", 10.0));
    if (lensFile.empty()) Fail(c.loc, "realistic camera: no lens description file (\"string lensfile\") given");
    FileLoc lensLoc = ParamLoc(p, "lensfile", c.loc);
    if (!(apertureDiameter > 0)) Fail(ParamLoc(p, "aperturediameter", c.loc), "\"aperturediameter\" must be positive");
    if (!(focusDistance > 0)) Fail(ParamLoc(p, "focusdistance", c.loc), "\"focusdistance\" must be positive");
    std::string path = ResolvePath(ctx.desc.baseDirectory, lensFile);
    s.inputFiles.push_back(path);
    std::vector<LensTableRow> table = ReadLensTable(path, lensLoc);
    bool haveStop = false;
    for (const LensTableRow &r : table) haveStop |= r.curvatureRadius == 0;
    if (!haveStop) ctx.diag.Warning(lensLoc, "realistic camera: the lens table has no aperture stop (a row of radius 0); \"aperturediameter\" is ignored");
    std::string error, warning;
    if (!MakeRealisticCamera(c.worldFromCamera, s.film.width, s.film.height, s.film.diagonalMm, table, apertureDiameter,
                             focusDistance, &s.camera, &s.lensElements, &s.exitPupilBounds, &error, &warning))
        Fail(ParamLoc(p, "focusdistance", lensLoc), "realistic camera: " + error);
    if (!warning.empty()) ctx.diag.Warning(ParamLoc(p, "aperturediameter", c.loc), "realistic camera: " + warning);
    bool anyPupil = false;
    for (const Bounds2f &b : s.exitPupilBounds) anyPupil |= !b.IsDegenerate();
    if (!anyPupil) ctx.diag.Warning(lensLoc, "realistic camera: no ray from the film gets through the lens system (a black image)");
    p.ReportUnused(ctx.diag, "Camera \"realistic\"");
}

void BuildCamera(BuildContext &ctx) {
    const CameraEntity &c = ctx.desc.camera;
    HostScene &s = ctx.scene;
    const ParameterDictionary &p = c.params;
    std::string name = c.name.empty() ? "perspective" : c.name;
    if (name == "realistic") {
        BuildRealisticCamera(ctx);
        return;
    }
    if (!OneOf(name, {"perspective", "orthographic", "spherical"})) Fail(c.loc, "unknown camera type " + Quoted(name));
    Float lensRadius = Float(p.GetOneFloat("lensradius", 0));
    Float focalDistance = Float(p.GetOneFloat("focaldistance", 1e6));
    Float frame = 0;
    if (p.Has("frameaspectratio")) {
        frame = Float(p.GetOneFloat("frameaspectratio", 1));
        if (!(frame > 0)) Fail(ParamLoc(p, "frameaspectratio", c.loc), "\"frameaspectratio\" must be positive");
    }
    Float screen[4];
    bool haveScreen = false;
    if (p.Has("screenwindow")) {
        std::vector<double> sw = p.GetFloatArray("screenwindow");
        if (sw.size() != 4) Fail(ParamLoc(p, "screenwindow", c.loc), "\"screenwindow\" should have four values");
        for (int i = 0; i < 4; ++i) screen[i] = Float(sw[i]);
        if (!(screen[1] > screen[0]) || !(screen[3] > screen[2]))
            Fail(ParamLoc(p, "screenwindow", c.loc), "\"screenwindow\" must have xmin < xmax and ymin < ymax");
        haveScreen = true;
    }
    s.stats.cameraType = name;
    s.stats.cameraPosition = c.worldFromCamera.ApplyPoint(Vec3f(0, 0, 0));
    Vec3f dir = c.worldFromCamera.ApplyVector(Vec3f(0, 0, 1));
    if (LengthSquared(dir) > 0) s.stats.cameraDirection = Normalize(dir);
    if (lensRadius < 0) Fail(ParamLoc(p, "lensradius", c.loc), "\"lensradius\" must not be negative");
    if (lensRadius > 0 && !(focalDistance > 0)) Fail(ParamLoc(p, "focaldistance", c.loc), "\"focaldistance\" must be positive");
    if (name == "orthographic") {
        s.camera = MakeOrthographicCamera(c.worldFromCamera, s.film.width, s.film.height, lensRadius, focalDistance,
                                          haveScreen ? screen : nullptr, frame);
        p.ReportUnused(ctx.diag, "Camera " + Quoted(name));
        return;
    }
    if (name == "spherical") {
        // pbrt-v4 reads the projective cameras' parameters here too and ignores them.
        FileLoc mloc = ParamLoc(p, "mapping", c.loc);
        std::string mapping = p.GetOneString("mapping", "equalarea");
        CameraKind kind;
        if (mapping == "equalarea") kind = CameraKind::SphericalEqualArea;
        else if (mapping == "equirectangular") kind = CameraKind::SphericalEquirect;
        else Fail(mloc, "unknown spherical camera \"mapping\" " + Quoted(mapping) + " (expected equalarea or equirectangular)");
        if (kind == CameraKind::SphericalEqualArea && s.film.width != s.film.height)
            ctx.diag.Warning(mloc, "spherical camera: the equal-area mapping expects a square image (" +
                                       std::to_string(s.film.width) + "x" + std::to_string(s.film.height) + ")");
        if (lensRadius > 0) ctx.diag.Warning(ParamLoc(p, "lensradius", c.loc), "spherical camera: \"lensradius\" is ignored (as pbrt-v4)");
        s.camera = MakeSphericalCamera(c.worldFromCamera, s.film.width, s.film.height, kind);
        p.ReportUnused(ctx.diag, "Camera " + Quoted(name));
        return;
    }
    double fov = p.GetOneFloat("fov", 90);
    if (!(fov > 0 && fov < 180))
        Fail(ParamLoc(p, "fov", c.loc), "\"fov\" must be between 0 and 180 degrees (exclusive), got " + std::to_string(fov));
    s.camera = MakePerspectiveCamera(c.worldFromCamera, s.film.width, s.film.height, Float(fov), lensRadius, focalDistance,
                                     haveScreen ? screen : nullptr, frame);
    s.stats.fov = fov;
    p.ReportUnused(ctx.diag, "Camera " + Quoted(name));
}

// pbrt-v4's Option directive (BasicSceneBuilder::Option): the name compared lower-cased without
// '_' and '-', the value as the raw token. What changes Lucerna's picture is applied
// (ctx.sceneOptions); what only changes pbrt-v4's run is accepted; what Lucerna cannot do is
// reported by name.
void ReadOptionDirectives(BuildContext &ctx) {
    for (const SceneDescription::OptionEntry &o : ctx.desc.options) {
        std::string name;
        for (unsigned char c : o.name)
            if (c != '_' && c != '-') name += char(std::tolower(c));
        auto boolValue = [&] {
            if (o.value != "true" && o.value != "false")
                Fail(o.loc, "Option " + Quoted(o.name) + ": expected true or false (unquoted), got " + o.value);
            return o.value == "true";
        };
        auto stringValue = [&] {
            if (o.value.size() < 3 || o.value.front() != '"' || o.value.back() != '"')
                Fail(o.loc, "Option " + Quoted(o.name) + ": expected a quoted string, got " + o.value);
            return o.value.substr(1, o.value.size() - 2);
        };
        auto numberValue = [&](bool integer) {
            char *end = nullptr;
            double v = std::strtod(o.value.c_str(), &end);
            if (o.value.empty() || *end != '\0' || !std::isfinite(v) || (integer && (v != std::floor(v) || std::abs(v) > 2147483647.0)))
                Fail(o.loc, "Option " + Quoted(o.name) + ": expected " + (integer ? "an integer" : "a number") + ", got " + o.value);
            return v;
        };
        if (name == "disablepixeljitter") ctx.sceneOptions.disablePixelJitter = boolValue();
        else if (name == "disablewavelengthjitter") ctx.sceneOptions.disableWavelengthJitter = boolValue();
        else if (name == "seed") ctx.sceneOptions.seed = int(numberValue(true));
        else if (name == "disabletexturefiltering") boolValue();  // Lucerna always reads the finest level, as this makes pbrt-v4 do
        else if (name == "wavefront") boolValue();                // pbrt-v4's choice of its own GPU/wavefront integrator
        else if (name == "rendercoordsys") {
            std::string sys = stringValue();
            if (!OneOf(sys, {"camera", "cameraworld", "world"}))
                Fail(o.loc, Quoted(sys) + ": unknown rendering coordinate system (camera, cameraworld or world)");
        } else if (name == "forcediffuse") {
            if (boolValue()) ctx.Collect([&] { FailUnsupported(o.loc, "Option \"forcediffuse\"", "materials are rendered as written"); });
        } else if (name == "displacementedgescale") {
            numberValue(false);
            ctx.diag.Warning(o.loc, "Option \"displacementedgescale\" has no effect: Lucerna does not tessellate displacement");
        } else if (name == "msereferenceimage" || name == "msereferenceout") {
            stringValue();
            ctx.diag.Unsupported(o.loc, "Option " + Quoted(o.name), "ignored (compare images with `lucerna diff`)");
        } else if (name == "pixelstats") {
            if (boolValue()) ctx.diag.Unsupported(o.loc, "Option \"pixelstats\"", "ignored (no per-pixel statistics images)");
        } else {
            Fail(o.loc, Quoted(o.name) + ": unknown option");
        }
    }
}

void BuildFilter(BuildContext &ctx) {
    const SceneEntity &f = ctx.desc.filter;
    HostScene &s = ctx.scene;
    const ParameterDictionary &p = f.params;
    std::string name = f.name.empty() ? "gaussian" : f.name;
    if (!OneOf(name, {"box", "gaussian", "triangle", "mitchell", "sinc"})) Fail(f.loc, "unknown filter type " + Quoted(name));
    Float defRadius = name == "box" ? 0.5f : name == "gaussian" ? 1.5f : name == "sinc" ? 4.f : 2.f;
    Float xr = Float(p.GetOneFloat("xradius", defRadius)), yr = Float(p.GetOneFloat("yradius", defRadius));
    if (!(xr > 0)) Fail(ParamLoc(p, "xradius", f.loc), "filter radius must be positive");
    if (!(yr > 0)) Fail(ParamLoc(p, "yradius", f.loc), "filter radius must be positive");
    Float sigma = -1, B = NAN, C = NAN;
    if (name == "gaussian") {
        sigma = Float(p.GetOneFloat("sigma", 0.5));
        if (!(sigma > 0)) Fail(ParamLoc(p, "sigma", f.loc), "gaussian \"sigma\" must be positive");
    }
    if (name == "mitchell") {
        B = Float(p.GetOneFloat("B", 1.0 / 3));
        C = Float(p.GetOneFloat("C", 1.0 / 3));
    }
    Float tau = -1;
    if (name == "sinc") {
        tau = Float(p.GetOneFloat("tau", 3.0));
        if (!(tau > 0)) Fail(ParamLoc(p, "tau", f.loc), "sinc \"tau\" must be positive");
    }
    s.filter = MakeFilter(name, xr, yr, sigma, B, C, tau);
    BuildFilterDistribution(s.filter, s.distributions2D, s.distData);
    s.filter.disableJitter = ctx.sceneOptions.disablePixelJitter;
    s.stats.filterType = name;
    p.ReportUnused(ctx.diag, "PixelFilter " + Quoted(name));
}

// pbrt-v4's samplers and their parameters; the Sampler is built here, once, with all of them.
void BuildSampler(BuildContext &ctx) {
    const SceneEntity &e = ctx.desc.sampler;
    HostScene &scene = ctx.scene;
    RenderSettings &rs = scene.settings;
    const ParameterDictionary &p = e.params;
    std::string name = e.name.empty() ? "zsobol" : e.name;
    if (!OneOf(name, {"sobol", "zsobol", "paddedsobol", "independent", "halton", "pmj02bn", "stratified"}))
        Fail(e.loc, "unknown sampler type " + Quoted(name));
    scene.stats.samplerName = name;
    SamplerOptions options;
    int spp = 0;
    if (name == "stratified") {
        options.xSamples = p.GetOneInt("xsamples", 4);
        options.ySamples = p.GetOneInt("ysamples", 4);
        options.jitter = p.GetOneBool("jitter", true);
        if (options.xSamples <= 0 || options.ySamples <= 0)
            Fail(e.loc, "stratified sampler: \"xsamples\" and \"ysamples\" must be positive");
        spp = options.xSamples * options.ySamples;
    } else {
        spp = p.GetOneInt("pixelsamples", 16);
        if (spp <= 0) Fail(ParamLoc(p, "pixelsamples", e.loc), "\"pixelsamples\" must be positive");
        if (spp > (1 << 24)) Fail(ParamLoc(p, "pixelsamples", e.loc), "\"pixelsamples\" must be at most 2^24");
    }
    rs.spp = spp;
    rs.seed = uint32_t(p.GetOneInt("seed", ctx.sceneOptions.seed));
    if (OneOf(name, {"sobol", "zsobol", "paddedsobol", "halton"})) {
        FileLoc loc = ParamLoc(p, "randomization", e.loc);
        options.randomization = p.GetOneString("randomization", "");
        if (!OneOf(options.randomization, {"", "none", "permutedigits", "fastowen", "owen"}))
            Fail(loc, "unknown randomization " + Quoted(options.randomization) +
                          " (expected none, permutedigits, fastowen or owen)");
        if (name == "halton" && options.randomization == "fastowen")
            Fail(loc, "halton sampler: \"fastowen\" randomization is not available (pbrt-v4 refuses it too)");
    }
    if (name == "sobol" && Max(scene.film.width, scene.film.height) > 65536)
        Fail(e.loc, "sobol sampler: resolutions above 65536 pixels are not supported");
    if (name == "pmj02bn" && spp > kPMJ02BNSamples)
        Fail(ParamLoc(p, "pixelsamples", e.loc), "pmj02bn sampler: at most " + std::to_string(kPMJ02BNSamples) +
                                                      " samples per pixel (pbrt-v4's limit)");
    std::string report;
    scene.sampler = MakeSampler(name, spp, int(rs.seed), scene.film.width, scene.film.height, options, &report);
    if (scene.sampler.kind == SamplerKind::PMJ02BN)
        scene.pmjPoints = BuildPMJ02BNTables(scene.sampler.samplesPerPixel, 0x706d6a3032626eull, &scene.sampler.pmjTileSize);
    for (size_t i = 0, j; i < report.size(); i = j + 1) {
        j = report.find('\n', i);
        if (j == std::string::npos) j = report.size();
        std::string line = report.substr(i, j - i);
        if (!line.empty()) ctx.diag.Warning(e.loc, line);
    }
    p.ReportUnused(ctx.diag, "Sampler " + Quoted(name));
}

void BuildIntegrator(BuildContext &ctx) {
    const SceneEntity &e = ctx.desc.integrator;
    RenderSettings &rs = ctx.scene.settings;
    const ParameterDictionary &p = e.params;
    ctx.scene.stats.integratorAsRead = e.name;
    // A scene with a collimated beam has paths with two kernels (the regularized connection from a
    // specular vertex to the beam): their bias and variance balance at lambda = 1/8, where paths
    // with one kernel still converge (docs/regularization.md, "Two regularized vertices").
    for (const LightEntity &l : ctx.desc.lights)
        if (l.name == "collimated") rs.regLambda = 1.0 / 8;
    if (e.name.empty()) return;  // pbrt-v4's default "volpath": the same image as "path" without media
    rs.maxDepth = p.GetOneInt("maxdepth", 5);
    if (rs.maxDepth < 0) Fail(ParamLoc(p, "maxdepth", e.loc), "\"maxdepth\" must not be negative");
    if (e.name == "path") {
        rs.integrator = IntegratorKind::Path;
        if (p.GetOneBool("regularize", false))
            ctx.diag.Unsupported(ParamLoc(p, "regularize", e.loc), "pbrt-v4's \"bool regularize\" (BSDF roughening)",
                                 "the unbiased path tracer is used");
        (void)p.GetOneString("lightsampler", "bvh");  // sampling choice only: Lucerna samples lights by power
    } else if (e.name == "regpath") {
        rs.integrator = IntegratorKind::RegPath;
        rs.regRadius = p.GetOneFloat("radius", 0);
        rs.regLambda = p.GetOneFloat("lambda", rs.regLambda);
        rs.regAngle = p.GetOneFloat("angle", 2);
        if (p.Has("radius") && !(rs.regRadius > 0)) Fail(ParamLoc(p, "radius", e.loc), "\"radius\" must be positive");
        rs.mnee = p.GetOneBool("mnee", true);
        rs.nearSpecular = p.GetOneBool("near-specular", true);
        rs.regFootprint = p.GetOneFloat("footprint", -1);
        if (p.Has("footprint") && !(rs.regFootprint >= 0 && rs.regFootprint <= 1e6))
            Fail(ParamLoc(p, "footprint", e.loc), "\"footprint\" must be in [0, 1e6] pixels");
        if (!(rs.regLambda >= 0 && rs.regLambda <= 1)) Fail(ParamLoc(p, "lambda", e.loc), "\"lambda\" must be in [0, 1]");
        if (!(rs.regAngle > 0 && rs.regAngle <= 90)) Fail(ParamLoc(p, "angle", e.loc), "\"angle\" must be in (0, 90] degrees");
    } else if (OneOf(e.name, {"volpath", "bdpt", "mlt", "sppm", "lightpath", "simplepath", "simplevolpath", "randomwalk"})) {
        ctx.diag.Unsupported(e.loc, "Integrator " + Quoted(e.name), "rendered with Lucerna's \"path\" (same maxdepth); paths through specular surfaces to point, spot or tiny lights need --integrator regpath");
        rs.integrator = IntegratorKind::Path;
        MarkAllUsed(p);  // its other parameters (radius, photons, ...) have no "path" equivalent
    } else if (OneOf(e.name, {"ambientocclusion", "aov", "function"})) {
        FailUnsupported(e.loc, "Integrator " + Quoted(e.name));
    } else {
        Fail(e.loc, "unknown integrator " + Quoted(e.name));
    }
    p.ReportUnused(ctx.diag, "Integrator " + Quoted(e.name));
}

}  // namespace
}  // namespace build

std::unique_ptr<HostScene> BuildScene(const SceneDescription &desc, Diagnostics &diag, const BuildOptions &opts) {
    using namespace build;
    auto scene = std::make_unique<HostScene>();
    BuildContext ctx{desc, diag, opts, *scene};
    scene->inputFiles = desc.inputFiles;

    // Every unsupported feature is collected (ctx.Collect) and the build goes on, so that the one
    // error thrown at the end lists them all; another error ends the build at once, after them.
    auto throwCollected = [&](const SceneError *last) {
        if (ctx.unsupportedErrors.empty()) return;
        SceneError all = ctx.unsupportedErrors.front();
        for (size_t i = 1; i < ctx.unsupportedErrors.size(); ++i) all.AddFollowing(ctx.unsupportedErrors[i]);
        if (last) all.AddFollowing(*last);
        throw all;
    };
    try {
        ReadOptionDirectives(ctx);

        // Rendering options, in pbrt-v4's order (filter, film, camera, sampler, integrator).
        ctx.Collect([&] { BuildFilter(ctx); });
        BuildFilm(ctx, ExposureTime(ctx));
        scene->film.disableWavelengthJitter = ctx.sceneOptions.disableWavelengthJitter;
        ctx.Collect([&] { BuildCamera(ctx); });
        {   // through the scene's lens arrays (the realistic camera's)
            CameraData c = scene->camera;
            c.lensElements = SpanOf(scene->lensElements);
            c.exitPupilBounds = SpanOf(scene->exitPupilBounds);
            SetPixelFootprint(c);
            scene->camera.pixelWidth = c.pixelWidth;
            scene->camera.pixelSpread = c.pixelSpread;
        }
        BuildSampler(ctx);
        ctx.Collect([&] { BuildIntegrator(ctx); });

        ctx.Collect([&] { BuildMedia(ctx); });
        IndexTextures(ctx);
        BuildMaterials(ctx);
        BuildShapes(ctx);
        scene->walkInterfaces = !scene->media.empty();
        for (const Shape &sh : scene->shapes) scene->walkInterfaces |= sh.material == NoIndex;
        if (scene->mediumData.size() > size_t(UINT32_MAX))
            ctx.Collect([&] { FailUnsupported({}, "media grids of more than 2^32 values in all"); });
        BuildLights(ctx);
        FinishLights(ctx);
        for (uint32_t i = 0; i < NumColorSpaces; ++i)
            scene->illuminantTables[i] = scene->spectra.IlluminantTable(ColorSpaceId(i));
    } catch (const SceneError &e) {
        throwCollected(&e);
        throw;
    }
    throwCollected(nullptr);
    // regpath's auto r0 (0.04 x this, RenderSettings::ResolvedRegRadius).
    scene->settings.sceneDiagonal = scene->bounds.Empty() ? 0 : Length(scene->bounds.Diagonal());
    return scene;
}

std::unique_ptr<HostScene> LoadScene(const std::string &filename, Diagnostics &diag, const BuildOptions &opts) {
    std::unique_ptr<HostScene> scene;
    {
        SceneDescription desc = ParseSceneFile(filename, diag);
        scene = BuildScene(desc, diag, opts);
    }
#if defined(__GLIBC__)
    // The description is gone: hand its many small blocks (millions of ObjectInstance records in
    // deque chunks) back to the system before the render allocates its accelerators. Without this
    // glibc keeps them: 3.2 M instances render in 1.04 GB instead of 0.7 (docs/benchmarks.md).
    malloc_trim(0);
#endif
    return scene;
}

}  // namespace lu
