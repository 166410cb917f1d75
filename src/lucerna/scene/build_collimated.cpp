// Lucerna scene builder: LightSource "collimated" (a Lucerna extension, docs/lights.md): a disc or
// a rectangle emitting a collimated beam (laser, collimated LED) with a uniform or gaussian irradiance
// profile, a spectrum or a laser line, normalized to "power" watts or scaled as pbrt-v4's lights.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lucerna/lights/collimated.h"
#include "lucerna/scene/build_internal.h"

namespace lu::build {

namespace {

// A float parameter that must be finite and positive (when present).
double PositiveFloat(const ParameterDictionary &p, const std::string &name, double def, const FileLoc &loc) {
    double v = p.GetOneFloat(name, def);
    if (!(v > 0) || !std::isfinite(v))
        Fail(ParamLoc(p, name, loc), "collimated light: " + Quoted(name) + " must be positive (got " + FormatNumber(v) + ")");
    return v;
}

// The laser line: a gaussian of full width at half maximum `bandwidth` nm around `wavelength`,
// tabulated at 1 nm (hence bandwidth >= 1 nm).
Spectrum LaserLine(BuildContext &ctx, const ParameterDictionary &p, const FileLoc &loc) {
    double lambda0 = p.GetOneFloat("wavelength", 0);
    if (!(lambda0 >= 360 && lambda0 <= 830))
        Fail(ParamLoc(p, "wavelength", loc), "collimated light: \"wavelength\" must be in [360, 830] nm (got " + FormatNumber(lambda0) + ")");
    double bw = p.GetOneFloat("bandwidth", 1);
    if (!(bw >= 1 && bw <= 470))
        Fail(ParamLoc(p, "bandwidth", loc), "collimated light: \"bandwidth\" (full width at half maximum) must be in [1, 470] nm "
                                            "(got " + FormatNumber(bw) + "; spectra are tabulated at 1 nm)");
    std::vector<double> lambdas, values;
    for (int l = 360; l <= 830; ++l) {
        lambdas.push_back(l);
        values.push_back(std::exp(-4 * std::log(2.0) * (l - lambda0) * (l - lambda0) / (bw * bw)));
    }
    std::optional<Spectrum> s = ctx.Registry().FromPiecewise(lambdas, values);
    if (!s) Fail(loc, "collimated light: cannot tabulate the laser line");
    return *s;
}

// The integral of s over [360, 830] nm (trapezoids at 1 nm: exact for the tabulated spectra).
double SpectrumIntegral(BuildContext &ctx, const Spectrum &s) {
    double sum = 0;
    for (int l = 360; l <= 830; ++l) sum += (l == 360 || l == 830 ? 0.5 : 1.0) * ctx.Registry().Eval(s, Float(l));
    return sum;
}

}  // namespace

void BuildCollimated(BuildContext &ctx, const LightEntity &e, Light &l, std::string *description) {
    const ParameterDictionary &p = e.params;
    const std::string owner = "LightSource \"collimated\"";
    l.kind = LightKind::Collimated;
    // ---- Spectrum: "E" (any pbrt-v4 spectrum), or a laser line ----
    std::optional<Spectrum> E = GetSpectrum(ctx, p, "E", SpectrumType::Illuminant);
    bool line = p.Has("wavelength");
    if (E && line) Fail(ParamLoc(p, "wavelength", e.loc), "collimated light: give either \"E\" or \"wavelength\", not both");
    if (!line && p.Has("bandwidth")) Fail(ParamLoc(p, "bandwidth", e.loc), "collimated light: \"bandwidth\" needs \"wavelength\"");
    l.spectrum = line ? LaserLine(ctx, p, e.loc) : E ? *E : IlluminantSpectrum(ctx, e.colorSpace);
    // ---- Geometry: the disc at "from", the beam towards "to", after the CTM ----
    Vec3f from = p.GetOnePoint3f("from").value_or(Vec3f(0, 0, 0));
    Vec3f to = p.GetOnePoint3f("to").value_or(Vec3f(0, 0, 1));
    if (!(LengthSquared(to - from) > 0)) Fail(ParamLoc(p, "to", e.loc), "collimated light: \"from\" and \"to\" must differ");
    // The aperture's frame: z along the beam, x the light-space x axis made perpendicular to it
    // (the y axis when the beam runs along x), so that a rectangle's "width" lies along x.
    Vec3f z = Normalize(to - from);
    Vec3f x = Vec3f(1, 0, 0) - z * z.x;
    if (LengthSquared(x) < 1e-6f) x = Vec3f(0, 1, 0) - z * z.y;
    x = Normalize(x);
    l.renderFromLight = e.renderFromObject * TranslateTransform(from) * FromColumns(x, Cross(z, x), z);
    l.position = l.renderFromLight.ApplyPoint(Vec3f(0, 0, 0));
    Vec3f ax = l.renderFromLight.ApplyVector(Vec3f(1, 0, 0)), ay = l.renderFromLight.ApplyVector(Vec3f(0, 1, 0));
    Vec3f az = l.renderFromLight.ApplyVector(Vec3f(0, 0, 1));
    Float sx = Length(ax), sy = Length(ay), sz = Length(az);
    if (!(sx > 0 && sy > 0 && sz > 0) || !std::isfinite(sx) || !std::isfinite(sy) || !std::isfinite(sz) ||
        !std::isfinite(l.position.x + l.position.y + l.position.z))
        Fail(e.loc, "collimated light: the transformation is singular");
    // The aperture keeps its shape perpendicular to the beam only under rotations, translations
    // and uniform scales in its plane.
    if (std::abs(sx - sy) > 1e-4f * sx || std::abs(Dot(ax, az)) > 1e-4f * sx * sz || std::abs(Dot(ay, az)) > 1e-4f * sy * sz ||
        std::abs(Dot(ax, ay)) > 1e-4f * sx * sy)
        Fail(e.loc, "collimated light: the transformation shears or scales the aperture unevenly (it must keep its "
                    "shape perpendicular to the beam)");
    l.direction = az / sz;
    l.beamU = ax / sx;
    // ---- Aperture: a disc of "radius", or a rectangle of "width" x "height" (light-space x, y) ----
    std::string aperture = p.GetOneString("aperture", "disc");
    double radius = 0, size = 0;
    if (aperture == "disc") {
        for (const char *name : {"width", "height"})
            if (p.Has(name)) Fail(ParamLoc(p, name, e.loc), std::string("collimated light: ") + Quoted(name) + " applies to "
                                                           "the \"rect\" aperture only (the disc has \"radius\")");
        radius = PositiveFloat(p, "radius", 0.001, e.loc);
        size = radius;
    } else if (aperture == "rect") {
        if (p.Has("radius")) Fail(ParamLoc(p, "radius", e.loc), "collimated light: \"radius\" applies to the \"disc\" "
                                                               "aperture only (the rectangle has \"width\" and \"height\")");
        double width = PositiveFloat(p, "width", 0.002, e.loc);
        double height = PositiveFloat(p, "height", width, e.loc);
        l.beamHalf = Vec2f(Float(width / 2 * sx), Float(height / 2 * sx));
        radius = std::sqrt(width * width + height * height) / 2;   // the half diagonal (bounds)
        size = std::min(width, height) / 2;
    } else {
        Fail(ParamLoc(p, "aperture", e.loc), "collimated light: unknown \"aperture\" " + Quoted(aperture) +
                                                 " (expected \"disc\" or \"rect\")");
    }
    // ---- Profile ----
    std::string profile = p.GetOneString("profile", "uniform");
    double waist = 0;
    if (profile == "gaussian") {
        waist = PositiveFloat(p, "waist", size, e.loc);
    } else if (profile == "uniform") {
        if (p.Has("waist")) Fail(ParamLoc(p, "waist", e.loc), "collimated light: \"waist\" applies to the \"gaussian\" profile only");
    } else {
        Fail(ParamLoc(p, "profile", e.loc), "collimated light: unknown \"profile\" " + Quoted(profile) +
                                                " (expected \"uniform\" or \"gaussian\")");
    }
    l.beamRadius = Float(radius * sx);
    l.beamWaist = Float(waist * sx);
    // ---- Scale: "power" watts (radiometric, over 360-830 nm), else pbrt-v4's photometric scale ----
    double scale = p.GetOneFloat("scale", 1);
    if (!(scale >= 0) || !std::isfinite(scale))
        Fail(ParamLoc(p, "scale", e.loc), owner + ": \"scale\" must not be negative (got " + FormatNumber(scale) + ")");
    Float area = BeamProfileIntegral(l);
    if (!(area > 0))
        Fail(ParamLoc(p, BeamIsRectangle(l) ? "width" : "radius", e.loc),
             "collimated light: the aperture is too small (zero area in float)");
    if (p.Has("power")) {
        double P = PositiveFloat(p, "power", 1, e.loc);
        double integral = SpectrumIntegral(ctx, l.spectrum);
        if (!(integral > 0))
            Fail(e.loc, "collimated light: the spectrum has no energy in [360, 830] nm; \"power\" cannot normalize it");
        l.scale = Float(scale * P / (integral * double(area)));
    } else {
        Float photometric = ctx.Registry().ToPhotometric(l.spectrum);
        l.scale = Float(photometric > 0 ? scale / photometric : scale);
    }
    ctx.scene.collimatedLightLocs.push_back(e.loc);
    // "rect 0.3 x 0.1, gaussian waist 0.05, 532 nm line (10 nm wide), 0.5 W" (render-space sizes).
    std::string d = BeamIsRectangle(l) ? "rect " + FormatNumber(2 * l.beamHalf.x) + " x " + FormatNumber(2 * l.beamHalf.y)
                                       : "disc radius " + FormatNumber(l.beamRadius);
    d += l.beamWaist > 0 ? ", gaussian waist " + FormatNumber(l.beamWaist) : ", uniform";
    if (line) d += ", " + FormatNumber(p.GetOneFloat("wavelength", 0)) + " nm line (" + FormatNumber(p.GetOneFloat("bandwidth", 1)) + " nm wide)";
    if (p.Has("power")) d += ", " + FormatNumber(p.GetOneFloat("power", 1) * scale) + " W";
    *description = d;
}

}  // namespace lu::build
