// Lucerna (host): light power (pbrt-v4 Light::Phi; goniometric and IES profiles, projection and
// image area lights included), the
// power light-selection CDF of lights/light_sampler.h (PowerLightSampler) and the image infinite
// light's distributions.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "lucerna/lights/collimated.h"
#include "lucerna/lights/light_sampler.h"
#include "lucerna/scene/distribution_build.h"

namespace lu {

// The integral over the sphere of a profile table, without scale and spectrum: pbrt-v4's
// GoniometricLight::Phi for images (4 pi times the mean texel: each subtends 4 pi / N sr); for a
// vertex table, 4 pi times the mean of its interpolant (midpoint rule over the n x n cells).
// falloff (optional): a factor of the light-space direction (a spot light's cone, whose axis is
// the table's -z).
inline double ProfileIntegral(const ImageData &im, const Float *texels, bool vertices, const Light *spot = nullptr) {
    uint32_t n = vertices ? im.width - 1 : im.width;
    double sum = 0;
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
            Vec2f uv((Float(x) + 0.5f) / Float(n), (Float(y) + 0.5f) / Float(n));
            double v = vertices ? ProfileValueAt(im, texels, uv, true) : texels[im.offset + uint64_t(y) * im.width + x];
            if (spot) {
                Vec3f w = EqualAreaSquareToSphere(uv);
                v *= SpotFalloff(*spot, Vec3f(w.x, w.y, -w.z));
            }
            sum += v;
        }
    return 4 * Pi * sum / (double(n) * n);
}

// Projection light: the change of variables from the screen window (at distance 1 along the axis)
// to solid angle at the center of texel (x, y), d omega / dA = cos^3 theta (pbrt-v4's dwdA), times
// the texel's area A / N there: the solid angle the texel subtends, to first order.
inline double ProjectionTexelSolidAngle(const Light &l, const ImageData &im, uint32_t x, uint32_t y) {
    double t = l.projectionTan;
    double sx = (2 * (double(x) + 0.5) / im.width - 1) * l.projectionScreen.x;
    double sy = (2 * (double(y) + 0.5) / im.height - 1) * l.projectionScreen.y;
    double cosTheta = 1 / std::sqrt(1 + t * t * (sx * sx + sy * sy));
    double area = 4 * t * t * double(l.projectionScreen.x) * double(l.projectionScreen.y);
    return cosTheta * cosTheta * cosTheta * area / (double(im.width) * im.height);
}

// The mean over an RGB image's texels of their RGB illuminant spectra at lambda (pbrt-v4's
// DiffuseAreaLight::Phi); weight (optional): a factor per texel (x, y).
template <typename Weight>
inline SampledSpectrum ImageSpectrumSum(const SceneView &s, const ImageData &im, const SampledWavelengths &lambda,
                                        Weight weight) {
    SampledSpectrum sum(0);
    for (uint32_t y = 0; y < im.height; ++y)
        for (uint32_t x = 0; x < im.width; ++x) {
            Float rgb[3];
            ImageRGB(s, im, int(x), int(y), rgb);
            sum += SampleSpectrum(RGBIlluminantSpectrum(s, rgb, im.colorSpace), lambda, s.spectra) * Float(weight(x, y));
        }
    return sum;
}

// pbrt-v4's Light::Phi(lambda): emitted power at the sampled wavelengths.
inline SampledSpectrum LightPhi(const Light &l, const SceneView &s, const SampledWavelengths &lambda) {
    SampledSpectrum spec = SampleSpectrum(l.spectrum, lambda, s.spectra) * l.scale;
    switch (l.kind) {
    case LightKind::Point: return spec * (4 * Pi);
    case LightKind::Spot:
        if (l.profile != NoIndex)
            return spec * Float(ProfileIntegral(s.images[l.profile], s.texels.ptr, l.profileVertices, &l));
        return spec * (2 * Pi * ((1 - l.cosFalloffStart) + (l.cosFalloffStart - l.cosFalloffEnd) / 2));
    case LightKind::Goniometric:
        return spec * Float(ProfileIntegral(s.images[l.profile], s.texels.ptr, l.profileVertices));
    case LightKind::Distant: return spec * (Pi * Sqr(l.sceneRadius));
    case LightKind::DiffuseArea: {
        if (l.image != NoIndex) {   // the image's mean spectrum (pbrt-v4: no distortion of the uv mapping)
            const ImageData &im = s.images[l.image];
            spec = ImageSpectrumSum(s, im, lambda, [](uint32_t, uint32_t) { return 1.0; }) *
                   (l.scale / Float(uint64_t(im.width) * im.height));
        }
        return spec * (Pi * (l.twoSided ? 2 : 1) * ShapeArea(s, s.shapes[l.shape], l.primitive));
    }
    case LightKind::Projection: {
        const ImageData &im = s.images[l.image];
        return ImageSpectrumSum(s, im, lambda, [&](uint32_t x, uint32_t y) {
                   return ProjectionTexelSolidAngle(l, im, x, y);
               }) * l.scale;
    }
    case LightKind::UniformInfinite: return spec * (4 * Pi * Pi * Sqr(l.sceneRadius));
    case LightKind::ImageInfinite: {
        const ImageData &im = s.images[l.image];
        SampledSpectrum sum = ImageSpectrumSum(s, im, lambda, [](uint32_t, uint32_t) { return 1.0; });
        return sum * (4 * Pi * Pi * Sqr(l.sceneRadius) * l.scale / Float(uint64_t(im.width) * im.height));
    }
    case LightKind::Collimated: return spec * BeamProfileIntegral(l);
    }
    return SampledSpectrum(0);
}

