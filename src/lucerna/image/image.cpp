// Lucerna image files: OpenEXR through the OpenEXR 3 library (generic FrameBuffer API, float32)
// and PNG through libpng. Semantics follow pbrt-v4's util/image.cpp (sRGB PNG, linear EXR).
#include "lucerna/image/image.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfChromaticitiesAttribute.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

namespace lu {

namespace {

// Upper bound on values (width * height * channels) an image file may declare: a corrupt header
// must give an ImageError, not a huge allocation.
constexpr size_t MaxImageValues = size_t(1) << 30;

std::string Lower(std::string s) {
    for (char &c : s) c = char(std::tolower((unsigned char)c));
    return s;
}

std::string Extension(const std::string &filename) {
    return Lower(std::filesystem::path(filename).extension().string());
}

[[noreturn]] void Fail(const std::string &filename, const std::string &reason) {
    throw ImageError(filename + ": " + reason);
}

// The first `maxBytes` bytes of the file (all of it by default).
std::vector<unsigned char> ReadFileBytes(const std::string &filename, size_t maxBytes = SIZE_MAX) {
    std::error_code ec;
    if (std::filesystem::is_directory(filename, ec)) Fail(filename, "is a directory");
    std::FILE *f = std::fopen(filename.c_str(), "rb");
    if (!f) Fail(filename, std::string("cannot open: ") + std::strerror(errno));
    std::vector<unsigned char> bytes;
    unsigned char buf[1 << 16];
    size_t n;
    while (bytes.size() < maxBytes &&
           (n = std::fread(buf, 1, std::min(sizeof(buf), maxBytes - bytes.size()), f)) > 0)
        bytes.insert(bytes.end(), buf, buf + n);
    bool bad = std::ferror(f);
    std::fclose(f);
    if (bad) Fail(filename, "read error");
    return bytes;
}

// "<name>.tmp-<pid>" beside the target; renamed over it once complete.
std::string TempName(const std::string &filename) {
    return filename + ".tmp-" + std::to_string(::getpid());
}

void CommitTemp(const std::string &tmp, const std::string &filename) {
    std::error_code ec;
    std::filesystem::rename(tmp, filename, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        Fail(filename, "cannot rename the temporary file into place: " + ec.message());
    }
}

void CheckWritable(const std::string &filename, const Image &image) {
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4)
        Fail(filename, "cannot write an image of " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) + " pixels with " +
                           std::to_string(image.channels) + " channels (need 1 to 4)");
    if (image.pixels.size() != size_t(image.width) * image.height * image.channels)
        Fail(filename, "pixel buffer size does not match width * height * channels");
}

// ---- OpenEXR ----

Image ReadEXR(const std::string &filename, ImageMetadata *metadata) {
    try {
        Imf::InputFile file(filename.c_str());
        const Imf::Header &header = file.header();
        const Imath::Box2i dw = header.dataWindow();
        long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
        if (w <= 0 || h <= 0) Fail(filename, "empty data window");

        const Imf::ChannelList &list = header.channels();
        std::vector<std::string> names;
        if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B")) {
            names = {"R", "G", "B"};
            if (list.findChannel("A")) names.push_back("A");
        } else if (list.findChannel("Y")) {
            names = {"Y"};
            if (list.findChannel("A")) names.push_back("A");
        } else {
            int count = 0;
            std::string all, only;
            for (auto it = list.begin(); it != list.end(); ++it, ++count) {
                all += (all.empty() ? "" : ", ") + std::string(it.name());
                only = it.name();
            }
            if (count != 1) Fail(filename, "no R,G,B or Y channels (channels: " + all + ")");
            names = {only};
        }
        size_t values = size_t(w) * size_t(h) * names.size();
        if (w > (1 << 16) || h > (1 << 16) || values > MaxImageValues)
            Fail(filename, "image too large (" + std::to_string(w) + "x" + std::to_string(h) + ")");

        Image image;
        image.width = int(w);
        image.height = int(h);
        image.channels = int(names.size());
        image.pixels.assign(values, 0.f);
        Imf::FrameBuffer fb;
        size_t xStride = sizeof(float) * image.channels, yStride = xStride * image.width;
        for (int c = 0; c < image.channels; ++c)
            fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, dw, xStride, yStride));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (auto *ch = header.findTypedAttribute<Imf::ChromaticitiesAttribute>("chromaticities")) {
            const Imf::Chromaticities &c = ch->value();
            image.hasChromaticities = true;
            image.chromaticities = {c.red.x, c.red.y, c.green.x, c.green.y, c.blue.x, c.blue.y, c.white.x, c.white.y};
        }

        if (metadata) {
            metadata->clear();
            for (auto it = header.begin(); it != header.end(); ++it) {
                const Imf::Attribute &a = it.attribute();
                if (auto *s = dynamic_cast<const Imf::StringAttribute *>(&a))
                    (*metadata)[it.name()] = s->value();
                else if (auto *i = dynamic_cast<const Imf::IntAttribute *>(&a))
                    (*metadata)[it.name()] = std::to_string(i->value());
                else if (auto *f = dynamic_cast<const Imf::FloatAttribute *>(&a))
                    (*metadata)[it.name()] = std::to_string(f->value());
                else if (auto *d = dynamic_cast<const Imf::DoubleAttribute *>(&a))
                    (*metadata)[it.name()] = std::to_string(d->value());
            }
        }
        return image;
    } catch (const ImageError &) {
        throw;
    } catch (const std::exception &e) {
        Fail(filename, std::string("corrupt or unreadable OpenEXR file: ") + e.what());
    }
}

