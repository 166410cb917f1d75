// Lucerna scene builder: material values that would render NaN, infinity or negative radiance
// (negative roughness, eta <= 0, |g| > 1, ...) are located errors. pbrt-v4 accepts most of them
// and renders NaN or black; here they stop the build with the parameter's FILE:LINE:COL.
#include <cmath>
#include <cstdio>

#include "lucerna/scene/build_internal.h"

namespace lu::build {

namespace {

// The values a float texture can take when the builder knows them: constants, and checkerboards,
// scales and mixes (by a constant amount in [0, 1]) of textures it knows (children in `nodes`).
bool KnownRange(const FloatTexture &t, const std::vector<FloatTexture> &nodes, Float *lo, Float *hi, int depth = 0) {
    auto child = [&](uint32_t i, Float *l, Float *h) {
        return i < nodes.size() && depth < MaxTextureDepth && KnownRange(nodes[i], nodes, l, h, depth + 1);
    };
    Float l0, h0, l1, h1;
    switch (t.kind) {
    case TextureKind::Constant:
        *lo = *hi = t.value;
        return true;
    case TextureKind::Checkerboard:
        if (!child(t.tex[0], &l0, &h0) || !child(t.tex[1], &l1, &h1)) return false;
        *lo = Min(l0, l1);
        *hi = Max(h0, h1);
        return true;
    case TextureKind::Scale: {
        if (!child(t.tex[0], &l0, &h0) || !child(t.amount, &l1, &h1)) return false;
        Float p[4] = {l0 * l1, l0 * h1, h0 * l1, h0 * h1};
        *lo = Min(Min(p[0], p[1]), Min(p[2], p[3]));
        *hi = Max(Max(p[0], p[1]), Max(p[2], p[3]));
        return true;
    }
    case TextureKind::Mix: {
        Float la, ha;
        if (!child(t.amount, &la, &ha) || la < 0 || ha > 1) return false;
        if (!child(t.tex[0], &l0, &h0) || !child(t.tex[1], &l1, &h1)) return false;
        *lo = Min(l0, l1);
        *hi = Max(h0, h1);
        return true;
    }
    default: return false;
    }
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
void CheckRange(const FloatTexture &t, const std::vector<FloatTexture> &nodes, Float lo, Float hi, const ParameterDictionary &p,
                std::initializer_list<const char *> names, const FileLoc &loc, const std::string &owner,
                const std::string &rule) {
    FileLoc at;
    std::string name = Present(p, names, loc, &at);
    if (t.kind == TextureKind::ImageMap && lo >= 0 && t.scale < 0)
        Fail(at, owner + ": the image texture of " + Quoted(name) + " has a negative \"scale\" (" + FormatNumber(t.scale) + ")");
    Float vLo, vHi;
    if (!KnownRange(t, nodes, &vLo, &vHi) || (vLo >= lo && vHi <= hi)) return;
    Fail(at, owner + ": " + Quoted(name) + " " + rule + " (got " + FormatNumber(vLo < lo ? vLo : vHi) + ")");
}

// Spectrum textures: constant spectra were checked when read (no negative values); an image
// texture with a negative "scale" would give negative reflectance (or eta).
void CheckScale(const SpectrumTexture &t, const ParameterDictionary &p, const char *name, const FileLoc &loc,
                const std::string &owner) {
    if (t.kind == TextureKind::ImageMap && t.scale < 0)
        Fail(ParamLoc(p, name, loc), owner + ": the image texture of " + Quoted(name) + " has a negative \"scale\" (" +
                                         FormatNumber(t.scale) + ")");
}

// Fails at the parameter when a known value of t is <= 0.
void CheckPositive(const FloatTexture &t, const std::vector<FloatTexture> &nodes, const ParameterDictionary &p,
                   const char *name, const FileLoc &loc, const std::string &owner, const std::string &rule) {
    Float vLo, vHi;
    if (!KnownRange(t, nodes, &vLo, &vHi) || vLo > 0) return;
    Fail(ParamLoc(p, name, loc), owner + ": " + Quoted(name) + " " + rule + " (got " + FormatNumber(vLo) + ")");
}

}  // namespace

void CheckMaterialValues(const Material &m, const std::vector<FloatTexture> &nodes, const ParameterDictionary &p,
                         const FileLoc &loc, const std::string &owner) {
    bool coatedConductor = m.kind == MaterialKind::CoatedConductor;
    bool rough = m.kind == MaterialKind::Conductor || m.kind == MaterialKind::Dielectric ||
                 m.kind == MaterialKind::CoatedDiffuse;
    if (rough) {
        // alpha = sqrt(roughness) (remapped) or roughness itself: negative is NaN or meaningless.
        CheckRange(m.uRoughness, nodes, 0, Infinity, p, {"uroughness", "roughness"}, loc, owner, "must not be negative");
        CheckRange(m.vRoughness, nodes, 0, Infinity, p, {"vroughness", "roughness"}, loc, owner, "must not be negative");
    }
    if (coatedConductor) {
        CheckRange(m.uRoughness, nodes, 0, Infinity, p, {"interface.uroughness", "interface.roughness"}, loc, owner,
                   "must not be negative");
        CheckRange(m.vRoughness, nodes, 0, Infinity, p, {"interface.vroughness", "interface.roughness"}, loc, owner,
                   "must not be negative");
        CheckRange(m.conductorURoughness, nodes, 0, Infinity, p, {"conductor.uroughness", "conductor.roughness"}, loc,
                   owner, "must not be negative");
        CheckRange(m.conductorVRoughness, nodes, 0, Infinity, p, {"conductor.vroughness", "conductor.roughness"}, loc,
                   owner, "must not be negative");
    }
    CheckScale(m.reflectance, p, "reflectance", loc, owner);
    CheckScale(m.albedo, p, "albedo", loc, owner);
    CheckScale(m.transmittance, p, "transmittance", loc, owner);
    CheckScale(m.conductorEta, p, coatedConductor ? "conductor.eta" : "eta", loc, owner);
    CheckScale(m.conductorK, p, coatedConductor ? "conductor.k" : "k", loc, owner);
    bool hasEta = m.kind == MaterialKind::Dielectric || m.kind == MaterialKind::ThinDielectric ||
                  m.kind == MaterialKind::CoatedDiffuse || coatedConductor;
    const char *etaName = coatedConductor ? "interface.eta" : "eta";
    if (hasEta && m.eta.kind == SpectrumKind::Constant && !(m.eta.scale > 0))
        Fail(ParamLoc(p, etaName, loc), owner + ": " + Quoted(etaName) + " (index of refraction) must be positive (got " +
                                            FormatNumber(m.eta.scale) + ")");
    if (m.kind == MaterialKind::CoatedDiffuse || coatedConductor) {
        CheckRange(m.thickness, nodes, 0, Infinity, p, {"thickness"}, loc, owner, "must not be negative");
        // The Henyey-Greenstein phase function is negative for |g| > 1.
        CheckRange(m.g, nodes, -1, 1, p, {"g"}, loc, owner, "must be in [-1, 1]");
        if (m.nSamples < 1) Fail(ParamLoc(p, "nsamples", loc), owner + ": \"nsamples\" must be at least 1 (got " + std::to_string(m.nSamples) + ")");
        if (m.maxDepth < 0) Fail(ParamLoc(p, "maxdepth", loc), owner + ": \"maxdepth\" must not be negative (got " + std::to_string(m.maxDepth) + ")");
    }
    if (m.kind == MaterialKind::Hair) {
        // pbrt-v4 clamps the roughnesses to [0.01, 1] silently; a value outside (0, 1] is a
        // mistake (the fits for v and s are made for (0, 1]), an index <= 0 has no refraction.
        CheckRange(m.betaM, nodes, 0, 1, p, {"beta_m"}, loc, owner, "must be in (0, 1]");
        CheckRange(m.betaN, nodes, 0, 1, p, {"beta_n"}, loc, owner, "must be in (0, 1]");
        CheckPositive(m.betaM, nodes, p, "beta_m", loc, owner, "must be in (0, 1]");
        CheckPositive(m.betaN, nodes, p, "beta_n", loc, owner, "must be in (0, 1]");
        CheckPositive(m.hairEta, nodes, p, "eta", loc, owner, "(index of refraction) must be positive");
        CheckRange(m.eumelanin, nodes, 0, Infinity, p, {"eumelanin"}, loc, owner, "must not be negative");
        CheckRange(m.pheomelanin, nodes, 0, Infinity, p, {"pheomelanin"}, loc, owner, "must not be negative");
        CheckScale(m.hairSigmaA, p, "sigma_a", loc, owner);
    }
    if (m.kind == MaterialKind::DiffuseTransmission && !std::isfinite(m.scale))
        Fail(ParamLoc(p, "scale", loc), owner + ": \"scale\" must be finite (got " + FormatNumber(m.scale) + ")");
}

}  // namespace lu::build
