// Lucerna scene builder: participating media (MakeNamedMedium), after pbrt-v4's media.cpp
// Create() functions: homogeneous (with the named scattering presets), uniformgrid, rgbgrid, cloud
// and nanovdb (read with NanoVDB, resampled losslessly onto a dense grid), their 16^3 majorant
// grids, and the camera's medium. Shapes resolve their MediumInterface names
// with ResolveMedium.
#include <algorithm>
#include <cmath>

// NanoVDB (Debian's libnanovdb-dev, header-only) reads .nvdb files; zlib-compressed ones too.
#define NANOVDB_USE_ZIP 1
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include "lucerna/scene/build_internal.h"

namespace lu::build {

namespace {

// ---- pbrt-v4's named scattering presets (GetMediumScatteringProperties) ----
// Measured sigma'_s and sigma_a in mm^-1 (RGB), used as sigma_s and sigma_a.
struct MeasuredMedium {
    const char *name;
    Float sigmaPrimeS[3], sigmaA[3];
};
// Jensen, Marschner, Levoy, Hanrahan, "A Practical Model for Subsurface Light Transport", SIGGRAPH
// 2001, and Narasimhan, Gupta, Donner, Ramamoorthi, Nayar, Jensen, "Acquiring Scattering
// Properties of Participating Media by Dilution", SIGGRAPH 2006.
const MeasuredMedium kPresets[] = {
    {"Apple", {2.29f, 2.39f, 1.97f}, {0.0030f, 0.0034f, 0.046f}},
    {"Chicken1", {0.15f, 0.21f, 0.38f}, {0.015f, 0.077f, 0.19f}},
    {"Chicken2", {0.19f, 0.25f, 0.32f}, {0.018f, 0.088f, 0.20f}},
    {"Cream", {7.38f, 5.47f, 3.15f}, {0.0002f, 0.0028f, 0.0163f}},
    {"Ketchup", {0.18f, 0.07f, 0.03f}, {0.061f, 0.97f, 1.45f}},
    {"Marble", {2.19f, 2.62f, 3.00f}, {0.0021f, 0.0041f, 0.0071f}},
    {"Potato", {0.68f, 0.70f, 0.55f}, {0.0024f, 0.0090f, 0.12f}},
    {"Skimmilk", {0.70f, 1.22f, 1.90f}, {0.0014f, 0.0025f, 0.0142f}},
    {"Skin1", {0.74f, 0.88f, 1.01f}, {0.032f, 0.17f, 0.48f}},
    {"Skin2", {1.09f, 1.59f, 1.79f}, {0.013f, 0.070f, 0.145f}},
    {"Spectralon", {11.6f, 20.4f, 14.9f}, {0.00f, 0.00f, 0.00f}},
    {"Wholemilk", {2.55f, 3.21f, 3.77f}, {0.0011f, 0.0024f, 0.014f}},
    {"Lowfat Milk", {0.89187f, 1.5136f, 2.532f}, {0.002875f, 0.00575f, 0.0115f}},
    {"Reduced Milk", {2.4858f, 3.1669f, 4.5214f}, {0.0025556f, 0.0051111f, 0.012778f}},
    {"Regular Milk", {4.5513f, 5.8294f, 7.136f}, {0.0015333f, 0.0046f, 0.019933f}},
    {"Espresso", {0.72378f, 0.84557f, 1.0247f}, {4.7984f, 6.5751f, 8.8493f}},
    {"Mint Mocha Coffee", {0.31602f, 0.38538f, 0.48131f}, {3.772f, 5.8228f, 7.82f}},
    {"Lowfat Soy Milk", {0.30576f, 0.34233f, 0.61664f}, {0.0014375f, 0.0071875f, 0.035937f}},
    {"Regular Soy Milk", {0.59223f, 0.73866f, 1.4693f}, {0.0019167f, 0.0095833f, 0.065167f}},
    {"Lowfat Chocolate Milk", {0.64925f, 0.83916f, 1.1057f}, {0.0115f, 0.0368f, 0.1564f}},
    {"Regular Chocolate Milk", {1.4585f, 2.1289f, 2.9527f}, {0.010063f, 0.043125f, 0.14375f}},
    {"Coke", {8.9053e-05f, 8.372e-05f, 0}, {0.10014f, 0.16503f, 0.2468f}},
    {"Pepsi", {6.1697e-05f, 4.2564e-05f, 0}, {0.091641f, 0.14158f, 0.20729f}},
    {"Sprite", {6.0306e-06f, 6.4139e-06f, 6.5504e-06f}, {0.001886f, 0.0018308f, 0.0020025f}},
    {"Gatorade", {0.0024574f, 0.003007f, 0.0037325f}, {0.024794f, 0.019289f, 0.008878f}},
    {"Chardonnay", {1.7982e-05f, 1.3758e-05f, 1.2023e-05f}, {0.010782f, 0.011855f, 0.023997f}},
    {"White Zinfandel", {1.7501e-05f, 1.9069e-05f, 1.288e-05f}, {0.012072f, 0.016184f, 0.019843f}},
    {"Merlot", {2.1129e-05f, 0, 0}, {0.11632f, 0.25191f, 0.29434f}},
    {"Budweiser Beer", {2.4356e-05f, 2.4079e-05f, 1.0564e-05f}, {0.011492f, 0.024911f, 0.057786f}},
    {"Coors Light Beer", {5.0922e-05f, 4.301e-05f, 0}, {0.006164f, 0.013984f, 0.034983f}},
    {"Clorox", {0.0024035f, 0.0031373f, 0.003991f}, {0.0033542f, 0.014892f, 0.026297f}},
    {"Apple Juice", {0.00013612f, 0.00015836f, 0.000227f}, {0.012957f, 0.023741f, 0.052184f}},
    {"Cranberry Juice", {0.00010402f, 0.00011646f, 7.8139e-05f}, {0.039437f, 0.094223f, 0.12426f}},
    {"Grape Juice", {5.382e-05f, 0, 0}, {0.10404f, 0.23958f, 0.29325f}},
    {"Ruby Grapefruit Juice", {0.011002f, 0.010927f, 0.011036f}, {0.085867f, 0.18314f, 0.25262f}},
    {"White Grapefruit Juice", {0.22826f, 0.23998f, 0.32748f}, {0.0138f, 0.018831f, 0.056781f}},
    {"Shampoo", {0.0007176f, 0.0008303f, 0.0009016f}, {0.014107f, 0.045693f, 0.061717f}},
    {"Strawberry Shampoo", {0.00015671f, 0.00015947f, 1.518e-05f}, {0.01449f, 0.05796f, 0.075823f}},
    {"Head & Shoulders Shampoo", {0.023805f, 0.028804f, 0.034306f}, {0.084621f, 0.15688f, 0.20365f}},
    {"Lemon Tea Powder", {0.040224f, 0.045264f, 0.051081f}, {2.4288f, 4.5757f, 7.2127f}},
    {"Orange Powder", {0.00015617f, 0.00017482f, 0.0001762f}, {0.001449f, 0.003441f, 0.007863f}},
    {"Pink Lemonade Powder", {0.00012103f, 0.00013073f, 0.00012528f}, {0.001165f, 0.002366f, 0.003195f}},
    {"Cappuccino Powder", {1.8436f, 2.5851f, 2.1662f}, {35.844f, 49.547f, 61.084f}},
    {"Salt Powder", {0.027333f, 0.032451f, 0.031979f}, {0.28415f, 0.3257f, 0.34148f}},
    {"Sugar Powder", {0.00022272f, 0.00025513f, 0.000271f}, {0.012638f, 0.031051f, 0.050124f}},
    {"Suisse Mocha Powder", {2.7979f, 3.5452f, 4.3365f}, {17.502f, 27.004f, 35.433f}},
    {"Pacific Ocean Surface Water", {0.0001764f, 0.00032095f, 0.00019617f}, {0.031845f, 0.031324f, 0.030147f}},
};

// The largest value of a spectrum over the visible range (1 nm steps; exact for the sigmoid's
// monotone pieces up to that step).
Float SpectrumMax(BuildContext &ctx, const Spectrum &s) {
    Float m = 0;
    for (int l = 360; l <= 830; ++l) m = std::max(m, ctx.Registry().Eval(s, Float(l)));
    return m;
}

// ---- Parameters ----

std::string Where(const MediumEntity &e) { return "medium " + Quoted(e.name); }

Spectrum SpectrumOr(BuildContext &ctx, const ParameterDictionary &p, const std::string &name, SpectrumType type,
                    Float def) {
    std::optional<Spectrum> s = GetSpectrum(ctx, p, name, type);
    return s ? *s : Spectrum::Const(def);
}

Float CheckedFloat(const MediumEntity &e, const std::string &name, double def, double lo, double hi, bool openLo,
                   bool openHi) {
    double v = e.params.GetOneFloat(name, def);
    bool ok = std::isfinite(v) && (openLo ? v > lo : v >= lo) && (openHi ? v < hi : v <= hi);
    if (!ok)
        Fail(ParamLoc(e.params, name, e.loc), Where(e) + ": \"" + name + "\" must be in " + (openLo ? "(" : "[") +
                                                    std::to_string(lo) + ", " + std::to_string(hi) + (openHi ? ")" : "]") +
                                                    ", got " + std::to_string(v));
    return Float(v);
}

// sigma_a and sigma_s (pbrt-v4: a preset when named and found, else the parameters, else 1),
// "scale" and "g".
void ScatteringParams(BuildContext &ctx, const MediumEntity &e, Medium &m, bool allowPreset) {
    const ParameterDictionary &p = e.params;
    bool preset = false;
    if (allowPreset) {
        std::string name = p.GetOneString("preset", "");
        if (!name.empty()) {
            for (const MeasuredMedium &mm : kPresets)
                if (name == mm.name) {
                    m.sigmaA = ctx.Registry().FromRGB({mm.sigmaA[0], mm.sigmaA[1], mm.sigmaA[2]}, SpectrumType::Unbounded);
                    m.sigmaS = ctx.Registry().FromRGB({mm.sigmaPrimeS[0], mm.sigmaPrimeS[1], mm.sigmaPrimeS[2]},
                                                      SpectrumType::Unbounded);
                    preset = true;
                }
            if (!preset) ctx.diag.Warning(ParamLoc(p, "preset", e.loc), Where(e) + ": material preset " + Quoted(name) + " not found");
        }
    }
    if (!preset) {
        m.sigmaA = SpectrumOr(ctx, p, "sigma_a", SpectrumType::Unbounded, 1);
        m.sigmaS = SpectrumOr(ctx, p, "sigma_s", SpectrumType::Unbounded, 1);
    }
    m.sigmaScale = CheckedFloat(e, "scale", 1, 0, 1e30, false, false);
    m.g = CheckedFloat(e, "g", 0, -1, 1, true, true);
}

// nx, ny, nz and a check that `count` samples fill them.
void GridSize(const MediumEntity &e, size_t count, const std::string &what, uint32_t *nx, uint32_t *ny, uint32_t *nz) {
    const ParameterDictionary &p = e.params;
    int n[3] = {p.GetOneInt("nx", 1), p.GetOneInt("ny", 1), p.GetOneInt("nz", 1)};
    const char *names[3] = {"nx", "ny", "nz"};
    for (int i = 0; i < 3; ++i)
        if (n[i] < 1) Fail(ParamLoc(p, names[i], e.loc), Where(e) + ": \"" + names[i] + "\" must be at least 1");
    uint64_t total = uint64_t(n[0]) * uint64_t(n[1]) * uint64_t(n[2]);
    if (total != count)
        Fail(ParamLoc(p, what, e.loc), Where(e) + ": " + std::to_string(count) + " \"" + what + "\" values, but nx*ny*nz = " +
                                           std::to_string(n[0]) + "*" + std::to_string(n[1]) + "*" + std::to_string(n[2]) +
                                           " = " + std::to_string(total));
    *nx = uint32_t(n[0]);
    *ny = uint32_t(n[1]);
    *nz = uint32_t(n[2]);
}

MediumGrid AddFloatGrid(HostScene &s, const std::vector<double> &v, uint32_t nx, uint32_t ny, uint32_t nz) {
    MediumGrid g;
    g.nx = nx;
    g.ny = ny;
    g.nz = nz;
    g.channels = 1;
    g.offset = s.mediumData.size();
    for (double x : v) s.mediumData.push_back(Float(x));
    return g;
}

void CheckNonNegative(const MediumEntity &e, const std::string &name, const std::vector<double> &v) {
    for (size_t i = 0; i < v.size(); ++i)
        if (!(v[i] >= 0))
            Fail(ParamLoc(e.params, name, e.loc), Where(e) + ": \"" + name + "\" value " + std::to_string(i) + " is " +
                                                      std::to_string(v[i]) + " (must be >= 0)");
}

void Bounds(const MediumEntity &e, Medium &m) {
    std::optional<Vec3f> p0 = e.params.GetOnePoint3f("p0"), p1 = e.params.GetOnePoint3f("p1");
    m.bounds.pMin = p0 ? *p0 : Vec3f(0, 0, 0);
    m.bounds.pMax = p1 ? *p1 : Vec3f(1, 1, 1);
    for (int i = 0; i < 3; ++i)
        if (!(m.bounds.pMax[i] > m.bounds.pMin[i]))
            Fail(ParamLoc(e.params, "p1", e.loc), Where(e) + ": the bounds need p0 < p1 on every axis");
    m.renderFromMedium = e.renderFromObject;
}

// The bounds in [0,1]^3 of majorant voxel (x, y, z) of a 16^3 grid.
constexpr uint32_t kMajorantRes = 16;
Bounds3f MajorantVoxel(uint32_t x, uint32_t y, uint32_t z) {
    Bounds3f b;
    b.pMin = Vec3f(Float(x) / kMajorantRes, Float(y) / kMajorantRes, Float(z) / kMajorantRes);
    b.pMax = Vec3f(Float(x + 1) / kMajorantRes, Float(y + 1) / kMajorantRes, Float(z + 1) / kMajorantRes);
    return b;
}

// pbrt-v4's SampledGrid::MaxValue: the largest sample that can influence a lookup in b.
template <typename F>
Float GridMax(const MediumGrid &g, const Bounds3f &b, F value) {
    int lo[3], hi[3];
    const int n[3] = {int(g.nx), int(g.ny), int(g.nz)};
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::max(int(std::floor(b.pMin[a] * n[a] - 0.5f)), 0);
        hi[a] = std::min(int(std::floor(b.pMax[a] * n[a] - 0.5f)) + 1, n[a] - 1);
    }
    Float m = value(lo[0], lo[1], lo[2]);
    for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
            for (int x = lo[0]; x <= hi[0]; ++x) m = std::max(m, value(x, y, z));
    return m;
}

MediumGrid AddMajorantGrid(HostScene &s, const std::vector<Float> &values) {
    MediumGrid g;
    g.nx = g.ny = g.nz = kMajorantRes;
    g.offset = s.mediumData.size();
    s.mediumData.insert(s.mediumData.end(), values.begin(), values.end());
    return g;
}

// Majorants of a one-channel density grid: the largest density that can influence each majorant
// voxel (sigma_t is applied per ray).
MediumGrid DensityMajorants(HostScene &s, const MediumGrid &dg) {
    std::vector<Float> maj;
    for (uint32_t z = 0; z < kMajorantRes; ++z)
        for (uint32_t y = 0; y < kMajorantRes; ++y)
            for (uint32_t x = 0; x < kMajorantRes; ++x)
                maj.push_back(GridMax(dg, MajorantVoxel(x, y, z), [&](int i, int j, int k) {
                    return s.mediumData[dg.offset + (uint64_t(k) * dg.ny + j) * dg.nx + i];
                }));
    return AddMajorantGrid(s, maj);
}

// An "rgb NAME" array of n RGB triples as a 4-channel spectrum grid (sigmoid coefficients and
// scale per sample); channels == 0 when absent.
MediumGrid AddRGBGrid(BuildContext &ctx, const MediumEntity &e, const std::string &name, SpectrumType type,
                      std::vector<Float> *maxPerSample) {
    MediumGrid g;
    g.channels = 0;
    if (!e.params.Has(name)) return g;
    const ParsedParameter *p = e.params.Find(name);
    if (p->type != "rgb") Fail(p->loc, Where(e) + ": \"" + name + "\" must be an \"rgb\" array");
    if (p->numbers.empty() || p->numbers.size() % 3 != 0)
        Fail(p->loc, Where(e) + ": \"rgb " + name + "\" needs a multiple of 3 values");
    HostScene &s = ctx.scene;
    g.channels = 4;
    g.kind = type == SpectrumType::Illuminant ? SpectrumKind::RGBIlluminant : SpectrumKind::RGBUnbounded;
    g.colorSpace = p->colorSpace;
    g.offset = s.mediumData.size();
    size_t n = p->numbers.size() / 3;
    g.nx = uint32_t(n);   // the caller sets the dimensions
    for (size_t i = 0; i < n; ++i) {
        RGB rgb = {Float(p->numbers[3 * i]), Float(p->numbers[3 * i + 1]), Float(p->numbers[3 * i + 2])};
        for (int c = 0; c < 3; ++c)
            if (!(rgb[c] >= 0) || !std::isfinite(rgb[c]))
                Fail(p->loc, Where(e) + ": \"rgb " + name + "\" value " + std::to_string(i) + " has a negative or non-finite component");
        Spectrum sp = ctx.Registry().FromRGB(rgb, type, ColorSpaceId(g.colorSpace));
        s.mediumData.push_back(sp.c[0]);
        s.mediumData.push_back(sp.c[1]);
        s.mediumData.push_back(sp.c[2]);
        s.mediumData.push_back(sp.scale);
        if (maxPerSample) {
            Spectrum eval;
            eval.kind = SpectrumKind::RGBUnbounded;
            for (int c = 0; c < 3; ++c) eval.c[c] = s.mediumData[s.mediumData.size() - 4 + c];
            eval.scale = s.mediumData.back();
            maxPerSample->push_back(eval.scale > 0 ? SpectrumMax(ctx, eval) : 0);
        }
    }
    return g;
}

// ---- The medium types ----

void BuildHomogeneous(BuildContext &ctx, const MediumEntity &e, Medium &m) {
    m.kind = MediumKind::Homogeneous;
    ScatteringParams(ctx, e, m, true);
    std::optional<Spectrum> Le = GetSpectrum(ctx, e.params, "Le", SpectrumType::Illuminant);
    Float LeScale = CheckedFloat(e, "Lescale", 1, 0, 1e30, false, false);
    if (Le && SpectrumMax(ctx, *Le) > 0) {
        m.Le = *Le;
        m.LeScale = LeScale / ctx.Registry().ToPhotometric(*Le);
        m.emissive = m.LeScale > 0;
    }
}

void BuildUniformGrid(BuildContext &ctx, const MediumEntity &e, Medium &m) {
    const ParameterDictionary &p = e.params;
    HostScene &s = ctx.scene;
    m.kind = MediumKind::UniformGrid;
    std::vector<double> density = p.GetFloatArray("density");
    if (density.empty()) Fail(e.loc, Where(e) + ": no \"density\" values for the \"uniformgrid\" medium");
    CheckNonNegative(e, "density", density);
    uint32_t nx, ny, nz;
    GridSize(e, density.size(), "density", &nx, &ny, &nz);
    std::vector<double> temperature = p.GetFloatArray("temperature");
    if (!temperature.empty() && temperature.size() != density.size())
        Fail(ParamLoc(p, "temperature", e.loc), Where(e) + ": " + std::to_string(temperature.size()) +
                                                    " \"temperature\" values for " + std::to_string(density.size()) +
                                                    " \"density\" values");
    std::optional<Spectrum> Le = GetSpectrum(ctx, p, "Le", SpectrumType::Illuminant);
    if (Le && !temperature.empty())
        Fail(ParamLoc(p, "Le", e.loc), Where(e) + ": both \"Le\" and \"temperature\" were given");
    Float LeNorm = 1;
    bool haveLe = Le && SpectrumMax(ctx, *Le) > 0;
    if (haveLe) {
        m.Le = *Le;
        LeNorm = 1 / ctx.Registry().ToPhotometric(*Le);
    }
    std::vector<double> LeScale = p.GetFloatArray("Lescale");
    CheckNonNegative(e, "Lescale", LeScale);
    ScatteringParams(ctx, e, m, false);
    Bounds(e, m);
    m.temperatureOffset = Float(p.GetOneFloat("temperatureoffset", p.GetOneFloat("temperaturecutoff", 0)));
    m.temperatureScale = Float(p.GetOneFloat("temperaturescale", 1));

    m.density = AddFloatGrid(s, density, nx, ny, nz);
    if (LeScale.empty()) {
        m.LeGrid = AddFloatGrid(s, {double(LeNorm)}, 1, 1, 1);
    } else {
        if (LeScale.size() != density.size())
            Fail(ParamLoc(p, "Lescale", e.loc), Where(e) + ": " + std::to_string(LeScale.size()) + " \"Lescale\" values for " +
                                                    std::to_string(density.size()) + " \"density\" values");
        for (double &v : LeScale) v *= LeNorm;
        m.LeGrid = AddFloatGrid(s, LeScale, nx, ny, nz);
    }
    if (!temperature.empty()) m.temperature = AddFloatGrid(s, temperature, nx, ny, nz);
    m.emissive = !temperature.empty() || haveLe;
    m.majorant = DensityMajorants(s, m.density);
}

// ---- nanovdb ----

using NanoGrid = nanovdb::GridHandle<nanovdb::HostBuffer>;

// Largest dense grid a NanoVDB grid may become (samples; 4 bytes each).
constexpr uint64_t kMaxDenseVoxels = uint64_t(1) << 28;

// The float grid `gridName` of a NanoVDB file; an empty handle when the file has no such grid and
// it is optional. SceneError at loc for an unreadable file, a missing required grid, a grid that
// is not float or not a fog volume (pbrt-v4's checks), or non-finite / negative values.
NanoGrid ReadNanoGrid(const MediumEntity &e, const std::string &path, const std::string &gridName, bool required,
                      const FileLoc &loc) {
    NanoGrid h;
    try {
        std::vector<nanovdb::io::GridMetaData> meta = nanovdb::io::readGridMetaData(path);
        std::string names;
        bool found = false;
        for (const auto &g : meta) {
            found |= g.gridName == gridName;
            names += (names.empty() ? "" : ", ") + Quoted(g.gridName);
        }
        if (!found) {
            if (!required) return h;
            Fail(loc, Where(e) + ": NanoVDB file " + Quoted(path) + " has no grid " + Quoted(gridName) + " (it has " +
                          (names.empty() ? std::string("none") : names) + ")");
        }
        h = nanovdb::io::readGrid<nanovdb::HostBuffer>(path, gridName);
    } catch (const SceneError &) {
        throw;
    } catch (const std::exception &ex) {
        Fail(loc, Where(e) + ": cannot read NanoVDB file " + Quoted(path) + ": " + ex.what());
    }
    const nanovdb::FloatGrid *g = h.grid<float>();
    if (!g) Fail(loc, Where(e) + ": grid " + Quoted(gridName) + " of " + Quoted(path) + " is not a float grid");
    if (!g->isFogVolume() && !g->isUnknown())
        Fail(loc, Where(e) + ": grid " + Quoted(gridName) + " of " + Quoted(path) +
                      " is not a fog volume (a level set or other class; pbrt-v4 refuses it too)");
    return h;
}

// The medium-from-index transform of a NanoVDB grid (its index-to-world map: NanoVDB's world is the
// medium space); false when the map is singular.
bool NanoIndexToMedium(const nanovdb::FloatGrid &g, Transform *t) {
    const nanovdb::Map &map = g.map();
    Matrix4 m;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m.m[r][c] = Float(map.mMatD[3 * r + c]);
        m.m[r][3] = Float(map.mVecD[r]);
    }
    Matrix4 inv;
    if (!Inverse(m, &inv)) return false;
    *t = Transform(m, inv);
    return true;
}

