// Lucerna: warps from [0,1)^2 to common domains, with their pdfs and inverses
// (Shirley-Chiu concentric disk, cosine hemisphere, uniform sphere/cone, triangles).
#pragma once

#include "lucerna/util/vecmath.h"

namespace lu {

LU_INLINE Vec2f SampleUniformDiskConcentric(Vec2f u) {
    Vec2f o(2 * u.x - 1, 2 * u.y - 1);
    if (o.x == 0 && o.y == 0) return {0, 0};
    Float theta, r;
    if (std::abs(o.x) > std::abs(o.y)) { r = o.x; theta = PiOver4 * (o.y / o.x); }
    else { r = o.y; theta = PiOver2 - PiOver4 * (o.x / o.y); }
    return {r * std::cos(theta), r * std::sin(theta)};
}

// Cosine-weighted hemisphere around +z; pdfW = cos(theta)/pi.
LU_INLINE Vec3f SampleCosineHemisphere(Vec2f u) {
    Vec2f d = SampleUniformDiskConcentric(u);
    Float z = SafeSqrt(1 - d.x * d.x - d.y * d.y);
    return {d.x, d.y, z};
}
LU_INLINE Float CosineHemispherePDF(Float cosTheta) { return cosTheta * InvPi; }

LU_INLINE Vec3f SampleUniformSphere(Vec2f u) {
    Float z = 1 - 2 * u.x;
    Float r = SafeSqrt(1 - z * z);
    Float phi = 2 * Pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
LU_INLINE Float UniformSpherePDF() { return Inv4Pi; }

LU_INLINE Vec3f SampleUniformHemisphere(Vec2f u) {
    Float z = u.x;
    Float r = SafeSqrt(1 - z * z);
    Float phi = 2 * Pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
LU_INLINE Float UniformHemispherePDF() { return Inv2Pi; }

// Uniform direction in the cone of half-angle acos(cosThetaMax) around +z; pdfW = 1/(2 pi (1 - cosThetaMax)).
LU_INLINE Vec3f SampleUniformCone(Vec2f u, Float cosThetaMax) {
    Float cosTheta = (1 - u.x) + u.x * cosThetaMax;
    Float sinTheta = SafeSqrt(1 - cosTheta * cosTheta);
    Float phi = u.y * 2 * Pi;
    return SphericalDirection(sinTheta, cosTheta, phi);
}
LU_INLINE Float UniformConePDF(Float cosThetaMax) { return 1 / (2 * Pi * (1 - cosThetaMax)); }

// Uniform barycentrics (b0, b1, b2) over a triangle (Heitz 2019 low-distortion map).
LU_INLINE void SampleUniformTriangle(Vec2f u, Float *b0, Float *b1, Float *b2) {
    if (u.x < u.y) {
        *b0 = u.x / 2; *b1 = u.y - *b0;
    } else {
        *b1 = u.y / 2; *b0 = u.x - *b1;
    }
    *b2 = 1 - *b0 - *b1;
}

LU_INLINE Float SampleExponential(Float u, Float a) { return -std::log(1 - u) / a; }

// Linear interpolation pdf on [0,1] between a and b, and its sampling.
LU_INLINE Float SampleLinear(Float u, Float a, Float b) {
    if (u == 0 && a == 0) return 0;
    Float x = u * (a + b) / (a + std::sqrt(Lerp(u, a * a, b * b)));
    return Min(x, OneMinusEpsilon);
}

}  // namespace lu
