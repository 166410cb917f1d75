// Lucerna: scattering building blocks of the BxDFs (host and device): dielectric and conductor
// Fresnel, the anisotropic Trowbridge-Reitz distribution with visible-normal sampling, and the
// Henyey-Greenstein phase function. Follows pbrt-v4's util/scattering.h and util/sampling.h.
#pragma once

#include "lucerna/util/vecmath.h"
#include "lucerna/spectrum/sampled.h"

namespace lu {

// Uniform point on the unit disk by the polar map (r = sqrt(u0), phi = 2 pi u1).
LU_INLINE Vec2f SampleUniformDiskPolar(Vec2f u) {
    Float r = std::sqrt(u.x);
    Float theta = 2 * Pi * u.y;
    return {r * std::cos(theta), r * std::sin(theta)};
}

// ---- Fresnel ----

// Unpolarized Fresnel reflectance of a dielectric interface with relative index eta = n_t / n_i.
// cosTheta_i < 0 means the incident direction is on the inside (eta is inverted). 1 on TIR.
LU_INLINE Float FrDielectric(Float cosTheta_i, Float eta) {
    cosTheta_i = Clamp(cosTheta_i, Float(-1), Float(1));
    if (cosTheta_i < 0) {
        eta = 1 / eta;
        cosTheta_i = -cosTheta_i;
    }
    Float sin2Theta_i = 1 - Sqr(cosTheta_i);
    Float sin2Theta_t = sin2Theta_i / Sqr(eta);
    if (sin2Theta_t >= 1) return 1;
    Float cosTheta_t = SafeSqrt(1 - sin2Theta_t);
    Float rParl = (eta * cosTheta_i - cosTheta_t) / (eta * cosTheta_i + cosTheta_t);
    Float rPerp = (cosTheta_i - eta * cosTheta_t) / (cosTheta_i + eta * cosTheta_t);
    return (Sqr(rParl) + Sqr(rPerp)) / 2;
}

// Minimal complex arithmetic for the conductor Fresnel term.
struct Complex {
    Float re = 0, im = 0;
    Complex() = default;
    LU_HD constexpr Complex(Float re, Float im = 0) : re(re), im(im) {}
    LU_HD Complex operator+(Complex b) const { return {re + b.re, im + b.im}; }
    LU_HD Complex operator-(Complex b) const { return {re - b.re, im - b.im}; }
    LU_HD Complex operator*(Complex b) const { return {re * b.re - im * b.im, re * b.im + im * b.re}; }
    LU_HD Complex operator/(Complex b) const {
        Float s = 1 / (b.re * b.re + b.im * b.im);
        return {s * (re * b.re + im * b.im), s * (im * b.re - re * b.im)};
    }
};
LU_INLINE Float Norm(Complex z) { return z.re * z.re + z.im * z.im; }
// Principal square root (branch cut on the negative real axis).
LU_INLINE Complex Sqrt(Complex z) {
    Float n = std::sqrt(Norm(z));
    if (n == 0) return {0, 0};
    Float t1 = std::sqrt(Float(0.5) * (n + std::abs(z.re)));
    Float t2 = Float(0.5) * z.im / t1;
    if (z.re >= 0) return {t1, t2};
    return {std::abs(t2), std::copysign(t1, z.im)};
}

// Fresnel reflectance of a conductor with complex relative index eta + i k (cosTheta_i in [0,1]).
LU_INLINE Float FrComplex(Float cosTheta_i, Complex eta) {
    cosTheta_i = Clamp(cosTheta_i, Float(0), Float(1));
    Float sin2Theta_i = 1 - Sqr(cosTheta_i);
    Complex sin2Theta_t = Complex(sin2Theta_i) / (eta * eta);
    Complex cosTheta_t = Sqrt(Complex(1) - sin2Theta_t);
    Complex ci(cosTheta_i);
    Complex rParl = (eta * ci - cosTheta_t) / (eta * ci + cosTheta_t);
    Complex rPerp = (ci - eta * cosTheta_t) / (ci + eta * cosTheta_t);
    return (Norm(rParl) + Norm(rPerp)) / 2;
}

// The scalar FrComplex per wavelength, written branch-free (selects) so that the loops vectorize;
// every lane computes the same IEEE operations, hence the same values.
LU_INLINE SampledSpectrum FrComplex(Float cosTheta_i, const SampledSpectrum &eta, const SampledSpectrum &k) {
    cosTheta_i = Clamp(cosTheta_i, Float(0), Float(1));
    Float sin2Theta_i = 1 - Sqr(cosTheta_i);
    Float er[NSpectrumSamples], ei[NSpectrumSamples], out[NSpectrumSamples];
    for (int i = 0; i < NSpectrumSamples; ++i) { er[i] = eta[i]; ei[i] = k[i]; }
    for (int i = 0; i < NSpectrumSamples; ++i) {
        Complex e(er[i], ei[i]);
        Complex sin2Theta_t = Complex(sin2Theta_i) / (e * e);
        Complex z = Complex(1) - sin2Theta_t;
        // Sqrt(z), principal branch, as Sqrt() above.
        Float n = std::sqrt(Norm(z));
        Float t1 = std::sqrt(Float(0.5) * (n + std::abs(z.re)));
        Float t2 = Float(0.5) * z.im / t1;
        bool pos = z.re >= 0;
        Complex cosTheta_t(n == 0 ? Float(0) : (pos ? t1 : std::abs(t2)),
                           n == 0 ? Float(0) : (pos ? t2 : std::copysign(t1, z.im)));
        Complex ci(cosTheta_i);
        Complex rParl = (e * ci - cosTheta_t) / (e * ci + cosTheta_t);
        Complex rPerp = (ci - e * cosTheta_t) / (ci + e * cosTheta_t);
        out[i] = (Norm(rParl) + Norm(rPerp)) / 2;
    }
    SampledSpectrum r;
    for (int i = 0; i < NSpectrumSamples; ++i) r[i] = out[i];
    return r;
}

// ---- Trowbridge-Reitz (GGX) microfacet distribution ----

// Directions are in the local shading frame (z = normal). D and the visible-normal density are
// with respect to solid angle of the microfacet normal wm.
struct TrowbridgeReitzDistribution {
    Float alphaX = 0, alphaY = 0;

