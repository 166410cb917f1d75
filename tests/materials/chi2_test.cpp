// Chi-square tests of every non-Dirac BxDF's sampler against its pdf (Sidak-corrected 1e-4
// level over the suite), with the per-sample check that Sample_f's f/pdf equal f()/PDF().
#include <gtest/gtest.h>

#include "materials/bxdf_test_helpers.h"

namespace lu::test {
namespace {

constexpr long kSamples = 400000;

struct Chi2Case {
    const char *name;
    BSDF bsdf;
    Vec3f wo;   // local
};

void RunChi2(const Chi2Case &c, uint64_t seed) {
    BSDFChi2 r = Chi2TestBSDF(c.bsdf, c.wo, kSamples, seed);
    SCOPED_TRACE(c.name);
    if (getenv("LU_VERBOSE")) printf("%s: %s mism=%ld\n", c.name, r.chi2.message.c_str(), r.mismatches);
    EXPECT_TRUE(Chi2Accepts(r.chi2, 1e-4, NumChi2Tests));
    EXPECT_EQ(r.mismatches, 0) << r.firstMismatch;
    EXPECT_LE(r.chi2.pdfIntegral, 1.0 + 1e-3) << r.chi2.message;
}

SampledSpectrum GoldEta() { return Spec(0.2f, 0.4f, 1.1f, 1.5f); }
SampledSpectrum GoldK() { return Spec(3.9f, 2.5f, 1.9f, 1.8f); }
Float Remap(Float r) { return TrowbridgeReitzDistribution::RoughnessToAlpha(r); }

TEST(Chi2, Diffuse) {
    RunChi2({"diffuse above", MakeDiffuse(SampledSpectrum(0.7f)), Dir(30, 10)}, 1);
    RunChi2({"diffuse below", MakeDiffuse(SampledSpectrum(0.7f)), Dir(150, 200)}, 2);
}

TEST(Chi2, DiffuseTransmission) {
    // Lobe choice by the largest component of R and T: unequal channels test the pdf's weights.
    RunChi2({"diffusetransmission above", MakeDiffuseTransmission(Spec(0.2f, 0.5f, 0.3f, 0.1f), Spec(0.7f, 0.2f, 0.1f, 0.4f)), Dir(35, 15)}, 25);
    RunChi2({"diffusetransmission below, T only", MakeDiffuseTransmission(SampledSpectrum(0), SampledSpectrum(0.6f)), Dir(140, 60)}, 26);
}

TEST(Chi2, ConductorIsotropic) {
    RunChi2({"conductor r=0.05 (remapped), 30 deg", MakeConductor(Remap(0.05f), Remap(0.05f), GoldEta(), GoldK()), Dir(30, 40)}, 3);
    RunChi2({"conductor r=0.3 (remapped), 60 deg", MakeConductor(Remap(0.3f), Remap(0.3f), GoldEta(), GoldK()), Dir(60, 100)}, 4);
    RunChi2({"conductor r=0.8 (remapped), 10 deg", MakeConductor(Remap(0.8f), Remap(0.8f), GoldEta(), GoldK()), Dir(10, 0)}, 5);
    RunChi2({"conductor alpha=0.05, 45 deg", MakeConductor(0.05f, 0.05f, GoldEta(), GoldK()), Dir(45, 300)}, 6);
    RunChi2({"conductor alpha=0.3, grazing 85 deg", MakeConductor(0.3f, 0.3f, GoldEta(), GoldK()), Dir(85, 20)}, 7);
    RunChi2({"conductor alpha=0.3, from below", MakeConductor(0.3f, 0.3f, GoldEta(), GoldK()), Dir(120, 70)}, 8);
}

TEST(Chi2, ConductorAnisotropic) {
    RunChi2({"conductor alpha=(0.05,0.3), 45 deg", MakeConductor(0.05f, 0.3f, GoldEta(), GoldK()), Dir(45, 30)}, 9);
    RunChi2({"conductor alpha=(0.5,0.1), 70 deg", MakeConductor(0.5f, 0.1f, GoldEta(), GoldK()), Dir(70, 120)}, 10);
}

TEST(Chi2, DielectricOutside) {
    RunChi2({"dielectric 1.5 alpha=0.3, 30 deg", MakeDielectric(1.5f, 0.3f, 0.3f), Dir(30, 0)}, 11);
    RunChi2({"dielectric 1.33 r=0.05 (remapped), 60 deg", MakeDielectric(1.33f, Remap(0.05f), Remap(0.05f)), Dir(60, 45)}, 12);
    RunChi2({"dielectric 2.4 alpha=0.2, 45 deg", MakeDielectric(2.4f, 0.2f, 0.2f), Dir(45, 250)}, 13);
    RunChi2({"dielectric 1.5 alpha=(0.1,0.4), 50 deg", MakeDielectric(1.5f, 0.1f, 0.4f), Dir(50, 80)}, 14);
    RunChi2({"dielectric 1.5 r=0.8 (remapped), grazing 85 deg", MakeDielectric(1.5f, Remap(0.8f), Remap(0.8f)), Dir(85, 10)}, 15);
    RunChi2({"dielectric 1/1.5 alpha=0.3, 40 deg", MakeDielectric(1 / 1.5f, 0.3f, 0.3f), Dir(40, 10)}, 16);
}

TEST(Chi2, DielectricInside) {
    RunChi2({"dielectric 1.5 alpha=0.3, inside 150 deg", MakeDielectric(1.5f, 0.3f, 0.3f), Dir(150, 30)}, 17);
    RunChi2({"dielectric 1.33 alpha=0.5, inside 160 deg", MakeDielectric(1.33f, 0.5f, 0.5f), Dir(160, 300)}, 18);
    RunChi2({"dielectric 2.4 alpha=0.2, inside 120 deg (TIR)", MakeDielectric(2.4f, 0.2f, 0.2f), Dir(120, 100)}, 19);
    RunChi2({"dielectric 1.5 alpha=0.1, inside grazing 95 deg", MakeDielectric(1.5f, 0.1f, 0.1f), Dir(95, 0)}, 20);
}

TEST(Chi2, DielectricImportanceMode) {
    // The pdf does not depend on the mode, but Sample_f's f does; run the same test in Importance mode.
    BSDFChi2 r = Chi2TestBSDF(MakeDielectric(1.5f, 0.4f, 0.4f), Dir(35, 20), kSamples, 21, TransportMode::Importance);
    EXPECT_TRUE(Chi2Accepts(r.chi2, 1e-4, NumChi2Tests));
    EXPECT_EQ(r.mismatches, 0) << r.firstMismatch;
    r = Chi2TestBSDF(MakeDielectric(1.5f, 0.4f, 0.4f), Dir(140, 20), kSamples, 22, TransportMode::Importance);
    EXPECT_TRUE(Chi2Accepts(r.chi2, 1e-4, NumChi2Tests));
    EXPECT_EQ(r.mismatches, 0) << r.firstMismatch;
}

// The chi-square test must be able to fail: pdfs that disagree with the sampler are rejected
// (a conductor sampled with one roughness and evaluated with another; a dielectric whose pdf
// uses another index of refraction, which moves the transmission lobe).
TEST(Chi2, DetectsWrongPdf) {
    BSDF sampled = MakeConductor(0.3f, 0.3f, GoldEta(), GoldK());
    BSDF wrong = MakeConductor(0.33f, 0.33f, GoldEta(), GoldK());
    BSDFChi2 r = Chi2TestBSDF(sampled, Dir(40, 0), kSamples, 23, TransportMode::Radiance, 20, 40, &wrong);
    EXPECT_TRUE(Chi2Rejects(r.chi2, 1e-4, NumChi2Tests));
    BSDF glass = MakeDielectric(1.5f, 0.3f, 0.3f), otherGlass = MakeDielectric(1.45f, 0.3f, 0.3f);
    r = Chi2TestBSDF(glass, Dir(30, 0), kSamples, 24, TransportMode::Radiance, 20, 40, &otherGlass);
    EXPECT_TRUE(Chi2Rejects(r.chi2, 1e-4, NumChi2Tests));
    // The right pdf for the same samples passes (the rejections are the pdfs' doing).
    r = Chi2TestBSDF(sampled, Dir(40, 0), kSamples, 23);
    EXPECT_TRUE(Chi2Accepts(r.chi2, 1e-4, NumChi2Tests));
}

// Henyey-Greenstein phase sampling (media vertices) against its density over the sphere, for
// back-, iso- and forward scattering, with a wrong-g control that must be rejected.
TEST(Chi2, HenyeyGreenstein) {
    Vec3f wo = Normalize(Vec3f(0.3f, -0.5f, 0.8f));
    auto run = [&](Float gSample, Float gPdf, uint64_t seed) {
        RNG rng(seed, 5);
        Chi2Options opts;
        opts.samples = 200000;
        return Chi2SampleTest(
            SphereDomain(20, 40),
            [&](Chi2Point *p) {
                Float pdf;
                Vec3f wi = SampleHenyeyGreenstein(wo, gSample, Vec2f(rng.UniformFloat(), rng.UniformFloat()), &pdf);
                *p = {wi.x, wi.y, wi.z};
                return pdf > 0;
            },
            [&](const Chi2Point &p) { return double(HenyeyGreenstein(Dot(wo, Vec3f(Float(p.x), Float(p.y), Float(p.z))), gPdf)); },
            opts);
    };
    uint64_t seed = 100;
    for (Float g : {-0.6f, 0.f, 0.3f, 0.85f}) {
        SCOPED_TRACE(g);
        EXPECT_TRUE(Chi2Accepts(run(g, g, ++seed), 1e-4, 4));
    }
    EXPECT_TRUE(Chi2Rejects(run(0.3f, 0.36f, 200), 1e-4, 1));
}

}  // namespace
}  // namespace lu::test
