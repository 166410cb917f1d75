// Lucerna: what a ray hit, as the integrator, materials and lights see it (host and device).
#pragma once

#include "lucerna/util/vecmath.h"

namespace lu {

// Raw hit from a backend's closest-hit query: enough to rebuild the SurfaceInteraction.
struct HitRecord {
    Float t = Infinity;
    uint32_t shape = 0xffffffffu;   // index into SceneView::shapes (the geometry id)
    uint32_t primitive = 0;         // triangle index within the mesh (0 for analytic shapes)
    Float b1 = 0, b2 = 0;           // barycentrics of vertices 1 and 2 (triangles)
    uint32_t instance = 0xffffffffu; // SceneView::instances index when the shape is a prototype's
    LU_HD bool Hit() const { return shape != 0xffffffffu; }
};

struct SurfaceInteraction {
    Vec3f p;          // render-space position
    Vec3f n;          // geometric normal, unit, oriented as pbrt-v4 (flipped by ReverseOrientation/handedness)
    Vec3f ns;         // shading normal, unit, in the hemisphere of n
    Vec3f dpdu;       // tangent for the shading frame (anisotropic roughness)
    Vec2f uv;
    Vec3f wo;         // unit, towards the previous vertex
    uint32_t shape = 0xffffffffu, primitive = 0;
    uint32_t material = 0xffffffffu;  // NoIndex: interface
    uint32_t areaLight = 0xffffffffu; // light index of the emitting primitive, or NoIndex
    uint32_t instance = 0xffffffffu;  // HitRecord::instance: the shape is a prototype's, seen through it
};

// pbrt-v4's shading-geometry partial derivatives at a hit (its SurfaceInteraction::shading
// dpdu, dpdv, dndu, dndv), render space. Bump mapping needs them; they are computed on demand
// (ComputeShadingDerivatives, geometry/shapes.h), not for every hit.
struct ShadingDerivatives {
    Vec3f dpdu, dpdv;   // shading tangents (for meshes with normals: pbrt-v4's ss, ts)
    Vec3f dndu, dndv;   // derivatives of the unit shading normal along u and v
};

// Where texture lookups happen.
struct TextureEvalContext {
    Vec3f p;
    Vec3f n;
    Vec2f uv;
};

}  // namespace lu
