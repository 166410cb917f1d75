// Lucerna CLI: scene loading and backend dispatch shared by `render` and `converge`.
#include "apps/render_common.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "apps/commands.h"
#include "lucerna/backend/cpu/cpu_render.h"
#if defined(LUCERNA_HAVE_CUDA)
#include "lucerna/backend/cuda/cuda_api.h"
#include "lucerna/backend/cuda/cuda_render.h"
#include "lucerna/backend/cuda/device_buffer.h"
#endif
#include "lucerna/image/image.h"

namespace lu::app {

namespace {
uint64_t Fnv1a(const std::string &s, uint64_t h = 1469598103934665603ull) {
    for (unsigned char c : s) { h ^= c; h *= 1099511628211ull; }
    return h;
}
}  // namespace

double DefaultRegRadius(const Bounds3f &b) {
    if (b.Empty()) return 0.01;
    return 0.04 * Length(b.Diagonal());   // chosen by bench/reg_radius.sh, see docs/regularization.md
}

int PrepareRender(const RenderRequest &req, Prepared *out) {
    Diagnostics diag;
    BuildOptions opts;
    if (!req.res.empty()) {
        int w = 0, h = 0;
        char x = 0;
        std::istringstream is(req.res);
        if (!(is >> w >> x >> h) || (x != 'x' && x != 'X') || w <= 0 || h <= 0 || int64_t(w) * h > (int64_t(1) << 27)) {
            std::fprintf(stderr, "lucerna: --res %s: expected WxH with positive sizes (at most 2^27 pixels)\n", req.res.c_str());
            return ExitBadInput;
        }
        opts.resX = w;
        opts.resY = h;
    }
    // ---- Device: cuda, cpu, or auto (the GPU when one is usable) ----
    const std::string &device = req.device;
    if (device != "auto" && device != "cpu" && device != "cuda") {
        std::fprintf(stderr, "lucerna: unknown device \"%s\" (expected auto, cpu or cuda)\n", device.c_str());
        return ExitBadInput;
    }
    std::string gpuName, whyNot = "this build has no CUDA backend";
    bool haveGpu = false;
#if defined(LUCERNA_HAVE_CUDA)
    if (device != "cpu") haveGpu = CudaDeviceAvailable(&gpuName);
    if (!haveGpu) whyNot = gpuName.rfind("no CUDA device: ", 0) == 0 ? gpuName.substr(16) : gpuName;
#endif
    if (device == "cuda" && !haveGpu) {
        std::fprintf(stderr, "lucerna: --device cuda: no usable CUDA GPU (%s); use --device cpu or auto\n", whyNot.c_str());
        return ExitBadInput;
    }
    static bool announced = false;   // once per process (converge prepares several renders)
    out->deviceName = haveGpu ? "cuda " + gpuName : "cpu";
    if (!announced) {
        announced = true;
        if (haveGpu) std::fprintf(stderr, "device: %s\n", gpuName.c_str());
        else if (device == "auto") std::fprintf(stderr, "device: cpu (no CUDA GPU: %s)\n", whyNot.c_str());
        else std::fprintf(stderr, "device: cpu\n");
    }
    try {
        out->scene = LoadScene(req.sceneFile, diag, opts);
    } catch (const SceneError &e) {
        std::fprintf(stderr, "%s\n", e.Format().c_str());
        return ExitBadInput;
    }
    const RenderSettings &s = out->scene->settings;
    RenderJob &job = out->job;
    std::string integrator = req.integrator.empty() ? s.integrator : req.integrator;
    if (integrator != "path" && integrator != "regpath") {
        std::fprintf(stderr, "lucerna: unknown integrator \"%s\" (supported: path, regpath)\n", integrator.c_str());
        return ExitBadInput;
    }
    out->integratorName = integrator;
    job.spp = req.spp > 0 ? req.spp : std::max(1, s.spp);
    job.timeLimit = req.time;
    job.seed = uint32_t(req.seed >= 0 ? req.seed : s.seed);
    job.maxDepth = req.maxDepth >= 0 ? req.maxDepth : s.maxDepth;
    job.threads = req.threads;
    job.progress = req.progress;
    job.samplerName = s.sampler;
    job.samplerSpp = std::max(1, s.spp);
    job.regularize = integrator == "regpath";
    job.regLambda = req.regLambda >= 0 ? req.regLambda : s.regLambda;
    double r0 = req.regRadius > 0 ? req.regRadius : s.regRadius;
    job.regRadius = r0 > 0 ? r0 : DefaultRegRadius(out->scene->bounds);
    double angleDeg = req.regAngle > 0 ? req.regAngle : s.regAngle;
    job.regAngle = (angleDeg > 0 ? angleDeg : 2.0) * M_PI / 180;
    if (req.time > 0 && req.spp <= 0) job.spp = 1 << 24;   // time-bounded: passes until the budget

    std::ostringstream key;
    key << std::filesystem::absolute(req.sceneFile).string() << '|' << out->scene->View().film.width << 'x'
        << out->scene->View().film.height << '|' << integrator << '|' << job.seed << '|' << job.maxDepth << '|'
        << job.regRadius << '|' << job.regLambda << '|' << job.regAngle << '|' << job.samplerName << '|' << job.samplerSpp;
    out->sceneHash = Fnv1a(key.str());
    out->sceneFile = req.sceneFile;
    return ExitOk;
}

int RunBackend(Prepared &prep, FilmAccumulator &film, const PassCallback &onPass, RenderOutcome *out) {
#if defined(LUCERNA_HAVE_CUDA)
    if (prep.deviceName.rfind("cuda", 0) == 0) {
        try {
            out->stats = RenderCUDA(*prep.scene, prep.job, film, onPass);
        } catch (const CudaError &e) {
            std::fprintf(stderr, "lucerna: CUDA error: %s\n", e.what());
            return ExitInternal;
        }
    } else
#endif
        out->stats = RenderCPU(*prep.scene, prep.job, film, onPass);
    out->passes = film.passes;
    out->width = film.width;
    out->height = film.height;
    out->integrator = prep.integratorName;
    out->device = prep.deviceName;
    out->sceneFile = prep.sceneFile;
    out->regRadius = prep.job.regRadius;
    out->regLambda = prep.job.regLambda;
    out->regAngle = prep.job.regAngle;
    return ExitOk;
}

std::string DefaultOutputName(const Prepared &prep) {
    std::string f = prep.scene->settings.outputFilename;
    if (f.empty()) f = std::filesystem::path(prep.sceneFile).stem().string() + ".exr";
    return f;
}

void WriteOutputs(const Prepared &prep, const FilmAccumulator &film, const RenderOutcome &out, const std::string &path, bool png) {
    Image img = film.Resolve(prep.scene->View().film);
    ImageMetadata meta;
    meta["lucerna.spp"] = std::to_string(film.passes);
    meta["lucerna.integrator"] = out.integrator;
    meta["lucerna.seed"] = std::to_string(prep.job.seed);
    meta["lucerna.scene"] = prep.sceneFile;
    meta["lucerna.interrupted"] = out.stats.interrupted ? "1" : "0";
    meta["lucerna.rejectedSamples"] = std::to_string(out.stats.rejected);
    auto parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    WriteImage(path, img, meta);
    if (png && std::filesystem::path(path).extension() != ".png") {
        std::string p = std::filesystem::path(path).replace_extension(".png").string();
        WritePNG(p, img);
    }
}

std::string SummaryLine(const RenderOutcome &o) {
    const RenderStats &s = o.stats;
    double sec = std::max(1e-9, s.seconds);
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "spp %u  seconds %.3f  samples/s %.4g  rays/s %.4g  rejected %" PRIu64 "  bvh %.3fs  device %s  integrator %s",
                  o.passes, s.seconds, s.samples / sec, s.rays / sec, s.rejected, s.buildSeconds, o.device.c_str(),
                  o.integrator.c_str());
    std::string line = buf;
    if (o.integrator == "regpath") {
        std::snprintf(buf, sizeof buf, "  r0 %.4g  regularized connections %" PRIu64 " (%.2f%% of energy)", o.regRadius,
                      s.regConnections, s.totalEnergy > 0 ? 100.0 * s.regEnergy / s.totalEnergy : 0.0);
        line += buf;
    }
    return line;
}

