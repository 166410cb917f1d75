// Tests of image/image.h: EXR and PNG round trips, metadata, atomic writes, and ImageError on
// missing, truncated and corrupt files (never a crash).
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "lucerna/image/image.h"
#include "support/test_support.h"

namespace lu {
namespace {

namespace fs = std::filesystem;

Image RandomImage(int w, int h, int c, uint32_t seed, float lo, float hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    Image im = MakeImage(w, h, c);
    for (float &v : im.pixels) v = u(rng);
    return im;
}

std::vector<char> ReadBytes(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

void WriteBytes(const std::string &path, const char *data, size_t n) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(data, std::streamsize(n));
}

// Calls ReadImage and requires an ImageError whose message names the file.
void ExpectImageError(const std::string &path) {
    try {
        ReadImage(path);
        ADD_FAILURE() << "no ImageError for " << path;
    } catch (const ImageError &e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}

bool NoTempFiles(const std::string &dir) {
    for (auto &entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().find(".tmp-") != std::string::npos) return false;
    return true;
}

TEST(ImageIO, ExrRoundTripIsExactWithMetadata) {
    std::string dir = test::TempDir("exr_round_trip");
    for (int channels : {1, 2, 3, 4}) {
        Image im = RandomImage(7, 5, channels, 17 + channels, -3, 1000);  // not square: catches transposes
        im.At(0, 0, 0) = 1e-30f;
        im.At(6, 4, channels - 1) = 6.5e4f;
        std::string path = dir + "/a" + std::to_string(channels) + ".exr";
        WriteEXR(path, im, {{"lucerna.spp", "64"}, {"lucerna.integrator", "regpath"}});
        ImageMetadata meta;
        Image back = ReadImage(path, false, &meta);
        ASSERT_EQ(back.width, 7);
        ASSERT_EQ(back.height, 5);
        ASSERT_EQ(back.channels, channels);
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 7; ++x)
                for (int c = 0; c < back.channels; ++c) ASSERT_EQ(back.At(x, y, c), im.At(x, y, c)) << x << "," << y;
        EXPECT_EQ(meta["lucerna.spp"], "64");
        EXPECT_EQ(meta["lucerna.integrator"], "regpath");
    }
    EXPECT_TRUE(NoTempFiles(dir));
}

TEST(ImageIO, ExrKeepsNonFiniteValuesAndCountsThem) {
    std::string dir = test::TempDir("exr_nan");
    Image im = MakeImage(3, 2, 3, 0.5f);
    im.At(1, 0, 2) = std::numeric_limits<float>::quiet_NaN();
    im.At(2, 1, 0) = std::numeric_limits<float>::infinity();
    im.At(0, 1, 1) = -std::numeric_limits<float>::infinity();
    EXPECT_EQ(CountNonFinite(im), 3u);
    WriteEXR(dir + "/n.exr", im);
    Image back = ReadImage(dir + "/n.exr");
    EXPECT_EQ(CountNonFinite(back), 3u);
    EXPECT_TRUE(std::isnan(back.At(1, 0, 2)));
    EXPECT_EQ(CountNonFinite(MakeImage(4, 4, 3, 1.f)), 0u);
}

TEST(ImageIO, ExrReservedMetadataKeyIsRefused) {
    std::string dir = test::TempDir("exr_reserved");
    EXPECT_THROW(WriteEXR(dir + "/r.exr", MakeImage(2, 2, 3), {{"channels", "x"}}), ImageError);
    EXPECT_FALSE(fs::exists(dir + "/r.exr"));
    EXPECT_TRUE(NoTempFiles(dir));
}

// Files written by other programs: half floats, a data window not at the origin, odd channels.
TEST(ImageIO, ExrFromOtherWriters) {
    std::string dir = test::TempDir("exr_foreign");
    const int w = 4, h = 3;
    Imath::Box2i dw(Imath::V2i(10, 20), Imath::V2i(10 + w - 1, 20 + h - 1));
    {
        Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(63, 63)), dw);
        for (const char *n : {"R", "G", "B"}) header.channels().insert(n, Imf::Channel(Imf::HALF));
        std::vector<half> px(size_t(w) * h * 3);
        for (size_t i = 0; i < px.size(); ++i) px[i] = half(0.25f * float(i));
        Imf::FrameBuffer fb;
        for (int c = 0; c < 3; ++c)
            fb.insert(c == 0 ? "R" : c == 1 ? "G" : "B",
                      Imf::Slice::Make(Imf::HALF, px.data() + c, dw, 3 * sizeof(half), 3 * sizeof(half) * w));
        Imf::OutputFile file((dir + "/half.exr").c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(h);
    }
    Image im = ReadImage(dir + "/half.exr");
    ASSERT_EQ(im.width, w);
    ASSERT_EQ(im.height, h);
    ASSERT_EQ(im.channels, 3);
    EXPECT_EQ(im.At(0, 0, 0), 0.f);
    EXPECT_EQ(im.At(1, 0, 2), 0.25f * 5);
    EXPECT_EQ(im.At(3, 2, 2), 0.25f * 35);

