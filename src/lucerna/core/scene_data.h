// Lucerna: the render-ready scene as plain data (spans and indices, no pointers between
// objects), shared by the CPU and CUDA backends. The host builder (scene/builder.*) fills it
// from a parsed pbrt-v4 scene; one upload per array moves it to the GPU.
#pragma once

#include "lucerna/spectrum/color_space.h"
#include "lucerna/spectrum/spectrum.h"
#include "lucerna/util/vecmath.h"

namespace lu {

constexpr uint32_t NoIndex = 0xffffffffu;

template <typename T>
struct Span {
    const T *ptr = nullptr;
    uint32_t size = 0;
    LU_HD const T &operator[](uint32_t i) const { return ptr[i]; }
    LU_HD bool empty() const { return size == 0; }
};

// ---- Images and textures ----

enum class WrapMode : uint8_t { Repeat, Clamp, Black, OctahedralSphere };

// An image of float texels (channels interleaved), stored in SceneView::texels from `offset`.
struct ImageData {
    uint32_t width = 0, height = 0, channels = 0;
    uint64_t offset = 0;
    WrapMode wrap = WrapMode::Repeat;
    // The color space of the texels' RGB (pbrt-v4: the file's, from EXR chromaticities; sRGB
    // otherwise), a ColorSpaceId: selects the RGB -> spectrum table and the illuminant.
    uint8_t colorSpace = 0;
};

// A texture mapping (pbrt-v4's TextureMapping2D / TextureMapping3D). 2D kinds give (s, t):
//   UV:          (su u + du, sv v + dv)
//   Spherical:   (theta / pi, phi / 2 pi) of the direction to p in texture space
//   Cylindrical: ((pi + atan2(y, x)) / 2 pi, z) of p in texture space
//   Planar:      (du + dot(p, vs), dv + dot(p, vt)) of p in texture space
// Point (3D) gives p in texture space. Texture space = textureFromRender * render space (the
// inverse of the CTM at the Texture directive).
enum class TextureMappingKind : uint8_t { UV, Spherical, Cylindrical, Planar, Point };

struct TextureMapping {
    TextureMappingKind kind = TextureMappingKind::UV;
    Float su = 1, sv = 1, du = 0, dv = 0;   // uv; planar uses du, dv (pbrt-v4's udelta, vdelta)
    Vec3f vs = Vec3f(1, 0, 0), vt = Vec3f(0, 1, 0);  // planar (pbrt-v4's v1, v2)
    Matrix4 textureFromRender;              // every kind but UV
};

// The closed set of texture kinds (pbrt-v4's textures.h). Float textures use every kind but
// Marble; spectrum textures every kind but FBm, Wrinkled and Windy. Children are indices into
// SceneView::floatTextures / spectrumTextures (see `tex` and `amount` below); the builder keeps
// the nesting at most MaxTextureDepth levels deep (materials/texture.h evaluates level by level).
enum class TextureKind : uint8_t {
    Constant,      // value
    Scale,         // tex[0] * amount (pbrt-v4's "tex" * "scale")
    Mix,           // (1 - amount) tex[0] + amount tex[1]
    DirectionMix,  // w tex[0] + (1 - w) tex[1], w = |dot(n, dir)|
    Bilerp,        // bilinear in (s, t) between v00, v01, v10, v11
    ImageMap,      // image lookup (bilinear or nearest texel), times scale, optionally inverted
    Checkerboard,  // tex[0] on even checks, tex[1] on odd; 2D (s, t) or 3D (Point mapping)
    Dots,          // tex[0] inside the polka dots, tex[1] outside
    FBm,           // fractional Brownian motion of Perlin noise at the 3D point
    Wrinkled,      // turbulence (sum of |noise| octaves)
    Windy,         // |FBm(0.1 p, 3 octaves)| * FBm(p, 6 octaves)
    Marble,        // pbrt-v4's marble color spline driven by FBm
};

constexpr int MaxTextureDepth = 8;  // nesting levels of texture children below a material's texture

// A float texture node (roughness, thickness, mix amounts, ...).
struct FloatTexture {
    TextureKind kind = TextureKind::Constant;
    bool invert = false;             // ImageMap: max(0, 1 - v)
    bool pointFilter = false;        // ImageMap: nearest texel instead of bilinear
    Float value = 0;                 // Constant
    uint32_t tex[2] = {NoIndex, NoIndex};  // children in floatTextures (Scale: tex[0]; Mix, DirectionMix,
                                           // Checkerboard, Dots: tex[0], tex[1])
    uint32_t amount = NoIndex;       // Scale: the "scale" texture; Mix: the "amount" texture (floatTextures)
    Float v00 = 0, v01 = 1, v10 = 0, v11 = 1;  // Bilerp
    uint32_t image = NoIndex;        // ImageMap: one-channel image (the builder reduces RGB(A) as pbrt-v4)
    Float scale = 1;                 // ImageMap multiplier
    int octaves = 8;                 // FBm, Wrinkled
    Float omega = 0.5f;              // FBm, Wrinkled ("roughness")
    Vec3f dir = Vec3f(0, 1, 0);      // DirectionMix: unit, render space
    TextureMapping mapping;
};

// A spectrum texture node. ImageMap holds RGB texels converted per lookup (RGBAlbedo for
// reflectances, RGBUnbounded otherwise: `unbounded`); Marble is always an albedo.
struct SpectrumTexture {
    TextureKind kind = TextureKind::Constant;
    bool invert = false;
    bool pointFilter = false;
    bool unbounded = false;
    Spectrum value;                  // Constant
    uint32_t tex[4] = {NoIndex, NoIndex, NoIndex, NoIndex};  // children in spectrumTextures (as FloatTexture;
                                                            // Bilerp: v00, v01, v10, v11)
    uint32_t amount = NoIndex;       // Scale, Mix: float child (floatTextures)
    uint32_t image = NoIndex;        // ImageMap (1 or 3 channels)
    Float scale = 1;                 // ImageMap multiplier; Marble: point scale
    int octaves = 8;                 // Marble
    Float omega = 0.5f, variation = 0.2f;  // Marble
    Vec3f dir = Vec3f(0, 1, 0);      // DirectionMix
    TextureMapping mapping;
};

// ---- Materials ----

enum class MaterialKind : uint8_t {
    Diffuse, Conductor, Dielectric, ThinDielectric, CoatedDiffuse, Interface,
    CoatedConductor, DiffuseTransmission, Mix, Hair, Measured
};

// One table of pbrt-v4's PiecewiseLinear2D<nParams> (util/sampling.h) in SceneView::measuredData:
// a bilinear density over [0,1]^2 of nx x ny vertices (x contiguous), one slice per vertex of the
// parameter grid (parameter 0 outermost), linear in the parameters in between. Offsets index
// measuredData; marginalCdf and conditionalCdf are NoIndex for tables that are only evaluated.
struct PiecewiseLinear2DTable {
    uint32_t nx = 0, ny = 0;
    uint32_t nParams = 0;                            // 0, 2 or 3
    uint32_t paramSize[3] = {1, 1, 1};
    uint32_t paramStride[3] = {0, 0, 0};             // in slices; 0 for a parameter of resolution 1
    uint32_t paramValues[3] = {NoIndex, NoIndex, NoIndex};  // ascending values, paramSize[i] each
    uint32_t data = NoIndex;                         // density values (nx * ny per slice)
    uint32_t marginalCdf = NoIndex;                  // ny per slice
    uint32_t conditionalCdf = NoIndex;               // nx * ny per slice
};

// A measured BRDF (pbrt-v4's MeasuredBRDF, Dupuy & Jakob 2018): the tables of an RGL .bsdf file.
// ndf: D(wm) over (theta2u, phi2u) of wm; sigma: the projected area of the microsurface seen from
// w over the same coordinates; vndf: the visible normals' density over the unit square, given
// (phi_i, theta_i) of wo; luminance: the luminance of the reflectance over the vndf's sample
// space, same parameters; spectra: the reflectance over the sample space given (phi_i, theta_i,
// wavelength in nm).
struct MeasuredBRDFData {
    PiecewiseLinear2DTable ndf, sigma, vndf, luminance, spectra;
    bool isotropic = true;   // phi_i has at most 2 values: wm's phi is relative to wo's
    bool jacobian = false;   // the file's "jacobian" flag (read, unused, as pbrt-v4)
};

// How a hair material gives its absorption (pbrt-v4's HairMaterial: the first of "sigma_a",
// "reflectance" (or "color"), "eumelanin"/"pheomelanin" present; none: eumelanin 1.3).
enum class HairColor : uint8_t { SigmaA, Reflectance, Melanin };

struct Material {
    MaterialKind kind = MaterialKind::Diffuse;
    SpectrumTexture reflectance;          // diffuse, coateddiffuse, diffusetransmission, (coated)conductor when useReflectance
    SpectrumTexture conductorEta, conductorK;   // conductor; coatedconductor's conductor.eta / conductor.k
    bool useReflectance = false;          // (coated)conductor given "reflectance" instead of eta/k
    FloatTexture uRoughness, vRoughness;  // conductor, dielectric, coateddiffuse and coatedconductor (interface roughness)
    bool remapRoughness = true;
    Spectrum eta = Spectrum::Const(1.5f); // dielectric, thindielectric, coated* interface;
                                          // a non-constant eta makes the dielectric dispersive
    // coateddiffuse and coatedconductor (pbrt-v4 defaults)
    FloatTexture thickness;               // default 0.01
    FloatTexture g;                       // default 0
    SpectrumTexture albedo;               // default 0
    int maxDepth = 10, nSamples = 1;
    FloatTexture conductorURoughness, conductorVRoughness;   // coatedconductor's conductor.roughness (default 0)
    // diffusetransmission: reflectance (default 0.25), transmittance (default 0.25), both times scale
    SpectrumTexture transmittance;
    Float scale = 1;
    // mix: mixMaterials[1] where a hash u of (p, wo) in [0,1) is <= amount, else mixMaterials[0]
    // (pbrt-v4's MixMaterial::ChooseMaterial); the children are earlier materials, maybe mixes.
    FloatTexture amount;                  // default 0.5
    uint32_t mixMaterials[2] = {NoIndex, NoIndex};
    // "normalmap" (any material but mix): scene.images index of a linear RGB image, tangent-space
    // normals in [0,1]^3, repeat wrap (pbrt-v4's NormalMap); NoIndex: none.
    uint32_t normalMap = NoIndex;
    // "displacement" (any material but mix and interface): floatTextures index of the bump map's
    // displacement along the shading normal (pbrt-v4's BumpMap; a normal map takes precedence);
    // NoIndex: none.
    uint32_t displacement = NoIndex;
    // A "texture" eta (dielectric, thindielectric, coated* interface): floatTextures index,
    // evaluated per hit and the same at every wavelength (it overrides `eta`); NoIndex: `eta`.
    uint32_t etaTexture = NoIndex;
    // hair (pbrt-v4's HairMaterial): the absorption from hairSigmaA, `reflectance` or the melanin
    // concentrations (hairColor says which); hairEta (default 1.55), betaM and betaN (longitudinal
    // and azimuthal roughness, default 0.3, used clamped to [0.01, 1]), hairAlpha (the cuticle
    // scale tilt in degrees, default 2).
    HairColor hairColor = HairColor::Melanin;
    SpectrumTexture hairSigmaA;
    FloatTexture eumelanin, pheomelanin;
    FloatTexture hairEta, betaM, betaN, hairAlpha;
    // measured: the tables of the "filename" file in SceneView::measuredData.
    MeasuredBRDFData measured;
};

// ---- Shapes ----

enum class ShapeKind : uint8_t { Triangles, Sphere, Disk, Cylinder, BilinearPatches, Curves };

// A triangle mesh with world-space vertices. Triangle t of the mesh uses
// indices[firstIndex + 3t .. +2], relative to firstVertex.
struct TriangleMesh {
    uint32_t firstVertex = 0, vertexCount = 0;
    uint32_t firstIndex = 0, triangleCount = 0;
    uint32_t normalOffset = NoIndex;  // per-vertex shading normals (world space) at normals[normalOffset + i]
    uint32_t uvOffset = NoIndex;      // per-vertex uv at uvs[uvOffset + i]
    bool flipNormals = false;         // ReverseOrientation XOR transform swaps handedness
};

// pbrt-v4 sphere of radius r at the object origin, cut (pbrt-v4's partial sphere) to
// zMin <= z <= zMax and 0 <= phi <= phiMax (radians). The defaults are the full sphere; use
// SetSphereClip for a partial one (it keeps thetaZMin, thetaZMax, the polar angles of zMin and
// zMax, in step).
struct Sphere {
    Transform renderFromObject;
    Float radius = 1;
    Float zMin = -Infinity, zMax = Infinity;   // clamped to [-radius, radius] by SetSphereClip
    Float thetaZMin = Pi, thetaZMax = 0;       // acos(zMin / r), acos(zMax / r)
    Float phiMax = 2 * Pi;
    bool flipNormals = false;
};

// pbrt-v4 disk at z = height in object space, facing +z, between innerRadius and radius and
// 0 <= phi <= phiMax (radians).
struct Disk {
    Transform renderFromObject;
    Float height = 0, radius = 1, innerRadius = 0;
    Float phiMax = 2 * Pi;
    bool flipNormals = false;
};

// pbrt-v4 cylinder: the open tube x^2 + y^2 = radius^2, zMin <= z <= zMax (no caps),
// 0 <= phi <= phiMax (radians), in object space.
struct Cylinder {
    Transform renderFromObject;
    Float radius = 1, zMin = -1, zMax = 1;
    Float phiMax = 2 * Pi;
    bool flipNormals = false;
};

// pbrt-v4's bilinear patch mesh, in render space like a TriangleMesh: patch i has the vertices
// indices[firstIndex + 4i .. +3] (relative to firstVertex) in pbrt-v4's order p00, p10, p01, p11,
// the surface p(u, v) = (1-u)(1-v) p00 + u(1-v) p10 + (1-u)v p01 + uv p11. Only patches that are
// not parallelograms (with affine uv and normals) are kept as patches: the others are exactly two
// triangles and go to a TriangleMesh (scene/build_shapes.cpp).
struct BilinearMesh {
    uint32_t firstVertex = 0, vertexCount = 0;
    uint32_t firstIndex = 0, patchCount = 0;
    uint32_t normalOffset = NoIndex;  // per-vertex shading normals at normals[normalOffset + i]
    uint32_t uvOffset = NoIndex;      // per-vertex uv at uvs[uvOffset + i]
    bool flipNormals = false;         // ReverseOrientation XOR transform swaps handedness
};

// pbrt-v4's curve types: a ribbon facing the ray ("flat"), the same shaded as a tube
// ("cylinder"), a ribbon oriented by normals at its ends ("ribbon").
enum class CurveType : uint8_t { Flat, Cylinder, Ribbon };

// One cubic Bezier segment of a "curve" shape in its object space, with pbrt-v4's CurveCommon
// data: widths at u = 0 and 1, and for ribbons the unit normals at the ends.
struct CurveSegment {
    Vec3f cp[4];
    Float width[2];
    Vec3f n[2];
};

// A "curve" shape: segments curveSegments[firstSegment ..] intersected in object space (pbrt-v4's
// Curve). Each segment is split into 2^splitDepth pieces over u (pbrt-v4's "splitdepth"), the
// primitives of the shape: primitive p is piece p & (2^splitDepth - 1) of segment p >> splitDepth.
struct CurveSet {
    Transform renderFromObject;
    uint32_t firstSegment = 0, segmentCount = 0;
    CurveType type = CurveType::Flat;
    uint8_t splitDepth = 3;
    bool flipNormals = false;   // ReverseOrientation XOR the transform swaps handedness
};

// pbrt-v4's Radians(Clamp(phimax, 0, 360)), exactly 2 pi at 360 (so that a full shape is not a
// partial one by a rounding).
LU_INLINE Float PhiMaxRadians(Float degrees) { return degrees >= 360 ? 2 * Pi : Radians(Clamp(degrees, Float(0), Float(360))); }

// pbrt-v4's Sphere constructor: z range ordered and clamped to [-r, r], phimax (degrees) clamped
// to [0, 360].
LU_INLINE void SetSphereClip(Sphere &sp, Float zMin, Float zMax, Float phiMaxDegrees) {
    Float r = sp.radius, z0 = zMin < zMax ? zMin : zMax, z1 = zMin < zMax ? zMax : zMin;
    sp.zMin = Clamp(z0, -r, r);
    sp.zMax = Clamp(z1, -r, r);
    sp.thetaZMin = std::acos(Clamp(z0 / r, Float(-1), Float(1)));
    sp.thetaZMax = std::acos(Clamp(z1 / r, Float(-1), Float(1)));
    sp.phiMax = PhiMaxRadians(phiMaxDegrees);
}

// A partial sphere: anything cut away (pbrt-v4's clip tests apply).
LU_INLINE bool IsPartial(const Sphere &sp) { return sp.zMin > -sp.radius || sp.zMax < sp.radius || sp.phiMax < 2 * Pi; }

// One entry per shape in the scene; its index is the geometry id used by every backend.
struct Shape {
    ShapeKind kind = ShapeKind::Triangles;
    uint32_t index = 0;            // into triangleMeshes, spheres, disks, cylinders, bilinearMeshes or curveSets
    uint32_t material = NoIndex;   // NoIndex: interface (no surface, rays pass through)
    uint32_t areaLight = NoIndex;  // first light index; primitive i of the shape has light areaLight + i
    uint32_t primitiveCount = 1;   // triangles of a mesh, patches, curve pieces; 1 for quadrics
    // pbrt-v4's MediumInterface: a ray leaving the surface along w enters outsideMedium when
    // Dot(w, n) > 0 (n: the oriented geometric normal), else insideMedium (NoIndex: vacuum).
    // Without a transition (no MediumInterface, or inside == outside) a ray keeps its medium.
    bool mediumTransition = false;
    uint32_t insideMedium = NoIndex, outsideMedium = NoIndex;
    // pbrt-v4's "alpha" cut-out: floatTextures index of the alpha texture tested at every
    // candidate hit (geometry/alpha.h); NoIndex: opaque (no test, no texture lookup).
    uint32_t alpha = NoIndex;
};

// ---- Object instancing (pbrt-v4's ObjectBegin / ObjectInstance, one level) ----

// A prototype: the shapes of one object definition, in object (instance) space, at
// shapes[firstShape .. firstShape + shapeCount - 1]. Prototype shapes come after every
// render-space shape (TopLevelShapeCount) and carry no area lights (pbrt-v4 ignores them).
struct Prototype {
    uint32_t firstShape = 0, shapeCount = 0;
    Bounds3f bounds;   // object space
};

// One use of a prototype: an affine render-from-instance map (top three rows) and its inverse.
// A hit on an instance is reconstructed in render space (geometry/shapes.h ComputeInteraction):
// triangle vertices by renderFromInstance, normals by the inverse transpose, the triangle
// orientation flipped once more when the map swaps handedness (as the flattened copy would be).
struct Instance {
    Float renderFromInstance[3][4];
    Float instanceFromRender[3][4];
    uint32_t prototype = 0;
    uint32_t swapsHandedness = 0;   // 1: det of the linear part < 0
};

LU_INLINE Vec3f InstancePoint(const Float (&m)[3][4], const Vec3f &p) {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3], m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
}
LU_INLINE Vec3f InstanceVector(const Float (&m)[3][4], const Vec3f &v) {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}
// A normal by the inverse transpose, given the inverse (instanceFromRender).
LU_INLINE Vec3f InstanceNormal(const Float (&inv)[3][4], const Vec3f &n) {
    return {inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z, inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
            inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z};
}
// The instance's map as a Transform (bottom rows 0 0 0 1).
LU_INLINE Transform InstanceTransform(const Instance &in) {
    Transform t;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            t.m.m[i][j] = in.renderFromInstance[i][j];
            t.mInv.m[i][j] = in.instanceFromRender[i][j];
        }
    return t;
}

