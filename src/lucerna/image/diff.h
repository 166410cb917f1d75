// Lucerna `diff` command logic (host only): compares an image with a reference using metrics.h
// and prints "metric value" lines. apps/cmd_diff.cpp is its CLI11 front end.
#pragma once

#include <ostream>
#include <string>

namespace lu {

struct DiffOptions {
    std::string image, reference;
    std::string metric = "all";  // mse | rmse | relmse | mape | all
    std::string crop;            // "X0,Y0,X1,Y1" (half-open) or empty for the whole image
    std::string errorImage;      // per-pixel error image to write (.exr or .png), or empty
    int blockSize = 0;           // > 0: compare BxB block means instead of pixels
    bool zTest = false;          // also run the block z-test (metrics.h) with blockSize (8 if 0)
    double alpha = 1e-4;         // its family-wise level
};

// Help text stating the metric formulas (shared by --help and docs/convergence.md).
const char *DiffMetricsHelp();

// Runs the comparison; prints results to `out`, problems to `err`. Returns 0 on success (a failed
// z-test is reported in the output, not the status) and 2 on bad input: unreadable images, sizes
// or channels that differ, a bad or outside crop, an unknown metric, an unwritable error image.
int RunDiff(const DiffOptions &options, std::ostream &out, std::ostream &err);

}  // namespace lu
