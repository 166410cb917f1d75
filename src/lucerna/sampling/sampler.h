// Lucerna: pixel samplers as one value type (host and device), after pbrt-v4's samplers.h:
// IndependentSampler, ZSobolSampler (the default), PaddedSobolSampler, StratifiedSampler,
// HaltonSampler and SobolSampler (the global Sobol' sequence over the image).
// Every value depends only on (pixel, sample index, dimension, seed) and the configuration,
// never on call history across pixels or threads.
#pragma once

#include "lucerna/sampling/lowdiscrepancy.h"
#include "lucerna/sampling/rng.h"
#include "lucerna/sampling/sequences.h"
#include "lucerna/util/vecmath.h"

#if (defined(__x86_64__) || defined(_M_X64)) && defined(__GNUC__) && !defined(__CUDACC__)
#include <immintrin.h>
#endif

namespace lu {

// ---- ZSobol digit shuffles, vectorized (x86-64 host only, chosen at run time) ----

// ZSobolDigits*(rest, nDigits, dimMix): the nDigits base-4 digits of `rest` (digit k at bits 2k,
// 1 <= nDigits <= 32), each replaced by PermuteBase4Digit(MixBits((rest >> (2k + 2)) ^ dimMix)
// >> 24) % 24, digit): the scalar loop of Sampler::ZSobolSampleIndex, several digits per
// instruction. Level 0 = scalar, 1 = AVX2, 2 = AVX-512 (F, DQ), 3 = AVX-512 (F, DQ, BW, VBMI).
#if (defined(__x86_64__) || defined(_M_X64)) && defined(__GNUC__) && !defined(__CUDACC__)
#define LU_ZSOBOL_SIMD 1
namespace detail {

constexpr uint64_t kPermWords[3] = {0xb1e19c6c78d8b4e4ull, 0x72d236c68d2d39c9ull, 0x93634b1b87271e4eull};

// Low 64 bits of x * c per lane, from 32-bit multiplies.
__attribute__((target("avx2"))) inline __m256i MulLo64(__m256i x, uint64_t c) {
    const __m256i cLo = _mm256_set1_epi64x(int64_t(c & 0xffffffffu)), cHi = _mm256_set1_epi64x(int64_t(c >> 32));
    __m256i lo = _mm256_mul_epu32(x, cLo);
    __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(x, 32), cLo), _mm256_mul_epu32(x, cHi));
    return _mm256_add_epi64(lo, _mm256_slli_epi64(cross, 32));
}

// y % 24 per lane for y < 2^40: 8 ((y >> 3) % 3) + (y & 7), the mod 3 by folding (2^16 = 1 mod 3)
// and an exact multiply-shift (t * 174763) >> 19 = t / 3 for t < 2^19.
__attribute__((target("avx2"))) inline __m256i Mod24(__m256i y) {
    const __m256i m32 = _mm256_set1_epi64x(0xffffffff), m16 = _mm256_set1_epi64x(0xffff);
    __m256i z = _mm256_srli_epi64(y, 3);
    __m256i t = _mm256_add_epi64(_mm256_and_si256(z, m32), _mm256_srli_epi64(z, 32));   // < 2^33
    t = _mm256_add_epi64(_mm256_and_si256(t, m16), _mm256_srli_epi64(t, 16));           // < 2^18
    __m256i q = _mm256_srli_epi64(_mm256_mul_epu32(t, _mm256_set1_epi64x(174763)), 19);
    __m256i r3 = _mm256_sub_epi64(t, _mm256_add_epi64(q, _mm256_add_epi64(q, q)));
    return _mm256_or_si256(_mm256_slli_epi64(r3, 3), _mm256_and_si256(y, _mm256_set1_epi64x(7)));
}

