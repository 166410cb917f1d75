// Lucerna: Perlin noise as pbrt-v4 defines it (util/noise.cpp): gradient noise over the integer
// lattice with Ken Perlin's permutation (Improved Noise, SIGGRAPH 2002), the quintic fade
// 6t^5 - 15t^4 + 10t^3, and pbrt-v4's gradient selection; FBm and Turbulence sum octaves of it.
#pragma once

#include "lucerna/util/vecmath.h"

namespace lu {

// Ken Perlin's permutation of 0..255, indexed modulo 256.
LU_INLINE int NoisePermutation(int i) {
    static constexpr uint8_t perm[256] = {
    151, 160, 137,  91,  90,  15, 131,  13, 201,  95,  96,  53, 194, 233,   7, 225,
    140,  36, 103,  30,  69, 142,   8,  99,  37, 240,  21,  10,  23, 190,   6, 148,
    247, 120, 234,  75,   0,  26, 197,  62,  94, 252, 219, 203, 117,  35,  11,  32,
     57, 177,  33,  88, 237, 149,  56,  87, 174,  20, 125, 136, 171, 168,  68, 175,
     74, 165,  71, 134, 139,  48,  27, 166,  77, 146, 158, 231,  83, 111, 229, 122,
     60, 211, 133, 230, 220, 105,  92,  41,  55,  46, 245,  40, 244, 102, 143,  54,
     65,  25,  63, 161,   1, 216,  80,  73, 209,  76, 132, 187, 208,  89,  18, 169,
    200, 196, 135, 130, 116, 188, 159,  86, 164, 100, 109, 198, 173, 186,   3,  64,
     52, 217, 226, 250, 124, 123,   5, 202,  38, 147, 118, 126, 255,  82,  85, 212,
    207, 206,  59, 227,  47,  16,  58,  17, 182, 189,  28,  42, 223, 183, 170, 213,
    119, 248, 152,   2,  44, 154, 163,  70, 221, 153, 101, 155, 167,  43, 172,   9,
    129,  22,  39, 253,  19,  98, 108, 110,  79, 113, 224, 232, 178, 185, 112, 104,
    218, 246,  97, 228, 251,  34, 242, 193, 238, 210, 144,  12, 191, 179, 162, 241,
     81,  51, 145, 235, 249,  14, 239, 107,  49, 192, 214,  31, 181, 199, 106, 157,
    184,  84, 204, 176, 115, 121,  50,  45, 127,   4, 150, 254, 138, 236, 205,  93,
    222, 114,  67,  29,  24,  72, 243, 141, 128, 195,  78,  66, 215,  61, 156, 180};
    return perm[i & 255];
}

// The gradient of lattice point (x, y, z) (in [0, 256]^3) dotted with the offset (dx, dy, dz):
// two of the offset's components, each with a sign, picked by the low 4 bits of the hash.
LU_INLINE Float NoiseGradient(int x, int y, int z, Float dx, Float dy, Float dz) {
    int h = NoisePermutation(NoisePermutation(NoisePermutation(x) + y) + z) & 15;
    Float u = (h < 8 || h == 12 || h == 13) ? dx : dy;
    Float v = (h < 4 || h == 12 || h == 13) ? dy : dz;
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// Perlin's quintic fade curve: 0 at 0, 1 at 1, first and second derivatives 0 at both ends.
LU_INLINE Float NoiseFade(Float t) { return t * t * t * (t * (t * 6 - 15) + 10); }

// Noise at (x, y, z): 0 at every lattice point, roughly in [-1, 1], period 256 on each axis.
LU_INLINE Float Noise(Float x, Float y, Float z) {
    // Coordinates beyond 2^30 would overflow the int cell index: fold them (as pbrt-v4).
    x = std::fmod(x, Float(1 << 30));
    y = std::fmod(y, Float(1 << 30));
    z = std::fmod(z, Float(1 << 30));
    Float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    Float dx = x - fx, dy = y - fy, dz = z - fz;
    int ix = int(fx) & 255, iy = int(fy) & 255, iz = int(fz) & 255;
    Float g000 = NoiseGradient(ix, iy, iz, dx, dy, dz);
    Float g100 = NoiseGradient(ix + 1, iy, iz, dx - 1, dy, dz);
    Float g010 = NoiseGradient(ix, iy + 1, iz, dx, dy - 1, dz);
    Float g110 = NoiseGradient(ix + 1, iy + 1, iz, dx - 1, dy - 1, dz);
    Float g001 = NoiseGradient(ix, iy, iz + 1, dx, dy, dz - 1);
    Float g101 = NoiseGradient(ix + 1, iy, iz + 1, dx - 1, dy, dz - 1);
    Float g011 = NoiseGradient(ix, iy + 1, iz + 1, dx, dy - 1, dz - 1);
    Float g111 = NoiseGradient(ix + 1, iy + 1, iz + 1, dx - 1, dy - 1, dz - 1);
    Float wx = NoiseFade(dx), wy = NoiseFade(dy), wz = NoiseFade(dz);
    Float y0 = Lerp(wy, Lerp(wx, g000, g100), Lerp(wx, g010, g110));
    Float y1 = Lerp(wy, Lerp(wx, g001, g101), Lerp(wx, g011, g111));
    return Lerp(wz, y0, y1);
}
LU_INLINE Float Noise(const Vec3f &p) { return Noise(p.x, p.y, p.z); }

// pbrt-v4's SmoothStep (0 below a, 1 above b, Hermite in between).
LU_INLINE Float NoiseSmoothStep(Float x, Float a, Float b) {
    if (a == b) return x < a ? 0 : 1;
    Float t = Clamp((x - a) / (b - a), Float(0), Float(1));
    return t * t * (3 - 2 * t);
}

// The number of octaves pbrt-v4 sums for a footprint whose larger squared differential is
// len2: clamp(-1 - log2(len2) / 2, 0, maxOctaves). A zero footprint (Lucerna point-samples
// textures: no ray differentials) gives maxOctaves.
LU_INLINE Float NoiseOctaves(Float len2, int maxOctaves) {
    if (!(len2 > 0)) return Float(maxOctaves);
    return Clamp(-1 - std::log2(len2) / 2, Float(0), Float(maxOctaves));
}

// Fractional Brownian motion: sum over octaves i of omega^i Noise(1.99^i p); the last,
// fractional octave fades in with SmoothStep (pbrt-v4's FBm). len2: squared footprint.
LU_INLINE Float FBm(const Vec3f &p, Float omega, int maxOctaves, Float len2 = 0) {
    Float n = NoiseOctaves(len2, maxOctaves);
    int nInt = int(n);
    Float sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < nInt; ++i) {
        sum += o * Noise(p * lambda);
        lambda *= 1.99f;
        o *= omega;
    }
    Float nPartial = n - nInt;
    if (nPartial > 0) sum += o * NoiseSmoothStep(nPartial, .3f, .7f) * Noise(p * lambda);
    return sum;
}

// Turbulence: FBm of |Noise|; octaves cut off by the footprint count as their average 0.2
// (pbrt-v4's Turbulence, including its 0.2 omega^n term after the last full octave).
LU_INLINE Float Turbulence(const Vec3f &p, Float omega, int maxOctaves, Float len2 = 0) {
    Float n = NoiseOctaves(len2, maxOctaves);
    int nInt = int(n);
    Float sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < nInt; ++i) {
        sum += o * std::abs(Noise(p * lambda));
        lambda *= 1.99f;
        o *= omega;
    }
    Float nPartial = n - nInt;
    Float wPartial = NoiseSmoothStep(nPartial, .3f, .7f);
    sum += o * ((1 - wPartial) * 0.2f + (wPartial > 0 ? wPartial * std::abs(Noise(p * lambda)) : 0));
    for (int i = nInt; i < maxOctaves; ++i) {
        sum += o * 0.2f;
        o *= omega;
    }
    return sum;
}

}  // namespace lu
