// Lucerna scene builder: spectrum-valued parameters ("rgb", "spectrum", "blackbody"), after
// pbrt-v4's ParameterDictionary::extractSpectrumArray (paramdict.cpp).
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lucerna/scene/build_internal.h"

namespace lu::build {

// A number as the user wrote it, near enough: "%g".
static std::string Number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", x);
    return buf;
}

Spectrum IlluminantSpectrum(BuildContext &ctx, uint8_t cs) {
    Spectrum s;
    s.kind = SpectrumKind::Tabulated;
    s.scale = 1;
    s.table = ctx.Registry().IlluminantTable(ColorSpaceId(cs));
    return s;
}

// pbrt-v4's PiecewiseLinearSpectrum::Read: whitespace-separated (lambda, value) pairs, '#'
// comments to the end of the line; not normalized. Returns "" or what is wrong with the file
// (naming its line); *lines gets the line of each pair.
static std::string ReadSpectrumFile(const std::string &path, std::vector<double> *lambda, std::vector<double> *value,
                                    std::vector<int> *lines) {
    std::ifstream in(path);
    if (!in) return "cannot be opened";
    std::vector<double> v;
    std::vector<int> at;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        if (auto h = line.find('#'); h != std::string::npos) line.resize(h);
        std::istringstream is(line);
        std::string tok;
        while (is >> tok) {
            char *end = nullptr;
            double d = std::strtod(tok.c_str(), &end);
            if (end == tok.c_str() || *end != '\0')
                return "line " + std::to_string(lineNo) + ": " + Quoted(tok) + " is not a number";
            if (!std::isfinite(d)) return "line " + std::to_string(lineNo) + ": " + Quoted(tok) + " is not a finite number";
            v.push_back(d);
            at.push_back(lineNo);
        }
    }
    if (v.empty()) return "has no (wavelength, value) pairs";
    if (v.size() % 2 != 0) return "has an odd number of values (" + std::to_string(v.size()) + "): it needs (wavelength, value) pairs";
    for (size_t i = 0; i < v.size(); i += 2) {
        if (i > 0 && !(v[i] > v[i - 2]))
            return "line " + std::to_string(at[i]) + ": wavelengths are not increasing (" + Number(v[i - 2]) + " nm, then " +
                   Number(v[i]) + " nm)";
        lambda->push_back(v[i]);
        value->push_back(v[i + 1]);
        lines->push_back(at[i]);
    }
    return "";
}

// (lambda, value) pairs of parameter `name` (inline or from `file`, lines[i] the file line of
// pair i) as a tabulated spectrum, pbrt-v4's PiecewiseLinearSpectrum: 0 outside the range given.
// Values that would render negative radiance or NaN are errors at loc: negative values, and
// eta <= 0. Unbounded spectra (eta, k) that do not cover 360-830 nm are extended with their end
// values (with a warning): 0 there would be an eta of 0, whose Fresnel term is NaN (in pbrt-v4
// too); emission and reflectance keep pbrt-v4's 0.
static Spectrum FromPairs(BuildContext &ctx, std::vector<double> lambda, std::vector<double> value,
                          const std::string &name, SpectrumType type, const FileLoc &loc, const std::string &file = "",
                          const std::vector<int> &lines = {}) {
    std::string what = "spectrum " + Quoted(name) + (file.empty() ? std::string() : " from " + Quoted(file));
    for (size_t i = 0; i < value.size(); ++i) {
        std::string at = " at " + Number(lambda[i]) + " nm" + (lines.empty() ? std::string() : " (line " + std::to_string(lines[i]) + ")");
        if (value[i] < 0) Fail(loc, what + " has a negative value " + Number(value[i]) + at);
        if (type == SpectrumType::Unbounded && name == "eta" && !(value[i] > 0))
            Fail(loc, what + ": the index of refraction must be positive, got " + Number(value[i]) + at);
    }
    if (type == SpectrumType::Unbounded && (lambda.front() > LambdaMin || lambda.back() < LambdaMax)) {
        ctx.diag.Warning(loc, what + " covers " + Number(lambda.front()) + "-" + Number(lambda.back()) +
                                  " nm only; extended with its end values to 360-830 nm (pbrt-v4 evaluates it as 0 "
                                  "outside, which makes an index of refraction 0 and its Fresnel term NaN)");
        if (lambda.front() > LambdaMin) {
            lambda.insert(lambda.begin(), LambdaMin - 1);
            value.insert(value.begin(), value.front());
        }
        if (lambda.back() < LambdaMax) {
            lambda.push_back(LambdaMax + 1);
            value.push_back(value.back());
        }
    }
    std::optional<Spectrum> s = ctx.Registry().FromPiecewise(lambda, value);
    if (!s) Fail(loc, "invalid " + what);
    return *s;
}

