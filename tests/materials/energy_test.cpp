// Energy, Fresnel, reciprocity and Dirac-lobe tests of the BxDFs: white furnaces, analytic
// Fresnel reflectance, f(wo,wi) = f(wi,wo) (and the eta^2 relation across transmission), and
// SpecularLobes agreeing with Sample_f's Dirac samples.
#include <gtest/gtest.h>

#include "materials/bxdf_test_helpers.h"

namespace lu::test {
namespace {

// ---- Fresnel ----

// Textbook unpolarized Fresnel reflectance from outside (n1 = 1, n2 = eta) in double precision.
double FresnelReference(double cosI, double eta) {
    double sinI = std::sqrt(std::max(0.0, 1 - cosI * cosI));
    double sinT = sinI / eta;
    if (sinT >= 1) return 1;
    double cosT = std::sqrt(1 - sinT * sinT);
    double rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    double rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5 * (rs * rs + rp * rp);
}

TEST(Fresnel, DielectricMatchesAnalytic) {
    for (double eta : {1.33, 1.5, 2.4, 1 / 1.5}) {
        for (int i = 0; i <= 90; ++i) {
            double theta = Radians(Float(i));
            double c = std::cos(theta);
            EXPECT_NEAR(FrDielectric(Float(c), Float(eta)), FresnelReference(c, eta), 2e-5) << "eta " << eta << " deg " << i;
            // From inside: the relative index inverts.
            EXPECT_NEAR(FrDielectric(Float(-c), Float(eta)), FresnelReference(c, 1 / eta), 2e-5) << "inside, eta " << eta;
        }
        // Normal incidence: ((eta - 1) / (eta + 1))^2.
        EXPECT_NEAR(FrDielectric(1, Float(eta)), Sqr((eta - 1) / (eta + 1)), 1e-6);
        // Brewster angle: the parallel component vanishes, R = r_perp^2 / 2.
        double thetaB = std::atan(eta), cB = std::cos(thetaB), sB = std::sin(thetaB);
        double cT = std::sqrt(1 - Sqr(sB / eta));
        double rPerp = (cB - eta * cT) / (cB + eta * cT);
        EXPECT_NEAR(FrDielectric(Float(cB), Float(eta)), 0.5 * rPerp * rPerp, 1e-5);
    }
    // Total internal reflection beyond the critical angle (inside glass, eta = 1.5).
    double critical = std::asin(1 / 1.5);
    EXPECT_EQ(FrDielectric(-Float(std::cos(critical + 0.01)), 1.5f), 1.0f);
    EXPECT_LT(FrDielectric(-Float(std::cos(critical - 0.01)), 1.5f), 1.0f);
    // eta = 1: no reflection at all.
    EXPECT_NEAR(FrDielectric(0.3f, 1.0f), 0.0f, 1e-7f);
}

TEST(Fresnel, Conductor) {
    // Normal incidence: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
    for (auto nk : {std::pair<double, double>{0.2, 3.9}, {1.1, 1.9}, {1.0, 0.0}, {2.5, 0.5}}) {
        double ref = (Sqr(nk.first - 1) + Sqr(nk.second)) / (Sqr(nk.first + 1) + Sqr(nk.second));
        EXPECT_NEAR(FrComplex(1, Complex(Float(nk.first), Float(nk.second))), ref, 1e-5);
    }
    // k = 0 reduces to the dielectric formula; grazing incidence reflects everything.
    for (int i = 0; i < 90; i += 7) {
        Float c = std::cos(Radians(Float(i)));
        EXPECT_NEAR(FrComplex(c, Complex(1.5f, 0)), FrDielectric(c, 1.5f), 1e-5);
    }
    EXPECT_NEAR(FrComplex(0, Complex(0.2f, 3.9f)), 1.0, 1e-5);
    // pbrt-v4's reflectance -> (eta = 1, k = 2 sqrt(r) / sqrt(1 - r)) gives F(normal) = r.
    for (Float r : {0.1f, 0.5f, 0.9f}) {
        Float k = 2 * std::sqrt(r) / std::sqrt(1 - r);
        EXPECT_NEAR(FrComplex(1, Complex(1, k)), r, 1e-5);
    }
}

TEST(Scattering, HenyeyGreensteinSampling) {
    // pbrt-v4 convention: wo and wi point away, so the mean of dot(wo, wi) is -g; the returned
    // pdf is the phase function value (perfect importance sampling), which integrates to 1.
    Vec3f wo = Normalize(Vec3f(0.3f, -0.4f, 0.5f));
    for (Float g : {-0.7f, -0.2f, 0.f, 0.5f, 0.9f}) {
        RNG rng(31, 7);
        double sumCos = 0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            Float pdf;
            Vec3f wi = SampleHenyeyGreenstein(wo, g, Vec2f(rng.UniformFloat(), rng.UniformFloat()), &pdf);
            ASSERT_NEAR(Length(wi), 1, 1e-4f);
            ASSERT_NEAR(pdf, HenyeyGreenstein(Dot(wo, wi), g), 2e-3f * pdf);
            sumCos += Dot(wo, wi);
        }
        EXPECT_NEAR(sumCos / n, -g, 0.006) << "g " << g;
        double integral = 0;
        for (int i = 0; i < 2000; ++i) integral += 2 * Pi * HenyeyGreenstein(-1 + 2 * (i + 0.5f) / 2000, g) * (2.0 / 2000);
        EXPECT_NEAR(integral, 1, 2e-3) << "g " << g;
    }
}

// ---- White furnaces ----

TEST(Energy, DiffuseAlbedoIsReflectance) {
    SampledSpectrum R = Spec(0.2f, 0.5f, 0.8f, 1.0f);
    BSDF b = MakeDiffuse(R);
    for (Float th : {0.f, 40.f, 89.f, 130.f}) {
        Vec3f wo = b.shadingFrame.FromLocal(Dir(th, 33));
        RNG rng(7, 1);
        for (int i = 0; i < 1000; ++i) {
            BSDFSample bs;
            ASSERT_TRUE(b.Sample_f(wo, rng.UniformFloat(), Vec2f(rng.UniformFloat(), rng.UniformFloat()), &bs));
            SampledSpectrum w = bs.f * (AbsDot(bs.wi, b.shadingFrame.z) / bs.pdf);
            for (int c = 0; c < NSpectrumSamples; ++c) ASSERT_NEAR(w[c], R[c], 1e-5f);
            ASSERT_TRUE(SameHemisphere(b.shadingFrame.ToLocal(bs.wi), b.shadingFrame.ToLocal(wo)));
        }
    }
}

TEST(Energy, SmoothDielectricConservesEnergy) {
    for (Float eta : {1.33f, 1.5f, 2.4f}) {
        BSDF b = MakeDielectric(eta, 0, 0);
        ASSERT_TRUE(b.IsSpecular());
        for (Float th : {0.f, 30.f, 60.f, 85.f, 100.f, 130.f, 160.f, 179.f}) {
            Vec3f woL = Dir(th, 70);
            Vec3f wo = b.shadingFrame.FromLocal(woL);
            int nR = 0, nT = 0;
            for (int i = 0; i < 200; ++i) {
                Float uc = (i + 0.5f) / 200;
                BSDFSample bs;
                ASSERT_TRUE(b.Sample_f(wo, uc, Vec2f(0.5f, 0.5f), &bs, TransportMode::Importance));
                // Importance mode: each sample weighs R / pr = T / pt = 1 (reflects + transmits exactly 1).
                Float w = bs.f[0] * AbsDot(bs.wi, b.shadingFrame.z) / bs.pdf;
                ASSERT_NEAR(w, 1, 1e-4f) << "eta " << eta << " theta " << th;
                BSDFSample br;
                ASSERT_TRUE(b.Sample_f(wo, uc, Vec2f(0.5f, 0.5f), &br, TransportMode::Radiance));
                Float wr = br.f[0] * AbsDot(br.wi, b.shadingFrame.z) / br.pdf;
                if (br.IsTransmission()) {
                    ++nT;
                    // Radiance mode scales transmission by 1 / eta'^2, eta' = n_t / n_i.
                    ASSERT_NEAR(wr, 1 / Sqr(br.eta), 1e-4f);
                    ASSERT_NEAR(br.eta, woL.z > 0 ? eta : 1 / eta, 1e-6f);
                    // Snell's law.
                    Vec3f wi = b.shadingFrame.ToLocal(br.wi);
                    ASSERT_NEAR(woL.x + br.eta * wi.x, 0, 1e-4f);
                    ASSERT_NEAR(woL.y + br.eta * wi.y, 0, 1e-4f);
                    ASSERT_LT(wi.z * woL.z, 0);
                } else {
                    ++nR;
                    ASSERT_NEAR(wr, 1, 1e-4f);
                }
            }
            // The reflection probability is Fresnel's R (stratified uc: exact up to 1/200).
            Float R = FrDielectric(woL.z, eta);
            EXPECT_NEAR(nR / 200.0, R, 1.0 / 200 + 1e-6) << "eta " << eta << " theta " << th;
        }
    }
}

TEST(Energy, IndexMatchedDielectricPassesThrough) {
    for (Float alpha : {0.f, 0.3f}) {
        BSDF b = MakeDielectric(1, alpha, alpha);
        EXPECT_TRUE(b.IsSpecular());
        Vec3f wo = b.shadingFrame.FromLocal(Dir(35, 10));
        BSDFSample bs;
        ASSERT_TRUE(b.Sample_f(wo, 0.3f, Vec2f(0.2f, 0.7f), &bs));
        EXPECT_TRUE(bs.IsTransmission() && bs.IsSpecular());
        EXPECT_NEAR(Distance(bs.wi, -wo), 0, 1e-5f);
        EXPECT_NEAR(bs.f[0] * AbsDot(bs.wi, b.shadingFrame.z) / bs.pdf, 1, 1e-5f);
        EXPECT_EQ(b.f(wo, -wo)[0], 0);
        EXPECT_EQ(b.PDF(wo, -wo), 0);
    }
}

TEST(Energy, ThinDielectric) {
    BSDF b = MakeThinDielectric(1.5f);
    ASSERT_TRUE(b.IsSpecular());
    for (Float th : {0.f, 45.f, 80.f, 120.f}) {
        Vec3f woL = Dir(th, 10);
        Vec3f wo = b.shadingFrame.FromLocal(woL);
        // Slab reflectance R' = R + T^2 R / (1 - R^2) (all inner bounces summed).
        Float R = FrDielectric(AbsCosTheta(woL), 1.5f), T = 1 - R;
        Float Rs = R + T * T * R / (1 - R * R);
        int nR = 0;
        for (int i = 0; i < 400; ++i) {
            BSDFSample bs;
            ASSERT_TRUE(b.Sample_f(wo, (i + 0.5f) / 400, Vec2f(0.5f, 0.5f), &bs));
            ASSERT_NEAR(bs.f[0] * AbsDot(bs.wi, b.shadingFrame.z) / bs.pdf, 1, 1e-4f);
            if (bs.IsReflection()) {
                ++nR;
            } else {
                ASSERT_NEAR(Distance(bs.wi, -wo), 0, 1e-5f);   // straight through
            }
        }
        EXPECT_NEAR(nR / 400.0, Rs, 1.0 / 400 + 1e-6);
    }
}

// Albedo of a rough BSDF two ways: the mean Sample_f weight (MC) and adaptive quadrature of
// f |cos| over the sphere; they must agree within the MC error (checks f/pdf normalization).
void CheckAlbedo(const char *name, const BSDF &b, Vec3f woL, TransportMode mode, double maxAlbedo, uint64_t seed) {
    SCOPED_TRACE(name);
    MeanEstimate mc = SampledAlbedo(b, woL, 200000, seed, 0, mode);
    Vec3f wo = b.shadingFrame.FromLocal(Normalize(woL));
    AdaptiveIntegrator2D integ([&](double th, double ph) {
        Vec3f wl = DirD(th, ph);
        return double(b.f(wo, b.shadingFrame.FromLocal(wl), mode)[0]) * std::abs(wl.z) * std::sin(th);
    }, 1e-5, 1e-10, 7);
    double quad = 0;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j)
            quad += integ.Integrate(M_PI * i / 16, M_PI * (i + 1) / 16, 2 * M_PI * j / 16, 2 * M_PI * (j + 1) / 16);
    if (getenv("LU_VERBOSE")) printf("%s: mc %.5f +- %.5f quad %.5f evals %ld\n", name, mc.mean, mc.stdErr, quad, integ.evaluations);
    EXPECT_NEAR(mc.mean, quad, 5 * mc.stdErr + 2e-3 * quad) << "mc " << mc.mean << " +- " << mc.stdErr << " quad " << quad;
    EXPECT_LE(quad, maxAlbedo + 1e-3);
    EXPECT_LE(mc.mean, maxAlbedo + 5 * mc.stdErr);
}