__attribute__((target("avx2"))) inline uint64_t ZSobolDigitsAVX2(uint64_t rest, int nDigits, uint64_t dimMix) {
    const __m256i vRest = _mm256_set1_epi64x(int64_t(rest)), vDim = _mm256_set1_epi64x(int64_t(dimMix));
    const __m256i w0 = _mm256_set1_epi64x(int64_t(kPermWords[0])), w1 = _mm256_set1_epi64x(int64_t(kPermWords[1])),
                  w2 = _mm256_set1_epi64x(int64_t(kPermWords[2]));
    const __m256i three = _mm256_set1_epi64x(3), seven = _mm256_set1_epi64x(7), fifteen = _mm256_set1_epi64x(15);
    __m256i shift = _mm256_setr_epi64x(0, 2, 4, 6);   // 2k for the lanes' digits k
    const __m256i step = _mm256_set1_epi64x(8), two = _mm256_set1_epi64x(2);
    __m256i acc = _mm256_setzero_si256();
    for (int k = 0; k < nDigits; k += 4) {
        __m256i digit = _mm256_and_si256(_mm256_srlv_epi64(vRest, shift), three);
        __m256i x = _mm256_xor_si256(_mm256_srlv_epi64(vRest, _mm256_add_epi64(shift, two)), vDim);   // 0 past 64 bits
        x = _mm256_xor_si256(x, _mm256_srli_epi64(x, 31));
        x = MulLo64(x, 0x7fb5d329728ea185ull);
        x = _mm256_xor_si256(x, _mm256_srli_epi64(x, 27));
        x = MulLo64(x, 0x81dadef4bc2dd44dull);
        x = _mm256_xor_si256(x, _mm256_srli_epi64(x, 33));
        __m256i p = Mod24(_mm256_srli_epi64(x, 24));
        __m256i word = _mm256_blendv_epi8(w0, w1, _mm256_cmpgt_epi64(p, seven));
        word = _mm256_blendv_epi8(word, w2, _mm256_cmpgt_epi64(p, fifteen));
        __m256i perm = _mm256_srlv_epi64(word, _mm256_slli_epi64(_mm256_and_si256(p, seven), 3));
        __m256i pd = _mm256_and_si256(_mm256_srlv_epi64(perm, _mm256_add_epi64(digit, digit)), three);
        acc = _mm256_or_si256(acc, _mm256_sllv_epi64(pd, shift));   // lanes with 2k >= 64 add nothing
        shift = _mm256_add_epi64(shift, step);
    }
    __m128i a = _mm_or_si128(_mm256_castsi256_si128(acc), _mm256_extracti128_si256(acc, 1));
    uint64_t index = uint64_t(_mm_cvtsi128_si64(a)) | uint64_t(_mm_extract_epi64(a, 1));
    // Lanes past the last digit (k >= nDigits) may have set bits at 2 nDigits and above.
    return nDigits >= 32 ? index : index & ((uint64_t(1) << (2 * nDigits)) - 1);
}

