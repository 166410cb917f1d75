// Lucerna: pbrt-v4's RealisticCamera ray tracing through a lens system (host and device):
// spherical interfaces, the aperture stop, the exit pupil sampling and the camera ray weight
// cos^4(theta) / (pdf_A * LensRearZ^2). After pbrt-v4's cameras.h/.cpp (TraceLensesFromFilm,
// TraceLensesFromScene, SampleExitPupil, GenerateRay); the host set-up is scene/lens_build.cpp.
//
// Lens space is pbrt-v4's: camera space with z negated, the film at z = 0, the lens system at
// z < 0 (the rear element's vertex at z = -LensRearZ, the front one's at -LensFrontZ).
#pragma once

#include "lucerna/core/scene_data.h"

namespace lu {

// Distance from the film to the rear element's vertex (meters).
LU_INLINE Float LensRearZ(Span<LensElement> e) { return e[e.size - 1].thickness; }

// Distance from the film to the front element's vertex (meters).
LU_INLINE Float LensFrontZ(Span<LensElement> e) {
    Float z = 0;
    for (uint32_t i = 0; i < e.size; ++i) z += e[i].thickness;
    return z;
}

LU_INLINE Float RearElementRadius(Span<LensElement> e) { return e[e.size - 1].apertureRadius; }

// The intersection of ray (lens space) with the sphere of `radius` centred at (0, 0, zCenter)
// on the side that faces the ray (pbrt-v4's choice of root); n is the unit normal facing -ray.d.
LU_INLINE bool IntersectSphericalElement(Float radius, Float zCenter, const Ray &ray, Float *t, Vec3f *n) {
    Vec3f o = ray.o - Vec3f(0, 0, zCenter);
    Float A = Dot(ray.d, ray.d), B = 2 * Dot(ray.d, o), C = Dot(o, o) - Sqr(radius);
    Float discrim = B * B - 4 * A * C;
    if (discrim < 0) return false;
    Float root = std::sqrt(discrim);
    Float q = B < 0 ? -Float(0.5) * (B - root) : -Float(0.5) * (B + root);   // stable roots
    Float t0 = q / A, t1 = C / q;
    if (t0 > t1) { Float tmp = t0; t0 = t1; t1 = tmp; }
    bool useCloserT = (ray.d.z > 0) != (radius < 0);
    *t = useCloserT ? t0 : t1;
    if (!(*t >= 0)) return false;
    *n = FaceForward(Normalize(o + ray.d * *t), -ray.d);
    return true;
}

// Camera space <-> lens space (z negated; the same map both ways).
LU_INLINE Ray FlipZ(const Ray &r) {
    Ray f;
    f.o = Vec3f(r.o.x, r.o.y, -r.o.z);
    f.d = Vec3f(r.d.x, r.d.y, -r.d.z);
    f.tMax = Infinity;
    return f;
}

// Carries the lens-space ray *r across interface e, whose vertex is at z = elementZ, moving
// towards the film (+z) or the scene (-z): it must meet the interface inside its aperture, and
// it refracts there from index etaI into etaT (the stop only clips). False when it is blocked,
// goes the wrong way at the stop, or is totally internally reflected.
LU_INLINE bool CrossLensInterface(const LensElement &e, Float elementZ, bool towardFilm, Float etaI, Float etaT, Ray *r) {
    bool isStop = e.curvatureRadius == 0;
    Float t;
    Vec3f n;
    if (isStop) {
        if (towardFilm ? r->d.z <= 0 : r->d.z >= 0) return false;
        t = (elementZ - r->o.z) / r->d.z;
    } else if (!IntersectSphericalElement(e.curvatureRadius, elementZ + e.curvatureRadius, *r, &t, &n)) {
        return false;
    }
    Vec3f pHit = (*r)(t);
    if (Sqr(pHit.x) + Sqr(pHit.y) > Sqr(e.apertureRadius)) return false;
    r->o = pHit;
    if (!isStop) {
        Vec3f w;
        if (!Refract(Normalize(-r->d), n, etaT / etaI, nullptr, &w)) return false;
        r->d = w;
    }
    return true;
}

// The index of the medium on the film side of interface i (0 in a table means air).
LU_INLINE Float LensEtaBehind(Span<LensElement> e, int i) { return e[uint32_t(i)].eta != 0 ? e[uint32_t(i)].eta : Float(1); }

// Traces a camera-space ray leaving the film (z = 0, towards +z) through the lens system from the
// rear element to the front one. Returns the ray's weight (1, or 0 when an element's rim or the
// aperture stop blocks it or it is totally internally reflected); *rOut (camera space, optional)
// is the ray leaving the front element.
LU_INLINE Float TraceLensesFromFilm(Span<LensElement> elements, const Ray &rCamera, Ray *rOut) {
    Float elementZ = 0;
    Ray r = FlipZ(rCamera);
    for (int i = int(elements.size) - 1; i >= 0; --i) {
        elementZ -= elements[uint32_t(i)].thickness;
        Float etaT = i > 0 ? LensEtaBehind(elements, i - 1) : Float(1);
        if (!CrossLensInterface(elements[uint32_t(i)], elementZ, false, LensEtaBehind(elements, i), etaT, &r)) return 0;
    }
    if (rOut) *rOut = FlipZ(r);
    return 1;
}

// Traces a camera-space ray from the scene (towards -z) through the lens system from the front
// element to the rear one; false when blocked. *rOut (camera space, optional) leaves the rear element.
LU_INLINE bool TraceLensesFromScene(Span<LensElement> elements, const Ray &rCamera, Ray *rOut) {
    Float elementZ = -LensFrontZ(elements);
    Ray r = FlipZ(rCamera);
    for (int i = 0; i < int(elements.size); ++i) {
        Float etaI = i > 0 ? LensEtaBehind(elements, i - 1) : Float(1);
        if (!CrossLensInterface(elements[uint32_t(i)], elementZ, true, etaI, LensEtaBehind(elements, i), &r)) return false;
        elementZ += elements[uint32_t(i)].thickness;
    }
    if (rOut) *rOut = FlipZ(r);
    return true;
}

// A point on the rear element's plane (camera space z = LensRearZ) sampled uniformly in the exit
// pupil bound of film point pFilm (camera space, meters), rotated to pFilm's azimuth, with its
// pdf with respect to area (1 / bound area). False when no ray from pFilm gets through.
LU_INLINE bool SampleExitPupil(const CameraData &c, Vec2f pFilm, Vec2f uLens, Vec3f *pPupil, Float *pdfA) {
    Float rFilm = std::sqrt(Sqr(pFilm.x) + Sqr(pFilm.y));
    uint32_t n = c.exitPupilBounds.size;
    int rIndex = int(rFilm / (c.filmDiagonal / 2) * Float(n));
    if (rIndex > int(n) - 1) rIndex = int(n) - 1;
    if (rIndex < 0) rIndex = 0;
    const Bounds2f &b = c.exitPupilBounds[uint32_t(rIndex)];
    if (b.IsDegenerate()) return false;
    Vec2f pLens = b.Lerp(uLens);
    *pdfA = 1 / b.Area();
    Float sinTheta = rFilm != 0 ? pFilm.y / rFilm : 0;
    Float cosTheta = rFilm != 0 ? pFilm.x / rFilm : 1;
    *pPupil = Vec3f(cosTheta * pLens.x - sinTheta * pLens.y, sinTheta * pLens.x + cosTheta * pLens.y,
                    LensRearZ(c.lensElements));
    return true;
}

// pbrt-v4's RealisticCamera::GenerateRay in camera space: the film point of raster position
// pFilm (mirrored through the axis: the lens inverts the image), a pupil sample from uLens,
// traced to the scene. *weight = cos^4(theta) / (pdfA * LensRearZ^2), theta the film ray's angle
// to the axis; false (weight 0) when the ray is vignetted.
LU_INLINE bool GenerateRealisticRay(const CameraData &c, Vec2f pFilm, Vec2f uLens, Ray *rCameraOut, Float *weight) {
    *weight = 0;
    Vec2f s(pFilm.x / Float(c.width), pFilm.y / Float(c.height));
    Vec2f p2((1 - s.x) * c.physicalExtentMin.x + s.x * c.physicalExtentMax.x,
             (1 - s.y) * c.physicalExtentMin.y + s.y * c.physicalExtentMax.y);
    Vec3f pFilm3(-p2.x, p2.y, 0);
    Vec3f pPupil;
    Float pdfA;
    if (!SampleExitPupil(c, Vec2f(pFilm3.x, pFilm3.y), uLens, &pPupil, &pdfA)) return false;
    Ray rFilm;
    rFilm.o = pFilm3;
    rFilm.d = pPupil - pFilm3;
    Float w = TraceLensesFromFilm(c.lensElements, rFilm, rCameraOut);
    if (w == 0) return false;
    Float cosTheta = Normalize(rFilm.d).z;
    *weight = w * Sqr(Sqr(cosTheta)) / (pdfA * Sqr(LensRearZ(c.lensElements)));
    return true;
}

}  // namespace lu
