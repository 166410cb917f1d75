// Lucerna CPU microbenchmarks (Google Benchmark): the per-sample building blocks of the path
// tracer on real data (the shared Cornell box: its area light, diffuse materials and surface
// points found by camera rays), so that optimizations of one piece can be measured in isolation.
//     build-perf/bench/lucerna_micro_bench [--benchmark_filter=Sampler]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <memory>
#include <random>
#include <vector>

#include "lucerna/scene/sampler_build.h"
#include "lucerna/backend/cpu/embree_scene.h"
#include "lucerna/integrators/path.h"
#include "lucerna/scene/builder.h"

using namespace lu;

namespace {

// ---- Shared fixture: the Cornell box and surface points seen by the camera ----

struct CornellData {
    std::unique_ptr<HostScene> host;
    SceneView view;
    std::unique_ptr<EmbreeScene> embree;
    std::vector<SurfaceInteraction> points;   // first hits of camera rays, with a material
    std::vector<SampledWavelengths> lambdas;
    std::vector<Vec2f> u2;
    std::vector<Float> u1;
};

CornellData &Cornell() {
    static CornellData *data = [] {
        auto *d = new CornellData;
        Diagnostics diag;
        diag.quiet = true;
        BuildOptions opts;
        opts.resX = opts.resY = 64;
        d->host = LoadScene(LUCERNA_DATA_DIR "/scenes/bitterli-cornell-box/scene-v4.pbrt", diag, opts);
        d->view = d->host->View();
        d->embree = std::make_unique<EmbreeScene>(d->view);
        EmbreeTracer tracer{d->embree.get()};
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> uni(0.f, 0.99999f);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                Ray ray;
                if (!GenerateRay(d->view.camera, Vec2f(x + uni(rng), y + uni(rng)), Vec2f(0.5f, 0.5f), &ray)) continue;
                HitRecord hit;
                if (!tracer.Intersect(ray, &hit)) continue;
                SurfaceInteraction si = ComputeInteraction(d->view, hit, ray);
                if (si.material == NoIndex || si.areaLight != NoIndex) continue;
                d->points.push_back(si);
            }
        for (size_t i = 0; i < 4096; ++i) {
            d->lambdas.push_back(SampledWavelengths::SampleVisible(uni(rng)));
            d->u2.push_back(Vec2f(uni(rng), uni(rng)));
            d->u1.push_back(uni(rng));
        }
        return d;
    }();
    return *data;
}

// ---- Samplers ----

