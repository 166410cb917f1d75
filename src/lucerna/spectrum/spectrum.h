// Lucerna: spectra as plain data for shared (host/device) code, and their evaluation at sampled
// wavelengths. RGB values are upsampled on the host with Jakob & Hanika's sigmoid polynomials
// (as pbrt-v4 does); the device only evaluates the resulting coefficients.
#pragma once

#include "lucerna/spectrum/sampled.h"

namespace lu {

// Tabulated spectra are stored densely at 1 nm from 360 to 830 nm (471 values).
constexpr int TabulatedSpectrumSize = 471;

enum class SpectrumKind : uint8_t {
    Constant,       // value = scale
    RGBAlbedo,      // value = sigmoid(poly(c, lambda)), in [0,1]
    RGBUnbounded,   // value = scale * sigmoid(poly(c, lambda))
    RGBIlluminant,  // value = scale * sigmoid(poly(c, lambda)) * table[lambda] (table: the color space illuminant)
    Tabulated,      // value = scale * table[lambda]
    Blackbody,      // value = scale * Planck(lambda, T = c[0]); scale normalizes the peak to 1
};

struct Spectrum {
    SpectrumKind kind = SpectrumKind::Constant;
    Float scale = 0;
    Float c[3] = {0, 0, 0};   // sigmoid polynomial coefficients (c0 l^2 + c1 l + c2), or T for blackbody
    uint32_t table = 0;       // index of a tabulated spectrum in SpectrumTables::data (units of 471 floats)

    LU_HD static Spectrum Const(Float v) { Spectrum s; s.kind = SpectrumKind::Constant; s.scale = v; return s; }
    LU_HD bool IsConstant() const { return kind == SpectrumKind::Constant; }
};

// Device-visible spectral tables; every pointer is into one upload.
struct SpectrumTables {
    const Float *data = nullptr;  // tabulated spectra, TabulatedSpectrumSize floats each
    uint32_t count = 0;
};

// Branch-free (a select), so that the loops over the wavelengths vectorize.
LU_INLINE Float SigmoidPolynomial(const Float c[3], Float lambda) {
    Float x = (c[0] * lambda + c[1]) * lambda + c[2];
    Float y = 0.5f + x / (2 * std::sqrt(1 + x * x));
    return std::isinf(x) ? (x > 0 ? Float(1) : Float(0)) : y;
}

LU_INLINE Float BlackbodyRadiance(Float lambdaNm, Float T) {
    if (T <= 0) return 0;
    const double c = 299792458., h = 6.62606957e-34, kb = 1.3806488e-23;
    double l = lambdaNm * 1e-9;
    return Float((2 * h * c * c) / (l * l * l * l * l * (std::exp((h * c) / (l * kb * T)) - 1)));
}

LU_INLINE Float LookupTabulated(const Float *t, Float lambda) {
    Float x = lambda - LambdaMin;
    if (!(x >= 0) || x > TabulatedSpectrumSize - 1) return 0;
    int i = Min(int(x), TabulatedSpectrumSize - 2);
    Float f = x - i;
    return (1 - f) * t[i] + f * t[i + 1];
}

LU_INLINE Float EvalSpectrum(const Spectrum &s, Float lambda, const SpectrumTables &tab) {
    switch (s.kind) {
    case SpectrumKind::Constant: return s.scale;
    case SpectrumKind::RGBAlbedo: return SigmoidPolynomial(s.c, lambda);
    case SpectrumKind::RGBUnbounded: return s.scale * SigmoidPolynomial(s.c, lambda);
    case SpectrumKind::RGBIlluminant:
        return s.scale * SigmoidPolynomial(s.c, lambda) * LookupTabulated(tab.data + size_t(s.table) * TabulatedSpectrumSize, lambda);
    case SpectrumKind::Tabulated: return s.scale * LookupTabulated(tab.data + size_t(s.table) * TabulatedSpectrumSize, lambda);
    case SpectrumKind::Blackbody: return s.scale * BlackbodyRadiance(lambda, s.c[0]);
    }
    return 0;
}

#if defined(LU_SPECTRUM_SSE)
// SigmoidPolynomial and LookupTabulated at four wavelengths as SSE vectors: the same IEEE
// operations in the same order, so the same values; the table lookup's index arithmetic and
// interpolation vectorized too (only the eight loads stay scalar).
inline __m128 SigmoidPolynomial4(const Float c[3], __m128 lambda) {
    __m128 x = _mm_add_ps(_mm_mul_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(c[0]), lambda), _mm_set1_ps(c[1])), lambda),
                          _mm_set1_ps(c[2]));
    __m128 y = _mm_add_ps(_mm_set1_ps(0.5f),
                          _mm_div_ps(x, _mm_mul_ps(_mm_set1_ps(2), _mm_sqrt_ps(_mm_add_ps(_mm_set1_ps(1), _mm_mul_ps(x, x))))));
    __m128 absX = _mm_andnot_ps(_mm_set1_ps(-0.f), x);
    __m128 inf = _mm_cmpeq_ps(absX, _mm_set1_ps(Infinity));
    __m128 step = _mm_and_ps(_mm_cmpgt_ps(x, _mm_setzero_ps()), _mm_set1_ps(1));
    return _mm_or_ps(_mm_and_ps(inf, step), _mm_andnot_ps(inf, y));
}
inline __m128 LookupTabulated4(const Float *t, __m128 lambda) {
    __m128 x = _mm_sub_ps(lambda, _mm_set1_ps(LambdaMin));
    __m128 valid = _mm_and_ps(_mm_cmpge_ps(x, _mm_setzero_ps()), _mm_cmple_ps(x, _mm_set1_ps(TabulatedSpectrumSize - 1)));
    __m128i i = _mm_cvttps_epi32(_mm_and_ps(valid, x));   // 0 in invalid lanes (no stray loads)
    __m128i last = _mm_set1_epi32(TabulatedSpectrumSize - 2);
    __m128i over = _mm_cmpgt_epi32(i, last);
    i = _mm_or_si128(_mm_and_si128(over, last), _mm_andnot_si128(over, i));
    __m128 f = _mm_sub_ps(x, _mm_cvtepi32_ps(i));
    alignas(16) int32_t idx[4];
    _mm_store_si128(reinterpret_cast<__m128i *>(idx), i);
    __m128 t0 = _mm_setr_ps(t[idx[0]], t[idx[1]], t[idx[2]], t[idx[3]]);
    __m128 t1 = _mm_setr_ps(t[idx[0] + 1], t[idx[1] + 1], t[idx[2] + 1], t[idx[3] + 1]);
    __m128 v = _mm_add_ps(_mm_mul_ps(_mm_sub_ps(_mm_set1_ps(1), f), t0), _mm_mul_ps(f, t1));
    return _mm_and_ps(valid, v);
}
#endif

