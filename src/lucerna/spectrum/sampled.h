// Lucerna: point-sampled spectra carried along a path (hero wavelengths), after pbrt-v4's
// SampledSpectrum / SampledWavelengths: 4 wavelengths per path, sampled by visible importance.
#pragma once

#include "lucerna/util/common.h"

// Not with clang (the fuzz builds): it refuses a non-const reference to a vector element.
#if (defined(__x86_64__) || defined(_M_X64)) && !defined(__CUDA_ARCH__) && defined(__GNUC__) && !defined(__clang__)
#include <emmintrin.h>
#include <xmmintrin.h>
#define LU_SPECTRUM_SSE 1
#endif

namespace lu {

constexpr int NSpectrumSamples = 4;
constexpr Float LambdaMin = 360, LambdaMax = 830;

// On x86-64 hosts the samples are one SSE vector (GCC/Clang vector extension: v[i] reads and
// writes sample i, arithmetic is elementwise): the psABI then passes and returns a SampledSpectrum
// in one xmm register instead of two 8-byte halves, which callers stored and reloaded as a whole
// (a store-forwarding stall per non-inlined call), and the operators are single SSE instructions
// with the same IEEE results. Device code gets a plain array of the same size and alignment.
// All host code (nvcc's host pass included) must see the same choice: the functions returning a
// SampledSpectrum are inline, and one copy of each is kept at link time.
struct SampledSpectrum {
#if defined(LU_SPECTRUM_SSE)
    static_assert(NSpectrumSamples == 4, "one __m128 per SampledSpectrum");
    __m128 v;
    SampledSpectrum() : v(_mm_setzero_ps()) {}
    explicit SampledSpectrum(Float c) : v(_mm_set1_ps(c)) {}
#define LU_SS_OP(op)                                                                        \
    SampledSpectrum operator op(const SampledSpectrum &b) const { SampledSpectrum r; r.v = v op b.v; return r; } \
    SampledSpectrum &operator op##=(const SampledSpectrum &b) { v = v op b.v; return *this; }                 \
    SampledSpectrum operator op(Float s) const { SampledSpectrum r; r.v = v op _mm_set1_ps(s); return r; }   \
    SampledSpectrum &operator op##=(Float s) { v = v op _mm_set1_ps(s); return *this; }
#else
    alignas(16) Float v[NSpectrumSamples];
    LU_HD SampledSpectrum() { for (int i = 0; i < NSpectrumSamples; ++i) v[i] = 0; }
    LU_HD explicit SampledSpectrum(Float c) { for (int i = 0; i < NSpectrumSamples; ++i) v[i] = c; }
#define LU_SS_OP(op)                                                                        \
    LU_HD SampledSpectrum operator op(const SampledSpectrum &b) const {                     \
        SampledSpectrum r;                                                                  \
        for (int i = 0; i < NSpectrumSamples; ++i) { r.v[i] = v[i] op b.v[i]; }            \
        return r;                                                                           \
    }                                                                                       \
    LU_HD SampledSpectrum &operator op##=(const SampledSpectrum &b) {                        \
        for (int i = 0; i < NSpectrumSamples; ++i) { v[i] op## = b.v[i]; }                  \
        return *this;                                                                       \
    }                                                                                       \
    LU_HD SampledSpectrum operator op(Float s) const {                                       \
        SampledSpectrum r;                                                                  \
        for (int i = 0; i < NSpectrumSamples; ++i) { r.v[i] = v[i] op s; }                 \
        return r;                                                                           \
    }                                                                                       \
    LU_HD SampledSpectrum &operator op##=(Float s) {                                          \
        for (int i = 0; i < NSpectrumSamples; ++i) { v[i] op## = s; }                       \
        return *this;                                                                       \
    }
#endif
    LU_HD Float operator[](int i) const { return v[i]; }
    LU_HD Float &operator[](int i) { return v[i]; }
    LU_SS_OP(+) LU_SS_OP(-) LU_SS_OP(*) LU_SS_OP(/)
#undef LU_SS_OP
#if defined(LU_SPECTRUM_SSE)
    // One compare and one branch instead of four of each (NaN counts as nonzero, as below).
    bool IsBlack() const { return _mm_movemask_ps(_mm_cmpneq_ps(v, _mm_setzero_ps())) == 0; }
#else
    LU_HD bool IsBlack() const { for (int i = 0; i < NSpectrumSamples; ++i) if (v[i] != 0) return false; return true; }
#endif
    LU_HD explicit operator bool() const { return !IsBlack(); }
    LU_HD Float MaxValue() const { Float m = v[0]; for (int i = 1; i < NSpectrumSamples; ++i) m = Max(m, v[i]); return m; }
    LU_HD Float MinValue() const { Float m = v[0]; for (int i = 1; i < NSpectrumSamples; ++i) m = Min(m, v[i]); return m; }
    LU_HD Float Average() const { Float s = 0; for (int i = 0; i < NSpectrumSamples; ++i) s += v[i]; return s / NSpectrumSamples; }
#if defined(LU_SPECTRUM_SSE)
    // |v| < inf in every lane (false for NaN), as the loop below.
    bool IsFinite() const {
        return _mm_movemask_ps(_mm_cmplt_ps(_mm_andnot_ps(_mm_set1_ps(-0.f), v), _mm_set1_ps(Infinity))) == 0xf;
    }
#else
    LU_HD bool IsFinite() const { for (int i = 0; i < NSpectrumSamples; ++i) if (!std::isfinite(v[i])) return false; return true; }
#endif
};

LU_INLINE SampledSpectrum operator*(Float s, const SampledSpectrum &a) { return a * s; }
LU_INLINE SampledSpectrum SafeDiv(const SampledSpectrum &a, const SampledSpectrum &b) {
    SampledSpectrum r; for (int i = 0; i < NSpectrumSamples; ++i) r.v[i] = b.v[i] != 0 ? a.v[i] / b.v[i] : 0; return r;
}
LU_INLINE SampledSpectrum Sqrt(const SampledSpectrum &a) {
    SampledSpectrum r; for (int i = 0; i < NSpectrumSamples; ++i) r.v[i] = SafeSqrt(a.v[i]); return r;
}
LU_INLINE SampledSpectrum Exp(const SampledSpectrum &a) {
    SampledSpectrum r; for (int i = 0; i < NSpectrumSamples; ++i) r.v[i] = std::exp(a.v[i]); return r;
}
LU_INLINE SampledSpectrum ClampZero(const SampledSpectrum &a) {
    SampledSpectrum r; for (int i = 0; i < NSpectrumSamples; ++i) r.v[i] = Max(Float(0), a.v[i]); return r;
}

// Visible-importance wavelength sampling, pdf proportional to 1/cosh^2(0.0072 (lambda - 538)),
// restricted to [360, 830] nm (pbrt-v4's SampleVisibleWavelengths).
// Evaluated as 1 / cosh^2(x) = 4 e^(2x) / (1 + e^(2x))^2 and atanh(y) = log((1 + y) / (1 - y)) / 2:
// one expf or logf each instead of coshf (two exponentials) and atanhf (log1pf), equal up to
// float rounding.
LU_INLINE Float VisibleWavelengthsPDF(Float lambda) {
    if (lambda < 360 || lambda > 830) return 0;
    Float e = std::exp(0.0144f * (lambda - 538));   // 0.0144f is exactly 2 * 0.0072f
    return 0.0039398042f * 4 * e / ((1 + e) * (1 + e));
}
LU_INLINE Float SampleVisibleWavelength(Float u) {
    Float y = 0.85691062f - 1.82750197f * u;
    return 538 - 138.888889f * (0.5f * std::log((1 + y) / (1 - y)));
}
// The pdf of SampleVisibleWavelength(u) from its y = 0.85691062 - 1.82750197 u, without an
// exponential: 0.0144 (lambda - 538) = -2 atanh(y) (0.0144 * 138.888889 = 2), and
// 1 / cosh^2(atanh y) = (1 - y)(1 + y). Equal to VisibleWavelengthsPDF(lambda) up to float
// rounding; 0 where the rounded lambda falls outside [360, 830], as there.
LU_INLINE Float VisibleWavelengthsPDFFromY(Float onePlusY, Float oneMinusY, Float lambda) {
    if (lambda < 360 || lambda > 830) return 0;
    return 0.0039398042f * (oneMinusY * onePlusY);
}

#if defined(LU_SPECTRUM_SSE)
// Natural logarithm of four positive normal floats (Cephes logf: mantissa in [sqrt(1/2),
// sqrt(2)), degree-9 polynomial; within about 1 ulp of logf).
inline __m128 Log4(__m128 x) {
    __m128i xi = _mm_castps_si128(x);
    __m128i e = _mm_sub_epi32(_mm_srli_epi32(xi, 23), _mm_set1_epi32(127));
    __m128 m = _mm_castsi128_ps(_mm_or_si128(_mm_and_si128(xi, _mm_set1_epi32(0x007fffff)), _mm_set1_epi32(0x3f800000)));
    __m128 big = _mm_cmpgt_ps(m, _mm_set1_ps(1.41421356237f));   // m in [1, 2): halve above sqrt(2)
    m = _mm_or_ps(_mm_and_ps(big, _mm_mul_ps(m, _mm_set1_ps(0.5f))), _mm_andnot_ps(big, m));
    e = _mm_sub_epi32(e, _mm_castps_si128(big));   // big is -1 where halved
    __m128 fe = _mm_cvtepi32_ps(e);
    __m128 f = _mm_sub_ps(m, _mm_set1_ps(1));
    __m128 z = _mm_mul_ps(f, f);
    __m128 r = _mm_set1_ps(7.0376836292e-2f);
    const float c[8] = {-1.1514610310e-1f, 1.1676998740e-1f, -1.2420140846e-1f, 1.4249322787e-1f,
                        -1.6668057665e-1f, 2.0000714765e-1f, -2.4999993993e-1f, 3.3333331174e-1f};
    for (float ci : c) r = _mm_add_ps(_mm_mul_ps(r, f), _mm_set1_ps(ci));
    r = _mm_mul_ps(_mm_mul_ps(r, f), z);
    r = _mm_add_ps(r, _mm_mul_ps(fe, _mm_set1_ps(-2.12194440e-4f)));
    r = _mm_sub_ps(r, _mm_mul_ps(z, _mm_set1_ps(0.5f)));
    return _mm_add_ps(_mm_add_ps(f, r), _mm_mul_ps(fe, _mm_set1_ps(0.693359375f)));
}
#endif

struct SampledWavelengths {
    Float lambda[NSpectrumSamples];
    Float pdf[NSpectrumSamples];

