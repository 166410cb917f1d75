// Lucerna: host set-up of pbrt-v4's realistic camera: the lens table reader, the thick-lens
// approximation that focuses the lens system, and the exit pupil bounds (after pbrt-v4's
// RealisticCamera constructor, ComputeThickLensApproximation, FocusThickLens, BoundExitPupil).
// The per-ray tracing shared with the GPU is camera/realistic.h.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "lucerna/camera/realistic.h"
#include "lucerna/sampling/sequences.h"
#include "lucerna/scene/camera_build.h"

namespace lu {

std::vector<LensTableRow> ReadLensTable(const std::string &path, const FileLoc &at) {
    std::ifstream in(path);
    if (!in) throw SceneError(at, "cannot read the lens description file \"" + path + "\"");
    std::vector<LensTableRow> rows;
    auto file = std::make_shared<const std::string>(path);
    auto locAt = [&](int line, int col) {
        FileLoc loc;
        loc.file = file;
        loc.line = line;
        loc.col = col;
        return loc;
    };
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        size_t hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        std::vector<double> values;
        std::string word;
        int column = 1;
        while (words >> word) {
            size_t pos = line.find(word, size_t(std::max(0, column - 1)));
            column = int(pos) + 1;
            char *end = nullptr;
            double v = std::strtod(word.c_str(), &end);
            if (end != word.c_str() + word.size() || !std::isfinite(v))
                throw SceneError(locAt(lineNo, column), "\"" + word + "\" is not a number (a lens table row is: curvature radius, thickness, index of refraction, aperture diameter, in mm)");
            values.push_back(v);
            column += int(word.size());
        }
        if (values.empty()) continue;
        if (values.size() != 4)
            throw SceneError(locAt(lineNo, 1), "a lens table row has 4 values (curvature radius, thickness, index of refraction, aperture diameter), this one has " + std::to_string(values.size()));
        LensTableRow r{values[0], values[1], values[2], values[3]};
        if (!(r.apertureDiameter > 0))
            throw SceneError(locAt(lineNo, 1), "the aperture diameter (4th value) must be positive");
        if (r.thickness < 0 || r.eta < 0)
            throw SceneError(locAt(lineNo, 1), "the thickness and the index of refraction must not be negative");
        rows.push_back(r);
    }
    if (rows.empty()) throw SceneError(at, "the lens description file \"" + path + "\" holds no lens interface");
    return rows;
}

namespace {

// pbrt-v4's ComputeCardinalPoints (lens-space z = -camera z): the focal point where the exiting
// ray crosses the axis, the principal plane where it meets the entering ray's height.
void CardinalPoints(const Ray &rIn, const Ray &rOut, Float *pz, Float *fz) {
    Float tf = -rOut.o.x / rOut.d.x;
    *fz = -rOut(tf).z;
    Float tp = (rIn.o.x - rOut.o.x) / rOut.d.x;
    *pz = -rOut(tp).z;
}

}  // namespace

bool ComputeThickLensApproximation(Span<LensElement> elements, Float filmDiagonal, Float pz[2], Float fz[2]) {
    Float x = Float(0.001) * filmDiagonal;
    Ray rScene, rFilm;
    rScene.o = Vec3f(x, 0, LensFrontZ(elements) + 1);
    rScene.d = Vec3f(0, 0, -1);
    if (!TraceLensesFromScene(elements, rScene, &rFilm) || rFilm.d.x == 0) return false;
    CardinalPoints(rScene, rFilm, &pz[0], &fz[0]);
    rFilm.o = Vec3f(x, 0, LensRearZ(elements) - 1);
    rFilm.d = Vec3f(0, 0, 1);
    if (TraceLensesFromFilm(elements, rFilm, &rScene) == 0 || rScene.d.x == 0) return false;
    CardinalPoints(rFilm, rScene, &pz[1], &fz[1]);
    return true;
}

