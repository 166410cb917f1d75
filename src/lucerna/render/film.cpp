// Lucerna: film accumulation, resolve to sRGB, checkpoint files.
#include "lucerna/render/film.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

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
        if (s[3] == 0) continue;
        double xyz[3] = {s[0] / s[3], s[1] / s[3], s[2] / s[3]};
        for (int c = 0; c < 3; ++c)
            img.pixels[3 * p + c] = float(film.xyzToOutput[c][0] * xyz[0] + film.xyzToOutput[c][1] * xyz[1] +
                                          film.xyzToOutput[c][2] * xyz[2]);
    }
    return img;
}

namespace {
constexpr char kMagic[8] = {'L', 'U', 'C', 'K', 'P', 'T', '0', '1'};

void WriteString(std::ofstream &f, const std::string &s) {
    uint32_t n = uint32_t(s.size());
    f.write(reinterpret_cast<const char *>(&n), 4);
    f.write(s.data(), n);
}
bool ReadString(std::ifstream &f, std::string *s) {
    uint32_t n = 0;
    if (!f.read(reinterpret_cast<char *>(&n), 4) || n > (1u << 20)) return false;
    s->resize(n);
    return bool(f.read(s->data(), n));
}
}  // namespace

void SaveCheckpoint(const std::string &path, const FilmAccumulator &film, const CheckpointInfo &info) {
    std::string tmp = path + ".tmp-" + std::to_string(getpid());
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) throw std::runtime_error("cannot write checkpoint " + tmp);
        f.write(kMagic, 8);
        int32_t wh[2] = {film.width, film.height};
        f.write(reinterpret_cast<const char *>(wh), 8);
        f.write(reinterpret_cast<const char *>(&film.passes), 4);
        f.write(reinterpret_cast<const char *>(&info.seed), 4);
        f.write(reinterpret_cast<const char *>(&info.sceneHash), 8);
        f.write(reinterpret_cast<const char *>(&info.seconds), 8);
        WriteString(f, info.sceneFile);
        WriteString(f, info.integrator);
        f.write(reinterpret_cast<const char *>(film.xyzw.data()), std::streamsize(film.xyzw.size() * sizeof(double)));
        f.write(kMagic, 8);
        if (!f) throw std::runtime_error("cannot write checkpoint " + tmp);
    }
    std::filesystem::rename(tmp, path);
}

void LoadCheckpoint(const std::string &path, FilmAccumulator *film, CheckpointInfo *info) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error(path + ": cannot open checkpoint");
    char magic[8];
    int32_t wh[2];
    if (!f.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0) throw std::runtime_error(path + ": not a Lucerna checkpoint");
    if (!f.read(reinterpret_cast<char *>(wh), 8) || wh[0] <= 0 || wh[1] <= 0 || int64_t(wh[0]) * wh[1] > (int64_t(1) << 28))
        throw std::runtime_error(path + ": corrupt checkpoint header");
    uint32_t passes = 0;
    f.read(reinterpret_cast<char *>(&passes), 4);
    f.read(reinterpret_cast<char *>(&info->seed), 4);
    f.read(reinterpret_cast<char *>(&info->sceneHash), 8);
    f.read(reinterpret_cast<char *>(&info->seconds), 8);
    if (!f || !ReadString(f, &info->sceneFile) || !ReadString(f, &info->integrator))
        throw std::runtime_error(path + ": truncated checkpoint");
    film->Resize(wh[0], wh[1]);
    film->passes = passes;
    if (!f.read(reinterpret_cast<char *>(film->xyzw.data()), std::streamsize(film->xyzw.size() * sizeof(double))) ||
        !f.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0)
        throw std::runtime_error(path + ": truncated checkpoint");
}

}  // namespace lu