// pbrt-v4's "nanovdb" medium: the float grids "density" (gridname) and optionally "temperature"
// (temperaturename) of a .nvdb file, sigma_a/sigma_s/scale/g, Lescale, temperatureoffset (or
// temperaturecutoff) and temperaturescale. pbrt-v4 samples the grid trilinearly in index space,
// voxel (i, j, k) at index point (i, j, k), inside the world box of the index box [lo, hi + 1].
// Lucerna stores the voxels lo..hi+1 (the last is background) as a dense grid whose samples sit at
// those index points: medium space is the index space (bounds [lo - 1/2, hi + 3/2]) and
// renderFromMedium = CTM * map. Every lookup then equals pbrt-v4's, except within half a voxel
// below the lower faces of the index box, where pbrt-v4 is 0 (outside its box) and Lucerna
// interpolates towards the first voxel.
void BuildNanoVDB(BuildContext &ctx, const MediumEntity &e, Medium &m) {
    const ParameterDictionary &p = e.params;
    HostScene &s = ctx.scene;
    m.kind = MediumKind::UniformGrid;
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty()) Fail(e.loc, Where(e) + ": \"nanovdb\" needs \"string filename\"");
    FileLoc floc = ParamLoc(p, "filename", e.loc);
    std::string path = ResolvePath(ctx.desc.baseDirectory, filename);
    NanoGrid dh = ReadNanoGrid(e, path, p.GetOneString("gridname", "density"), true, floc);
    NanoGrid th = ReadNanoGrid(e, path, p.GetOneString("temperaturename", "temperature"), false, floc);
    s.inputFiles.push_back(path);
    const nanovdb::FloatGrid &dg = *dh.grid<float>();
    const nanovdb::FloatGrid *tg = th ? th.grid<float>() : nullptr;

    ScatteringParams(ctx, e, m, false);
    m.LeScale = CheckedFloat(e, "Lescale", 1, 0, 1e30, false, false);
    m.temperatureOffset = Float(p.GetOneFloat("temperatureoffset", p.GetOneFloat("temperaturecutoff", 0)));
    m.temperatureScale = Float(p.GetOneFloat("temperaturescale", 1));

    // The index box: the density grid's, with the temperature grid's when it shares the map.
    auto box = dg.indexBBox();
    nanovdb::Coord lo = box.min(), hi = box.max();
    bool sameMap = tg && std::equal(std::begin(tg->map().mMatD), std::end(tg->map().mMatD), std::begin(dg.map().mMatD)) &&
                   std::equal(std::begin(tg->map().mVecD), std::end(tg->map().mVecD), std::begin(dg.map().mVecD));
    if (tg && sameMap && !tg->tree().isEmpty()) {
        auto tb = tg->indexBBox();
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], tb.min()[a]);
            hi[a] = std::max(hi[a], tb.max()[a]);
        }
    }
    if (dg.tree().isEmpty()) {
        // No active voxel: a medium that holds nothing (pbrt-v4 renders it as empty space).
        lo = hi = nanovdb::Coord(0);
    }
    uint64_t n[3];
    for (int a = 0; a < 3; ++a) n[a] = uint64_t(int64_t(hi[a]) - int64_t(lo[a])) + 2;   // lo..hi+1
    uint64_t total = n[0] * n[1] * n[2];
    if (total > kMaxDenseVoxels)
        Fail(floc, Where(e) + ": the NanoVDB grid spans " + std::to_string(n[0]) + "x" + std::to_string(n[1]) + "x" +
                       std::to_string(n[2]) + " voxels, more than Lucerna's dense grids hold (" +
                       std::to_string(kMaxDenseVoxels) + " voxels, 1 GiB); crop or resample it");

    m.bounds.pMin = Vec3f(Float(lo[0]) - 0.5f, Float(lo[1]) - 0.5f, Float(lo[2]) - 0.5f);
    m.bounds.pMax = Vec3f(Float(hi[0]) + 1.5f, Float(hi[1]) + 1.5f, Float(hi[2]) + 1.5f);
    Transform indexToMedium;
    if (!NanoIndexToMedium(dg, &indexToMedium))
        Fail(floc, Where(e) + ": the NanoVDB grid's index-to-world map is singular");
    m.renderFromMedium = e.renderFromObject * indexToMedium;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(m.renderFromMedium.m.m[r][c]) || !std::isfinite(m.renderFromMedium.mInv.m[r][c]))
                Fail(floc, Where(e) + ": the NanoVDB grid's index-to-world map (or the CTM) is singular");

    // Dense copies of the voxels, checked as pbrt-v4's other grids are.
    auto fill = [&](const nanovdb::FloatGrid &g, bool ownLattice, const char *what) {
        MediumGrid out;
        out.nx = uint32_t(n[0]);
        out.ny = uint32_t(n[1]);
        out.nz = uint32_t(n[2]);
        out.channels = 1;
        out.offset = s.mediumData.size();
        s.mediumData.resize(s.mediumData.size() + total);
        Float *dst = s.mediumData.data() + out.offset;
        auto acc = g.getAccessor();
        // A grid with another map is sampled (trilinearly, as pbrt-v4 does) at this lattice's points.
        nanovdb::SampleFromVoxels<nanovdb::FloatGrid::TreeType, 1, false> sampler(g.tree());
        for (uint64_t z = 0; z < n[2]; ++z)
            for (uint64_t y = 0; y < n[1]; ++y)
                for (uint64_t x = 0; x < n[0]; ++x) {
                    nanovdb::Coord ijk(lo[0] + int(x), lo[1] + int(y), lo[2] + int(z));
                    float v;
                    if (ownLattice) {
                        v = acc.getValue(ijk);
                    } else {
                        nanovdb::Vec3d w = dg.indexToWorld(nanovdb::Vec3d(ijk[0], ijk[1], ijk[2]));
                        v = sampler(g.worldToIndexF(nanovdb::Vec3f(float(w[0]), float(w[1]), float(w[2]))));
                    }
                    if (!std::isfinite(v) || v < 0)
                        Fail(floc, Where(e) + ": " + what + " voxel (" + std::to_string(ijk[0]) + ", " + std::to_string(ijk[1]) +
                                       ", " + std::to_string(ijk[2]) + ") of " + Quoted(path) + " is " + std::to_string(v) +
                                       " (must be finite and >= 0)");
                    dst[(z * n[1] + y) * n[0] + x] = v;
                }
        return out;
    };
    m.density = fill(dg, true, "density");
    if (tg) m.temperature = fill(*tg, sameMap, "temperature");
    m.LeGrid = MediumGrid();   // nx == 0: the constant m.LeScale (pbrt-v4's nanovdb Lescale)
    m.emissive = tg && m.LeScale > 0;
    m.majorant = DensityMajorants(s, m.density);
}

