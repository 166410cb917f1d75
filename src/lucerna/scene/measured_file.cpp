// Lucerna scene builder: the RGL tensor file reader and the measured BRDF's tables (pbrt-v4's
// util/tensor and MeasuredBRDF::Create, every size and offset checked against the file).
#include "lucerna/scene/measured_file.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

namespace lu {

namespace {

std::string Q(const std::string &s) { return "\"" + s + "\""; }

[[noreturn]] void Bad(const std::string &path, const std::string &what) {
    throw MeasuredFileError(Q(path) + ": " + what);
}

size_t TypeSize(TensorType t) {
    switch (t) {
    case TensorType::UInt8: case TensorType::Int8: return 1;
    case TensorType::UInt16: case TensorType::Int16: case TensorType::Float16: return 2;
    case TensorType::UInt32: case TensorType::Int32: case TensorType::Float32: return 4;
    case TensorType::UInt64: case TensorType::Int64: case TensorType::Float64: return 8;
    default: return 0;
    }
}

// A cursor over the header that refuses to read past the end of the file.
struct Reader {
    const std::vector<uint8_t> &b;
    const std::string &path;
    size_t pos = 0;
    void Get(void *dst, size_t n, const char *what) {
        if (n > b.size() - pos) Bad(path, std::string("truncated tensor file (") + what + " at byte " + std::to_string(pos) + ")");
        std::memcpy(dst, b.data() + pos, n);
        pos += n;
    }
};

}  // namespace

TensorFile ParseTensorFile(const std::vector<uint8_t> &bytes, const std::string &path) {
    Reader r{bytes, path};
    if (bytes.size() < 12 + 2 + 4) Bad(path, "not a tensor file (" + std::to_string(bytes.size()) + " bytes, too small)");
    char header[12];
    uint8_t version[2];
    uint32_t nFields = 0;
    r.Get(header, 12, "header");
    if (std::memcmp(header, "tensor_file", 12) != 0) Bad(path, "not a tensor file (no \"tensor_file\" header)");
    r.Get(version, 2, "version");
    if (version[0] != 1 || version[1] != 0)
        Bad(path, "unknown tensor file version " + std::to_string(version[0]) + "." + std::to_string(version[1]) + " (need 1.0)");
    r.Get(&nFields, 4, "field count");
    // Each field header takes at least 13 bytes: a count beyond that is a corrupt file.
    if (uint64_t(nFields) * 13 > bytes.size())
        Bad(path, "truncated or corrupt tensor file (" + std::to_string(nFields) + " fields need more than the file's " +
                      std::to_string(bytes.size()) + " bytes)");
    TensorFile tf;
    for (uint32_t i = 0; i < nFields; ++i) {
        uint16_t nameLength = 0, ndim = 0;
        uint8_t dtype = 0;
        uint64_t offset = 0;
        r.Get(&nameLength, 2, "field name length");
        std::string name(nameLength, '\0');
        r.Get(name.data(), nameLength, "field name");
        r.Get(&ndim, 2, "field rank");
        r.Get(&dtype, 1, "field type");
        r.Get(&offset, 8, "field offset");
        TensorField f;
        f.dtype = TensorType(dtype);
        size_t elem = TypeSize(f.dtype);
        if (elem == 0) Bad(path, "field " + Q(name) + ": unknown data type " + std::to_string(dtype));
        uint64_t count = 1;
        for (uint16_t d = 0; d < ndim; ++d) {
            uint64_t n = 0;
            r.Get(&n, 8, "field shape");
            if (n != 0 && count > (uint64_t(1) << 40) / n) Bad(path, "field " + Q(name) + ": shape too large");
            count *= n;
            f.shape.push_back(n);
        }
        uint64_t size = count * elem;
        if (offset > bytes.size() || size > bytes.size() - offset)
            Bad(path, "truncated tensor file (field " + Q(name) + " needs bytes " + std::to_string(offset) + ".." +
                          std::to_string(offset + size) + ", the file has " + std::to_string(bytes.size()) + ")");
        f.bytes.assign(bytes.begin() + long(offset), bytes.begin() + long(offset + size));
        if (tf.fields.count(name)) Bad(path, "field " + Q(name) + " appears twice");
        tf.fields[name] = std::move(f);
    }
    return tf;
}

TensorFile ReadTensorFile(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) Bad(path, "unable to open the measured BRDF file");
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) Bad(path, "unable to read the measured BRDF file");
    return ParseTensorFile(bytes, path);
}

