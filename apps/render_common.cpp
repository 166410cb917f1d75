// Lucerna CLI: scene loading, settings and backend dispatch shared by `render` and `converge`.
#include "apps/render_common.h"

#include <cctype>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "apps/commands.h"
#include "apps/json.h"
#include "lucerna/backend/cpu/cpu_render.h"
#if defined(LUCERNA_HAVE_CUDA)
#include "lucerna/backend/cuda/cuda_api.h"
#include "lucerna/backend/cuda/cuda_render.h"
#include "lucerna/backend/cuda/device_buffer.h"
#endif
#include "lucerna/image/image.h"
#include "lucerna/render/rejected_sample.h"
#include "lucerna/render/distributed.h"

namespace lu::app {

namespace {

uint64_t Fnv1a(const std::string &s, uint64_t h = 1469598103934665603ull) {
    for (unsigned char c : s) { h ^= c; h *= 1099511628211ull; }
    return h;
}

// "WxH" exactly: decimal digits, 'x' or 'X', decimal digits; both positive.
bool ParseResolution(const std::string &s, int *w, int *h) {
    size_t x = s.find_first_of("xX");
    if (x == std::string::npos) return false;
    auto number = [](const std::string &t, int *v) {
        if (t.empty() || t.size() > 9) return false;
        for (char c : t)
            if (c < '0' || c > '9') return false;
        *v = std::stoi(t);
        return *v > 0;
    };
    return number(s.substr(0, x), w) && number(s.substr(x + 1), h);
}

bool Given(const SettingOverrides &o, const std::string &name) {
    for (const auto &[n, v] : o)
        if (n == name) return true;
    return false;
}

}  // namespace

void AddSettingOptions(CLI::App *sub, SettingOverrides *overrides, const std::vector<std::string> &exclude) {
    for (const SettingInfo &info : RenderSettingInfos()) {
        std::string name = info.name;
        if (std::find(exclude.begin(), exclude.end(), name) != exclude.end()) continue;
        sub->add_option_function<std::string>("--" + name, [overrides, name](const std::string &v) {
            overrides->emplace_back(name, v);
        }, info.help);
    }
    if (std::find(exclude.begin(), exclude.end(), "progress") == exclude.end())
        sub->add_flag_callback("-q,--quiet", [overrides] { overrides->emplace_back("progress", "false"); },
                               "No progress line (progress false)");
}

int PrepareRender(const std::string &sceneFile, const std::string &res, const SettingOverrides &overrides, Prepared *out) {
    Diagnostics diag;
    BuildOptions opts;
    if (!res.empty()) {
        int w = 0, h = 0;
        if (!ParseResolution(res, &w, &h) || int64_t(w) * h > (int64_t(1) << 27)) {
            std::fprintf(stderr, "lucerna: --res %s: expected WxH with positive sizes (at most 2^27 pixels)\n", res.c_str());
            return ExitBadInput;
        }
        opts.resX = w;
        opts.resY = h;
    }
    // The command line's settings are checked before the scene is read.
    RenderSettings check;
    for (const auto &[name, value] : overrides) {
        std::string error;
        if (!SetRenderSetting(check, name, value, &error)) {
            std::fprintf(stderr, "lucerna: --%s\n", error.c_str());
            return ExitBadInput;
        }
    }
    // ---- Device: cuda, cpu, or auto (the GPU when one is usable) ----
    DeviceKind device = check.device;
    std::string gpuName, whyNot = "this build has no CUDA backend";
    bool haveGpu = false;
#if defined(LUCERNA_HAVE_CUDA)
    if (device != DeviceKind::CPU) haveGpu = CudaDeviceAvailable(&gpuName);
    if (!haveGpu) whyNot = gpuName.rfind("no CUDA device: ", 0) == 0 ? gpuName.substr(16) : gpuName;
#endif
    if (device == DeviceKind::CUDA && !haveGpu) {
        std::fprintf(stderr, "lucerna: --device cuda: no usable CUDA GPU (%s); use --device cpu or auto\n", whyNot.c_str());
        return ExitBadInput;
    }
    static bool announced = false;   // once per process (converge prepares several renders)
    out->deviceName = haveGpu ? "cuda " + gpuName : "cpu";
    if (!announced) {
        announced = true;
        if (haveGpu) std::fprintf(stderr, "device: %s\n", gpuName.c_str());
        else if (device == DeviceKind::Auto) std::fprintf(stderr, "device: cpu (no CUDA GPU: %s)\n", whyNot.c_str());
        else std::fprintf(stderr, "device: cpu\n");
    }
    try {
        out->scene = LoadScene(sceneFile, diag, opts);
    } catch (const SceneError &e) {
        std::fprintf(stderr, "%s\n", e.Format().c_str());
        return ExitBadInput;
    }
    RenderSettings &s = out->settings;
    s = out->scene->settings;
    for (const auto &[name, value] : overrides) {
        std::string error;
        SetRenderSetting(s, name, value, &error);   // checked above
    }
    if (Given(overrides, "time") && !Given(overrides, "spp")) s.spp = 1 << 24;   // time-bounded: passes until the budget
    if (!s.Regularizes())   // a beam's emission is a Dirac delta in direction: only the regularized kernel reaches it
        for (const FileLoc &loc : out->scene->collimatedLightLocs)
            diag.Warning(loc, "collimated light: path cannot connect to a collimated beam (it renders black); use regpath");
    s.device = haveGpu ? DeviceKind::CUDA : DeviceKind::CPU;

    const Sampler &smp = out->scene->sampler;
    std::ostringstream key;
    key << std::filesystem::absolute(sceneFile).string() << '|' << out->scene->film.width << 'x' << out->scene->film.height
        << '|' << out->scene->stats.samplerName << '|' << int(smp.kind) << '|' << smp.samplesPerPixel << '|'
        << int(smp.randomize) << '|' << smp.xPixelSamples << 'x' << smp.yPixelSamples << '|' << smp.jitter;
    out->checkpointKey = HashRenderSettings(s, Fnv1a(key.str()));
    out->sceneFile = sceneFile;
    return ExitOk;
}

namespace {

int RunLocalBackend(Prepared &prep, FilmAccumulator &film, const RenderControl &control, RenderOutcome *out) {
#if defined(LUCERNA_HAVE_CUDA)
    if (prep.settings.device == DeviceKind::CUDA) {
        try {
            out->stats = RenderCUDA(*prep.scene, prep.settings, film, control);
        } catch (const CudaError &e) {
            std::fprintf(stderr, "lucerna: CUDA error: %s\n", e.what());
            return ExitInternal;
        }
    } else
#endif
        out->stats = RenderCPU(*prep.scene, prep.settings, film, control);
    out->passes = film.passes;
    return ExitOk;
}

}  // namespace

// Under mpirun: this rank's share through render/distributed.h; the sums end on rank 0.
int RunBackend(Prepared &prep, FilmAccumulator &film, const RenderControl &control, RenderOutcome *out) {
    if (!MpiSession::Active()) return RunLocalBackend(prep, film, control, out);
    const FilmData &fd = prep.scene->film;
    if (film.width != fd.width || film.height != fd.height) film.Resize(fd.width, fd.height);
    int rc = ExitOk;
    BackendFn backend = [&](const RenderSettings &s, FilmAccumulator &f, const RenderControl &c) {
        RenderSettings keep = prep.settings;
        prep.settings = s;
        rc = RunLocalBackend(prep, f, c, out);
        prep.settings = keep;
        if (rc != ExitOk) throw DistributedError("rank " + std::to_string(MpiSession::Rank()) + ": the backend failed");
        return out->stats;
    };
    try {
        out->stats = RunDistributed(prep.settings, prep.checkpointKey, film, control, backend);
    } catch (const DistributedError &e) {
        std::fprintf(stderr, "lucerna: error: %s\n", e.what());
        return ExitBadInput;
    }
    out->passes = film.passes;
    out->writer = MpiSession::Rank() == 0;
    if (MpiSession::Size() > 1) prep.deviceName += " (rank 0 of " + std::to_string(MpiSession::Size()) + " MPI ranks)";
    return ExitOk;
}

std::string DefaultOutputName(const Prepared &prep) {
    std::string f = prep.scene->outputFilename;
    if (f.empty()) f = std::filesystem::path(prep.sceneFile).stem().string() + ".exr";
    return f;
}

std::string PngPreviewPath(const std::string &output) {
    return std::filesystem::path(output).replace_extension(".png").string();
}

std::string Lower(std::string s) {
    for (char &c : s) c = char(std::tolower((unsigned char)c));
    return s;
}

void WriteOutputs(const Prepared &prep, const FilmAccumulator &film, const RenderOutcome &out, const std::string &path, bool png) {
    Image img = film.Resolve(prep.scene->View().film);
    // pbrt-v4's WriteEXR: chromaticities for every film color space but sRGB (PNG: the film's
    // RGB with the sRGB curve, no conversion, as pbrt-v4's WritePNG).
    if (prep.scene->filmColorSpace != ColorSpaceId::SRGB) {
        const RGBColorSpace &cs = GetRGBColorSpace(prep.scene->filmColorSpace);
        img.hasChromaticities = true;
        img.chromaticities = {float(cs.r[0]), float(cs.r[1]), float(cs.g[0]), float(cs.g[1]),
                              float(cs.b[0]), float(cs.b[1]), float(cs.w[0]), float(cs.w[1])};
    }
    ImageMetadata meta;
    meta["lucerna.spp"] = std::to_string(film.passes);
    meta["lucerna.integrator"] = IntegratorName(prep.settings.integrator);
    meta["lucerna.seed"] = std::to_string(prep.settings.seed);
    meta["lucerna.scene"] = prep.sceneFile;
    meta["lucerna.settings"] = DescribeRenderSettings(prep.settings);
    meta["lucerna.interrupted"] = out.stats.interrupted ? "1" : "0";
    meta["lucerna.rejectedSamples"] = std::to_string(out.stats.rejected);
    auto parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    WriteImage(path, img, meta);
    if (png && Lower(std::filesystem::path(path).extension().string()) != ".png") WritePNG(PngPreviewPath(path), img);
}

std::string SummaryLine(const Prepared &prep, const RenderOutcome &o) {
    const RenderStats &s = o.stats;
    double sec = std::max(1e-9, s.seconds);
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "spp %u  seconds %.3f  samples/s %.4g  rays/s %.4g  rejected %" PRIu64 "  bvh %.3fs  device %s  integrator %s",
                  o.passes, s.seconds, s.samples / sec, s.rays / sec, s.rejected, s.buildSeconds, prep.deviceName.c_str(),
                  IntegratorName(prep.settings.integrator));
    std::string line = buf;
    if (prep.settings.Regularizes()) {
        double k = prep.settings.ResolvedRegFootprint();
        if (k > 0) std::snprintf(buf, sizeof buf, "  footprint %.3g px", k);
        else std::snprintf(buf, sizeof buf, "  r0 %.4g", prep.settings.ResolvedRegRadius());
        line += buf;
        std::snprintf(buf, sizeof buf, "  regularized connections %" PRIu64 " (%.2f%% of energy)  MNEE %" PRIu64, s.regConnections,
                      s.totalEnergy > 0 ? 100.0 * s.regEnergy / s.totalEnergy : 0.0, s.mneeConnections);
        line += buf;
    }
    return line;
}

