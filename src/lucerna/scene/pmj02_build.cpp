// Lucerna (host): the pmj02 construction (Christensen, Kensler, Kilpatrick 2018, section 5).
// From N = 4^k points to 2N: point N + i goes into the sub-quadrant diagonally opposite point i
// within point i's cell (the 2^-k grid); from 2N to 4N: the two new points of each cell take its
// two empty sub-quadrants (in random order). Inside its sub-quadrant a new point takes a pair of
// (x, y) strata of width 2^-n (2^n = the new count) such that every elementary interval of the
// 2^n-point net it falls in is still empty, tried in random order, then is jittered within the
// pair's cell.
#include "lucerna/scene/pmj02_build.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lucerna/sampling/rng.h"

namespace lu {

namespace {

// Occupancy of the elementary intervals of a 2^n-point net: level a has 2^a columns (x) by
// 2^(n - a) rows (y), interval (ix, iy) at bit ix * 2^(n - a) + iy.
struct NetOccupancy {
    int n = 0;
    std::vector<std::vector<bool>> levels;

    void Reset(int log2n) {
        n = log2n;
        levels.assign(n + 1, std::vector<bool>(size_t(1) << n, false));
    }
    // Strata (X, Y) at resolution 2^n: interval (X >> (n - a), Y >> a) at level a.
    bool Free(uint32_t X, uint32_t Y) const {
        for (int a = 0; a <= n; ++a)
            if (levels[a][(size_t(X >> (n - a)) << (n - a)) + (Y >> a)]) return false;
        return true;
    }
    void Mark(uint32_t X, uint32_t Y) {
        for (int a = 0; a <= n; ++a) levels[a][(size_t(X >> (n - a)) << (n - a)) + (Y >> a)] = true;
    }
};

uint32_t Stratum(float v, int n) { return std::min(uint32_t(double(v) * double(1u << n)), (1u << n) - 1); }

// A value in stratum s of width 2^-n, jittered by u in [0, 1), strictly inside the stratum in float.
float InStratum(uint32_t s, int n, double u) {
    double w = 1.0 / double(1u << n);
    float v = float((s + u) * w);
    float hi = float((s + 1) * w);
    if (v >= hi) v = std::nextafter(hi, 0.0f);
    return v;
}

// Places point p in the sub-quadrant [x0, x0 + size) x [y0, y0 + size) (in units of 2^-n
// strata) of a 2^n-point net; false at a dead end.
bool PlacePoint(NetOccupancy &occ, RNG &rng, uint32_t x0, uint32_t y0, uint32_t size, Vec2f *p) {
    int n = occ.n;
    std::vector<uint32_t> xs, ys;
    for (uint32_t X = x0; X < x0 + size; ++X)
        if (!occ.levels[n][size_t(X)]) xs.push_back(X);   // level n: columns of width 2^-n
    for (uint32_t Y = y0; Y < y0 + size; ++Y)
        if (!occ.levels[0][size_t(Y)]) ys.push_back(Y);   // level 0: rows of height 2^-n
    for (size_t i = xs.size(); i > 1; --i) std::swap(xs[i - 1], xs[rng.Uniform<uint32_t>() % i]);
    for (size_t i = ys.size(); i > 1; --i) std::swap(ys[i - 1], ys[rng.Uniform<uint32_t>() % i]);
    for (uint32_t X : xs)
        for (uint32_t Y : ys)
            if (occ.Free(X, Y)) {
                occ.Mark(X, Y);
                *p = Vec2f(InStratum(X, n, rng.Uniform<double>()), InStratum(Y, n, rng.Uniform<double>()));
                return true;
            }
    return false;
}

bool TryGenerate(uint32_t count, RNG &rng, std::vector<Vec2f> *out) {
    std::vector<Vec2f> &pts = *out;
    pts.assign(1, Vec2f(float(rng.Uniform<double>()), float(rng.Uniform<double>())));
    NetOccupancy occ;
    for (uint32_t N = 1; N < count; N *= 2) {
        int n = 0;   // log2 of the new count 2N
        while ((1u << n) < 2 * N) ++n;
        occ.Reset(n);
        for (const Vec2f &q : pts) occ.Mark(Stratum(q.x, n), Stratum(q.y, n));
        pts.resize(2 * N);
        if (n % 2 == 1) {
            // N = 4^k: cells of 2^-k hold one point each; the new one goes diagonally opposite.
            int k = (n - 1) / 2;
            uint32_t sub = 1u << (n - k - 1);   // sub-quadrant side in 2^-n strata
            for (uint32_t i = 0; i < N; ++i) {
                uint32_t cx = Stratum(pts[i].x, k), cy = Stratum(pts[i].y, k);
                uint32_t qx = Stratum(pts[i].x, k + 1) & 1, qy = Stratum(pts[i].y, k + 1) & 1;
                uint32_t x0 = (2 * cx + (1 - qx)) * sub, y0 = (2 * cy + (1 - qy)) * sub;
                if (!PlacePoint(occ, rng, x0, y0, sub, &pts[N + i])) return false;
            }
        } else {
            // N = 2 4^k: cells of 2^-k hold two points in opposite sub-quadrants; the two empty
            // ones take points N + i and N + (i ^ N / 2), in random order.
            int k = (n - 2) / 2;
            uint32_t sub = 1u << (n - k - 1);
            for (uint32_t i = 0; i < N / 2; ++i) {
                uint32_t cx = Stratum(pts[i].x, k), cy = Stratum(pts[i].y, k);
                uint32_t qx = Stratum(pts[i].x, k + 1) & 1, qy = Stratum(pts[i].y, k + 1) & 1;
                // The empty sub-quadrants: (1 - qx, qy) and (qx, 1 - qy).
                bool swap = rng.Uniform<uint32_t>() & 1;
                uint32_t ax = 1 - qx, ay = qy, bx = qx, by = 1 - qy;
                if (swap) { std::swap(ax, bx); std::swap(ay, by); }
                if (!PlacePoint(occ, rng, (2 * cx + ax) * sub, (2 * cy + ay) * sub, sub, &pts[N + i])) return false;
                if (!PlacePoint(occ, rng, (2 * cx + bx) * sub, (2 * cy + by) * sub, sub, &pts[N + i + N / 2]))
                    return false;
            }
        }
    }
    pts.resize(count);
    return true;
}

}  // namespace

std::vector<Vec2f> GeneratePMJ02(uint32_t count, uint64_t seed, int *restarts) {
    if (count == 0 || (count & (count - 1)) != 0 || count > (1u << 20))
        throw std::invalid_argument("GeneratePMJ02: count must be a power of two in [1, 2^20]");
    RNG rng(seed, 0x504d4a3032ull);   // "PMJ02"
    std::vector<Vec2f> pts;
    int tries = 0;
    while (!TryGenerate(count, rng, &pts)) ++tries;
    if (restarts) *restarts = tries;
    return pts;
}

std::vector<Vec2f> BuildPMJ02BNTables(int spp, uint64_t seed, int *tileSize) {
    if (spp < 1 || spp > kPMJ02BNSamples)
        throw std::invalid_argument("pmj02bn: samples per pixel must be in [1, " + std::to_string(kPMJ02BNSamples) + "]");
    // pbrt-v4: the tile holds the whole first set, RoundUpPow4(spp) points per pixel.
    int log4Spp = 0;
    while ((1 << (2 * log4Spp)) < spp) ++log4Spp;
    int log4N = 0;
    while ((1 << (2 * log4N)) < kPMJ02BNSamples) ++log4N;
    int tile = 1 << (log4N - log4Spp);
    *tileSize = tile;
    std::vector<Vec2f> sets[kPMJ02BNSets];
    uint32_t perSet = uint32_t(RoundUpPow2(uint64_t(spp)));
    sets[0] = GeneratePMJ02(uint32_t(kPMJ02BNSamples), seed);
    for (int k = 1; k < kPMJ02BNSets; ++k) sets[k] = GeneratePMJ02(perSet, seed + uint64_t(k));
    std::vector<Vec2f> out(size_t(tile) * tile * spp + size_t(kPMJ02BNSets) * spp);
    std::vector<int> stored(size_t(tile) * tile, 0);
    for (const Vec2f &p : sets[0]) {
        double x = double(p.x) * tile, y = double(p.y) * tile;
        int ix = std::min(int(x), tile - 1), iy = std::min(int(y), tile - 1);
        size_t pixel = size_t(ix) + size_t(iy) * tile;
        if (stored[pixel] == spp) continue;   // spp not a power of 4: the first spp of the pixel's points
        out[pixel * spp + size_t(stored[pixel]++)] =
            Vec2f(std::min(float(x - ix), OneMinusEpsilon), std::min(float(y - iy), OneMinusEpsilon));
    }
    for (int s : stored)
        if (s != spp) throw std::logic_error("pmj02bn: the first set is not stratified over the pixel tile");
    size_t base = size_t(tile) * tile * spp;
    for (int k = 0; k < kPMJ02BNSets; ++k)
        for (int i = 0; i < spp; ++i) out[base + size_t(k) * spp + size_t(i)] = sets[k][size_t(i)];
    return out;
}

bool IsZeroTwoNet(const std::vector<Vec2f> &points, int log2n) {
    size_t n = size_t(1) << log2n;
    if (points.size() < n) return false;
    for (int a = 0; a <= log2n; ++a) {
        std::vector<int> count(n, 0);
        for (size_t i = 0; i < n; ++i) {
            const Vec2f &p = points[i];
            if (!(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1)) return false;
            size_t ix = size_t(double(p.x) * double(size_t(1) << a));
            size_t iy = size_t(double(p.y) * double(size_t(1) << (log2n - a)));
            if (++count[(ix << (log2n - a)) + iy] > 1) return false;
        }
    }
    return true;
}

}  // namespace lu
