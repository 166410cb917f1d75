// Lucerna CPU backend: progressive rendering over image tiles with oneTBB; one pass is one
// sample per pixel; results depend only on the seed and pass index, never on the thread count.
#pragma once

#include "lucerna/render/render_job.h"
#include "lucerna/scene/builder.h"

namespace lu {

// Renders passes film.passes .. job.spp-1 (so a resumed film continues where it stopped).
RenderStats RenderCPU(const HostScene &scene, const RenderJob &job, FilmAccumulator &film, const PassCallback &onPass = {});

}  // namespace lu