// ---- Lights ----

enum class LightKind : uint8_t { Point, Spot, Distant, DiffuseArea, UniformInfinite, ImageInfinite, Goniometric, Collimated,
                                 Projection };

struct Light {
    LightKind kind = LightKind::Point;
    Spectrum spectrum;           // I (point, spot, goniometric), L (distant, area, uniform infinite); images: unused
    Float scale = 1;             // includes pbrt-v4's 1/SpectrumToPhotometric and `power` normalizations
    Transform renderFromLight;   // point, spot, image infinite, goniometric (with pbrt-v4's y/z swap),
                                 // projection (with pbrt-v4's y flip: the CTM times Scale(1, -1, 1))
    Vec3f position;              // point, spot, goniometric, projection (render space)
    Vec3f direction;             // distant: direction the light travels *from* (wLight, towards the light)
    Float cosFalloffStart = 1, cosFalloffEnd = 0;  // spot
    uint32_t shape = NoIndex, primitive = 0;       // area light: the emitting shape and primitive
    bool twoSided = false;
    // RGB image (illuminant RGB, wrap Clamp but for image infinite) in SceneView::images: image
    // infinite (equal-area map), projection (the projected slide, nearest texel), diffuse area
    // with "filename" (NoIndex: the spectrum; else bilinear at the surface (u, 1 - v)).
    uint32_t image = NoIndex;
    uint32_t distribution = NoIndex;  // image infinite: index into SceneView::distributions2D
    Vec3f sceneCenter;           // distant / infinite / collimated: bounding sphere of the scene
    Float sceneRadius = 0;
    // A sphere containing every point SampleLi can return (area, point, spot lights; filled by the
    // builder); boundRadius < 0: none (distant, infinite). regpath culls light samples with it.
    Vec3f boundCenter;
    Float boundRadius = -1;
    // Goniometric (and spot with an IES profile): a one-channel equal-area table of the intensity
    // scale over the light-space sphere (images[profile]); NoIndex: none. An image's n x n texels
    // (nearest, as pbrt-v4), or for IES files (profileVertices) (n+1)^2 vertex samples,
    // interpolated linearly (lights/lights.h, ProfileValueAt).
    uint32_t profile = NoIndex;
    bool profileVertices = false;
    // Collimated beam (Lucerna extension, lights/collimated.h): an aperture at `position` whose
    // normal `direction` is the beam's direction of travel, a disc of radius beamRadius
    // (beamHalf.x == 0) or a rectangle of half sizes beamHalf along beamU and direction x beamU
    // (beamRadius: its half diagonal); spectral irradiance E(y) = spectrum * scale * profile,
    // profile uniform (beamWaist == 0) or gaussian exp(-2 rho^2 / beamWaist^2) (1/e^2 radius
    // beamWaist, rho the distance from the axis), 0 outside the aperture.
    Float beamRadius = 0, beamWaist = 0;
    Vec3f beamU;
    Vec2f beamHalf;
    // Projection (pbrt-v4's ProjectionLight): light-space +z is the axis; direction w projects to
    // the screen point (w.x, w.y) / (w.z projectionTan) (projectionTan = tan(fov / 2)), inside the
    // window [-projectionScreen, projectionScreen] (the shorter image side spans [-1, 1]).
    Float projectionTan = 1;
    Vec2f projectionScreen = Vec2f(1, 1);
};