// GCC 12's AVX-512 intrinsic headers trip -Wmaybe-uninitialized (their _mm512_undefined_*).
#pragma GCC diagnostic push
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#pragma GCC diagnostic ignored "-Wuninitialized"
// y % 24 for y < 2^40 in doubles: q = floor(fma(y, 1/24, 2^-10)) is exactly floor(y / 24) (the
// error, below 2^-16, cannot cross an integer: y / 24 has a fraction 0 or >= 1/24 and at most
// 23/24), and y - 24 q is exact.
__attribute__((target("avx512f,avx512dq"))) inline __m512i Mod24AVX512(__m512i y) {
    __m512d yd = _mm512_cvtepu64_pd(y);
    __m512d t = _mm512_fmadd_pd(yd, _mm512_set1_pd(1.0 / 24), _mm512_set1_pd(0x1p-10));
    __m512d q = _mm512_roundscale_pd(t, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    return _mm512_cvttpd_epu64(_mm512_fnmadd_pd(q, _mm512_set1_pd(24), yd));
}

// One step of 8 digits (lanes k = shift / 2): the digit and its permutation number p.
__attribute__((target("avx512f,avx512dq"))) inline __m512i ZSobolPerm8(__m512i vRest, __m512i shift, __m512i vDim,
                                                                       __m512i *digit) {
    *digit = _mm512_and_si512(_mm512_srlv_epi64(vRest, shift), _mm512_set1_epi64(3));
    __m512i x = _mm512_xor_si512(_mm512_srlv_epi64(vRest, _mm512_add_epi64(shift, _mm512_set1_epi64(2))), vDim);
    x = _mm512_xor_si512(x, _mm512_srli_epi64(x, 31));
    x = _mm512_mullo_epi64(x, _mm512_set1_epi64(int64_t(0x7fb5d329728ea185ull)));
    x = _mm512_xor_si512(x, _mm512_srli_epi64(x, 27));
    x = _mm512_mullo_epi64(x, _mm512_set1_epi64(int64_t(0x81dadef4bc2dd44dull)));
    x = _mm512_xor_si512(x, _mm512_srli_epi64(x, 33));
    return Mod24AVX512(_mm512_srli_epi64(x, 24));
}

// Level 2: AVX-512 F + DQ.
__attribute__((target("avx512f,avx512dq"))) inline uint64_t ZSobolDigitsAVX512(uint64_t rest, int nDigits,
                                                                            uint64_t dimMix) {
    const __m512i vRest = _mm512_set1_epi64(int64_t(rest)), vDim = _mm512_set1_epi64(int64_t(dimMix));
    const __m512i words = _mm512_setr_epi64(int64_t(kPermWords[0]), int64_t(kPermWords[1]), int64_t(kPermWords[2]), 0,
                                            0, 0, 0, 0);
    const __m512i three = _mm512_set1_epi64(3), seven = _mm512_set1_epi64(7);
    __m512i shift = _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), acc = _mm512_setzero_si512();
    for (int k = 0; k < nDigits; k += 8) {
        __m512i digit, p = ZSobolPerm8(vRest, shift, vDim, &digit);
        __m512i word = _mm512_permutexvar_epi64(_mm512_srli_epi64(p, 3), words);
        __m512i perm = _mm512_srlv_epi64(word, _mm512_slli_epi64(_mm512_and_si512(p, seven), 3));
        __m512i pd = _mm512_and_si512(_mm512_srlv_epi64(perm, _mm512_add_epi64(digit, digit)), three);
        acc = _mm512_or_si512(acc, _mm512_sllv_epi64(pd, shift));
        shift = _mm512_add_epi64(shift, _mm512_set1_epi64(16));
    }
    uint64_t index = uint64_t(_mm512_reduce_or_epi64(acc));
    return nDigits >= 32 ? index : index & ((uint64_t(1) << (2 * nDigits)) - 1);
}

// Level 3: + VBMI, the 96-entry PermuteBase4Digit table in one byte permute (index 4 p + digit in
// each lane's low byte; the other index bytes are 0 and read entry 0, which is 0).
__attribute__((target("avx512f,avx512dq,avx512bw,avx512vbmi"))) inline uint64_t ZSobolDigitsAVX512VBMI(
    uint64_t rest, int nDigits, uint64_t dimMix) {
    alignas(64) static constexpr uint8_t table[128] = {
        0, 1, 2, 3, 0, 1, 3, 2, 0, 2, 1, 3, 0, 2, 3, 1, 0, 3, 2, 1, 0, 3, 1, 2, 1, 0, 2, 3, 1, 0, 3, 2,
        1, 2, 0, 3, 1, 2, 3, 0, 1, 3, 2, 0, 1, 3, 0, 2, 2, 1, 0, 3, 2, 1, 3, 0, 2, 0, 1, 3, 2, 0, 3, 1,
        2, 3, 0, 1, 2, 3, 1, 0, 3, 1, 2, 0, 3, 1, 0, 2, 3, 2, 1, 0, 3, 2, 0, 1, 3, 0, 2, 1, 3, 0, 1, 2};
    const __m512i vRest = _mm512_set1_epi64(int64_t(rest)), vDim = _mm512_set1_epi64(int64_t(dimMix));
    const __m512i tableLo = _mm512_load_si512(table), tableHi = _mm512_load_si512(table + 64);
    __m512i shift = _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), acc = _mm512_setzero_si512();
    for (int k = 0; k < nDigits; k += 8) {
        __m512i digit, p = ZSobolPerm8(vRest, shift, vDim, &digit);
        __m512i pd = _mm512_permutex2var_epi8(tableLo, _mm512_or_si512(_mm512_slli_epi64(p, 2), digit), tableHi);
        acc = _mm512_or_si512(acc, _mm512_sllv_epi64(pd, shift));
        shift = _mm512_add_epi64(shift, _mm512_set1_epi64(16));
    }
    uint64_t index = uint64_t(_mm512_reduce_or_epi64(acc));
    return nDigits >= 32 ? index : index & ((uint64_t(1) << (2 * nDigits)) - 1);
}
#pragma GCC diagnostic pop

