// pbrt-v4's texture list evaluated in the shared code (materials/texture.h, noise.h): mappings at
// known points, pattern means and parities, composites of constants, Perlin noise against an
// independent double-precision evaluation, FBm / turbulence octave counts, marble and dots.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "lucerna/materials/texture.h"
#include "lucerna/sampling/rng.h"
#include "lucerna/spectra/registry.h"

namespace lu::test {
namespace {

template <typename T>
Span<T> MakeSpan(const std::vector<T> &v) {
    Span<T> s; s.ptr = v.data(); s.size = uint32_t(v.size()); return s;
}

TextureEvalContext At(Vec3f p, Vec2f uv = Vec2f(0, 0), Vec3f n = Vec3f(0, 0, 1)) {
    TextureEvalContext c; c.p = p; c.uv = uv; c.n = n; return c;
}
TextureEvalContext AtUV(Float u, Float v) { return At(Vec3f(0, 0, 0), Vec2f(u, v)); }

Matrix4 Translation(Float x, Float y, Float z) {
    Matrix4 m; m.m[0][3] = x; m.m[1][3] = y; m.m[2][3] = z; return m;
}
Matrix4 Scaling(Float x, Float y, Float z) {
    Matrix4 m; m.m[0][0] = x; m.m[1][1] = y; m.m[2][2] = z; return m;
}

FloatTexture ConstF(Float v) { FloatTexture t; t.kind = TextureKind::Constant; t.value = v; return t; }
SpectrumTexture ConstS(Float v) { SpectrumTexture t; t.kind = TextureKind::Constant; t.value = Spectrum::Const(v); return t; }

// A SceneView over texture child arrays (and the sRGB table, for marble).
struct TextureScene {
    std::vector<FloatTexture> floats;
    std::vector<SpectrumTexture> spectra;
    std::vector<Float> coeffs, zNodes;
    uint32_t AddF(const FloatTexture &t) { floats.push_back(t); return uint32_t(floats.size() - 1); }
    uint32_t AddS(const SpectrumTexture &t) { spectra.push_back(t); return uint32_t(spectra.size() - 1); }
    SceneView View() {
        SceneView v;
        v.floatTextures = MakeSpan(floats);
        v.spectrumTextures = MakeSpan(spectra);
        if (coeffs.empty()) {
            RGBToSpectrumTableData t = SRGBToSpectrumTable();
            coeffs.assign(t.coeffs, t.coeffs + size_t(t.res) * t.res * t.res * 9);
            zNodes.assign(t.zNodes, t.zNodes + t.res);
        }
        v.rgbToSpecCoeffs = MakeSpan(coeffs);
        v.rgbToSpecZNodes = MakeSpan(zNodes);
        v.rgbToSpecRes = uint32_t(zNodes.size());
        return v;
    }
};

SampledWavelengths Lambdas() { return SampledWavelengths::SampleVisible(0.3f); }

// ---- Mappings ----

TEST(TextureMapping, UVSphericalCylindricalPlanarPointAtKnownPoints) {
    TextureMapping uv;
    uv.su = 2; uv.sv = 3; uv.du = 0.5f; uv.dv = -1;
    Vec2f st = Map2D(uv, AtUV(0.25f, 0.5f));
    EXPECT_FLOAT_EQ(st.x, 1.0f);
    EXPECT_FLOAT_EQ(st.y, 0.5f);

    // Spherical about the point (1, 2, 3): theta / pi from +z, phi / 2 pi from +x towards +y.
    TextureMapping sph;
    sph.kind = TextureMappingKind::Spherical;
    sph.textureFromRender = Translation(-1, -2, -3);
    struct { Vec3f d; Float s, t; } sphCases[] = {
        {{0, 0, 2}, 0, 0}, {{0, 0, -0.5f}, 1, 0}, {{3, 0, 0}, 0.5f, 0}, {{0, 1, 0}, 0.5f, 0.25f},
        {{-1, 0, 0}, 0.5f, 0.5f}, {{0, -1, 0}, 0.5f, 0.75f}, {{1, 1, std::sqrt(2.f)}, 0.25f, 0.125f}};
    for (auto &c : sphCases) {
        Vec2f r = Map2D(sph, At(Vec3f(1, 2, 3) + c.d));
        EXPECT_NEAR(r.x, c.s, 1e-6f);
        EXPECT_NEAR(r.y, c.t, 1e-6f);
    }

    // Cylindrical about the z axis scaled by 1/2: s = (pi + atan2(y, x)) / 2 pi, t = z / 2.
    TextureMapping cyl;
    cyl.kind = TextureMappingKind::Cylindrical;
    cyl.textureFromRender = Scaling(0.5f, 0.5f, 0.5f);
    struct { Vec3f p; Float s, t; } cylCases[] = {
        {{1, 0, 4}, 0.5f, 2}, {{0, 1, 0}, 0.75f, 0}, {{0, -1, -2}, 0.25f, -1}, {{-1, 1e-7f, 1}, 1.0f, 0.5f}};
    for (auto &c : cylCases) {
        Vec2f r = Map2D(cyl, At(c.p));
        EXPECT_NEAR(r.x, c.s, 1e-6f);
        EXPECT_NEAR(r.y, c.t, 1e-6f);
    }

    // Planar: s = du + dot(p', vs), t = dv + dot(p', vt), p' = textureFromRender p.
    TextureMapping pl;
    pl.kind = TextureMappingKind::Planar;
    pl.textureFromRender = Translation(0, 0, -1);
    pl.vs = Vec3f(1, 0, 0); pl.vt = Vec3f(0, 2, 1);
    pl.du = 0.25f; pl.dv = 0.5f;
    Vec2f r = Map2D(pl, At(Vec3f(3, 1, 2)));  // p' = (3, 1, 1)
    EXPECT_FLOAT_EQ(r.x, 3.25f);
    EXPECT_FLOAT_EQ(r.y, 3.5f);

    TextureMapping pt;
    pt.kind = TextureMappingKind::Point;
    pt.textureFromRender = Translation(1, 0, 0);
    Vec3f q = Map3D(pt, At(Vec3f(1, 2, 3)));
    EXPECT_EQ(q, Vec3f(2, 2, 3));
}

// ---- Patterns ----

TEST(Texture, CheckerboardMeanOverLargeSquareIsTheAverage) {
    TextureScene ts;
    FloatTexture cb;
    cb.kind = TextureKind::Checkerboard;
    cb.tex[0] = ts.AddF(ConstF(0.2f));
    cb.tex[1] = ts.AddF(ConstF(0.9f));
    cb.mapping.su = 7; cb.mapping.sv = 7;   // 7 x 7 checks per unit of (u, v)
    SceneView scene = ts.View();
    const int n = 700;  // stratified: 50 x 50 samples per check
    double sum = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) sum += EvalFloatTexture(cb, AtUV((i + 0.5f) / n * 2 - 0.5f, (j + 0.5f) / n * 2), scene);
    // [-0.5, 1.5] x [0, 2]: 14 x 14 checks, half of each value.
    EXPECT_NEAR(sum / (double(n) * n), (0.2 + 0.9) / 2, 1e-6);
    EXPECT_EQ(EvalFloatTexture(cb, AtUV(0.01f, 0.01f), scene), 0.2f);   // (0.07, 0.07): even
    EXPECT_EQ(EvalFloatTexture(cb, AtUV(0.15f, 0.01f), scene), 0.9f);   // (1.05, 0.07): odd
    EXPECT_EQ(EvalFloatTexture(cb, AtUV(-0.01f, 0.01f), scene), 0.9f);  // floor -1: odd
    // Huge coordinates keep the parity (no int overflow): floor(3e9) + floor(0) is even.
    cb.mapping.su = 1; cb.mapping.sv = 1;
    EXPECT_EQ(EvalFloatTexture(cb, AtUV(3e9f, 0.5f), scene), 0.2f);
    EXPECT_EQ(EvalFloatTexture(cb, AtUV(3e9f + 256, 1.5f), scene), 0.9f);
}

TEST(Texture, Checkerboard3DParityAtKnownPoints) {
    TextureScene ts;
    SpectrumTexture cb;
    cb.kind = TextureKind::Checkerboard;
    cb.tex[0] = ts.AddS(ConstS(0.25f));
    cb.tex[1] = ts.AddS(ConstS(0.75f));
    cb.mapping.kind = TextureMappingKind::Point;
    cb.mapping.textureFromRender = Scaling(2, 2, 2);   // cells of size 1/2 in render space
    SceneView scene = ts.View();
    SampledWavelengths lambda = Lambdas();
    struct { Vec3f p; Float v; } cases[] = {
        {{0.1f, 0.1f, 0.1f}, 0.25f},   {{0.6f, 0.1f, 0.1f}, 0.75f},  {{0.6f, 0.6f, 0.1f}, 0.25f},
        {{0.6f, 0.6f, 0.6f}, 0.75f},   {{-0.1f, 0.1f, 0.1f}, 0.75f}, {{-0.1f, -0.1f, -0.1f}, 0.75f},
        {{-0.6f, -0.6f, 0.1f}, 0.25f}, {{1.1f, 2.1f, 3.1f}, 0.25f}};  // (2,4,6): even
    for (auto &c : cases) EXPECT_EQ(EvalSpectrumTexture(cb, At(c.p), lambda, scene)[1], c.v) << c.p.x << " " << c.p.y << " " << c.p.z;
    // Mean over a cube of 4^3 cells.
    double sum = 0;
    const int n = 40;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                sum += EvalSpectrumTexture(cb, At(Vec3f((i + .5f) / n * 2, (j + .5f) / n * 2, (k + .5f) / n * 2)), lambda, scene)[0];
    EXPECT_NEAR(sum / (n * n * n), 0.5, 1e-6);
}

TEST(Texture, BilerpCornersAndCenter) {
    TextureScene ts;
    SceneView scene = ts.View();
    FloatTexture b;
    b.kind = TextureKind::Bilerp;
    b.v00 = 1; b.v01 = 2; b.v10 = 3; b.v11 = 5;
    EXPECT_FLOAT_EQ(EvalFloatTexture(b, AtUV(0, 0), scene), 1);
    EXPECT_FLOAT_EQ(EvalFloatTexture(b, AtUV(0, 1), scene), 2);
    EXPECT_FLOAT_EQ(EvalFloatTexture(b, AtUV(1, 0), scene), 3);
    EXPECT_FLOAT_EQ(EvalFloatTexture(b, AtUV(1, 1), scene), 5);
    EXPECT_FLOAT_EQ(EvalFloatTexture(b, AtUV(0.5f, 0.5f), scene), 2.75f);
    EXPECT_FLOAT_EQ(EvalFloatTexture(b, AtUV(0.25f, 0), scene), 1.5f);

    SpectrumTexture s;
    s.kind = TextureKind::Bilerp;
    s.tex[0] = ts.AddS(ConstS(1));   // v00
    s.tex[1] = ts.AddS(ConstS(2));   // v01
    s.tex[2] = ts.AddS(ConstS(3));   // v10
    s.tex[3] = ts.AddS(ConstS(5));   // v11
    scene = ts.View();
    SampledWavelengths lambda = Lambdas();
    EXPECT_FLOAT_EQ(EvalSpectrumTexture(s, AtUV(0, 1), lambda, scene)[0], 2);
    EXPECT_FLOAT_EQ(EvalSpectrumTexture(s, AtUV(1, 0), lambda, scene)[2], 3);
    EXPECT_FLOAT_EQ(EvalSpectrumTexture(s, AtUV(0.5f, 0.5f), lambda, scene)[3], 2.75f);
}

// ---- Composites of constants ----

TEST(Texture, ScaleMixDirectionMixOfConstants) {
    TextureScene ts;
    uint32_t a = ts.AddF(ConstF(0.3f)), b = ts.AddF(ConstF(0.8f)), two = ts.AddF(ConstF(2)), q = ts.AddF(ConstF(0.25f));
    uint32_t zero = ts.AddF(ConstF(0)), one = ts.AddF(ConstF(1));
    uint32_t sa = ts.AddS(ConstS(0.3f)), sb = ts.AddS(ConstS(0.8f));
    SceneView scene = ts.View();
    SampledWavelengths lambda = Lambdas();

    FloatTexture scale; scale.kind = TextureKind::Scale; scale.tex[0] = a; scale.amount = two;
    EXPECT_FLOAT_EQ(EvalFloatTexture(scale, AtUV(0, 0), scene), 0.6f);
    // A zero factor gives 0 without evaluating the texture (pbrt-v4): an infinite texture stays 0.
    ts.floats.push_back(ConstF(Infinity));
    scene = ts.View();
    FloatTexture scaleInf; scaleInf.kind = TextureKind::Scale; scaleInf.tex[0] = uint32_t(ts.floats.size() - 1);
    scaleInf.amount = zero;
    EXPECT_EQ(EvalFloatTexture(scaleInf, AtUV(0, 0), scene), 0.0f);

    FloatTexture mix; mix.kind = TextureKind::Mix; mix.tex[0] = a; mix.tex[1] = b; mix.amount = q;
    EXPECT_FLOAT_EQ(EvalFloatTexture(mix, AtUV(0, 0), scene), 0.75f * 0.3f + 0.25f * 0.8f);
    mix.amount = one;
    EXPECT_FLOAT_EQ(EvalFloatTexture(mix, AtUV(0, 0), scene), 0.8f);
    mix.amount = zero;
    EXPECT_FLOAT_EQ(EvalFloatTexture(mix, AtUV(0, 0), scene), 0.3f);

    // directionmix: w = |dot(n, dir)| weights tex1.
    FloatTexture dm; dm.kind = TextureKind::DirectionMix; dm.tex[0] = a; dm.tex[1] = b; dm.dir = Vec3f(0, 1, 0);
    for (Float deg : {0.f, 30.f, 60.f, 90.f, 150.f}) {
        Float th = Radians(deg);
        Vec3f n(0, std::cos(th), std::sin(th));
        Float w = std::abs(std::cos(th));
        EXPECT_NEAR(EvalFloatTexture(dm, At(Vec3f(0, 0, 0), Vec2f(0, 0), n), scene), w * 0.3f + (1 - w) * 0.8f, 1e-6f) << deg;
    }

    SpectrumTexture smix; smix.kind = TextureKind::Mix; smix.tex[0] = sa; smix.tex[1] = sb; smix.amount = q;
    EXPECT_FLOAT_EQ(EvalSpectrumTexture(smix, AtUV(0, 0), lambda, scene)[2], 0.75f * 0.3f + 0.25f * 0.8f);
    SpectrumTexture sscale; sscale.kind = TextureKind::Scale; sscale.tex[0] = sb; sscale.amount = two;
    EXPECT_FLOAT_EQ(EvalSpectrumTexture(sscale, AtUV(0, 0), lambda, scene)[1], 1.6f);
    SpectrumTexture sdm; sdm.kind = TextureKind::DirectionMix; sdm.tex[0] = sa; sdm.tex[1] = sb;
    sdm.dir = Normalize(Vec3f(1, 1, 0));
    Float w = std::sqrt(0.5f);
    EXPECT_NEAR(EvalSpectrumTexture(sdm, At(Vec3f(0, 0, 0), Vec2f(0, 0), Vec3f(-1, 0, 0)), lambda, scene)[0],
                w * 0.3f + (1 - w) * 0.8f, 1e-6f);
}

// Children nest level by level: a chain of MaxTextureDepth scale nodes (each x2) over a
// checkerboard of constants evaluates fully.
TEST(Texture, NestingToMaxDepthEvaluates) {
    TextureScene ts;
    uint32_t two = ts.AddF(ConstF(2));
    FloatTexture leaf = ConstF(0.5f);
    uint32_t child = ts.AddF(leaf);
    FloatTexture node;
    for (int i = 0; i < MaxTextureDepth; ++i) {
        node = FloatTexture();
        node.kind = TextureKind::Scale;
        node.tex[0] = child;
        node.amount = two;
        if (i + 1 < MaxTextureDepth) child = ts.AddF(node);
    }
    SceneView scene = ts.View();
    EXPECT_FLOAT_EQ(EvalFloatTexture(node, AtUV(0, 0), scene), 0.5f * float(1 << MaxTextureDepth));
}

// ---- Noise ----

// Perlin noise written from its definition in double precision: the 8 lattice gradients dotted
// with the offsets, weighted by the quintic fade (independent of noise.h's bit tricks: the
// gradients come from this table of pbrt-v4's 16 hash cases).
double ReferenceNoise(double x, double y, double z) {
    static const int grad[16][3] = {{1, 1, 0},  {-1, 1, 0},  {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                                    {1, 0, -1}, {-1, 0, -1}, {0, 1, 1},  {0, -1, 1},  {0, 1, -1}, {0, -1, -1},
                                    {1, 1, 0},  {-1, 1, 0},  {0, 1, -1}, {0, -1, -1}};
    double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    int ix = int(fx), iy = int(fy), iz = int(fz);
    auto fade = [](double t) { return t * t * t * (10 - 15 * t + 6 * t * t); };
    double sum = 0;
    for (int c = 0; c < 8; ++c) {
        int cx = c & 1, cy = (c >> 1) & 1, cz = (c >> 2) & 1;
        double dx = x - fx - cx, dy = y - fy - cy, dz = z - fz - cz;
        int h = NoisePermutation(NoisePermutation(NoisePermutation((ix + cx) & 255) + ((iy + cy) & 255)) + ((iz + cz) & 255)) & 15;
        double g = grad[h][0] * dx + grad[h][1] * dy + grad[h][2] * dz;
        double w = (cx ? fade(x - fx) : 1 - fade(x - fx)) * (cy ? fade(y - fy) : 1 - fade(y - fy)) *
                   (cz ? fade(z - fz) : 1 - fade(z - fz));
        sum += w * g;
    }
    return sum;
}

TEST(Noise, PermutationIsPerlins) {
    std::vector<int> seen(256, 0);
    for (int i = 0; i < 256; ++i) seen[NoisePermutation(i)]++;
    for (int i = 0; i < 256; ++i) EXPECT_EQ(seen[i], 1) << i;
    // Perlin's reference permutation (Improved Noise, 2002) begins 151 160 137 91 90 15 and
    // ends 61 156 180; indices wrap modulo 256.
    int head[6] = {151, 160, 137, 91, 90, 15};
    for (int i = 0; i < 6; ++i) EXPECT_EQ(NoisePermutation(i), head[i]);
    EXPECT_EQ(NoisePermutation(253), 61);
    EXPECT_EQ(NoisePermutation(254), 156);
    EXPECT_EQ(NoisePermutation(255), 180);
    EXPECT_EQ(NoisePermutation(256), 151);
    EXPECT_EQ(NoisePermutation(511), 180);
}

TEST(Noise, MatchesDefinitionZeroAtLatticeRangeAndMean) {
    RNG rng(7);
    double sum = 0, sum2 = 0, maxAbs = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        Float x = 600 * rng.Uniform<float>() - 300, y = 600 * rng.Uniform<float>() - 300, z = 600 * rng.Uniform<float>() - 300;
        Float v = Noise(x, y, z);
        if (i < 2000) {
            ASSERT_NEAR(v, ReferenceNoise(x, y, z), 2e-5) << x << " " << y << " " << z;
        }
        sum += v; sum2 += double(v) * v;
        maxAbs = std::max(maxAbs, std::abs(double(v)));
    }
    // Perlin noise with these gradients stays within [-1, 1] (and gets near its ends).
    EXPECT_LE(maxAbs, 1.0);
    EXPECT_GT(maxAbs, 0.7);
    double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, 0, 5 * sd / std::sqrt(double(n)));
    EXPECT_GT(sd, 0.1);
    // Zero at every lattice point, and periodic with period 256.
    for (int i = -3; i < 3; ++i) EXPECT_EQ(Noise(Float(i), Float(2 * i), Float(5 - i)), 0.0f);
    EXPECT_NEAR(Noise(0.3f, 0.6f, 0.2f), Noise(256.3f, 0.6f, -255.8f), 1e-4f);
    // Fixed points, reproducible: the value at (0.5, 0.5, 0.5) of cell 0 and a far point.
    EXPECT_NEAR(Noise(0.5f, 0.5f, 0.5f), ReferenceNoise(0.5, 0.5, 0.5), 1e-6);
    EXPECT_NEAR(Noise(12.25f, -3.5f, 7.75f), ReferenceNoise(12.25, -3.5, 7.75), 1e-6);
    EXPECT_NE(Noise(0.5f, 0.5f, 0.5f), 0.0f);
    // Coordinates beyond int range fold instead of overflowing.
    EXPECT_TRUE(std::isfinite(Noise(3e12f, -7e15f, 1e30f)));
}