std::string StatsJson(const Prepared &prep, const RenderOutcome &o) {
    const RenderStats &s = o.stats;
    const RenderSettings &rs = prep.settings;
    bool reg = rs.Regularizes();
    double sec = std::max(1e-9, s.seconds);
    JsonObject settings, first, j;
    for (const SettingInfo &info : RenderSettingInfos()) settings.Add(info.name, RenderSettingValue(rs, info.name));
    const RejectedSample &fr = s.firstRejected;
    first.Add("x", fr.x).Add("y", fr.y).Add("depth", fr.depth);
    if (fr.Valid())
        first.Add("cause", RejectCauseName(fr.cause))
            .Add("value", BadValueName(fr.badValue))
            .Add("source", RejectedSource(*prep.scene, fr))
            .Add("message", DescribeRejectedSample(*prep.scene, fr));
    j.Add("scene", prep.sceneFile)
        .Add("integrator", IntegratorName(rs.integrator))
        .Add("device", prep.deviceName)
        .AddRaw("settings", settings.Str())
        .Add("width", prep.scene->film.width)
        .Add("height", prep.scene->film.height)
        .Add("spp", o.passes)
        .Add("seconds", s.seconds)
        .Add("samples", s.samples)
        .Add("samples_per_second", s.samples / sec)
        .Add("rays", s.rays)
        .Add("shadow_rays", s.shadowRays)
        .Add("rays_per_second", s.rays / sec)
        .Add("bvh_build_seconds", s.buildSeconds)
        .Add("rejected_samples", s.rejected)
        .AddRaw("first_rejected", first.Str())
        .Add("regularized_connections", s.regConnections)
        .Add("mnee_connections", s.mneeConnections)
        .Add("reg_radius", reg ? rs.ResolvedRegRadius() : 0.0)
        .Add("reg_footprint_pixels", reg ? rs.ResolvedRegFootprint() : 0.0)
        .Add("reg_lambda", reg ? rs.regLambda : 0.0)
        .Add("reg_angle_degrees", reg ? rs.regAngle : 0.0)
        .Add("regularized_energy_share", s.totalEnergy > 0 ? s.regEnergy / s.totalEnergy : 0.0)
        .Add("interrupted", s.interrupted);
    return j.Pretty() + "\n";
}

}  // namespace lu::app
