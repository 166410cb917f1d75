// Lucerna scene builder: material values that would render NaN, infinity or negative radiance
// (negative roughness, eta <= 0, |g| > 1, ...) are located errors. pbrt-v4 accepts most of them
// and renders NaN or black; here they stop the build with the parameter's FILE:LINE:COL.
#include <cstdio>

#include "lucerna/scene/build_internal.h"

namespace lu::build {

namespace {

std::string Number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", x);
    return buf;
}

// The values a float texture can take when the builder knows them (constant, checkerboard).
bool KnownRange(const FloatTexture &t, Float *lo, Float *hi) {
    if (t.kind == TextureKind::Constant) {
        *lo = *hi = t.value;
        return true;
    }
    if (t.kind == TextureKind::Checkerboard) {
        *lo = Min(t.tex1, t.tex2);
        *hi = Max(t.tex1, t.tex2);
        return true;
    }
    return false;
}

// The first of `names` present in p (else the first name) and its location (else loc).
std::string Present(const ParameterDictionary &p, std::initializer_list<const char *> names, const FileLoc &loc, FileLoc *at) {
    for (const char *n : names)
        if (p.Has(n)) {
            *at = ParamLoc(p, n, loc);
            return n;
        }
    *at = loc;
    return *names.begin();
}

// Fails at the parameter unless every known value of t lies in [lo, hi]. Image textures are
// non-negative images times "scale": a negative scale is refused when lo >= 0.
void CheckRange(const FloatTexture &t, Float lo, Float hi, const ParameterDictionary &p,
                std::initializer_list<const char *> names, const FileLoc &loc, const std::string &owner,
                const std::string &rule) {
    FileLoc at;
    std::string name = Present(p, names, loc, &at);
    if (t.kind == TextureKind::ImageMap && lo >= 0 && t.scale < 0)
        Fail(at, owner + ": the image texture of " + Quoted(name) + " has a negative \"scale\" (" + Number(t.scale) + ")");
    Float vLo, vHi;
    if (!KnownRange(t, &vLo, &vHi) || (vLo >= lo && vHi <= hi)) return;
    Fail(at, owner + ": " + Quoted(name) + " " + rule + " (got " + Number(vLo < lo ? vLo : vHi) + ")");
}

// Spectrum textures: constant spectra were checked when read (no negative values); an image
// texture with a negative "scale" would give negative reflectance (or eta).
void CheckScale(const SpectrumTexture &t, const ParameterDictionary &p, const char *name, const FileLoc &loc,
                const std::string &owner) {
    if (t.kind == TextureKind::ImageMap && t.scale < 0)
        Fail(ParamLoc(p, name, loc), owner + ": the image texture of " + Quoted(name) + " has a negative \"scale\" (" +
                                         Number(t.scale) + ")");
}

}  // namespace

void CheckMaterialValues(const Material &m, const ParameterDictionary &p, const FileLoc &loc, const std::string &owner) {
    bool rough = m.kind == MaterialKind::Conductor || m.kind == MaterialKind::Dielectric ||
                 m.kind == MaterialKind::CoatedDiffuse;
    if (rough) {
        // alpha = sqrt(roughness) (remapped) or roughness itself: negative is NaN or meaningless.
        CheckRange(m.uRoughness, 0, Infinity, p, {"uroughness", "roughness"}, loc, owner, "must not be negative");
        CheckRange(m.vRoughness, 0, Infinity, p, {"vroughness", "roughness"}, loc, owner, "must not be negative");
    }
    CheckScale(m.reflectance, p, "reflectance", loc, owner);
    CheckScale(m.albedo, p, "albedo", loc, owner);
    CheckScale(m.conductorEta, p, "eta", loc, owner);
    CheckScale(m.conductorK, p, "k", loc, owner);
    bool hasEta = m.kind == MaterialKind::Dielectric || m.kind == MaterialKind::ThinDielectric ||
                  m.kind == MaterialKind::CoatedDiffuse;
    if (hasEta && m.eta.kind == SpectrumKind::Constant && !(m.eta.scale > 0))
        Fail(ParamLoc(p, "eta", loc), owner + ": \"eta\" (index of refraction) must be positive (got " + Number(m.eta.scale) + ")");
    if (m.kind == MaterialKind::CoatedDiffuse) {
        CheckRange(m.thickness, 0, Infinity, p, {"thickness"}, loc, owner, "must not be negative");
        // The Henyey-Greenstein phase function is negative for |g| > 1.
        CheckRange(m.g, -1, 1, p, {"g"}, loc, owner, "must be in [-1, 1]");
        if (m.nSamples < 1) Fail(ParamLoc(p, "nsamples", loc), owner + ": \"nsamples\" must be at least 1 (got " + std::to_string(m.nSamples) + ")");
        if (m.maxDepth < 0) Fail(ParamLoc(p, "maxdepth", loc), owner + ": \"maxdepth\" must not be negative (got " + std::to_string(m.maxDepth) + ")");
    }
}

}  // namespace lu::build