TEST(Noise, FBmAndTurbulenceOctaves) {
    Vec3f p(1.37f, -2.11f, 0.53f);
    Float omega = 0.6f;
    // Full octaves (zero footprint): sum of omega^i Noise(1.99^i p).
    for (int oct = 0; oct <= 8; ++oct) {
        double fbm = 0, turb = 0, o = 1;
        Float l = 1;
        for (int i = 0; i < oct; ++i) {
            fbm += o * Noise(p * l);
            turb += o * std::abs(Noise(p * l));
            o *= omega; l *= 1.99f;
        }
        turb += 0.2 * o;   // pbrt-v4 adds the clamped octaves' average after the last full one
        EXPECT_NEAR(FBm(p, omega, oct), fbm, 1e-5) << oct;
        EXPECT_NEAR(Turbulence(p, omega, oct), turb, 1e-5) << oct;
    }
    EXPECT_EQ(FBm(p, omega, 0), 0.0f);
    EXPECT_FLOAT_EQ(FBm(p, omega, 1), Noise(p));
    EXPECT_FLOAT_EQ(Turbulence(p, omega, 0), 0.2f);
    // A footprint limits the octaves: len2 = 2^-8 gives -1 + 4 = 3 of 8.
    EXPECT_FLOAT_EQ(NoiseOctaves(std::ldexp(1.f, -8), 8), 3);
    EXPECT_FLOAT_EQ(NoiseOctaves(0, 8), 8);
    EXPECT_FLOAT_EQ(NoiseOctaves(1e6f, 8), 0);
    EXPECT_NEAR(FBm(p, omega, 8, std::ldexp(1.f, -8)), FBm(p, omega, 3), 1e-6f);
    // len2 = 2^-7: 2.5 octaves, the third faded in with SmoothStep(0.5; 0.3, 0.7) = 0.5.
    Float partial = FBm(p, omega, 8, std::ldexp(1.f, -7));
    EXPECT_NEAR(partial, FBm(p, omega, 2) + 0.5f * omega * omega * Noise(p * (1.99f * 1.99f)), 1e-5f);
    // Turbulence with 3 of 5 octaves: pbrt-v4 adds 0.2 omega^3 for the cut-off fraction and 0.2
    // omega^i for each of octaves 3 and 4 (omega^3 counted twice, as pbrt-v4 does).
    Float t = Turbulence(p, omega, 5, std::ldexp(1.f, -8));
    EXPECT_NEAR(t, Turbulence(p, omega, 3) + 0.2f * std::pow(omega, 3.f) + 0.2f * std::pow(omega, 4.f), 1e-5f);
    // Bounded by sum of omega^i; mean near 0 for FBm, positive for turbulence.
    RNG rng(3);
    double s = 0, st = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        Vec3f q(100 * rng.Uniform<float>(), 100 * rng.Uniform<float>(), 100 * rng.Uniform<float>());
        Float f = FBm(q, 0.5f, 8);
        ASSERT_LE(std::abs(f), 2.0f);
        s += f;
        st += Turbulence(q, 0.5f, 8);
    }
    EXPECT_NEAR(s / n, 0, 0.02);
    EXPECT_GT(st / n, 0.2);
}