TEST(Energy, RoughConductorFurnace) {
    // eta = 1, k = 0: no reflection at all.
    BSDF black = MakeConductor(0.3f, 0.3f, SampledSpectrum(1), SampledSpectrum(0));
    Vec3f wo = black.shadingFrame.FromLocal(Dir(30, 0));
    EXPECT_EQ(black.f(wo, black.shadingFrame.FromLocal(Dir(30, 180)))[0], 0);
    BSDFSample bs;
    EXPECT_FALSE(black.Sample_f(wo, 0.5f, Vec2f(0.3f, 0.6f), &bs));
    // k -> infinity: F = 1, a white furnace; single scattering only loses energy.
    SampledSpectrum eta(1), k(1e4f);
    for (Float a : {0.05f, 0.3f, 0.8f}) {
        for (Float th : {0.f, 60.f, 85.f}) {
            BSDF b = MakeConductor(a, a, eta, k);
            std::string name = "alpha " + std::to_string(a) + " theta " + std::to_string(th);
            CheckAlbedo(name.c_str(), b, Dir(th, 15), TransportMode::Radiance, 1.0, 100 + int(th));
        }
    }
    // Nearly smooth: almost all energy is kept.
    MeanEstimate e = SampledAlbedo(MakeConductor(0.05f, 0.05f, eta, k), Dir(20, 0), 100000, 5);
    EXPECT_GT(e.mean, 0.99);
    MeanEstimate ea = SampledAlbedo(MakeConductor(0.05f, 0.4f, eta, k), Dir(50, 60), 100000, 6);
    EXPECT_LE(ea.mean, 1 + 5 * ea.stdErr);
    EXPECT_GT(ea.mean, 0.85);
}

