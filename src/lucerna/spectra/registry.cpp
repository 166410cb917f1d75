// Lucerna: SpectrumRegistry (host): CIE tables, pbrt-v4's named spectra and RGB upsampling.
// Follows pbrt-v4 util/spectrum.cpp (PiecewiseLinearSpectrum::FromInterleaved, InnerProduct,
// SpectrumToPhotometric, SpectrumToXYZ) and util/colorspace.cpp (RGBColorSpace matrices).
#include "lucerna/spectra/registry.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <span>

#include "lucerna/spectra/cie_data.h"
#include "lucerna/spectra/color_space_data.h"
#include "lucerna/spectrum/rgb_to_spectrum.h"

namespace lu {

namespace {

// Piecewise-linear (lambda, value) spectrum sampled at 360..830 nm; 0 outside [front, back]
// (pbrt-v4 PiecewiseLinearSpectrum::operator()).
std::vector<double> SamplePiecewise(const std::vector<double> &l, const std::vector<double> &v) {
    std::vector<double> out(TabulatedSpectrumSize, 0.0);
    for (int i = 0; i < TabulatedSpectrumSize; ++i) {
        double lambda = LambdaMin + i;
        if (l.empty() || lambda < l.front() || lambda > l.back()) continue;
        if (l.size() == 1) { out[i] = v[0]; continue; }
        size_t k = size_t(std::upper_bound(l.begin(), l.end(), lambda) - l.begin());
        k = std::clamp<size_t>(k, 1, l.size() - 1) - 1;  // l[k] <= lambda <= l[k + 1]
        double t = (lambda - l[k]) / (l[k + 1] - l[k]);
        out[i] = (1 - t) * v[k] + t * v[k + 1];
    }
    return out;
}

// pbrt-v4 FromInterleaved: extends the samples with constant values to cover the visible range,
// and optionally normalizes to luminance CIE_Y_integral.
std::vector<double> SampleNamed(std::vector<double> l, std::vector<double> v, bool normalize) {
    if (l.front() > LambdaMin) {
        l.insert(l.begin(), LambdaMin - 1);
        v.insert(v.begin(), v.front());
    }
    if (l.back() < LambdaMax) {
        l.push_back(LambdaMax + 1);
        v.push_back(v.back());
    }
    std::vector<double> out = SamplePiecewise(l, v);
    if (normalize) {
        double y = 0;
        for (int i = 0; i < TabulatedSpectrumSize; ++i) y += out[i] * data::CIE_Y[i];
        for (double &x : out) x *= CIE_Y_integral / y;
    }
    return out;
}

std::vector<Float> ToFloat(const std::vector<double> &d) { return std::vector<Float>(d.begin(), d.end()); }

using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 Inverse(const Mat3 &m) {
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    Mat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            r[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
        }
    return r;
}

// pbrt-v4 RGBColorSpace(r, g, b, illuminant): white point from the illuminant's 1 nm table.
RGBColorSpace MakeColorSpace(ColorSpaceId id) {
    const data::ColorSpaceDefinition &d = data::ColorSpaces[uint32_t(id)];
    SpectrumRegistry reg;
    std::optional<Spectrum> illum = reg.Named(d.illuminant);
    XYZ W = reg.ToXYZ(*illum);
    RGBColorSpace cs;
    cs.id = id;
    cs.name = d.name;
    cs.illuminant = d.illuminant;
    cs.r = {d.r[0], d.r[1]};
    cs.g = {d.g[0], d.g[1]};
    cs.b = {d.b[0], d.b[1]};
    double sum = double(W[0]) + W[1] + W[2];
    cs.w = {W[0] / sum, W[1] / sum};
    const double *prim[3] = {d.r, d.g, d.b};
    Mat3 rgb;
    for (int c = 0; c < 3; ++c) {  // XYZ::FromxyY(primary, Y = 1) as column c
        double x = prim[c][0], y = prim[c][1];
        rgb[0][c] = x / y;
        rgb[1][c] = 1;
        rgb[2][c] = (1 - x - y) / y;
    }
    Mat3 inv = Inverse(rgb);
    double C[3];
    for (int i = 0; i < 3; ++i) C[i] = inv[i][0] * W[0] + inv[i][1] * W[1] + inv[i][2] * W[2];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) cs.xyzFromRGB[i][j] = rgb[i][j] * C[j];
    cs.rgbFromXYZ = Inverse(cs.xyzFromRGB);
    return cs;
}

std::array<Float, 3> Apply(const Mat3 &m, const std::array<Float, 3> &v) {
    std::array<Float, 3> r;
    for (int i = 0; i < 3; ++i) r[i] = Float(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2]);
    return r;
}

}  // namespace

