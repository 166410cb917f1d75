// Lucerna scene builder: interprets a parsed pbrt-v4 SceneDescription into the render-ready
// arrays of core/scene_data.h, with pbrt-v4's semantics for every parameter (after pbrt-v4's
// scene.cpp and the Create() functions of shapes, materials, lights, textures, film and cameras).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lucerna/core/scene_data.h"
#include "lucerna/sampling/sampler.h"
#include "lucerna/scene/description.h"
#include "lucerna/scene/render_settings.h"
#include "lucerna/spectra/registry.h"

namespace lu {

// What `lucerna info` reports. Type names are pbrt-v4's ("trianglemesh", "conductor", ...).
struct SceneStats {
    std::map<std::string, int> shapesByType;     // Shape directives (flattened copies included, a prototype's once)
    std::map<std::string, int> lightsByType;     // LightSource types; "diffuse area" counts emitting primitives
    std::map<std::string, int> materialsByType;  // every Material / MakeNamedMaterial, "interface" included
    std::map<std::string, int> mediaByType;      // MakeNamedMedium types
    uint64_t triangles = 0;                      // rendered, after triangulating (each instance's counted)
    uint64_t bilinearPatches = 0;                // curved patches kept as patches (each Shape directive once)
    uint64_t curveSegments = 0;                  // cubic Bezier segments of "curve" shapes (each directive once)
    int areaLightShapes = 0;                     // shapes carrying an AreaLightSource
    int floatTextures = 0, spectrumTextures = 0;
    int instanceDefinitions = 0, instanceUses = 0;
    int instancedUses = 0;                       // uses kept as instances (the rest are flattened copies)
    int prototypes = 0;
    std::string cameraType = "perspective";
    double fov = 90;                             // degrees, on the shorter image axis (pbrt-v4)
    Vec3f cameraPosition, cameraDirection;       // render (= world) space
    std::string filterType = "gaussian";
    std::string integratorAsRead;                // the Integrator directive's name ("" when absent)
    std::string samplerName = "zsobol";          // the Sampler directive's (pbrt-v4's default: zsobol)
    // One line per light with an intensity profile (goniometric image or IES file):
    // "light 3: goniometric \"a.ies\": LM-63-2002, type C, ..."
    std::vector<std::string> lightProfiles;
};

// Owns every array the SceneView spans point into.
class HostScene {
  public:
    SceneView View() const;

    RenderSettings settings;   // as the scene's Integrator and Sampler directives set them (r0 resolved)
    Sampler sampler;           // the Sampler directive with all its options (seed: settings.seed)
    std::string outputFilename;   // Film "filename" ("" when absent)
    ColorSpaceId filmColorSpace = ColorSpaceId::SRGB;  // the ColorSpace in effect at Film: the output image's
    uint32_t illuminantTables[NumColorSpaces] = {TableD65, TableD65, TableD65, TableD65};  // in spectra
    std::vector<std::string> inputFiles;   // every file the scene read: the description's, then PLY meshes, images, spectra
    SceneStats stats;
    SpectrumRegistry spectra;
    Bounds3f bounds;

    std::vector<Vec3f> positions, normals;
    std::vector<Vec2f> uvs;
    std::vector<uint32_t> indices;
    std::vector<TriangleMesh> triangleMeshes;
    std::vector<Sphere> spheres;
    std::vector<Disk> disks;
    std::vector<Cylinder> cylinders;
    std::vector<BilinearMesh> bilinearMeshes;
    std::vector<CurveSet> curveSets;
    std::vector<CurveSegment> curveSegments;
    std::vector<Shape> shapes;
    std::vector<Prototype> prototypes;   // object instancing (build_shapes.cpp says which uses are instanced)
    std::vector<Instance> instances;
    std::vector<Material> materials;
    std::vector<Light> lights;
    std::vector<Float> lightCdf;
    std::vector<uint32_t> infiniteLights;
    std::vector<ImageData> images;
    std::vector<Float> texels;
    std::vector<FloatTexture> floatTextures;       // texture children (SceneView::floatTextures)
    std::vector<SpectrumTexture> spectrumTextures;
    std::vector<Distribution2D> distributions2D;
    std::vector<Float> distData;
    std::vector<Vec2f> pmjPoints;   // the pmj02bn sampler's tables (scene/pmj02_build.h)
    std::vector<Medium> media;
    std::vector<Float> mediumData;
    std::vector<Float> measuredData;   // measured materials' tables (SceneView::measuredData)
    bool walkInterfaces = false;   // media or interface shapes: shadow rays walk through interfaces
    std::vector<FileLoc> collimatedLightLocs;   // where each LightSource "collimated" is (the path warning)
    CameraData camera;
    std::vector<LensElement> lensElements;    // realistic camera (CameraData::lensElements)
    std::vector<Bounds2f> exitPupilBounds;    // realistic camera (CameraData::exitPupilBounds)
    FilmData film;
    FilterData filter;

    // Where each material, light and medium was declared, for messages about the render (the
    // first rejected sample): e.g. `Material "conductor" at scene.pbrt:12:1`. Per entity an index
    // into `origins` (NoIndex, or past the end: not recorded).
    std::vector<std::string> origins;
    std::vector<uint32_t> materialOrigin, lightOrigin, mediumOrigin;
    // Records `what` as the origin of entity `index` of one of the per-entity lists above.
    void SetOrigin(std::vector<uint32_t> &list, size_t index, const std::string &what);
    // The origin of entity `index` ("" when none was recorded).
    std::string OriginOf(const std::vector<uint32_t> &list, uint32_t index) const;
};

struct BuildOptions {
    int resX = 0, resY = 0;   // --res override; 0: from the Film directive
    // The most triangles one "loopsubdiv" shape may refine into (about 40 bytes of scene each:
    // the default is some 2.7 GB); more is an error naming "levels".
    uint64_t maxSubdivisionTriangles = uint64_t(1) << 26;
};

// Throws SceneError (at the offending entity or parameter) for bad input and for unsupported
// features that would change the picture; records the others in diag.
std::unique_ptr<HostScene> BuildScene(const SceneDescription &desc, Diagnostics &diag, const BuildOptions &opts);
// ParseSceneFile + BuildScene.
std::unique_ptr<HostScene> LoadScene(const std::string &filename, Diagnostics &diag, const BuildOptions &opts);

// The human-readable report `lucerna info` prints: resolution, camera, film, integrator and
// sampler as read, shape / triangle / light / material counts by type, world bounds, every
// warning and every unsupported feature by name (scene/scene_summary.cpp).
std::string SceneSummary(const HostScene &scene, const Diagnostics &diag);

}  // namespace lu