TEST(Energy, RoughDielectricFurnace) {
    // In Importance mode (wi and wo swapped relative to the light) energy is conserved: <= 1.
    struct C { Float eta, alpha, theta; };
    for (C c : {C{1.5f, 0.3f, 30}, C{1.5f, 0.3f, 150}, C{1.33f, 0.6f, 70}, C{2.4f, 0.2f, 120}, C{1.5f, 0.1f, 95}}) {
        BSDF b = MakeDielectric(c.eta, c.alpha, c.alpha);
        std::string name = "eta " + std::to_string(c.eta) + " alpha " + std::to_string(c.alpha) + " theta " +
                           std::to_string(c.theta);
        CheckAlbedo(name.c_str(), b, Dir(c.theta, 25), TransportMode::Importance, 1.0, 200 + int(c.theta));
        // Radiance mode from outside: transmission is scaled by 1/eta^2 < 1.
        if (c.theta < 90 && c.eta > 1)
            CheckAlbedo((name + " radiance").c_str(), b, Dir(c.theta, 25), TransportMode::Radiance, 1.0, 300);
    }
}

// ---- Reciprocity ----

TEST(Reciprocity, ReflectionIsSymmetric) {
    std::vector<BSDF> bsdfs = {MakeDiffuse(SampledSpectrum(0.6f)),
                               MakeConductor(0.2f, 0.2f, Spec(0.2f, 0.4f, 1.1f, 1.5f), Spec(3.9f, 2.5f, 1.9f, 1.8f)),
                               MakeConductor(0.1f, 0.5f, SampledSpectrum(1.3f), SampledSpectrum(2.0f)),
                               MakeDielectric(1.5f, 0.3f, 0.3f), MakeDielectric(2.4f, 0.15f, 0.45f),
                               MakeDiffuseTransmission(SampledSpectrum(0.3f), SampledSpectrum(0.5f))};
    RNG rng(99, 3);
    for (const BSDF &b : bsdfs) {
        int checked = 0;
        for (int i = 0; i < 2000; ++i) {
            Vec3f a = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
            Vec3f c = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
            if (!SameHemisphere(a, c) || std::abs(a.z) < 0.02f || std::abs(c.z) < 0.02f) continue;
            Vec3f wo = b.shadingFrame.FromLocal(a), wi = b.shadingFrame.FromLocal(c);
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                SampledSpectrum f1 = b.f(wo, wi, mode), f2 = b.f(wi, wo, mode);
                for (int k = 0; k < NSpectrumSamples; ++k)
                    ASSERT_NEAR(f1[k], f2[k], 1e-4f * std::max(f1[k], f2[k]) + 1e-7f) << "kind " << int(b.kind);
            }
            ++checked;
        }
        EXPECT_GT(checked, 500);
    }
}