// ---- Noise-driven textures ----

TEST(Texture, NoiseTexturesFollowTheirDefinitions) {
    TextureScene ts;
    SceneView scene = ts.View();
    Vec3f p(0.7f, 1.9f, -3.3f);
    FloatTexture t;
    t.mapping.kind = TextureMappingKind::Point;
    t.mapping.textureFromRender = Scaling(3, 3, 3);
    t.octaves = 5; t.omega = 0.4f;
    t.kind = TextureKind::FBm;
    EXPECT_FLOAT_EQ(EvalFloatTexture(t, At(p), scene), FBm(p * 3.f, 0.4f, 5));
    t.kind = TextureKind::Wrinkled;
    EXPECT_FLOAT_EQ(EvalFloatTexture(t, At(p), scene), Turbulence(p * 3.f, 0.4f, 5));
    t.kind = TextureKind::Windy;
    EXPECT_FLOAT_EQ(EvalFloatTexture(t, At(p), scene),
                    std::abs(FBm(p * 3.f * .1f, .5f, 3)) * FBm(p * 3.f, .5f, 6));
}

TEST(Texture, MarbleSplineRangeAndKnownPoint) {
    TextureScene ts;
    SceneView scene = ts.View();
    SampledWavelengths lambda = Lambdas();
    // variation 0: t = 0.5 + 0.5 sin(scale y); at y = 0, t = 0.5: segment 3 at its start, the
    // control colour (0.5, 0.5, 0.5) x 1.5 = 0.75 grey: a constant albedo spectrum.
    Float rgb[3];
    MarbleRGB(Vec3f(0.3f, 0, 0.2f), 1, 0, 0.5f, 8, rgb);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 0.75f, 1e-6f);
    SpectrumTexture m;
    m.kind = TextureKind::Marble;
    m.mapping.kind = TextureMappingKind::Point;
    m.scale = 1; m.variation = 0;
    SampledSpectrum v = EvalSpectrumTexture(m, At(Vec3f(0.3f, 0, 0.2f)), lambda, scene);
    for (int i = 0; i < NSpectrumSamples; ++i) EXPECT_NEAR(v[i], 0.75f, 1e-4f);
    // t = 1 (sin = 1 at y = pi/2): the last segment's end, colour (0.58, 0.58, 0.6) x 1.5.
    MarbleRGB(Vec3f(0, Pi / 2, 0), 1, 0, 0.5f, 8, rgb);
    EXPECT_NEAR(rgb[0], 0.87f, 1e-4f);
    EXPECT_NEAR(rgb[2], 0.9f, 1e-4f);
    // The spline stays in the control colours' hull: R, G in [0.3, 0.9], B in [0.495, 0.9].
    RNG rng(11);
    for (int i = 0; i < 5000; ++i) {
        Vec3f q(20 * rng.Uniform<float>(), 20 * rng.Uniform<float>(), 20 * rng.Uniform<float>());
        MarbleRGB(q, 2.5f, 0.5f, 0.5f, 8, rgb);
        for (int c = 0; c < 2; ++c) ASSERT_TRUE(rgb[c] >= 0.3f - 1e-5f && rgb[c] <= 0.9f + 1e-5f) << rgb[c];
        ASSERT_TRUE(rgb[2] >= 0.495f - 1e-5f && rgb[2] <= 0.9f + 1e-5f) << rgb[2];
    }
}