// Arguments: samples per pixel, image resolution (square). Each iteration is one Get1D (or Get2D)
// in a pixel sample of 20 dimensions, pixels visited in scanline order.
template <bool TwoD>
void SamplerLoop(benchmark::State &state, const char *name) {
    int spp = int(state.range(0)), res = int(state.range(1));
    Sampler s = MakeSampler(name, spp, 0, res, res);
    int x = 0, y = 0, index = 0, dims = 0;
    float acc = 0;
    s.StartPixelSample(0, 0, 0);
    for (auto _ : state) {
        if (dims == 20) {
            dims = 0;
            if (++x == res) { x = 0; if (++y == res) { y = 0; index = (index + 1) % spp; } }
            s.StartPixelSample(x, y, index);
        }
        if constexpr (TwoD) {
            Vec2f u = s.Get2D();
            acc += u.x + u.y;
        } else {
            acc += s.Get1D();
        }
        ++dims;
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}

void BM_ZSobolGet1D(benchmark::State &state) { SamplerLoop<false>(state, "zsobol"); }
void BM_ZSobolGet2D(benchmark::State &state) { SamplerLoop<true>(state, "zsobol"); }
void BM_IndependentGet1D(benchmark::State &state) { SamplerLoop<false>(state, "independent"); }
BENCHMARK(BM_ZSobolGet1D)->Args({16, 32})->Args({64, 128})->Args({8192, 128})->Args({64, 1024});
BENCHMARK(BM_ZSobolGet2D)->Args({64, 128})->Args({8192, 128});
BENCHMARK(BM_IndependentGet1D)->Args({64, 128});

// Arguments: spp, resolution, digit-shuffle level (0 scalar, 1 AVX2, 2 AVX-512, 3 AVX-512 VBMI; capped to the CPUs).
void BM_ZSobolSampleIndex(benchmark::State &state) {
    int spp = int(state.range(0)), res = int(state.range(1));
    Sampler s = MakeSampler("zsobol", spp, 0, res, res);
    s.simd = uint8_t(std::min<int64_t>(state.range(2), s.simd));
    state.SetLabel("level " + std::to_string(int(s.simd)));
    s.StartPixelSample(res / 3, res / 5, spp / 3);
    uint64_t acc = 0;
    for (auto _ : state) {
        acc += s.ZSobolSampleIndex();
        s.dimension = (s.dimension + 1) & 63;
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ZSobolSampleIndex)->Args({64, 128, 3})->Args({8192, 128, 0})->Args({8192, 128, 1})->Args({8192, 128, 2})->Args({8192, 128, 3});

void BM_SampleVisibleWavelengths(benchmark::State &state) {
    Float u = 0.1234f, acc = 0;
    for (auto _ : state) {
        SampledWavelengths w = SampledWavelengths::SampleVisible(u);
        acc += w.lambda[3] + w.pdf[2];
        u += 0.618034f;
        if (u >= 1) u -= 1;
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleVisibleWavelengths);

// ---- Light sampling (the Cornell box's area light: two triangles) ----

void BM_SampleLiAreaLight(benchmark::State &state) {
    CornellData &d = Cornell();
    const SceneView &s = d.view;
    size_t i = 0;
    Float acc = 0;
    for (auto _ : state) {
        const SurfaceInteraction &si = d.points[i % d.points.size()];
        Float pmf;
        uint32_t li = SampleLight(s, d.u1[i & 4095], &pmf);
        LightLiSample ls;
        LightSampleContext ctx;
        ctx.p = si.p; ctx.n = si.n; ctx.ns = si.ns;
        if (SampleLi(s.lights[li], s, ctx, d.u2[i & 4095], d.lambdas[i & 4095], &ls)) acc += ls.pdf + ls.L[0];
        ++i;
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleLiAreaLight);

void BM_PDFLiAreaLight(benchmark::State &state) {
    CornellData &d = Cornell();
    const SceneView &s = d.view;
    // Directions towards sampled light points (what a BSDF-sampled ray hitting the light gives).
    struct Query { LightSampleContext ctx; Vec3f wi, p, n; uint32_t li; };
    std::vector<Query> q;
    for (size_t i = 0; i < 4096; ++i) {
        const SurfaceInteraction &si = d.points[i % d.points.size()];
        Float pmf;
        uint32_t li = SampleLight(s, d.u1[i], &pmf);
        LightSampleContext ctx;
        ctx.p = si.p; ctx.n = si.n; ctx.ns = si.ns;
        LightLiSample ls;
        if (SampleLi(s.lights[li], s, ctx, d.u2[i], d.lambdas[i], &ls)) q.push_back({ctx, ls.wi, ls.pLight, ls.nLight, li});
    }
    size_t i = 0;
    Float acc = 0;
    for (auto _ : state) {
        const Query &e = q[i++ % q.size()];
        acc += PDF_Li(s.lights[e.li], s, e.ctx, e.wi, e.p, e.n);
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PDFLiAreaLight);

// ---- Materials (the Cornell box's diffuse RGB reflectances) ----

void BM_MakeBSDF(benchmark::State &state) {
    CornellData &d = Cornell();
    size_t i = 0;
    Float acc = 0;
    for (auto _ : state) {
        const SurfaceInteraction &si = d.points[i % d.points.size()];
        SampledWavelengths lambda = d.lambdas[i & 4095];
        BSDF bsdf;
        if (MakeBSDF(d.view.materials[si.material], si, lambda, d.view, &bsdf)) acc += bsdf.shadingFrame.x.x;
        ++i;
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MakeBSDF);

// f + PDF (what next-event estimation evaluates) and Sample_f, on prebuilt BSDFs.
void BM_BSDFEvalAndSample(benchmark::State &state) {
    CornellData &d = Cornell();
    std::vector<BSDF> bsdfs(d.points.size());
    for (size_t k = 0; k < d.points.size(); ++k) {
        SampledWavelengths lambda = d.lambdas[k & 4095];
        MakeBSDF(d.view.materials[d.points[k].material], d.points[k], lambda, d.view, &bsdfs[k]);
    }
    size_t i = 0;
    Float acc = 0;
    for (auto _ : state) {
        size_t k = i % d.points.size();
        const SurfaceInteraction &si = d.points[k];
        Vec3f wi = Normalize(si.ns + Vec3f(d.u2[i & 4095].x - 0.5f, d.u2[i & 4095].y - 0.5f, 0.3f));
        SampledSpectrum f = bsdfs[k].f(si.wo, wi);
        Float pdf = bsdfs[k].PDF(si.wo, wi);
        BSDFSample bs;
        if (bsdfs[k].Sample_f(si.wo, d.u1[i & 4095], d.u2[(i + 7) & 4095], &bs)) acc += bs.pdf;
        acc += f[0] + pdf;
        ++i;
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BSDFEvalAndSample);

// ---- Ray queries (Embree): rays from the camera's first hits in random directions ----

std::vector<Ray> SecondaryRays(CornellData &d) {
    std::vector<Ray> rays;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uni(0.f, 1.f);
    for (size_t i = 0; i < 4096; ++i) {
        const SurfaceInteraction &si = d.points[i % d.points.size()];
        Frame f = Frame::FromZ(si.n);
        Ray r;
        r.d = f.FromLocal(SampleCosineHemisphere(Vec2f(uni(rng), uni(rng))));
        r.o = OffsetRayOrigin(si.p, si.n, r.d);
        r.tMax = Infinity;
        rays.push_back(r);
    }
    return rays;
}

void BM_EmbreeIntersect(benchmark::State &state) {
    CornellData &d = Cornell();
    std::vector<Ray> rays = SecondaryRays(d);
    size_t i = 0;
    Float acc = 0;
    for (auto _ : state) {
        HitRecord hit;
        if (d.embree->Intersect(rays[i++ & 4095], &hit)) acc += hit.t;
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EmbreeIntersect);

void BM_EmbreeOccluded(benchmark::State &state) {
    CornellData &d = Cornell();
    std::vector<Ray> rays = SecondaryRays(d);
    for (Ray &r : rays) r.tMax = 0.5f;
    size_t i = 0;
    int acc = 0;
    for (auto _ : state) acc += d.embree->Occluded(rays[i++ & 4095]);
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EmbreeOccluded);

// ---- Whole camera samples (1 thread, the scene's maxdepth): samples per second ----

// Argument: spp; the second benchmark uses the independent sampler (what pbrt-v4's reference
// renders used), so the difference is the cost of ZSobol in context.
void RenderSampleCornell(benchmark::State &state, const char *samplerName) {
    CornellData &d = Cornell();
    EmbreeTracer tracer{d.embree.get()};
    int spp = int(state.range(0));
    Sampler sampler = MakeSampler(samplerName, spp, 0, 64, 64);
    PathSettings ps;
    ps.maxDepth = d.host->settings.maxDepth;
    PathStats st;
    int x = 0, y = 0;
    uint32_t index = 0;
    Float acc = 0;
    for (auto _ : state) {
        CameraSampleResult r = RenderSample(x, y, index, sampler, d.view, tracer, ps, st);
        acc += r.L[0];
        if (++x == 64) { x = 0; if (++y == 64) { y = 0; index = (index + 1) % uint32_t(spp); } }
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(state.iterations());
    state.counters["rays/sample"] = benchmark::Counter(double(st.rays) / double(state.iterations()));
}
void BM_RenderSampleCornell(benchmark::State &state) { RenderSampleCornell(state, "zsobol"); }
void BM_RenderSampleCornellIndependent(benchmark::State &state) { RenderSampleCornell(state, "independent"); }
BENCHMARK(BM_RenderSampleCornell)->Arg(64)->Arg(8192);
BENCHMARK(BM_RenderSampleCornellIndependent)->Arg(8192);

}  // namespace

BENCHMARK_MAIN();