// Piecewise-constant 2D distribution (for image lights), tables in SceneView::distData:
// marginal cdf (ny+1) at `offset`, conditional cdfs ((nx+1) * ny) after it, and function values.
struct Distribution2D {
    uint32_t nx = 0, ny = 0;
    uint64_t offset = 0;   // start in distData
    Float integral = 0;
};

// ---- Participating media (pbrt-v4's media.h) ----

enum class MediumKind : uint8_t { Homogeneous, UniformGrid, RGBGrid, Cloud };

// A grid of samples over the medium's bounds (pbrt-v4's SampledGrid: sample (x, y, z) sits at
// ((x + 0.5) / nx, ...) of the bounds, trilinear in between, 0 outside): `channels` floats per
// sample at SceneView::mediumData[offset + ((z * ny + y) * nx + x) * channels]. Float grids have
// 1 channel; spectrum grids 4: the sigmoid coefficients and scale of an RGB spectrum.
struct MediumGrid {
    uint32_t nx = 0, ny = 0, nz = 0, channels = 1;
    uint64_t offset = 0;
    SpectrumKind kind = SpectrumKind::RGBUnbounded;   // spectrum grids: Unbounded or Illuminant
    uint8_t colorSpace = 0;  // ColorSpaceId of the grid's RGB (its illuminant, for Illuminant grids)
};

