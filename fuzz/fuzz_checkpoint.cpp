// libFuzzer target: the checkpoint reader (render/film.cpp) must never crash, read out of bounds
// or allocate beyond the file's size; bad input may only throw std::runtime_error, and an accepted
// checkpoint must be consistent (its sums sized by its resolution, all finite).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

#include "lucerna/render/film.h"

using namespace lu;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    std::istringstream in(std::string(reinterpret_cast<const char *>(data), size));
    FilmAccumulator film;
    CheckpointInfo info;
    try {
        ReadCheckpoint(in, size, "fuzz.ckpt", &film, &info);
    } catch (const std::runtime_error &e) {
        if (std::string(e.what()).rfind("fuzz.ckpt: ", 0) != 0) std::abort();   // every message names the file
        if (film.width != 0 || film.passes != 0) std::abort();                  // a refused file changes nothing
        return 0;
    }
    if (film.width <= 0 || film.height <= 0 || film.xyzw.size() != size_t(film.width) * film.height * 4) std::abort();
    for (double v : film.xyzw)
        if (!std::isfinite(v)) std::abort();
    if (!std::isfinite(info.seconds) || info.seconds < 0) std::abort();
    return 0;
}
