// Lucerna image error metrics, block statistics and block z-tests (definitions in metrics.h).
// The incomplete beta continued fraction is written from its textbook definition (Lentz's method).
#include "lucerna/image/metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

#include "lucerna/util/common.h"

namespace lu {

namespace {

constexpr double Inf = std::numeric_limits<double>::infinity();
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
constexpr double MaxZ = 38;

void CheckBlockSize(int blockSize) {
    if (blockSize < 1) throw ImageError("block size must be at least 1 (got " + std::to_string(blockSize) + ")");
}

std::string SizeText(const Image &im) {
    return fmt::format("{}x{} with {} channel{}", im.width, im.height, im.channels, im.channels == 1 ? "" : "s");
}

// Regularized incomplete beta I_x(a, b) by the continued fraction (converges for x < (a+1)/(a+b+2)).
double BetaContinuedFraction(double a, double b, double x) {
    const double tiny = 1e-300;
    double c = 1, d = 1 - (a + b) * x / (a + 1);
    if (std::abs(d) < tiny) d = tiny;
    d = 1 / d;
    double h = d;
    for (int m = 1; m < 10000; ++m) {
        double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((a + m2 - 1) * (a + m2));
        d = 1 + aa * d; if (std::abs(d) < tiny) d = tiny;
        c = 1 + aa / c; if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1));
        d = 1 + aa * d; if (std::abs(d) < tiny) d = tiny;
        c = 1 + aa / c; if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (std::abs(del - 1) < 1e-15) break;
    }
    return h;
}

double RegularizedIncompleteBeta(double a, double b, double x) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    double logFront = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    if (x < (a + 1) / (a + b + 2)) return std::exp(logFront) * BetaContinuedFraction(a, b, x) / a;
    return 1 - std::exp(logFront) * BetaContinuedFraction(b, a, 1 - x) / b;
}

// Accumulates the four metrics' sums for one pair of values.
struct ErrorSums {
    double se = 0, rel = 0, ape = 0;
    size_t count = 0, nonFinite = 0;
    void Add(double v, double r) {
        double e = v - r;
        se += e * e;
        rel += e * e / (r * r + RelMSEEpsilon);
        ape += std::abs(e) / (std::abs(r) + MAPEEpsilon);
        ++count;
        nonFinite += !std::isfinite(v) || !std::isfinite(r);
    }
    ErrorStats Stats() const {
        ErrorStats s;
        s.count = count;
        s.nonFinite = nonFinite;
        if (count == 0) return s;
        s.mse = se / count;
        s.rmse = std::sqrt(s.mse);
        s.relMSE = rel / count;
        s.mape = ape / count;
        return s;
    }
};

bool KeepBlock(int count, int blockSize) { return 2 * count >= blockSize * blockSize; }

// Shared frame of the three z-tests: block layout and the result's arrays.
ZTestResult MakeZResult(const Crop &c, int channels, const ZTestOptions &o) {
    CheckBlockSize(o.blockSize);
    ZTestResult r;
    r.blockSize = o.blockSize;
    r.crop = c;
    r.channels = channels;
    r.blocksX = (c.Width() + o.blockSize - 1) / o.blockSize;
    r.blocksY = (c.Height() + o.blockSize - 1) / o.blockSize;
    size_t n = size_t(r.blocksX) * r.blocksY * channels;
    r.z.assign(n, NaN);
    r.diff.assign(n, NaN);
    r.refMean.assign(n, NaN);
    r.stdErr.assign(n, NaN);
    r.dof.assign(n, NaN);
    r.alpha = o.alpha;
    return r;
}

// Pixel rectangle of block (bx, by).
Crop BlockRect(const ZTestResult &r, int bx, int by) {
    Crop b;
    b.x0 = r.crop.x0 + bx * r.blockSize;
    b.y0 = r.crop.y0 + by * r.blockSize;
    b.x1 = std::min(b.x0 + r.blockSize, r.crop.x1);
    b.y1 = std::min(b.y0 + r.blockSize, r.crop.y1);
    return b;
}

