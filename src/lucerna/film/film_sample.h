// Lucerna: one camera sample onto the film (host and device), after pbrt-v4's RGBFilm::AddSample
// with the "cie1931" sensor: the spectral radiance becomes XYZ (times the imaging ratio), samples
// that are not finite or negative are kept off the film, the largest component is clamped to
// maxComponentValue, and the pixel gets weight * XYZ and the filter weight.
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/spectrum/color.h"

namespace lu {

// Writes the sample's pass-buffer pixel xyzw (4 floats: weighted X, Y, Z and the filter weight).
// Returns false, writing zeros, for a rejected sample (the caller counts it).
LU_INLINE bool WriteFilmSample(const SampledSpectrum &L, const SampledWavelengths &lambda, Float filterWeight,
                               const SceneView &scene, float *xyzw) {
    Float xyz[3];
    SensorXYZ(L, lambda, scene.spectra, scene.film.imagingRatio, xyz);
    bool ok = IsFinite(xyz[0]) && IsFinite(xyz[1]) && IsFinite(xyz[2]) && IsFinite(filterWeight) && L.MinValue() >= 0;
    if (!ok) {
        xyzw[0] = xyzw[1] = xyzw[2] = xyzw[3] = 0;
        return false;
    }
    Float m = Max(xyz[0], Max(xyz[1], xyz[2]));
    if (m > scene.film.maxComponentValue)
        for (Float &c : xyz) c *= scene.film.maxComponentValue / m;
    xyzw[0] = filterWeight * xyz[0];
    xyzw[1] = filterWeight * xyz[1];
    xyzw[2] = filterWeight * xyz[2];
    xyzw[3] = filterWeight;
    return true;
}

}  // namespace lu
