// Lucerna: float and spectrum textures at a surface point (host and device): pbrt-v4's texture
// list (textures.h/.cpp) and its 2D/3D mappings, evaluated level by level over child indices.
// No ray differentials: lookups use a zero-width footprint (finest image level, all noise octaves).
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"
#include "lucerna/lights/equal_area.h"
#include "lucerna/materials/noise.h"
#include "lucerna/spectrum/rgb_to_spectrum.h"

// Nested texture levels are separate (not inlined) functions on the device, so that the kernel
// holds each level's code once.
#if defined(__CUDACC__)
#define LU_TEXTURE_NOINLINE __noinline__
#else
#define LU_TEXTURE_NOINLINE
#endif

namespace lu {

// ---- Mappings ----

LU_INLINE Vec3f ApplyTextureTransform(const Matrix4 &m, const Vec3f &p) {
    Float x = m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3];
    Float y = m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3];
    Float z = m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3];
    Float w = m.m[3][0] * p.x + m.m[3][1] * p.y + m.m[3][2] * p.z + m.m[3][3];
    return w == 1 ? Vec3f(x, y, z) : Vec3f(x, y, z) / w;
}

// (s, t) of a 2D mapping (pbrt-v4's UVMapping, SphericalMapping, CylindricalMapping,
// PlanarMapping::Map without the differentials).
LU_INLINE Vec2f Map2D(const TextureMapping &m, const TextureEvalContext &ctx) {
    switch (m.kind) {
    case TextureMappingKind::UV: return {m.su * ctx.uv.x + m.du, m.sv * ctx.uv.y + m.dv};
    case TextureMappingKind::Spherical: {
        Vec3f d = Normalize(ApplyTextureTransform(m.textureFromRender, ctx.p));
        Float theta = SafeACos(d.z), phi = std::atan2(d.y, d.x);
        if (phi < 0) phi += 2 * Pi;
        return {theta * InvPi, phi * Inv2Pi};
    }
    case TextureMappingKind::Cylindrical: {
        Vec3f pt = ApplyTextureTransform(m.textureFromRender, ctx.p);
        return {(Pi + std::atan2(pt.y, pt.x)) * Inv2Pi, pt.z};
    }
    case TextureMappingKind::Planar: {
        Vec3f pt = ApplyTextureTransform(m.textureFromRender, ctx.p);
        return {m.du + Dot(pt, m.vs), m.dv + Dot(pt, m.vt)};
    }
    case TextureMappingKind::Point: break;
    }
    return {0, 0};
}

// The texture-space point of a 3D mapping (pbrt-v4's PointTransformMapping).
LU_INLINE Vec3f Map3D(const TextureMapping &m, const TextureEvalContext &ctx) {
    return ApplyTextureTransform(m.textureFromRender, ctx.p);
}

// ---- Pattern weights ----

// 1 - 2 (floor(x) mod 2): +1 on even cells, -1 on odd ones (pbrt-v4's zero-width checkerboard
// filter). Computed in float so that huge coordinates do not overflow an int.
LU_INLINE Float CheckerSign(Float x) {
    Float f = std::floor(x);
    return f - 2 * std::floor(f / 2) == 0 ? Float(1) : Float(-1);
}

// pbrt-v4's checkerboard weight of tex2: 0 where floor(s) + floor(t) is even, 1 where odd.
LU_INLINE Float Checkerboard(Vec2f st) { return 0.5f - 0.5f * CheckerSign(st.x) * CheckerSign(st.y); }
// The 3D checkerboard: parity of floor(x) + floor(y) + floor(z).
LU_INLINE Float Checkerboard3D(const Vec3f &p) {
    return 0.5f - 0.5f * CheckerSign(p.x) * CheckerSign(p.y) * CheckerSign(p.z);
}