// EvalSpectrum at every wavelength, with the kind dispatched once (same values).
LU_INLINE SampledSpectrum SampleSpectrum(const Spectrum &s, const SampledWavelengths &w, const SpectrumTables &tab) {
    SampledSpectrum r;
#if defined(LU_SPECTRUM_SSE)
    switch (s.kind) {
    case SpectrumKind::Constant: r.v = _mm_set1_ps(s.scale); return r;
    case SpectrumKind::RGBAlbedo: r.v = SigmoidPolynomial4(s.c, _mm_loadu_ps(w.lambda)); return r;
    case SpectrumKind::RGBUnbounded:
        r.v = _mm_mul_ps(_mm_set1_ps(s.scale), SigmoidPolynomial4(s.c, _mm_loadu_ps(w.lambda)));
        return r;
    case SpectrumKind::RGBIlluminant: {
        __m128 l = _mm_loadu_ps(w.lambda);
        __m128 v = _mm_mul_ps(_mm_set1_ps(s.scale), SigmoidPolynomial4(s.c, l));
        r.v = _mm_mul_ps(v, LookupTabulated4(tab.data + size_t(s.table) * TabulatedSpectrumSize, l));
        return r;
    }
    default: break;
    }
#endif
    switch (s.kind) {
    case SpectrumKind::Constant:
        for (int i = 0; i < NSpectrumSamples; ++i) r[i] = s.scale;
        break;
    case SpectrumKind::RGBAlbedo:
        for (int i = 0; i < NSpectrumSamples; ++i) r[i] = SigmoidPolynomial(s.c, w.lambda[i]);
        break;
    case SpectrumKind::RGBUnbounded:
        for (int i = 0; i < NSpectrumSamples; ++i) r[i] = s.scale * SigmoidPolynomial(s.c, w.lambda[i]);
        break;
    case SpectrumKind::RGBIlluminant: {
        const Float *t = tab.data + size_t(s.table) * TabulatedSpectrumSize;
        for (int i = 0; i < NSpectrumSamples; ++i) r[i] = s.scale * SigmoidPolynomial(s.c, w.lambda[i]);  // vectorizes
        for (int i = 0; i < NSpectrumSamples; ++i) r[i] = r[i] * LookupTabulated(t, w.lambda[i]);
        break;
    }
    default:
        for (int i = 0; i < NSpectrumSamples; ++i) r[i] = EvalSpectrum(s, w.lambda[i], tab);
    }
    return r;
}

}  // namespace lu
