// Lucerna material tests: BSDF construction helpers, an adaptive quadrature of pdfs over
// (theta, phi) cells, and the chi-square test of BSDF::Sample_f against BSDF::PDF (after
// pbrt-v4's bsdfs_test.cpp and Mitsuba's chi2 harness).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "lucerna/materials/bsdf.h"
#include "support/test_support.h"

namespace lu::test {

// A fixed, non-trivial shading frame so the tests also cover render <-> local conversion.
inline Frame TestFrame() {
    Vec3f n = Normalize(Vec3f(0.3f, -0.5f, 0.8f));
    Vec3f dpdu = Vec3f(1, 0.2f, 0.1f);
    return Frame::FromXZ(dpdu, n);
}

inline SampledSpectrum Spec(Float a, Float b, Float c, Float d) {
    SampledSpectrum s;
    s[0] = a; s[1] = b; s[2] = c; s[3] = d;
    return s;
}

inline BSDF MakeDiffuse(const SampledSpectrum &R) {
    BSDF b; b.shadingFrame = TestFrame(); b.kind = BxDFKind::Diffuse; b.diffuse = DiffuseBxDF(R); return b;
}
inline BSDF MakeConductor(Float ax, Float ay, const SampledSpectrum &eta, const SampledSpectrum &k) {
    BSDF b; b.shadingFrame = TestFrame(); b.kind = BxDFKind::Conductor;
    b.conductor = ConductorBxDF(TrowbridgeReitzDistribution(ax, ay), eta, k); return b;
}
inline BSDF MakeDielectric(Float eta, Float ax, Float ay) {
    BSDF b; b.shadingFrame = TestFrame(); b.kind = BxDFKind::Dielectric;
    b.dielectric = DielectricBxDF(eta, TrowbridgeReitzDistribution(ax, ay)); return b;
}
inline BSDF MakeThinDielectric(Float eta) {
    BSDF b; b.shadingFrame = TestFrame(); b.kind = BxDFKind::ThinDielectric;
    b.thinDielectric = ThinDielectricBxDF(eta); return b;
}
inline BSDF MakeCoated(Float eta, Float alpha, const SampledSpectrum &R, Float thickness, const SampledSpectrum &albedo,
                       Float g, int maxDepth = 10, int nSamples = 1) {
    BSDF b; b.shadingFrame = TestFrame(); b.kind = BxDFKind::CoatedDiffuse;
    b.coatedDiffuse = CoatedDiffuseBxDF(DielectricBxDF(eta, TrowbridgeReitzDistribution(alpha, alpha)), DiffuseBxDF(R),
                                        thickness, albedo, g, maxDepth, nSamples);
    return b;
}

// Local direction from spherical angles (theta from +z).
inline Vec3f Dir(Float thetaDeg, Float phiDeg = 0) {
    Float t = Radians(thetaDeg), p = Radians(phiDeg);
    return Vec3f(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}
inline Vec3f DirD(double theta, double phi) {
    return Vec3f(Float(std::sin(theta) * std::cos(phi)), Float(std::sin(theta) * std::sin(phi)), Float(std::cos(theta)));
}

// Adaptive 2D integration of g(theta, phi) over a rectangle: 4x4 Gauss-Legendre per cell,
// compared against the sum over its 4 children; recursion stops when they agree to relTol
// (or absTol) or at maxDepth.
class AdaptiveIntegrator2D {
  public:
    using Fn = std::function<double(double, double)>;
    AdaptiveIntegrator2D(Fn g, double relTol = 2e-4, double absTol = 1e-9, int maxDepth = 6)
        : g_(std::move(g)), relTol_(relTol), absTol_(absTol), maxDepth_(maxDepth) {}

    double Integrate(double x0, double x1, double y0, double y1) {
        return Recurse(x0, x1, y0, y1, GL(x0, x1, y0, y1), 0);
    }
    long evaluations = 0;

  private:
    double GL(double x0, double x1, double y0, double y1) {
        static const double nodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
        static const double weights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
        double cx = 0.5 * (x0 + x1), hx = 0.5 * (x1 - x0), cy = 0.5 * (y0 + y1), hy = 0.5 * (y1 - y0);
        double s = 0;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) s += weights[i] * weights[j] * g_(cx + hx * nodes[i], cy + hy * nodes[j]);
        evaluations += 16;
        return s * hx * hy;
    }
    double Recurse(double x0, double x1, double y0, double y1, double whole, int depth) {
        double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
        double a = GL(x0, xm, y0, ym), b = GL(xm, x1, y0, ym), c = GL(x0, xm, ym, y1), d = GL(xm, x1, ym, y1);
        double sum = a + b + c + d;
        if (depth >= maxDepth_ || std::abs(sum - whole) <= std::max(relTol_ * std::abs(sum), absTol_)) return sum;
        return Recurse(x0, xm, y0, ym, a, depth + 1) + Recurse(xm, x1, y0, ym, b, depth + 1) +
               Recurse(x0, xm, ym, y1, c, depth + 1) + Recurse(xm, x1, ym, y1, d, depth + 1);
    }
    Fn g_;
    double relTol_, absTol_;
    int maxDepth_;
};

// Number of chi-square tests in the material suite, for the Sidak correction of the 1e-4 level.
constexpr int NumChi2Tests = 22;
inline double Chi2Threshold() { return 1 - std::pow(1 - 1e-4, 1.0 / NumChi2Tests); }

struct Chi2Result {
    double pValue = 0;
    std::string message;
    long failures = 0;         // Sample_f returned false
    long mismatches = 0;       // non-specular samples whose f/pdf disagree with f()/PDF()
    std::string firstMismatch;
    double integral = 0;       // integral of PDF over the sphere
};

// Histograms N samples of bsdf.Sample_f(wo) over a (theta, phi) grid in the local frame and tests
// them against the integral of PDF over each cell (plus one cell for failed samples). Also checks
// that each sample's f and pdf equal f() and PDF() for the sampled direction.
inline Chi2Result Chi2TestBSDF(const BSDF &bsdf, Vec3f woLocal, long n, uint64_t seed,
                               TransportMode mode = TransportMode::Radiance, int nTheta = 20, int nPhi = 40) {
    Chi2Result res;
    Vec3f wo = bsdf.shadingFrame.FromLocal(Normalize(woLocal));
    std::vector<double> observed(size_t(nTheta * nPhi) + 1, 0.0), expected(size_t(nTheta * nPhi) + 1, 0.0);
    RNG rng(seed, 0x9e3779b97f4a7c15ull);
    for (long i = 0; i < n; ++i) {
        Float uc = rng.UniformFloat();
        Vec2f u(rng.UniformFloat(), rng.UniformFloat());
        BSDFSample bs;
        if (!bsdf.Sample_f(wo, uc, u, &bs, mode)) {
            observed.back() += 1;
            ++res.failures;
            continue;
        }
        Vec3f wl = bsdf.shadingFrame.ToLocal(bs.wi);
        double theta = std::acos(std::clamp(double(wl.z), -1.0, 1.0));
        double phi = std::atan2(double(wl.y), double(wl.x));
        if (phi < 0) phi += 2 * M_PI;
        int ti = std::min(nTheta - 1, int(theta / M_PI * nTheta));
        int pi = std::min(nPhi - 1, int(phi / (2 * M_PI) * nPhi));
        observed[size_t(ti * nPhi + pi)] += 1;
        if (!bs.IsSpecular()) {
            SampledSpectrum f = bsdf.f(wo, bs.wi, mode);
            Float pdf = bsdf.PDF(wo, bs.wi, mode);
            bool ok = std::abs(pdf - bs.pdf) <= 2e-3f * std::max(pdf, bs.pdf);
            for (int k = 0; k < NSpectrumSamples; ++k)
                ok = ok && std::abs(f[k] - bs.f[k]) <= 2e-3f * std::max(std::abs(f[k]), std::abs(bs.f[k]));
            if (!ok) {
                if (res.mismatches == 0)
                    res.firstMismatch = "wi=(" + std::to_string(wl.x) + "," + std::to_string(wl.y) + "," +
                                        std::to_string(wl.z) + ") pdf " + std::to_string(bs.pdf) + " vs " +
                                        std::to_string(pdf) + ", f0 " + std::to_string(bs.f[0]) + " vs " +
                                        std::to_string(f[0]);
                ++res.mismatches;
            }
        }
    }
    AdaptiveIntegrator2D integ([&](double theta, double phi) {
        Vec3f wl = DirD(theta, phi);
        return double(bsdf.PDF(wo, bsdf.shadingFrame.FromLocal(wl), mode)) * std::sin(theta);
    });
    double total = 0;
    for (int ti = 0; ti < nTheta; ++ti)
        for (int pi = 0; pi < nPhi; ++pi) {
            double t0 = M_PI * ti / nTheta, t1 = M_PI * (ti + 1) / nTheta;
            double p0 = 2 * M_PI * pi / nPhi, p1 = 2 * M_PI * (pi + 1) / nPhi;
            double v = integ.Integrate(t0, t1, p0, p1);
            total += v;
            expected[size_t(ti * nPhi + pi)] = v * double(n);
        }
    res.integral = total;
    expected.back() = std::max(0.0, 1 - total) * double(n);
    res.pValue = ChiSquarePValue(observed, expected, &res.message);
    res.message += ", integral " + std::to_string(total) + ", failures " + std::to_string(res.failures) +
                   ", evals " + std::to_string(integ.evaluations);
    return res;
}

// Mean and standard error of the sample weights f |cos| / pdf of Sample_f from wo (local), i.e.
// a Monte Carlo estimate of the directional albedo; channel c.
struct MeanEstimate {
    double mean = 0, stdErr = 0;
};
inline MeanEstimate SampledAlbedo(const BSDF &bsdf, Vec3f woLocal, long n, uint64_t seed, int c = 0,
                                  TransportMode mode = TransportMode::Radiance) {
    Vec3f wo = bsdf.shadingFrame.FromLocal(Normalize(woLocal));
    Vec3f nrm = bsdf.shadingFrame.z;
    RNG rng(seed, 12345);
    double sum = 0, sum2 = 0;
    for (long i = 0; i < n; ++i) {
        Float uc = rng.UniformFloat();
        Vec2f u(rng.UniformFloat(), rng.UniformFloat());
        BSDFSample bs;
        double w = 0;
        if (bsdf.Sample_f(wo, uc, u, &bs, mode)) w = double(bs.f[c]) * std::abs(Dot(bs.wi, nrm)) / bs.pdf;
        sum += w;
        sum2 += w * w;
    }
    MeanEstimate e;
    e.mean = sum / n;
    e.stdErr = std::sqrt(std::max(0.0, sum2 / n - e.mean * e.mean) / n);
    return e;
}

}  // namespace lu::test