struct Medium {
    MediumKind kind = MediumKind::Homogeneous;
    Float g = 0;                      // Henyey-Greenstein asymmetry
    // homogeneous, uniformgrid, cloud: sigma_{a,s}(lambda) = sigmaScale * spectrum (* density)
    Spectrum sigmaA, sigmaS;
    Float sigmaScale = 1;
    Spectrum Le;                      // homogeneous, uniformgrid (illuminant; scale folded into LeScale)
    Float LeScale = 0;                // homogeneous: constant; uniformgrid: times the Lescale grid
    bool emissive = false;
    Transform renderFromMedium;       // grids and cloud
    Bounds3f bounds;                  // medium space (p0, p1)
    MediumGrid density;               // uniformgrid: density; rgbgrid: sigma_a (channels 0 if absent)
    MediumGrid density2;              // rgbgrid: sigma_s
    MediumGrid LeGrid;                // uniformgrid: Lescale grid (1 sample if constant); rgbgrid: Le
    MediumGrid temperature;           // uniformgrid (nx == 0: none): Le = blackbody((T - offset) * scale)
    Float temperatureScale = 1, temperatureOffset = 0;
    MediumGrid majorant;              // 16^3 maximum density (or sigma_t for rgbgrid) over the bounds
    Float cloudDensity = 1, wispiness = 1, frequency = 5;   // cloud
};

