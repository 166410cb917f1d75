// Lucerna: the collimated beam light (a Lucerna extension: laser, collimated LED), host and device.
// An aperture (a disc or a rectangle) emits irradiance E(y) along its normal n only:
// L(y, w) = E(y) delta(w - n). Under regpath the delta is replaced by the cone kernel K of
// half-angle sigma_N around n (regularized at the light): L_r(y, w) = E(y) K(w) / cos theta_y.
// See docs/lights.md.
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

LU_INLINE bool BeamIsRectangle(const Light &l) { return l.beamHalf.x > 0; }

// The coordinates of a point y of the aperture's plane along beamU and direction x beamU.
LU_INLINE Vec2f BeamLocal(const Light &l, Vec3f y) {
    Vec3f d = y - l.position;
    return Vec2f(Dot(d, l.beamU), Dot(d, Cross(l.direction, l.beamU)));
}

// The irradiance profile's shape at the aperture point (x, y) (1 at the axis): uniform
// (beamWaist == 0) or gaussian exp(-2 rho^2 / w^2) (w: the 1/e^2 radius); 0 outside the aperture.
LU_INLINE Float BeamProfile(const Light &l, Vec2f xy) {
    Float rho2 = Sqr(xy.x) + Sqr(xy.y);
    bool inside = BeamIsRectangle(l) ? std::abs(xy.x) <= l.beamHalf.x && std::abs(xy.y) <= l.beamHalf.y
                                     : rho2 <= Sqr(l.beamRadius);
    if (!inside) return 0;
    return l.beamWaist > 0 ? std::exp(-2 * rho2 / Sqr(l.beamWaist)) : Float(1);
}

// The integral of BeamProfile over the aperture. Disc of radius R: pi R^2 (uniform),
// pi w^2 / 2 (1 - exp(-2 R^2 / w^2)) (gaussian truncated at R). Rectangle of half sizes a, b:
// 4 a b (uniform), pi w^2 / 2 erf(sqrt 2 a / w) erf(sqrt 2 b / w) (the gaussian is separable).
// The beam's power per unit wavelength is E_lambda(axis) times this.
LU_INLINE Float BeamProfileIntegral(const Light &l) {
    Float w = l.beamWaist;
    if (BeamIsRectangle(l)) {
        Float a = l.beamHalf.x, b = l.beamHalf.y;
        if (w > 0) return Pi * Sqr(w) / 2 * std::erf(Float(1.41421356) * a / w) * std::erf(Float(1.41421356) * b / w);
        return 4 * a * b;
    }
    if (w > 0) return Pi * Sqr(w) / 2 * -std::expm1(-2 * Sqr(l.beamRadius) / Sqr(w));
    return Pi * Sqr(l.beamRadius);
}

// Spectral irradiance at the aperture point y (on a surface facing the beam).
LU_INLINE SampledSpectrum BeamIrradiance(const Light &l, const SceneView &s, Vec3f y, const SampledWavelengths &lambda) {
    Float g = BeamProfile(l, BeamLocal(l, y));
    if (g == 0) return SampledSpectrum(0);
    return SampleSpectrum(l.spectrum, lambda, s.spectra) * (l.scale * g);
}

