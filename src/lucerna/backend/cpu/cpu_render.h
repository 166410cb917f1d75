// Lucerna CPU backend: each pass over 16x16-pixel tiles with oneTBB, through the shared pass
// driver (render/pass_driver.h); rays by Embree, or by the shared BVH traversal that the CUDA
// kernel runs (settings.cpuTracer). Results depend only on the seed and the pass index, never on
// the thread count.
#pragma once

#include "lucerna/render/pass_driver.h"
#include "lucerna/scene/builder.h"

namespace lu {

// Renders passes film.passes .. settings.spp - 1 (resizing an empty film to the scene's resolution).
RenderStats RenderCPU(const HostScene &scene, const RenderSettings &settings, FilmAccumulator &film,
                      const RenderControl &control = {});

}  // namespace lu