PiecewiseLinear2DTable AddPiecewiseLinear2D(std::vector<Float> &data, const float *values, uint32_t nx, uint32_t ny,
                                            uint32_t nParams, const uint32_t *paramSize,
                                            const float *const *paramValues, bool normalize) {
    PiecewiseLinear2DTable t;
    t.nx = nx;
    t.ny = ny;
    t.nParams = nParams;
    uint32_t slices = 1;
    for (int d = int(nParams) - 1; d >= 0; --d) {   // the last parameter varies fastest
        t.paramSize[d] = paramSize[d];
        t.paramStride[d] = paramSize[d] > 1 ? slices : 0;
        t.paramValues[d] = uint32_t(data.size());
        data.insert(data.end(), paramValues[d], paramValues[d] + paramSize[d]);
        slices *= paramSize[d];
    }
    size_t n = size_t(nx) * ny;
    t.data = uint32_t(data.size());
    data.resize(data.size() + slices * n);
    if (!normalize) {
        // PLEvaluate multiplies by (nx - 1)(ny - 1): store the values divided by it.
        Float scale = 1 / Float(uint64_t(nx - 1) * (ny - 1));
        for (size_t i = 0; i < slices * n; ++i) data[t.data + i] = values[i] * scale;
        return t;
    }
    t.marginalCdf = uint32_t(data.size());
    data.resize(data.size() + size_t(slices) * ny);
    t.conditionalCdf = uint32_t(data.size());
    data.resize(data.size() + slices * n);
    for (uint32_t s = 0; s < slices; ++s) {
        const float *v = values + s * n;
        Float *cond = data.data() + t.conditionalCdf + s * n, *marg = data.data() + t.marginalCdf + size_t(s) * ny;
        Float *out = data.data() + t.data + s * n;
        // Trapezoidal cdfs of the piecewise-linear rows, then of the rows' integrals.
        for (uint32_t y = 0; y < ny; ++y) {
            double sum = 0;
            cond[y * nx] = 0;
            for (uint32_t x = 0; x + 1 < nx; ++x) {
                sum += 0.5 * (double(v[y * nx + x]) + double(v[y * nx + x + 1]));
                cond[y * nx + x + 1] = Float(sum);
            }
        }
        marg[0] = 0;
        double sum = 0;
        for (uint32_t y = 0; y + 1 < ny; ++y) {
            sum += 0.5 * (double(cond[(y + 1) * nx - 1]) + double(cond[(y + 2) * nx - 1]));
            marg[y + 1] = Float(sum);
        }
        // A slice without mass stays 0 (its samples are rejected) rather than becoming NaN.
        Float norm = marg[ny - 1] > 0 ? 1 / marg[ny - 1] : 0;
        for (size_t i = 0; i < n; ++i) {
            cond[i] *= norm;
            out[i] = v[i] * norm;
        }
        for (uint32_t y = 0; y < ny; ++y) marg[y] *= norm;
    }
    return t;
}

namespace {

struct FieldCheck {
    const TensorFile &tf;
    const std::string &path;
    const TensorField &Get(const std::string &name, TensorType type, size_t rank) const {
        auto it = tf.fields.find(name);
        if (it == tf.fields.end()) Bad(path, "invalid measured BRDF file: no field " + Q(name));
        const TensorField &f = it->second;
        if (f.dtype != type)
            Bad(path, "invalid measured BRDF file: field " + Q(name) + " must be " +
                          (type == TensorType::UInt8 ? "uint8" : "float32"));
        if (f.shape.size() != rank)
            Bad(path, "invalid measured BRDF file: field " + Q(name) + " must have " + std::to_string(rank) +
                          " dimensions (has " + std::to_string(f.shape.size()) + ")");
        return f;
    }
    void Extent(const TensorField &f, const std::string &name, size_t dim, uint64_t want, const std::string &what) const {
        if (f.shape[dim] != want)
            Bad(path, "invalid measured BRDF file: field " + Q(name) + " dimension " + std::to_string(dim) + " is " +
                          std::to_string(f.shape[dim]) + ", must be " + std::to_string(want) + " (" + what + ")");
    }
    void AtLeast(const TensorField &f, const std::string &name, size_t dim, uint64_t least) const {
        if (f.shape[dim] < least)
            Bad(path, "invalid measured BRDF file: field " + Q(name) + " dimension " + std::to_string(dim) + " is " +
                          std::to_string(f.shape[dim]) + ", must be at least " + std::to_string(least));
        if (f.shape[dim] > (1u << 20)) Bad(path, "invalid measured BRDF file: field " + Q(name) + " is too large");
    }
    // float32 values: finite, and non-negative unless signedOk (copied: the bytes may be unaligned).
    std::vector<float> Floats(const TensorField &f, const std::string &name, bool nonNegative) const {
        std::vector<float> v(f.bytes.size() / 4);
        std::memcpy(v.data(), f.bytes.data(), v.size() * 4);
        for (size_t i = 0; i < v.size(); ++i)
            if (!std::isfinite(v[i]) || (nonNegative && v[i] < 0))
                Bad(path, "invalid measured BRDF file: field " + Q(name) + " value " + std::to_string(i) + " is " +
                              std::to_string(v[i]) + (nonNegative ? " (must be finite and >= 0)" : " (must be finite)"));
        return v;
    }
    void Ascending(const std::vector<float> &v, const std::string &name) const {
        for (size_t i = 1; i < v.size(); ++i)
            if (!(v[i] > v[i - 1])) Bad(path, "invalid measured BRDF file: field " + Q(name) + " must be increasing");
    }
};

}  // namespace