Bounds2f BoundExitPupil(Span<LensElement> elements, Float filmX0, Float filmX1, int nSamples) {
    Bounds2f pupil;
    Float rearRadius = RearElementRadius(elements);
    Float r = Float(1.5) * rearRadius;
    for (int i = 0; i < nSamples; ++i) {
        Vec3f pFilm(Lerp((i + Float(0.5)) / nSamples, filmX0, filmX1), 0, 0);
        Vec3f pRear(Lerp(RadicalInverse(0, uint64_t(i)), -r, r), Lerp(RadicalInverse(1, uint64_t(i)), -r, r),
                    LensRearZ(elements));
        Vec2f p(pRear.x, pRear.y);
        Ray ray;
        ray.o = pFilm;
        ray.d = pRear - pFilm;
        if (pupil.Inside(p) || TraceLensesFromFilm(elements, ray, nullptr) != 0) pupil.Expand(p);
    }
    if (pupil.IsDegenerate()) return Bounds2f();
    // Grow by the sample spacing so that the bound covers the pupil between the samples.
    Float delta = 2 * std::sqrt(2 * Sqr(2 * r)) / std::sqrt(Float(nSamples));
    pupil.pMin = pupil.pMin - Vec2f(delta, delta);
    pupil.pMax = pupil.pMax + Vec2f(delta, delta);
    return pupil;
}

bool MakeRealisticCamera(const Transform &renderFromCamera, int width, int height, Float filmDiagonalMm,
                         const std::vector<LensTableRow> &table, Float apertureDiameterMm, Float focusDistance,
                         CameraData *camera, std::vector<LensElement> *elements, std::vector<Bounds2f> *pupilBounds,
                         std::string *error, std::string *apertureWarning, int pupilIntervals, int pupilSamples) {
    elements->clear();
    for (const LensTableRow &row : table) {
        double diameter = row.apertureDiameter;
        if (row.curvatureRadius == 0) {
            if (apertureDiameterMm > diameter) {
                if (apertureWarning)
                    *apertureWarning = "\"aperturediameter\" " + std::to_string(apertureDiameterMm) +
                                       " mm is larger than the lens's stop (" + std::to_string(diameter) +
                                       " mm); the stop's diameter is used";
            } else {
                diameter = apertureDiameterMm;
            }
        }
        elements->push_back(LensElement{Float(row.curvatureRadius / 1000), Float(row.thickness / 1000), Float(row.eta),
                                        Float(diameter / 1000 / 2)});
    }
    Float diagonal = filmDiagonalMm / 1000;
    Span<LensElement> span{elements->data(), uint32_t(elements->size())};

    // FocusThickLens: move the film so that the plane at focusDistance is in focus.
    Float pz[2], fz[2];
    if (!ComputeThickLensApproximation(span, diagonal, pz, fz)) {
        *error = "a ray parallel to the axis does not get through the lens system (no thick-lens approximation)";
        return false;
    }
    Float f = fz[0] - pz[0];
    Float z = -focusDistance;
    Float c = (pz[1] - z - pz[0]) * (pz[1] - z - 4 * f - pz[0]);
    if (!(c > 0) || !(f > 0)) {
        *error = "the lens system cannot focus at \"focusdistance\" " + std::to_string(focusDistance) +
                 " m (too close for a focal length of " + std::to_string(f * 1000) + " mm)";
        return false;
    }
    Float delta = (pz[1] - z + pz[0] - std::sqrt(c)) / 2;
    elements->back().thickness += delta;
    if (!(elements->back().thickness > 0)) {
        *error = "focusing at \"focusdistance\" " + std::to_string(focusDistance) + " m puts the film inside the lens";
        return false;
    }

    CameraData cam;
    cam.kind = CameraKind::Realistic;
    cam.renderFromCamera = renderFromCamera;
    cam.width = width;
    cam.height = height;
    Float aspect = Float(height) / Float(width);
    Float x = std::sqrt(Sqr(diagonal) / (1 + Sqr(aspect))), y = aspect * x;
    cam.physicalExtentMin = Vec2f(-x / 2, -y / 2);
    cam.physicalExtentMax = Vec2f(x / 2, y / 2);
    cam.filmDiagonal = diagonal;

    // The exit pupil bounds for pupilIntervals radial intervals of the film, in parallel.
    pupilBounds->assign(size_t(pupilIntervals), Bounds2f());
    span = Span<LensElement>{elements->data(), uint32_t(elements->size())};
    unsigned nThreads = std::max(1u, std::min(std::thread::hardware_concurrency(), unsigned(pupilIntervals)));
    std::vector<std::thread> threads;
    for (unsigned t = 0; t < nThreads; ++t)
        threads.emplace_back([&, t] {
            for (int i = int(t); i < pupilIntervals; i += int(nThreads)) {
                Float r0 = Float(i) / pupilIntervals * diagonal / 2, r1 = Float(i + 1) / pupilIntervals * diagonal / 2;
                (*pupilBounds)[size_t(i)] = BoundExitPupil(span, r0, r1, pupilSamples);
            }
        });
    for (std::thread &th : threads) th.join();
    *camera = cam;
    return true;
}

}  // namespace lu
