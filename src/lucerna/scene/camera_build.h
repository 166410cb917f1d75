// Lucerna (host): construction of the shared camera and filter data (camera/camera.h,
// camera/filter.h) from pbrt-v4 parameters: PerspectiveCamera, the filters and their sampling tables.
#pragma once

#include <string>
#include <vector>

#include "lucerna/camera/camera.h"
#include "lucerna/camera/filter.h"

namespace lu {

// pbrt-v4's perspective camera: fovDeg spans the shorter image axis; the screen window defaults
// to [-a, a] x [-1, 1] for aspect a = width/height > 1, else [-1, 1] x [-1/a, 1/a];
// screenWindow (xmin, xmax, ymin, ymax) overrides it; frameAspectRatio > 0 replaces width/height
// in that default. renderFromCamera maps the left-handed camera space to render space.
CameraData MakePerspectiveCamera(const Transform &renderFromCamera, int width, int height, Float fovDeg,
                                 Float lensRadius, Float focalDistance, const Float *screenWindow,
                                 Float frameAspectRatio = 0);

// pbrt-v4's orthographic camera: the same screen window as the perspective camera, mapped to the
// plane z = 0 of camera space (pbrt-v4's Orthographic(0, 1) is the identity there).
CameraData MakeOrthographicCamera(const Transform &renderFromCamera, int width, int height, Float lensRadius,
                                  Float focalDistance, const Float *screenWindow, Float frameAspectRatio = 0);

// pbrt-v4's spherical camera: equal-area (kind SphericalEqualArea) or equirectangular mapping of
// the whole image to the sphere of directions.
CameraData MakeSphericalCamera(const Transform &renderFromCamera, int width, int height, CameraKind kind);

// pbrt-v4's filter by name with its defaults: gaussian (radius 1.5, sigma 0.5), box (0.5),
// triangle (2), mitchell (2, B = C = 1/3), sinc (pbrt-v4's LanczosSincFilter: 4, tau 3). A
// radius, sigma or tau <= 0 (or NaN) and a NaN B or C mean "not given": the default is used.
// Throws std::invalid_argument for an unknown name.
FilterData MakeFilter(const std::string &name, Float xradius = -1, Float yradius = -1, Float sigma = -1,
                      Float B = NAN, Float C = NAN, Float tau = -1);

// Tabulates |f| for gaussian, mitchell and sinc filters into a Distribution2D over [0,1]^2 (cells of
// 1/32 pixel, as pbrt-v4), appends it to dists/distData and sets f.distribution. Box and
// triangle need no table (f.distribution = NoIndex).
void BuildFilterDistribution(FilterData &f, std::vector<Distribution2D> &dists, std::vector<Float> &distData);
// FilmData::filterWeightFloor for filter f (its distribution built): half a sample's expected
// weight for mitchell and sinc, 0 for the filters without negative lobes.
Float FilterWeightFloor(const FilterData &f, const std::vector<Distribution2D> &dists);

}  // namespace lu
