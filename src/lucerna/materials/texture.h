// Lucerna: float and spectrum textures at a surface point (host and device): constant, 2D
// checkerboard, bilinear image maps over pbrt-v4's uv mapping (textures.cpp, Image::Bilerp).
// No ray differentials: lookups use the finest level unfiltered (pbrt-v4 filters by footprint).
#pragma once

#include "lucerna/core/interaction.h"
#include "lucerna/core/scene_data.h"
#include "lucerna/spectrum/rgb_to_spectrum.h"

namespace lu {

// (s, t) = (su u + du, sv v + dv), pbrt-v4's UVMapping.
LU_INLINE Vec2f MapUV(const UVMapping &m, Vec2f uv) { return {m.su * uv.x + m.du, m.sv * uv.y + m.dv}; }

// pbrt-v4's 2D checkerboard for a zero-width filter: 0 where floor(s) + floor(t) is even
// (tex1), 1 where odd (tex2).
LU_INLINE Float Checkerboard(Vec2f st) {
    int parity = (int(std::floor(st.x)) + int(std::floor(st.y))) & 1;
    return parity ? Float(1) : Float(0);
}

// ---- Images ----

// Texel (x, y), channel c, of an image stored row-major with row 0 at the top (pbrt-v4's Image),
// after applying the image's wrap mode; 0 outside for WrapMode::Black.
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

// Texture st -> image st: texture t = 0 is the bottom of the image (pbrt-v4 flips t).
LU_INLINE Vec2f TextureToImageST(Vec2f st) { return {st.x, 1 - st.y}; }

// ---- RGB -> spectrum for image texels ----

// pbrt-v4's RGBAlbedoSpectrum (rgb clamped to [0,1]) or RGBUnboundedSpectrum of the scene's
// color space table, sampled at lambda.
LU_INLINE SampledSpectrum RGBToSampledSpectrum(const Float rgb[3], bool unbounded, const SampledWavelengths &lambda,
                                               const SceneView &scene) {
    if (scene.rgbToSpecRes < 2 || scene.rgbToSpecCoeffs.empty()) return SampledSpectrum(0);
    const Float *coeffs = scene.rgbToSpecCoeffs.ptr, *zNodes = scene.rgbToSpecZNodes.ptr;
    Spectrum s = unbounded ? RGBUnboundedSpectrum(coeffs, zNodes, scene.rgbToSpecRes, rgb[0], rgb[1], rgb[2])
                           : RGBAlbedoSpectrum(coeffs, zNodes, scene.rgbToSpecRes, rgb[0], rgb[1], rgb[2]);
    return SampleSpectrum(s, lambda, scene.spectra);
}

// ---- Texture evaluation ----

LU_INLINE Float EvalFloatTexture(const FloatTexture &tex, const TextureEvalContext &ctx, const SceneView &scene) {
    switch (tex.kind) {
    case TextureKind::Constant: return tex.value;
    case TextureKind::Checkerboard: {
        Float wt = Checkerboard(MapUV(tex.mapping, ctx.uv));
        return (1 - wt) * tex.tex1 + wt * tex.tex2;
    }
    case TextureKind::ImageMap: {
        if (tex.image == NoIndex) return 0;
        const ImageData &img = scene.images[tex.image];
        Vec2f st = TextureToImageST(MapUV(tex.mapping, ctx.uv));
        Float v = tex.scale * ImageBilerp(img, scene, st, 0);
        return tex.invert ? Max(Float(0), 1 - v) : v;
    }
    }
    return 0;
}

LU_INLINE SampledSpectrum EvalSpectrumTexture(const SpectrumTexture &tex, const TextureEvalContext &ctx,
                                              const SampledWavelengths &lambda, const SceneView &scene) {
    switch (tex.kind) {
    case TextureKind::Constant: return SampleSpectrum(tex.value, lambda, scene.spectra);
    case TextureKind::Checkerboard: {
        Float wt = Checkerboard(MapUV(tex.mapping, ctx.uv));
        SampledSpectrum t0(0), t1(0);
        if (wt != 1) t0 = SampleSpectrum(tex.tex1, lambda, scene.spectra);
        if (wt != 0) t1 = SampleSpectrum(tex.tex2, lambda, scene.spectra);
        return t0 * (1 - wt) + t1 * wt;
    }
    case TextureKind::ImageMap: {
        if (tex.image == NoIndex) return SampledSpectrum(0);
        const ImageData &img = scene.images[tex.image];
        Vec2f st = TextureToImageST(MapUV(tex.mapping, ctx.uv));
        Float rgb[3];
        if (img.channels >= 3) {
            for (int c = 0; c < 3; ++c) rgb[c] = tex.scale * ImageBilerp(img, scene, st, c);
        } else {
            rgb[0] = rgb[1] = rgb[2] = tex.scale * ImageBilerp(img, scene, st, 0);
        }
        for (int c = 0; c < 3; ++c) rgb[c] = Max(Float(0), tex.invert ? 1 - rgb[c] : rgb[c]);
        return RGBToSampledSpectrum(rgb, tex.unbounded, lambda, scene);
    }
    }
    return SampledSpectrum(0);
}

}  // namespace lu
