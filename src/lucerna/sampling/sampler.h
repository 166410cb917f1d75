// Lucerna: pixel samplers as one value type (host and device), after pbrt-v4's samplers.h:
// IndependentSampler, ZSobolSampler (the default), PaddedSobolSampler and StratifiedSampler.
// Every value depends only on (pixel, sample index, dimension, seed) and the configuration,
// never on call history across pixels or threads.
#pragma once

#include "lucerna/sampling/lowdiscrepancy.h"
#include "lucerna/sampling/rng.h"
#include "lucerna/util/vecmath.h"

#if !defined(LU_DEVICE_CODE)
#include <cstdio>
#include <string>
#endif

namespace lu {

enum class SamplerKind : uint8_t { Independent, ZSobol, PaddedSobol, Stratified };

// Usage per pixel sample: StartPixelSample(px, py, index), then Get1D / Get2D / GetPixel2D in a
// fixed order; each call consumes 1 or 2 dimensions. Starting at dimension d gives the same
// values as starting at 0 and consuming d dimensions first.
//
// Sample indices >= samplesPerPixel (progressive rendering past the nominal count) are
// deterministic: index i is split into pass = i / n and r = i % n, where n is the pattern size
// (2^log2SamplesPerPixel for ZSobol, samplesPerPixel for PaddedSobol/Stratified); pass 0 is
// exactly pbrt-v4's sample r, and pass k > 0 reuses pattern sample r under an independent
// randomization (the seed mixed with k; "none" randomization becomes a digit permutation for
// k > 0). Each pass is thus a fresh stratified set, so the estimate stays unbiased and keeps
// converging. The independent sampler needs no passes (PCG32 stream offset index * 65536 + dim).
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

    // ---- Per pixel-sample state (set by StartPixelSample) ----
    int px = 0, py = 0;
    int sampleIndex = 0;      // index within the pattern (r above)
    int dimension = 0;
    uint32_t pass = 0;
    int passSeed = 0;         // seed, mixed with the pass for pass > 0
    uint64_t mortonIndex = 0; // ZSobol
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
        return Get2DOther();
    }

    LU_HD Float Get1DOther() {
        switch (kind) {
        case SamplerKind::Independent: ++dimension; return rng.Uniform<float>();
        case SamplerKind::PaddedSobol: {
            uint64_t hash = PixelDimensionHash();
            int index = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash));
            ++dimension;
            return SobolSample(uint64_t(index), 0, Randomizer(), uint32_t(hash >> 32));
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
        case SamplerKind::PaddedSobol: {
            uint64_t hash = PixelDimensionHash();
            int index = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash));
            dimension += 2;
            RandomizeStrategy r = Randomizer();
            return {SobolSample(uint64_t(index), 0, r, uint32_t(hash)),
                    SobolSample(uint64_t(index), 1, r, uint32_t(hash >> 32))};
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

    // The sample for the position in the pixel (all kinds here: the next 2D sample, as pbrt-v4).
    LU_HD Vec2f GetPixel2D() { return Get2D(); }

    // ---- Internals ----

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

#if !defined(LU_DEVICE_CODE)
// Options of pbrt-v4's Sampler directive beyond the sample count and seed.
struct SamplerOptions {
    std::string randomization;   // "none", "permutedigits", "fastowen", "owen"; "" = pbrt-v4 default
    int xSamples = 0, ySamples = 0;  // stratified; used when xSamples * ySamples == spp
    bool jitter = true;          // stratified
};

// Builds a sampler by pbrt-v4 name: "independent", "zsobol" (default), "paddedsobol",
// "stratified". "sobol", "halton", "pmj02bn" and unknown names fall back to ZSobol with the
// requested spp. As pbrt-v4 does, "zsobol" rounds a non-power-of-two spp down to a power of two.
// Anything noteworthy (fallbacks, rounding) is appended to *report (one line each) when given,
// else printed to stderr as a warning.
inline Sampler MakeSampler(const std::string &name, int spp, int seed, int width, int height,
                           const SamplerOptions &options = {}, std::string *report = nullptr) {
    auto note = [&](const std::string &msg) {
        if (report) *report += msg + "\n";
        else std::fprintf(stderr, "warning: %s\n", msg.c_str());
    };
    Sampler s;
    s.seed = seed;
    s.samplesPerPixel = Max(1, spp);
    bool roundZSobol = true;
    if (name == "independent") s.kind = SamplerKind::Independent;
    else if (name == "zsobol" || name.empty()) s.kind = SamplerKind::ZSobol;
    else if (name == "paddedsobol") s.kind = SamplerKind::PaddedSobol;
    else if (name == "stratified") s.kind = SamplerKind::Stratified;
    else {
        s.kind = SamplerKind::ZSobol;
        roundZSobol = false;
        if (name == "sobol" || name == "halton" || name == "pmj02bn")
            note("sampler \"" + name + "\" is not implemented; using \"zsobol\" instead");
        else
            note("unknown sampler \"" + name + "\"; using \"zsobol\" instead");
    }

    const std::string &rnd = options.randomization;
    if (rnd.empty() || rnd == "fastowen") s.randomize = RandomizeStrategy::FastOwen;
    else if (rnd == "none") s.randomize = RandomizeStrategy::None;
    else if (rnd == "permutedigits") s.randomize = RandomizeStrategy::PermuteDigits;
    else if (rnd == "owen") s.randomize = RandomizeStrategy::Owen;
    else {
        s.randomize = RandomizeStrategy::FastOwen;
        note("unknown randomization \"" + rnd + "\"; using \"fastowen\"");
    }

    if (s.kind == SamplerKind::ZSobol) {
        int n = s.samplesPerPixel;
        s.log2SamplesPerPixel = Log2Int(uint64_t(n));
        if (!IsPowerOf2(n)) {
            if (roundZSobol) {
                s.samplesPerPixel = 1 << s.log2SamplesPerPixel;
                note("zsobol: " + std::to_string(n) + " samples per pixel rounded down to " +
                     std::to_string(s.samplesPerPixel) + " (as pbrt-v4)");
            } else {
                note("zsobol: " + std::to_string(n) + " samples per pixel is not a power of two; samples past " +
                     std::to_string(1 << s.log2SamplesPerPixel) + " use a second randomized pattern");
            }
        }
        int res = int(RoundUpPow2(Max(1, Max(width, height))));
        s.nBase4Digits = Log2Int(uint64_t(res)) + (s.log2SamplesPerPixel + 1) / 2;
    } else if (s.kind == SamplerKind::Stratified) {
        int n = s.samplesPerPixel;
        if (options.xSamples > 0 && options.ySamples > 0 && options.xSamples * options.ySamples == n) {
            s.xPixelSamples = options.xSamples;
            s.yPixelSamples = options.ySamples;
        } else {
            // pbrt-v4's factorization for an overridden sample count.
            int div = int(std::sqrt(double(n)));
            while (n % div) --div;
            s.xPixelSamples = n / div;
            s.yPixelSamples = n / s.xPixelSamples;
        }
        s.jitter = options.jitter;
    } else if (s.kind == SamplerKind::PaddedSobol && !IsPowerOf2(s.samplesPerPixel)) {
        note("paddedsobol: non power-of-two sample count " + std::to_string(s.samplesPerPixel) + " is sub-optimal");
    }
    return s;
}
#endif

}  // namespace lu
