// Lucerna CUDA backend: the render-ready scene and its BVH in device memory, one upload per span
// of SceneView (core/scene_data.h) and per BVH array (geometry/bvh.h). Plain header.
#pragma once

#include "lucerna/backend/cuda/device_buffer.h"
#include "lucerna/accel/bvh_build.h"

namespace lu {

class DeviceScene {
  public:
    // Copies every span of `host` and both arrays of `bvh` to the device (throws CudaError).
    DeviceScene(const SceneView &host, const GpuBVH &bvh);

    // Views whose spans point into device memory (pass them to kernels by value).
    const SceneView &View() const { return view_; }
    const BVHView &Bvh() const { return bvhView_; }
    size_t DeviceBytes() const { return bytes_; }

  private:
    template <typename T>
    Span<T> Upload(DeviceBuffer<T> &buf, Span<T> host);

    DeviceBuffer<Vec3f> positions_, normals_;
    DeviceBuffer<Vec2f> uvs_;
    DeviceBuffer<uint32_t> indices_;
    DeviceBuffer<TriangleMesh> meshes_;
    DeviceBuffer<Sphere> spheres_;
    DeviceBuffer<Disk> disks_;
    DeviceBuffer<Cylinder> cylinders_;
    DeviceBuffer<BilinearMesh> bilinearMeshes_;
    DeviceBuffer<CurveSet> curveSets_;
    DeviceBuffer<CurveSegment> curveSegments_;
    DeviceBuffer<Shape> shapes_;
    DeviceBuffer<Prototype> prototypes_;
    DeviceBuffer<Instance> instances_;
    DeviceBuffer<Material> materials_;
    DeviceBuffer<Light> lights_;
    DeviceBuffer<Float> lightCdf_;
    DeviceBuffer<uint32_t> infiniteLights_;
    DeviceBuffer<ImageData> images_;
    DeviceBuffer<Float> texels_;
    DeviceBuffer<FloatTexture> floatTextures_;
    DeviceBuffer<SpectrumTexture> spectrumTextures_;
    DeviceBuffer<Distribution2D> distributions2D_;
    DeviceBuffer<Float> distData_;
    DeviceBuffer<Vec2f> pmjPoints_;
    DeviceBuffer<Float> spectra_;
    DeviceBuffer<Float> rgbToSpecCoeffs_, rgbToSpecZNodes_;
    DeviceBuffer<Medium> media_;
    DeviceBuffer<Float> mediumData_;
    DeviceBuffer<Float> measuredData_;
    DeviceBuffer<LensElement> lensElements_;
    DeviceBuffer<Bounds2f> exitPupilBounds_;
    DeviceBuffer<BVHNode> nodes_;
    DeviceBuffer<PrimRef> prims_;
    DeviceBuffer<int32_t> prototypeRoots_;
    SceneView view_;
    BVHView bvhView_;
    size_t bytes_ = 0;
};

}  // namespace lu