TEST(Reciprocity, TransmissionEtaSquared) {
    for (Float eta : {1.33f, 1.5f, 2.4f}) {
        BSDF b = MakeDielectric(eta, 0.35f, 0.2f);
        RNG rng(17, 5);
        int nonzero = 0;
        for (int i = 0; i < 3000; ++i) {
            Vec3f a = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
            Vec3f c = SampleUniformSphere(Vec2f(rng.UniformFloat(), rng.UniformFloat()));
            if (SameHemisphere(a, c) || std::abs(a.z) < 0.02f || std::abs(c.z) < 0.02f) continue;
            Vec3f wo = b.shadingFrame.FromLocal(a), wi = b.shadingFrame.FromLocal(c);
            Float fr = b.f(wo, wi, TransportMode::Radiance)[0], frRev = b.f(wi, wo, TransportMode::Radiance)[0];
            Float fi = b.f(wo, wi, TransportMode::Importance)[0], fiRev = b.f(wi, wo, TransportMode::Importance)[0];
            // Radiance BTDF: f(wo, wi) / n_i^2 = f(wi, wo) / n_o^2, i.e. f(wo,wi) etap^2 = f(wi,wo),
            // etap = n_i / n_o (= eta when wo is outside).
            Float etap = a.z > 0 ? eta : 1 / eta;
            // Skip float-degenerate pairs where a direction is nearly tangent to the half vector
            // (the BTDF vanishes there and its backfacing test flips on rounding).
            Vec3f wm = Normalize(c * etap + a);
            if (std::abs(Dot(wm, a)) < 0.05f || std::abs(Dot(wm, c)) < 0.05f) continue;
            ASSERT_NEAR(fr * Sqr(etap), frRev, 1e-3f * std::max(fr * Sqr(etap), frRev) + 1e-8f);
            // The adjoint: Radiance-mode f(wo, wi) is Importance-mode f(wi, wo).
            ASSERT_NEAR(fr, fiRev, 1e-3f * std::max(fr, fiRev) + 1e-8f);
            ASSERT_NEAR(fi, frRev, 1e-3f * std::max(fi, frRev) + 1e-8f);
            if (fr > 0) ++nonzero;
        }
        EXPECT_GT(nonzero, 200);
    }
}