// Where the ray o + t d (d unit) crosses the beam's aperture from its front (d against n), for
// tMin < t < tMax: true with *t and the point *y.
LU_INLINE bool BeamDiscCrossing(const Light &l, Vec3f o, Vec3f d, Float tMin, Float tMax, Float *t, Vec3f *y) {
    Float dn = Dot(d, l.direction);
    if (!(dn < 0)) return false;
    Float tt = Dot(l.position - o, l.direction) / dn;
    if (!(tt > tMin && tt < tMax)) return false;
    Vec3f p = o + d * tt;
    if (BeamIsRectangle(l)) {
        Vec2f xy = BeamLocal(l, p);
        if (!(std::abs(xy.x) <= l.beamHalf.x && std::abs(xy.y) <= l.beamHalf.y)) return false;
    } else if (!(DistanceSquared(p, l.position) <= Sqr(l.beamRadius))) {
        return false;
    }
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

// Regularized radiance leaving aperture point y along wEmit: E(y) K(wEmit) / cos theta_y.
LU_INLINE SampledSpectrum BeamRadiance(const Light &l, const SceneView &s, Vec3f y, Vec3f wEmit, Float oneMinusCos,
                                       const SampledWavelengths &lambda) {
    Float K = BeamKernel(l, wEmit, oneMinusCos);
    Float cosY = Dot(wEmit, l.direction);
    if (K == 0 || !(cosY > 0)) return SampledSpectrum(0);
    return BeamIrradiance(l, s, y, lambda) * (K / cosY);
}

// The aperture-area technique's density at aperture point y. Disc: the profile over its integral
// (uniform: 1 / (pi R^2)), so that area samples follow the beam's irradiance. Rectangle: uniform,
// 1 / (4 a b), for either profile (the truncated gaussian's inverse needs erf^-1, which the
// host's standard library lacks; the cone technique covers a narrow waist in a wide rectangle).
LU_INLINE Float BeamAreaPdf(const Light &l, Vec3f y) {
    Float g = BeamProfile(l, BeamLocal(l, y));
    if (!(g > 0)) return 0;
    if (BeamIsRectangle(l)) return 1 / (4 * l.beamHalf.x * l.beamHalf.y);
    return g / BeamProfileIntegral(l);
}

// An aperture point with density BeamAreaPdf. Disc: rho^2 by inverting the profile's radial
// distribution (uniform: u R^2; gaussian truncated at R: -w^2/2 log(1 + u (exp(-2 R^2 / w^2) - 1))).
// Rectangle: uniform.
LU_INLINE Vec3f SampleBeamAperture(const Light &l, Vec2f u) {
    if (BeamIsRectangle(l)) {
        Vec3f v = Cross(l.direction, l.beamU);
        return l.position + l.beamU * ((2 * u.x - 1) * l.beamHalf.x) + v * ((2 * u.y - 1) * l.beamHalf.y);
    }
    Float R2 = Sqr(l.beamRadius), rho2 = u.x * R2;
    if (l.beamWaist > 0) {
        Float w2 = Sqr(l.beamWaist);
        rho2 = Min(R2, -w2 / 2 * std::log1p(u.x * std::expm1(-2 * R2 / w2)));
    }
    Float rho = std::sqrt(Max(Float(0), rho2)), phi = 2 * Pi * u.y;
    Frame f = Frame::FromZ(l.direction);
    return l.position + f.FromLocal(Vec3f(rho * std::cos(phi), rho * std::sin(phi), 0));
}

// The explicit techniques' solid-angle pdf at a vertex for the direction that reaches aperture point
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
//    then the aperture point y where the ray along wi meets it; kept when the ray meets it;
//  - aperture area: y on the aperture (BeamAreaPdf), wi towards it; kept when the emitted
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
        y = SampleBeamAperture(l, Vec2f(Min(OneMinusEpsilon, 2 * u.x - 1), u.y));
        Vec3f d = y - ctx.p;
        t = Length(d);
        if (!(t > 0) || !(Dot(d, l.direction) < 0)) return false;   // ctx.p must be in front of the aperture
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

// The solid-angle pdf at ctx.p of SampleBeamLi for direction wi (unit) reaching the aperture.
LU_INLINE Float BeamPdfW(const Light &l, const LightSampleContext &ctx, Vec3f wi, Float oneMinusCos) {
    Float t;
    Vec3f y;
    if (!BeamDiscCrossing(l, ctx.p, wi, 0, Infinity, &t, &y)) return 0;
    return BeamMixturePdfW(l, y, t, -wi, oneMinusCos);
}

// ---- The beam in a medium: the region where the beam-segment technique samples ----
// In a scattering medium every point from which the regularized beam is seen (within the cone of
// 1 - cos sigma around -n, the aperture in front) scatters its light. The points lie in the
// half-space in front of the aperture, within R + s tan sigma of the axis at axial distance s. The
// technique of integrators/collimated.h samples distances along a ray segment uniformly inside a
// fixed region that is convex, so that a ray meets it in one interval: the cylinder of radius
// R + L tan sigma and length L in front of the aperture (R: the aperture's outer radius, L: the
// beam's reach, the farthest a point of the scene's bounding sphere (sceneCenter, sceneRadius) can
// lie along the axis). The medium may extend beyond the scene: free-flight vertices cover that.
// The region need not equal the points that see the beam: it decides which technique estimates
// the beam's light at a medium point (inside: the beam techniques; outside: free-flight vertices,
// as for every other light).

LU_INLINE Float BeamReach(const Light &l) { return Distance(l.position, l.sceneCenter) + l.sceneRadius; }

// The region's radius for the pass's cone 1 - cos sigma (Infinity from 90 degrees on).
LU_INLINE Float BeamRegionRadius(const Light &l, Float oneMinusCos) {
    Float cosS = 1 - oneMinusCos, sinS = SafeSqrt(oneMinusCos * (2 - oneMinusCos));
    return cosS > 0 ? l.beamRadius + BeamReach(l) * sinS / cosS : Infinity;
}

// Whether the point x lies in the beam's region.
LU_INLINE bool InBeamRegion(const Light &l, Vec3f x, Float regionRadius) {
    Vec3f d = x - l.position;
    Float s = Dot(d, l.direction);
    return s > 0 && s < BeamReach(l) && LengthSquared(d - l.direction * s) < Sqr(regionRadius);
}

// The interval (*t0, *t1) of the ray o + t d (d unit) within [0, tMax] inside the beam's region;
// false when empty.
LU_INLINE bool BeamRegionInterval(const Light &l, Vec3f o, Vec3f d, Float tMax, Float regionRadius, Float *t0, Float *t1) {
    Vec3f q = o - l.position;
    Float s0 = Dot(q, l.direction), ds = Dot(d, l.direction);
    Float lo = 0, hi = tMax, reach = BeamReach(l);
    // In front of the aperture and within its reach: 0 < s0 + t ds < reach.
    if (ds > 0) {
        lo = Max(lo, -s0 / ds);
        hi = Min(hi, (reach - s0) / ds);
    } else if (ds < 0) {
        hi = Min(hi, -s0 / ds);
        lo = Max(lo, (reach - s0) / ds);
    } else if (!(s0 > 0 && s0 < reach)) {
        return false;
    }
    // Within the cylinder: |qr + t dr|^2 < rc^2 (qr, dr: the parts perpendicular to the axis).
    Vec3f qr = q - l.direction * s0, dr = d - l.direction * ds;
    Float a = LengthSquared(dr), b = Dot(qr, dr), c = LengthSquared(qr) - Sqr(regionRadius);
    if (!(regionRadius < Infinity)) {
        // A half-space slab: the axial bounds alone.
    } else if (a < Float(1e-12)) {
        if (!(c < 0)) return false;   // parallel to the axis: all in or all out
    } else {
        Float disc = b * b - a * c;
        if (!(disc > 0)) return false;
        Float root = std::sqrt(disc);
        // Roots without cancellation: qq = -(b + sign(b) root), roots qq / a and c / qq.
        Float qq = b < 0 ? -b + root : -b - root;
        Float r0 = qq / a, r1 = c / qq;
        lo = Max(lo, Min(r0, r1));
        hi = Min(hi, Max(r0, r1));
    }
    if (!(hi > lo)) return false;
    *t0 = lo;
    *t1 = hi;
    return true;
}

}  // namespace lu