SpectrumRegistry::SpectrumRegistry() {
    data_.reserve(size_t(8) * TabulatedSpectrumSize);
    data_.insert(data_.end(), data::CIE_X, data::CIE_X + TabulatedSpectrumSize);
    data_.insert(data_.end(), data::CIE_Y, data::CIE_Y + TabulatedSpectrumSize);
    data_.insert(data_.end(), data::CIE_Z, data::CIE_Z + TabulatedSpectrumSize);
    std::optional<Spectrum> d65 = Named("stdillum-D65");
    (void)d65;  // lands at index TableD65 (3); Named() caches it
}

uint32_t SpectrumRegistry::AddTable(const std::vector<Float> &values471) {
    uint32_t index = uint32_t(data_.size() / TabulatedSpectrumSize);
    data_.insert(data_.end(), values471.begin(), values471.end());
    data_.resize(size_t(index + 1) * TabulatedSpectrumSize, 0.f);
    return index;
}

uint32_t SpectrumRegistry::IlluminantTable(ColorSpaceId cs) {
    if (cs == ColorSpaceId::SRGB) return TableD65;
    return Named(data::ColorSpaces[uint32_t(cs)].illuminant)->table;
}

Spectrum SpectrumRegistry::FromRGB(const RGB &rgb, SpectrumType type, ColorSpaceId cs) {
    RGBToSpectrumTableData t = RGBToSpectrumTable(cs);
    switch (type) {
    case SpectrumType::Albedo: return RGBAlbedoSpectrum(t.coeffs, t.zNodes, t.res, rgb[0], rgb[1], rgb[2]);
    case SpectrumType::Unbounded: return RGBUnboundedSpectrum(t.coeffs, t.zNodes, t.res, rgb[0], rgb[1], rgb[2]);
    case SpectrumType::Illuminant:
        return RGBIlluminantSpectrum(t.coeffs, t.zNodes, t.res, rgb[0], rgb[1], rgb[2], IlluminantTable(cs));
    }
    return Spectrum::Const(0);
}

std::optional<Spectrum> SpectrumRegistry::FromPiecewise(const std::vector<double> &lambdas,
                                                        const std::vector<double> &values) {
    if (lambdas.empty() || lambdas.size() != values.size()) return std::nullopt;
    for (size_t i = 0; i < lambdas.size(); ++i) {
        if (!std::isfinite(lambdas[i]) || !std::isfinite(values[i])) return std::nullopt;
        if (i > 0 && !(lambdas[i] > lambdas[i - 1])) return std::nullopt;
    }
    Spectrum s;
    s.kind = SpectrumKind::Tabulated;
    s.scale = 1;
    s.table = AddTable(ToFloat(SamplePiecewise(lambdas, values)));
    return s;
}

Spectrum SpectrumRegistry::Blackbody(Float T) const {
    Spectrum s;
    s.kind = SpectrumKind::Blackbody;
    s.c[0] = T;
    s.scale = 0;
    if (T > 0) {
        Float lambdaMax = Float(2.8977721e-3 / T * 1e9);  // Wien's displacement law, nm
        Float peak = BlackbodyRadiance(lambdaMax, T);
        s.scale = peak > 0 ? 1 / peak : 0;
    }
    return s;
}

std::vector<std::string> SpectrumRegistry::NamedSpectrumNames() {
    // pbrt-v4's GetNamedSpectrum() names, except the camera sensor curves (canon_eos_*, nikon_*,
    // sony_ilce_*, hasselblad_*_{r,g,b}), which Lucerna does not provide.
    std::vector<std::string> names;
    for (const auto &m : std::span(data::MeasuredSpectra, size_t(data::NumMeasuredSpectra))) names.push_back(m.name);
    for (const auto &il : data::Illuminants) names.push_back(il.name);
    return names;
}

