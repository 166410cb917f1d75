// Lucerna: vectors, frames, bounds, rays and 4x4 transforms (host and device).
// One 3-vector type serves points, vectors and normals; Transform knows which it applies to.
#pragma once

#include "lucerna/util/common.h"

namespace lu {

struct Vec2f {
    Float x = 0, y = 0;
    Vec2f() = default;
    LU_HD constexpr Vec2f(Float x, Float y) : x(x), y(y) {}
    LU_HD Float operator[](int i) const { return i == 0 ? x : y; }
    LU_HD Float &operator[](int i) { return i == 0 ? x : y; }
    LU_HD Vec2f operator+(Vec2f b) const { return {x + b.x, y + b.y}; }
    LU_HD Vec2f operator-(Vec2f b) const { return {x - b.x, y - b.y}; }
    LU_HD Vec2f operator*(Float s) const { return {x * s, y * s}; }
};
using Point2f = Vec2f;

struct Vec3f {
    Float x = 0, y = 0, z = 0;
    Vec3f() = default;
    LU_HD constexpr Vec3f(Float x, Float y, Float z) : x(x), y(y), z(z) {}
    LU_HD Float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    LU_HD Float &operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    LU_HD Vec3f operator+(const Vec3f &b) const { return {x + b.x, y + b.y, z + b.z}; }
    LU_HD Vec3f operator-(const Vec3f &b) const { return {x - b.x, y - b.y, z - b.z}; }
    LU_HD Vec3f operator-() const { return {-x, -y, -z}; }
    LU_HD Vec3f operator*(Float s) const { return {x * s, y * s, z * s}; }
    LU_HD Vec3f operator*(const Vec3f &b) const { return {x * b.x, y * b.y, z * b.z}; }
    LU_HD Vec3f operator/(Float s) const { Float inv = 1 / s; return {x * inv, y * inv, z * inv}; }
    LU_HD Vec3f &operator+=(const Vec3f &b) { x += b.x; y += b.y; z += b.z; return *this; }
    LU_HD Vec3f &operator-=(const Vec3f &b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
    LU_HD Vec3f &operator*=(Float s) { x *= s; y *= s; z *= s; return *this; }
    LU_HD bool operator==(const Vec3f &b) const { return x == b.x && y == b.y && z == b.z; }
    LU_HD bool operator!=(const Vec3f &b) const { return !(*this == b); }
};
using Point3f = Vec3f;
using Normal3f = Vec3f;

LU_INLINE Vec3f operator*(Float s, const Vec3f &v) { return v * s; }
LU_INLINE Float Dot(const Vec3f &a, const Vec3f &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
LU_INLINE Float AbsDot(const Vec3f &a, const Vec3f &b) { return std::abs(Dot(a, b)); }
LU_INLINE Vec3f Cross(const Vec3f &a, const Vec3f &b) {
    // Computed in double to avoid catastrophic cancellation (as pbrt-v4 does with DifferenceOfProducts).
    return {Float(double(a.y) * b.z - double(a.z) * b.y), Float(double(a.z) * b.x - double(a.x) * b.z),
            Float(double(a.x) * b.y - double(a.y) * b.x)};
}
LU_INLINE Float LengthSquared(const Vec3f &v) { return Dot(v, v); }
LU_INLINE Float Length(const Vec3f &v) { return std::sqrt(Dot(v, v)); }
LU_INLINE Vec3f Normalize(const Vec3f &v) { return v / Length(v); }
LU_INLINE Float Distance(const Vec3f &a, const Vec3f &b) { return Length(a - b); }
LU_INLINE Float DistanceSquared(const Vec3f &a, const Vec3f &b) { return LengthSquared(a - b); }
LU_INLINE Vec3f Abs(const Vec3f &v) { return {std::abs(v.x), std::abs(v.y), std::abs(v.z)}; }
LU_INLINE Vec3f Min(const Vec3f &a, const Vec3f &b) { return {Min(a.x, b.x), Min(a.y, b.y), Min(a.z, b.z)}; }
LU_INLINE Vec3f Max(const Vec3f &a, const Vec3f &b) { return {Max(a.x, b.x), Max(a.y, b.y), Max(a.z, b.z)}; }
LU_INLINE Float MaxComponent(const Vec3f &v) { return Max(v.x, Max(v.y, v.z)); }
LU_INLINE Vec3f FaceForward(const Vec3f &n, const Vec3f &v) { return Dot(n, v) < 0 ? -n : n; }
LU_INLINE bool IsFinite(const Vec3f &v) { return IsFinite(v.x) && IsFinite(v.y) && IsFinite(v.z); }

// Reflection of wo about n (both pointing away from the surface).
LU_INLINE Vec3f Reflect(const Vec3f &wo, const Vec3f &n) { return -wo + 2 * Dot(wo, n) * n; }

// Refraction of wi about n (same hemisphere as wi) with relative eta = eta_t / eta_i.
// Returns false on total internal reflection. After pbrt-v4's Refract().
LU_INLINE bool Refract(const Vec3f &wi, Vec3f n, Float eta, Float *etap, Vec3f *wt) {
    Float cosTheta_i = Dot(n, wi);
    if (cosTheta_i < 0) { eta = 1 / eta; cosTheta_i = -cosTheta_i; n = -n; }
    Float sin2Theta_i = Max(Float(0), 1 - Sqr(cosTheta_i));
    Float sin2Theta_t = sin2Theta_i / Sqr(eta);
    if (sin2Theta_t >= 1) return false;
    Float cosTheta_t = SafeSqrt(1 - sin2Theta_t);
    *wt = -wi / eta + (cosTheta_i / eta - cosTheta_t) * n;
    if (etap) *etap = eta;
    return true;
}

// Orthonormal basis around a unit vector (Duff et al. 2017).
LU_INLINE void CoordinateSystem(const Vec3f &v1, Vec3f *v2, Vec3f *v3) {
    Float sign = std::copysign(Float(1), v1.z);
    Float a = -1 / (sign + v1.z);
    Float b = v1.x * v1.y * a;
    *v2 = Vec3f(1 + sign * v1.x * v1.x * a, sign * b, -sign * v1.x);
    *v3 = Vec3f(b, sign + v1.y * v1.y * a, -v1.y);
}

// Orthonormal frame; local z is the surface normal for BSDF evaluation.
struct Frame {
    Vec3f x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
    LU_HD static Frame FromZ(const Vec3f &z) { Frame f; f.z = z; CoordinateSystem(z, &f.x, &f.y); return f; }
    // Frame with z = n and x as close as possible to the tangent dpdu.
    LU_HD static Frame FromXZ(const Vec3f &dpdu, const Vec3f &n) {
        Vec3f x = dpdu - n * Dot(n, dpdu);
        Float l2 = LengthSquared(x);
        if (!(l2 > 1e-12f)) return FromZ(n);
        Frame f; f.z = n; f.x = x / std::sqrt(l2); f.y = Cross(f.z, f.x); return f;
    }
    LU_HD Vec3f ToLocal(const Vec3f &v) const { return {Dot(v, x), Dot(v, y), Dot(v, z)}; }
    LU_HD Vec3f FromLocal(const Vec3f &v) const { return x * v.x + y * v.y + z * v.z; }
};

// Spherical geometry in the local shading frame (z up).
LU_INLINE Float CosTheta(const Vec3f &w) { return w.z; }
LU_INLINE Float Cos2Theta(const Vec3f &w) { return w.z * w.z; }
LU_INLINE Float AbsCosTheta(const Vec3f &w) { return std::abs(w.z); }
LU_INLINE Float Sin2Theta(const Vec3f &w) { return Max(Float(0), 1 - Cos2Theta(w)); }
LU_INLINE Float SinTheta(const Vec3f &w) { return std::sqrt(Sin2Theta(w)); }
LU_INLINE Float TanTheta(const Vec3f &w) { return SinTheta(w) / CosTheta(w); }
LU_INLINE Float Tan2Theta(const Vec3f &w) { return Sin2Theta(w) / Cos2Theta(w); }
LU_INLINE Float CosPhi(const Vec3f &w) { Float s = SinTheta(w); return s == 0 ? 1 : Clamp(w.x / s, Float(-1), Float(1)); }
LU_INLINE Float SinPhi(const Vec3f &w) { Float s = SinTheta(w); return s == 0 ? 0 : Clamp(w.y / s, Float(-1), Float(1)); }
LU_INLINE bool SameHemisphere(const Vec3f &a, const Vec3f &b) { return a.z * b.z > 0; }
LU_INLINE Vec3f SphericalDirection(Float sinTheta, Float cosTheta, Float phi) {
    return {Clamp(sinTheta, Float(-1), Float(1)) * std::cos(phi), Clamp(sinTheta, Float(-1), Float(1)) * std::sin(phi),
            Clamp(cosTheta, Float(-1), Float(1))};
}

struct Bounds3f {
    Vec3f pMin{Infinity, Infinity, Infinity}, pMax{-Infinity, -Infinity, -Infinity};
    LU_HD void Expand(const Vec3f &p) { pMin = Min(pMin, p); pMax = Max(pMax, p); }
    LU_HD void Expand(const Bounds3f &b) { pMin = Min(pMin, b.pMin); pMax = Max(pMax, b.pMax); }
    LU_HD bool Empty() const { return pMin.x > pMax.x || pMin.y > pMax.y || pMin.z > pMax.z; }
    LU_HD Vec3f Diagonal() const { return pMax - pMin; }
    LU_HD Vec3f Center() const { return (pMin + pMax) * 0.5f; }
};

// A ray with parametric extent (0, tMax).
struct Ray {
    Vec3f o, d;
    Float tMax = Infinity;
    LU_HD Vec3f operator()(Float t) const { return o + d * t; }
};

// Offsets a ray origin off a surface along the geometric normal n towards w, scaled with the
// magnitude of p so it stays above float rounding of the intersection (a robust fixed-scale
// alternative to pbrt-v4's error-bound offsets).
LU_INLINE Vec3f OffsetRayOrigin(const Vec3f &p, const Vec3f &n, const Vec3f &w) {
    Float mag = Max(Float(1), MaxComponent(Abs(p)));
    Vec3f off = n * (mag * 2e-5f);
    return Dot(w, n) < 0 ? p - off : p + off;
}

// Row-major 4x4 matrix; m[i][j] is row i, column j. Points are column vectors: p' = M p.
struct Matrix4 {
    Float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    LU_HD static Matrix4 Identity() { return Matrix4(); }
    LU_HD bool operator==(const Matrix4 &o) const {
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                if (m[i][j] != o.m[i][j]) return false;
        return true;
    }
    LU_HD bool IsIdentity() const { return *this == Matrix4(); }
};

LU_INLINE Matrix4 Mul(const Matrix4 &a, const Matrix4 &b) {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += double(a.m[i][k]) * b.m[k][j];
            r.m[i][j] = Float(s);
        }
    return r;
}

LU_INLINE Matrix4 Transpose(const Matrix4 &a) {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
    return r;
}

// Inverse by Gauss-Jordan elimination with partial pivoting, in double. Returns false if singular.
LU_INLINE bool Inverse(const Matrix4 &a, Matrix4 *out) {
    double m[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) { m[i][j] = a.m[i][j]; m[i][j + 4] = (i == j); }
    for (int c = 0; c < 4; ++c) {
        int piv = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::abs(m[r][c]) > std::abs(m[piv][c])) piv = r;
        if (std::abs(m[piv][c]) < 1e-300) return false;
        if (piv != c)
            for (int j = 0; j < 8; ++j) { double t = m[c][j]; m[c][j] = m[piv][j]; m[piv][j] = t; }
        double inv = 1.0 / m[c][c];
        for (int j = 0; j < 8; ++j) m[c][j] *= inv;
        for (int r = 0; r < 4; ++r)
            if (r != c) {
                double f = m[r][c];
                if (f != 0)
                    for (int j = 0; j < 8; ++j) m[r][j] -= f * m[c][j];
            }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out->m[i][j] = Float(m[i][j + 4]);
    return true;
}

// An affine or projective transform with its inverse.
struct Transform {
    Matrix4 m, mInv;
    Transform() = default;
    LU_HD Transform(const Matrix4 &m, const Matrix4 &mInv) : m(m), mInv(mInv) {}
    LU_HD Vec3f ApplyPoint(const Vec3f &p) const {
        Float x = m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3];
        Float y = m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3];
        Float z = m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3];
        Float w = m.m[3][0] * p.x + m.m[3][1] * p.y + m.m[3][2] * p.z + m.m[3][3];
        return w == 1 ? Vec3f(x, y, z) : Vec3f(x, y, z) / w;
    }
    LU_HD Vec3f ApplyVector(const Vec3f &v) const {
        return {m.m[0][0] * v.x + m.m[0][1] * v.y + m.m[0][2] * v.z, m.m[1][0] * v.x + m.m[1][1] * v.y + m.m[1][2] * v.z,
                m.m[2][0] * v.x + m.m[2][1] * v.y + m.m[2][2] * v.z};
    }
    // Normals transform by the inverse transpose.
    LU_HD Vec3f ApplyNormal(const Vec3f &n) const {
        return {mInv.m[0][0] * n.x + mInv.m[1][0] * n.y + mInv.m[2][0] * n.z,
                mInv.m[0][1] * n.x + mInv.m[1][1] * n.y + mInv.m[2][1] * n.z,
                mInv.m[0][2] * n.x + mInv.m[1][2] * n.y + mInv.m[2][2] * n.z};
    }
    LU_HD Transform Inverted() const { return Transform(mInv, m); }
    LU_HD bool IsIdentity() const { return m.IsIdentity(); }
    // True when the upper 3x3 has a negative determinant (handedness flips).
    LU_HD bool SwapsHandedness() const {
        double det = double(m.m[0][0]) * (double(m.m[1][1]) * m.m[2][2] - double(m.m[1][2]) * m.m[2][1]) -
                     double(m.m[0][1]) * (double(m.m[1][0]) * m.m[2][2] - double(m.m[1][2]) * m.m[2][0]) +
                     double(m.m[0][2]) * (double(m.m[1][0]) * m.m[2][1] - double(m.m[1][1]) * m.m[2][0]);
        return det < 0;
    }
};

LU_INLINE Transform operator*(const Transform &a, const Transform &b) {
    return Transform(Mul(a.m, b.m), Mul(b.mInv, a.mInv));
}

}  // namespace lu
