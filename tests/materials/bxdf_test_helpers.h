// Lucerna material tests: BSDF construction helpers, the chi-square test of BSDF::Sample_f
// against BSDF::PDF through the harness of support/chi2.h (after pbrt-v4's bsdfs_test.cpp), and
// the sampled directional albedo.
#pragma once

#include <algorithm>
#include <cmath>
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

inline BSDF MakeCoatedConductor(Float eta, Float coatAlpha, Float conductorAlpha, const SampledSpectrum &cEta,
                                const SampledSpectrum &cK, Float thickness, const SampledSpectrum &albedo, Float g,
                                int maxDepth = 10, int nSamples = 1) {
    BSDF b; b.shadingFrame = TestFrame(); b.kind = BxDFKind::CoatedConductor;
    b.coatedConductor = CoatedConductorBxDF(
        DielectricBxDF(eta, TrowbridgeReitzDistribution(coatAlpha, coatAlpha)),
        ConductorBxDF(TrowbridgeReitzDistribution(conductorAlpha, conductorAlpha), cEta, cK), thickness, albedo, g,
        maxDepth, nSamples);
    return b;
}
inline BSDF MakeDiffuseTransmission(const SampledSpectrum &R, const SampledSpectrum &T) {
    BSDF b; b.shadingFrame = TestFrame(); b.kind = BxDFKind::DiffuseTransmission;
    b.diffuseTransmission = DiffuseTransmissionBxDF(R, T); return b;
}

// Local direction from spherical angles (theta from +z).
inline Vec3f Dir(Float thetaDeg, Float phiDeg = 0) {
    Float t = Radians(thetaDeg), p = Radians(phiDeg);
    return Vec3f(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}
inline Vec3f DirD(double theta, double phi) {
    return Vec3f(Float(std::sin(theta) * std::cos(phi)), Float(std::sin(theta) * std::sin(phi)), Float(std::cos(theta)));
}

// Number of chi-square tests in the material suite, for the Sidak correction of the 1e-4 level.
constexpr int NumChi2Tests = 27;   // 24 + hair_test's 3

struct BSDFChi2 {
    Chi2Result chi2;           // the harness's result (support/chi2.h)
    long mismatches = 0;       // non-specular samples whose f/pdf disagree with f()/PDF()
    std::string firstMismatch;
};

// The chi-square test of bsdf.Sample_f(wo) against PDF over the sphere of local directions
// (support/chi2.h, a (theta, phi) grid; failed samples form one more cell). pdfBsdf, when given,
// supplies the pdf instead (negative tests). Also checks that each sample's f and pdf equal f()
// and PDF() for the sampled direction.
inline BSDFChi2 Chi2TestBSDF(const BSDF &bsdf, Vec3f woLocal, long n, uint64_t seed,
                             TransportMode mode = TransportMode::Radiance, int nTheta = 20, int nPhi = 40,
                             const BSDF *pdfBsdf = nullptr) {
    BSDFChi2 res;
    Vec3f wo = bsdf.shadingFrame.FromLocal(Normalize(woLocal));
    RNG rng(seed, 0x9e3779b97f4a7c15ull);
    auto sample = [&](Chi2Point *p) {
        Float uc = rng.UniformFloat();
        Vec2f u(rng.UniformFloat(), rng.UniformFloat());
        BSDFSample bs;
        if (!bsdf.Sample_f(wo, uc, u, &bs, mode)) return false;
        Vec3f wl = bsdf.shadingFrame.ToLocal(bs.wi);
        *p = {wl.x, wl.y, wl.z};
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
        return true;
    };
    const BSDF &pb = pdfBsdf ? *pdfBsdf : bsdf;
    auto pdf = [&](const Chi2Point &w) {
        Vec3f wl(Float(w.x), Float(w.y), Float(w.z));
        return double(pb.PDF(wo, pb.shadingFrame.FromLocal(wl), mode));
    };
    Chi2Options opts;
    opts.samples = n;
    opts.integralTolerance = 1e-3;
    res.chi2 = Chi2SampleTest(SphereDomain(nTheta, nPhi), sample, pdf, opts);
    return res;
}

// Mean and standard error of the sample weights f |cos| / pdf of Sample_f from wo (local), i.e.
// a Monte Carlo estimate of the directional albedo; channel c.
struct MeanEstimate {
    double mean = 0, stdErr = 0;
};
// The mean of n values and its standard error from their sum and sum of squares.
inline MeanEstimate MeanOfSums(double sum, double sum2, long n) {
    MeanEstimate e;
    e.mean = sum / n;
    e.stdErr = std::sqrt(std::max(0.0, sum2 / n - e.mean * e.mean) / n);
    return e;
}
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
    return MeanOfSums(sum, sum2, n);
}

}  // namespace lu::test
