// Lucerna image error metrics (host only): MSE / RMSE / relMSE / MAPE over an optional crop,
// per-pixel error images, block means, the bias^2 / variance split over independent runs, and
// block z-tests of a noisy render against a reference (as Mitsuba's Z-test with Sidak correction).
//
// Conventions. Two images are compared over their colour channels: both must have the same size;
// channel counts must be equal, or both >= 3 (RGB vs RGBA); alpha is never compared (1 or 2
// channels: channel 0; 3 or 4 channels: R,G,B). Sums run over the N = pixels x channels values
// v (image) and r (reference) in the crop, in double precision:
//   MSE    = (1/N) sum (v - r)^2                  RMSE = sqrt(MSE)
//   relMSE = (1/N) sum (v - r)^2 / (r^2 + 0.01)   MAPE = (1/N) sum |v - r| / (|r| + 0.01)
// Non-finite values are not skipped: they make the metrics NaN or Inf (ErrorStats counts them).
//
// Block z-test statistics. Blocks of B x B pixels tile the crop from its top-left corner; edge
// blocks with fewer than B*B/2 pixels are dropped. For each kept block and channel,
//   d = mean over the block of the render  -  mean over the block of the reference,
//   z = d / sqrt(SE^2 + (relTolerance |ref mean|)^2 + absTolerance^2),
// with the standard error SE of d estimated in one of three ways:
//  - one render (ZTestBlocks(render, ref)): from the spread of the per-pixel differences v - r
//    inside the block, SE^2 = s^2 / n (s^2 the n-1 sample variance over the block's n pixels),
//    t-distributed with n-1 degrees of freedom. Pixels must be independent estimates (pbrt-style
//    filter importance sampling: each sample lands in one pixel). This includes the reference's
//    own pixel noise, and any image structure where v and r differ makes SE larger
//    (conservative);
//  - K >= 2 independent runs (ZTestBlocks(runs, ref)): d uses the mean over runs, SE^2 is the
//    sample variance of the K per-run block means over K, K-1 degrees of freedom. Exact for any
//    pixel correlation; the reference is taken as noise-free (use the tolerances otherwise);
//  - a per-pixel variance of the pixel estimate (ZTestBlocksWithVariance): SE^2 = sum var / n^2,
//    normal (infinite degrees of freedom); the reference is taken as noise-free.
// A t value with nu degrees of freedom is turned into the normal z with the same two-sided
// p-value, so every test reads on one scale. Under the null hypothesis (the render's expectation
// equals the reference) each |z| exceeds T with probability p1 = 2 (1 - Phi(T)); over M tests
// (kept blocks x channels) the Sidak bound T solves 1 - (1 - p1)^M = alpha, i.e.
// p1 = 1 - (1 - alpha)^(1/M): the chance that ANY |z| > T is alpha (for independent tests; it is
// conservative for the positively correlated R,G,B of one block). So a test asserts
// `result.Passed()`, i.e. max |z| <= T, and prints `result.Summary()` when it fails.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lucerna/image/image.h"