// Fills z from diff / stdErr / dof and the tolerances, then the summary numbers.
void FinishZResult(ZTestResult &r, const ZTestOptions &o) {
    r.tests = 0;
    for (size_t i = 0; i < r.z.size(); ++i) {
        if (std::isnan(r.dof[i])) continue;  // dropped block
        ++r.tests;
        double tol2 = Sqr(o.relTolerance * std::abs(r.refMean[i])) + Sqr(o.absTolerance);
        double denom = std::sqrt(Sqr(r.stdErr[i]) + tol2);
        double t;
        if (std::isnan(r.diff[i])) t = NaN;
        else if (r.diff[i] == 0) t = 0;
        else if (denom == 0) t = r.diff[i] > 0 ? Inf : -Inf;
        else t = r.diff[i] / denom;
        r.z[i] = std::isnan(t) ? t : TToZ(t, r.dof[i]);
    }
    r.threshold = SidakThreshold(o.alpha, std::max<size_t>(r.tests, 1));
    r.failed = 0;
    r.maxAbsZ = 0;
    for (int by = 0; by < r.blocksY; ++by)
        for (int bx = 0; bx < r.blocksX; ++bx)
            for (int c = 0; c < r.channels; ++c) {
                size_t i = (size_t(by) * r.blocksX + bx) * r.channels + c;
                if (std::isnan(r.dof[i])) continue;
                double a = std::isnan(r.z[i]) ? Inf : std::abs(r.z[i]);  // NaN render values fail
                if (a > r.threshold) ++r.failed;
                if (a > r.maxAbsZ || r.worstBx < 0) {
                    r.maxAbsZ = a;
                    r.worstBx = bx;
                    r.worstBy = by;
                    r.worstC = c;
                }
            }
}

}  // namespace

// ---- Crops and channels ----

Crop ParseCrop(const std::string &text) {
    Crop c;
    char comma[3];
    std::istringstream in(text);
    if (!(in >> c.x0 >> comma[0] >> c.y0 >> comma[1] >> c.x1 >> comma[2] >> c.y1) || comma[0] != ',' ||
        comma[1] != ',' || comma[2] != ',' || !(in >> std::ws).eof())
        throw ImageError("bad crop '" + text + "': expected X0,Y0,X1,Y1 (integers, half-open)");
    if (c.x1 <= c.x0 || c.y1 <= c.y0)
        throw ImageError("bad crop '" + text + "': empty rectangle (need X0 < X1 and Y0 < Y1)");
    return c;
}

Crop ResolveCrop(const std::optional<Crop> &crop, int width, int height) {
    if (!crop) return Crop{0, 0, width, height};
    const Crop &c = *crop;
    if (c.x0 < 0 || c.y0 < 0 || c.x1 > width || c.y1 > height || c.x1 <= c.x0 || c.y1 <= c.y0)
        throw ImageError(fmt::format("crop {},{},{},{} does not lie inside the {}x{} image", c.x0, c.y0, c.x1,
                                     c.y1, width, height));
    return c;
}

int ComparedChannels(const Image &image, const Image &reference) {
    if (image.width != reference.width || image.height != reference.height)
        throw ImageError("image sizes differ: " + SizeText(image) + " vs reference " + SizeText(reference));
    auto colour = [](int ch) { return ch == 2 ? 1 : std::min(ch, 3); };
    int a = image.channels, b = reference.channels;
    if (a < 1 || b < 1 || (colour(a) != colour(b)))
        throw ImageError("channel counts cannot be compared: " + SizeText(image) + " vs reference " +
                         SizeText(reference));
    return colour(a);
}

// ---- Whole-image metrics ----

const char *MetricName(Metric metric) {
    switch (metric) {
    case Metric::MSE: return "mse";
    case Metric::RMSE: return "rmse";
    case Metric::RelMSE: return "relmse";
    case Metric::MAPE: return "mape";
    }
    return "?";
}

std::optional<Metric> ParseMetric(std::string_view name) {
    std::string n(name);
    for (char &c : n) c = char(std::tolower((unsigned char)c));
    for (Metric m : {Metric::MSE, Metric::RMSE, Metric::RelMSE, Metric::MAPE})
        if (n == MetricName(m)) return m;
    return std::nullopt;
}

double ErrorStats::Get(Metric metric) const {
    switch (metric) {
    case Metric::MSE: return mse;
    case Metric::RMSE: return rmse;
    case Metric::RelMSE: return relMSE;
    case Metric::MAPE: return mape;
    }
    return NaN;
}

ErrorStats ComputeErrors(const Image &image, const Image &reference, const std::optional<Crop> &crop) {
    int nc = ComparedChannels(image, reference);
    Crop c = ResolveCrop(crop, image.width, image.height);
    ErrorSums sums;
    for (int y = c.y0; y < c.y1; ++y)
        for (int x = c.x0; x < c.x1; ++x)
            for (int ch = 0; ch < nc; ++ch) sums.Add(image.At(x, y, ch), reference.At(x, y, ch));
    return sums.Stats();
}

