// Lucerna: light sampling and emission for point, spot, goniometric, projection, distant, diffuse
// area (constant or image), uniform and image infinite lights (host and device), after pbrt-v4's
// lights.h/.cpp: SampleLi / PDF_Li / L / Le, with shape sampling in shape_sampling.h and the
// power-based light selection in light_sampler.h.
#pragma once

#include "lucerna/lights/equal_area.h"
#include "lucerna/lights/rgb_illuminant.h"
#include "lucerna/lights/shape_sampling.h"
#include "lucerna/materials/texture.h"
#include "lucerna/sampling/distribution.h"
#include "lucerna/sampling/hash.h"

namespace lu {

// An incident-radiance sample from one light at the reference point.
struct LightLiSample {
    SampledSpectrum L;             // radiance arriving along -wi (intensity / r^2 for point and spot)
    Vec3f wi;                      // unit, from the reference point towards the light
    Float pdf = 0;                 // solid angle at ctx.p (pdfW); 1 for delta lights
    Vec3f pLight;                  // the sampled light point (infinite and distant: ctx.p + 2 R wi)
    Vec3f nLight;                  // geometric normal at pLight (area lights), else (0,0,0)
    Vec2f uvLight;                 // surface uv at pLight (area lights with an alpha or an image)
    Float distance = Infinity;     // shadow-ray length to pLight; Infinity for distant/infinite
    bool isDelta = false;
};

LU_INLINE bool IsDeltaLight(const Light &l) {
    return l.kind == LightKind::Point || l.kind == LightKind::Spot || l.kind == LightKind::Distant ||
           l.kind == LightKind::Goniometric || l.kind == LightKind::Projection;
}

LU_INLINE bool IsInfiniteLight(const Light &l) {
    return l.kind == LightKind::UniformInfinite || l.kind == LightKind::ImageInfinite;
}

// pbrt-v4's SmoothStep: 0 below a, 1 above b, Hermite in between (a == b: a step at a).
LU_INLINE Float SmoothStep(Float x, Float a, Float b) {
    if (a == b) return x < a ? 0 : 1;
    Float t = Clamp((x - a) / (b - a), Float(0), Float(1));
    return t * t * (3 - 2 * t);
}

// Spot light falloff for a unit direction wLight in light space (+z is the spot axis).
LU_INLINE Float SpotFalloff(const Light &l, const Vec3f &wLight) {
    return SmoothStep(wLight.z, l.cosFalloffEnd, l.cosFalloffStart);
}

// The value at equal-area coordinates uv of a one-channel profile table: pbrt-v4's nearest texel
// (GoniometricLight::I: coordinates clamped), or for a vertex table ((n+1) x (n+1) samples at
// uv = (i, j) / n, n even: tables made from IES files) linear on the two triangles of each cell,
// split along the diagonal parallel to the map's fold in that quadrant (|u| + |v| = 1 in
// [-1,1]^2, the equator), so that no triangle straddles a fold (the edges and the axes are cell
// edges): the interpolant is continuous on the sphere and second-order accurate everywhere.
LU_INLINE Float ProfileValueAt(const ImageData &im, const Float *texels, Vec2f uv, bool vertices) {
    const Float *t = texels + im.offset;
    int width = int(im.width), height = int(im.height);
    if (!vertices) {
        int x = Clamp(int(uv.x * Float(width)), 0, width - 1), y = Clamp(int(uv.y * Float(height)), 0, height - 1);
        return t[uint64_t(y) * uint32_t(width) + uint32_t(x)];
    }
    int n = width - 1;
    Float px = uv.x * Float(n), py = uv.y * Float(n);
    int i = Clamp(int(std::floor(px)), 0, n - 1), j = Clamp(int(std::floor(py)), 0, n - 1);
    Float fx = Clamp(px - Float(i), Float(0), Float(1)), fy = Clamp(py - Float(j), Float(0), Float(1));
    const Float *row0 = t + uint64_t(j) * uint32_t(width) + uint32_t(i), *row1 = row0 + width;
    Float v00 = row0[0], v10 = row0[1], v01 = row1[0], v11 = row1[1];
    if ((2 * i >= n) == (2 * j >= n)) {   // fold along x + y = const: split from (1, 0) to (0, 1)
        if (fx + fy <= 1) return v00 + fx * (v10 - v00) + fy * (v01 - v00);
        return v11 + (1 - fx) * (v01 - v11) + (1 - fy) * (v10 - v11);
    }
    // fold along x - y = const: split from (0, 0) to (1, 1)
    if (fx >= fy) return v00 + fx * (v10 - v00) + fy * (v11 - v10);
    return v00 + fy * (v01 - v00) + fx * (v11 - v01);
}

// The intensity scale of l's profile table (Light::profile) at the unit light-space direction w.
LU_INLINE Float ProfileValue(const Light &l, const SceneView &s, Vec3f w) {
    return ProfileValueAt(s.images[l.profile], s.texels.ptr, EqualAreaSphereToSquare(w), l.profileVertices);
}

// ---- Projection light (pbrt-v4's ProjectionLight) ----

// Texel (x, y) of an RGB(A) or one-channel image as RGB.
LU_INLINE void ImageRGB(const SceneView &s, const ImageData &im, int x, int y, Float rgb[3]) {
    const Float *t = s.texels.ptr + im.offset + (uint64_t(y) * im.width + x) * im.channels;
    for (int c = 0; c < 3; ++c) rgb[c] = t[im.channels >= 3 ? c : 0];
}

// The image coordinates (st in [0,1]^2, st.y = 0 at the top row) that the light-space unit
// direction w projects to; false behind the near plane (w.z < 1e-3, pbrt-v4's hither) or outside
// the screen window (its edges belong to it, as pbrt-v4's Inside).
LU_INLINE bool ProjectionImageST(const Light &l, Vec3f w, Vec2f *st) {
    if (!(w.z >= Float(1e-3))) return false;
    Float sx = w.x / (w.z * l.projectionTan), sy = w.y / (w.z * l.projectionTan);
    Vec2f half = l.projectionScreen;
    if (!(sx >= -half.x && sx <= half.x && sy >= -half.y && sy <= half.y)) return false;
    *st = Vec2f((sx + half.x) / (2 * half.x), (sy + half.y) / (2 * half.y));
    return true;
}

// Intensity of a projection light towards the light-space unit direction w: the nearest texel
// (coordinates truncated and clamped, pbrt-v4's LookupNearestChannel) as an RGB illuminant
// spectrum, times scale; 0 outside the frustum.
LU_INLINE SampledSpectrum ProjectionI(const Light &l, const SceneView &s, Vec3f w, const SampledWavelengths &lambda) {
    Vec2f st;
    if (!ProjectionImageST(l, w, &st)) return SampledSpectrum(0);
    const ImageData &im = s.images[l.image];
    int x = Clamp(int(st.x * Float(im.width)), 0, int(im.width) - 1);
    int y = Clamp(int(st.y * Float(im.height)), 0, int(im.height) - 1);
    Float rgb[3];
    ImageRGB(s, im, x, y, rgb);
    return SampleSpectrum(RGBIlluminantSpectrum(s, rgb, im.colorSpace), lambda, s.spectra) * l.scale;
}

// Radiance leaving an area light point p (normal n, surface uv) in direction w. One-sided lights
// emit only on the side n points to. With an image (Light::image): pbrt-v4's bilinear lookup at
// (u, 1 - v) (the image's top row at v = 1), clamped at the edges, as an RGB illuminant spectrum.
LU_INLINE SampledSpectrum AreaLightL(const Light &l, const SceneView &s, Vec3f /*p*/, Vec3f n, Vec2f uv, Vec3f w,
                                     const SampledWavelengths &lambda) {
    if (l.kind != LightKind::DiffuseArea) return SampledSpectrum(0);
    if (!l.twoSided && Dot(n, w) < 0) return SampledSpectrum(0);
    if (l.image != NoIndex) {
        const ImageData &im = s.images[l.image];
        Vec2f st(uv.x, 1 - uv.y);
        Float rgb[3];
        for (int c = 0; c < 3; ++c) rgb[c] = ImageBilerp(im, s, st, im.channels >= 3 ? c : 0);
        return SampleSpectrum(RGBIlluminantSpectrum(s, rgb, im.colorSpace), lambda, s.spectra) * l.scale;
    }
    return SampleSpectrum(l.spectrum, lambda, s.spectra) * l.scale;
}

// pbrt-v4's DiffuseAreaLight::AlphaMasked: the emitting shape's alpha a at light point p (uv: its
// surface uv; the texture sees no normal, as pbrt-v4's Interaction(p, uv)) cuts the emission out
// where a <= 0, or where HashFloat(p) > a for 0 < a < 1 (a hash of the point, so that light
// sampling and emitter hits agree). SampleLi and emitter hits test it; AreaLightL does not.
LU_INLINE bool AreaLightAlphaMasked(const Light &l, const SceneView &s, Vec3f p, Vec2f uv) {
    uint32_t alpha = s.shapes[l.shape].alpha;
    if (alpha == NoIndex) return false;
    TextureEvalContext ctx;
    ctx.p = p;
    ctx.n = Vec3f(0, 0, 0);
    ctx.uv = uv;
    Float a = EvalFloatTexture(s.floatTextures[alpha], ctx, s);
    if (a >= 1) return false;
    if (a <= 0) return true;
    return HashFloat(p) > a;
}

// ---- Image infinite light ----

// Emitted radiance of an image infinite light at equal-area image coordinates uv (nearest texel,
// octahedral wrap), as pbrt-v4's ImageInfiniteLight::ImageLe.
LU_INLINE SampledSpectrum ImageInfiniteLe(const Light &l, const SceneView &s, Vec2f uv,
                                          const SampledWavelengths &lambda) {
    const ImageData &im = s.images[l.image];
    int x = int(uv.x * Float(im.width)), y = int(uv.y * Float(im.height));
    WrapOctahedral(&x, &y, int(im.width), int(im.height));
    Float rgb[3];
    ImageRGB(s, im, x, y, rgb);
    return SampleSpectrum(RGBIlluminantSpectrum(s, rgb, im.colorSpace), lambda, s.spectra) * l.scale;
}

// Radiance arriving along an escaped ray with unit direction dir, from an infinite light.
LU_INLINE SampledSpectrum InfiniteLightLe(const Light &l, const SceneView &s, Vec3f dir,
                                          const SampledWavelengths &lambda) {
    if (l.kind == LightKind::UniformInfinite) return SampleSpectrum(l.spectrum, lambda, s.spectra) * l.scale;
    if (l.kind == LightKind::ImageInfinite) {
        Vec3f wLight = Normalize(l.renderFromLight.Inverted().ApplyVector(dir));
        return ImageInfiniteLe(l, s, EqualAreaSphereToSquare(wLight), lambda);
    }
    return SampledSpectrum(0);
}

// The two distributions of an image infinite light: l.distribution is pbrt-v4's plain one, and
// l.distribution + 1 the MIS-compensated one (see BuildImageInfiniteDistributions).
LU_INLINE const Distribution2D &ImageLightDistribution(const Light &l, const SceneView &s, bool allowIncompletePDF) {
    return s.distributions2D[l.distribution + (allowIncompletePDF ? 1 : 0)];
}

// ---- SampleLi / PDF_Li ----

// Samples incident radiance from light l at ctx. Returns false when no sample was produced (the
// caller adds nothing). allowIncompletePDF selects pbrt-v4's MIS-aware sampling for infinite
// lights (uniform infinite: no light sample; image: the compensated distribution); pass the same
// value to PDF_Li. pbrt-v4's PathIntegrator passes true.
LU_INLINE bool SampleLi(const Light &l, const SceneView &s, const LightSampleContext &ctx, Vec2f u,
                        const SampledWavelengths &lambda, LightLiSample *ls, bool allowIncompletePDF = false) {
    // The defaults of LightLiSample, stored field by field (a whole-struct assignment goes
    // through a stack temporary whose narrow stores stall the wide reloads).
    ls->L = SampledSpectrum(0);
    ls->wi = ls->pLight = ls->nLight = Vec3f(0, 0, 0);
    ls->uvLight = Vec2f(0, 0);
    ls->pdf = 0;
    ls->distance = Infinity;
    ls->isDelta = false;
    switch (l.kind) {
    case LightKind::Point:
    case LightKind::Spot:
    case LightKind::Goniometric:
    case LightKind::Projection: {
        Vec3f d = l.position - ctx.p;
        Float d2 = LengthSquared(d);
        if (d2 == 0) return false;
        ls->wi = d / std::sqrt(d2);
        SampledSpectrum I;
        if (l.kind == LightKind::Projection)
            I = ProjectionI(l, s, Normalize(l.renderFromLight.Inverted().ApplyVector(-ls->wi)), lambda);
        else
            I = SampleSpectrum(l.spectrum, lambda, s.spectra) * l.scale;
        if (l.kind == LightKind::Spot) {
            Vec3f wLight = Normalize(l.renderFromLight.Inverted().ApplyVector(-ls->wi));
            I *= SpotFalloff(l, wLight);
            // An IES profile on a spot light: its nadir is the spot axis (+z), C0 the frame's +x.
            if (l.profile != NoIndex) I *= ProfileValue(l, s, Vec3f(wLight.x, wLight.y, -wLight.z));
        } else if (l.kind == LightKind::Goniometric) {
            I *= ProfileValue(l, s, Normalize(l.renderFromLight.Inverted().ApplyVector(-ls->wi)));
        }
        ls->L = I / d2;
        ls->pdf = 1;
        ls->pLight = l.position;
        ls->distance = std::sqrt(d2);
        ls->isDelta = true;
        return !ls->L.IsBlack();
    }
    case LightKind::Distant: {
        ls->wi = Normalize(l.direction);
        ls->L = SampleSpectrum(l.spectrum, lambda, s.spectra) * l.scale;
        ls->pdf = 1;
        ls->pLight = ctx.p + ls->wi * (2 * l.sceneRadius);
        ls->isDelta = true;
        return !ls->L.IsBlack();
    }
    case LightKind::DiffuseArea: {
        const Shape &shape = s.shapes[l.shape];
        ShapeSample ss;
        if (!SampleShape(s, shape, l.primitive, ctx, u, &ss, /*wantUV=*/shape.alpha != NoIndex || l.image != NoIndex) ||
            !(ss.pdf > 0))
            return false;
        Vec3f d = ss.p - ctx.p;
        Float dist = Length(d);
        if (dist == 0) return false;
        if (shape.alpha != NoIndex && AreaLightAlphaMasked(l, s, ss.p, ss.uv)) return false;
        ls->wi = d / dist;
        ls->L = AreaLightL(l, s, ss.p, ss.n, ss.uv, -ls->wi, lambda);
        if (ls->L.IsBlack()) return false;
        ls->pdf = ss.pdf;
        ls->pLight = ss.p;
        ls->nLight = ss.n;
        ls->uvLight = ss.uv;
        ls->distance = dist;
        return true;
    }
    case LightKind::UniformInfinite: {
        if (allowIncompletePDF) return false;
        ls->wi = SampleUniformSphere(u);
        ls->pdf = UniformSpherePDF();
        ls->L = SampleSpectrum(l.spectrum, lambda, s.spectra) * l.scale;
        ls->pLight = ctx.p + ls->wi * (2 * l.sceneRadius);
        return !ls->L.IsBlack();
    }
    case LightKind::ImageInfinite: {
        Float mapPDF = 0;
        Vec2f uv = SampleDistribution2D(s, ImageLightDistribution(l, s, allowIncompletePDF), u, &mapPDF);
        if (mapPDF == 0) return false;
        Vec3f wLight = EqualAreaSquareToSphere(uv);
        ls->wi = Normalize(l.renderFromLight.ApplyVector(wLight));
        ls->pdf = mapPDF / (4 * Pi);  // the equal-area map has constant Jacobian 4 pi
        ls->L = ImageInfiniteLe(l, s, uv, lambda);
        ls->pLight = ctx.p + ls->wi * (2 * l.sceneRadius);
        return !ls->L.IsBlack();
    }
    case LightKind::Collimated: break;   // needs the pass's cone: SampleBeamLi (lights/collimated.h)
    }
    return false;
}

// Solid-angle pdf at ctx.p that SampleLi returns direction wi (unit). For area lights, pLight is
// where wi hits the light and nLight its geometric normal there (found by the caller's ray);
// infinite lights ignore them. 0 for delta lights.
LU_INLINE Float PDF_Li(const Light &l, const SceneView &s, const LightSampleContext &ctx, Vec3f wi, Vec3f pLight,
                       Vec3f nLight, bool allowIncompletePDF = false) {
    switch (l.kind) {
    case LightKind::DiffuseArea: return ShapePDF(s, s.shapes[l.shape], l.primitive, ctx, wi, pLight, nLight);
    case LightKind::UniformInfinite: return allowIncompletePDF ? 0 : UniformSpherePDF();
    case LightKind::ImageInfinite: {
        Vec3f wLight = Normalize(l.renderFromLight.Inverted().ApplyVector(wi));
        Vec2f uv = EqualAreaSphereToSquare(wLight);
        return Distribution2DPDF(s, ImageLightDistribution(l, s, allowIncompletePDF), uv) / (4 * Pi);
    }
    default: return 0;
    }
}

}  // namespace lu

#include "lucerna/lights/light_sampler.h"
