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

// The disc-area technique's density at disc point y: the profile over its integral (uniform:
// 1 / (pi R^2)), so that area samples follow the beam's irradiance.
LU_INLINE Float BeamAreaPdf(const Light &l, Vec3f y) {
    Float g = BeamProfile(l, DistanceSquared(y, l.position));
    return g > 0 ? g / BeamProfileIntegral(l.beamRadius, l.beamWaist) : Float(0);
}

// A disc point with density BeamAreaPdf: rho^2 by inverting the profile's radial distribution
// (uniform: u R^2; gaussian truncated at R: -w^2/2 log(1 + u (exp(-2 R^2 / w^2) - 1))).
LU_INLINE Vec3f SampleBeamDisc(const Light &l, Vec2f u) {
    Float R2 = Sqr(l.beamRadius), rho2 = u.x * R2;
    if (l.beamWaist > 0) {
        Float w2 = Sqr(l.beamWaist);
        rho2 = Min(R2, -w2 / 2 * std::log1p(u.x * std::expm1(-2 * R2 / w2)));
    }
    Float rho = std::sqrt(Max(Float(0), rho2)), phi = 2 * Pi * u.y;
    Frame f = Frame::FromZ(l.direction);
    return l.position + f.FromLocal(Vec3f(rho * std::cos(phi), rho * std::sin(phi), 0));
}

// The explicit techniques' solid-angle pdf at a vertex for the direction that reaches disc point
// y at distance t, leaving it along wEmit: the even mixture of the cone technique (K) and the
// disc-area technique (BeamAreaPdf t^2 / cos theta_y). 0 where the cone does not reach.
LU_INLINE Float BeamMixturePdfW(const Light &l, Vec3f y, Float t, Vec3f wEmit, Float oneMinusCos) {
    Float K = BeamKernel(l, wEmit, oneMinusCos);
    Float cosY = Dot(wEmit, l.direction);
    if (K == 0 || !(cosY > 0)) return 0;
    return Float(0.5) * K + Float(0.5) * BeamAreaPdf(l, y) * Sqr(t) / cosY;
}

// The explicit technique at ctx.p, one of two picked by u.x with probability 1/2 each (pdf: their
// mixture, BeamMixturePdfW):
//  - cone: a direction wi uniform in the cone of 1 - cos sigma = oneMinusCos around -n (pdfW = K),
//    then the disc point y where the ray along wi meets the disc; kept when the ray meets it;
//  - disc area: y on the disc by the beam's profile, wi towards it; kept when the emitted
//    direction -wi lies within the cone. Where the disc seen from ctx.p is much smaller than the
//    cone (a narrow beam, a wide kernel) this one keeps nearly every sample, the cone almost none;
//    where it is much larger, the reverse.
// ls->L = L_r(y, -wi), ls->pdf = the mixture. False when the sample misses or ctx.p is behind.
LU_INLINE bool SampleBeamLi(const Light &l, const SceneView &s, const LightSampleContext &ctx, Vec2f u,
                            Float oneMinusCos, const SampledWavelengths &lambda, LightLiSample *ls) {
    if (!(oneMinusCos > 0)) return false;
    Vec3f wi, y;
    Float t;
    if (u.x < Float(0.5)) {
        // 1 - cos theta = u (1 - cos sigma) keeps the tiny cones of late passes exact.
        Float omc = Min(Float(1), 2 * u.x) * oneMinusCos;
        Float cosTheta = 1 - omc, sinTheta = SafeSqrt(omc * (2 - omc));
        Vec3f wl = SphericalDirection(sinTheta, cosTheta, 2 * Pi * u.y);   // around +z = n
        Frame f = Frame::FromZ(l.direction);
        wi = -Normalize(f.FromLocal(wl));
        if (!BeamDiscCrossing(l, ctx.p, wi, 0, Infinity, &t, &y)) return false;
    } else {
        y = SampleBeamDisc(l, Vec2f(Min(OneMinusEpsilon, 2 * u.x - 1), u.y));
        Vec3f d = y - ctx.p;
        t = Length(d);
        if (!(t > 0) || !(Dot(d, l.direction) < 0)) return false;   // ctx.p must be in front of the disc
        wi = d / t;
    }
    Vec3f wEmit = -wi;
    SampledSpectrum L = BeamRadiance(l, s, y, wEmit, oneMinusCos, lambda);
    Float pdf = BeamMixturePdfW(l, y, t, wEmit, oneMinusCos);
    if (L.IsBlack() || !(pdf > 0)) return false;
    ls->L = L;
    ls->wi = wi;
    ls->pdf = pdf;
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
    return BeamMixturePdfW(l, y, t, -wi, oneMinusCos);
}

}  // namespace lu