// ---- Dirac lobes ----

// Every Dirac sample of Sample_f matches one SpecularLobes entry: same direction, and
// weight = f |cos| / pdf * (choice probability = pdf), i.e. f |cos|; the lobes' choice
// probabilities sum to 1 (no lobe missing).
void CheckLobes(const BSDF &b, Vec3f woL, TransportMode mode, const char *name) {
    SCOPED_TRACE(name);
    Vec3f wo = b.shadingFrame.FromLocal(woL);
    SpecularLobe lobes[2];
    int n = b.SpecularLobes(wo, lobes, mode);
    ASSERT_GE(n, 1);
    double probSeen[2] = {0, 0};
    const int N = 256;
    for (int i = 0; i < N; ++i) {
        BSDFSample bs;
        if (!b.Sample_f(wo, (i + 0.5f) / N, Vec2f(0.37f, 0.61f), &bs, mode)) continue;
        if (!bs.IsSpecular()) continue;
        int match = -1;
        for (int l = 0; l < n; ++l)
            if (Distance(lobes[l].wi, bs.wi) < 1e-4f) match = l;
        ASSERT_GE(match, 0) << "sample direction not among the lobes";
        EXPECT_EQ(lobes[match].flags, bs.flags);
        EXPECT_NEAR(lobes[match].eta, bs.eta, 1e-6f);
        SampledSpectrum w = bs.f * (AbsDot(bs.wi, b.shadingFrame.z) / bs.pdf) * bs.pdf;
        for (int k = 0; k < NSpectrumSamples; ++k)
            EXPECT_NEAR(lobes[match].weight[k], w[k], 1e-5f + 1e-4f * w[k]);
        probSeen[match] = bs.pdf;
        // The lobe-aware MIS of the regularized connection uses the lobe's selection probability.
        EXPECT_NEAR(lobes[match].pdf, bs.pdf, 1e-5f) << "lobe " << match;
    }
    if (b.IsSpecular()) {
        EXPECT_NEAR(probSeen[0] + probSeen[1], 1, 1e-5);
    }
    for (int l = 0; l < n; ++l) EXPECT_GT(probSeen[l], 0) << "lobe " << l << " never sampled";
}

