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
    Chi2Result r = Chi2TestBSDF(c.bsdf, c.wo, kSamples, seed);
    SCOPED_TRACE(c.name);
    if (getenv("LU_VERBOSE")) printf("%s: %s mism=%ld\n", c.name, r.message.c_str(), r.mismatches);
    EXPECT_GT(r.pValue, Chi2Threshold()) << r.message;
    EXPECT_EQ(r.mismatches, 0) << r.firstMismatch;
    EXPECT_LE(r.integral, 1.0 + 1e-3) << r.message;
}

SampledSpectrum GoldEta() { return Spec(0.2f, 0.4f, 1.1f, 1.5f); }
SampledSpectrum GoldK() { return Spec(3.9f, 2.5f, 1.9f, 1.8f); }
Float Remap(Float r) { return TrowbridgeReitzDistribution::RoughnessToAlpha(r); }

TEST(Chi2, Diffuse) {
    RunChi2({"diffuse above", MakeDiffuse(SampledSpectrum(0.7f)), Dir(30, 10)}, 1);
    RunChi2({"diffuse below", MakeDiffuse(SampledSpectrum(0.7f)), Dir(150, 200)}, 2);
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
    Chi2Result r = Chi2TestBSDF(MakeDielectric(1.5f, 0.4f, 0.4f), Dir(35, 20), kSamples, 21, TransportMode::Importance);
    EXPECT_GT(r.pValue, Chi2Threshold()) << r.message;
    EXPECT_EQ(r.mismatches, 0) << r.firstMismatch;
    r = Chi2TestBSDF(MakeDielectric(1.5f, 0.4f, 0.4f), Dir(140, 20), kSamples, 22, TransportMode::Importance);
    EXPECT_GT(r.pValue, Chi2Threshold()) << r.message;
    EXPECT_EQ(r.mismatches, 0) << r.firstMismatch;
}

// The chi-square test must be able to fail: a pdf that disagrees with the sampler (a conductor
// sampled with one roughness, evaluated with another) is rejected.
TEST(Chi2, DetectsWrongPdf) {
    BSDF sampled = MakeConductor(0.3f, 0.3f, GoldEta(), GoldK());
    BSDF wrong = MakeConductor(0.33f, 0.33f, GoldEta(), GoldK());
    Vec3f wo = sampled.shadingFrame.FromLocal(Dir(40, 0));
    std::vector<double> obs(20 * 40 + 1, 0), expct(20 * 40 + 1, 0);
    RNG rng(23, 1);
    for (long i = 0; i < kSamples; ++i) {
        BSDFSample bs;
        if (!sampled.Sample_f(wo, rng.UniformFloat(), Vec2f(rng.UniformFloat(), rng.UniformFloat()), &bs)) {
            obs.back() += 1;
            continue;
        }
        Vec3f wl = sampled.shadingFrame.ToLocal(bs.wi);
        double th = std::acos(std::clamp(double(wl.z), -1.0, 1.0)), ph = std::atan2(double(wl.y), double(wl.x));
        if (ph < 0) ph += 2 * M_PI;
        obs[size_t(std::min(19, int(th / M_PI * 20)) * 40 + std::min(39, int(ph / (2 * M_PI) * 40)))] += 1;
    }
    AdaptiveIntegrator2D integ([&](double th, double ph) {
        return double(wrong.PDF(wo, wrong.shadingFrame.FromLocal(DirD(th, ph)))) * std::sin(th);
    });
    double total = 0;
    for (int ti = 0; ti < 20; ++ti)
        for (int pi = 0; pi < 40; ++pi) {
            double v = integ.Integrate(M_PI * ti / 20, M_PI * (ti + 1) / 20, 2 * M_PI * pi / 40, 2 * M_PI * (pi + 1) / 40);
            expct[size_t(ti * 40 + pi)] = v * kSamples;
            total += v;
        }
    expct.back() = std::max(0.0, 1 - total) * kSamples;
    std::string msg;
    EXPECT_LT(ChiSquarePValue(obs, expct, &msg), 1e-8) << msg;
}

}  // namespace
}  // namespace lu::test
