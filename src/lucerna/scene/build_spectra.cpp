// Lucerna scene builder: spectrum-valued parameters ("rgb", "spectrum", "blackbody"), after
// pbrt-v4's ParameterDictionary::extractSpectrumArray (paramdict.cpp).
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lucerna/scene/build_internal.h"

namespace lu::build {

Spectrum IlluminantSpectrum() {
    Spectrum s;
    s.kind = SpectrumKind::Tabulated;
    s.scale = 1;
    s.table = TableD65;
    return s;
}

// pbrt-v4's PiecewiseLinearSpectrum::Read: whitespace-separated (lambda, value) pairs, '#'
// comments to the end of the line; not normalized.
static bool ReadSpectrumFile(const std::string &path, std::vector<double> *lambda, std::vector<double> *value) {
    std::ifstream in(path);
    if (!in) return false;
    std::vector<double> v;
    std::string line;
    while (std::getline(in, line)) {
        if (auto h = line.find('#'); h != std::string::npos) line.resize(h);
        std::istringstream is(line);
        std::string tok;
        while (is >> tok) {
            char *end = nullptr;
            double d = std::strtod(tok.c_str(), &end);
            if (end == tok.c_str() || *end != '\0') return false;
            v.push_back(d);
        }
    }
    if (v.empty() || v.size() % 2 != 0) return false;
    for (size_t i = 0; i < v.size(); i += 2) {
        if (i > 0 && v[i] <= v[i - 2]) return false;
        lambda->push_back(v[i]);
        value->push_back(v[i + 1]);
    }
    return true;
}

Spectrum NamedOrFileSpectrum(BuildContext &ctx, const std::string &name, const FileLoc &loc) {
    if (std::optional<Spectrum> s = ctx.Registry().Named(name)) return *s;
    // Not a named spectrum: pbrt-v4 then tries a file of that name.
    std::string path = ResolvePath(ctx.desc.baseDirectory, name);
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec)) {
        std::vector<double> lambda, value;
        ctx.scene.inputFiles.push_back(path);
        if (!ReadSpectrumFile(path, &lambda, &value)) Fail(loc, Quoted(name) + ": unable to read a valid spectrum file");
        std::optional<Spectrum> s = ctx.Registry().FromPiecewise(lambda, value);
        if (!s) Fail(loc, Quoted(name) + ": invalid spectrum in file");
        return *s;
    }
    Fail(loc, "unknown named spectrum " + Quoted(name));
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
        return ctx.Registry().FromRGB(rgb, type);
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
        std::optional<Spectrum> s = ctx.Registry().FromPiecewise(lambda, value);
        if (!s) Fail(p->loc, "invalid \"spectrum " + name + "\"");
        return *s;
    }
    if (p->strings.size() != 1) Fail(p->loc, "\"spectrum " + name + "\" needs one spectrum name or (lambda, value) pairs");
    return NamedOrFileSpectrum(ctx, p->strings[0], p->loc);
}

}  // namespace lu::build