TEST(SpecularLobes, MatchSample_f) {
    BSDF gold = MakeConductor(0, 0, Spec(0.2f, 0.4f, 1.1f, 1.5f), Spec(3.9f, 2.5f, 1.9f, 1.8f));
    EXPECT_TRUE(gold.IsSpecular());
    CheckLobes(gold, Dir(40, 20), TransportMode::Radiance, "smooth conductor");
    CheckLobes(gold, Dir(130, 20), TransportMode::Radiance, "smooth conductor, back side");
    for (Float eta : {1.33f, 1.5f, 2.4f}) {
        BSDF glass = MakeDielectric(eta, 0, 0);
        for (Float th : {10.f, 70.f, 89.f, 110.f, 150.f, 175.f})
            for (TransportMode m : {TransportMode::Radiance, TransportMode::Importance})
                CheckLobes(glass, Dir(th, 50), m, "smooth dielectric");
    }
    // Total internal reflection: a single lobe of weight 1.
    BSDF glass = MakeDielectric(1.5f, 0, 0);
    SpecularLobe lobes[2];
    ASSERT_EQ(glass.SpecularLobes(glass.shadingFrame.FromLocal(Dir(130, 0)), lobes), 1);
    EXPECT_NEAR(lobes[0].weight[0], 1, 1e-6f);
    BSDF thin = MakeThinDielectric(1.5f);
    CheckLobes(thin, Dir(30, 0), TransportMode::Radiance, "thin dielectric");
    CheckLobes(thin, Dir(160, 0), TransportMode::Radiance, "thin dielectric, back side");
    // Coated diffuse with a smooth coat: its Dirac part is the coat reflection.
    BSDF coated = MakeCoated(1.5f, 0, SampledSpectrum(0.5f), 0.01f, SampledSpectrum(0), 0);
    EXPECT_FALSE(coated.IsSpecular());
    CheckLobes(coated, Dir(50, 0), TransportMode::Radiance, "coated diffuse");
    CheckLobes(coated, Dir(140, 0), TransportMode::Radiance, "coated diffuse, back side");
    // Rough BSDFs have no Dirac lobes.
    EXPECT_EQ(MakeConductor(0.2f, 0.2f, SampledSpectrum(1), SampledSpectrum(3)).SpecularLobes(Vec3f(0, 0, 1), lobes), 0);
    EXPECT_EQ(MakeDiffuse(SampledSpectrum(0.5f)).SpecularLobes(Vec3f(0, 0, 1), lobes), 0);
    EXPECT_FALSE(MakeDielectric(1.5f, 0.2f, 0.2f).IsSpecular());
}

TEST(Flags, MatchPbrt) {
    EXPECT_EQ(MakeDiffuse(SampledSpectrum(0.5f)).Flags(), BxDF_DiffuseReflection);
    EXPECT_EQ(MakeDiffuse(SampledSpectrum(0)).Flags(), BxDF_Unset);
    EXPECT_EQ(MakeConductor(0, 0, SampledSpectrum(1), SampledSpectrum(1)).Flags(), BxDF_SpecularReflection);
    EXPECT_EQ(MakeConductor(0.0009f, 0.5f, SampledSpectrum(1), SampledSpectrum(1)).Flags(), BxDF_GlossyReflection);
    EXPECT_EQ(MakeConductor(0.0009f, 0.0009f, SampledSpectrum(1), SampledSpectrum(1)).Flags(), BxDF_SpecularReflection);
    EXPECT_EQ(MakeDielectric(1.5f, 0, 0).Flags(), BxDF_Reflection | BxDF_Transmission | BxDF_Specular);
    EXPECT_EQ(MakeDielectric(1.5f, 0.1f, 0.1f).Flags(), BxDF_Reflection | BxDF_Transmission | BxDF_Glossy);
    EXPECT_EQ(MakeDielectric(1, 0, 0).Flags(), BxDF_Transmission | BxDF_Specular);
    EXPECT_EQ(MakeThinDielectric(1.5f).Flags(), BxDF_Reflection | BxDF_Transmission | BxDF_Specular);
    EXPECT_EQ(MakeCoated(1.5f, 0, SampledSpectrum(0.5f), 0.01f, SampledSpectrum(0), 0).Flags(),
              BxDF_Reflection | BxDF_Specular | BxDF_Diffuse);
    EXPECT_EQ(MakeCoated(1.5f, 0.2f, SampledSpectrum(0), 0.01f, SampledSpectrum(0), 0).Flags(),
              BxDF_Reflection | BxDF_Glossy);
}

}  // namespace
}  // namespace lu::test