    auto writeChannels = [&](const std::string &path, std::vector<std::string> names) {
        Imf::Header header(2, 2);
        std::vector<float> px(4 * names.size(), 2.f);
        Imf::FrameBuffer fb;
        for (size_t c = 0; c < names.size(); ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, (char *)(px.data() + c), sizeof(float) * names.size(),
                                           sizeof(float) * names.size() * 2));
        }
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(2);
    };
    writeChannels(dir + "/z.exr", {"Z"});
    Image z = ReadImage(dir + "/z.exr");
    EXPECT_EQ(z.channels, 1);
    EXPECT_EQ(z.At(1, 1, 0), 2.f);
    writeChannels(dir + "/xz.exr", {"X", "Z"});
    ExpectImageError(dir + "/xz.exr");
}

TEST(ImageIO, PngRoundTripWithinQuantization) {
    std::string dir = test::TempDir("png_round_trip");
    for (int channels : {1, 3, 4}) {
        Image im = RandomImage(9, 4, channels, 5 + channels, 0, 1);
        std::string path = dir + "/p" + std::to_string(channels) + ".png";
        WritePNG(path, im);
        Image back = ReadImage(path);
        Image raw = ReadImage(path, /*pngIsLinear*/ true);
        ASSERT_EQ(back.width, 9);
        ASSERT_EQ(back.height, 4);
        ASSERT_EQ(back.channels, channels);
        for (size_t i = 0; i < im.pixels.size(); ++i) {
            bool alpha = channels == 4 && i % 4 == 3;
            float encoded = alpha ? im.pixels[i] : LinearToSRGB(im.pixels[i]);
            // 8-bit quantization in the encoded domain: within half a step (plus float slack).
            EXPECT_NEAR(raw.pixels[i], encoded, 0.5f / 255 + 1e-6f) << i;
            float expectLinear = alpha ? raw.pixels[i] : SRGBToLinear(raw.pixels[i]);
            EXPECT_NEAR(back.pixels[i], expectLinear, 1e-6f) << i;
        }
    }
    EXPECT_TRUE(NoTempFiles(dir));
}

TEST(ImageIO, PngClampsAndEncodesSRGB) {
    std::string dir = test::TempDir("png_clamp");
    Image im = MakeImage(6, 1, 3);
    float values[6] = {-1.f, 0.f, 0.5f, 1.f, 7.f, std::numeric_limits<float>::quiet_NaN()};
    for (int x = 0; x < 6; ++x)
        for (int c = 0; c < 3; ++c) im.At(x, 0, c) = values[x];
    WritePNG(dir + "/c.png", im);
    Image raw = ReadImage(dir + "/c.png", true);
    EXPECT_EQ(raw.At(0, 0, 0), 0.f);
    EXPECT_EQ(raw.At(1, 0, 0), 0.f);
    EXPECT_EQ(raw.At(2, 0, 0), 188.f / 255);  // sRGB(0.5) = 0.7354 -> 187.5... rounds to 188
    EXPECT_EQ(raw.At(3, 0, 0), 1.f);
    EXPECT_EQ(raw.At(4, 0, 0), 1.f);
    EXPECT_EQ(raw.At(5, 0, 0), 0.f);
    // The sRGB curve itself (IEC 61966-2-1).
    EXPECT_NEAR(LinearToSRGB(0.5f), 0.735357f, 1e-5f);
    EXPECT_NEAR(SRGBToLinear(0.735357f), 0.5f, 1e-5f);
    EXPECT_NEAR(LinearToSRGB(0.002f), 0.02584f, 1e-6f);  // linear segment
}

