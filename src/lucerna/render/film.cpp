// Lucerna: film accumulation, resolve to sRGB, checkpoint files (versioned, CRC-32 checked).
#include "lucerna/render/film.h"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace lu {

void FilmAccumulator::Commit(const PassBuffer &pass) {
    size_t n = xyzw.size();
    for (size_t i = 0; i < n; ++i) xyzw[i] += double(pass.xyzw[i]);
    ++passes;
}

Image FilmAccumulator::Resolve(const FilmData &film) const {
    Image img;
    img.width = width;
    img.height = height;
    img.channels = 3;
    img.pixels.assign(size_t(width) * height * 3, 0.f);
    for (size_t p = 0; p < size_t(width) * height; ++p) {
        const double *s = &xyzw[4 * p];
        // pbrt-v4's sum / weightSum, except that the weight sum of a filter with negative lobes
        // is kept at or above half its expectation: its signed sum can come arbitrarily near 0
        // (a sinc at 4 spp), which would blow the pixel up. Consistent: the floor acts with a
        // probability that falls to 0 as the sample count grows.
        double w = std::max(s[3], double(passes) * double(film.filterWeightFloor));
        if (w == 0) continue;
        double xyz[3] = {s[0] / w, s[1] / w, s[2] / w};
        for (int c = 0; c < 3; ++c)
            img.pixels[3 * p + c] = float(film.xyzToOutput[c][0] * xyz[0] + film.xyzToOutput[c][1] * xyz[1] +
                                          film.xyzToOutput[c][2] * xyz[2]);
    }
    return img;
}

// ---- Checkpoints ----
// Format 2, native byte order (little-endian on every supported machine):
//   "LUCKPT" + two version digits ("02"), u32 width, height, passes, seed, u64 scene hash,
//   f64 seconds, string scene file, string integrator (u32 length + bytes), u64 count of the sums
//   (width * height * 4), the sums (f64), and the CRC-32 (zlib) of every byte before it.
// Format 1 ("LUCKPT01") had no count and no checksum: it is refused by name.

namespace {

constexpr char kMagicPrefix[6] = {'L', 'U', 'C', 'K', 'P', 'T'};
constexpr int kCheckpointVersion = 2;

[[noreturn]] void Corrupt(const std::string &path, const std::string &why) {
    throw std::runtime_error(path + ": corrupt checkpoint: " + why);
}

// Writes through a CRC-32.
class CrcWriter {
  public:
    explicit CrcWriter(const std::string &path) : f_(path, std::ios::binary | std::ios::trunc) {}
    bool Good() const { return bool(f_); }
    void Put(const void *data, size_t n) {
        const auto *p = static_cast<const unsigned char *>(data);
        for (size_t done = 0; done < n;) {
            uInt chunk = uInt(std::min<size_t>(n - done, size_t(1) << 30));
            crc_ = crc32(crc_, p + done, chunk);
            done += chunk;
        }
        f_.write(static_cast<const char *>(data), std::streamsize(n));
    }
    template <typename T> void Put(const T &v) { Put(&v, sizeof v); }
    void PutString(const std::string &s) {
        uint32_t n = uint32_t(s.size());
        Put(n);
        Put(s.data(), n);
    }
    uint32_t Crc() const { return uint32_t(crc_); }
    std::ofstream &Stream() { return f_; }

  private:
    std::ofstream f_;
    uLong crc_ = crc32(0L, Z_NULL, 0);
};

// Reads through a CRC-32, never past `limit` bytes (the file's size less its checksum).
class CrcReader {
  public:
    CrcReader(std::istream &f, const std::string &path, uint64_t limit, uLong crc)
        : f_(f), path_(path), left_(limit), crc_(crc) {}
    void Get(void *data, size_t n, const char *what) {
        if (n > left_) Corrupt(path_, std::string("truncated in the ") + what);
        if (!f_.read(static_cast<char *>(data), std::streamsize(n))) Corrupt(path_, std::string("cannot read the ") + what);
        const auto *p = static_cast<const unsigned char *>(data);
        for (size_t done = 0; done < n;) {
            uInt chunk = uInt(std::min<size_t>(n - done, size_t(1) << 30));
            crc_ = crc32(crc_, p + done, chunk);
            done += chunk;
        }
        left_ -= n;
    }
    template <typename T> T Get(const char *what) {
        T v;
        Get(&v, sizeof v, what);
        return v;
    }
    std::string GetString(const char *what) {
        uint32_t n = Get<uint32_t>(what);
        if (n > (1u << 20) || n > left_) Corrupt(path_, std::string("bad length of the ") + what);
        std::string s(n, '\0');
        Get(s.data(), n, what);
        return s;
    }
    uint64_t Left() const { return left_; }
    uint32_t Crc() const { return uint32_t(crc_); }

