// Lucerna: the first rejected sample of a render in words (where in the image, what value, and
// which material, light or medium of the scene produced it, with its file:line), for the summary
// on stderr and --stats-json (host only).
#pragma once

#include <string>

#include "lucerna/integrators/stats.h"
#include "lucerna/scene/builder.h"

namespace lu {

// "NaN", "an infinite value", "a negative value".
const char *BadValueName(BadValue v);
// "emission", "light connection", "scattering", "medium", "film" (for JSON).
const char *RejectCauseName(RejectCause c);
// The scene entity of a rejected sample: `Material "conductor" at scene.pbrt:4:1` ("" for Film).
std::string RejectedSource(const HostScene &scene, const RejectedSample &r);
// One sentence: `at pixel (3, 4), depth 2: NaN in a light connection at a surface of Material
// "conductor" at scene.pbrt:4:1 (its BSDF or the light's radiance)`.
std::string DescribeRejectedSample(const HostScene &scene, const RejectedSample &r);

}  // namespace lu