// 16-bit, gray and palette PNGs written by libpng's simplified API.
TEST(ImageIO, PngFromOtherWriters) {
    std::string dir = test::TempDir("png_foreign");
    auto write = [&](const std::string &path, png_uint_32 format, const void *data, const void *colormap,
                     int colormapEntries) {
        png_image p;
        std::memset(&p, 0, sizeof(p));
        p.version = PNG_IMAGE_VERSION;
        p.width = 3;
        p.height = 2;
        p.format = format;
        p.colormap_entries = png_uint_32(colormapEntries);
        ASSERT_TRUE(png_image_write_to_file(&p, path.c_str(), 0, data, 0, colormap)) << p.message;
    };
    uint16_t gray16[6] = {0, 1000, 20000, 40000, 65535, 12345};
    write(dir + "/g16.png", PNG_FORMAT_LINEAR_Y, gray16, nullptr, 0);
    Image g = ReadImage(dir + "/g16.png", true);
    ASSERT_EQ(g.channels, 1);
    for (int i = 0; i < 6; ++i) EXPECT_FLOAT_EQ(g.pixels[i], gray16[i] / 65535.f);
    Image gs = ReadImage(dir + "/g16.png");
    EXPECT_NEAR(gs.pixels[3], SRGBToLinear(40000 / 65535.f), 1e-6f);

    uint8_t palette[2 * 3] = {255, 0, 0, 0, 0, 255};
    uint8_t indices[6] = {0, 1, 1, 0, 0, 1};
    write(dir + "/pal.png", PNG_FORMAT_RGB_COLORMAP, indices, palette, 2);
    Image pal = ReadImage(dir + "/pal.png", true);
    ASSERT_EQ(pal.channels, 3);
    EXPECT_EQ(pal.At(0, 0, 0), 1.f);
    EXPECT_EQ(pal.At(1, 0, 2), 1.f);
    EXPECT_EQ(pal.At(1, 0, 0), 0.f);
}

TEST(ImageIO, WriteImageChoosesByExtensionAndWritesAtomically) {
    std::string dir = test::TempDir("write_image");
    Image a = MakeImage(4, 4, 3, 0.25f), b = MakeImage(4, 4, 3, 0.75f);
    WriteImage(dir + "/x.EXR", a);
    WriteImage(dir + "/x.EXR", b);  // replaces the existing file
    EXPECT_EQ(ReadImage(dir + "/x.EXR").At(2, 2, 1), 0.75f);
    WriteImage(dir + "/x.png", a);
    EXPECT_EQ(ReadImage(dir + "/x.png").channels, 3);
    EXPECT_THROW(WriteImage(dir + "/x.tga", a), ImageError);
    EXPECT_THROW(WriteImage(dir + "/no/such/dir/x.exr", a), ImageError);
    EXPECT_THROW(WriteImage(dir + "/no/such/dir/x.png", a), ImageError);
    EXPECT_THROW(WriteImage(dir + "/bad.exr", MakeImage(0, 4, 3)), ImageError);
    Image wrongSize = MakeImage(4, 4, 3);
    wrongSize.pixels.pop_back();
    EXPECT_THROW(WriteImage(dir + "/bad.png", wrongSize), ImageError);
    EXPECT_TRUE(NoTempFiles(dir));
    EXPECT_FALSE(fs::exists(dir + "/bad.exr"));
}

TEST(ImageIO, MissingEmptyAndGarbageFilesGiveImageError) {
    std::string dir = test::TempDir("garbage");
    ExpectImageError(dir + "/missing.exr");
    ExpectImageError(dir + "/missing.png");
    ExpectImageError(dir);  // a directory
    WriteBytes(dir + "/empty.exr", "", 0);
    ExpectImageError(dir + "/empty.exr");
    std::string junk = "this is not an image at all, just some text\n";
    for (const char *name : {"/junk.exr", "/junk.png", "/junk.jpg"}) {
        WriteBytes(dir + name, junk.data(), junk.size());
        ExpectImageError(dir + name);
    }
    // Valid magic numbers followed by garbage.
    std::string exrJunk = std::string("\x76\x2f\x31\x01", 4) + junk;
    WriteBytes(dir + "/magic.exr", exrJunk.data(), exrJunk.size());
    ExpectImageError(dir + "/magic.exr");
    std::string pngJunk = std::string("\x89PNG\r\n\x1a\n", 8) + junk;
    WriteBytes(dir + "/magic.png", pngJunk.data(), pngJunk.size());
    ExpectImageError(dir + "/magic.png");
}

