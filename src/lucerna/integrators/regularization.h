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

// The kernel of one pass (the same for every pixel of the pass).
struct RegularizationParams {
    bool enabled = false;
    Float radius = 0;    // r_N for this pass (world units)
    Float angle = 0;     // sigma_N for this pass (radians), lights at infinity
};

// Per-pass parameters: r_N = r0 * N^-lambda, sigma_N = sigma0 * N^-lambda, N >= 1.
LU_INLINE RegularizationParams RegularizationForPass(bool enabled, Float r0, Float sigma0, Float lambda, uint32_t passIndex) {
    RegularizationParams p;
    p.enabled = enabled;
    Float s = std::pow(Float(passIndex + 1), -lambda);
    p.radius = r0 * s;
    p.angle = sigma0 * s;
    return p;
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

// The kernel's cap for a light point at distance d (d = Infinity: angular kernel).
LU_INLINE Float RegularizedOneMinusCos(const RegularizationParams &rp, Float d) {
    if (d == Infinity) return OneMinusCosAngle(rp.angle);
    return OneMinusConeCosForDisc(d, rp.radius);
}

// Conservative culling before sampling a light at a specular vertex p: can a point of the sphere
// (c, R) lie inside the cone around D for radius r? The cone is widest for the nearest point
// (cos sigma = d / sqrt(d^2 + r^2) falls with d), so nothing is reachable when the angle from D to
// c exceeds sigma(d_min) + beta, beta = the sphere's angular radius. In 1 - cos terms (no
// cancellation for the tiny cones of late passes), with a margin for float rounding.
LU_INLINE bool RegularizedConeMayReach(const Vec3f &p, const Vec3f &D, const Vec3f &c, Float R, Float r) {
    Vec3f pc = c - p;
    Float L = Length(pc);
    R = R * Float(1.001) + Float(1e-5) * L;
    if (!(L > R)) return true;
    Float dMin = L - R;
    Float h = std::sqrt(dMin * dMin + r * r);
    Float oneMinusCosS = OneMinusConeCosForDisc(dMin, r), sinS = r / h, cosS = dMin / h;
    Float sinB = R / L, cosB = SafeSqrt(1 - sinB * sinB), oneMinusCosB = sinB * sinB / (1 + cosB);
    // 1 - cos(sigma + beta) = (1 - cos sigma) + cos sigma (1 - cos beta) + sin sigma sin beta.
    Float limit = oneMinusCosS + cosS * oneMinusCosB + sinS * sinB;
    return OneMinusCosBetween(D, pc / L) <= limit * Float(1.01) + Float(1e-7);
}

}  // namespace lu