void BuildRGBGrid(BuildContext &ctx, const MediumEntity &e, Medium &m) {
    const ParameterDictionary &p = e.params;
    HostScene &s = ctx.scene;
    m.kind = MediumKind::RGBGrid;
    std::vector<Float> maxA, maxS;
    m.density = AddRGBGrid(ctx, e, "sigma_a", SpectrumType::Unbounded, &maxA);
    m.density2 = AddRGBGrid(ctx, e, "sigma_s", SpectrumType::Unbounded, &maxS);
    m.LeGrid = AddRGBGrid(ctx, e, "Le", SpectrumType::Illuminant, nullptr);
    if (m.density.channels == 0 && m.density2.channels == 0)
        Fail(e.loc, Where(e) + ": the \"rgbgrid\" medium needs \"sigma_a\" and/or \"sigma_s\" values");
    size_t n = m.density.channels ? m.density.nx : m.density2.nx;
    if (m.density.channels && m.density2.channels && m.density.nx != m.density2.nx)
        Fail(ParamLoc(p, "sigma_s", e.loc), Where(e) + ": " + std::to_string(m.density.nx) + " \"sigma_a\" and " +
                                                std::to_string(m.density2.nx) + " \"sigma_s\" values");
    if (m.LeGrid.channels && !m.density.channels)
        Fail(ParamLoc(p, "Le", e.loc), Where(e) + ": \"Le\" needs \"sigma_a\" values as well");
    if (m.LeGrid.channels && m.LeGrid.nx != n)
        Fail(ParamLoc(p, "Le", e.loc), Where(e) + ": " + std::to_string(m.LeGrid.nx) + " \"Le\" values for " +
                                           std::to_string(n) + " density values");
    uint32_t nx, ny, nz;
    GridSize(e, n, m.density.channels ? "sigma_a" : "sigma_s", &nx, &ny, &nz);
    for (MediumGrid *g : {&m.density, &m.density2, &m.LeGrid})
        if (g->channels) {
            g->nx = nx;
            g->ny = ny;
            g->nz = nz;
        } else {
            g->nx = 0;
        }
    Bounds(e, m);
    m.LeScale = CheckedFloat(e, "Lescale", 1, 0, 1e30, false, false);
    m.g = CheckedFloat(e, "g", 0, -1, 1, true, true);
    m.sigmaScale = CheckedFloat(e, "scale", 1, 0, 1e30, false, false);
    m.emissive = m.LeGrid.channels && m.LeScale > 0;
    // Majorants: sigmaScale * (max sigma_a + max sigma_s) over each voxel (1 for an absent grid).
    std::vector<Float> maj;
    for (uint32_t z = 0; z < kMajorantRes; ++z)
        for (uint32_t y = 0; y < kMajorantRes; ++y)
            for (uint32_t x = 0; x < kMajorantRes; ++x) {
                Bounds3f b = MajorantVoxel(x, y, z);
                auto maxOf = [&](const MediumGrid &g, const std::vector<Float> &mx) -> Float {
                    if (!g.channels) return 1;
                    return GridMax(g, b, [&](int i, int j, int k) { return mx[(size_t(k) * g.ny + j) * g.nx + i]; });
                };
                maj.push_back(m.sigmaScale * (maxOf(m.density, maxA) + maxOf(m.density2, maxS)));
            }
    m.majorant = AddMajorantGrid(s, maj);
}