TEST(Texture, PolkaDotsFollowNoiseCells) {
    // A cell (centred on integers) has a dot iff Noise at (s + 0.5, t + 0.5) > 0; the dot covers
    // the cell centre (shift <= 0.15 < radius 0.35) and never the cell corners.
    int withDot = 0;
    for (int t = -20; t < 20; ++t)
        for (int s = -20; s < 20; ++s) {
            bool has = Noise(s + .5f, t + .5f, .5f) > 0;
            withDot += has;
            EXPECT_EQ(InsidePolkaDot(Vec2f(Float(s), Float(t))), has) << s << " " << t;
            EXPECT_FALSE(InsidePolkaDot(Vec2f(s + 0.499f, t + 0.499f)));
            EXPECT_FALSE(InsidePolkaDot(Vec2f(s - 0.499f, t + 0.499f)));
        }
    EXPECT_GT(withDot, 1600 / 4);
    EXPECT_LT(withDot, 1600 * 3 / 4);
    TextureScene ts;
    FloatTexture d;
    d.kind = TextureKind::Dots;
    d.tex[0] = ts.AddF(ConstF(7));   // inside the dots
    d.tex[1] = ts.AddF(ConstF(3));
    SceneView scene = ts.View();
    int s = 0, t = 0;
    while (!(Noise(s + .5f, t + .5f, .5f) > 0)) ++s;
    EXPECT_EQ(EvalFloatTexture(d, AtUV(Float(s), Float(t)), scene), 7);
    EXPECT_EQ(EvalFloatTexture(d, AtUV(s + 0.49f, t + 0.49f), scene), 3);
}

