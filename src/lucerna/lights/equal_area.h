// Lucerna: Clarberg's equal-area octahedral mapping between [0,1]^2 and the unit sphere, as
// pbrt-v4's EqualAreaSquareToSphere / EqualAreaSphereToSquare (used by image infinite lights).
#pragma once

#include "lucerna/util/vecmath.h"

namespace lu {

// Maps p in [0,1]^2 to a unit direction; uniform area on the square maps to uniform solid angle.
LU_INLINE Vec3f EqualAreaSquareToSphere(Vec2f p) {
    Float u = 2 * p.x - 1, v = 2 * p.y - 1;
    Float up = std::abs(u), vp = std::abs(v);
    // Signed distance from the diagonal |u| + |v| = 1 picks the hemisphere.
    Float signedDistance = 1 - (up + vp);
    Float r = 1 - std::abs(signedDistance);
    Float phi = (r == 0 ? 1 : (vp - up) / r + 1) * (Pi / 4);
    Float z = std::copysign(1 - r * r, signedDistance);
    Float cosPhi = std::copysign(std::cos(phi), u);
    Float sinPhi = std::copysign(std::sin(phi), v);
    Float s = r * SafeSqrt(2 - r * r);
    return {cosPhi * s, sinPhi * s, z};
}

// Inverse of EqualAreaSquareToSphere for a unit direction d; returns a point in [0,1]^2.
LU_INLINE Vec2f EqualAreaSphereToSquare(Vec3f d) {
    Float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
    Float r = SafeSqrt(1 - z);
    Float a = Max(x, y), b = Min(x, y);
    b = a == 0 ? 0 : b / a;
    // Minimax polynomial for atan(b) * 2 / pi on [0,1] (the coefficients pbrt-v4 uses).
    const Float c[7] = {0.406758566246788489601959989e-5f, 0.636226545274016134946890922156f,
                        0.61572017898280213493197203466e-2f, -0.247333733281268944196501420480f,
                        0.881770664775316294736387951347e-1f, 0.419038818029165735901852432784e-1f,
                        -0.251390972343483509333252996350e-1f};
    Float phi = EvaluatePolynomial(b, c);
    if (x < y) phi = 1 - phi;
    Float v = phi * r, u = r - v;
    if (d.z < 0) {  // lower hemisphere: mirror across the diagonal
        Float t = u;
        u = 1 - v;
        v = 1 - t;
    }
    u = std::copysign(u, d.x);
    v = std::copysign(v, d.y);
    return {0.5f * (u + 1), 0.5f * (v + 1)};
}

// Wraps integer pixel coordinates outside [0,res) across the octahedral seams (pbrt-v4's
// WrapMode::OctahedralSphere), then clamps.
LU_INLINE void WrapOctahedral(int *x, int *y, int w, int h) {
    if (*x < 0) { *x = -*x; *y = h - 1 - *y; }
    else if (*x >= w) { *x = 2 * w - 1 - *x; *y = h - 1 - *y; }
    if (*y < 0) { *x = w - 1 - *x; *y = -*y; }
    else if (*y >= h) { *x = w - 1 - *x; *y = 2 * h - 1 - *y; }
    *x = Clamp(*x, 0, w - 1);
    *y = Clamp(*y, 0, h - 1);
}

}  // namespace lu
