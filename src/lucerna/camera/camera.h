// Lucerna: pbrt-v4's PerspectiveCamera (pinhole or thin lens) as plain data plus ray generation
// (host and device), and pbrt-v4's GetCameraSample. Camera space is left-handed: +z forward,
// +x right, +y up; raster space has (0,0) at the top-left image corner and y pointing down.
#pragma once

#include "lucerna/core/scene_data.h"
#include "lucerna/camera/filter.h"
#include "lucerna/sampling/sampler.h"
#include "lucerna/sampling/warp.h"

namespace lu {

// The render-space ray through raster point pFilm (pixels; pixel (x, y) covers [x, x+1) x
// [y, y+1)) with lens sample uLens in [0,1)^2 (ignored for a pinhole). Thin lens: the ray leaves
// a uniform point of the lens disk (radius lensRadius, at the camera origin) towards the point
// where the pinhole ray meets the plane z = focalDistance. ray->d is unit length, tMax = inf.
// Returns false only for a degenerate direction.
LU_INLINE bool GenerateRay(const CameraData &c, Vec2f pFilm, Vec2f uLens, Ray *ray) {
    Vec3f pCamera = c.cameraFromRaster.ApplyPoint(Vec3f(pFilm.x, pFilm.y, 0));
    Vec3f o(0, 0, 0);
    Vec3f d = Normalize(pCamera);
    if (c.lensRadius > 0) {
        Vec2f pLens = SampleUniformDiskConcentric(uLens) * c.lensRadius;
        Float ft = c.focalDistance / d.z;
        Vec3f pFocus = d * ft;
        o = Vec3f(pLens.x, pLens.y, 0);
        d = Normalize(pFocus - o);
    }
    Vec3f dRender = c.renderFromCamera.ApplyVector(d);
    Float len = Length(dRender);
    if (!(len > 0) || !IsFinite(dRender)) return false;
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
// in that order: the renderer's rounding).
// (pbrt-v4's integrators draw the wavelength sample with Get1D() before calling this.)
LU_INLINE CameraSample GetCameraSample(Sampler &sampler, int px, int py, const FilterData &filter,
                                       const SceneView &scene) {
    FilterSample fs = SampleFilter(filter, scene, sampler.GetPixel2D());
    CameraSample cs;
    cs.pFilm = Vec2f(Float(px) + 0.5f + fs.p.x, Float(py) + 0.5f + fs.p.y);
    cs.time = sampler.Get1D();
    cs.pLens = sampler.Get2D();
    cs.filterWeight = fs.weight;
    return cs;
}

}  // namespace lu
