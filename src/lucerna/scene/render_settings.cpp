// Lucerna (host): the render settings' names, checks, text forms and hash (render_settings.h).
#include "lucerna/scene/render_settings.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>

namespace lu {

PathSettings RenderSettings::ForPass(uint32_t pass) const {
    PathSettings ps;
    ps.maxDepth = maxDepth;
    ps.strategy = lightStrategy;
    ps.reg = RegularizationForPass(Regularizes(), Float(ResolvedRegRadius()), Float(regAngle * M_PI / 180),
                                   Float(regLambda), pass, Float(ResolvedRegFootprint()));
    ps.mnee = Regularizes() && mnee;
    ps.beamSegments = Regularizes() && beamSegments;
    ps.nearSpecular = Regularizes() && nearSpecular;
    return ps;
}

namespace {

// ---- Text forms of the value types ----

template <typename E>
struct EnumNames;
template <>
struct EnumNames<IntegratorKind> {
    static constexpr const char *names[] = {"path", "regpath"};
};
template <>
struct EnumNames<LightStrategy> {
    static constexpr const char *names[] = {"mis", "nee", "bsdf"};
};
template <>
struct EnumNames<DeviceKind> {
    static constexpr const char *names[] = {"auto", "cpu", "cuda"};
};
template <>
struct EnumNames<CpuTracer> {
    static constexpr const char *names[] = {"embree", "bvh"};
};

template <typename E>
std::string ExpectedNames() {
    std::string s;
    for (const char *n : EnumNames<E>::names) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
}

template <typename E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
bool Parse(const std::string &text, E *v, std::string *why) {
    int i = 0;
    for (const char *n : EnumNames<E>::names) {
        if (text == n) {
            *v = E(i);
            return true;
        }
        ++i;
    }
    *why = "expected one of " + ExpectedNames<E>();
    return false;
}
template <typename E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
std::string Format(E v) {
    return EnumNames<E>::names[int(v)];
}

// Integers and floating point: the whole text must be the number (from_chars rejects "12x").
template <typename T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, int> = 0>
bool Parse(const std::string &text, T *v, std::string *why) {
    const char *b = text.data(), *e = text.data() + text.size();
    T x{};
    auto [p, ec] = std::from_chars(b, e, x);
    if (ec != std::errc() || p != e || text.empty()) {
        *why = std::is_integral_v<T> ? "expected an integer" : "expected a number";
        return false;
    }
    if constexpr (std::is_floating_point_v<T>)
        if (!std::isfinite(x)) {
            *why = "expected a finite number";
            return false;
        }
    *v = x;
    return true;
}
template <typename T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>, int> = 0>
std::string Format(T v) {
    std::ostringstream o;
    o.precision(9);
    o << v;
    return o.str();
}

bool Parse(const std::string &text, bool *v, std::string *why) {
    if (text == "true" || text == "1") { *v = true; return true; }
    if (text == "false" || text == "0") { *v = false; return true; }
    *why = "expected true or false";
    return false;
}
std::string Format(bool v) { return v ? "true" : "false"; }

// ---- The settings, each once: name, field, check ----

// Calls f(info, field, check) for every setting; check(value, &why) returns false when invalid.
template <typename S, typename F>
void ForEachSetting(S &s, F &&f) {
    auto any = [](const auto &, std::string *) { return true; };
    auto range = [](auto lo, auto hi, bool loOpen = false) {
        return [=](const auto &v, std::string *why) {
            if ((loOpen ? v > lo : v >= lo) && v <= hi) return true;
            std::ostringstream o;
            o << "must be " << (loOpen ? "> " : ">= ") << lo << " and <= " << hi;
            *why = o.str();
            return false;
        };
    };
    const std::vector<SettingInfo> &info = RenderSettingInfos();
    int i = 0;
    f(info[i++], s.integrator, any);
    f(info[i++], s.maxDepth, range(0, 100000));
    f(info[i++], s.lightStrategy, any);
    f(info[i++], s.regRadius, range(0.0, 1e30, true));   // 0: auto (ResolvedRegRadius)
    f(info[i++], s.regLambda, range(0.0, 1.0));
    f(info[i++], s.regAngle, range(0.0, 90.0, true));
    f(info[i++], s.regFootprint, range(0.0, 1e6));       // -1: auto (ResolvedRegFootprint)
    f(info[i++], s.mnee, any);
    f(info[i++], s.beamSegments, any);
    f(info[i++], s.nearSpecular, any);
    f(info[i++], s.seed, any);
    f(info[i++], s.spp, range(1, 1 << 24));
    f(info[i++], s.timeLimit, range(0.0, 1e9));
    f(info[i++], s.threads, range(0, 4096));
    f(info[i++], s.device, any);
    f(info[i++], s.cpuTracer, any);
    f(info[i++], s.progress, any);
}

}  // namespace

const std::vector<SettingInfo> &RenderSettingInfos() {
    static const std::vector<SettingInfo> infos = {
        {"integrator", "path or regpath (default: the scene's Integrator, else path)", true},
        {"maxdepth", "maximum path depth (default: the scene's, else 5)", true},
        {"light-strategy", "direct-light techniques: mis, nee or bsdf (diagnosis; default mis)", true},
        {"reg-radius", "regpath: initial radius r0 in world units (default auto: 0.04 x the scene's diagonal; given, it turns the footprint kernels off unless --reg-footprint is given too)", true},
        {"reg-lambda", "regpath: shrink exponent lambda, r_N = r0 N^-lambda (default 1/6; 1/8 in scenes with a collimated light)", true},
        {"reg-angle", "regpath: initial angle sigma0 in degrees for lights at infinity (default 2)", true},
        {"reg-footprint", "regpath: kernels from the pixel's footprint, blurring by at most K N^-lambda pixels (default auto: 16 unless a radius is given; 0: r0 everywhere)", true},
        {"mnee", "regpath: manifold next-event estimation through refractive chains (true or false; default true)", true},
        {"beam-segments", "regpath: collimated beams in media sampled along ray segments (true or false; default true)", true},
        {"near-specular", "regpath: rough conductors, dielectrics and coats with alpha below 0.1 (after a non-specular vertex) and smooth coats of coateddiffuse/coatedconductor (everywhere) widened toward the kernel's angle for delta lights (true or false; default true)", true},
        {"seed", "random seed (default: the scene's Sampler \"seed\", else 0)", true},
        {"spp", "samples per pixel = passes (default: the scene's Sampler \"pixelsamples\")", false},
        {"time", "time budget in seconds: stop at the first pass boundary after it", false},
        {"threads", "CPU threads (default: all cores)", false},
        {"device", "cpu, cuda or auto (default: auto, the GPU when one is usable)", false},
        {"tracer", "CPU ray tracer: embree, or bvh (the traversal the CUDA kernel runs)", false},
        {"progress", "progress line on stderr (true or false)", false},
    };
    return infos;
}

// "auto" for a setting the scene resolves (reg-radius 0, reg-footprint -1).
bool IsAutoSetting(const RenderSettings &s, const char *name) {
    return (!std::strcmp(name, "reg-radius") && !(s.regRadius > 0)) || (!std::strcmp(name, "reg-footprint") && s.regFootprint < 0);
}

bool SetRenderSetting(RenderSettings &s, const std::string &name, const std::string &value, std::string *error) {
    if (value == "auto" && (name == "reg-radius" || name == "reg-footprint")) {
        if (name == "reg-radius") s.regRadius = 0;
        else s.regFootprint = -1;
        return true;
    }
    bool found = false, ok = false;
    ForEachSetting(s, [&](const SettingInfo &info, auto &field, auto check) {
        if (found || name != info.name) return;
        found = true;
        std::string why;
        std::decay_t<decltype(field)> v = field;
        ok = Parse(value, &v, &why) && check(v, &why);
        if (ok) field = v;
        else *error = std::string(info.name) + " \"" + value + "\": " + why;
    });
    if (!found) *error = "unknown setting \"" + name + "\"";
    return ok;
}

std::string RenderSettingValue(const RenderSettings &s, const std::string &name) {
    std::string out;
    ForEachSetting(s, [&](const SettingInfo &info, const auto &field, auto) {
        if (name == info.name) out = IsAutoSetting(s, info.name) ? "auto" : Format(field);
    });
    return out;
}

std::string DescribeRenderSettings(const RenderSettings &s) {
    std::string out;
    ForEachSetting(s, [&](const SettingInfo &info, const auto &field, auto) {
        std::string value = Format(field);
        if (IsAutoSetting(s, info.name)) {   // with what it resolves to
            double resolved = std::strcmp(info.name, "reg-radius") ? s.ResolvedRegFootprint() : s.ResolvedRegRadius();
            value = "auto (" + Format(resolved) + ")";
        }
        out += (out.empty() ? "" : ", ") + std::string(info.name) + " " + value;
    });
    return out;
}

uint64_t HashRenderSettings(const RenderSettings &s, uint64_t h) {
    auto mix = [&](const std::string &text) {
        for (unsigned char c : text) { h ^= c; h *= 1099511628211ull; }
        h ^= '|'; h *= 1099511628211ull;
    };
    ForEachSetting(s, [&](const SettingInfo &info, const auto &field, auto) {
        if (info.affectsImage) mix(std::string(info.name) + "=" + Format(field));
    });
    return h;
}

bool ParseIntegratorName(const std::string &name, IntegratorKind *kind) {
    std::string why;
    return Parse(name, kind, &why);
}

const char *IntegratorName(IntegratorKind k) { return EnumNames<IntegratorKind>::names[int(k)]; }

}  // namespace lu
