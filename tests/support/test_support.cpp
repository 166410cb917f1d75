// Lucerna test support: shared paths and the chi-square test (regularized incomplete gamma).
#include "support/test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <string>
#include <unistd.h>

namespace lu::test {

std::string SharedPath(const std::string &rel) { return std::string(LUCERNA_SHARED_DIR) + "/" + rel; }
std::string SourcePath(const std::string &rel) { return std::string(LUCERNA_SOURCE_DIR) + "/" + rel; }
std::string TempDir(const std::string &name) {
    // ctest runs each test in its own process, several at once: the pid keeps their folders apart.
    auto p = std::filesystem::temp_directory_path() / ("lucerna_test_" + name + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p.string();
}

// Upper regularized incomplete gamma Q(a, x) by series / continued fraction (Numerical Recipes
// formulation, written from the definitions).
static double GammaQ(double a, double x) {
    if (x <= 0) return 1;
    double gln = std::lgamma(a);
    if (x < a + 1) {
        double ap = a, sum = 1 / a, del = sum;
        for (int n = 0; n < 10000; ++n) {
            ap += 1; del *= x / ap; sum += del;
            if (std::abs(del) < std::abs(sum) * 1e-15) break;
        }
        return 1 - sum * std::exp(-x + a * std::log(x) - gln);
    }
    double b = x + 1 - a, c = 1 / 1e-300, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b; if (std::abs(d) < 1e-300) d = 1e-300;
        c = b + an / c; if (std::abs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (std::abs(del - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - gln) * h;
}

double ChiSquarePValue(const std::vector<double> &observed, const std::vector<double> &expected,
                       std::string *message) {
    std::vector<size_t> order(observed.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
    double pooledObs = 0, pooledExp = 0, chsq = 0;
    int dof = 0;
    for (size_t i : order) {
        if (expected[i] == 0) {
            if (observed[i] > 0) {
                if (message) *message = "observed samples in a cell with zero expected count";
                return 0;
            }
            continue;
        }
        if (expected[i] < 5) {
            pooledObs += observed[i]; pooledExp += expected[i];
        } else {
            chsq += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
            ++dof;
        }
    }
    if (pooledExp > 0) {
        chsq += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
        ++dof;
    }
    dof -= 1;
    if (dof <= 0) { if (message) *message = "too few cells"; return 1; }
    double p = GammaQ(dof / 2.0, chsq / 2.0);
    if (message) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "chi2 = %.2f, dof = %d, p = %.3g", chsq, dof, p);
        *message = buf;
    }
    return p;
}

}  // namespace lu::test