// ---- Camera and film ----

// pbrt-v4's cameras; spherical with its two image mappings.
enum class CameraKind : uint8_t { Perspective, Orthographic, SphericalEqualArea, SphericalEquirect, Realistic };

// One spherical interface of a realistic camera's lens system (pbrt-v4's LensElementInterface),
// in meters; curvatureRadius 0 is the aperture stop. eta is the index of the medium behind the
// interface (towards the film); 0 means air. thickness: distance to the next interface.
struct LensElement {
    Float curvatureRadius = 0, thickness = 0, eta = 0, apertureRadius = 0;
};

// An axis-aligned 2D box (the exit pupil's bound on the rear element's plane, meters).
struct Bounds2f {
    Vec2f pMin{Infinity, Infinity}, pMax{-Infinity, -Infinity};
    LU_HD bool IsDegenerate() const { return !(pMax.x > pMin.x) || !(pMax.y > pMin.y); }
    LU_HD Float Area() const { return (pMax.x - pMin.x) * (pMax.y - pMin.y); }
    LU_HD bool Inside(Vec2f p) const { return p.x >= pMin.x && p.x <= pMax.x && p.y >= pMin.y && p.y <= pMax.y; }
    LU_HD void Expand(Vec2f p) {
        pMin = Vec2f(Min(pMin.x, p.x), Min(pMin.y, p.y));
        pMax = Vec2f(Max(pMax.x, p.x), Max(pMax.y, p.y));
    }
    LU_HD Vec2f Lerp(Vec2f t) const {
        return {(1 - t.x) * pMin.x + t.x * pMax.x, (1 - t.y) * pMin.y + t.y * pMax.y};
    }
};