    // Stratified: the first wavelength from u, the others offset by 1/N in the primary sample.
    LU_HD static SampledWavelengths SampleVisible(Float u) {
        SampledWavelengths w;
#if defined(LU_SPECTRUM_SSE)
        // The four wavelengths at once (same arithmetic as below, with Log4 for std::log), and
        // one 16-byte store per array: the caller copies w with 16-byte loads, which cannot be
        // forwarded from four 4-byte stores.
        __m128 up = _mm_add_ps(_mm_set1_ps(u), _mm_setr_ps(0, 0.25f, 0.5f, 0.75f));
        __m128 wrap = _mm_cmpgt_ps(up, _mm_set1_ps(1));
        up = _mm_or_ps(_mm_and_ps(wrap, _mm_sub_ps(up, _mm_set1_ps(1))), _mm_andnot_ps(wrap, up));
        __m128 y = _mm_sub_ps(_mm_set1_ps(0.85691062f), _mm_mul_ps(_mm_set1_ps(1.82750197f), up));
        __m128 onePlusY = _mm_add_ps(_mm_set1_ps(1), y), oneMinusY = _mm_sub_ps(_mm_set1_ps(1), y);
        __m128 l = _mm_sub_ps(_mm_set1_ps(538), _mm_mul_ps(_mm_set1_ps(138.888889f),
                                                           _mm_mul_ps(_mm_set1_ps(0.5f), Log4(_mm_div_ps(onePlusY, oneMinusY)))));
        __m128 inside = _mm_and_ps(_mm_cmpge_ps(l, _mm_set1_ps(360)), _mm_cmple_ps(l, _mm_set1_ps(830)));
        __m128 p = _mm_and_ps(inside, _mm_mul_ps(_mm_set1_ps(0.0039398042f), _mm_mul_ps(oneMinusY, onePlusY)));
        _mm_storeu_ps(w.lambda, l);
        _mm_storeu_ps(w.pdf, p);
#else
        for (int i = 0; i < NSpectrumSamples; ++i) {
            Float up = u + Float(i) / NSpectrumSamples;
            if (up > 1) up -= 1;
            Float y = 0.85691062f - 1.82750197f * up;   // as SampleVisibleWavelength
            Float onePlusY = 1 + y, oneMinusY = 1 - y;
            w.lambda[i] = 538 - 138.888889f * (0.5f * std::log(onePlusY / oneMinusY));
            w.pdf[i] = VisibleWavelengthsPDFFromY(onePlusY, oneMinusY, w.lambda[i]);
        }
#endif
        return w;
    }
    LU_HD SampledSpectrum PDF() const { SampledSpectrum r; for (int i = 0; i < NSpectrumSamples; ++i) r.v[i] = pdf[i]; return r; }
    // Wavelength-dependent refraction (dispersion): keep only the hero wavelength.
    LU_HD void TerminateSecondary() {
        if (SecondaryTerminated()) return;
        for (int i = 1; i < NSpectrumSamples; ++i) pdf[i] = 0;
        pdf[0] /= NSpectrumSamples;
    }
    LU_HD bool SecondaryTerminated() const {
        for (int i = 1; i < NSpectrumSamples; ++i) if (pdf[i] != 0) return false;
        return true;
    }
};

}  // namespace lu
