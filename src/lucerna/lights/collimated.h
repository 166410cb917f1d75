// Lucerna: the collimated beam light (a Lucerna extension: laser, collimated LED), host and device.
// A disc emits irradiance E(y) along its normal n only: L(y, w) = E(y) delta(w - n). Under regpath
// the delta is replaced by the cone kernel K of half-angle sigma_N around n (regularized at the
// light): L_r(y, w) = E(y) K(w) / cos theta_y. See docs/lights.md.
#pragma once

#include "lucerna/integrators/regularization.h"
#include "lucerna/lights/lights.h"
#include "lucerna/sampling/warp.h"

namespace lu {

// The beam's cone for this pass: 1 - cos sigma_N, the angular schedule sigma_N = sigma0 N^-lambda
// of lights at infinity; 0 when the pass does not regularize (the beam cannot be reached then).
LU_INLINE Float BeamOneMinusCos(const RegularizationParams &rp) {
    return rp.enabled ? OneMinusCosAngle(rp.angle) : Float(0);
}

// The irradiance profile's shape at squared distance rho2 from the axis (1 at the axis): uniform
// (beamWaist == 0) or gaussian exp(-2 rho^2 / w^2) (w: the 1/e^2 radius); 0 outside the disc.
LU_INLINE Float BeamProfile(const Light &l, Float rho2) {
    if (!(rho2 <= Sqr(l.beamRadius))) return 0;
    return l.beamWaist > 0 ? std::exp(-2 * rho2 / Sqr(l.beamWaist)) : Float(1);
}

// The integral of BeamProfile over the disc: pi R^2 (uniform), pi w^2 / 2 (1 - exp(-2 R^2 / w^2))
// (gaussian truncated at R). The beam's power per unit wavelength is E_lambda(axis) times this.
LU_INLINE Float BeamProfileIntegral(Float radius, Float waist) {
    if (waist > 0) return Pi * Sqr(waist) / 2 * -std::expm1(-2 * Sqr(radius) / Sqr(waist));
    return Pi * Sqr(radius);
}

// Spectral irradiance at the disc point y (on a surface facing the beam).
LU_INLINE SampledSpectrum BeamIrradiance(const Light &l, const SceneView &s, Vec3f y, const SampledWavelengths &lambda) {
    Float g = BeamProfile(l, DistanceSquared(y, l.position));
    if (g == 0) return SampledSpectrum(0);
    return SampleSpectrum(l.spectrum, lambda, s.spectra) * (l.scale * g);
}

// Where the ray o + t d (d unit) crosses the beam's disc from its front (d against n), for
// tMin < t < tMax: true with *t and the point *y.
LU_INLINE bool BeamDiscCrossing(const Light &l, Vec3f o, Vec3f d, Float tMin, Float tMax, Float *t, Vec3f *y) {
    Float dn = Dot(d, l.direction);
    if (!(dn < 0)) return false;
    Float tt = Dot(l.position - o, l.direction) / dn;
    if (!(tt > tMin && tt < tMax)) return false;
    Vec3f p = o + d * tt;
    if (!(DistanceSquared(p, l.position) <= Sqr(l.beamRadius))) return false;
    *t = tt;
    *y = p;
    return true;
}

// The cone kernel's solid-angle density K(w) for the emitted direction wEmit (unit, leaving the
// disc): 1 / (2 pi (1 - cos sigma)) within sigma of n, else 0. The explicit technique samples
// directions towards the light with this density, so it is also that technique's pdfW.
LU_INLINE Float BeamKernel(const Light &l, Vec3f wEmit, Float oneMinusCos) {
    if (!(oneMinusCos > 0) || !(OneMinusCosBetween(wEmit, l.direction) < oneMinusCos)) return 0;
    return ConePdfW(oneMinusCos);
}

// Regularized radiance leaving disc point y along wEmit: E(y) K(wEmit) / cos theta_y.
LU_INLINE SampledSpectrum BeamRadiance(const Light &l, const SceneView &s, Vec3f y, Vec3f wEmit, Float oneMinusCos,
                                       const SampledWavelengths &lambda) {
    Float K = BeamKernel(l, wEmit, oneMinusCos);
    Float cosY = Dot(wEmit, l.direction);
    if (K == 0 || !(cosY > 0)) return SampledSpectrum(0);
    return BeamIrradiance(l, s, y, lambda) * (K / cosY);
}

// The explicit technique at ctx.p: a direction wi uniform in the cone of 1 - cos sigma =
// oneMinusCos around -n (pdfW = K), then the disc point y where the ray along wi meets the disc.
// ls->L = L_r(y, -wi), ls->pdf = K. False when the ray misses the disc or ctx.p is behind it.
LU_INLINE bool SampleBeamLi(const Light &l, const SceneView &s, const LightSampleContext &ctx, Vec2f u,
                            Float oneMinusCos, const SampledWavelengths &lambda, LightLiSample *ls) {
    if (!(oneMinusCos > 0)) return false;
    // 1 - cos theta = u (1 - cos sigma) keeps the tiny cones of late passes exact.
    Float omc = u.x * oneMinusCos;
    Float cosTheta = 1 - omc, sinTheta = SafeSqrt(omc * (2 - omc));
    Vec3f wl = SphericalDirection(sinTheta, cosTheta, 2 * Pi * u.y);   // around +z = n
    Frame f = Frame::FromZ(l.direction);
    Vec3f wEmit = Normalize(f.FromLocal(wl));
    Vec3f wi = -wEmit;
    Float t;
    Vec3f y;
    if (!BeamDiscCrossing(l, ctx.p, wi, 0, Infinity, &t, &y)) return false;
    SampledSpectrum L = BeamRadiance(l, s, y, wEmit, oneMinusCos, lambda);
    if (L.IsBlack()) return false;
    ls->L = L;
    ls->wi = wi;
    ls->pdf = ConePdfW(oneMinusCos);
    ls->pLight = y;
    ls->nLight = l.direction;
    ls->distance = t;
    ls->isDelta = false;
    return true;
}

// The solid-angle pdf at ctx.p of SampleBeamLi for direction wi (unit) reaching the disc.
LU_INLINE Float BeamPdfW(const Light &l, const LightSampleContext &ctx, Vec3f wi, Float oneMinusCos) {
    Float t;
    Vec3f y;
    if (!BeamDiscCrossing(l, ctx.p, wi, 0, Infinity, &t, &y)) return 0;
    return BeamKernel(l, -wi, oneMinusCos);
}

}  // namespace lu