struct CameraData {
    CameraKind kind = CameraKind::Perspective;
    Transform renderFromCamera;   // camera space is left-handed, looking down +z (pbrt-v4)
    Transform cameraFromRaster;   // perspective, orthographic (unused by spherical)
    Float lensRadius = 0, focalDistance = 1e6f;
    int width = 0, height = 0;    // full film resolution (pixels)
    uint32_t medium = NoIndex;    // the medium camera rays start in (CameraBegin's outside medium)
    // Realistic camera (pbrt-v4's RealisticCamera): the lens interfaces from the scene side to
    // the film (the last one's thickness is the rear element-film distance), the exit pupil's
    // bounds for equal radial intervals of film distance in [0, filmDiagonal / 2], and the
    // film's physical extent (meters, centred on the axis). The spans point into the scene's
    // arrays (HostScene::lensElements, exitPupilBounds; uploaded by the CUDA backend).
    Span<LensElement> lensElements;
    Span<Bounds2f> exitPupilBounds;
    Float filmDiagonal = 0;
    Vec2f physicalExtentMin, physicalExtentMax;
    // A pixel's footprint near the image centre (SetPixelFootprint): the width of the pixel's ray
    // cone at distance t from the camera is pixelWidth + pixelSpread * t (world units; spread in
    // radians). regpath's footprint kernels read it (RegularizationAtVertex).
    Float pixelWidth = 0, pixelSpread = 0;
};

