// Lucerna: point-sampled spectra carried along a path (hero wavelengths), after pbrt-v4's
// SampledSpectrum / SampledWavelengths: 4 wavelengths per path, sampled by visible importance.
#pragma once

#include "lucerna/util/common.h"

#if (defined(__x86_64__) || defined(_M_X64)) && !defined(__CUDA_ARCH__) && defined(__GNUC__)
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
    LU_HD bool IsBlack() const { for (int i = 0; i < NSpectrumSamples; ++i) if (v[i] != 0) return false; return true; }
    LU_HD explicit operator bool() const { return !IsBlack(); }
    LU_HD Float MaxValue() const { Float m = v[0]; for (int i = 1; i < NSpectrumSamples; ++i) m = Max(m, v[i]); return m; }
    LU_HD Float MinValue() const { Float m = v[0]; for (int i = 1; i < NSpectrumSamples; ++i) m = Min(m, v[i]); return m; }
    LU_HD Float Average() const { Float s = 0; for (int i = 0; i < NSpectrumSamples; ++i) s += v[i]; return s / NSpectrumSamples; }
    LU_HD bool IsFinite() const { for (int i = 0; i < NSpectrumSamples; ++i) if (!std::isfinite(v[i])) return false; return true; }
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

struct SampledWavelengths {
    Float lambda[NSpectrumSamples];
    Float pdf[NSpectrumSamples];

    // Stratified: the first wavelength from u, the others offset by 1/N in the primary sample.
    LU_HD static SampledWavelengths SampleVisible(Float u) {
        SampledWavelengths w;
        Float l[NSpectrumSamples], p[NSpectrumSamples];
        for (int i = 0; i < NSpectrumSamples; ++i) {
            Float up = u + Float(i) / NSpectrumSamples;
            if (up > 1) up -= 1;
            l[i] = SampleVisibleWavelength(up);
            p[i] = VisibleWavelengthsPDF(l[i]);
        }
#if defined(LU_SPECTRUM_SSE)
        // One 16-byte store per array: the caller copies w with 16-byte loads, which cannot be
        // forwarded from four 4-byte stores.
        _mm_storeu_ps(w.lambda, _mm_setr_ps(l[0], l[1], l[2], l[3]));
        _mm_storeu_ps(w.pdf, _mm_setr_ps(p[0], p[1], p[2], p[3]));
#else
        for (int i = 0; i < NSpectrumSamples; ++i) { w.lambda[i] = l[i]; w.pdf[i] = p[i]; }
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