std::string StatsJson(const RenderOutcome &o) {
    const RenderStats &s = o.stats;
    double sec = std::max(1e-9, s.seconds);
    std::ostringstream j;
    j.precision(10);
    j << "{\n  \"scene\": \"" << o.sceneFile << "\",\n  \"integrator\": \"" << o.integrator << "\",\n  \"device\": \""
      << o.device << "\",\n  \"width\": " << o.width << ",\n  \"height\": " << o.height << ",\n  \"spp\": " << o.passes
      << ",\n  \"seconds\": " << s.seconds << ",\n  \"samples\": " << s.samples << ",\n  \"samples_per_second\": "
      << s.samples / sec << ",\n  \"rays\": " << s.rays << ",\n  \"shadow_rays\": " << s.shadowRays
      << ",\n  \"rays_per_second\": " << s.rays / sec << ",\n  \"bvh_build_seconds\": " << s.buildSeconds
      << ",\n  \"rejected_samples\": " << s.rejected << ",\n  \"first_rejected\": {\"x\": " << s.firstRejectedX
      << ", \"y\": " << s.firstRejectedY << ", \"depth\": " << s.firstRejectedDepth << "},\n  \"regularized_connections\": "
      << s.regConnections << ",\n  \"reg_radius\": " << (o.integrator == "regpath" ? o.regRadius : 0)
      << ",\n  \"reg_lambda\": " << (o.integrator == "regpath" ? o.regLambda : 0)
      << ",\n  \"reg_angle_degrees\": " << (o.integrator == "regpath" ? Degrees(Float(o.regAngle)) : 0)
      << ",\n  \"regularized_energy_share\": " << (s.totalEnergy > 0 ? s.regEnergy / s.totalEnergy : 0)
      << ",\n  \"interrupted\": " << (s.interrupted ? "true" : "false") << "\n}\n";
    return j.str();
}

}  // namespace lu::app