// ---- PNG ----

struct PngDecoded {
    const unsigned char *data = nullptr;
    size_t size = 0, offset = 0;
    int width = 0, height = 0, channels = 0, bitDepth = 0;
    std::vector<unsigned char> raw;  // decoded rows, big-endian for 16-bit
    std::vector<png_bytep> rows;
    char message[256] = {};
};

void PngReadCallback(png_structp png, png_bytep out, png_size_t length) {
    auto *d = static_cast<PngDecoded *>(png_get_io_ptr(png));
    if (length > d->size - d->offset) png_error(png, "unexpected end of file (truncated)");
    std::memcpy(out, d->data + d->offset, length);
    d->offset += length;
}

void PngErrorCallback(png_structp png, png_const_charp msg) {
    auto *d = static_cast<PngDecoded *>(png_get_error_ptr(png));
    std::snprintf(d->message, sizeof(d->message), "%s", msg);
    png_longjmp(png, 1);
}

void PngWarningCallback(png_structp, png_const_charp) {}

// libpng reports errors by longjmp: everything that must survive one lives in *d (owned by the
// caller), and no object with a destructor is created in this frame after setjmp.
bool DecodePng(PngDecoded *d) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, d, PngErrorCallback, PngWarningCallback);
    if (!png) {
        std::snprintf(d->message, sizeof(d->message), "out of memory");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        std::snprintf(d->message, sizeof(d->message), "out of memory");
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_set_read_fn(png, d, PngReadCallback);
    png_set_user_limits(png, 1 << 16, 1 << 16);
    png_read_info(png, info);
    png_uint_32 w = 0, h = 0;
    int bitDepth = 0, colorType = 0, interlace = 0;
    png_get_IHDR(png, info, &w, &h, &bitDepth, &colorType, &interlace, nullptr, nullptr);
    if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    d->width = int(w);
    d->height = int(h);
    d->channels = png_get_channels(png, info);
    d->bitDepth = png_get_bit_depth(png, info);
    size_t rowBytes = png_get_rowbytes(png, info);
    if (size_t(w) * h * d->channels > MaxImageValues || rowBytes != size_t(w) * d->channels * (d->bitDepth / 8))
        png_error(png, "image too large or unsupported layout");
    d->raw.resize(rowBytes * h);
    d->rows.resize(h);
    for (png_uint_32 y = 0; y < h; ++y) d->rows[y] = d->raw.data() + rowBytes * y;
    png_read_image(png, d->rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

Image ReadPNG(const std::string &filename, const std::vector<unsigned char> &bytes, bool linear) {
    PngDecoded d;
    d.data = bytes.data();
    d.size = bytes.size();
    if (!DecodePng(&d)) Fail(filename, std::string("corrupt or unreadable PNG file: ") + d.message);
    if (d.channels < 1 || d.channels > 4 || (d.bitDepth != 8 && d.bitDepth != 16))
        Fail(filename, "unsupported PNG layout");
    Image image = MakeImage(d.width, d.height, d.channels);
    float lut[256];
    for (int i = 0; i < 256; ++i) lut[i] = linear ? i / 255.f : SRGBToLinear(i / 255.f);
    // Alpha (the 2nd of gray+alpha, the 4th of RGBA) is always linear.
    bool hasAlpha = d.channels == 2 || d.channels == 4;
    size_t n = image.pixels.size();
    for (size_t i = 0; i < n; ++i) {
        bool isAlpha = hasAlpha && (i % d.channels) == size_t(d.channels - 1);
        if (d.bitDepth == 8) {
            unsigned char v = d.raw[i];
            image.pixels[i] = isAlpha ? v / 255.f : lut[v];
        } else {
            float v = ((d.raw[2 * i] << 8) | d.raw[2 * i + 1]) / 65535.f;
            image.pixels[i] = (isAlpha || linear) ? v : SRGBToLinear(v);
        }
    }
    return image;
}

}  // namespace

// ---- Public API ----

Image MakeImage(int width, int height, int channels, float fill) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.pixels.assign(size_t(std::max(width, 0)) * std::max(height, 0) * std::max(channels, 0), fill);
    return image;
}

size_t CountNonFinite(const Image &image) {
    size_t n = 0;
    for (float v : image.pixels) n += !std::isfinite(v);
    return n;
}

