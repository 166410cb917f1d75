// Lucerna: light selection proportional to power through SceneView::lightCdf (host and device),
// and the host helpers that build it and the image-light distributions; after pbrt-v4's
// PowerLightSampler (lightsamplers.cpp) and the Phi() methods of lights.cpp.
#pragma once

#include "lucerna/lights/lights.h"

namespace lu {

// Picks a light with probability lightCdf[i+1] - lightCdf[i]; NoIndex (and *pmf = 0) if the scene
// has no lights.
LU_INLINE uint32_t SampleLight(const SceneView &s, Float u, Float *pmf) {
    uint32_t n = s.lights.size;
    if (n == 0 || s.lightCdf.size != n + 1) {
        if (pmf) *pmf = 0;
        return NoIndex;
    }
    uint32_t i = FindCdfInterval(s.lightCdf.ptr, n, u);
    if (pmf) *pmf = s.lightCdf[i + 1] - s.lightCdf[i];
    return i;
}

// Probability that SampleLight picks light i.
LU_INLINE Float LightPMF(const SceneView &s, uint32_t light) {
    if (light >= s.lights.size || s.lightCdf.size != s.lights.size + 1) return 0;
    return s.lightCdf[light + 1] - s.lightCdf[light];
}

}  // namespace lu