// The power pbrt-v4's PowerLightSampler assigns to a light: Phi at the wavelengths
// SampleVisible(0.5), divided by their pdfs, averaged (an estimate of the integral of Phi over
// wavelength). Collimated beams (a Lucerna extension) get that integral exactly, 1 nm steps over
// 360-830 nm: a laser line a few nm wide would fall between the four wavelengths and get no
// light samples at all.
inline Float LightPower(const Light &l, const SceneView &s) {
    if (l.kind == LightKind::Collimated) {
        double sum = 0;
        for (int nm = 360; nm <= 830; ++nm)
            sum += (nm == 360 || nm == 830 ? 0.5 : 1.0) * double(EvalSpectrum(l.spectrum, Float(nm), s.spectra));
        return Float(sum * double(l.scale) * double(BeamProfileIntegral(l)));
    }
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    return SafeDiv(LightPhi(l, s, lambda), lambda.PDF()).Average();
}

// The share of light selections that go to collimated beams, split evenly among them, when a
// scene has beams: the rest follows power. A beam concentrates its power on a spot, where it
// outshines lights thousands of times stronger; by power alone a 5 mW laser next to a 100 W
// lamp would get 1 light sample in 20,000 and its spot would stay noise.
constexpr double kBeamSelectionShare = 0.5;

// The light selection CDF (size lights + 1) proportional to LightPower (uniform if every light
// has zero power, as pbrt-v4), mixed with kBeamSelectionShare spread evenly over the collimated
// beams when there are any: pmf_i = (1 - s) Phi_i / sum Phi + s [i is a beam] / beams. Needs
// every field of s that LightPower reads (shapes, spectra, images, rgb table). Empty when there
// are no lights.
inline std::vector<Float> BuildLightCdf(const SceneView &s) {
    std::vector<Float> cdf;
    uint32_t n = s.lights.size;
    if (n == 0) return cdf;
    std::vector<double> power(n);
    double total = 0;
    uint32_t beams = 0;
    for (uint32_t i = 0; i < n; ++i) {
        Float p = LightPower(s.lights[i], s);
        power[i] = (p > 0 && std::isfinite(p)) ? double(p) : 0.0;
        total += power[i];
        beams += s.lights[i].kind == LightKind::Collimated;
    }
    if (total == 0) {
        for (auto &p : power) p = 1;
        total = n;
    }
    if (beams > 0) {
        for (uint32_t i = 0; i < n; ++i)
            power[i] = (1 - kBeamSelectionShare) * power[i] / total +
                       (s.lights[i].kind == LightKind::Collimated ? kBeamSelectionShare / beams : 0.0);
        total = 1;
    }
    cdf.resize(n + 1);
    cdf[0] = 0;
    double run = 0;
    for (uint32_t i = 0; i < n; ++i) {
        run += power[i];
        cdf[i + 1] = Float(run / total);
    }
    cdf[n] = 1;
    return cdf;
}

// The two sampling distributions of an image infinite light over a square equal-area RGB(A)
// image (row-major, top row first): pbrt-v4's `distribution` (average of the channels per
// texel) and the MIS-compensated one (max(0, v - average), all-ones if that is all zero).
// Appends both to `dists` (plain first) and returns the index of the plain one, which goes in
// Light::distribution.
inline uint32_t BuildImageInfiniteDistributions(const float *texels, int width, int height, int channels,
                                                std::vector<Distribution2D> &dists, std::vector<Float> &distData) {
    size_t count = size_t(width) * height;
    std::vector<float> d(count);
    double sum = 0;
    for (size_t i = 0; i < count; ++i) {
        const float *t = texels + i * channels;
        float v = channels >= 3 ? (t[0] + t[1] + t[2]) / 3 : t[0];
        d[i] = v;
        sum += v;
    }
    uint32_t index = uint32_t(dists.size());
    dists.push_back(BuildDistribution2D(d.data(), width, height, distData));
    float average = float(sum / double(count));
    bool allZero = true;
    for (float &v : d) {
        v = std::max(v - average, 0.f);
        if (v != 0) allZero = false;
    }
    if (allZero) std::fill(d.begin(), d.end(), 1.f);
    dists.push_back(BuildDistribution2D(d.data(), width, height, distData));
    return index;
}

}  // namespace lu