std::optional<Spectrum> SpectrumRegistry::Named(const std::string &name) {
    for (const auto &[n, s] : namedCache_)
        if (n == name) return s;
    std::vector<double> l, v;
    bool normalize = false;
    for (const auto &il : data::Illuminants)
        if (name == il.name) {
            for (int i = 0; i < il.n; ++i) {
                l.push_back(double(il.lambda0) + double(il.step) * i);
                v.push_back(il.values[i]);
            }
            normalize = true;
        }
    for (int k = 0; k < data::NumMeasuredSpectra && l.empty(); ++k)
        if (name == data::MeasuredSpectra[k].name)
            for (int i = 0; i < data::MeasuredSpectra[k].n; ++i) {
                l.push_back(data::MeasuredSpectra[k].lv[2 * i]);
                v.push_back(data::MeasuredSpectra[k].lv[2 * i + 1]);
            }
    if (l.empty()) return std::nullopt;
    Spectrum s;
    s.kind = SpectrumKind::Tabulated;
    s.scale = 1;
    s.table = AddTable(ToFloat(SampleNamed(l, v, normalize)));
    namedCache_.emplace_back(name, s);
    return s;
}

Float SpectrumRegistry::ToPhotometric(const Spectrum &s) const {
    SpectrumTables tab = Tables();
    double y = 0;
    for (int i = 0; i < TabulatedSpectrumSize; ++i) {
        Float lambda = LambdaMin + i;
        Float v = s.kind == SpectrumKind::RGBIlluminant
                      ? LookupTabulated(tab.data + size_t(s.table) * TabulatedSpectrumSize, lambda)
                      : EvalSpectrum(s, lambda, tab);
        y += double(data::CIE_Y[i]) * v;
    }
    return Float(y);
}

XYZ SpectrumRegistry::ToXYZ(const Spectrum &s) const {
    SpectrumTables tab = Tables();
    double xyz[3] = {0, 0, 0};
    for (int i = 0; i < TabulatedSpectrumSize; ++i) {
        double v = EvalSpectrum(s, LambdaMin + i, tab);
        xyz[0] += data::CIE_X[i] * v;
        xyz[1] += data::CIE_Y[i] * v;
        xyz[2] += data::CIE_Z[i] * v;
    }
    return {Float(xyz[0] / CIE_Y_integral), Float(xyz[1] / CIE_Y_integral), Float(xyz[2] / CIE_Y_integral)};
}

const RGBColorSpace &GetRGBColorSpace(ColorSpaceId cs) {
    static const RGBColorSpace spaces[NumColorSpaces] = {
        MakeColorSpace(ColorSpaceId::SRGB), MakeColorSpace(ColorSpaceId::DCI_P3),
        MakeColorSpace(ColorSpaceId::Rec2020), MakeColorSpace(ColorSpaceId::ACES2065_1)};
    return spaces[uint32_t(cs) < NumColorSpaces ? uint32_t(cs) : 0];
}

std::optional<ColorSpaceId> ColorSpaceFromName(const std::string &name) {
    std::string lower;
    for (char c : name) lower += char(std::tolower((unsigned char)c));
    int i = data::ColorSpaceIndex(lower.c_str());
    if (i < 0) return std::nullopt;
    return ColorSpaceId(i);
}

std::optional<ColorSpaceId> LookupColorSpace(const std::array<double, 2> &r, const std::array<double, 2> &g,
                                             const std::array<double, 2> &b, const std::array<double, 2> &w) {
    auto close = [](const std::array<double, 2> &a, const std::array<double, 2> &c) {
        for (int i = 0; i < 2; ++i)
            if (a[i] != c[i] && !(std::abs((a[i] - c[i]) / c[i]) < 1e-3)) return false;
        return true;
    };
    for (uint32_t i = 0; i < NumColorSpaces; ++i) {
        const RGBColorSpace &cs = GetRGBColorSpace(ColorSpaceId(i));
        if (close(r, cs.r) && close(g, cs.g) && close(b, cs.b) && close(w, cs.w)) return cs.id;
    }
    return std::nullopt;
}

RGB RGBColorSpace::ToRGB(const XYZ &xyz) const { return Apply(rgbFromXYZ, xyz); }
XYZ RGBColorSpace::ToXYZ(const RGB &rgb) const { return Apply(xyzFromRGB, rgb); }

XYZ RGBToXYZ(const RGB &rgb) { return GetRGBColorSpace(ColorSpaceId::SRGB).ToXYZ(rgb); }
RGB XYZToRGB(const XYZ &xyz) { return GetRGBColorSpace(ColorSpaceId::SRGB).ToRGB(xyz); }

}  // namespace lu
