// Lucerna (host): the sampler of sampling/sampler.h built from pbrt-v4's Sampler directive.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include "lucerna/sampling/sampler.h"

namespace lu {

// Options of pbrt-v4's Sampler directive beyond the sample count and seed.
struct SamplerOptions {
    std::string randomization;   // "none", "permutedigits", "fastowen", "owen"; "" = pbrt-v4 default
    int xSamples = 0, ySamples = 0;  // stratified; used when xSamples * ySamples == spp
    bool jitter = true;          // stratified
};

// Builds a sampler by pbrt-v4 name: "independent", "zsobol" (default), "paddedsobol",
// "stratified", "halton", "sobol", "pmj02bn" (its tables: BuildPMJ02BNTables, bound by
// RenderSampler). Unknown names fall back to ZSobol with the requested spp. As pbrt-v4 does, "zsobol" rounds a non-power-of-two spp down to a power of two.
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
#if defined(LU_ZSOBOL_SIMD)
    static const uint8_t simdLevel = detail::ZSobolSimdLevel();
    s.simd = simdLevel;
#endif
    s.samplesPerPixel = Max(1, spp);
    bool roundZSobol = true;
    if (name == "independent") s.kind = SamplerKind::Independent;
    else if (name == "zsobol" || name.empty()) s.kind = SamplerKind::ZSobol;
    else if (name == "paddedsobol") s.kind = SamplerKind::PaddedSobol;
    else if (name == "stratified") s.kind = SamplerKind::Stratified;
    else if (name == "halton") s.kind = SamplerKind::Halton;
    else if (name == "sobol") s.kind = SamplerKind::Sobol;
    else if (name == "pmj02bn") s.kind = SamplerKind::PMJ02BN;
    else {
        s.kind = SamplerKind::ZSobol;
        roundZSobol = false;
        note("unknown sampler \"" + name + "\"; using \"zsobol\" instead");
    }
    if (s.kind == SamplerKind::PMJ02BN) {
        int n = s.samplesPerPixel, p4 = 1;
        while (p4 < n) p4 *= 4;
        if (p4 != n)
            note("pmj02bn: results are best with a power-of-4 sample count (1, 4, 16, 64, ...), got " + std::to_string(n));
    }

    const std::string &rnd = options.randomization;
    if (rnd.empty() && s.kind == SamplerKind::Halton) s.randomize = RandomizeStrategy::PermuteDigits;   // pbrt-v4's default
    else if (rnd.empty() || rnd == "fastowen") s.randomize = RandomizeStrategy::FastOwen;
    else if (rnd == "none") s.randomize = RandomizeStrategy::None;
    else if (rnd == "permutedigits") s.randomize = RandomizeStrategy::PermuteDigits;
    else if (rnd == "owen") s.randomize = RandomizeStrategy::Owen;
    else {
        s.randomize = RandomizeStrategy::FastOwen;
        note("unknown randomization \"" + rnd + "\"; using \"fastowen\"");
    }

    if (s.kind == SamplerKind::Halton && s.randomize == RandomizeStrategy::FastOwen) {
        s.randomize = RandomizeStrategy::PermuteDigits;
        note("halton: \"fastowen\" randomization is not available; using \"permutedigits\"");
    }
    if (s.kind == SamplerKind::Halton) {
        // pbrt-v4: the smallest 2^j (3^k) covering the resolution, up to 128 pixels; the pixel's
        // first index by the Chinese remainder theorem needs the inverses of one scale mod the other.
        int res[2] = {Max(1, width), Max(1, height)};
        for (int i = 0; i < 2; ++i) {
            int base = i == 0 ? 2 : 3, scale = 1, exp = 0;
            while (scale < Min(res[i], 128)) {
                scale *= base;
                ++exp;
            }
            s.haltonBaseScale[i] = scale;
            s.haltonBaseExponent[i] = exp;
        }
        auto inverseMod = [](int64_t a, int64_t n) -> int {
            if (n == 1) return 0;
            for (int64_t x = 1; x < n; ++x)
                if ((a * x) % n == 1) return int(x);
            return 0;   // unreachable: powers of 2 and 3 are coprime
        };
        s.haltonMultInverse[0] = inverseMod(s.haltonBaseScale[1], s.haltonBaseScale[0]);
        s.haltonMultInverse[1] = inverseMod(s.haltonBaseScale[0], s.haltonBaseScale[1]);
    } else if (s.kind == SamplerKind::Sobol) {
        int res = int(RoundUpPow2(Max(1, Max(width, height))));
        s.sobolLog2Scale = Log2Int(uint64_t(res));
        if (!IsPowerOf2(s.samplesPerPixel))
            note("sobol: non power-of-two sample count " + std::to_string(s.samplesPerPixel) + " is sub-optimal");
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

}  // namespace lu
