// Lucerna: float images in memory and their files (OpenEXR via the OpenEXR library, PNG via
// libpng), host only.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace lu {

// Row-major, top row first, channels interleaved (RGB or RGBA or one channel), linear values.
struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<float> pixels;
    // OpenEXR "chromaticities" (red, green, blue, white xy): read from an EXR that has them,
    // written by WriteEXR when set (pbrt-v4 writes them for every non-sRGB film).
    bool hasChromaticities = false;
    std::array<float, 8> chromaticities{};
    float &At(int x, int y, int c) { return pixels[(size_t(y) * width + x) * channels + c]; }
    float At(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels + c]; }
};

// Unreadable, missing or corrupt image files (message names the file and the reason).
class ImageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// String attributes stored in the EXR header (e.g. "lucerna.spp" = "64").
using ImageMetadata = std::map<std::string, std::string>;

// Reads .exr (RGB(A) or Y as float) or .png (8/16-bit; sRGB-decoded to linear unless `linear`).
Image ReadImage(const std::string &filename, bool pngIsLinear = false, ImageMetadata *metadata = nullptr);
// Writes float32 EXR (RGB) with metadata, atomically (temporary name, then rename).
void WriteEXR(const std::string &filename, const Image &image, const ImageMetadata &metadata = {});
// Writes an 8-bit sRGB PNG (clamped), atomically.
void WritePNG(const std::string &filename, const Image &image);
// Chooses the format by extension (.exr or .png).
void WriteImage(const std::string &filename, const Image &image, const ImageMetadata &metadata = {});

// ---- Helpers (added with the image module) ----
// A width x height image with `channels` channels, every value `fill`.
Image MakeImage(int width, int height, int channels, float fill = 0);
// Number of NaN or infinite values over all pixels and channels (the scene builder refuses
// textures where this is nonzero; ReadImage itself keeps such values as they are).
size_t CountNonFinite(const Image &image);
// The sRGB transfer functions (IEC 61966-2-1, piecewise), as pbrt-v4's LinearToSRGB/SRGBToLinear.
float LinearToSRGB(float linear);
float SRGBToLinear(float encoded);

}  // namespace lu
