// DenseNearestOffset (color.h) against lround for every float in [256, 1024) and edge cases.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "lucerna/spectrum/color.h"

using namespace lu;

namespace {
int RefOffset(float lambda) {
    if (!std::isfinite(lambda) || std::abs(lambda) > 1e9f) return -1;
    long o = std::lround(lambda) - 360;
    return (o < 0 || o >= TabulatedSpectrumSize) ? -1 : int(o);
}
}  // namespace

TEST(ColorFastPath, DenseNearestOffsetMatchesLround) {
    for (float x = 256.f; x < 1024.f; x = std::nextafter(x, 2048.f)) ASSERT_EQ(DenseNearestOffset(x), RefOffset(x)) << x;
    for (float x : {-1e30f, -360.f, -0.5f, 0.f, 0.49999997f, 0.5f, 1.f, 359.49997f, 359.5f, 830.49994f, 830.5f, 1e30f,
                    INFINITY, -INFINITY, NAN})
        EXPECT_EQ(DenseNearestOffset(x), RefOffset(x)) << x;
}
