// Lucerna CUDA backend: uploading a SceneView and its BVH (one cudaMemcpy per array).
#include "lucerna/backend/cuda/device_scene.h"

namespace lu {

template <typename T>
Span<T> DeviceScene::Upload(DeviceBuffer<T> &buf, Span<T> host) {
    buf.Upload(host.ptr, host.size);
    bytes_ += buf.Bytes();
    return buf.View();
}

DeviceScene::DeviceScene(const SceneView &host, const GpuBVH &bvh) {
    // Every span of SceneView must be uploaded below; this trips when SceneView changes (1016:
    // CameraData::pixelWidth/pixelSpread, deltaLights, scalars, copied with view_ = host).
    static_assert(sizeof(SceneView) == 1016, "SceneView changed: upload its new spans in DeviceScene");
    view_ = host;   // scalars (camera, film, filter, bounds, table sizes) copy as they are
    view_.positions = Upload(positions_, host.positions);
    view_.normals = Upload(normals_, host.normals);
    view_.uvs = Upload(uvs_, host.uvs);
    view_.indices = Upload(indices_, host.indices);
    view_.triangleMeshes = Upload(meshes_, host.triangleMeshes);
    view_.spheres = Upload(spheres_, host.spheres);
    view_.disks = Upload(disks_, host.disks);
    view_.cylinders = Upload(cylinders_, host.cylinders);
    view_.bilinearMeshes = Upload(bilinearMeshes_, host.bilinearMeshes);
    view_.curveSets = Upload(curveSets_, host.curveSets);
    view_.curveSegments = Upload(curveSegments_, host.curveSegments);
    view_.shapes = Upload(shapes_, host.shapes);
    view_.prototypes = Upload(prototypes_, host.prototypes);
    view_.instances = Upload(instances_, host.instances);
    view_.materials = Upload(materials_, host.materials);
    view_.lights = Upload(lights_, host.lights);
    view_.lightCdf = Upload(lightCdf_, host.lightCdf);
    view_.infiniteLights = Upload(infiniteLights_, host.infiniteLights);
    view_.images = Upload(images_, host.images);
    view_.texels = Upload(texels_, host.texels);
    view_.floatTextures = Upload(floatTextures_, host.floatTextures);
    view_.spectrumTextures = Upload(spectrumTextures_, host.spectrumTextures);
    view_.distributions2D = Upload(distributions2D_, host.distributions2D);
    view_.distData = Upload(distData_, host.distData);
    view_.pmjPoints = Upload(pmjPoints_, host.pmjPoints);
    view_.rgbToSpecCoeffs = Upload(rgbToSpecCoeffs_, host.rgbToSpecCoeffs);
    view_.rgbToSpecZNodes = Upload(rgbToSpecZNodes_, host.rgbToSpecZNodes);
    view_.media = Upload(media_, host.media);
    view_.mediumData = Upload(mediumData_, host.mediumData);
    view_.measuredData = Upload(measuredData_, host.measuredData);
    view_.camera.lensElements = Upload(lensElements_, host.camera.lensElements);
    view_.camera.exitPupilBounds = Upload(exitPupilBounds_, host.camera.exitPupilBounds);
    Span<Float> spectra{host.spectra.data, uint32_t(host.spectra.count * TabulatedSpectrumSize)};
    view_.spectra.data = Upload(spectra_, spectra).ptr;
    view_.spectra.count = host.spectra.count;

    BVHView hb = bvh.View();
    bvhView_.nodes = Upload(nodes_, hb.nodes);
    bvhView_.prims = Upload(prims_, hb.prims);
    bvhView_.prototypeRoots = Upload(prototypeRoots_, hb.prototypeRoots);
}

}  // namespace lu