TEST(ImageIO, TruncatedFilesGiveImageError) {
    std::string dir = test::TempDir("truncated");
    Image im = RandomImage(32, 24, 3, 3, 0, 1);
    WriteEXR(dir + "/full.exr", im, {{"lucerna.spp", "8"}});
    WritePNG(dir + "/full.png", im);
    for (const char *ext : {".exr", ".png"}) {
        std::vector<char> bytes = ReadBytes(dir + "/full" + ext);
        ASSERT_GT(bytes.size(), 100u);
        for (size_t keep : {size_t(4), size_t(9), size_t(40), bytes.size() / 3, bytes.size() / 2, bytes.size() - 20,
                            bytes.size() - 1}) {
            std::string path = dir + "/cut" + std::to_string(keep) + ext;
            WriteBytes(path, bytes.data(), keep);
            ExpectImageError(path);
        }
    }
}

// Random byte corruption: every outcome must be an image or an ImageError, never a crash.
TEST(ImageIO, CorruptedBytesNeverCrash) {
    std::string dir = test::TempDir("corrupted");
    Image im = RandomImage(16, 8, 3, 4, 0, 1);
    WriteEXR(dir + "/full.exr", im);
    WritePNG(dir + "/full.png", im);
    std::mt19937 rng(12345);
    int errors = 0, reads = 0;
    for (const char *ext : {".exr", ".png"}) {
        std::vector<char> bytes = ReadBytes(dir + "/full" + ext);
        for (int trial = 0; trial < 150; ++trial) {
            std::vector<char> b = bytes;
            int flips = 1 + int(rng() % 4);
            for (int f = 0; f < flips; ++f) b[rng() % b.size()] = char(rng());
            std::string path = dir + "/bad" + ext;
            WriteBytes(path, b.data(), b.size());
            try {
                Image r = ReadImage(path);
                EXPECT_EQ(r.pixels.size(), size_t(r.width) * r.height * r.channels);
                ++reads;
            } catch (const ImageError &) {
                ++errors;
            }
        }
    }
    EXPECT_GT(errors, 0);  // corruption was noticed at least sometimes (PNG CRCs, EXR headers)
    EXPECT_EQ(errors + reads, 300);
}

}  // namespace
}  // namespace lu

namespace lu {
namespace {

// pbrt-v4's own EXRs (data/refs): every shared reference reads with the resolution and spp of its .txt.
TEST(ImageIO, ReadsTheSharedReferences) {
    std::string refs = test::SharedPath("refs");
    ASSERT_TRUE(fs::is_directory(refs)) << refs << " missing";
    int count = 0;
    for (auto &entry : fs::directory_iterator(refs)) {
        if (entry.path().extension() != ".exr") continue;
        std::string txt = (entry.path().parent_path() / (entry.path().stem().string() + ".txt")).string();
        std::ifstream in(txt);
        std::string text((std::istreambuf_iterator<char>(in)), {});
        int w = 0, h = 0, spp = 0;
        size_t at = text.find("resolution: ");
        ASSERT_NE(at, std::string::npos) << txt;
        ASSERT_EQ(std::sscanf(text.c_str() + at, "resolution: %dx%d spp: %d", &w, &h, &spp), 3) << txt;
        ImageMetadata meta;
        Image im = ReadImage(entry.path().string(), false, &meta);
        EXPECT_EQ(im.width, w) << entry.path();
        EXPECT_EQ(im.height, h) << entry.path();
        EXPECT_EQ(im.channels, 3);
        EXPECT_EQ(CountNonFinite(im), 0u);
        EXPECT_EQ(meta["samplesPerPixel"], std::to_string(spp));
        ++count;
    }
    EXPECT_EQ(count, 9);  // every reference of data/refs/README.md
}

}  // namespace
}  // namespace lu