// pbrt-v4's CloudMedium::Create: density (1), wispiness (1), frequency (5), sigma_a and sigma_s
// (1), g, p0/p1; no "scale" (pbrt-v4 reads none for the cloud, so it is left unused).
void BuildCloud(BuildContext &ctx, const MediumEntity &e, Medium &m) {
    const ParameterDictionary &p = e.params;
    m.kind = MediumKind::Cloud;
    m.sigmaA = SpectrumOr(ctx, p, "sigma_a", SpectrumType::Unbounded, 1);
    m.sigmaS = SpectrumOr(ctx, p, "sigma_s", SpectrumType::Unbounded, 1);
    m.sigmaScale = 1;
    m.g = CheckedFloat(e, "g", 0, -1, 1, true, true);
    m.cloudDensity = CheckedFloat(e, "density", 1, 0, 1e30, false, false);
    m.wispiness = CheckedFloat(e, "wispiness", 1, 0, 1e30, false, false);
    m.frequency = CheckedFloat(e, "frequency", 5, 0, 1e30, false, false);
    Bounds(e, m);
}

}  // namespace

void BuildMedia(BuildContext &ctx) {
    HostScene &s = ctx.scene;
    for (const MediumEntity &e : ctx.desc.media) {
        std::string type = e.params.GetOneString("type", "");
        Medium m;
        if (type.empty()) Fail(e.loc, Where(e) + " has no \"string type\" parameter");
        if (type == "homogeneous") BuildHomogeneous(ctx, e, m);
        else if (type == "uniformgrid") BuildUniformGrid(ctx, e, m);
        else if (type == "rgbgrid") BuildRGBGrid(ctx, e, m);
        else if (type == "cloud") BuildCloud(ctx, e, m);
        else if (type == "nanovdb") BuildNanoVDB(ctx, e, m);
        else
            Fail(ParamLoc(e.params, "type", e.loc), Where(e) + ": unknown medium type " + Quoted(type) +
                                                       " (expected homogeneous, uniformgrid, rgbgrid, cloud or nanovdb)");
        ctx.media[e.name] = uint32_t(s.media.size());
        s.SetOrigin(s.mediumOrigin, s.media.size(), "MakeNamedMedium " + Quoted(e.name) + " at " + e.loc.ToString());
        s.media.push_back(m);
        s.stats.mediaByType[type]++;
        e.params.ReportUnused(ctx.diag, "MakeNamedMedium " + Quoted(e.name));
    }
    s.camera.medium = ResolveMedium(ctx, ctx.desc.camera.medium, ctx.desc.camera.loc);
}

uint32_t ResolveMedium(BuildContext &ctx, const std::string &name, const FileLoc &loc) {
    if (name.empty()) return NoIndex;
    auto it = ctx.media.find(name);
    if (it == ctx.media.end()) Fail(loc, "medium " + Quoted(name) + " is not defined (MakeNamedMedium)");
    return it->second;
}

}  // namespace lu::build