// A named spectrum, or pbrt-v4's fallback: a spectrum file of that name (parameter `param`).
static Spectrum NamedOrFile(BuildContext &ctx, const std::string &name, const FileLoc &loc, const std::string &param,
                            SpectrumType type) {
    if (std::optional<Spectrum> s = ctx.Registry().Named(name)) return *s;
    std::string path = ResolvePath(ctx.desc.baseDirectory, name);
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec)) {
        std::vector<double> lambda, value;
        ctx.scene.inputFiles.push_back(path);
        std::vector<int> lines;
        std::string error = ReadSpectrumFile(path, &lambda, &value, &lines);
        if (!error.empty()) Fail(loc, "spectrum file " + Quoted(name) + " " + error);
        return FromPairs(ctx, std::move(lambda), std::move(value), param, type, loc, name, lines);
    }
    Fail(loc, "unknown named spectrum " + Quoted(name));
}

Spectrum NamedOrFileSpectrum(BuildContext &ctx, const std::string &name, const FileLoc &loc) {
    return NamedOrFile(ctx, name, loc, "", SpectrumType::Unbounded);
}

std::optional<Spectrum> GetSpectrum(BuildContext &ctx, const ParameterDictionary &params, const std::string &name,
                                    SpectrumType type) {
    std::string t = params.TypeOf(name);
    if (t.empty()) return std::nullopt;
    if (t != "rgb" && t != "spectrum" && t != "blackbody")
        Fail(ParamLoc(params, name, {}), "parameter " + Quoted(t + " " + name) +
                                             " has the wrong type: expected \"rgb\", \"spectrum\" or \"blackbody\"");
    const ParsedParameter *p = params.Find(name);
    if (!p) return std::nullopt;
    if (t == "rgb") {
        if (p->numbers.size() != 3) Fail(p->loc, "\"rgb " + name + "\" needs exactly 3 values");
        RGB rgb = {Float(p->numbers[0]), Float(p->numbers[1]), Float(p->numbers[2])};
        if (rgb[0] < 0 || rgb[1] < 0 || rgb[2] < 0) Fail(p->loc, "RGB parameter " + Quoted(name) + " has a negative component");
        if (type == SpectrumType::Albedo && (rgb[0] > 1 || rgb[1] > 1 || rgb[2] > 1))
            Fail(p->loc, "RGB parameter " + Quoted(name) + " used as an albedo has a component > 1");
        return ctx.Registry().FromRGB(rgb, type, ColorSpaceId(p->colorSpace));
    }
    if (t == "blackbody") {
        if (p->numbers.size() != 1) Fail(p->loc, "\"blackbody " + name + "\" needs exactly one value (temperature in kelvin)");
        if (!(p->numbers[0] > 0)) Fail(p->loc, "\"blackbody " + name + "\": temperature must be positive");
        return ctx.Registry().Blackbody(Float(p->numbers[0]));
    }
    // "spectrum": inline (lambda, value) pairs, or one named spectrum / spectrum file.
    if (!p->numbers.empty()) {
        if (p->numbers.size() % 2 != 0) Fail(p->loc, "odd number of values for \"spectrum " + name + "\"");
        std::vector<double> lambda, value;
        for (size_t i = 0; i < p->numbers.size(); i += 2) {
            if (i > 0 && p->numbers[i] <= p->numbers[i - 2])
                Fail(p->loc, "\"spectrum " + name + "\": wavelengths are not increasing");
            lambda.push_back(p->numbers[i]);
            value.push_back(p->numbers[i + 1]);
        }
        return FromPairs(ctx, std::move(lambda), std::move(value), name, type, p->loc);
    }
    if (p->strings.size() != 1) Fail(p->loc, "\"spectrum " + name + "\" needs one spectrum name or (lambda, value) pairs");
    return NamedOrFile(ctx, p->strings[0], p->loc, name, type);
}

}  // namespace lu::build
