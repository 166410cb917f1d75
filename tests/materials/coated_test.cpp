// Tests of the stochastic layered (pbrt-v4 LayeredBxDF) model over a diffuse and a conductor base
// (coated diffuse, coated conductor): exact index-matched cases, agreement of the two independent
// estimators (Sample_f weights vs f() integrated over cosine-sampled directions, per band of
// cos theta_i), energy conservation (a lossless coat over a near-perfect mirror keeps ~all of it)
// and determinism.
#include <gtest/gtest.h>

#include "materials/bxdf_test_helpers.h"

namespace lu::test {
namespace {

// With an index-matched, smooth coat and no medium, light passes the coat, attenuated by
// exp(-thickness / |cos|) each way, and reflects once off the base: f = R/pi Tr(wo) Tr(wi).
TEST(CoatedDiffuse, IndexMatchedCoatIsAttenuatedLambertian) {
    SampledSpectrum R = Spec(0.2f, 0.4f, 0.6f, 0.8f);
    Float t = 0.3f;
    BSDF b = MakeCoated(1.0f, 0, R, t, SampledSpectrum(0), 0);
    RNG rng(4, 4);
    for (int i = 0; i < 200; ++i) {
        Vec3f a = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        Vec3f c = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        if (std::abs(a.z) < 0.05f || std::abs(c.z) < 0.05f) continue;
        SampledSpectrum f = b.f(b.shadingFrame.FromLocal(a), b.shadingFrame.FromLocal(c));
        for (int k = 0; k < NSpectrumSamples; ++k) {
            Float ref = SameHemisphere(a, c) ? R[k] * InvPi * std::exp(-t / std::abs(a.z)) * std::exp(-t / std::abs(c.z)) : 0;
            ASSERT_NEAR(f[k], ref, 1e-5f * ref + 1e-7f) << "wo.z " << a.z << " wi.z " << c.z;
        }
    }
}

struct CoatedCase {
    const char *name;
    BSDF bsdf;
    Vec3f wo;
};

// Per band of cos theta_i (and in total): E[Sample_f weight restricted to the band] against
// E[pi f(wo, wi)] over cosine-sampled wi in the band (plus the coat's Dirac reflection, which f()
// cannot return). z-tests at |z| < 4.5 (two-sided 7e-6 each; ~1e-4 over the suite).
void CheckEstimatorsAgree(const CoatedCase &cc, uint64_t seed) {
    SCOPED_TRACE(cc.name);
    const BSDF &b = cc.bsdf;
    const int nBands = 4;
    const long n = 60000;
    Vec3f woL = Normalize(cc.wo);
    Vec3f wo = b.shadingFrame.FromLocal(woL);
    Float sideSign = woL.z > 0 ? 1 : -1;
    // Estimator 1: Sample_f weights binned by |cos theta_i|.
    std::vector<double> s1(nBands + 1, 0), s1sq(nBands + 1, 0);
    double specular = 0, specularSq = 0;
    RNG rng(seed, 1);
    for (long i = 0; i < n; ++i) {
        BSDFSample bs;
        Float uc = rng.UniformFloat();
        Vec2f u(rng.UniformFloat(), rng.UniformFloat());
        if (!b.Sample_f(wo, uc, u, &bs)) continue;
        Vec3f wl = b.shadingFrame.ToLocal(bs.wi);
        ASSERT_TRUE(SameHemisphere(wl, woL)) << "a coated diffuse or conductor only reflects";
        ASSERT_TRUE(bs.pdfIsProportional);
        double w = bs.f[0] * std::abs(wl.z) / bs.pdf;
        if (bs.IsSpecular()) {
            specular += w; specularSq += w * w;
            continue;
        }
        int band = std::min(nBands - 1, int(std::abs(wl.z) * nBands));
        s1[band] += w; s1sq[band] += w * w;
    }
    // Estimator 2: cosine-sampled wi, weight pi f, stratified so that each band gets n samples.
    std::vector<double> s2(nBands + 1, 0), s2sq(nBands + 1, 0);
    RNG rng2(seed, 2);
    for (int band = 0; band < nBands; ++band) {
        // cos theta uniform-in-cos^2 within the band: cosine sampling restricted to [c0, c1].
        double c0 = double(band) / nBands, c1 = double(band + 1) / nBands;
        double bandMass = c1 * c1 - c0 * c0;   // fraction of the cosine-weighted hemisphere
        for (long i = 0; i < n; ++i) {
            double u0 = rng2.UniformFloat(), u1 = rng2.UniformFloat();
            double cosT = std::sqrt(c0 * c0 + u0 * bandMass);
            double sinT = std::sqrt(std::max(0.0, 1 - cosT * cosT)), phi = 2 * M_PI * u1;
            Vec3f wl(Float(sinT * std::cos(phi)), Float(sinT * std::sin(phi)), Float(cosT * sideSign));
            double w = M_PI * bandMass * b.f(wo, b.shadingFrame.FromLocal(wl))[0];
            s2[band] += w; s2sq[band] += w * w;
        }
    }
    double tot1 = 0, var1 = 0, tot2 = 0, var2 = 0;
    for (int band = 0; band < nBands; ++band) {
        double m1 = s1[band] / n, v1 = (s1sq[band] / n - m1 * m1) / n;
        double m2 = s2[band] / n, v2 = (s2sq[band] / n - m2 * m2) / n;
        double z = (m1 - m2) / std::sqrt(v1 + v2 + 1e-30);
        EXPECT_LT(std::abs(z), 4.5) << "band " << band << ": Sample_f " << m1 << " vs f " << m2;
        tot1 += m1; var1 += v1; tot2 += m2; var2 += v2;
    }
    // The coat's Dirac reflection: its expected weight is FrDielectric(|cos wo|) (R / pr * pr).
    const DielectricBxDF &top = b.kind == BxDFKind::CoatedDiffuse ? b.coatedDiffuse.top : b.coatedConductor.top;
    Float Rcoat = top.IsDirac() ? FrDielectric(std::abs(woL.z), top.eta) : 0;
    double mSpec = specular / n, vSpec = (specularSq / n - mSpec * mSpec) / n;
    EXPECT_LT(std::abs(mSpec - Rcoat), 4.5 * std::sqrt(vSpec) + 1e-6) << "specular coat " << mSpec << " vs " << Rcoat;
    double albedo = tot1 + mSpec;
    if (getenv("LU_VERBOSE"))
        printf("%s: albedo %.4f (diffuse part %.4f +- %.4f, via f %.4f +- %.4f)\n", cc.name, albedo, tot1,
               std::sqrt(var1), tot2, std::sqrt(var2));
    EXPECT_LE(albedo, 1 + 4.5 * std::sqrt(var1 + vSpec));
}

BSDF ExactMIS(BSDF b) {
    if (b.kind == BxDFKind::CoatedDiffuse) b.coatedDiffuse.pbrtExitMIS = false;
    else b.coatedConductor.pbrtExitMIS = false;
    return b;
}

TEST(CoatedDiffuse, SampleAndEvalAgree) {
    const int deep = 100;   // deep walks so that both estimators see the same (untruncated) BSDF
    // Smooth coats: pbrt-v4's estimators agree as they are.
    CheckEstimatorsAgree({"smooth coat 1.5, R 0.5", MakeCoated(1.5f, 0, SampledSpectrum(0.5f), 0.01f, SampledSpectrum(0), 0, deep), Dir(30, 0)}, 1);
    CheckEstimatorsAgree({"smooth coat 1.5, R 0.9, grazing", MakeCoated(1.5f, 0, SampledSpectrum(0.9f), 0.01f, SampledSpectrum(0), 0, deep), Dir(80, 0)}, 2);
    CheckEstimatorsAgree({"smooth coat, scattering medium", MakeCoated(1.5f, 0, SampledSpectrum(0.6f), 0.2f, SampledSpectrum(0.8f), 0.3f, deep), Dir(20, 0)}, 4);
    // Rough coats: with the exact MIS pdf (pbrt-v4's reverse-direction pdf biases f(), see below).
    CheckEstimatorsAgree({"rough coat 1.5 alpha 0.3, R 0.7", ExactMIS(MakeCoated(1.5f, 0.3f, SampledSpectrum(0.7f), 0.01f, SampledSpectrum(0), 0, deep)), Dir(45, 20)}, 3);
    CheckEstimatorsAgree({"rough coat 1.33, medium g -0.5", ExactMIS(MakeCoated(1.33f, 0.2f, SampledSpectrum(0.4f), 0.5f, SampledSpectrum(0.5f), -0.5f, deep)), Dir(60, 90)}, 5);
    CheckEstimatorsAgree({"two-sided: from below", ExactMIS(MakeCoated(1.5f, 0.2f, SampledSpectrum(0.5f), 0.01f, SampledSpectrum(0), 0, deep)), Dir(140, 0)}, 6);
}

// pbrt-v4 parity: its f() for a rough coat exceeds the Sample_f estimate (here by ~7%); this pins
// down that the default reproduces pbrt-v4's weights rather than the exact ones.
TEST(CoatedDiffuse, PbrtRoughCoatBias) {
    BSDF b = MakeCoated(1.5f, 0.3f, SampledSpectrum(0.7f), 0.01f, SampledSpectrum(0), 0, 100);
    BSDF exact = ExactMIS(b);
    Vec3f wo = b.shadingFrame.FromLocal(Dir(45, 20));
    RNG rng(5, 5);
    double sumPbrt = 0, sumExact = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        Vec3f wl = SampleCosineHemisphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        Vec3f wi = b.shadingFrame.FromLocal(wl);
        sumPbrt += b.f(wo, wi)[0];
        sumExact += exact.f(wo, wi)[0];
    }
    EXPECT_GT(sumPbrt / sumExact, 1.03);
    EXPECT_LT(sumPbrt / sumExact, 1.15);
}

TEST(CoatedDiffuse, EnergyConservation) {
    // White base, white non-absorbing medium, pbrt-v4 defaults otherwise: albedo <= 1.
    for (Float alpha : {0.f, 0.3f}) {
        for (Float th : {10.f, 60.f, 85.f}) {
            BSDF b = MakeCoated(1.5f, alpha, SampledSpectrum(1), 0.1f, SampledSpectrum(1), 0);
            MeanEstimate e = SampledAlbedo(b, Dir(th, 0), 40000, 11);
            EXPECT_LE(e.mean, 1 + 4.5 * e.stdErr) << "alpha " << alpha << " theta " << th;
            EXPECT_GT(e.mean, 0.5) << "alpha " << alpha << " theta " << th;
        }
    }
}

TEST(CoatedDiffuse, DeterministicAndPositivePdf) {
    BSDF b = MakeCoated(1.5f, 0.2f, SampledSpectrum(0.5f), 0.05f, SampledSpectrum(0.3f), 0.2f);
    RNG rng(8, 8);
    for (int i = 0; i < 500; ++i) {
        Vec3f wo = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        Vec3f wi = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
        if (std::abs(wo.z) < 1e-3f) continue;
        Vec3f woR = b.shadingFrame.FromLocal(wo), wiR = b.shadingFrame.FromLocal(wi);
        // Seeded by hashing the directions (pbrt-v4): the same query gives the same estimate.
        EXPECT_EQ(b.f(woR, wiR)[0], b.f(woR, wiR)[0]);
        Float pdf = b.PDF(woR, wiR);
        EXPECT_EQ(pdf, b.PDF(woR, wiR));
        // Mixed with a uniform density: never below 0.1 / (4 pi).
        EXPECT_GE(pdf, 0.1f / (4 * Pi) * 0.999f);
        BSDFSample s1, s2;
        bool ok1 = b.Sample_f(woR, 0.7f, Vec2f(0.2f, 0.9f), &s1), ok2 = b.Sample_f(woR, 0.7f, Vec2f(0.2f, 0.9f), &s2);
        ASSERT_EQ(ok1, ok2);
        if (ok1) {
            EXPECT_EQ(s1.wi, s2.wi);
        }
    }
}

// ---- Coated conductor: the same layered code over ConductorBxDF ----

SampledSpectrum CuEta() { return Spec(0.27f, 0.68f, 1.1f, 1.2f); }
SampledSpectrum CuK() { return Spec(3.6f, 2.6f, 2.5f, 2.3f); }

// With an index-matched smooth coat, no medium and a smooth conductor base, the whole BSDF is a
// mirror whose weight is the conductor's Fresnel times the coat's attenuation both ways
// (the relative index of the base is the conductor's over the coat's, here 1).
TEST(CoatedConductor, IndexMatchedSmoothIsAttenuatedMirror) {
    Float t = 0.2f;
    BSDF b = MakeCoatedConductor(1.0f, 0, 0, CuEta(), CuK(), t, SampledSpectrum(0), 0);
    EXPECT_TRUE(b.IsSpecular());
    for (Float th : {10.f, 45.f, 75.f}) {
        Vec3f wo = b.shadingFrame.FromLocal(Dir(th, 30));
        BSDFSample bs;
        ASSERT_TRUE(b.Sample_f(wo, 0.3f, Vec2f(0.6f, 0.2f), &bs));
        Vec3f wl = b.shadingFrame.ToLocal(bs.wi);
        EXPECT_NEAR(wl.z, std::cos(Radians(th)), 1e-5f);
        EXPECT_TRUE(bs.IsSpecular());
        Float c = std::cos(Radians(th));
        SampledSpectrum F = FrComplex(c, CuEta(), CuK());
        for (int k = 0; k < NSpectrumSamples; ++k) {
            double w = bs.f[k] * std::abs(wl.z) / bs.pdf;
            EXPECT_NEAR(w, F[k] * std::exp(-2 * t / c), 2e-5) << "theta " << th << " channel " << k;
        }
    }
}

TEST(CoatedConductor, SampleAndEvalAgree) {
    const int deep = 100;
    CheckEstimatorsAgree({"smooth coat over rough copper", MakeCoatedConductor(1.5f, 0, 0.3f, CuEta(), CuK(), 0.01f, SampledSpectrum(0), 0, deep), Dir(30, 0)}, 11);
    CheckEstimatorsAgree({"smooth coat over rough copper, medium", MakeCoatedConductor(1.5f, 0, 0.2f, CuEta(), CuK(), 0.3f, SampledSpectrum(0.7f), 0.4f, deep), Dir(50, 60)}, 12);
    CheckEstimatorsAgree({"rough coat over smooth copper", ExactMIS(MakeCoatedConductor(1.5f, 0.3f, 0, CuEta(), CuK(), 0.01f, SampledSpectrum(0), 0, deep)), Dir(40, 10)}, 13);
    CheckEstimatorsAgree({"rough coat over rough copper, from below", ExactMIS(MakeCoatedConductor(1.33f, 0.2f, 0.4f, CuEta(), CuK(), 0.05f, SampledSpectrum(0), 0, deep)), Dir(130, 200)}, 14);
}

// White furnace: a lossless coat (zero thickness: no attenuation, no medium) over a near-perfect
// mirror (reflectance 0.9999 -> eta 1, k ~ 200, divided by the coat's index) reflects everything
// but the mirror's ~1e-4 per bounce; a rough base loses its microfacet multiple scattering, so
// only albedo <= 1 holds there. Reciprocity does not hold exactly (stochastic estimates).
TEST(CoatedConductor, WhiteFurnace) {
    SampledSpectrum r(0.9999f);
    SampledSpectrum k = Sqrt(r) * 2 / Sqrt(SampledSpectrum(1) - r);
    for (Float th : {0.f, 40.f, 80.f}) {
        BSDF b = MakeCoatedConductor(1.5f, 0, 0, SampledSpectrum(1) / 1.5f, k / 1.5f, 0, SampledSpectrum(0), 0, 100);
        MeanEstimate e = SampledAlbedo(b, Dir(th, 0), 20000, 21);
        EXPECT_GT(e.mean, 0.995) << "theta " << th;
        EXPECT_LE(e.mean, 1 + 1e-5) << "theta " << th;
        for (Float cr : {0.f, 0.3f}) {
            BSDF rough = MakeCoatedConductor(1.5f, 0.3f, cr, SampledSpectrum(1) / 1.5f, k / 1.5f, 0.1f,
                                             SampledSpectrum(1), 0.2f, 100);
            MeanEstimate er = SampledAlbedo(rough, Dir(th, 0), 20000, 22);
            EXPECT_LE(er.mean, 1 + 4.5 * er.stdErr) << "theta " << th << " conductor roughness " << cr;
            // Rough interfaces lose their single-scattering microfacet deficit at every one of the
            // many internal bounces (pbrt-v4's model; measured 0.51-0.61 here): a sanity bound.
            EXPECT_GT(er.mean, 0.4) << "theta " << th << " conductor roughness " << cr;
        }
    }
}

}  // namespace
}  // namespace lu::test