MeasuredBRDFData BuildMeasuredBRDF(const TensorFile &tf, const std::string &path, std::vector<Float> &data) {
    FieldCheck c{tf, path};
    const TensorType F32 = TensorType::Float32;
    c.Get("description", TensorType::UInt8, 1);
    const TensorField &jacobian = c.Get("jacobian", TensorType::UInt8, 1);
    c.Extent(jacobian, "jacobian", 0, 1, "one flag");
    const TensorField &thetaI = c.Get("theta_i", F32, 1), &phiI = c.Get("phi_i", F32, 1);
    const TensorField &wavelengths = c.Get("wavelengths", F32, 1);
    c.AtLeast(thetaI, "theta_i", 0, 1);
    c.AtLeast(phiI, "phi_i", 0, 1);
    c.AtLeast(wavelengths, "wavelengths", 0, 1);
    const TensorField &ndf = c.Get("ndf", F32, 2), &sigma = c.Get("sigma", F32, 2);
    const TensorField &vndf = c.Get("vndf", F32, 4), &luminance = c.Get("luminance", F32, 4);
    const TensorField &spectra = c.Get("spectra", F32, 5);
    for (size_t d = 0; d < 2; ++d) {
        c.AtLeast(ndf, "ndf", d, 2);
        c.AtLeast(sigma, "sigma", d, 2);
        c.AtLeast(vndf, "vndf", d + 2, 2);
        c.AtLeast(luminance, "luminance", d + 2, 2);
    }
    const uint64_t nPhi = phiI.shape[0], nTheta = thetaI.shape[0], nLambda = wavelengths.shape[0];
    c.Extent(vndf, "vndf", 0, nPhi, "phi_i values");
    c.Extent(vndf, "vndf", 1, nTheta, "theta_i values");
    c.Extent(luminance, "luminance", 0, nPhi, "phi_i values");
    c.Extent(luminance, "luminance", 1, nTheta, "theta_i values");
    c.Extent(luminance, "luminance", 3, luminance.shape[2], "square");
    c.Extent(spectra, "spectra", 0, nPhi, "phi_i values");
    c.Extent(spectra, "spectra", 1, nTheta, "theta_i values");
    c.Extent(spectra, "spectra", 2, nLambda, "wavelengths");
    c.Extent(spectra, "spectra", 3, luminance.shape[2], "as luminance");
    c.Extent(spectra, "spectra", 4, luminance.shape[3], "as luminance");

    std::vector<float> theta = c.Floats(thetaI, "theta_i", false), phi = c.Floats(phiI, "phi_i", false);
    std::vector<float> lambda = c.Floats(wavelengths, "wavelengths", false);
    c.Ascending(theta, "theta_i");
    c.Ascending(phi, "phi_i");
    c.Ascending(lambda, "wavelengths");
    MeasuredBRDFData b;
    b.isotropic = nPhi <= 2;
    b.jacobian = jacobian.bytes[0] != 0;
    if (!b.isotropic) {
        // pbrt-v4: anisotropic data must cover the full circle of phi_i (no symmetry reduction).
        int reduction = int(std::rint(2 * Pi / (phi.back() - phi.front())));
        if (reduction != 1) Bad(path, "reduction " + std::to_string(reduction) + " (!= 1) not supported");
    }
    uint64_t total = data.size();
    // Each table's values, and at most as many again for its cdfs and its marginal.
    for (const TensorField *f : {&ndf, &sigma, &vndf, &luminance, &spectra}) total += 3 * f->bytes.size() / 4;
    if (total + 3 * (nPhi + nTheta + nLambda) > uint64_t(UINT32_MAX)) Bad(path, "measured data too large (more than 2^32 values)");

    std::vector<float> v = c.Floats(ndf, "ndf", true);
    b.ndf = AddPiecewiseLinear2D(data, v.data(), uint32_t(ndf.shape[1]), uint32_t(ndf.shape[0]), 0, nullptr, nullptr, false);
    v = c.Floats(sigma, "sigma", true);
    b.sigma = AddPiecewiseLinear2D(data, v.data(), uint32_t(sigma.shape[1]), uint32_t(sigma.shape[0]), 0, nullptr, nullptr,
                                   false);
    uint32_t res2[2] = {uint32_t(nPhi), uint32_t(nTheta)};
    const float *vals2[2] = {phi.data(), theta.data()};
    v = c.Floats(vndf, "vndf", true);
    b.vndf = AddPiecewiseLinear2D(data, v.data(), uint32_t(vndf.shape[3]), uint32_t(vndf.shape[2]), 2, res2, vals2, true);
    v = c.Floats(luminance, "luminance", true);
    b.luminance = AddPiecewiseLinear2D(data, v.data(), uint32_t(luminance.shape[3]), uint32_t(luminance.shape[2]), 2,
                                       res2, vals2, true);
    uint32_t res3[3] = {uint32_t(nPhi), uint32_t(nTheta), uint32_t(nLambda)};
    const float *vals3[3] = {phi.data(), theta.data(), lambda.data()};
    v = c.Floats(spectra, "spectra", false);
    b.spectra = AddPiecewiseLinear2D(data, v.data(), uint32_t(spectra.shape[4]), uint32_t(spectra.shape[3]), 3, res3,
                                     vals3, false);
    return b;
}

}  // namespace lu