float LinearToSRGB(float v) {
    if (v <= 0.0031308f) return 12.92f * v;
    return 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

float SRGBToLinear(float v) {
    if (v <= 0.04045f) return v * (1.f / 12.92f);
    return std::pow((v + 0.055f) * (1.f / 1.055f), 2.4f);
}

Image ReadImage(const std::string &filename, bool pngIsLinear, ImageMetadata *metadata) {
    if (metadata) metadata->clear();
    std::vector<unsigned char> bytes = ReadFileBytes(filename, 8);
    static const unsigned char exrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
    static const unsigned char pngMagic[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    // The contents decide the format; the extension only names what was expected.
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), exrMagic, 4) == 0) return ReadEXR(filename, metadata);
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), pngMagic, 8) == 0)
        return ReadPNG(filename, ReadFileBytes(filename), pngIsLinear);
    std::string ext = Extension(filename);
    if (bytes.empty()) Fail(filename, "empty file");
    if (ext == ".exr") Fail(filename, "not an OpenEXR file (bad magic number)");
    if (ext == ".png") Fail(filename, "not a PNG file (bad signature)");
    Fail(filename, "unknown image format (only .exr and .png are supported)");
}

void WriteEXR(const std::string &filename, const Image &image, const ImageMetadata &metadata) {
    CheckWritable(filename, image);
    static const char *names[4][4] = {{"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    std::string tmp = TempName(filename);
    try {
        Imf::Header header(image.width, image.height, 1.f, Imath::V2f(0, 0), 1.f, Imf::INCREASING_Y,
                           Imf::ZIP_COMPRESSION);
        for (const auto &[key, value] : metadata) {
            if (key.empty()) Fail(filename, "empty metadata key");
            if (header.find(key) != header.end())
                Fail(filename, "metadata key '" + key + "' is a reserved OpenEXR attribute");
            header.insert(key, Imf::StringAttribute(value));
        }
        if (image.hasChromaticities) {
            const std::array<float, 8> &c = image.chromaticities;
            header.insert("chromaticities", Imf::ChromaticitiesAttribute(Imf::Chromaticities(
                                                Imath::V2f(c[0], c[1]), Imath::V2f(c[2], c[3]),
                                                Imath::V2f(c[4], c[5]), Imath::V2f(c[6], c[7]))));
        }
        Imf::FrameBuffer fb;
        size_t xStride = sizeof(float) * image.channels, yStride = xStride * image.width;
        for (int c = 0; c < image.channels; ++c) {
            header.channels().insert(names[image.channels - 1][c], Imf::Channel(Imf::FLOAT));
            fb.insert(names[image.channels - 1][c],
                      Imf::Slice(Imf::FLOAT, (char *)(image.pixels.data() + c), xStride, yStride));
        }
        {
            Imf::OutputFile file(tmp.c_str(), header);
            file.setFrameBuffer(fb);
            file.writePixels(image.height);
        }  // the destructor writes the line offset table
    } catch (const ImageError &) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw;
    } catch (const std::exception &e) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        Fail(filename, std::string("cannot write OpenEXR file: ") + e.what());
    }
    CommitTemp(tmp, filename);
}

void WritePNG(const std::string &filename, const Image &image) {
    CheckWritable(filename, image);
    int nc = image.channels;
    bool hasAlpha = nc == 2 || nc == 4;
    std::vector<unsigned char> bytes(image.pixels.size());
    for (size_t i = 0; i < bytes.size(); ++i) {
        float v = image.pixels[i];
        bool isAlpha = hasAlpha && int(i % nc) == nc - 1;
        if (!std::isfinite(v)) v = v > 0 ? 1.f : 0.f;  // +Inf -> white, NaN and -Inf -> black
        v = std::clamp(v, 0.f, 1.f);
        if (!isAlpha) v = LinearToSRGB(v);
        bytes[i] = (unsigned char)std::lround(std::clamp(v, 0.f, 1.f) * 255.f);
    }
    png_image png;
    std::memset(&png, 0, sizeof(png));
    png.version = PNG_IMAGE_VERSION;
    png.width = png_uint_32(image.width);
    png.height = png_uint_32(image.height);
    static const png_uint_32 formats[4] = {PNG_FORMAT_GRAY, PNG_FORMAT_GA, PNG_FORMAT_RGB, PNG_FORMAT_RGBA};
    png.format = formats[nc - 1];
    std::string tmp = TempName(filename);
    int ok = png_image_write_to_file(&png, tmp.c_str(), 0, bytes.data(), 0, nullptr);
    if (!ok) {
        std::string why = png.message;
        png_image_free(&png);
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        Fail(filename, "cannot write PNG file: " + why);
    }
    CommitTemp(tmp, filename);
}

void WriteImage(const std::string &filename, const Image &image, const ImageMetadata &metadata) {
    std::string ext = Extension(filename);
    if (ext == ".exr") return WriteEXR(filename, image, metadata);
    if (ext == ".png") return WritePNG(filename, image);
    Fail(filename, "unknown image format '" + ext + "' (use .exr or .png)");
}

}  // namespace lu