// The best level this CPU runs (what MakeSampler stores in Sampler::simd).
inline uint8_t ZSobolSimdLevel() {
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq")) {
        if (__builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vbmi")) return 3;
        return 2;
    }
    if (__builtin_cpu_supports("avx2")) return 1;
    return 0;
}

}  // namespace detail
#endif

enum class SamplerKind : uint8_t { Independent, ZSobol, PaddedSobol, Stratified, Halton, Sobol, PMJ02BN };

// pbrt-v4's pmj02bn tables: 5 sequences of 65536 points (Lucerna builds its own, scene/pmj02_build.h).
constexpr int kPMJ02BNSets = 5, kPMJ02BNSamples = 65536;

// Usage per pixel sample: StartPixelSample(px, py, index), then Get1D / Get2D / GetPixel2D in a
// fixed order; each call consumes 1 or 2 dimensions. Starting at dimension d gives the same
// values as starting at 0 and consuming d dimensions first.
//
// Sample indices >= samplesPerPixel (progressive rendering past the nominal count) are
// deterministic: index i is split into pass = i / n and r = i % n, where n is the pattern size
// (2^log2SamplesPerPixel for ZSobol, samplesPerPixel for PaddedSobol/Stratified/PMJ02BN); pass 0 is
// exactly pbrt-v4's sample r, and pass k > 0 reuses pattern sample r under an independent
// randomization (the seed mixed with k; "none" randomization becomes a digit permutation for
// k > 0). Each pass is thus a fresh stratified set, so the estimate stays unbiased and keeps
// converging. The independent sampler needs no passes (PCG32 stream offset index * 65536 + dim),
// nor do Halton and Sobol: their sample index selects the index-th point of the global sequence
// that falls in the pixel, for any index, exactly as pbrt-v4 (which has no limit either).
struct Sampler {
    SamplerKind kind = SamplerKind::ZSobol;
    RandomizeStrategy randomize = RandomizeStrategy::FastOwen;
    int samplesPerPixel = 16;
    int seed = 0;
    // ZSobol: pattern of 2^log2SamplesPerPixel samples per pixel, Morton digits over the image.
    int log2SamplesPerPixel = 4, nBase4Digits = 0;
    // Stratified: xPixelSamples * yPixelSamples == samplesPerPixel.
    int xPixelSamples = 4, yPixelSamples = 4;
    bool jitter = true;
    // Halton: pbrt-v4's tiling of the image by 2^j x 3^k pixel blocks (j, k for up to 128 pixels).
    int haltonBaseScale[2] = {1, 1}, haltonBaseExponent[2] = {0, 0}, haltonMultInverse[2] = {0, 0};
    // Sobol: pixel indexing at scale 2^sobolLog2Scale (the resolution rounded up to a power of 2).
    int sobolLog2Scale = 0;
    // PMJ02BN: pixel samples over a tile of pmjTileSize^2 pixels, then kPMJ02BNSets sets of
    // samplesPerPixel points (BuildPMJ02BNTables' layout). pmjPoints is bound to the scene's
    // table (SceneView::pmjPoints, host or device) by RenderSampler before rendering.
    int pmjTileSize = 1;
    const Vec2f *pmjPoints = nullptr;
    // ZSobol digit shuffles: 0 scalar, 1 AVX2, 2 AVX-512, 3 AVX-512 VBMI (set by MakeSampler from the host CPU;
    // device code always runs the scalar loop). Every level gives the same values.
    uint8_t simd = 0;