  private:
    std::istream &f_;
    const std::string &path_;
    uint64_t left_;
    uLong crc_;
};

}  // namespace

void SaveCheckpoint(const std::string &path, const FilmAccumulator &film, const CheckpointInfo &info) {
    std::string tmp = path + ".tmp-" + std::to_string(getpid());
    auto fail = [&](const std::string &why) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw std::runtime_error("cannot write checkpoint " + path + ": " + why);
    };
    {
        CrcWriter w(tmp);
        if (!w.Good()) fail(std::strerror(errno));
        char magic[8];
        std::memcpy(magic, kMagicPrefix, 6);
        magic[6] = char('0' + kCheckpointVersion / 10);
        magic[7] = char('0' + kCheckpointVersion % 10);
        w.Put(magic, 8);
        w.Put(uint32_t(film.width));
        w.Put(uint32_t(film.height));
        w.Put(film.passes);
        w.Put(info.seed);
        w.Put(info.sceneHash);
        w.Put(info.seconds);
        w.PutString(info.sceneFile);
        w.PutString(info.integrator);
        w.Put(uint64_t(film.xyzw.size()));
        w.Put(film.xyzw.data(), film.xyzw.size() * sizeof(double));
        uint32_t crc = w.Crc();
        w.Stream().write(reinterpret_cast<const char *>(&crc), 4);
        w.Stream().close();
        if (!w.Stream()) fail("write error");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) fail(ec.message());
}

void LoadCheckpoint(const std::string &path, FilmAccumulator *film, CheckpointInfo *info) {
    std::ifstream f(path, std::ios::binary);
    std::error_code ec;
    uint64_t size = std::filesystem::file_size(path, ec);
    if (!f || ec) throw std::runtime_error(path + ": cannot open checkpoint" + (ec ? ": " + ec.message() : ""));
    ReadCheckpoint(f, size, path, film, info);
}

void ReadCheckpoint(std::istream &f, uint64_t size, const std::string &path, FilmAccumulator *film, CheckpointInfo *info) {
    char magic[8];
    if (size < 8 || !f.read(magic, 8) || std::memcmp(magic, kMagicPrefix, 6) != 0)
        throw std::runtime_error(path + ": not a Lucerna checkpoint");
    if (!std::isdigit((unsigned char)magic[6]) || !std::isdigit((unsigned char)magic[7]))
        throw std::runtime_error(path + ": not a Lucerna checkpoint (no format version)");
    int version = (magic[6] - '0') * 10 + (magic[7] - '0');
    if (version != kCheckpointVersion)
        throw std::runtime_error(path + ": checkpoint format version " + std::to_string(version) +
                                 (version < kCheckpointVersion ? " (an older Lucerna's, without a checksum)" : "") +
                                 " is not read by this Lucerna, which reads version " +
                                 std::to_string(kCheckpointVersion) + "; render again with --checkpoint to make a new one");
    if (size < 8 + 4) Corrupt(path, "too short");
    CrcReader r(f, path, size - 8 - 4, crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef *>(magic), 8));
    CheckpointInfo in;
    uint32_t width = r.Get<uint32_t>("header"), height = r.Get<uint32_t>("header");
    uint32_t passes = r.Get<uint32_t>("header");
    in.seed = r.Get<uint32_t>("header");
    in.sceneHash = r.Get<uint64_t>("header");
    in.seconds = r.Get<double>("header");
    in.sceneFile = r.GetString("scene file name");
    in.integrator = r.GetString("integrator name");
    uint64_t count = r.Get<uint64_t>("header");
    if (width == 0 || height == 0 || uint64_t(width) * height > (uint64_t(1) << 28) || count != uint64_t(width) * height * 4)
        Corrupt(path, "bad film size " + std::to_string(width) + "x" + std::to_string(height));
    if (r.Left() != count * sizeof(double))
        Corrupt(path, "the file has " + std::to_string(r.Left()) + " bytes of sums where " +
                          std::to_string(count * sizeof(double)) + " were expected");
    FilmAccumulator loaded;
    loaded.Resize(int(width), int(height));
    loaded.passes = passes;
    r.Get(loaded.xyzw.data(), loaded.xyzw.size() * sizeof(double), "sums");
    uint32_t stored = 0;
    if (!f.read(reinterpret_cast<char *>(&stored), 4)) Corrupt(path, "no checksum");
    if (stored != r.Crc()) {
        char b[96];
        std::snprintf(b, sizeof b, "checksum mismatch (stored CRC-32 %08x, computed %08x)", stored, r.Crc());
        Corrupt(path, b);
    }
    for (double v : loaded.xyzw)
        if (!std::isfinite(v)) Corrupt(path, "non-finite sums");
    if (!std::isfinite(in.seconds) || in.seconds < 0) Corrupt(path, "bad render time");
    *film = std::move(loaded);
    *info = std::move(in);
}

}  // namespace lu