enum class FilterKind : uint8_t { Box, Gaussian, Triangle, Mitchell, LanczosSinc };

struct FilterData {
    FilterKind kind = FilterKind::Gaussian;
    Float radiusX = 1.5f, radiusY = 1.5f;
    Float sigma = 0.5f;          // gaussian
    Float B = 1.f / 3, C = 1.f / 3;  // mitchell
    Float tau = 3;               // sinc: the Lanczos window's number of sinc periods
    uint32_t distribution = NoIndex;  // tabulated filter importance distribution (Distribution2D index)
    bool disableJitter = false;  // Option "disablepixeljitter": every sample at the pixel center, weight 1
};

struct FilmData {
    int width = 0, height = 0;
    Float imagingRatio = 1;      // exposure time * iso / 100
    Float xyzToOutput[3][3];     // XYZ -> linear RGB of the film's color space (white balance folded in, if any)
    Float maxComponentValue = Infinity;
    bool disableWavelengthJitter = false;  // Option "disablewavelengthjitter": wavelength sample u = 0.5
    // The least weight sum a pixel's sums are divided by, per sample (FilmAccumulator::Resolve):
    // half a sample's expected filter weight for filters with negative lobes (mitchell, sinc),
    // whose signed weight sums can fall near 0 at low sample counts; 0 for the others.
    Float filterWeightFloor = 0;
    Float diagonalMm = 35;       // the sensor's diagonal (Film "diagonal", mm; the realistic camera's film size)
};

