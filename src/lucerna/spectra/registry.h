// Lucerna: host-side spectral data (CIE 1931 observer, standard illuminants, pbrt-v4's named
// spectra, RGB -> spectrum upsampling) and the tables uploaded with a scene.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "lucerna/spectrum/color_space.h"
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

    // Linear RGB of color space cs -> spectrum as pbrt-v4: Albedo (clamped to [0,1]), Unbounded,
    // Illuminant (times the color space illuminant: D65, or ACES D60 for aces2065-1).
    Spectrum FromRGB(const RGB &rgb, SpectrumType type, ColorSpaceId cs = ColorSpaceId::SRGB);
    // The table index of color space cs's illuminant (TableD65 for srgb, dci-p3 and rec2020).
    uint32_t IlluminantTable(ColorSpaceId cs);
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

// One of pbrt-v4's RGB color spaces (RGBColorSpace): the chromaticities of its primaries, the xy
// of its illuminant's white, and RGB <-> XYZ derived from them as pbrt-v4's constructor does
// (columns: the primaries' XYZ with Y = 1, scaled so that RGB (1, 1, 1) is the illuminant's XYZ
// with Y = 1, from its 1 nm table).
struct RGBColorSpace {
    using Mat3 = std::array<std::array<double, 3>, 3>;
    ColorSpaceId id = ColorSpaceId::SRGB;
    std::string name;        // "srgb", "dci-p3", "rec2020", "aces2065-1"
    std::string illuminant;  // named spectrum: "stdillum-D65" or "illum-acesD60"
    std::array<double, 2> r{}, g{}, b{}, w{};
    Mat3 xyzFromRGB{}, rgbFromXYZ{};

    RGB ToRGB(const XYZ &xyz) const;
    XYZ ToXYZ(const RGB &rgb) const;
};
const RGBColorSpace &GetRGBColorSpace(ColorSpaceId cs);
// pbrt-v4's RGBColorSpace::GetNamed (case-insensitive); nullopt if unknown.
std::optional<ColorSpaceId> ColorSpaceFromName(const std::string &name);
// pbrt-v4's RGBColorSpace::Lookup (used for EXR chromaticities): the space whose primaries and
// white all match to 1e-3 relative, or nullopt.
std::optional<ColorSpaceId> LookupColorSpace(const std::array<double, 2> &r, const std::array<double, 2> &g,
                                             const std::array<double, 2> &b, const std::array<double, 2> &w);

// The Jakob-Hanika RGB -> sigmoid-coefficient tables (resolution 64), one per color space, as
// uploaded with a scene (SceneView::rgbToSpecCoeffs / rgbToSpecZNodes / rgbToSpecRes). All
// share the resolution and the z nodes.
struct RGBToSpectrumTableData {
    uint32_t res = 0;
    const Float *zNodes = nullptr;   // res values
    const Float *coeffs = nullptr;   // 3 * res^3 * 3 values: [maxComponent][z][y][x][coefficient]
};
RGBToSpectrumTableData RGBToSpectrumTable(ColorSpaceId cs);
RGBToSpectrumTableData SRGBToSpectrumTable();

}  // namespace lu
