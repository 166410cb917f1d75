// Lucerna: pbrt-v4's PerspectiveCamera and OrthographicCamera (pinhole or thin lens) and
// SphericalCamera (equal-area or equirectangular image) as plain data plus ray generation (host
// and device), and pbrt-v4's GetCameraSample. Camera space is left-handed: +z forward,
// +x right, +y up; raster space has (0,0) at the top-left image corner and y pointing down.
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/camera/filter.h"
#include "lucerna/camera/realistic.h"
#include "lucerna/lights/equal_area.h"
#include "lucerna/sampling/sampler.h"
#include "lucerna/sampling/warp.h"

namespace lu {

// pbrt-v4's WrapEqualAreaSquare: a point just outside [0,1]^2 (filter footprints at the image
// border) folded back as the equal-area parameterization continues across the square's edges.
LU_INLINE Vec2f WrapEqualAreaSquare(Vec2f uv) {
    if (uv.x < 0) { uv.x = -uv.x; uv.y = 1 - uv.y; }
    else if (uv.x > 1) { uv.x = 2 - uv.x; uv.y = 1 - uv.y; }
    if (uv.y < 0) { uv.x = 1 - uv.x; uv.y = -uv.y; }
    else if (uv.y > 1) { uv.x = 1 - uv.x; uv.y = 2 - uv.y; }
    return uv;
}

// The spherical camera's camera-space direction of image point uv = pFilm / resolution.
LU_INLINE Vec3f SphericalCameraDirection(CameraKind kind, Vec2f uv) {
    Vec3f dir;
    if (kind == CameraKind::SphericalEquirect) {
        Float theta = Pi * uv.y, phi = 2 * Pi * uv.x;
        dir = SphericalDirection(std::sin(theta), std::cos(theta), phi);
    } else {
        dir = EqualAreaSquareToSphere(WrapEqualAreaSquare(uv));
    }
    return Vec3f(dir.x, dir.z, dir.y);   // pbrt-v4 swaps y and z: the image's poles are camera +-y
}

// Its inverse: the image point uv in [0,1]^2 of a camera-space direction (for tests and tools).
LU_INLINE Vec2f SphericalCameraImagePoint(CameraKind kind, Vec3f dCamera) {
    Vec3f d = Normalize(Vec3f(dCamera.x, dCamera.z, dCamera.y));
    if (kind == CameraKind::SphericalEquirect) {
        Float theta = std::acos(Clamp(d.z, Float(-1), Float(1)));
        Float phi = std::atan2(d.y, d.x);
        if (phi < 0) phi += 2 * Pi;
        return {phi / (2 * Pi), theta / Pi};
    }
    return EqualAreaSphereToSquare(d);
}

// The render-space ray through raster point pFilm (pixels; pixel (x, y) covers [x, x+1) x
// [y, y+1)) with lens sample uLens in [0,1)^2 (ignored for a pinhole and the spherical camera).
// Perspective: from the camera origin through the raster point on the image plane; orthographic:
// from the raster point on the plane z = 0 along +z. Thin lens (both): the ray leaves a uniform
// point of the lens disk (radius lensRadius, centred on the pinhole ray's origin) towards the
// point where the pinhole ray meets the plane z = focalDistance. Spherical: from the origin in
// the direction of the image point pFilm / resolution. Realistic: pbrt-v4's lens system
// (camera/realistic.h), from the front element. ray->d is unit length, tMax = inf.
// *weight (optional) is the ray's camera weight, which multiplies its radiance: 1 for every camera
// but the realistic one (pbrt-v4's cos^4 / pupil pdf). Returns false (weight 0) for a degenerate
// direction or a vignetted realistic camera ray.
LU_INLINE bool GenerateRay(const CameraData &c, Vec2f pFilm, Vec2f uLens, Ray *ray, Float *weight = nullptr) {
    Vec3f o(0, 0, 0), d;
    if (weight) *weight = 1;
    if (c.kind == CameraKind::Realistic) {
        Ray rCamera;
        Float w;
        bool ok = GenerateRealisticRay(c, pFilm, uLens, &rCamera, &w);
        if (weight) *weight = w;
        if (!ok) return false;
        o = rCamera.o;
        d = rCamera.d;
    } else if (c.kind == CameraKind::Perspective || c.kind == CameraKind::Orthographic) {
        Vec3f pCamera = c.cameraFromRaster.ApplyPoint(Vec3f(pFilm.x, pFilm.y, 0));
        if (c.kind == CameraKind::Perspective) {
            d = Normalize(pCamera);
        } else {
            o = pCamera;
            d = Vec3f(0, 0, 1);
        }
        if (c.lensRadius > 0) {
            Vec2f pLens = SampleUniformDiskConcentric(uLens) * c.lensRadius;
            Float ft = c.focalDistance / d.z;
            Vec3f pFocus = o + d * ft;
            o = Vec3f(o.x + pLens.x, o.y + pLens.y, 0);
            d = Normalize(pFocus - o);
        }
    } else {
        Vec2f uv(pFilm.x / Float(c.width), pFilm.y / Float(c.height));
        d = SphericalCameraDirection(c.kind, uv);
    }
    Vec3f dRender = c.renderFromCamera.ApplyVector(d);
    Float len = Length(dRender);
    if (!(len > 0) || !IsFinite(dRender)) {
        if (weight) *weight = 0;
        return false;
    }
    ray->o = c.renderFromCamera.ApplyPoint(o);
    ray->d = dRender / len;
    ray->tMax = Infinity;
    return true;
}

// Everything a camera ray needs from the sampler, as pbrt-v4's CameraSample.
struct CameraSample {
    Vec2f pFilm;             // raster position (pixels)
    Float time = 0;          // shutter sample (Lucerna has no motion; drawn to keep pbrt's dimensions)
    Vec2f pLens;
    Float filterWeight = 1;  // FilterSample::weight
};

// pbrt-v4's GetCameraSample: the filter offset from sampler.GetPixel2D(), then one dimension for
// time and two for the lens, in that order. pFilm = pixel + (0.5, 0.5) + filter offset (summed
// in that order: the renderer's rounding). With the filter's disableJitter (Option
// "disablepixeljitter") the offset is 0 and the weight 1, as pbrt-v4.
// (pbrt-v4's integrators draw the wavelength sample with Get1D() before calling this.)
LU_INLINE CameraSample GetCameraSample(Sampler &sampler, int px, int py, const FilterData &filter,
                                       const SceneView &scene) {
    FilterSample fs = SampleFilter(filter, scene, sampler.GetPixel2D());
    if (filter.disableJitter) fs = {Vec2f(0, 0), Float(1)};   // pbrt-v4: the sample is still drawn
    CameraSample cs;
    cs.pFilm = Vec2f(Float(px) + 0.5f + fs.p.x, Float(py) + 0.5f + fs.p.y);
    cs.time = sampler.Get1D();
    cs.pLens = sampler.Get2D();
    cs.filterWeight = fs.weight;
    return cs;
}

}  // namespace lu
