// Lucerna: the low-discrepancy sequences of pbrt-v4's global samplers (host and device): prime
// bases and radical inverses (plain, digit-permuted, Owen-scrambled) for Halton, and Sobol'
// generator matrices for 1024 dimensions, computed from Lucerna's own lists (no tables copied).
#pragma once

#include "lucerna/sampling/hash.h"
#include "lucerna/sampling/lowdiscrepancy.h"
#include "lucerna/util/common.h"

namespace lu {

// ---- Primes (Halton bases) ----

constexpr int kPrimeTableSize = 1000;   // as pbrt-v4's PrimeTableSize: dimensions past it wrap to 2

struct PrimeTable {
    uint16_t p[kPrimeTableSize];
};

constexpr PrimeTable MakePrimeTable() {
    PrimeTable t{};
    int n = 0;
    for (int c = 2; n < kPrimeTableSize; ++c) {
        bool prime = true;
        for (int i = 0; i < n && int(t.p[i]) * int(t.p[i]) <= c; ++i)
            if (c % t.p[i] == 0) { prime = false; break; }
        if (prime) t.p[n++] = uint16_t(c);
    }
    return t;
}

inline constexpr PrimeTable kPrimes = MakePrimeTable();
#if defined(__CUDACC__)
[[maybe_unused]] static __device__ const PrimeTable kPrimesDevice = MakePrimeTable();
#endif

// The i-th prime (Prime(0) = 2), 0 <= i < kPrimeTableSize.
LU_INLINE int Prime(int i) {
#if defined(__CUDA_ARCH__)
    return kPrimesDevice.p[i];
#else
    return kPrimes.p[i];
#endif
}

// ---- Radical inverses ----

// Digits of a in base Prime(baseIndex), mirrored about the radix point.
LU_INLINE Float RadicalInverse(int baseIndex, uint64_t a) {
    int base = Prime(baseIndex);
    Float invBase = Float(1) / Float(base), invBaseN = 1;
    uint64_t reversedDigits = 0;
    while (a) {
        uint64_t next = a / uint64_t(base);
        uint64_t digit = a - next * uint64_t(base);
        reversedDigits = reversedDigits * uint64_t(base) + digit;
        invBaseN *= invBase;
        a = next;
    }
    return Min(Float(reversedDigits) * invBaseN, OneMinusEpsilon);
}

// The index whose first nDigits base-`base` digits, mirrored, are `inverse` (its inverse above,
// restricted to nDigits digits).
LU_INLINE uint64_t InverseRadicalInverse(uint64_t inverse, int base, int nDigits) {
    uint64_t index = 0;
    for (int i = 0; i < nDigits; ++i) {
        uint64_t digit = inverse % uint64_t(base);
        inverse /= uint64_t(base);
        index = index * uint64_t(base) + digit;
    }
    return index;
}

// pbrt-v4's DigitPermutation, evaluated on the fly instead of stored: digit `digitIndex` of base
// `base` is permuted by the Kensler permutation seeded with Hash(base, digitIndex, seed).
LU_INLINE int PermuteDigit(int base, int digitIndex, uint32_t seed, int digitValue) {
    uint64_t dseed = Hash(base, digitIndex, seed);
    return PermutationElement(uint32_t(digitValue), uint32_t(base), uint32_t(dseed));
}

// Radical inverse with a random permutation per digit position (pbrt-v4's ScrambledRadicalInverse
// with ComputeRadicalInversePermutations(seed)): every digit that a float can resolve is permuted,
// including the (zero) digits past the last nonzero digit of a.
LU_INLINE Float ScrambledRadicalInverse(int baseIndex, uint64_t a, uint32_t seed) {
    int base = Prime(baseIndex);
    Float invBase = Float(1) / Float(base), invBaseM = 1;
    uint64_t reversedDigits = 0;
    int digitIndex = 0;
    while (1 - Float(base - 1) * invBaseM < 1) {
        uint64_t next = a / uint64_t(base);
        int digitValue = int(a - next * uint64_t(base));
        reversedDigits = reversedDigits * uint64_t(base) + uint64_t(PermuteDigit(base, digitIndex, seed, digitValue));
        invBaseM *= invBase;
        ++digitIndex;
        a = next;
    }
    return Min(invBaseM * Float(reversedDigits), OneMinusEpsilon);
}

// Owen-scrambled radical inverse: each digit permuted by a hash of the digits before it.
LU_INLINE Float OwenScrambledRadicalInverse(int baseIndex, uint64_t a, uint32_t hash) {
    int base = Prime(baseIndex);
    uint64_t limit = ~0ull / uint64_t(base) - uint64_t(base);   // reversedDigits * base must not overflow
    Float invBase = Float(1) / Float(base), invBaseM = 1;
    uint64_t reversedDigits = 0;
    while (1 - invBaseM < 1 && reversedDigits < limit) {
        uint64_t next = a / uint64_t(base);
        int digitValue = int(a - next * uint64_t(base));
        uint32_t digitHash = uint32_t(MixBits(uint64_t(hash) ^ reversedDigits));
        digitValue = PermutationElement(uint32_t(digitValue), uint32_t(base), digitHash);
        reversedDigits = reversedDigits * uint64_t(base) + uint64_t(digitValue);
        invBaseM *= invBase;
        a = next;
    }
    return Min(invBaseM * Float(reversedDigits), OneMinusEpsilon);
}

// ---- Sobol' generator matrices ----
//
// Dimension 0 is the van der Corput sequence and dimension 1 the Pascal matrix (both identical to
// pbrt-v4's and to lowdiscrepancy.h's SobolGenerate). Dimension d >= 1 uses the d-th primitive
// polynomial over GF(2) in order of degree and value (x+1, x^2+x+1, x^3+x+1, x^3+x^2+1, ...), as
// Sobol' and Joe-Kuo order them. The initial direction numbers m_i
// (odd, < 2^i) of dimensions >= 2 are Lucerna's own pseudo-random choice (Bratley-Fox's random
// initialization, screened against gross 2D defects of consecutive dimensions), not Joe-Kuo's
// optimized ones that pbrt-v4 tabulates; the sequence is a valid
// Sobol' sequence (each dimension a (0,1)-sequence, dimensions 0 and 1 a (0,2)-sequence), but
// dimensions >= 2 differ from pbrt-v4's value by value.

constexpr int kSobolDimensions = 1024;   // as pbrt-v4's NSobolDimensions
constexpr int kSobolMatrixSize = 52;     // columns: indices below 2^52

struct SobolMatrices {
    uint32_t c[kSobolDimensions * kSobolMatrixSize];   // column k of dimension d at d * 52 + k; bit 31 = 1/2
};

namespace detail {

// a * b mod p over GF(2), deg p = s <= 31.
constexpr uint64_t Gf2MulMod(uint64_t a, uint64_t b, uint64_t p, int s) {
    uint64_t r = 0;
    while (b) {
        if (b & 1) r ^= a;
        b >>= 1;
        a <<= 1;
        if (a & (uint64_t(1) << s)) a ^= p;
    }
    return r;
}

constexpr uint64_t Gf2PowMod(uint64_t base, uint64_t e, uint64_t p, int s) {
    uint64_t r = 1;
    while (e) {
        if (e & 1) r = Gf2MulMod(r, base, p, s);
        base = Gf2MulMod(base, base, p, s);
        e >>= 1;
    }
    return r;
}

// p (degree s, bit s set) is primitive iff x has multiplicative order 2^s - 1 modulo p.
constexpr bool IsPrimitivePolynomial(uint64_t p, int s) {
    if (!(p & 1)) return false;
    uint64_t n = (uint64_t(1) << s) - 1;
    uint64_t x = s == 1 ? 1 : 2;   // x mod p (for s = 1, x = 1 mod x+1)
    if (Gf2PowMod(x, n, p, s) != 1) return false;
    uint64_t m = n;
    for (uint64_t q = 2; q * q <= m; ++q) {
        if (m % q) continue;
        while (m % q == 0) m /= q;
        if (Gf2PowMod(x, n / q, p, s) == 1) return false;
    }
    return !(m > 1 && Gf2PowMod(x, n / m, p, s) == 1);
}

constexpr uint64_t SplitMix(uint64_t v) {
    v += 0x9e3779b97f4a7c15ull;
    v = (v ^ (v >> 30)) * 0xbf58476d1ce4e5b9ull;
    v = (v ^ (v >> 27)) * 0x94d049bb133111ebull;
    return v ^ (v >> 31);
}

}  // namespace detail

// The first 1023 primitive polynomials over GF(2), bit i = coefficient of x^i, in order of degree
// and value: a mathematical enumeration (scripts/gen_primitive_polys.py prints it; the tests derive
// it again with IsPrimitivePolynomial), kept as a list because deriving it at compile time exceeds
// the compilers' constexpr budgets.
inline constexpr uint16_t kPrimitivePolynomials[kSobolDimensions - 1] = {
    3, 7, 11, 13, 19, 25, 37, 41, 47, 55, 59, 61, 67, 91, 97, 103,
    109, 115, 131, 137, 143, 145, 157, 167, 171, 185, 191, 193, 203, 211, 213, 229,
    239, 241, 247, 253, 285, 299, 301, 333, 351, 355, 357, 361, 369, 391, 397, 425,
    451, 463, 487, 501, 529, 539, 545, 557, 563, 601, 607, 617, 623, 631, 637, 647,
    661, 675, 677, 687, 695, 701, 719, 721, 731, 757, 761, 787, 789, 799, 803, 817,
    827, 847, 859, 865, 875, 877, 883, 895, 901, 911, 949, 953, 967, 971, 973, 981,
    985, 995, 1001, 1019, 1033, 1051, 1063, 1069, 1125, 1135, 1153, 1163, 1221, 1239, 1255, 1267,
    1279, 1293, 1305, 1315, 1329, 1341, 1347, 1367, 1387, 1413, 1423, 1431, 1441, 1479, 1509, 1527,
    1531, 1555, 1557, 1573, 1591, 1603, 1615, 1627, 1657, 1663, 1673, 1717, 1729, 1747, 1759, 1789,
    1815, 1821, 1825, 1849, 1863, 1869, 1877, 1881, 1891, 1917, 1933, 1939, 1969, 2011, 2035, 2041,
    2053, 2071, 2091, 2093, 2119, 2147, 2149, 2161, 2171, 2189, 2197, 2207, 2217, 2225, 2255, 2257,
    2273, 2279, 2283, 2293, 2317, 2323, 2341, 2345, 2363, 2365, 2373, 2377, 2385, 2395, 2419, 2421,
    2431, 2435, 2447, 2475, 2477, 2489, 2503, 2521, 2533, 2551, 2561, 2567, 2579, 2581, 2601, 2633,
    2657, 2669, 2681, 2687, 2693, 2705, 2717, 2727, 2731, 2739, 2741, 2773, 2783, 2793, 2799, 2801,
    2811, 2819, 2825, 2833, 2867, 2879, 2881, 2891, 2905, 2911, 2917, 2927, 2941, 2951, 2955, 2963,
    2965, 2991, 2999, 3005, 3017, 3035, 3037, 3047, 3053, 3083, 3085, 3097, 3103, 3159, 3169, 3179,
    3187, 3205, 3209, 3223, 3227, 3229, 3251, 3263, 3271, 3277, 3283, 3285, 3299, 3305, 3319, 3331,
    3343, 3357, 3367, 3373, 3393, 3399, 3413, 3417, 3427, 3439, 3441, 3475, 3487, 3497, 3515, 3517,
    3529, 3543, 3547, 3553, 3559, 3573, 3589, 3613, 3617, 3623, 3627, 3635, 3641, 3655, 3659, 3669,
    3679, 3697, 3707, 3709, 3713, 3731, 3743, 3747, 3771, 3791, 3805, 3827, 3833, 3851, 3865, 3889,
    3895, 3933, 3947, 3949, 3957, 3971, 3985, 3991, 3995, 4007, 4013, 4021, 4045, 4051, 4069, 4073,
    4179, 4201, 4219, 4221, 4249, 4305, 4331, 4359, 4383, 4387, 4411, 4431, 4439, 4449, 4459, 4485,
    4531, 4569, 4575, 4621, 4663, 4669, 4711, 4723, 4735, 4793, 4801, 4811, 4879, 4893, 4897, 4921,
    4927, 4941, 4977, 5017, 5027, 5033, 5127, 5169, 5175, 5199, 5213, 5223, 5237, 5287, 5293, 5331,
    5391, 5405, 5453, 5523, 5573, 5591, 5597, 5611, 5641, 5703, 5717, 5721, 5797, 5821, 5909, 5913,
    5955, 5957, 6005, 6025, 6061, 6067, 6079, 6081, 6231, 6237, 6289, 6295, 6329, 6383, 6427, 6453,
    6465, 6501, 6523, 6539, 6577, 6589, 6601, 6607, 6631, 6683, 6699, 6707, 6761, 6795, 6865, 6881,
    6901, 6923, 6931, 6943, 6999, 7057, 7079, 7103, 7105, 7123, 7173, 7185, 7191, 7207, 7245, 7303,
    7327, 7333, 7355, 7365, 7369, 7375, 7411, 7431, 7459, 7491, 7505, 7515, 7541, 7557, 7561, 7701,
    7705, 7727, 7749, 7761, 7783, 7795, 7823, 7907, 7953, 7963, 7975, 8049, 8089, 8123, 8125, 8137,
    8219, 8231, 8245, 8275, 8293, 8303, 8331, 8333, 8351, 8357, 8367, 8379, 8381, 8387, 8393, 8417,
    8435, 8461, 8469, 8489, 8495, 8507, 8515, 8551, 8555, 8569, 8585, 8599, 8605, 8639, 8641, 8647,
    8653, 8671, 8675, 8689, 8699, 8729, 8741, 8759, 8765, 8771, 8795, 8797, 8825, 8831, 8841, 8855,
    8859, 8883, 8895, 8909, 8943, 8951, 8955, 8965, 8999, 9003, 9031, 9045, 9049, 9071, 9073, 9085,
    9095, 9101, 9109, 9123, 9129, 9137, 9143, 9147, 9185, 9197, 9209, 9227, 9235, 9247, 9253, 9257,
    9277, 9297, 9303, 9313, 9325, 9343, 9347, 9371, 9373, 9397, 9407, 9409, 9415, 9419, 9443, 9481,
    9495, 9501, 9505, 9517, 9529, 9555, 9557, 9571, 9585, 9591, 9607, 9611, 9621, 9625, 9631, 9647,
    9661, 9669, 9679, 9687, 9707, 9731, 9733, 9745, 9773, 9791, 9803, 9811, 9817, 9833, 9847, 9851,
    9863, 9875, 9881, 9905, 9911, 9917, 9923, 9963, 9973, 10003, 10025, 10043, 10063, 10071, 10077, 10091,
    10099, 10105, 10115, 10129, 10145, 10169, 10183, 10187, 10207, 10223, 10225, 10247, 10265, 10271, 10275, 10289,
    10299, 10301, 10309, 10343, 10357, 10373, 10411, 10413, 10431, 10445, 10453, 10463, 10467, 10473, 10491, 10505,
    10511, 10513, 10523, 10539, 10549, 10559, 10561, 10571, 10581, 10615, 10621, 10625, 10643, 10655, 10671, 10679,
    10685, 10691, 10711, 10739, 10741, 10755, 10767, 10781, 10785, 10803, 10805, 10829, 10857, 10863, 10865, 10875,
    10877, 10917, 10921, 10929, 10949, 10967, 10971, 10987, 10995, 11009, 11029, 11043, 11045, 11055, 11063, 11075,
    11081, 11117, 11135, 11141, 11159, 11163, 11181, 11187, 11225, 11237, 11261, 11279, 11297, 11307, 11309, 11327,
    11329, 11341, 11377, 11403, 11405, 11413, 11427, 11439, 11453, 11461, 11473, 11479, 11489, 11495, 11499, 11533,
    11545, 11561, 11567, 11575, 11579, 11589, 11611, 11623, 11637, 11657, 11663, 11687, 11691, 11701, 11747, 11761,
    11773, 11783, 11795, 11797, 11817, 11849, 11855, 11867, 11869, 11873, 11883, 11919, 11921, 11927, 11933, 11947,
    11955, 11961, 11999, 12027, 12029, 12037, 12041, 12049, 12055, 12095, 12097, 12107, 12109, 12121, 12127, 12133,
    12137, 12181, 12197, 12207, 12209, 12239, 12253, 12263, 12269, 12277, 12287, 12295, 12309, 12313, 12335, 12361,
    12367, 12391, 12409, 12415, 12433, 12449, 12469, 12479, 12481, 12499, 12505, 12517, 12527, 12549, 12559, 12597,
    12615, 12621, 12639, 12643, 12657, 12667, 12707, 12713, 12727, 12741, 12745, 12763, 12769, 12779, 12781, 12787,
    12799, 12809, 12815, 12829, 12839, 12857, 12875, 12883, 12889, 12901, 12929, 12947, 12953, 12959, 12969, 12983,
    12987, 12995, 13015, 13019, 13031, 13063, 13077, 13103, 13137, 13149, 13173, 13207, 13211, 13227, 13241, 13249,
    13255, 13269, 13283, 13285, 13303, 13307, 13321, 13339, 13351, 13377, 13389, 13407, 13417, 13431, 13435, 13447,
    13459, 13465, 13477, 13501, 13513, 13531, 13543, 13561, 13581, 13599, 13605, 13617, 13623, 13637, 13647, 13661,
    13677, 13683, 13695, 13725, 13729, 13753, 13773, 13781, 13785, 13795, 13801, 13807, 13825, 13835, 13855, 13861,
    13871, 13883, 13897, 13905, 13915, 13939, 13941, 13969, 13979, 13981, 13997, 14027, 14035, 14037, 14051, 14063,
    14085, 14095, 14107, 14113, 14125, 14137, 14145, 14151, 14163, 14193, 14199, 14219, 14229, 14233, 14243, 14277,
    14287, 14289, 14295, 14301, 14305, 14323, 14339, 14341, 14359, 14365, 14375, 14387, 14411, 14425, 14441, 14449,
    14499, 14513, 14523, 14537, 14543, 14561, 14579, 14585, 14593, 14599, 14603, 14611, 14641, 14671, 14695, 14701,
    14723, 14725, 14743, 14753, 14759, 14765, 14795, 14797, 14803, 14831, 14839, 14845, 14855, 14889, 14895, 14909,
    14929, 14941, 14945, 14951, 14963, 14965, 14985, 15033, 15039, 15053, 15059, 15061, 15071, 15077, 15081, 15099,
    15121, 15147, 15149, 15157, 15167, 15187, 15193, 15203, 15205, 15215, 15217, 15223, 15243, 15257, 15269,
};

// Lucerna's initial direction numbers of dimension d >= 2 (degree s): m_i = 2 (SplitMix64(d << 16 |
// c << 8 | i) mod 2^(i-1)) + 1, i = 1..s, with c = kSobolInitCandidate[d - 2], the first candidate for
// which dimensions d-1 and d have no gross 2D defect over their first 4096 and 16384 points
// (scripts/gen_sobol_init.py chose them; tests/sampling/global_samplers_test.cpp checks the property).
inline constexpr uint8_t kSobolInitCandidate[kSobolDimensions - 2] = {
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0,
    0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0,
};

constexpr SobolMatrices MakeSobolMatrices() {
    SobolMatrices t{};
    for (int k = 0; k < kSobolMatrixSize; ++k) t.c[k] = k < 32 ? (1u << (31 - k)) : 0u;
    for (int dim = 1; dim < kSobolDimensions; ++dim) {
        uint64_t p = kPrimitivePolynomials[dim - 1];
        int s = 0;
        while ((p >> (s + 1)) != 0) ++s;
        uint64_t m[kSobolMatrixSize + 1] = {};
        for (int i = 1; i <= s && i <= kSobolMatrixSize; ++i) {
            if (dim == 1) m[i] = 1;   // (x+1, m_1 = 1): the Pascal matrix
            else {
                uint64_t key = (uint64_t(dim) << 16) | (uint64_t(kSobolInitCandidate[dim - 2]) << 8) | uint64_t(i);
                m[i] = ((detail::SplitMix(key) % (uint64_t(1) << (i - 1))) << 1) | 1;
            }
        }
        for (int k = s + 1; k <= kSobolMatrixSize; ++k) {
            uint64_t v = m[k - s] ^ (m[k - s] << s);
            for (int j = 1; j < s; ++j)
                if ((p >> (s - j)) & 1) v ^= m[k - j] << j;
            m[k] = v;
        }
        for (int k = 1; k <= kSobolMatrixSize; ++k)
            t.c[dim * kSobolMatrixSize + k - 1] = uint32_t(k <= 32 ? m[k] << (32 - k) : m[k] >> (k - 32));
    }
    return t;
}

#if defined(__CUDACC__)
[[maybe_unused]] static __device__ const SobolMatrices kSobolMatricesDevice = MakeSobolMatrices();
#endif
#if !defined(__CUDA_ARCH__)
// The host copy, computed on first use (a compile-time table would cost every translation unit
// that includes this header seconds of constant evaluation).
inline SobolMatrices MakeSobolMatricesAtRunTime() { return MakeSobolMatrices(); }
inline const SobolMatrices &HostSobolMatrices() {
    static const SobolMatrices table = MakeSobolMatricesAtRunTime();
    return table;
}
#endif

// The kSobolMatrixSize columns of one dimension.
LU_INLINE const uint32_t *SobolDimensionColumns(int dimension) {
#if defined(__CUDA_ARCH__)
    return kSobolMatricesDevice.c + dimension * kSobolMatrixSize;
#else
    return HostSobolMatrices().c + dimension * kSobolMatrixSize;
#endif
}

// The unrandomized 32-bit Sobol' value of index a (< 2^52) in any dimension < kSobolDimensions.
LU_INLINE uint32_t SobolGenerateAny(uint64_t a, int dimension) {
    if (dimension < 2) return SobolGenerate(a, dimension);
    const uint32_t *c = SobolDimensionColumns(dimension);
    uint32_t v = 0;
    for (int k = 0; a != 0 && k < kSobolMatrixSize; a >>= 1, ++k)
        if (a & 1) v ^= c[k];
    return v;
}

// Randomized Sobol' sample in [0, 1) of any dimension (pbrt-v4's SobolSample with the table).
LU_INLINE Float SobolSampleAny(uint64_t a, int dimension, RandomizeStrategy r, uint32_t hash) {
    uint32_t v = SobolGenerateAny(a, dimension);
    switch (r) {
    case RandomizeStrategy::None: break;
    case RandomizeStrategy::PermuteDigits: v = BinaryPermuteScrambler(hash)(v); break;
    case RandomizeStrategy::FastOwen: v = FastOwenScrambler(hash)(v); break;
    default: v = OwenScrambler(hash)(v); break;
    }
    return UInt32ToUnitFloat(v);
}

// pbrt-v4's SobolIntervalToIndex: the index of the `frame`-th Sobol' point (unrandomized) whose
// dimensions 0 and 1, scaled by 2^m (m <= 16), fall in pixel (px, py), px, py < 2^m. Dimensions
// 0 and 1 form a (0,2)-sequence, so each block of 2^2m indices holds exactly one such point: the
// low m index bits are px mirrored (van der Corput), bits m..2m-1 solve a linear system over GF(2)
// for py (the Pascal matrix), and the higher bits are `frame`.
LU_INLINE uint64_t SobolIntervalToIndex(int m, uint64_t frame, int px, int py) {
    if (m == 0) return frame;
    uint32_t maskM = (1u << m) - 1;
    uint64_t known = (uint64_t(frame) << (2 * m)) | uint64_t(ReverseBits32(uint32_t(px)) >> (32 - m));
    // Dimension 1's top m bits are bits 0..m-1 of SobolPascalReversed(index), mirrored; the map is
    // linear, so solve SobolPascalReversed(u) & maskM == target for u in bits m..2m-1.
    uint32_t target = (ReverseBits32(uint32_t(py)) >> (32 - m)) ^ (SobolPascalReversed(known) & maskM);
    // Gauss-Jordan elimination: rows are unknown bits (column image, combination of unknowns).
    uint32_t rowImage[16] = {}, rowCombo[16] = {};
    for (int i = 0; i < m; ++i) {
        rowImage[i] = SobolPascalReversed(uint64_t(1) << (m + i)) & maskM;
        rowCombo[i] = 1u << i;
    }
    uint32_t u = 0;
    for (int bit = 0; bit < m; ++bit) {
        int pivot = -1;
        for (int i = bit; i < m; ++i)
            if (rowImage[i] & (1u << bit)) { pivot = i; break; }
        if (pivot < 0) continue;   // cannot happen for a (0,2)-sequence
        uint32_t ti = rowImage[pivot], tc = rowCombo[pivot];
        rowImage[pivot] = rowImage[bit]; rowCombo[pivot] = rowCombo[bit];
        rowImage[bit] = ti; rowCombo[bit] = tc;
        for (int i = 0; i < m; ++i)
            if (i != bit && (rowImage[i] & (1u << bit))) { rowImage[i] ^= ti; rowCombo[i] ^= tc; }
    }
    // Now rowImage[bit] == 1 << bit: the combination rowCombo[bit] produces that image bit.
    for (int bit = 0; bit < m; ++bit)
        if (target & (1u << bit)) u ^= rowCombo[bit];
    return known | (uint64_t(u) << m);
}

}  // namespace lu
