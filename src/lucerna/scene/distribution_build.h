// Lucerna (host): builders of the piecewise-constant distributions of sampling/distribution.h;
// they append the tables to a std::vector<Float> that becomes SceneView::distData.
#pragma once

#include <cmath>
#include <vector>

#include "lucerna/sampling/distribution.h"

namespace lu {

// Appends a normalized cdf (n+1 values) for |f| over n bins to out; returns the integral of |f|
// over the unit interval (sum |f_i| / n). An all-zero function gets the uniform cdf (pbrt-v4).
inline Float AppendCdf(const float *f, size_t stride, uint32_t n, std::vector<Float> &out) {
    size_t start = out.size();
    out.push_back(0);
    double acc = 0;
    for (uint32_t i = 0; i < n; ++i) {
        acc += std::abs(double(f[i * stride])) / n;
        out.push_back(Float(acc));
    }
    if (acc == 0) {
        for (uint32_t i = 1; i <= n; ++i) out[start + i] = Float(i) / Float(n);
    } else {
        double run = 0;
        for (uint32_t i = 1; i <= n; ++i) {
            run += std::abs(double(f[(i - 1) * stride])) / n;
            out[start + i] = Float(run / acc);
        }
        out[start + n] = 1;
    }
    return Float(acc);
}

// Builds a 1D distribution of |func| over [min, max], appending its tables to distData.
inline Distribution1D BuildDistribution1D(const float *func, uint32_t n, std::vector<Float> &distData, Float min = 0,
                                          Float max = 1) {
    Distribution1D d;
    d.n = n;
    d.min = min;
    d.max = max;
    d.offset = distData.size();
    Float unitInt = AppendCdf(func, 1, n, distData);
    for (uint32_t i = 0; i < n; ++i) distData.push_back(std::abs(func[i]));
    d.integral = unitInt * (max - min);
    return d;
}

// Builds a 2D distribution of |func| over [0,1]^2 (func row-major, nx columns, ny rows, row 0 at
// v = 0), appending its tables to distData.
inline Distribution2D BuildDistribution2D(const float *func, int nx, int ny, std::vector<Float> &distData) {
    Distribution2D d;
    d.nx = uint32_t(nx);
    d.ny = uint32_t(ny);
    d.offset = distData.size();
    std::vector<float> rowInt(ny);
    for (int y = 0; y < ny; ++y) {
        double acc = 0;
        for (int x = 0; x < nx; ++x) acc += std::abs(double(func[size_t(y) * nx + x]));
        rowInt[y] = float(acc / nx);
    }
    d.integral = AppendCdf(rowInt.data(), 1, d.ny, distData);
    for (int y = 0; y < ny; ++y) AppendCdf(func + size_t(y) * nx, 1, d.nx, distData);
    for (size_t i = 0; i < size_t(nx) * ny; ++i) distData.push_back(std::abs(func[i]));
    return d;
}

}  // namespace lu
