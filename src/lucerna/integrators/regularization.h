// Lucerna: selective path regularization (Bogolepov, Ulyanov, Turlapov, "On one implementation of
// path tracing for the GPU", after Kaplanyan & Dachsbacher 2013). At a specular vertex the Dirac
// lobe around the ideal direction D is replaced by the cone kernel
//     phi_sigma(D, w) = 1 / (2 pi (1 - cos sigma))  if angle(D, w) < sigma, else 0,
// with cos sigma = d / sqrt(d^2 + r_N^2) for a light point at distance d, and sigma = sigma_N for
// lights at infinity; r_N = r0 N^-lambda, sigma_N = sigma0 N^-lambda (N = pass index, from 1).
// The MIS weights between this biased explicit technique and the unbiased implicit one are in
// integrators/mis.h. See docs/regularization.md.
#pragma once

#include "lucerna/util/vecmath.h"

namespace lu {

// The kernel of one pass, or of one vertex in it. The disc the cone covers at a light point at
// distance d has radius radius + radiusPerDistance * d.
struct RegularizationParams {
    bool enabled = false;
    Float radius = 0;             // r_N for this pass (world units)
    Float radiusPerDistance = 0;  // footprint kernels (RegularizationAtVertex); 0 in a pass's kernel
    Float angle = 0;              // sigma_N for this pass (radians): lights at infinity, collimated beams
    Float footprint = 0;          // K N^-lambda: the blur allowed at the receiver, in pixels (0: r_N everywhere)
};

// Per-pass parameters: r_N = r0 * N^-lambda, sigma_N = sigma0 * N^-lambda, N >= 1; with a
// footprint of K pixels (K > 0), K N^-lambda pixels.
LU_INLINE RegularizationParams RegularizationForPass(bool enabled, Float r0, Float sigma0, Float lambda, uint32_t passIndex,
                                                     Float footprintPixels = 0) {
    RegularizationParams p;
    p.enabled = enabled;
    Float s = std::pow(Float(passIndex + 1), -lambda);
    p.radius = r0 * s;
    p.angle = sigma0 * s;
    p.footprint = footprintPixels * s;
    return p;
}

// The kernel at a specular vertex y from the pass's (footprint kernels; else the pass's own), with
// T the length of the path from the camera to y and receiverT that to the last non-specular vertex
// x before y (negative: none, every vertex so far was specular), for a pixel cone of width
// pixelWidth + pixelSpread * t. The blur it allows is pass.footprint pixels where the path's light
// lands (the chain between is taken as flat):
//   - at x: B = K (w0 + a T_x), made by a cone of angle B / s at y (s = T - T_x, the length of the
//     chain from x to y): a disc of radius B d / s at a light point at distance d;
//   - from the camera (a light seen through Dirac vertices): the light's image within K pixels,
//     a disc of radius K (w0 + a (T + d)), the pixel's footprint at the light.
// Lights at infinity: the cone's angle, atan of the radius per distance. Collimated beams keep the
// pass's kernel (two kernels, see integrators/collimated.h).
LU_INLINE RegularizationParams RegularizationAtVertex(const RegularizationParams &pass, Float pixelWidth, Float pixelSpread,
                                                      Float receiverT, Float T) {
    if (!(pass.footprint > 0)) return pass;
    RegularizationParams rp = pass;
    if (receiverT < 0) {
        rp.radius = pass.footprint * (pixelWidth + pixelSpread * T);
        rp.radiusPerDistance = pass.footprint * pixelSpread;
    } else {
        Float s = Max(T - receiverT, Float(1e-6) * Max(T, Float(1)));
        rp.radius = 0;
        rp.radiusPerDistance = pass.footprint * (pixelWidth + pixelSpread * receiverT) / s;
    }
    return rp;
}

// cos sigma of the cone that covers a disc of radius r at distance d.
LU_INLINE Float ConeCosForDisc(Float d, Float r) { return d / std::sqrt(d * d + r * r); }

// The cone kernel's solid-angle density for cos sigma (uniform over the cap). For tiny cones,
// 1 - cos sigma is computed as r^2 / (d (d + sqrt(d^2 + r^2))) / ... via sin^2 to avoid cancellation.
LU_INLINE Float ConePdfW(Float oneMinusCos) { return oneMinusCos > 0 ? 1 / (2 * Pi * oneMinusCos) : Infinity; }

// 1 - cos sigma for the disc cone without cancellation: (sqrt(d^2+r^2) - d)/sqrt(d^2+r^2)
// = r^2 / (sqrt(d^2+r^2) (sqrt(d^2+r^2) + d)).
LU_INLINE Float OneMinusConeCosForDisc(Float d, Float r) {
    Float h = std::sqrt(d * d + r * r);
    return (r * r) / (h * (h + d));
}
// 1 - cos(sigma) = 2 sin^2(sigma / 2).
LU_INLINE Float OneMinusCosAngle(Float sigma) { return 2 * Sqr(std::sin(sigma / 2)); }

// 1 - cos of the angle between unit vectors a and b, accurate for small angles: |a - b|^2 / 2.
LU_INLINE Float OneMinusCosBetween(const Vec3f &a, const Vec3f &b) { return 0.5f * LengthSquared(a - b); }

// The kernel's half-angle for lights at infinity: atan of the radius per distance for footprint
// kernels, else the pass's sigma_N.
LU_INLINE Float RegularizedAngle(const RegularizationParams &rp) {
    return rp.radiusPerDistance > 0 ? std::atan(rp.radiusPerDistance) : rp.angle;
}

// The kernel's cap for a light point at distance d (d = Infinity: angular kernel).
LU_INLINE Float RegularizedOneMinusCos(const RegularizationParams &rp, Float d) {
    if (d == Infinity) return OneMinusCosAngle(RegularizedAngle(rp));
    return OneMinusConeCosForDisc(d, rp.radius + rp.radiusPerDistance * d);
}

// Conservative culling before sampling a light at a specular vertex p: can a point of the sphere
// (c, R) lie inside the cone around D for the disc radius r + rPerDistance d? The cone is widest for
// the nearest point (tan sigma = r / d + rPerDistance falls with d), so nothing is reachable when
// the angle from D to c exceeds sigma(d_min) + beta, beta = the sphere's angular radius. In 1 - cos
// terms (no cancellation for the tiny cones of late passes), with a margin for float rounding.
LU_INLINE bool RegularizedConeMayReach(const Vec3f &p, const Vec3f &D, const Vec3f &c, Float R, Float r,
                                       Float rPerDistance = 0) {
    Vec3f pc = c - p;
    Float L = Length(pc);
    R = R * Float(1.001) + Float(1e-5) * L;
    if (!(L > R)) return true;
    Float dMin = L - R;
    r += rPerDistance * dMin;
    Float h = std::sqrt(dMin * dMin + r * r);
    Float oneMinusCosS = OneMinusConeCosForDisc(dMin, r), sinS = r / h, cosS = dMin / h;
    Float sinB = R / L, cosB = SafeSqrt(1 - sinB * sinB), oneMinusCosB = sinB * sinB / (1 + cosB);
    // 1 - cos(sigma + beta) = (1 - cos sigma) + cos sigma (1 - cos beta) + sin sigma sin beta.
    Float limit = oneMinusCosS + cosS * oneMinusCosB + sinS * sinB;
    return OneMinusCosBetween(D, pc / L) <= limit * Float(1.01) + Float(1e-7);
}

}  // namespace lu