double ComputeMetric(Metric metric, const Image &image, const Image &reference, const std::optional<Crop> &crop) {
    return ComputeErrors(image, reference, crop).Get(metric);
}

Image ErrorImage(const Image &image, const Image &reference, Metric metric, const std::optional<Crop> &crop) {
    int nc = ComparedChannels(image, reference);
    Crop c = ResolveCrop(crop, image.width, image.height);
    Image out = MakeImage(c.Width(), c.Height(), 1);
    for (int y = c.y0; y < c.y1; ++y)
        for (int x = c.x0; x < c.x1; ++x) {
            ErrorSums sums;
            for (int ch = 0; ch < nc; ++ch) sums.Add(image.At(x, y, ch), reference.At(x, y, ch));
            out.At(x - c.x0, y - c.y0, 0) = float(sums.Stats().Get(metric));
        }
    return out;
}

// ---- Block means ----

BlockStats ComputeBlockStats(const Image &image, int blockSize, const std::optional<Crop> &crop) {
    CheckBlockSize(blockSize);
    Crop c = ResolveCrop(crop, image.width, image.height);
    BlockStats b;
    b.blockSize = blockSize;
    b.crop = c;
    b.channels = image.channels;
    b.blocksX = (c.Width() + blockSize - 1) / blockSize;
    b.blocksY = (c.Height() + blockSize - 1) / blockSize;
    b.mean.assign(size_t(b.blocksX) * b.blocksY * b.channels, 0.0);
    b.variance.assign(b.mean.size(), NaN);
    b.count.assign(size_t(b.blocksX) * b.blocksY, 0);
    for (int by = 0; by < b.blocksY; ++by)
        for (int bx = 0; bx < b.blocksX; ++bx) {
            int x0 = c.x0 + bx * blockSize, y0 = c.y0 + by * blockSize;
            int x1 = std::min(x0 + blockSize, c.x1), y1 = std::min(y0 + blockSize, c.y1);
            int n = (x1 - x0) * (y1 - y0);
            b.count[size_t(by) * b.blocksX + bx] = n;
            for (int ch = 0; ch < b.channels; ++ch) {
                double sum = 0;  // two passes: mean, then the centred sum of squares
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) sum += image.At(x, y, ch);
                double mean = sum / n, ss = 0;
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) ss += Sqr(image.At(x, y, ch) - mean);
                size_t i = (size_t(by) * b.blocksX + bx) * b.channels + ch;
                b.mean[i] = mean;
                if (n > 1) b.variance[i] = ss / (n - 1);
            }
        }
    return b;
}

ErrorStats CompareBlockMeans(const Image &image, const Image &reference, int blockSize,
                             const std::optional<Crop> &crop) {
    int nc = ComparedChannels(image, reference);
    BlockStats a = ComputeBlockStats(image, blockSize, crop), r = ComputeBlockStats(reference, blockSize, crop);
    ErrorSums sums;
    for (int by = 0; by < a.blocksY; ++by)
        for (int bx = 0; bx < a.blocksX; ++bx) {
            if (!KeepBlock(a.Count(bx, by), blockSize)) continue;
            for (int ch = 0; ch < nc; ++ch) sums.Add(a.Mean(bx, by, ch), r.Mean(bx, by, ch));
        }
    return sums.Stats();
}

// ---- Squared bias / variance ----

BiasVariance ComputeBiasVariance(const std::vector<Image> &runs, const Image &reference,
                                 const std::optional<Crop> &crop) {
    int k = int(runs.size());
    if (k < 2) throw ImageError("the bias/variance split needs at least 2 runs (got " + std::to_string(k) + ")");
    int nc = ComparedChannels(runs[0], reference);
    for (const Image &run : runs) ComparedChannels(run, reference);
    Crop c = ResolveCrop(crop, reference.width, reference.height);
    double bias2 = 0, var = 0, relBias2 = 0, relVar = 0;
    size_t n = 0;
    for (int y = c.y0; y < c.y1; ++y)
        for (int x = c.x0; x < c.x1; ++x)
            for (int ch = 0; ch < nc; ++ch) {
                double mean = 0;
                for (const Image &run : runs) mean += run.At(x, y, ch);
                mean /= k;
                double ss = 0;
                for (const Image &run : runs) ss += Sqr(run.At(x, y, ch) - mean);
                double s2 = ss / (k - 1), r = reference.At(x, y, ch);
                double b2 = Sqr(mean - r) - s2 / k, w = 1 / (r * r + RelMSEEpsilon);
                bias2 += b2;
                var += s2;
                relBias2 += w * b2;
                relVar += w * s2;
                ++n;
            }
    BiasVariance bv;
    bv.runs = k;
    bv.bias2 = bias2 / n;
    bv.variance = var / n;
    bv.relBias2 = relBias2 / n;
    bv.relVariance = relVar / n;
    bv.mse = bv.bias2 + bv.variance;
    bv.relMSE = bv.relBias2 + bv.relVariance;
    return bv;
}