// pbrt-v4's InsidePolkaDot: cells of unit size centred on integer (s, t); a cell has a dot when
// Noise at its centre is positive; the dot (radius 0.35) is shifted by up to 0.15 per axis.
LU_INLINE bool InsidePolkaDot(Vec2f st) {
    Float sCell = std::floor(st.x + .5f), tCell = std::floor(st.y + .5f);
    if (Noise(sCell + .5f, tCell + .5f, .5f) > 0) {
        const Float radius = .35f, maxShift = 0.5f - radius;
        Float sCenter = sCell + maxShift * Noise(sCell + 1.5f, tCell + 2.8f, .5f);
        Float tCenter = tCell + maxShift * Noise(sCell + 4.5f, tCell + 9.8f, .5f);
        Float ds = st.x - sCenter, dt = st.y - tCenter;
        if (ds * ds + dt * dt < radius * radius) return true;
    }
    return false;
}

// pbrt-v4's WindyTexture: wind strength (3 octaves at a tenth of the frequency) times wave height.
LU_INLINE Float Windy(const Vec3f &p) {
    Float windStrength = FBm(p * .1f, .5f, 3);
    Float waveHeight = FBm(p, .5f, 6);
    return std::abs(windStrength) * waveHeight;
}

// pbrt-v4's MarbleTexture colour: t = 0.5 + 0.5 sin(y + variation FBm(p)) of the scaled point
// drives a cubic Bezier spline through nine grey-blue control colours (times 1.5). Writes
// linear sRGB in [0, 0.9].
LU_INLINE void MarbleRGB(const Vec3f &pTexture, Float scale, Float variation, Float omega, int octaves, Float rgb[3]) {
    static constexpr Float colors[9][3] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                                           {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                                           {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
    Vec3f p = pTexture * scale;
    Float marble = p.y + variation * FBm(p, omega, octaves);
    Float t = .5f + .5f * std::sin(marble);
    const int nSeg = 9 - 3;
    int first = Min(int(std::floor(t * nSeg)), nSeg - 1);
    first = Max(first, 0);
    t = t * nSeg - first;
    // Cubic Bernstein basis over control points first .. first + 3.
    Float u = 1 - t;
    Float b[4] = {u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t};
    for (int c = 0; c < 3; ++c)
        rgb[c] = 1.5f * (b[0] * colors[first][c] + b[1] * colors[first + 1][c] + b[2] * colors[first + 2][c] +
                         b[3] * colors[first + 3][c]);
}

// ---- Images ----

// Texel (x, y), channel c, of an image stored row-major with row 0 at the top (pbrt-v4's Image),
// after applying the image's wrap mode; 0 outside for WrapMode::Black; OctahedralSphere folds
// across the seams of the equal-area octahedral layout (pbrt-v4's), as the light images do.
LU_INLINE Float ImageTexel(const ImageData &img, const SceneView &scene, int x, int y, int c) {
    int w = int(img.width), h = int(img.height);
    if (w <= 0 || h <= 0) return 0;
    switch (img.wrap) {
    case WrapMode::Repeat:
        x %= w; if (x < 0) x += w;
        y %= h; if (y < 0) y += h;
        break;
    case WrapMode::Clamp:
        x = Clamp(x, 0, w - 1);
        y = Clamp(y, 0, h - 1);
        break;
    case WrapMode::Black:
        if (x < 0 || x >= w || y < 0 || y >= h) return 0;
        break;
    case WrapMode::OctahedralSphere: WrapOctahedral(&x, &y, w, h); break;
    }
    return scene.texels.ptr[img.offset + (uint64_t(y) * uint64_t(w) + uint64_t(x)) * img.channels + uint64_t(c)];
}

// Bilinear interpolation of channel c at continuous image coordinates st in [0,1]^2 (st.y = 0
// at the top row), texel centers at half-integers (pbrt-v4's Image::BilerpChannel).
LU_INLINE Float ImageBilerp(const ImageData &img, const SceneView &scene, Vec2f st, int c) {
    Float x = st.x * img.width - 0.5f, y = st.y * img.height - 0.5f;
    Float fx = std::floor(x), fy = std::floor(y);
    int xi = int(fx), yi = int(fy);
    Float dx = x - fx, dy = y - fy;
    return (1 - dx) * (1 - dy) * ImageTexel(img, scene, xi, yi, c) + dx * (1 - dy) * ImageTexel(img, scene, xi + 1, yi, c) +
           (1 - dx) * dy * ImageTexel(img, scene, xi, yi + 1, c) + dx * dy * ImageTexel(img, scene, xi + 1, yi + 1, c);
}

// The nearest texel's channel c (pbrt-v4's "point" filter at the finest level).
LU_INLINE Float ImageNearest(const ImageData &img, const SceneView &scene, Vec2f st, int c) {
    int x = int(std::round(st.x * img.width - 0.5f)), y = int(std::round(st.y * img.height - 0.5f));
    return ImageTexel(img, scene, x, y, c);
}

LU_INLINE Float ImageLookup(const ImageData &img, const SceneView &scene, Vec2f st, int c, bool point) {
    return point ? ImageNearest(img, scene, st, c) : ImageBilerp(img, scene, st, c);
}

// Texture st -> image st: texture t = 0 is the bottom of the image (pbrt-v4 flips t).
LU_INLINE Vec2f TextureToImageST(Vec2f st) { return {st.x, 1 - st.y}; }

// ---- RGB -> spectrum for image texels ----

// pbrt-v4's RGBAlbedoSpectrum (rgb clamped to [0,1]) or RGBUnboundedSpectrum of color space cs
// (a ColorSpaceId), sampled at lambda.
LU_INLINE SampledSpectrum RGBToSampledSpectrum(const Float rgb[3], bool unbounded, const SampledWavelengths &lambda,
                                               const SceneView &scene, uint32_t cs = 0) {
    if (scene.rgbToSpecRes < 2 || scene.rgbToSpecCoeffs.empty()) return SampledSpectrum(0);
    const Float *coeffs = RGBToSpecCoeffs(scene, cs), *zNodes = scene.rgbToSpecZNodes.ptr;
    Spectrum s = unbounded ? RGBUnboundedSpectrum(coeffs, zNodes, scene.rgbToSpecRes, rgb[0], rgb[1], rgb[2])
                           : RGBAlbedoSpectrum(coeffs, zNodes, scene.rgbToSpecRes, rgb[0], rgb[1], rgb[2]);
    return SampleSpectrum(s, lambda, scene.spectra);
}

// ---- Leaf textures (no children) ----

LU_TEXTURE_NOINLINE LU_HD inline Float EvalNoiseTexture(const FloatTexture &tex, const TextureEvalContext &ctx) {
    Vec3f p = Map3D(tex.mapping, ctx);
    switch (tex.kind) {
    case TextureKind::FBm: return FBm(p, tex.omega, tex.octaves);
    case TextureKind::Wrinkled: return Turbulence(p, tex.omega, tex.octaves);
    case TextureKind::Windy: return Windy(p);
    default: return 0;
    }
}

LU_INLINE Float EvalFloatImage(const FloatTexture &tex, const TextureEvalContext &ctx, const SceneView &scene) {
    if (tex.image == NoIndex) return 0;
    const ImageData &img = scene.images[tex.image];
    Vec2f st = TextureToImageST(Map2D(tex.mapping, ctx));
    Float v = tex.scale * ImageLookup(img, scene, st, 0, tex.pointFilter);
    return tex.invert ? Max(Float(0), 1 - v) : v;
}

LU_INLINE SampledSpectrum EvalSpectrumImage(const SpectrumTexture &tex, const TextureEvalContext &ctx,
                                            const SampledWavelengths &lambda, const SceneView &scene) {
    if (tex.image == NoIndex) return SampledSpectrum(0);
    const ImageData &img = scene.images[tex.image];
    Vec2f st = TextureToImageST(Map2D(tex.mapping, ctx));
    Float rgb[3];
    if (img.channels >= 3) {
        for (int c = 0; c < 3; ++c) rgb[c] = tex.scale * ImageLookup(img, scene, st, c, tex.pointFilter);
    } else {
        rgb[0] = rgb[1] = rgb[2] = tex.scale * ImageLookup(img, scene, st, 0, tex.pointFilter);
    }
    for (int c = 0; c < 3; ++c) rgb[c] = Max(Float(0), tex.invert ? 1 - rgb[c] : rgb[c]);
    return RGBToSampledSpectrum(rgb, tex.unbounded, lambda, scene, img.colorSpace);
}

LU_TEXTURE_NOINLINE LU_HD inline SampledSpectrum EvalMarble(const SpectrumTexture &tex, const TextureEvalContext &ctx,
                                                            const SampledWavelengths &lambda, const SceneView &scene) {
    Float rgb[3];
    MarbleRGB(Map3D(tex.mapping, ctx), tex.scale, tex.variation, tex.omega, tex.octaves, rgb);
    return RGBToSampledSpectrum(rgb, false, lambda, scene);
}

// ---- Evaluation, one level per template instance ----
// A node at level D evaluates its children at level D - 1; the builder guarantees that no
// composite node sits at level 0 (nesting at most MaxTextureDepth).

template <int D>
LU_TEXTURE_NOINLINE LU_HD Float EvalFloatTextureNode(const FloatTexture &tex, const TextureEvalContext &ctx,
                                                     const SceneView &scene);
template <int D>
LU_TEXTURE_NOINLINE LU_HD SampledSpectrum EvalSpectrumTextureNode(const SpectrumTexture &tex, const TextureEvalContext &ctx,
                                              const SampledWavelengths &lambda, const SceneView &scene);

template <int D>
LU_INLINE Float EvalFloatTextureLevel(const FloatTexture &tex, const TextureEvalContext &ctx, const SceneView &scene) {
    switch (tex.kind) {
    case TextureKind::Constant: return tex.value;
    case TextureKind::ImageMap: return EvalFloatImage(tex, ctx, scene);
    case TextureKind::Bilerp: {
        Vec2f st = Map2D(tex.mapping, ctx);
        return (1 - st.x) * (1 - st.y) * tex.v00 + st.x * (1 - st.y) * tex.v10 + (1 - st.x) * st.y * tex.v01 +
               st.x * st.y * tex.v11;
    }
    case TextureKind::FBm:
    case TextureKind::Wrinkled:
    case TextureKind::Windy: return EvalNoiseTexture(tex, ctx);
    default: break;
    }
    if constexpr (D > 0) {
        auto child = [&](uint32_t i) { return EvalFloatTextureNode<D - 1>(scene.floatTextures[i], ctx, scene); };
        switch (tex.kind) {
        case TextureKind::Scale: {
            Float sc = child(tex.amount);
            return sc == 0 ? Float(0) : child(tex.tex[0]) * sc;
        }
        case TextureKind::Mix: {
            Float amt = child(tex.amount);
            Float t1 = amt != 1 ? child(tex.tex[0]) : Float(0);
            Float t2 = amt != 0 ? child(tex.tex[1]) : Float(0);
            return (1 - amt) * t1 + amt * t2;
        }
        case TextureKind::DirectionMix: {
            Float amt = AbsDot(ctx.n, tex.dir);
            Float t1 = amt != 0 ? child(tex.tex[0]) : Float(0);
            Float t2 = amt != 1 ? child(tex.tex[1]) : Float(0);
            return amt * t1 + (1 - amt) * t2;
        }
        case TextureKind::Checkerboard: {
            Float w = tex.mapping.kind == TextureMappingKind::Point ? Checkerboard3D(Map3D(tex.mapping, ctx))
                                                                   : Checkerboard(Map2D(tex.mapping, ctx));
            Float t0 = w != 1 ? child(tex.tex[0]) : Float(0);
            Float t1 = w != 0 ? child(tex.tex[1]) : Float(0);
            return (1 - w) * t0 + w * t1;
        }
        case TextureKind::Dots: return child(InsidePolkaDot(Map2D(tex.mapping, ctx)) ? tex.tex[0] : tex.tex[1]);
        default: break;
        }
    }
    return 0;
}

template <int D>
LU_INLINE SampledSpectrum EvalSpectrumTextureLevel(const SpectrumTexture &tex, const TextureEvalContext &ctx,
                                                   const SampledWavelengths &lambda, const SceneView &scene) {
    switch (tex.kind) {
    case TextureKind::Constant: return SampleSpectrum(tex.value, lambda, scene.spectra);
    case TextureKind::ImageMap: return EvalSpectrumImage(tex, ctx, lambda, scene);
    case TextureKind::Marble: return EvalMarble(tex, ctx, lambda, scene);
    default: break;
    }
    if constexpr (D > 0) {
        auto child = [&](uint32_t i) {
            return EvalSpectrumTextureNode<D - 1>(scene.spectrumTextures[i], ctx, lambda, scene);
        };
        auto floatChild = [&](uint32_t i) { return EvalFloatTextureNode<D - 1>(scene.floatTextures[i], ctx, scene); };
        switch (tex.kind) {
        case TextureKind::Scale: {
            Float sc = floatChild(tex.amount);
            return sc == 0 ? SampledSpectrum(0) : child(tex.tex[0]) * sc;
        }
        case TextureKind::Mix: {
            Float amt = floatChild(tex.amount);
            SampledSpectrum t1(0), t2(0);
            if (amt != 1) t1 = child(tex.tex[0]);
            if (amt != 0) t2 = child(tex.tex[1]);
            return t1 * (1 - amt) + t2 * amt;
        }
        case TextureKind::DirectionMix: {
            Float amt = AbsDot(ctx.n, tex.dir);
            SampledSpectrum t1(0), t2(0);
            if (amt != 0) t1 = child(tex.tex[0]);
            if (amt != 1) t2 = child(tex.tex[1]);
            return t1 * amt + t2 * (1 - amt);
        }
        case TextureKind::Bilerp: {
            Vec2f st = Map2D(tex.mapping, ctx);
            return child(tex.tex[0]) * ((1 - st.x) * (1 - st.y)) + child(tex.tex[2]) * (st.x * (1 - st.y)) +
                   child(tex.tex[1]) * ((1 - st.x) * st.y) + child(tex.tex[3]) * (st.x * st.y);
        }
        case TextureKind::Checkerboard: {
            Float w = tex.mapping.kind == TextureMappingKind::Point ? Checkerboard3D(Map3D(tex.mapping, ctx))
                                                                   : Checkerboard(Map2D(tex.mapping, ctx));
            SampledSpectrum t0(0), t1(0);
            if (w != 1) t0 = child(tex.tex[0]);
            if (w != 0) t1 = child(tex.tex[1]);
            return t0 * (1 - w) + t1 * w;
        }
        case TextureKind::Dots: return child(InsidePolkaDot(Map2D(tex.mapping, ctx)) ? tex.tex[0] : tex.tex[1]);
        default: break;
        }
    }
    return SampledSpectrum(0);
}

template <int D>
LU_TEXTURE_NOINLINE LU_HD Float EvalFloatTextureNode(const FloatTexture &tex, const TextureEvalContext &ctx,
                                                     const SceneView &scene) {
    return EvalFloatTextureLevel<D>(tex, ctx, scene);
}
template <int D>
LU_TEXTURE_NOINLINE LU_HD SampledSpectrum EvalSpectrumTextureNode(const SpectrumTexture &tex, const TextureEvalContext &ctx,
                                                                  const SampledWavelengths &lambda, const SceneView &scene) {
    return EvalSpectrumTextureLevel<D>(tex, ctx, lambda, scene);
}

// A material's texture (its children in scene.floatTextures / spectrumTextures).
LU_INLINE Float EvalFloatTexture(const FloatTexture &tex, const TextureEvalContext &ctx, const SceneView &scene) {
    return EvalFloatTextureLevel<MaxTextureDepth>(tex, ctx, scene);
}

LU_INLINE SampledSpectrum EvalSpectrumTexture(const SpectrumTexture &tex, const TextureEvalContext &ctx,
                                              const SampledWavelengths &lambda, const SceneView &scene) {
    return EvalSpectrumTextureLevel<MaxTextureDepth>(tex, ctx, lambda, scene);
}

}  // namespace lu
