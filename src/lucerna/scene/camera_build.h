// Lucerna (host): construction of the shared camera and filter data (camera/camera.h,
// camera/filter.h) from pbrt-v4 parameters: PerspectiveCamera, the filters and their sampling tables.
#pragma once

#include <string>
#include <vector>

#include "lucerna/camera/camera.h"
#include "lucerna/camera/filter.h"
#include "lucerna/scene/error.h"

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
// Sets c.pixelWidth and c.pixelSpread from the rays through the image centre and its neighbours
// one pixel over (through the lens centre; for a realistic camera the first lens position that
// gets through): the larger of the two directions' angles and origins' offsets.
void SetPixelFootprint(CameraData &c);

// One row of a realistic camera's lens table as the file gives it (millimeters) and where it is.
struct LensTableRow {
    double curvatureRadius = 0, thickness = 0, eta = 0, apertureDiameter = 0;
};

// Reads a pbrt-v4 lens table: rows of four numbers (curvature radius, thickness, index of
// refraction, aperture diameter; mm; radius 0 is the aperture stop), '#' to the end of a line a
// comment. Throws SceneError at path:line:col for a non-number or a row without four values, at
// `at` for a file that cannot be read or holds no row.
std::vector<LensTableRow> ReadLensTable(const std::string &path, const FileLoc &at);

// pbrt-v4's RealisticCamera constructor: the elements scaled to meters, the stop's diameter
// replaced by apertureDiameterMm (kept, with *apertureWarning set, when that is larger than the
// stop), the rear element-film distance from FocusThickLens(focusDistance) (meters), and the exit
// pupil bounds (pupilIntervals radial film intervals, pupilSamples rays each; pbrt-v4 uses 64
// and 2^20, 2^18 here: the bound is grown by the grid spacing either way). filmDiagonalMm: the Film's "diagonal". elements and pupilBounds receive the arrays the
// returned CameraData's spans must be pointed at (HostScene::View does it). Returns false with
// *error set when the lens cannot be focused there.
bool MakeRealisticCamera(const Transform &renderFromCamera, int width, int height, Float filmDiagonalMm,
                         const std::vector<LensTableRow> &table, Float apertureDiameterMm, Float focusDistance,
                         CameraData *camera, std::vector<LensElement> *elements, std::vector<Bounds2f> *pupilBounds,
                         std::string *error, std::string *apertureWarning = nullptr, int pupilIntervals = 64,
                         int pupilSamples = 1 << 18);

// pbrt-v4's BoundExitPupil: the bound on the rear element's plane of the points through which a
// ray from film points (x, 0, 0), x in [filmX0, filmX1], gets through the lens system (nSamples
// rays on a radical-inverse grid over 1.5x the rear element, expanded by the grid spacing).
Bounds2f BoundExitPupil(Span<LensElement> elements, Float filmX0, Float filmX1, int nSamples);

// pbrt-v4's thick-lens approximation: the principal plane pz[i] and focal point fz[i] (camera
// space z, meters) of rays entering from the scene (i = 0) and from the film (i = 1), traced
// parallel to the axis at height 0.001 * filmDiagonal (meters). False when a ray is blocked.
bool ComputeThickLensApproximation(Span<LensElement> elements, Float filmDiagonal, Float pz[2], Float fz[2]);

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
