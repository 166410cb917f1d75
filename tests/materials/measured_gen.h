// Lucerna tests: a generator of RGL tensor files (.bsdf, Dupuy & Jakob 2018) that tabulates an
// analytic BRDF, an isotropic Trowbridge-Reitz rough conductor with a smooth complex index, in
// the format's parameterization: ndf = D(wm) and sigma = the projected microsurface area over
// (theta2u, phi2u); vndf = the visible normals' density over the unit square (times its
// Jacobian 2 pi^2 u sin theta_m) for each theta_i; spectra = the reflectance F G2 / G1(wo) at the
// vertices of the vndf's sample space (warped by the vndf), luminance its CIE Y average.
// Writes the file the feature scene uses (scenes/features/measured-tr-conductor.bsdf; see
// Measured.FeatureFileIsTheGeneratorOutput).
#pragma once

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "lucerna/materials/bsdf.h"
#include "lucerna/scene/measured_file.h"
#include "lucerna/spectra/cie_data.h"

namespace lu::test {

struct MeasuredGenOptions {
    Float alpha = 0.3f;                    // Trowbridge-Reitz alpha (isotropic)
    int ndfTheta = 64, ndfPhi = 4;         // ndf and sigma vertices (x: theta2u, y: phi2u)
    int vndfRes = 48;                      // vndf vertices per side
    int sampleRes = 32;                    // luminance and spectra vertices per side
    int nThetaI = 10;                      // theta_i slices, uniform in [0, thetaIMax]
    int nPhiI = 1;                         // 1: isotropic (wm's phi relative to wo's); > 2: phi_i
                                           // slices uniform in [-pi, pi], wm's phi absolute
    Float thetaIMaxDeg = 88;               // the last slice (90 degrees: G2 / G1 is 0 / 0)
    std::vector<float> wavelengths = {400, 450, 500, 550, 600, 650, 700, 750};
};

// The analytic conductor's complex index, linear in lambda (a gold-like reddish metal).
inline Float GenEta(Float lambda) { return 1.4f + (0.2f - 1.4f) * (lambda - 400) / 350; }
inline Float GenK(Float lambda) { return 1.9f + (3.6f - 1.9f) * (lambda - 400) / 350; }

// The analytic BRDF the file tabulates, at the four wavelengths of lambda.
inline ConductorBxDF GenAnalyticConductor(const MeasuredGenOptions &o, const Float lambda[NSpectrumSamples]) {
    SampledSpectrum eta, k;
    for (int i = 0; i < NSpectrumSamples; ++i) {
        eta[i] = GenEta(lambda[i]);
        k[i] = GenK(lambda[i]);
    }
    return ConductorBxDF(TrowbridgeReitzDistribution(o.alpha, o.alpha), eta, k);
}

// ---- Tensor file writer (the layout ParseTensorFile reads) ----

struct GenField {
    std::string name;
    TensorType dtype;
    std::vector<uint64_t> shape;
    std::vector<uint8_t> bytes;
};
inline GenField FloatField(const std::string &name, std::vector<uint64_t> shape, const std::vector<float> &v) {
    GenField f{name, TensorType::Float32, std::move(shape), std::vector<uint8_t>(v.size() * 4)};
    std::memcpy(f.bytes.data(), v.data(), v.size() * 4);
    return f;
}
inline std::vector<uint8_t> WriteTensorBytes(const std::vector<GenField> &fields) {
    std::vector<uint8_t> out;
    auto put = [&](const void *p, size_t n) {
        const uint8_t *b = static_cast<const uint8_t *>(p);
        out.insert(out.end(), b, b + n);
    };
    put("tensor_file", 12);
    uint8_t version[2] = {1, 0};
    put(version, 2);
    uint32_t n = uint32_t(fields.size());
    put(&n, 4);
    uint64_t headerSize = out.size();
    for (const GenField &f : fields) headerSize += 2 + f.name.size() + 2 + 1 + 8 + 8 * f.shape.size();
    uint64_t offset = headerSize;
    for (const GenField &f : fields) {
        uint16_t len = uint16_t(f.name.size()), ndim = uint16_t(f.shape.size());
        uint8_t dtype = uint8_t(f.dtype);
        put(&len, 2);
        put(f.name.data(), len);
        put(&ndim, 2);
        put(&dtype, 1);
        put(&offset, 8);
        for (uint64_t s : f.shape) put(&s, 8);
        offset += f.bytes.size();
    }
    for (const GenField &f : fields) put(f.bytes.data(), f.bytes.size());
    return out;
}

// ---- The tabulation ----

// Projected microsurface area seen from a direction at theta (cos / G1 for Trowbridge-Reitz).
inline double GenSigma(double alpha, double theta) {
    double c = std::cos(theta), s = std::sin(theta);
    return 0.5 * (c + std::sqrt(c * c + alpha * alpha * s * s));
}
inline double GenD(double alpha, double cosTheta) {
    double c2 = cosTheta * cosTheta, a2 = alpha * alpha;
    if (c2 <= 0) return 0;
    double t2 = (1 - c2) / c2;
    return 1 / (Pi * a2 * c2 * c2 * Sqr(1 + t2 / a2));
}
inline double GenLambda(double alpha, double cosTheta) {
    double c2 = cosTheta * cosTheta;
    return (std::sqrt(1 + alpha * alpha * (1 - c2) / c2) - 1) / 2;
}
inline Float GenCIEY(float lambda) {
    int i = int(std::lround(lambda)) - 360;
    return i >= 0 && i < int(data::CIESamples) ? data::CIE_Y[i] : 0;
}

inline std::vector<uint8_t> GenerateMeasuredFile(const MeasuredGenOptions &o = {}) {
    const double alpha = o.alpha;
    std::vector<GenField> fields;
    std::string desc = "Lucerna test data: Trowbridge-Reitz conductor, alpha " + std::to_string(o.alpha) +
                       ", eta 1.4..0.2, k 1.9..3.6 over 400..750 nm (tests/materials/measured_gen.h)";
    fields.push_back({"description", TensorType::UInt8, {desc.size()}, std::vector<uint8_t>(desc.begin(), desc.end())});
    fields.push_back({"jacobian", TensorType::UInt8, {1}, {1}});
    std::vector<float> thetaI(o.nThetaI), phiI(o.nPhiI, 0.f);
    for (int j = 0; j < o.nThetaI; ++j) thetaI[j] = float(Radians(o.thetaIMaxDeg) * j / (o.nThetaI - 1));
    for (int p = 0; o.nPhiI > 1 && p < o.nPhiI; ++p) phiI[p] = float(MeasuredU2phi(Float(p) / (o.nPhiI - 1)));
    const uint64_t np = uint64_t(o.nPhiI);
    const bool isotropic = o.nPhiI <= 2;
    // wo of slice (p, j); wm's phi is relative to it for isotropic data.
    auto woOf = [&](int p, int j) {
        return SphericalDirection(std::sin(thetaI[j]), std::cos(thetaI[j]), isotropic ? 0 : phiI[p]);
    };
    fields.push_back(FloatField("theta_i", {thetaI.size()}, thetaI));
    fields.push_back(FloatField("phi_i", {np}, phiI));
    fields.push_back(FloatField("wavelengths", {o.wavelengths.size()}, o.wavelengths));

    // ndf and sigma over (x: theta2u, y: phi2u); isotropic, so the rows are equal.
    std::vector<float> ndf, sigma;
    for (int y = 0; y < o.ndfPhi; ++y)
        for (int x = 0; x < o.ndfTheta; ++x) {
            double theta = MeasuredU2theta(Float(x) / (o.ndfTheta - 1));
            ndf.push_back(float(GenD(alpha, std::cos(theta))));
            sigma.push_back(float(GenSigma(alpha, theta)));
        }
    fields.push_back(FloatField("ndf", {uint64_t(o.ndfPhi), uint64_t(o.ndfTheta)}, ndf));
    fields.push_back(FloatField("sigma", {uint64_t(o.ndfPhi), uint64_t(o.ndfTheta)}, sigma));

    // vndf per theta_i (wo at phi 0; wm's phi relative to it): (wo . wm)+ D(wm) / sigma(wo), as a
    // density over the unit square.
    const int nv = o.vndfRes, ns = o.sampleRes, nl = int(o.wavelengths.size());
    std::vector<float> vndf;
    for (int p = 0; p < o.nPhiI; ++p)
    for (int j = 0; j < o.nThetaI; ++j) {
        Vec3f wo = woOf(p, j);
        for (int y = 0; y < nv; ++y)
            for (int x = 0; x < nv; ++x) {
                Float ux = Float(x) / (nv - 1), uy = Float(y) / (nv - 1);
                Float thetaM = MeasuredU2theta(ux), phiM = MeasuredU2phi(uy);
                Vec3f wm = SphericalDirection(std::sin(thetaM), std::cos(thetaM), phiM);
                double v = std::max(0.0, double(Dot(wo, wm))) * GenD(alpha, wm.z) / GenSigma(alpha, thetaI[j]);
                vndf.push_back(float(v * 2 * Pi * Pi * ux * std::sin(thetaM)));
            }
    }
    fields.push_back(FloatField("vndf", {np, uint64_t(o.nThetaI), uint64_t(nv), uint64_t(nv)}, vndf));

    // The reflectance at the vertices of the sample space, through the vndf warp just built.
    std::vector<Float> warpData;
    uint32_t res2[2] = {uint32_t(np), uint32_t(o.nThetaI)};
    const float *vals2[2] = {phiI.data(), thetaI.data()};
    PiecewiseLinear2DTable warp = AddPiecewiseLinear2D(warpData, vndf.data(), nv, nv, 2, res2, vals2, true);
    std::vector<float> spectra(np * o.nThetaI * nl * ns * ns), luminance(np * o.nThetaI * ns * ns);
    for (int p = 0; p < o.nPhiI; ++p)
    for (int j = 0; j < o.nThetaI; ++j) {
        Vec3f wo = woOf(p, j);
        Float params[2] = {phiI[p], thetaI[j]};
        size_t slice = size_t(p) * o.nThetaI + j;
        double lambdaO = GenLambda(alpha, wo.z);
        for (int y = 0; y < ns; ++y)
            for (int x = 0; x < ns; ++x) {
                PLSample s = PLSampleTable(warp, warpData.data(), Vec2f(Float(x) / (ns - 1), Float(y) / (ns - 1)), params);
                Float thetaM = MeasuredU2theta(s.p.x), phiM = MeasuredU2phi(s.p.y);
                Vec3f wm = SphericalDirection(std::sin(thetaM), std::cos(thetaM), phiM);
                Vec3f wi = Reflect(wo, wm);
                double g2OverG1 = wi.z > 0 ? (1 + lambdaO) / (1 + lambdaO + GenLambda(alpha, wi.z)) : 0;
                double lum = 0, ySum = 0;
                for (int l = 0; l < nl; ++l) {
                    Float lam = o.wavelengths[l];
                    Float F = FrComplex(std::abs(Dot(wo, wm)), SampledSpectrum(GenEta(lam)), SampledSpectrum(GenK(lam)))[0];
                    float r = float(F * g2OverG1);
                    spectra[((slice * nl + l) * ns + y) * ns + x] = r;
                    lum += r * GenCIEY(lam);
                    ySum += GenCIEY(lam);
                }
                luminance[(slice * ns + y) * ns + x] = float(lum / ySum);
            }
    }
    fields.push_back(FloatField("luminance", {np, uint64_t(o.nThetaI), uint64_t(ns), uint64_t(ns)}, luminance));
    fields.push_back(FloatField("spectra", {np, uint64_t(o.nThetaI), uint64_t(nl), uint64_t(ns), uint64_t(ns)}, spectra));
    return WriteTensorBytes(fields);
}

}  // namespace lu::test