    // ---- Per pixel-sample state (set by StartPixelSample) ----
    int px = 0, py = 0;
    int sampleIndex = 0;      // index within the pattern (r above)
    int dimension = 0;
    uint32_t pass = 0;
    int passSeed = 0;         // seed, mixed with the pass for pass > 0
    uint64_t mortonIndex = 0; // ZSobol
    uint64_t globalIndex = 0; // Halton, Sobol: index of the pixel sample in the global sequence
    RNG rng;                  // Independent, Stratified

    LU_HD int SamplesPerPixel() const { return samplesPerPixel; }

    LU_HD void StartPixelSample(int x, int y, int index, int dim = 0) {
        px = x;
        py = y;
        dimension = dim;
        switch (kind) {
        case SamplerKind::Independent:
            pass = 0;
            sampleIndex = index;
            passSeed = seed;
            rng.SetSequence(uint64_t(int64_t(x + y * 65536)) | (uint64_t(int64_t(seed)) << 32));
            rng.Advance(int64_t(index) * 65536 + dim);
            break;
        case SamplerKind::ZSobol: {
            uint32_t n = 1u << log2SamplesPerPixel;
            pass = uint32_t(index) >> log2SamplesPerPixel;
            sampleIndex = int(uint32_t(index) & (n - 1));
            passSeed = PassSeed(seed, pass);
            mortonIndex = (EncodeMorton2(uint32_t(x), uint32_t(y)) << log2SamplesPerPixel) | uint64_t(sampleIndex);
            break;
        }
        case SamplerKind::Halton: {
            pass = 0;
            sampleIndex = index;
            passSeed = seed;
            int64_t stride = int64_t(haltonBaseScale[0]) * haltonBaseScale[1];
            int64_t offset = 0;
            if (stride > 1) {
                // The first index whose dimensions 0, 1 land in the pixel (mod 128 tiles), by the
                // Chinese remainder theorem over the 2^j x 3^k block.
                int pm[2] = {x % 128, y % 128};
                if (pm[0] < 0) pm[0] += 128;
                if (pm[1] < 0) pm[1] += 128;
                for (int i = 0; i < 2; ++i) {
                    uint64_t dimOffset = InverseRadicalInverse(uint64_t(pm[i]), i == 0 ? 2 : 3, haltonBaseExponent[i]);
                    offset += int64_t(dimOffset) * (stride / haltonBaseScale[i]) * haltonMultInverse[i];
                }
                offset %= stride;
            }
            globalIndex = uint64_t(offset + int64_t(index) * stride);
            dimension = Max(2, dim);
            break;
        }
        case SamplerKind::Sobol:
            pass = 0;
            sampleIndex = index;
            passSeed = seed;
            globalIndex = SobolIntervalToIndex(sobolLog2Scale, uint64_t(uint32_t(index)), x, y);
            dimension = Max(2, dim);
            break;
        case SamplerKind::PMJ02BN:
            pass = uint32_t(index) / uint32_t(samplesPerPixel);
            sampleIndex = int(uint32_t(index) % uint32_t(samplesPerPixel));
            passSeed = PassSeed(seed, pass);
            dimension = Max(2, dim);
            break;
        case SamplerKind::PaddedSobol:
        case SamplerKind::Stratified:
            pass = uint32_t(index) / uint32_t(samplesPerPixel);
            sampleIndex = int(uint32_t(index) % uint32_t(samplesPerPixel));
            passSeed = PassSeed(seed, pass);
            if (kind == SamplerKind::Stratified) {
                rng.SetSequence(uint64_t(int64_t(x + y * 65536)) | (uint64_t(int64_t(passSeed)) << 32));
                rng.Advance(int64_t(sampleIndex) * 65536 + dim);
            }
            break;
        }
    }

    // One value in [0, 1).
    LU_HD LU_SAMPLER_INLINE Float Get1D() {
        if (kind == SamplerKind::ZSobol) {   // the default: kept small so that it inlines
            uint64_t index = ZSobolSampleIndex();
            ++dimension;
            uint32_t hash = uint32_t(MixBits(uint64_t(int64_t(dimension ^ passSeed))));
            return SobolSample(index, 0, Randomizer(), hash);
        }
        if (kind == SamplerKind::Independent) {
            ++dimension;
            return rng.Uniform<float>();
        }
        return Get1DOther();
    }