// ---- Image lookups ----

TEST(Texture, PointFilterReadsTheNearestTexel) {
    // 2x2, one channel, row 0 at the top: [10 11; 12 13].
    std::vector<Float> texels = {10, 11, 12, 13};
    std::vector<ImageData> images(1);
    images[0].width = 2; images[0].height = 2; images[0].channels = 1;
    SceneView scene;
    scene.texels = MakeSpan(texels);
    scene.images = MakeSpan(images);
    FloatTexture t; t.kind = TextureKind::ImageMap; t.image = 0; t.pointFilter = true;
    EXPECT_EQ(EvalFloatTexture(t, AtUV(0.3f, 0.7f), scene), 10);   // image st (0.3, 0.3)
    EXPECT_EQ(EvalFloatTexture(t, AtUV(0.7f, 0.7f), scene), 11);
    EXPECT_EQ(EvalFloatTexture(t, AtUV(0.45f, 0.1f), scene), 12);
    EXPECT_EQ(EvalFloatTexture(t, AtUV(0.55f, 0.1f), scene), 13);
    t.pointFilter = false;
    // Bilinear at image (0.55, 0.9): 0.28 x 12 + 0.42 x 13 + 0.12 x 10 + 0.18 x 11 (rows wrap).
    EXPECT_NEAR(EvalFloatTexture(t, AtUV(0.55f, 0.1f), scene), 12.0f, 1e-5f);
}

}  // namespace
}  // namespace lu::test