// ---- Block z-tests ----

ZTestResult ZTestBlocks(const Image &render, const Image &reference, const ZTestOptions &o) {
    int nc = ComparedChannels(render, reference);
    Crop c = ResolveCrop(o.crop, render.width, render.height);
    ZTestResult r = MakeZResult(c, nc, o);
    for (int by = 0; by < r.blocksY; ++by)
        for (int bx = 0; bx < r.blocksX; ++bx) {
            Crop b = BlockRect(r, bx, by);
            int n = b.Width() * b.Height();
            if (!KeepBlock(n, o.blockSize) || n < 2) continue;
            for (int ch = 0; ch < nc; ++ch) {
                double sumD = 0, sumR = 0;
                for (int y = b.y0; y < b.y1; ++y)
                    for (int x = b.x0; x < b.x1; ++x) {
                        sumD += double(render.At(x, y, ch)) - reference.At(x, y, ch);
                        sumR += reference.At(x, y, ch);
                    }
                double meanD = sumD / n, ss = 0;
                for (int y = b.y0; y < b.y1; ++y)
                    for (int x = b.x0; x < b.x1; ++x)
                        ss += Sqr(double(render.At(x, y, ch)) - reference.At(x, y, ch) - meanD);
                size_t i = (size_t(by) * r.blocksX + bx) * nc + ch;
                r.diff[i] = meanD;
                r.refMean[i] = sumR / n;
                r.stdErr[i] = std::sqrt(ss / (n - 1) / n);
                r.dof[i] = n - 1;
            }
        }
    FinishZResult(r, o);
    return r;
}

ZTestResult ZTestBlocks(const std::vector<Image> &runs, const Image &reference, const ZTestOptions &o) {
    int k = int(runs.size());
    if (k < 2) throw ImageError("a z-test over runs needs at least 2 runs (got " + std::to_string(k) + ")");
    int nc = ComparedChannels(runs[0], reference);
    for (const Image &run : runs) ComparedChannels(run, reference);
    Crop c = ResolveCrop(o.crop, reference.width, reference.height);
    ZTestResult r = MakeZResult(c, nc, o);
    std::vector<double> perRun(k);
    for (int by = 0; by < r.blocksY; ++by)
        for (int bx = 0; bx < r.blocksX; ++bx) {
            Crop b = BlockRect(r, bx, by);
            int n = b.Width() * b.Height();
            if (!KeepBlock(n, o.blockSize)) continue;
            for (int ch = 0; ch < nc; ++ch) {
                double sumR = 0;
                for (int y = b.y0; y < b.y1; ++y)
                    for (int x = b.x0; x < b.x1; ++x) sumR += reference.At(x, y, ch);
                double mean = 0;
                for (int j = 0; j < k; ++j) {
                    double s = 0;
                    for (int y = b.y0; y < b.y1; ++y)
                        for (int x = b.x0; x < b.x1; ++x) s += runs[j].At(x, y, ch);
                    perRun[j] = s / n;
                    mean += perRun[j];
                }
                mean /= k;
                double ss = 0;
                for (double m : perRun) ss += Sqr(m - mean);
                size_t i = (size_t(by) * r.blocksX + bx) * nc + ch;
                r.refMean[i] = sumR / n;
                r.diff[i] = mean - r.refMean[i];
                r.stdErr[i] = std::sqrt(ss / (k - 1) / k);
                r.dof[i] = k - 1;
            }
        }
    FinishZResult(r, o);
    return r;
}