namespace lu {

constexpr double RelMSEEpsilon = 0.01;  // relMSE = (v-r)^2 / (r^2 + RelMSEEpsilon)
constexpr double MAPEEpsilon = 0.01;    // MAPE = |v-r| / (|r| + MAPEEpsilon)

// ---- Crops and channels ----

// Half-open pixel rectangle [x0, x1) x [y0, y1); (0,0) is the top-left pixel.
struct Crop {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int Width() const { return x1 - x0; }
    int Height() const { return y1 - y0; }
    bool operator==(const Crop &) const = default;
};
// Parses "X0,Y0,X1,Y1" (integers); throws ImageError on bad syntax or an empty rectangle.
Crop ParseCrop(const std::string &text);
// The crop to use for an image: the whole image when `crop` is empty. Throws ImageError when the
// crop does not lie inside the width x height image.
Crop ResolveCrop(const std::optional<Crop> &crop, int width, int height);
// Number of channels compared between two images (see the conventions above); throws ImageError
// naming both sizes / channel counts when they cannot be compared.
int ComparedChannels(const Image &image, const Image &reference);

// ---- Whole-image metrics ----

enum class Metric { MSE, RMSE, RelMSE, MAPE };
const char *MetricName(Metric metric);                 // "mse", "rmse", "relmse", "mape"
std::optional<Metric> ParseMetric(std::string_view name);  // case-insensitive; nullopt if unknown

struct ErrorStats {
    double mse = 0, rmse = 0, relMSE = 0, mape = 0;
    size_t count = 0;      // values compared (pixels x channels)
    size_t nonFinite = 0;  // of those, values where the image or the reference is NaN or Inf
    double Get(Metric metric) const;
};

ErrorStats ComputeErrors(const Image &image, const Image &reference, const std::optional<Crop> &crop = {});
double ComputeMetric(Metric metric, const Image &image, const Image &reference,
                     const std::optional<Crop> &crop = {});

// One-channel image of the crop's size: per pixel, the metric over that pixel's compared
// channels (MSE: mean (v-r)^2; RMSE: its square root; relMSE, MAPE: the per-value terms above,
// averaged over channels). Its mean over pixels is the image's metric (except for RMSE).
Image ErrorImage(const Image &image, const Image &reference, Metric metric = Metric::RelMSE,
                 const std::optional<Crop> &crop = {});

// ---- Block means ----

struct BlockStats {
    int blockSize = 0, blocksX = 0, blocksY = 0, channels = 0;
    Crop crop;                     // the region the blocks tile, from its top-left corner
    std::vector<double> mean;      // [(by * blocksX + bx) * channels + c]: mean over the block
    std::vector<double> variance;  // same layout: n-1 sample variance of the block's pixels
    std::vector<int> count;        // [by * blocksX + bx]: pixels in the block (edge blocks fewer)
    double Mean(int bx, int by, int c) const { return mean[(size_t(by) * blocksX + bx) * channels + c]; }
    int Count(int bx, int by) const { return count[size_t(by) * blocksX + bx]; }
};
// Block means and spreads of every channel of `image` (blocks include partial edge blocks).
BlockStats ComputeBlockStats(const Image &image, int blockSize, const std::optional<Crop> &crop = {});
// The metrics above computed between block means instead of pixels (noise-robust comparison
// with a grainy reference); blocks with fewer than B*B/2 pixels are dropped.
ErrorStats CompareBlockMeans(const Image &image, const Image &reference, int blockSize,
                             const std::optional<Crop> &crop = {});

// ---- Squared bias / variance over independent runs ----

// For K >= 2 runs v_k of the same render (independent seeds) and a reference r, per value:
//   bias2    = mean over values of (vbar - r)^2 - s^2 / K     (an unbiased estimate of bias^2;
//              it can come out slightly negative when the bias is below the noise)
//   variance = mean over values of s^2   (s^2: n-1 sample variance over the K runs; the variance
//              of ONE run's pixel estimate)
//   mse      = mean over runs of each run's MSE   ( = bias2 + variance exactly )
// and the relMSE analogues weighting each value by 1 / (r^2 + 0.01).
struct BiasVariance {
    int runs = 0;
    double mse = 0, bias2 = 0, variance = 0;
    double relMSE = 0, relBias2 = 0, relVariance = 0;
};
BiasVariance ComputeBiasVariance(const std::vector<Image> &runs, const Image &reference,
                                 const std::optional<Crop> &crop = {});

// ---- Block z-tests (statistics in the header comment) ----

struct ZTestOptions {
    int blockSize = 8;
    double alpha = 1e-4;        // family-wise false-failure probability over all tests
    double relTolerance = 0;    // systematic tolerance, relative to the reference block mean
    double absTolerance = 0;    // systematic tolerance, absolute
    std::optional<Crop> crop;   // default: the whole image
};

struct ZTestResult {
    int blockSize = 0, blocksX = 0, blocksY = 0, channels = 0;
    Crop crop;
    std::vector<double> z;       // [(by * blocksX + bx) * channels + c]; NaN for dropped blocks
    std::vector<double> diff;    // render block mean - reference block mean (same layout)
    std::vector<double> refMean; // reference block mean
    std::vector<double> stdErr;  // estimated standard error of diff (without the tolerances)
    std::vector<double> dof;     // degrees of freedom of the estimate (infinity: normal)
    size_t tests = 0;            // kept blocks x channels
    size_t failed = 0;           // tests with |z| > threshold
    double maxAbsZ = 0;          // largest |z| (0 when no test)
    int worstBx = -1, worstBy = -1, worstC = -1;
    double alpha = 0, threshold = 0;  // Sidak bound on |z| for family-wise level alpha
    bool Passed() const { return failed == 0; }
    // One line: tests, max |z| at which block (pixel rectangle) and channel, the bound, and the
    // block's render / reference means and standard error.
    std::string Summary() const;
    // blocksX x blocksY image of z with `channels` channels (NaN for dropped blocks).
    Image ZImage() const;
};

// One render; SE from the spread of v - r inside each block.
ZTestResult ZTestBlocks(const Image &render, const Image &reference, const ZTestOptions &options = {});
// K >= 2 independent renders; SE from the spread of the per-run block means.
ZTestResult ZTestBlocks(const std::vector<Image> &runs, const Image &reference,
                        const ZTestOptions &options = {});
// One render and the variance of each pixel's estimate (same channels as render, or 1 channel
// applied to all); SE^2 = sum var / n^2.
ZTestResult ZTestBlocksWithVariance(const Image &render, const Image &varianceOfMean, const Image &reference,
                                    const ZTestOptions &options = {});

// ---- Distribution helpers used above (exposed for tests) ----

// Standard normal upper tail Q(z) = P(Z > z), and its inverse: the z with Q(z) = q, q in (0, 1).
double NormalUpperTail(double z);
double NormalUpperTailInverse(double q);
// Two-sided p-value P(|T| >= |t|) of Student's t with `dof` degrees of freedom (dof may be
// infinite: normal).
double StudentTTwoSidedP(double t, double dof);
// Normal z with the same two-sided p-value as t with `dof` degrees of freedom (sign of t kept;
// |z| capped at 38 where the p-value underflows).
double TToZ(double t, double dof);
// Sidak bound T on |z| for M two-sided tests at family-wise level alpha.
double SidakThreshold(double alpha, size_t tests);

}  // namespace lu
