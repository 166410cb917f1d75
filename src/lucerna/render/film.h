// Lucerna: film accumulation shared by every backend (host), after pbrt-v4's RGBFilm with the
// "cie1931" sensor: each sample adds weight * XYZ(L) (times the imaging ratio) to its pixel; the
// resolved image is XYZ -> linear sRGB of sum / weightSum. Sums are kept in double so that a
// checkpointed and resumed render is bit-identical to an uninterrupted one.
#pragma once

#include <cstdint>
#include <istream>
#include <map>
#include <string>
#include <vector>

#include "lucerna/core/scene_data.h"
#include "lucerna/image/image.h"
#include "lucerna/spectrum/color.h"

namespace lu {

// One pass's samples (one per pixel) before they are committed to the film.
struct PassBuffer {
    int width = 0, height = 0;
    std::vector<float> xyzw;  // 4 floats per pixel: weighted X, Y, Z and the filter weight
    void Resize(int w, int h) { width = w; height = h; xyzw.assign(size_t(w) * h * 4, 0.f); }
};

struct FilmAccumulator {
    int width = 0, height = 0;
    uint32_t passes = 0;        // committed passes (samples per pixel)
    std::vector<double> xyzw;   // 4 doubles per pixel

    void Resize(int w, int h) { width = w; height = h; passes = 0; xyzw.assign(size_t(w) * h * 4, 0.0); }
    void Commit(const PassBuffer &pass);   // adds a complete pass
    // Linear sRGB (3 channels) of the accumulated samples.
    Image Resolve(const FilmData &film) const;
};

// Checkpoints: the accumulation state and everything needed to continue deterministically.
struct CheckpointInfo {
    std::string sceneFile;
    std::string integrator;
    uint32_t seed = 0;
    uint64_t sceneHash = 0;      // identifies the scene + options the sums belong to
    double seconds = 0;          // render time so far
};
// Format 2 (film.cpp): a version and a CRC-32 of every byte. Atomic (temporary file + rename).
// Throws std::runtime_error naming the file on I/O failure.
void SaveCheckpoint(const std::string &path, const FilmAccumulator &film, const CheckpointInfo &info);
// Throws std::runtime_error naming the file when it is missing, of another format version,
// truncated, longer than its header says, fails its checksum or holds non-finite sums; the film
// and info are then unchanged.
void LoadCheckpoint(const std::string &path, FilmAccumulator *film, CheckpointInfo *info);
// The same from a stream of `size` bytes; `name` is the file named in the messages (fuzz/fuzz_checkpoint.cpp).
void ReadCheckpoint(std::istream &in, uint64_t size, const std::string &name, FilmAccumulator *film, CheckpointInfo *info);

}  // namespace lu