ZTestResult ZTestBlocksWithVariance(const Image &render, const Image &varianceOfMean, const Image &reference,
                                    const ZTestOptions &o) {
    int nc = ComparedChannels(render, reference);
    if (varianceOfMean.width != render.width || varianceOfMean.height != render.height ||
        (varianceOfMean.channels != 1 && varianceOfMean.channels < nc))
        throw ImageError("variance image " + SizeText(varianceOfMean) + " does not match the render " +
                         SizeText(render));
    Crop c = ResolveCrop(o.crop, render.width, render.height);
    ZTestResult r = MakeZResult(c, nc, o);
    for (int by = 0; by < r.blocksY; ++by)
        for (int bx = 0; bx < r.blocksX; ++bx) {
            Crop b = BlockRect(r, bx, by);
            int n = b.Width() * b.Height();
            if (!KeepBlock(n, o.blockSize)) continue;
            for (int ch = 0; ch < nc; ++ch) {
                int vc = varianceOfMean.channels == 1 ? 0 : ch;
                double sumV = 0, sumR = 0, sumVar = 0;
                for (int y = b.y0; y < b.y1; ++y)
                    for (int x = b.x0; x < b.x1; ++x) {
                        sumV += render.At(x, y, ch);
                        sumR += reference.At(x, y, ch);
                        sumVar += varianceOfMean.At(x, y, vc);
                    }
                size_t i = (size_t(by) * r.blocksX + bx) * nc + ch;
                r.refMean[i] = sumR / n;
                r.diff[i] = sumV / n - r.refMean[i];
                r.stdErr[i] = std::sqrt(std::max(sumVar, 0.0)) / n;
                r.dof[i] = Inf;
            }
        }
    FinishZResult(r, o);
    return r;
}

std::string ZTestResult::Summary() const {
    if (tests == 0) return "z-test: no blocks to test";
    size_t i = (size_t(worstBy) * blocksX + worstBx) * channels + worstC;
    int x0 = crop.x0 + worstBx * blockSize, y0 = crop.y0 + worstBy * blockSize;
    int x1 = std::min(x0 + blockSize, crop.x1), y1 = std::min(y0 + blockSize, crop.y1);
    return fmt::format(
        "z-test {}: {} of {} block tests beyond the Sidak bound |z| <= {:.3f} (alpha {:g}, {}x{} blocks); "
        "max |z| = {:.3f} at pixels [{},{})x[{},{}) channel {}: render {:.6g} vs reference {:.6g} "
        "(diff {:.3g}, std. error {:.3g}, dof {:g})",
        Passed() ? "passed" : "FAILED", failed, tests, threshold, alpha, blockSize, blockSize, maxAbsZ, x0, x1,
        y0, y1, worstC, refMean[i] + diff[i], refMean[i], diff[i], stdErr[i], dof[i]);
}

Image ZTestResult::ZImage() const {
    Image im = MakeImage(blocksX, blocksY, channels);
    for (size_t i = 0; i < z.size(); ++i) im.pixels[i] = float(z[i]);
    return im;
}

// ---- Distribution helpers ----

double NormalUpperTail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

double NormalUpperTailInverse(double q) {
    if (!(q > 0)) return Inf;
    if (!(q < 1)) return -Inf;
    // Bisection on the monotone tail (erfc is accurate far into the tail, unlike 1 - CDF).
    double lo = -40, hi = 40;
    for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
        double mid = 0.5 * (lo + hi);
        (NormalUpperTail(mid) > q ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double StudentTTwoSidedP(double t, double dof) {
    if (std::isnan(t) || !(dof > 0)) return NaN;
    if (std::isinf(t)) return 0;
    if (std::isinf(dof) || dof > 1e7) return 2 * NormalUpperTail(std::abs(t));
    return RegularizedIncompleteBeta(dof / 2, 0.5, dof / (dof + t * t));
}

double TToZ(double t, double dof) {
    if (std::isnan(t)) return NaN;
    if (t == 0) return 0;
    if (std::isinf(dof) || dof > 1e7) return std::clamp(t, -MaxZ, MaxZ);
    double p = StudentTTwoSidedP(t, dof);
    double z = p > 0 ? std::min(NormalUpperTailInverse(p / 2), MaxZ) : MaxZ;
    return t < 0 ? -z : z;
}

double SidakThreshold(double alpha, size_t tests) {
    double perTest = -std::expm1(std::log1p(-alpha) / double(std::max<size_t>(tests, 1)));
    return NormalUpperTailInverse(perTest / 2);
}

}  // namespace lu
