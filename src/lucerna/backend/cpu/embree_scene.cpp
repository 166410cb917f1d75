// Lucerna CPU backend: Embree 3 scene construction and queries.
#include "lucerna/backend/cpu/embree_scene.h"

#include <cassert>
#include <chrono>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "lucerna/geometry/alpha.h"
#include "lucerna/geometry/shapes.h"

namespace lu {

namespace {

constexpr uint32_t kTwoLevelMaxShapes = 256;

using UserGeomData = EmbreeUserData;

Bounds3f TransformedBounds(const Transform &t, const Vec3f &lo, const Vec3f &hi) {
    Bounds3f b;
    for (int i = 0; i < 8; ++i) {
        Vec3f c((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
        b.Expand(t.ApplyPoint(c));
    }
    return b;
}

Bounds3f ShapeBounds(const SceneView &s, const Shape &shape) {
    if (shape.kind == ShapeKind::Sphere) {
        const Sphere &sp = s.spheres[shape.index];
        Float r = sp.radius;
        return TransformedBounds(sp.renderFromObject, Vec3f(-r, -r, -r), Vec3f(r, r, r));
    }
    if (shape.kind == ShapeKind::Cylinder) {   // the whole tube's box, also for a partial one
        const Cylinder &c = s.cylinders[shape.index];
        return TransformedBounds(c.renderFromObject, Vec3f(-c.radius, -c.radius, c.zMin), Vec3f(c.radius, c.radius, c.zMax));
    }
    const Disk &d = s.disks[shape.index];
    return TransformedBounds(d.renderFromObject, Vec3f(-d.radius, -d.radius, d.height), Vec3f(d.radius, d.radius, d.height));
}

// The callbacks' context (every query passes an EmbreeAlphaContext).
const EmbreeAlphaContext &AlphaContext(const RTCIntersectContext *c) {
    return *reinterpret_cast<const EmbreeAlphaContext *>(c);
}

// An analytic shape's hit, its alpha cut-out applied (IntersectAnalyticAlpha).
bool IntersectAnalytic(const SceneView &s, uint32_t shape, const Ray &r, const RTCIntersectContext *c, Float tMax,
                       Float *t) {
    const EmbreeAlphaContext &ac = AlphaContext(c);
    return IntersectAnalyticAlpha(s, shape, r, *ac.renderRay, ac.instance, tMax, t);
}

// A user geometry's primitive: a quadric (one per shape; its alpha's far side) or a bilinear
// patch or curve piece, whose (u, v) the hit carries.
bool IntersectUser(const SceneView &s, uint32_t shape, uint32_t prim, const Ray &r, const RTCIntersectContext *c,
                   Float tMax, Float *t, Float *u, Float *v) {
    if (IsQuadric(s.shapes[shape].kind)) return IntersectAnalytic(s, shape, r, c, tMax, t);
    const EmbreeAlphaContext &ac = AlphaContext(c);
    return IntersectPatchOrCurveAlpha(s, shape, prim, r, *ac.renderRay, ac.instance, tMax, t, u, v);
}

// Triangle meshes with alpha: drops the candidate hits the cut-out ignores (intersect and occluded).
void AlphaFilter(const RTCFilterFunctionNArguments *args) {
    auto *d = static_cast<const EmbreeUserData *>(args->geometryUserPtr);
    const EmbreeAlphaContext &ac = AlphaContext(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        HitRecord h;
        h.t = RTCRayN_tfar(args->ray, args->N, i);   // the candidate's distance
        h.shape = d->shape;
        h.primitive = RTCHitN_primID(args->hit, args->N, i);
        h.b1 = RTCHitN_u(args->hit, args->N, i);
        h.b2 = RTCHitN_v(args->hit, args->N, i);
        h.instance = ac.instance;
        if (!AlphaKeepsHit(*d->view, *ac.renderRay, h)) args->valid[i] = 0;
    }
}

[[maybe_unused]] bool IsFinite3(const Vec3f &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void UserBounds(const RTCBoundsFunctionArguments *args) {
    auto *d = static_cast<const UserGeomData *>(args->geometryUserPtr);
    const Shape &shape = d->view->shapes[d->shape];
    Bounds3f b = IsQuadric(shape.kind) ? ShapeBounds(*d->view, shape) : PatchOrCurveBounds(*d->view, shape, args->primID);
    assert(IsFinite3(b.pMin) && IsFinite3(b.pMax) && "Embree user geometry: non-finite bounds");
    // Pad slightly: the bounds must enclose float-rounded hits.
    Vec3f pad = (b.pMax - b.pMin) * 1e-5f + Vec3f(1e-6f, 1e-6f, 1e-6f);
    args->bounds_o->lower_x = b.pMin.x - pad.x; args->bounds_o->lower_y = b.pMin.y - pad.y; args->bounds_o->lower_z = b.pMin.z - pad.z;
    args->bounds_o->upper_x = b.pMax.x + pad.x; args->bounds_o->upper_y = b.pMax.y + pad.y; args->bounds_o->upper_z = b.pMax.z + pad.z;
}

void UserIntersect(const RTCIntersectFunctionNArguments *args) {
    auto *d = static_cast<const UserGeomData *>(args->geometryUserPtr);
    RTCRayHitN *rh = args->rayhit;
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        RTCRayN *rn = RTCRayHitN_RayN(rh, args->N);
        RTCHitN *hn = RTCRayHitN_HitN(rh, args->N);
        Ray r;
        r.o = Vec3f(RTCRayN_org_x(rn, args->N, i), RTCRayN_org_y(rn, args->N, i), RTCRayN_org_z(rn, args->N, i));
        r.d = Vec3f(RTCRayN_dir_x(rn, args->N, i), RTCRayN_dir_y(rn, args->N, i), RTCRayN_dir_z(rn, args->N, i));
        Float tfar = RTCRayN_tfar(rn, args->N, i);
        Float t, u = 0, v = 0;
        if (!IntersectUser(*d->view, d->shape, args->primID, r, args->context, tfar, &t, &u, &v)) continue;
        assert(t >= 0 && t <= tfar && "Embree user geometry: hit distance NaN or out of the ray's range");
        RTCRayN_tfar(rn, args->N, i) = t;
        RTCHitN_geomID(hn, args->N, i) = args->geomID;
        RTCHitN_primID(hn, args->N, i) = args->primID;
        RTCHitN_u(hn, args->N, i) = u;
        RTCHitN_v(hn, args->N, i) = v;
        RTCHitN_Ng_x(hn, args->N, i) = 0;
        RTCHitN_Ng_y(hn, args->N, i) = 0;
        RTCHitN_Ng_z(hn, args->N, i) = 1;
        RTCHitN_instID(hn, args->N, i, 0) = RTC_INVALID_GEOMETRY_ID;
    }
}

void UserOccluded(const RTCOccludedFunctionNArguments *args) {
    auto *d = static_cast<const UserGeomData *>(args->geometryUserPtr);
    RTCRayN *rn = args->ray;
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        Ray r;
        r.o = Vec3f(RTCRayN_org_x(rn, args->N, i), RTCRayN_org_y(rn, args->N, i), RTCRayN_org_z(rn, args->N, i));
        r.d = Vec3f(RTCRayN_dir_x(rn, args->N, i), RTCRayN_dir_y(rn, args->N, i), RTCRayN_dir_z(rn, args->N, i));
        Float t, u, v;
        if (IntersectUser(*d->view, d->shape, args->primID, r, args->context, RTCRayN_tfar(rn, args->N, i), &t, &u, &v))
            RTCRayN_tfar(rn, args->N, i) = -Infinity;
    }
}

// ---- Instances: one user geometry, primitive i = SceneView::instances[i] ----

using InstanceGeomData = EmbreeInstanceData;

void InstanceBounds(const RTCBoundsFunctionArguments *args) {
    auto *d = static_cast<const InstanceGeomData *>(args->geometryUserPtr);
    const Instance &in = d->view->instances[args->primID];
    const Bounds3f &ob = d->view->prototypes[in.prototype].bounds;
    Bounds3f b;
    for (int c = 0; c < 8; ++c)
        b.Expand(InstancePoint(in.renderFromInstance, Vec3f(c & 1 ? ob.pMax.x : ob.pMin.x, c & 2 ? ob.pMax.y : ob.pMin.y,
                                                             c & 4 ? ob.pMax.z : ob.pMin.z)));
    Vec3f pad = (b.pMax - b.pMin) * 1e-5f + Vec3f(1e-6f, 1e-6f, 1e-6f);
    args->bounds_o->lower_x = b.pMin.x - pad.x; args->bounds_o->lower_y = b.pMin.y - pad.y; args->bounds_o->lower_z = b.pMin.z - pad.z;
    args->bounds_o->upper_x = b.pMax.x + pad.x; args->bounds_o->upper_y = b.pMax.y + pad.y; args->bounds_o->upper_z = b.pMax.z + pad.z;
}

// The ray in object space: same t (the direction is not renormalized).
void ObjectRay(const Instance &in, RTCRayN *rn, unsigned N, unsigned i, RTCRay *r) {
    Vec3f o(RTCRayN_org_x(rn, N, i), RTCRayN_org_y(rn, N, i), RTCRayN_org_z(rn, N, i));
    Vec3f dir(RTCRayN_dir_x(rn, N, i), RTCRayN_dir_y(rn, N, i), RTCRayN_dir_z(rn, N, i));
    Vec3f oo = InstancePoint(in.instanceFromRender, o), od = InstanceVector(in.instanceFromRender, dir);
    r->org_x = oo.x; r->org_y = oo.y; r->org_z = oo.z;
    r->dir_x = od.x; r->dir_y = od.y; r->dir_z = od.z;
    r->tnear = RTCRayN_tnear(rn, N, i);
    r->tfar = RTCRayN_tfar(rn, N, i);
    r->time = 0;
    r->mask = 0xffffffffu;
    r->id = 0;
    r->flags = 0;
}

void InstanceIntersect(const RTCIntersectFunctionNArguments *args) {
    auto *d = static_cast<const InstanceGeomData *>(args->geometryUserPtr);
    const Instance &in = d->view->instances[args->primID];
    const uint32_t firstShape = d->view->prototypes[in.prototype].firstShape;
    RTCRayN *rn = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN *hn = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        RTCRayHit rh;
        ObjectRay(in, rn, args->N, i, &rh.ray);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        EmbreeAlphaContext ctx;
        rtcInitIntersectContext(&ctx.ctx);
        ctx.renderRay = AlphaContext(args->context).renderRay;
        ctx.instance = args->primID;
        rtcIntersect1((*d->prototypes)[in.prototype], &ctx.ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        RTCRayN_tfar(rn, args->N, i) = rh.ray.tfar;
        RTCHitN_geomID(hn, args->N, i) = firstShape + rh.hit.geomID;   // the shape id
        RTCHitN_primID(hn, args->N, i) = rh.hit.primID;
        RTCHitN_u(hn, args->N, i) = rh.hit.u;
        RTCHitN_v(hn, args->N, i) = rh.hit.v;
        RTCHitN_Ng_x(hn, args->N, i) = rh.hit.Ng_x;
        RTCHitN_Ng_y(hn, args->N, i) = rh.hit.Ng_y;
        RTCHitN_Ng_z(hn, args->N, i) = rh.hit.Ng_z;
        RTCHitN_instID(hn, args->N, i, 0) = args->primID;
    }
}

void InstanceOccluded(const RTCOccludedFunctionNArguments *args) {
    auto *d = static_cast<const InstanceGeomData *>(args->geometryUserPtr);
    const Instance &in = d->view->instances[args->primID];
    RTCRayN *rn = args->ray;
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        RTCRay r;
        ObjectRay(in, rn, args->N, i, &r);
        EmbreeAlphaContext ctx;
        rtcInitIntersectContext(&ctx.ctx);
        ctx.renderRay = AlphaContext(args->context).renderRay;
        ctx.instance = args->primID;
        rtcOccluded1((*d->prototypes)[in.prototype], &ctx.ctx, &r);
        if (r.tfar < 0) RTCRayN_tfar(rn, args->N, i) = -Infinity;
    }
}

void ErrorCallback(void *, RTCError code, const char *str) {
    throw std::runtime_error(std::string("Embree error ") + std::to_string(int(code)) + ": " + (str ? str : ""));
}

}  // namespace

EmbreeScene::EmbreeScene(const SceneView &s) : view_(&s) {
    auto t0 = std::chrono::steady_clock::now();
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("cannot create the Embree device");
    rtcSetDeviceErrorFunction(device_, ErrorCallback, nullptr);
    scene_ = rtcNewScene(device_);
    // Few shapes: Embree's two-level structure (BUILD_QUALITY_LOW: one BVH per shape under a
    // top-level BVH) traced the shared scenes faster than the single-level spatial-split BVH
    // (Embree instructions per ray -35% Cornell box, -9% Veach MIS and water caustic; paired
    // timings agree) and builds in a fraction of the time. Many shapes (overlapping bounds are
    // likelier) keep the single-level HIGH build. Hits are the same (up to exact ties).
    rtcSetSceneBuildQuality(scene_, s.shapes.size <= kTwoLevelMaxShapes ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_HIGH);
    userData_.reserve(s.shapes.size);
    const uint32_t topShapes = TopLevelShapeCount(s);
    auto newGeometry = [&](uint32_t id) {
        const Shape &shape = s.shapes[id];
        RTCGeometry g;
        if (shape.kind == ShapeKind::Triangles) {
            const TriangleMesh &m = s.triangleMeshes[shape.index];
            g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto *vb = static_cast<float *>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                    3 * sizeof(float), m.vertexCount));
            for (uint32_t v = 0; v < m.vertexCount; ++v) {
                const Vec3f &p = s.positions[m.firstVertex + v];
                assert(IsFinite3(p) && "Embree triangle mesh: non-finite vertex");
                vb[3 * v] = p.x; vb[3 * v + 1] = p.y; vb[3 * v + 2] = p.z;
            }
            auto *ib = static_cast<uint32_t *>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                       3 * sizeof(uint32_t), m.triangleCount));
            std::memcpy(ib, s.indices.ptr + m.firstIndex, size_t(m.triangleCount) * 3 * sizeof(uint32_t));
            if (shape.alpha != NoIndex) {
                userData_.push_back(EmbreeUserData{&s, id});
                rtcSetGeometryUserData(g, &userData_.back());
                rtcSetGeometryIntersectFilterFunction(g, AlphaFilter);
                rtcSetGeometryOccludedFilterFunction(g, AlphaFilter);
            }
        } else {
            g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
            userData_.push_back(EmbreeUserData{&s, id});
            rtcSetGeometryUserPrimitiveCount(g, IsQuadric(shape.kind) ? 1 : shape.primitiveCount);
            rtcSetGeometryUserData(g, &userData_.back());
            rtcSetGeometryBoundsFunction(g, UserBounds, nullptr);
            rtcSetGeometryIntersectFunction(g, UserIntersect);
            rtcSetGeometryOccludedFunction(g, UserOccluded);
        }
        rtcCommitGeometry(g);
        return g;
    };
    for (uint32_t id = 0; id < topShapes; ++id) {
        RTCGeometry g = newGeometry(id);
        rtcAttachGeometryByID(scene_, g, id);
        rtcReleaseGeometry(g);
    }
    // Prototypes: their shapes by local id (shape - firstShape) in a scene of their own.
    for (uint32_t p = 0; p < s.prototypes.size; ++p) {
        const Prototype &proto = s.prototypes[p];
        RTCScene ps = rtcNewScene(device_);
        rtcSetSceneBuildQuality(ps, RTC_BUILD_QUALITY_HIGH);
        for (uint32_t k = 0; k < proto.shapeCount; ++k) {
            RTCGeometry g = newGeometry(proto.firstShape + k);
            rtcAttachGeometryByID(ps, g, k);
            rtcReleaseGeometry(g);
        }
        rtcCommitScene(ps);
        prototypeScenes_.push_back(ps);
    }
    if (s.instances.size > 0) {
        // Medium quality with a compact BVH: 105 bytes per instance for 3.2 M instances (HIGH
        // needs more; native RTC_GEOMETRY_TYPE_INSTANCE 443 bytes; docs/benchmarks.md).
        instanceData_ = std::make_unique<EmbreeInstanceData>(EmbreeInstanceData{&s, &prototypeScenes_});
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, s.instances.size);
        rtcSetGeometryUserData(g, instanceData_.get());
        rtcSetGeometryBoundsFunction(g, InstanceBounds, nullptr);
        rtcSetGeometryIntersectFunction(g, InstanceIntersect);
        rtcSetGeometryOccludedFunction(g, InstanceOccluded);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(scene_, g, topShapes);
        rtcReleaseGeometry(g);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_COMPACT);
    }
    rtcCommitScene(scene_);
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

EmbreeScene::~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
    for (RTCScene ps : prototypeScenes_) rtcReleaseScene(ps);
    if (device_) rtcReleaseDevice(device_);
}

}  // namespace lu
