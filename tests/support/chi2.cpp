// Lucerna test support: the chi-square harness (support/chi2.h). The statistic, pooling and
// Sidak correction follow Mitsuba 3's chi2.py; the p-value is the regularized upper incomplete
// gamma function, written from its series and continued-fraction definitions.
#include "support/chi2.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <numeric>

namespace lu::test {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPoolThreshold = 5;  // cells expecting fewer samples are pooled
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Upper regularized incomplete gamma Q(a, x): the series for x < a + 1, else the continued
// fraction (modified Lentz).
double GammaQ(double a, double x) {
    if (x <= 0) return 1;
    double gln = std::lgamma(a);
    if (x < a + 1) {
        double ap = a, sum = 1 / a, del = sum;
        for (int n = 0; n < 10000; ++n) {
            ap += 1; del *= x / ap; sum += del;
            if (std::abs(del) < std::abs(sum) * 1e-15) break;
        }
        return std::max(0.0, 1 - sum * std::exp(-x + a * std::log(x) - gln));
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

struct Pearson {
    double chi2 = 0, p = kNaN;
    int dof = 0, pooledIn = 0, pooledOut = 0;
    std::string why;  // set when p is 0 by rule or NaN
};

// Pearson's statistic over cells sorted by expected count, low ones pooled (see chi2.h).
Pearson PearsonPooled(const std::vector<double> &observed, const std::vector<double> &expected) {
    Pearson r;
    std::vector<size_t> order(observed.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
    std::vector<std::pair<double, double>> groups;  // (observed, expected) of each final cell
    double poolO = 0, poolE = 0;
    int poolN = 0;
    bool lastIsPool = false;
    for (size_t i : order) {
        double o = observed[i], e = expected[i];
        if (e == 0) {
            if (o > 0) {
                char buf[160];
                std::snprintf(buf, sizeof buf, "%.0f samples in cell %zu, whose expected count is 0", o, i);
                r.why = buf;
                r.p = 0;
                return r;
            }
            continue;
        }
        if (e < kPoolThreshold) {
            poolO += o; poolE += e; ++poolN; ++r.pooledIn;
            if (poolE >= kPoolThreshold) {
                groups.push_back({poolO, poolE});
                ++r.pooledOut;
                lastIsPool = true;
                poolO = poolE = 0;
                poolN = 0;
            }
            continue;
        }
        if (poolN > 0) {  // a remainder below the threshold: into the last pool, else this cell
            if (lastIsPool) {
                groups.back().first += poolO;
                groups.back().second += poolE;
            } else {
                o += poolO;
                e += poolE;
                ++r.pooledOut;
            }
            poolO = poolE = 0;
            poolN = 0;
        }
        groups.push_back({o, e});
        lastIsPool = false;
    }
    if (poolN > 0) {
        if (!groups.empty()) {
            groups.back().first += poolO;
            groups.back().second += poolE;
        } else {
            groups.push_back({poolO, poolE});
            ++r.pooledOut;
        }
    }
    for (const auto &g : groups) r.chi2 += (g.first - g.second) * (g.first - g.second) / g.second;
    r.dof = int(groups.size()) - 1;
    if (r.dof < 1) {
        r.why = "only " + std::to_string(groups.size()) + " cell(s) after pooling: the test cannot be run (more samples or cells needed)";
        r.p = kNaN;
        return r;
    }
    r.p = GammaQ(r.dof / 2.0, r.chi2 / 2.0);
    return r;
}

std::string Fmt(const char *format, double a, double b = 0, double c = 0) {
    char buf[256];
    std::snprintf(buf, sizeof buf, format, a, b, c);
    return buf;
}

}  // namespace

Chi2Result Chi2Counts(const std::vector<double> &observed, const std::vector<double> &expected, double controlError) {
    Chi2Result r;
    r.controlError = controlError;
    if (observed.size() != expected.size() || observed.empty()) {
        r.message = "observed and expected counts differ in size or are empty";
        return r;
    }
    for (size_t i = 0; i < observed.size(); ++i) {
        if (!std::isfinite(observed[i]) || !std::isfinite(expected[i]) || observed[i] < 0 || expected[i] < 0) {
            r.message = "cell " + std::to_string(i) + ": non-finite or negative count (observed " +
                        std::to_string(observed[i]) + ", expected " + std::to_string(expected[i]) + ")";
            return r;
        }
        r.observedTotal += observed[i];
        r.expectedTotal += expected[i];
    }
    if (r.observedTotal <= 0) {
        r.message = "no samples";
        return r;
    }
    Pearson p = PearsonPooled(observed, expected);
    r.chi2 = p.chi2;
    r.dof = p.dof;
    r.pooledIn = p.pooledIn;
    r.pooledOut = p.pooledOut;
    r.pValue = p.p;
    if (!p.why.empty()) {
        r.message = p.why;
        if (!r.Valid()) return r;
    } else {
        r.message = Fmt("chi2 = %.2f, dof = %.0f, p = %.3g", p.chi2, p.dof, p.p);
    }
    if (r.pooledIn > 0) r.message += Fmt("; pooled %.0f low cells into %.0f", r.pooledIn, r.pooledOut);
    r.message += Fmt("; %.0f samples, expected total %.6g", r.observedTotal, r.expectedTotal);
    if (controlError > 0) {
        // Alternating +-controlError over the cells that expect samples, then the original total.
        std::vector<double> wrong = expected;
        double sign = 1, total = 0;
        for (double &e : wrong) {
            if (e > 0) { e *= 1 + sign * controlError; sign = -sign; }
            total += e;
        }
        if (total > 0)
            for (double &e : wrong) e *= r.expectedTotal / total;
        r.controlPValue = PearsonPooled(observed, wrong).p;
        r.message += Fmt("; control (%.0f%% cell errors): p = %.3g", 100 * controlError, r.controlPValue);
    }
    return r;
}

// ---- Domains ----

Chi2Domain SphereDomain(int nTheta, int nPhi) {
    Chi2Domain d;
    d.name = "sphere (theta, phi)";
    d.nu = nTheta;
    d.nv = nPhi;
    d.toParams = [](const Chi2Point &w, double *u, double *v) {
        double len = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
        if (!(std::abs(len - 1) < 1e-3)) return false;
        double theta = std::acos(std::clamp(w.z / len, -1.0, 1.0));
        double phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * kPi;
        *u = theta / kPi;
        *v = phi / (2 * kPi);
        return true;
    };
    d.fromParams = [](double u, double v, double *jacobian) {
        double theta = kPi * u, phi = 2 * kPi * v;
        *jacobian = std::sin(theta) * kPi * 2 * kPi;
        return Chi2Point{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    };
    return d;
}

Chi2Domain CapDomain(Chi2Point axis, double cosCap, int nTheta, int nPhi) {
    // An orthonormal frame (s, t, a) around the axis (Duff et al. 2017's construction).
    double len = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    Chi2Point a{axis.x / len, axis.y / len, axis.z / len};
    double sign = std::copysign(1.0, a.z);
    double p = -1 / (sign + a.z), q = a.x * a.y * p;
    Chi2Point s{1 + sign * a.x * a.x * p, sign * q, -sign * a.x};
    Chi2Point t{q, sign + a.y * a.y * p, -a.y};
    double capSpan = 1 - cosCap;  // u = (1 - cos theta) / capSpan
    Chi2Domain d;
    d.name = "cap (1 - cos theta, phi)";
    d.nu = nTheta;
    d.nv = nPhi;
    d.toParams = [=](const Chi2Point &w, double *u, double *v) {
        double l = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
        if (!(std::abs(l - 1) < 1e-3)) return false;
        double x = (w.x * s.x + w.y * s.y + w.z * s.z) / l, y = (w.x * t.x + w.y * t.y + w.z * t.z) / l;
        double z = (w.x * a.x + w.y * a.y + w.z * a.z) / l;
        // 1 - cos theta, accurate near theta = 0: sin^2 / (1 + cos) on the upper hemisphere.
        double oneMinusCos = z > 0 ? (x * x + y * y) / (1 + std::min(1.0, z)) : 1 - z;
        double uu = oneMinusCos / capSpan;
        if (uu > 1) return false;
        double phi = std::atan2(y, x);
        if (phi < 0) phi += 2 * kPi;
        *u = uu;
        *v = phi / (2 * kPi);
        return true;
    };
    d.fromParams = [=](double u, double v, double *jacobian) {
        double cosT = 1 - u * capSpan, sinT = std::sqrt(std::max(0.0, 1 - cosT * cosT));
        double phi = 2 * kPi * v;
        double x = sinT * std::cos(phi), y = sinT * std::sin(phi);
        *jacobian = capSpan * 2 * kPi;
        return Chi2Point{x * s.x + y * t.x + cosT * a.x, x * s.y + y * t.y + cosT * a.y, x * s.z + y * t.z + cosT * a.z};
    };
    return d;
}

Chi2Domain RectDomain(double x0, double x1, double y0, double y1, int nx, int ny) {
    Chi2Domain d;
    d.name = "rectangle";
    d.nu = nx;
    d.nv = ny;
    d.toParams = [=](const Chi2Point &p, double *u, double *v) {
        *u = (p.x - x0) / (x1 - x0);
        *v = (p.y - y0) / (y1 - y0);
        return *u >= 0 && *u <= 1 && *v >= 0 && *v <= 1;
    };
    d.fromParams = [=](double u, double v, double *jacobian) {
        *jacobian = (x1 - x0) * (y1 - y0);
        return Chi2Point{x0 + u * (x1 - x0), y0 + v * (y1 - y0), 0};
    };
    return d;
}

Chi2Domain IntervalDomain(double x0, double x1, int n) {
    Chi2Domain d;
    d.name = "interval";
    d.nu = n;
    d.nv = 1;
    d.toParams = [=](const Chi2Point &p, double *u, double *v) {
        *u = (p.x - x0) / (x1 - x0);
        *v = 0;
        return *u >= 0 && *u <= 1;
    };
    d.fromParams = [=](double u, double, double *jacobian) {
        *jacobian = x1 - x0;
        return Chi2Point{x0 + u * (x1 - x0), 0, 0};
    };
    return d;
}

// ---- Sampling test ----

Chi2Result Chi2SampleTest(const Chi2Domain &domain, const Chi2Sampler &sample, const Chi2Pdf &pdf,
                          const Chi2Options &opts) {
    const int nu = domain.nu, nv = domain.nv;
    const size_t cells = size_t(nu) * nv, failedCell = cells, outsideCell = cells + 1;
    std::vector<double> observed(cells + 2, 0), expected(cells + 2, 0);
    long failed = 0, outside = 0;
    for (long i = 0; i < opts.samples; ++i) {
        Chi2Point p;
        if (!sample(&p)) {
            ++failed;
            continue;
        }
        double u, v;
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !domain.toParams(p, &u, &v)) {
            ++outside;
            continue;
        }
        int iu = std::clamp(int(u * nu), 0, nu - 1), iv = std::clamp(int(v * nv), 0, nv - 1);
        observed[size_t(iu) * nv + iv] += 1;
    }
    if (opts.failuresInHistogram) observed[failedCell] = double(failed);
    observed[outsideCell] = double(outside);

    long badPdf = 0;
    Chi2Point firstBad;
    auto density = [&](double u, double v) {
        double jacobian = 0;
        Chi2Point p = domain.fromParams(u, v, &jacobian);
        double f = pdf(p);
        if (!(f >= 0) || !std::isfinite(f)) {
            if (badPdf++ == 0) firstBad = p;
            return 0.0;
        }
        return f * jacobian;
    };
    double integral = 0, jacobianUnused = 0;
    long refined = 0;
    for (int iu = 0; iu < nu; ++iu)
        for (int iv = 0; iv < nv; ++iv) {
            double u0 = double(iu) / nu, u1 = double(iu + 1) / nu, v0 = double(iv) / nv, v1 = double(iv + 1) / nv;
            size_t c = size_t(iu) * nv + iv;
            if (opts.cellMass) {
                double m = opts.cellMass(u0, u1, v0, v1);
                if (!(m >= 0) || !std::isfinite(m)) {
                    if (badPdf++ == 0) firstBad = domain.fromParams(u0, v0, &jacobianUnused);
                    m = 0;
                }
                integral += m;
                expected[c] = m * double(opts.samples);
                continue;
            }
            AdaptiveIntegrator2D integ(density, opts.relTol, 1e-9, opts.maxDepth, opts.minDepth);
            double m = integ.Integrate(u0, u1, v0, v1);
            if (m <= 0 && observed[c] > 0) {
                // Samples where the nodes saw no mass: a sliver of support between them?
                AdaptiveIntegrator2D fine(density, opts.relTol, 1e-12, std::max(opts.maxDepth, 5), 4);
                m = fine.Integrate(u0, u1, v0, v1);
                ++refined;
            }
            integral += m;
            expected[c] = m * double(opts.samples);
        }
    if (opts.failuresInHistogram) expected[failedCell] = std::max(0.0, 1 - integral) * double(opts.samples);

    Chi2Result r;
    if (badPdf > 0) {
        r = Chi2Result{};
        r.pValue = 0;
        r.message = std::to_string(badPdf) + " negative or NaN pdf values, the first at (" + std::to_string(firstBad.x) +
                    ", " + std::to_string(firstBad.y) + ", " + std::to_string(firstBad.z) + ")";
    } else if (integral > 1 + opts.integralTolerance) {
        r = Chi2Result{};
        r.pValue = 0;
        r.message = Fmt("the pdf integrates to %.6g over the domain (more than 1 + %.3g)", integral, opts.integralTolerance);
    } else {
        r = Chi2Counts(observed, expected, opts.controlError);
    }
    r.pdfIntegral = integral;
    r.samples = opts.samples;
    r.failed = failed;
    r.outside = outside;
    r.message += "; " + domain.name + " " + std::to_string(nu) + "x" + std::to_string(nv) + " cells, pdf integral " +
                 std::to_string(integral) + ", " + std::to_string(failed) + " failed, " + std::to_string(outside) +
                 " outside the domain";
    if (refined) r.message += ", " + std::to_string(refined) + " cells re-integrated finely";
    return r;
}

Chi2Result Chi2SampleTest(const Chi2Domain &domain, const Chi2Sampler &sample, const Chi2Options &opts) {
    return Chi2SampleTest(domain, sample, [](const Chi2Point &) { return kNaN; }, opts);
}

double SidakLevel(double level, int tests) { return 1 - std::pow(1 - level, 1.0 / std::max(1, tests)); }

// LU_CHI2_VERBOSE=1 prints every result's summary.
void Verbose(const char *what, const Chi2Result &r) {
    if (std::getenv("LU_CHI2_VERBOSE")) std::printf("[chi2 %s] %s\n", what, r.message.c_str());
}

::testing::AssertionResult Chi2Accepts(const Chi2Result &r, double level, int tests) {
    double alpha = SidakLevel(level, tests);
    Verbose("accepts?", r);
    if (!r.Valid()) return ::testing::AssertionFailure() << "the chi-square test could not be run: " << r.message;
    if (r.pValue < alpha)
        return ::testing::AssertionFailure() << "rejected: p = " << r.pValue << " < " << alpha << " (" << r.message << ")";
    if (r.controlError > 0 && !(r.controlPValue < alpha))
        return ::testing::AssertionFailure() << "no power: the counts perturbed by " << 100 * r.controlError
                                             << "% per cell are not rejected either (p = " << r.controlPValue
                                             << " >= " << alpha << "; " << r.message << ")";
    return ::testing::AssertionSuccess() << "accepted: p = " << r.pValue << " >= " << alpha << " (" << r.message << ")";
}

::testing::AssertionResult Chi2Rejects(const Chi2Result &r, double level, int tests) {
    double alpha = SidakLevel(level, tests);
    Verbose("rejects?", r);
    if (!r.Valid()) return ::testing::AssertionFailure() << "the chi-square test could not be run: " << r.message;
    if (r.pValue < alpha) return ::testing::AssertionSuccess() << "rejected: p = " << r.pValue << " (" << r.message << ")";
    return ::testing::AssertionFailure() << "not rejected: p = " << r.pValue << " >= " << alpha << " (" << r.message << ")";
}

// ---- Integration ----

double AdaptiveIntegrator2D::Integrate(double x0, double x1, double y0, double y1) {
    return Recurse(x0, x1, y0, y1, GL(x0, x1, y0, y1), 0);
}

double AdaptiveIntegrator2D::GL(double x0, double x1, double y0, double y1) {
    static const double nodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    static const double weights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    double cx = 0.5 * (x0 + x1), hx = 0.5 * (x1 - x0), cy = 0.5 * (y0 + y1), hy = 0.5 * (y1 - y0);
    double s = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) s += weights[i] * weights[j] * g_(cx + hx * nodes[i], cy + hy * nodes[j]);
    evaluations += 16;
    return s * hx * hy;
}

double AdaptiveIntegrator2D::Recurse(double x0, double x1, double y0, double y1, double whole, int depth) {
    double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
    double a = GL(x0, xm, y0, ym), b = GL(xm, x1, y0, ym), c = GL(x0, xm, ym, y1), d = GL(xm, x1, ym, y1);
    double sum = a + b + c + d;
    if (depth >= maxDepth_ ||
        (depth >= minDepth_ && std::abs(sum - whole) <= std::max(relTol_ * std::abs(sum), absTol_)))
        return sum;
    return Recurse(x0, xm, y0, ym, a, depth + 1) + Recurse(xm, x1, y0, ym, b, depth + 1) +
           Recurse(x0, xm, ym, y1, c, depth + 1) + Recurse(xm, x1, ym, y1, d, depth + 1);
}

}  // namespace lu::test