    // Two values in [0, 1)^2 (a 2D-stratified pair for the Sobol' kinds).
    LU_HD LU_SAMPLER_INLINE Vec2f Get2D() {
        if (kind == SamplerKind::ZSobol) {
            uint64_t index = ZSobolSampleIndex();
            dimension += 2;
            uint64_t bits = MixBits(uint64_t(int64_t(dimension ^ passSeed)));
            RandomizeStrategy r = Randomizer();
            if (r == RandomizeStrategy::FastOwen) return SobolSample2DFastOwen(index, uint32_t(bits), uint32_t(bits >> 32));
            return {SobolSample(index, 0, r, uint32_t(bits)), SobolSample(index, 1, r, uint32_t(bits >> 32))};
        }
        if (kind == SamplerKind::Independent) {
            dimension += 2;
            Float u0 = rng.Uniform<float>();
            Float u1 = rng.Uniform<float>();
            return {u0, u1};
        }
        return Get2DOther();
    }

    LU_HD Float Get1DOther() {
        switch (kind) {
        case SamplerKind::Independent: ++dimension; return rng.Uniform<float>();
        case SamplerKind::Halton:
            if (dimension >= kPrimeTableSize) dimension = 2;
            return HaltonDimension(dimension++);
        case SamplerKind::Sobol:
            if (dimension >= kSobolDimensions) dimension = 2;
            return SobolDimension(dimension++);
        case SamplerKind::PaddedSobol: {
            uint64_t hash = PixelDimensionHash();
            int index = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash));
            ++dimension;
            return SobolSample(uint64_t(index), 0, Randomizer(), uint32_t(hash >> 32));
        }
        case SamplerKind::PMJ02BN: {
            // pbrt-v4: the stratum permuted per pixel and dimension, jittered by a per-pixel offset.
            int index = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(PixelDimensionHash()));
            Float delta = PixelRotation(dimension);
            ++dimension;
            return Min((index + delta) / samplesPerPixel, OneMinusEpsilon);
        }
        default: {  // Stratified
            uint64_t hash = PixelDimensionHash();
            int stratum = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash));
            ++dimension;
            Float delta = jitter ? rng.Uniform<float>() : 0.5f;
            return Min((stratum + delta) / samplesPerPixel, OneMinusEpsilon);
        }
        }
    }

    LU_HD Vec2f Get2DOther() {
        switch (kind) {
        case SamplerKind::Independent: {
            dimension += 2;
            Float u0 = rng.Uniform<float>();
            Float u1 = rng.Uniform<float>();
            return {u0, u1};
        }
        case SamplerKind::Halton: {
            if (dimension + 1 >= kPrimeTableSize) dimension = 2;
            int d = dimension;
            dimension += 2;
            return {HaltonDimension(d), HaltonDimension(d + 1)};
        }
        case SamplerKind::Sobol: {
            if (dimension + 1 >= kSobolDimensions) dimension = 2;
            int d = dimension;
            dimension += 2;
            return {SobolDimension(d), SobolDimension(d + 1)};
        }
        case SamplerKind::PaddedSobol: {
            uint64_t hash = PixelDimensionHash();
            int index = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash));
            dimension += 2;
            RandomizeStrategy r = Randomizer();
            return {SobolSample(uint64_t(index), 0, r, uint32_t(hash)),
                    SobolSample(uint64_t(index), 1, r, uint32_t(hash >> 32))};
        }
        case SamplerKind::PMJ02BN: {
            // pbrt-v4: set dimension / 2 at the sample's own index while sets remain, then the sets
            // again at a permuted index; a Cranley-Patterson rotation per pixel and dimension.
            int index = sampleIndex, set = dimension / 2;
            if (set >= kPMJ02BNSets)
                index = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(PixelDimensionHash()));
            Vec2f u(0.5f, 0.5f);
            if (pmjPoints)
                u = pmjPoints[PMJPixelSampleCount() + size_t(set % kPMJ02BNSets) * size_t(samplesPerPixel) + size_t(index)];
            u = RotateToroidal(u, PixelRotation(dimension), PixelRotation(dimension + 1));
            dimension += 2;
            return u;
        }
        default: {  // Stratified
            uint64_t hash = PixelDimensionHash();
            int stratum = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash));
            dimension += 2;
            int sx = stratum % xPixelSamples, sy = stratum / xPixelSamples;
            Float dx = jitter ? rng.Uniform<float>() : 0.5f;
            Float dy = jitter ? rng.Uniform<float>() : 0.5f;
            return {Min((sx + dx) / xPixelSamples, OneMinusEpsilon), Min((sy + dy) / yPixelSamples, OneMinusEpsilon)};
        }
        }
    }

    // The sample for the position in the pixel: the next 2D sample, except for Halton and Sobol,
    // whose dimensions 0 and 1 (unrandomized) chose the pixel and give the offset in it (pbrt-v4).
    LU_HD Vec2f GetPixel2D() {
        if (kind == SamplerKind::Halton)
            return {RadicalInverse(0, globalIndex >> haltonBaseExponent[0]),
                    RadicalInverse(1, globalIndex / uint64_t(haltonBaseScale[1]))};
        if (kind == SamplerKind::Sobol) {
            Float scale = Float(1 << sobolLog2Scale);
            Float u0 = SobolSampleAny(globalIndex, 0, RandomizeStrategy::None, 0) * scale - Float(px);
            Float u1 = SobolSampleAny(globalIndex, 1, RandomizeStrategy::None, 0) * scale - Float(py);
            return {Clamp(u0, Float(0), OneMinusEpsilon), Clamp(u1, Float(0), OneMinusEpsilon)};
        }
        if (kind == SamplerKind::PMJ02BN) {
            // pbrt-v4: the pixel's share of the first set spread over the tile (no dimension is
            // consumed). Passes past the first rotate it (toroidally within the pixel).
            int tx = px % pmjTileSize, ty = py % pmjTileSize;
            if (tx < 0) tx += pmjTileSize;
            if (ty < 0) ty += pmjTileSize;
            if (!pmjPoints) return {0.5f, 0.5f};
            Vec2f u = pmjPoints[(size_t(tx) + size_t(ty) * size_t(pmjTileSize)) * size_t(samplesPerPixel) + size_t(sampleIndex)];
            if (pass > 0) {
                uint64_t h = MixBits(uint64_t(uint32_t(passSeed)) ^ 0x243f6a8885a308d3ull);
                return RotateToroidal(u, Float(h >> 40) * 0x1p-24f, Float((h >> 16) & 0xffffff) * 0x1p-24f);
            }
            return {Min(u.x, OneMinusEpsilon), Min(u.y, OneMinusEpsilon)};
        }
        return Get2D();
    }

    // ---- Internals ----

    // A point of [0,1)^2 shifted by (dx, dy) in [0,1), wrapped around the unit square.
    LU_HD static Vec2f RotateToroidal(Vec2f u, Float dx, Float dy) {
        u.x += dx;
        u.y += dy;
        if (u.x >= 1) u.x -= 1;
        if (u.y >= 1) u.y -= 1;
        return {Min(u.x, OneMinusEpsilon), Min(u.y, OneMinusEpsilon)};
    }

    // PMJ02BN: the number of pixel samples in the table (before the sets).
    LU_HD size_t PMJPixelSampleCount() const { return size_t(pmjTileSize) * size_t(pmjTileSize) * size_t(samplesPerPixel); }

    // PMJ02BN: the offset in [0, 1) of dimension d in this pixel (pbrt-v4's BlueNoise(d, pixel),
    // here white noise from a hash of the pixel, dimension and seed: Lucerna has no blue-noise table).
    LU_HD Float PixelRotation(int d) const {
        uint64_t h = MixBits((uint64_t(uint32_t(px)) << 48) ^ (uint64_t(uint32_t(py)) << 32) ^
                             (uint64_t(uint32_t(d)) << 16) ^ uint64_t(int64_t(passSeed)) ^ 0xb7e151628aed2a6bull);
        return Float(h >> 40) * 0x1p-24f;
    }

    // pbrt-v4's HaltonSampler::SampleDimension (PermuteDigits seeded by `seed`; Owen by dimension).
    LU_HD Float HaltonDimension(int d) const {
        if (randomize == RandomizeStrategy::None) return RadicalInverse(d, globalIndex);
        if (randomize == RandomizeStrategy::Owen)
            return OwenScrambledRadicalInverse(d, globalIndex, uint32_t(MixBits(1 + (uint64_t(d) << 4))));
        return ScrambledRadicalInverse(d, globalIndex, uint32_t(seed));
    }

    // pbrt-v4's SobolSampler::SampleDimension: the randomizer seeded by the dimension and seed.
    LU_HD Float SobolDimension(int d) const {
        uint32_t hash = uint32_t(MixBits((uint64_t(uint32_t(d)) << 32) ^ uint64_t(uint32_t(seed))));
        return SobolSampleAny(globalIndex, d, randomize, hash);
    }

    // pbrt-v4's ZSobolSampler::GetSampleIndex: Morton index with every base-4 digit shuffled by
    // one of the 24 permutations, chosen by a hash of the higher digits and the dimension. The
    // digits are visited from high to low with constant shifts only; the hashes do not depend
    // on each other, so they overlap in the pipeline.
    LU_HD LU_SAMPLER_INLINE uint64_t ZSobolSampleIndex() const {
        int pow2Samples = log2SamplesPerPixel & 1;
        // pbrt-v4 computes 0x55555555 * dimension in int and sign-extends it to 64 bits.
        uint64_t dimMix = uint64_t(int64_t(int32_t(0x55555555u * uint32_t(dimension))));
        // Digit i (pbrt-v4's numbering) sits at bit 2 i - pow2Samples of mortonIndex, for i from
        // pow2Samples to nBase4Digits - 1: the nDigits base-4 digits of `rest`, all of its bits.
        uint64_t rest = mortonIndex >> pow2Samples;
        int nDigits = nBase4Digits - pow2Samples;
        uint64_t index = 0;
#if defined(LU_ZSOBOL_SIMD)
        if (simd != 0 && nDigits > 0) {
            index = simd == 3   ? detail::ZSobolDigitsAVX512VBMI(rest, nDigits, dimMix)
                    : simd == 2 ? detail::ZSobolDigitsAVX512(rest, nDigits, dimMix)
                                : detail::ZSobolDigitsAVX2(rest, nDigits, dimMix);
        } else
#endif
        if (nDigits > 0) {
            uint64_t higher = nDigits < 32 ? rest >> (2 * nDigits) : 0;   // digits above the top one
            uint64_t aligned = rest << (64 - 2 * nDigits);                // top digit in bits 62..63
            for (int k = 0; k < nDigits; ++k) {
                int digit = int(aligned >> 62);
                aligned <<= 2;
                int p = int((MixBits(higher ^ dimMix) >> 24) % 24);
                index = (index << 2) | uint64_t(PermuteBase4Digit(p, digit));
                higher = (higher << 2) | uint64_t(digit);
            }
        }
        if (pow2Samples) index = (index << 1) | ((mortonIndex & 1) ^ (MixBits((mortonIndex >> 1) ^ dimMix) & 1));
        return index;
    }

    LU_HD uint64_t PixelDimensionHash() const {
        return MixBits((uint64_t(uint32_t(px)) << 48) ^ (uint64_t(uint32_t(py)) << 32) ^
                       (uint64_t(uint32_t(dimension)) << 16) ^ uint64_t(int64_t(passSeed)));
    }

    LU_HD RandomizeStrategy Randomizer() const {
        return (randomize == RandomizeStrategy::None && pass > 0) ? RandomizeStrategy::PermuteDigits : randomize;
    }

    LU_HD static int PassSeed(int seed, uint32_t pass) {
        if (pass == 0) return seed;
        return int(uint32_t(MixBits((uint64_t(uint32_t(seed)) << 32) ^ pass ^ 0x9e3779b97f4a7c15ull)));
    }
};

}  // namespace lu
