// Lucerna: host-side spectral data (CIE 1931 observer, standard illuminants, pbrt-v4's named
// spectra, RGB -> spectrum upsampling) and the tables uploaded with a scene.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "lucerna/spectrum/spectrum.h"

namespace lu {

// Reserved table indices in every SpectrumRegistry.
constexpr uint32_t TableCIE_X = 0, TableCIE_Y = 1, TableCIE_Z = 2, TableD65 = 3;
// Integral of the CIE Y matching function over 360..830 nm (pbrt-v4's CIE_Y_integral).
constexpr Float CIE_Y_integral = 106.856895f;

enum class SpectrumType { Albedo, Unbounded, Illuminant };

using RGB = std::array<Float, 3>;
using XYZ = std::array<Float, 3>;

class SpectrumRegistry {
  public:
    SpectrumRegistry();  // loads CIE X, Y, Z and D65 (normalized as pbrt-v4: Y integral = CIE_Y_integral)

    // Linear sRGB -> spectrum as pbrt-v4: Albedo (clamped to [0,1]), Unbounded, Illuminant
    // (times the color space illuminant, D65 for sRGB).
    Spectrum FromRGB(const RGB &rgb, SpectrumType type) const;
    // Piecewise-linear spectrum from (lambda, value) pairs; resampled to 1 nm. Empty on bad input.
    std::optional<Spectrum> FromPiecewise(const std::vector<double> &lambdas, const std::vector<double> &values);
    // Blackbody emitter at temperature T (kelvin), normalized to peak 1 (pbrt-v4's BlackbodySpectrum).
    Spectrum Blackbody(Float T) const;
    // pbrt-v4 named spectra ("metal-Cu-eta", "glass-BK7", "stdillum-D65", ...); nullopt if unknown.
    std::optional<Spectrum> Named(const std::string &name);
    static std::vector<std::string> NamedSpectrumNames();

    // Value of a spectrum at one wavelength (host).
    Float Eval(const Spectrum &s, Float lambda) const { return EvalSpectrum(s, lambda, Tables()); }
    // pbrt-v4's SpectrumToPhotometric: integral of Y * s (for RGB illuminants: of the illuminant only).
    Float ToPhotometric(const Spectrum &s) const;
    // Spectrum -> XYZ, normalized by CIE_Y_integral (as pbrt-v4's SpectrumToXYZ).
    XYZ ToXYZ(const Spectrum &s) const;

    SpectrumTables Tables() const { return {data_.data(), uint32_t(data_.size() / TabulatedSpectrumSize)}; }
    const std::vector<Float> &Data() const { return data_; }
    uint32_t AddTable(const std::vector<Float> &values471);

  private:
    std::vector<Float> data_;
    std::vector<std::pair<std::string, Spectrum>> namedCache_;
};

// XYZ -> linear sRGB (D65 white), and its inverse.
XYZ RGBToXYZ(const RGB &rgb);
RGB XYZToRGB(const XYZ &xyz);

// The Jakob-Hanika RGB -> sigmoid-coefficient table for sRGB (resolution 64), as uploaded with a
// scene (SceneView::rgbToSpecCoeffs / rgbToSpecZNodes / rgbToSpecRes).
struct RGBToSpectrumTableData {
    uint32_t res = 0;
    const Float *zNodes = nullptr;   // res values
    const Float *coeffs = nullptr;   // 3 * res^3 * 3 values: [maxComponent][z][y][x][coefficient]
};
RGBToSpectrumTableData SRGBToSpectrumTable();

}  // namespace lu