// ---- The whole scene, as spans over one upload per array ----

struct SceneView {
    Span<Vec3f> positions, normals;
    Span<Vec2f> uvs;
    Span<uint32_t> indices;
    Span<TriangleMesh> triangleMeshes;
    Span<Sphere> spheres;
    Span<Disk> disks;
    Span<Cylinder> cylinders;
    Span<BilinearMesh> bilinearMeshes;   // their vertices are in positions / normals / uvs / indices
    Span<CurveSet> curveSets;
    Span<CurveSegment> curveSegments;
    Span<Shape> shapes;
    Span<Prototype> prototypes;     // object instancing: empty when the scene has none
    Span<Instance> instances;
    Span<Material> materials;
    Span<Light> lights;
    Span<Float> lightCdf;           // light selection CDF (size lights.size + 1), proportional to power
    Span<uint32_t> infiniteLights;  // indices of lights with no position (for escaped rays)
    Span<ImageData> images;
    Span<Float> texels;
    Span<FloatTexture> floatTextures;        // texture children (a material holds its root textures)
    Span<SpectrumTexture> spectrumTextures;
    Span<Distribution2D> distributions2D;
    Span<Float> distData;
    Span<Vec2f> pmjPoints;     // the pmj02bn sampler's tables (Sampler::pmjPoints), else empty
    SpectrumTables spectra;
    // RGB -> sigmoid coefficient tables (Jakob & Hanika 2019), one per color space in ColorSpaceId
    // order, concatenated: each 3 * res^3 * 3 entries (res^3 * 3 per maximal component); zNodes
    // (size res) shared. Only sRGB's when nothing looks another one up at render time.
    Span<Float> rgbToSpecCoeffs, rgbToSpecZNodes;
    uint32_t rgbToSpecRes = 0;
    uint32_t illuminantTables[NumColorSpaces] = {0, 0, 0, 0};  // each color space's illuminant, in spectra
    Span<Medium> media;
    Span<Float> mediumData;         // the grids of the media (MediumGrid)
    Span<Float> measuredData;       // the tables of the measured materials (MeasuredBRDFData)
    // Shadow rays must walk through interface surfaces (the scene has media or "interface"
    // shapes); false: a shadow ray is one occlusion query.
    bool walkInterfaces = false;
    uint32_t transmitters = 0;      // materials that can transmit light (dielectric, thindielectric)
    uint32_t collimatedLights = 0;  // LightKind::Collimated lights (rays test their discs only when > 0)
    uint32_t deltaLights = 0;       // point, spot, distant, goniometric and projection lights (IsDeltaLight)
    uint32_t alphaShapes = 0;       // shapes with an alpha texture (the BVH tests Shape::alpha only when > 0)
    CameraData camera;
    FilmData film;
    FilterData filter;
    Bounds3f bounds;
};

// The RGB -> spectrum table of color space cs (a ColorSpaceId); sRGB's (the first) when the scene
// holds no table for cs.
LU_INLINE const Float *RGBToSpecCoeffs(const SceneView &s, uint32_t cs) {
    uint64_t size = uint64_t(9) * s.rgbToSpecRes * s.rgbToSpecRes * s.rgbToSpecRes;
    return (uint64_t(cs) + 1) * size <= s.rgbToSpecCoeffs.size ? s.rgbToSpecCoeffs.ptr + cs * size : s.rgbToSpecCoeffs.ptr;
}

LU_INLINE uint32_t IlluminantTable(const SceneView &s, uint32_t cs) {
    return s.illuminantTables[cs < NumColorSpaces ? cs : 0];
}

// Shapes in render space: every shape before the first prototype's.
LU_INLINE uint32_t TopLevelShapeCount(const SceneView &s) {
    return s.prototypes.size == 0 ? s.shapes.size : s.prototypes[0].firstShape;
}

}  // namespace lu
