// Lucerna: basic definitions shared by host and device code.
// LU_HD marks functions compiled for both CPU and GPU (after pbrt-v4's PBRT_CPU_GPU).
#pragma once

#include <cstdint>
#include <cmath>
#include <cfloat>

#if defined(__CUDACC__)
#define LU_HD __host__ __device__
#define LU_DEVICE_CODE 1
#else
#define LU_HD
#endif
#define LU_INLINE LU_HD inline

namespace lu {

using Float = float;

constexpr Float Pi = 3.14159265358979323846f;
constexpr Float InvPi = 0.31830988618379067154f;
constexpr Float Inv2Pi = 0.15915494309189533577f;
constexpr Float Inv4Pi = 0.07957747154594766788f;
constexpr Float PiOver2 = 1.57079632679489661923f;
constexpr Float PiOver4 = 0.78539816339744830961f;
constexpr Float OneMinusEpsilon = 0x1.fffffep-1f;
constexpr Float Infinity = INFINITY;

template <typename T>
LU_INLINE T Clamp(T v, T lo, T hi) { return v < lo ? lo : (v > hi ? hi : v); }
template <typename T>
LU_INLINE T Min(T a, T b) { return a < b ? a : b; }
template <typename T>
LU_INLINE T Max(T a, T b) { return a > b ? a : b; }
template <typename T>
LU_INLINE T Sqr(T v) { return v * v; }
template <typename T>
LU_INLINE void Swap(T &a, T &b) { T t = a; a = b; b = t; }

LU_INLINE Float Lerp(Float t, Float a, Float b) { return (1 - t) * a + t * b; }
LU_INLINE Float SafeSqrt(Float x) { return std::sqrt(Max(Float(0), x)); }
LU_INLINE Float SafeASin(Float x) { return std::asin(Clamp(x, Float(-1), Float(1))); }
LU_INLINE Float SafeACos(Float x) { return std::acos(Clamp(x, Float(-1), Float(1))); }
LU_INLINE Float Radians(Float deg) { return (Pi / 180) * deg; }
LU_INLINE Float Degrees(Float rad) { return (180 / Pi) * rad; }
LU_INLINE bool IsFinite(Float v) { return std::isfinite(v); }

// Evaluates a polynomial c[0] + c[1] t + ... by Horner's rule.
template <int N>
LU_INLINE Float EvaluatePolynomial(Float t, const Float (&c)[N]) {
    Float r = c[N - 1];
    for (int i = N - 2; i >= 0; --i) r = r * t + c[i];
    return r;
}

}  // namespace lu