    TrowbridgeReitzDistribution() = default;
    LU_HD TrowbridgeReitzDistribution(Float ax, Float ay) : alphaX(ax), alphaY(ay) {}

    // pbrt-v4's remapping of the user-facing "roughness" parameter.
    LU_HD static Float RoughnessToAlpha(Float roughness) { return std::sqrt(roughness); }

    // Below this alpha the surface is treated as perfectly smooth (a Dirac lobe).
    LU_HD bool EffectivelySmooth() const { return Max(alphaX, alphaY) < 1e-3f; }

    LU_HD Float D(const Vec3f &wm) const {
        Float tan2Theta = Tan2Theta(wm);
        if (std::isinf(tan2Theta)) return 0;
        Float cos4Theta = Sqr(Cos2Theta(wm));
        if (cos4Theta < 1e-16f) return 0;
        // Isotropic: cos^2 phi + sin^2 phi = 1, without SinTheta's sqrt and the four divisions.
        Float e = alphaX == alphaY ? tan2Theta / Sqr(alphaX)
                                   : tan2Theta * (Sqr(CosPhi(wm) / alphaX) + Sqr(SinPhi(wm) / alphaY));
        return 1 / (Pi * alphaX * alphaY * cos4Theta * Sqr(1 + e));
    }

    LU_HD Float Lambda(const Vec3f &w) const {
        Float tan2Theta = Tan2Theta(w);
        if (std::isinf(tan2Theta)) return 0;
        Float alpha2 = alphaX == alphaY ? Sqr(alphaX)   // isotropic, as in D
                                        : Sqr(CosPhi(w) * alphaX) + Sqr(SinPhi(w) * alphaY);
        return (std::sqrt(1 + alpha2 * tan2Theta) - 1) / 2;
    }
    LU_HD Float G1(const Vec3f &w) const { return 1 / (1 + Lambda(w)); }
    // Height-correlated masking-shadowing.
    LU_HD Float G(const Vec3f &wo, const Vec3f &wi) const { return 1 / (1 + Lambda(wo) + Lambda(wi)); }

    // Distribution of normals visible from w: G1(w) max(0, w.wm) D(wm) / cos(w) (|.| as pbrt-v4).
    LU_HD Float D(const Vec3f &w, const Vec3f &wm) const {
        return G1(w) / AbsCosTheta(w) * D(wm) * AbsDot(w, wm);
    }
    LU_HD Float PDF(const Vec3f &w, const Vec3f &wm) const { return D(w, wm); }

    // Samples a visible normal (always in the +z hemisphere) for direction w (Heitz 2018).
    LU_HD Vec3f Sample_wm(const Vec3f &w, Vec2f u) const {
        Vec3f wh = Normalize(Vec3f(alphaX * w.x, alphaY * w.y, w.z));
        if (wh.z < 0) wh = -wh;
        Vec3f t1 = (wh.z < 0.99999f) ? Normalize(Cross(Vec3f(0, 0, 1), wh)) : Vec3f(1, 0, 0);
        Vec3f t2 = Cross(wh, t1);
        Vec2f p = SampleUniformDiskPolar(u);
        Float h = std::sqrt(1 - Sqr(p.x));
        p.y = Lerp((1 + wh.z) / 2, h, p.y);
        Float pz = std::sqrt(Max(Float(0), 1 - Sqr(p.x) - Sqr(p.y)));
        Vec3f nh = t1 * p.x + t2 * p.y + wh * pz;
        return Normalize(Vec3f(alphaX * nh.x, alphaY * nh.y, Max(Float(1e-6f), nh.z)));
    }
};

// ---- Henyey-Greenstein phase function ----

// pbrt-v4 convention: wo and wi both point away from the scattering point, so g > 0 favours
// wi close to -wo (forward scattering). pdf over solid angle.
LU_INLINE Float HenyeyGreenstein(Float cosTheta, Float g) {
    g = Clamp(g, Float(-.99), Float(.99));
    Float denom = 1 + Sqr(g) + 2 * g * cosTheta;
    return Inv4Pi * (1 - Sqr(g)) / (denom * SafeSqrt(denom));
}

LU_INLINE Vec3f SampleHenyeyGreenstein(const Vec3f &wo, Float g, Vec2f u, Float *pdf) {
    g = Clamp(g, Float(-.99), Float(.99));
    Float cosTheta;
    if (std::abs(g) < 1e-3f)
        cosTheta = 1 - 2 * u.x;
    else
        cosTheta = -1 / (2 * g) * (1 + Sqr(g) - Sqr((1 - Sqr(g)) / (1 + g - 2 * g * u.x)));
    Float sinTheta = SafeSqrt(1 - Sqr(cosTheta));
    Float phi = 2 * Pi * u.y;
    Frame f = Frame::FromZ(wo);
    Vec3f wi = f.FromLocal(SphericalDirection(sinTheta, cosTheta, phi));
    if (pdf) *pdf = HenyeyGreenstein(cosTheta, g);
    return wi;
}

}  // namespace lu
