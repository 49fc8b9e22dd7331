// EmbreeAggregate: Embree 3 scenes for pbrt_ext's shapes.
#include "pbrt_ext/shapes/aggregate.h"

#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/log.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <deque>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace pbrt {

namespace {

const char *ErrorName(RTCError code) {
    switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
    }
}

void ReportEmbreeError(void *, RTCError code, const char *message) {
    Error("Embree: %s (%s)", message ? message : "", ErrorName(code));
}

// A shape's world box, padded so that float rounding in its transform cannot cut off a sliver
// of the surface that the exact intersection routine would report.
void SetBounds(const Bounds3f &b, RTCBounds *out) {
    Vector3f pad = (b.pMax - b.pMin) * 1e-5f + Vector3f(1e-7f, 1e-7f, 1e-7f);
    out->lower_x = b.pMin.x - pad.x;
    out->lower_y = b.pMin.y - pad.y;
    out->lower_z = b.pMin.z - pad.z;
    out->upper_x = b.pMax.x + pad.x;
    out->upper_y = b.pMax.y + pad.y;
    out->upper_z = b.pMax.z + pad.z;
}

// time: the ray's time as a fraction of the moving instances' interval (Embree's [0, 1]).
RTCRay ToEmbree(const Ray &ray, Float tMax, Float time) {
    RTCRay r;
    r.org_x = ray.o.x;
    r.org_y = ray.o.y;
    r.org_z = ray.o.z;
    r.dir_x = ray.d.x;
    r.dir_y = ray.d.y;
    r.dir_z = ray.d.z;
    r.tnear = 0;
    r.tfar = tMax;
    r.time = time;
    r.mask = ~0u;
    r.id = 0;
    r.flags = 0;
    return r;
}

// Single-ray queries (rtcIntersect1/rtcOccluded1) call user geometry with N = 1.
Ray RayFrom(const RTCRay &r) {
    return Ray(Point3f(r.org_x, r.org_y, r.org_z), Vector3f(r.dir_x, r.dir_y, r.dir_z));
}

void RecordHit(RTCRayHit *rh, const RTCIntersectFunctionNArguments *args, Float t, Float u,
               Float v, Point3f pObj) {
    rh->ray.tfar = t;
    rh->hit.u = u;
    rh->hit.v = v;
    // Ng is ours to use for user geometry: it carries a quadric's object-space hit point to
    // Intersect, which rebuilds the interaction only for the closest hit.
    rh->hit.Ng_x = pObj.x;
    rh->hit.Ng_y = pObj.y;
    rh->hit.Ng_z = pObj.z;
    rh->hit.primID = args->primID;
    rh->hit.geomID = args->geomID;
    rh->hit.instID[0] = args->context->instID[0];
}

// pbrt-v4's HashFloat: the hash of the values, mapped to [0, 1).
template <typename... Args>
Float HashFloat(Args... args) {
    return Float(uint32_t(Hash(args...))) * 0x1p-32f;
}

// pbrt-v4's alpha test of a hit, with u the hit's uniform number. pbrt-v4 follows a rejected hit
// with a new ray from it, hashed anew; hashing the hit's distance t with the ray (o, d, in the
// geometry's own space) gives each hit along one ray its own decision in the same way, so that
// stacked cut-outs are independent.
bool AlphaKeeps(const FloatTexture &alpha, const SurfaceInteraction &si, Float u) {
    Float a = alpha.Evaluate(TextureEvalContext(si));
    if (a >= 1)
        return true;
    return a > 0 && u <= a;
}

bool AlphaKeeps(const FloatTexture &alpha, const SurfaceInteraction &si, const Ray &ray, Float t) {
    return AlphaKeeps(alpha, si, HashFloat(ray.o, ray.d, t));
}

// What Embree's callbacks for one geometry read through its user pointer.
struct CallbackData {
    const void *shape;          // TriangleMesh, BilinearPatchMesh or a quadric
    const FloatTexture *alpha;  // null: opaque
};

const CallbackData &DataOf(const void *userPtr) {
    return *static_cast<const CallbackData *>(userPtr);
}

// Embree's barycentrics weight vertices 1 and 2.
std::array<Float, 3> Barycentrics(const RTCHit &hit) {
    return {1 - hit.u - hit.v, hit.u, hit.v};
}

// Embree calls a geometry's filter for every candidate hit of closest-hit and shadow queries
// alike, and skips the candidates it marks invalid; keeps(data, ray, its RTCRay, hit) is the
// alpha test's decision.
template <typename Keeps>
void AlphaFilter(const RTCFilterFunctionNArguments *args, Keeps keeps) {
    assert(args->N == 1);
    if (!args->valid[0])
        return;
    const RTCRay &r = *reinterpret_cast<const RTCRay *>(args->ray);
    const RTCHit &hit = *reinterpret_cast<const RTCHit *>(args->hit);
    if (!keeps(DataOf(args->geometryUserPtr), RayFrom(r), r, hit))
        args->valid[0] = 0;
}

// Triangle meshes with alpha only.
void TriangleAlphaFilter(const RTCFilterFunctionNArguments *args) {
    AlphaFilter(args, [](const CallbackData &data, const Ray &ray, const RTCRay &r, const RTCHit &hit) {
        SurfaceInteraction si = Triangle::InteractionFromIntersection(
            static_cast<const TriangleMesh *>(data.shape), int(hit.primID), Barycentrics(hit),
            -Normalize(ray.d));
        return AlphaKeeps(*data.alpha, si, ray, r.tfar);  // tfar is the candidate's distance
    });
}

// Curves with alpha only: the same test at the curve's (u, v) and point (pbrt-v4 tests every
// shape's hits alike). pbrt-v4's curves are strips facing the ray, crossed once; a round curve
// is crossed twice, so both of its hits share one decision, hashed from the ray and segment.
void CurveAlphaFilter(const RTCFilterFunctionNArguments *args) {
    AlphaFilter(args, [](const CallbackData &data, const Ray &ray, const RTCRay &r, const RTCHit &hit) {
        SurfaceInteraction si = CurveInteraction(*static_cast<const CurveMesh *>(data.shape),
                                                 int(hit.primID), hit.u, ray, r.tfar);
        return AlphaKeeps(*data.alpha, si, HashFloat(ray.o, ray.d, hit.primID));
    });
}

// How many times a ray can cross the quadric: the alpha test looks no further.
template <typename Quadric>
constexpr int kMaxQuadricHits = 1;
template <>
constexpr int kMaxQuadricHits<Sphere> = 2;
template <>
constexpr int kMaxQuadricHits<Cylinder> = 2;

// The first hit from `hit` on that the alpha test keeps. Past a rejected hit the search goes on
// with a ray from just beyond it, as pbrt-v4's continuation ray does. The step (1e-5 of the
// point's largest coordinate) is ~100 times the rounding of a ray origin placed there, so the
// rejected point is not found again; a ray that crosses less than that much of the quadric
// loses the farther crossing.
template <typename Quadric>
pstd::optional<QuadricIntersection> FirstKept(const Quadric &shape, const FloatTexture &alpha,
                                              const Ray &ray, Float tMax,
                                              pstd::optional<QuadricIntersection> hit) {
    Vector3f wo = -Normalize(ray.d);
    for (int tested = 1; hit; ++tested) {
        if (AlphaKeeps(alpha, shape.InteractionFromIntersection(*hit, wo), ray, hit->tHit))
            return hit;
        if (tested == kMaxQuadricHits<Quadric>)
            return {};
        Vector3f p = Abs(Vector3f(ray(hit->tHit)));
        Float t0 = hit->tHit + 1e-5f * std::max({p.x, p.y, p.z}) / Length(ray.d);
        hit = shape.BasicIntersect(Ray(ray(t0), ray.d), tMax - t0);
        if (hit)
            hit->tHit += t0;
    }
    return {};
}

// Embree intersects flat and normal-oriented curves as chains of straight pieces, 4 per segment
// by default, which can leave the true curve where it bends more than its width. The pieces
// for a curve within a tenth of its radius: a cubic's chord error over a piece of 1/N of its
// parameter is at most max|c''| / (8 N^2), and |c''| <= 6 max|p[i] - 2 p[i+1] + p[i+2]|.
float FlatCurveTessellation(const CurveMesh &curves) {
    Float bend = 0, minRadius = Infinity;
    for (int s = 0; s < curves.NumSegments(); ++s) {
        const Point3f *p = &curves.cp[4 * s];
        for (int i = 0; i < 2; ++i)
            bend = std::max(bend, 6 * Length((p[i] - p[i + 1]) + (p[i + 2] - p[i + 1])));
        minRadius = std::min(minRadius, std::min(curves.width[2 * s], curves.width[2 * s + 1]) / 2);
    }
    if (!(minRadius > 0))
        return 4;
    return Clamp(std::ceil(std::sqrt(bend / (8 * 0.1f * minRadius))), 4, 64);
}

// Spheres, cylinders and disks: one primitive per geometry.
template <typename Quadric>
struct QuadricCallbacks {
    static const Quadric &ShapeOf(const void *userPtr) {
        return *static_cast<const Quadric *>(DataOf(userPtr).shape);
    }
    // The nearest hit with tnear <= t < tfar that the alpha test keeps.
    static pstd::optional<QuadricIntersection> Hit(const void *userPtr, const RTCRay &r) {
        const Quadric &shape = ShapeOf(userPtr);
        Ray ray = RayFrom(r);
        pstd::optional<QuadricIntersection> isect = shape.BasicIntersect(ray, r.tfar);
        if (!isect || isect->tHit < r.tnear)
            return {};
        const FloatTexture *alpha = DataOf(userPtr).alpha;
        return alpha ? FirstKept(shape, *alpha, ray, r.tfar, isect) : isect;
    }
    static void Bounds(const RTCBoundsFunctionArguments *args) {
        SetBounds(ShapeOf(args->geometryUserPtr).Bounds(), args->bounds_o);
    }
    static void Intersect(const RTCIntersectFunctionNArguments *args) {
        assert(args->N == 1);
        if (!args->valid[0])
            return;
        RTCRayHit *rh = reinterpret_cast<RTCRayHit *>(args->rayhit);
        if (pstd::optional<QuadricIntersection> isect = Hit(args->geometryUserPtr, rh->ray))
            RecordHit(rh, args, isect->tHit, 0, 0, isect->pObj);
    }
    static void Occluded(const RTCOccludedFunctionNArguments *args) {
        assert(args->N == 1);
        if (!args->valid[0])
            return;
        RTCRay *ray = reinterpret_cast<RTCRay *>(args->ray);
        if (Hit(args->geometryUserPtr, *ray))
            ray->tfar = -Infinity;  // Embree's mark for an occluded ray
    }
};

struct PatchCallbacks {
    static const BilinearPatchMesh &MeshOf(const void *userPtr) {
        return *static_cast<const BilinearPatchMesh *>(DataOf(userPtr).shape);
    }
    static std::array<Point3f, 4> Corners(const BilinearPatchMesh &mesh, unsigned primID) {
        const int *v = &mesh.indices[4 * primID];
        return {mesh.p[v[0]], mesh.p[v[1]], mesh.p[v[2]], mesh.p[v[3]]};
    }
    // The nearest hit with tnear <= t < tfar, if the alpha test keeps it. A curved patch may be
    // crossed twice; the farther crossing is not looked for behind a rejected one.
    static pstd::optional<BilinearIntersection> Hit(const void *userPtr, unsigned primID,
                                                    const RTCRay &r) {
        const BilinearPatchMesh &mesh = MeshOf(userPtr);
        auto [p00, p10, p01, p11] = Corners(mesh, primID);
        Ray ray = RayFrom(r);
        pstd::optional<BilinearIntersection> hit =
            IntersectBilinearPatch(ray, r.tfar, p00, p10, p01, p11);
        if (!hit || hit->t < r.tnear)
            return {};
        const FloatTexture *alpha = DataOf(userPtr).alpha;
        if (alpha && !AlphaKeeps(*alpha,
                                 BilinearPatch::InteractionFromIntersection(
                                     &mesh, int(primID), hit->uv, -Normalize(ray.d)),
                                 ray, hit->t))
            return {};
        return hit;
    }
    static void Bounds(const RTCBoundsFunctionArguments *args) {
        auto [p00, p10, p01, p11] = Corners(MeshOf(args->geometryUserPtr), args->primID);
        SetBounds(Union(Bounds3f(p00, p10), Bounds3f(p01, p11)), args->bounds_o);
    }
    static void Intersect(const RTCIntersectFunctionNArguments *args) {
        assert(args->N == 1);
        if (!args->valid[0])
            return;
        RTCRayHit *rh = reinterpret_cast<RTCRayHit *>(args->rayhit);
        if (pstd::optional<BilinearIntersection> hit =
                Hit(args->geometryUserPtr, args->primID, rh->ray))
            RecordHit(rh, args, hit->t, hit->uv[0], hit->uv[1], Point3f());
    }
    static void Occluded(const RTCOccludedFunctionNArguments *args) {
        assert(args->N == 1);
        if (!args->valid[0])
            return;
        RTCRay *ray = reinterpret_cast<RTCRay *>(args->ray);
        if (Hit(args->geometryUserPtr, args->primID, *ray))
            ray->tfar = -Infinity;
    }
};

enum class GeometryKind : uint8_t {
    Triangles,
    BilinearPatches,
    Curves,
    Sphere,
    Cylinder,
    Disk,
    Instance
};

template <typename Quadric>
constexpr GeometryKind kQuadricKind = GeometryKind::Sphere;
template <>
constexpr GeometryKind kQuadricKind<Cylinder> = GeometryKind::Cylinder;
template <>
constexpr GeometryKind kQuadricKind<Disk> = GeometryKind::Disk;

// What a hit on geometry geomID of a scene needs, indexed by geomID.
struct GeometryRecord {
    GeometryKind kind;
    const void *shape;  // TriangleMesh, BilinearPatchMesh or a quadric; unused for instances
    PrimitiveAttributes attrs;
    int instanceIndex = -1;  // Instance: into Impl::instances
};

struct SceneData {
    RTCScene scene = nullptr;
    std::vector<GeometryRecord> geometries;
};

struct InstanceData {
    int objectId;
    KeyframedTransform worldFromInstance;
};

// A keyframe as Embree's instance motion blur takes it.
RTCQuaternionDecomposition ToEmbree(const TransformDecomposition &d) {
    RTCQuaternionDecomposition q;
    rtcInitQuaternionDecomposition(&q);
    rtcQuaternionDecompositionSetScale(&q, d.scale[0][0], d.scale[1][1], d.scale[2][2]);
    rtcQuaternionDecompositionSetSkew(&q, d.scale[0][1], d.scale[0][2], d.scale[1][2]);
    rtcQuaternionDecompositionSetQuaternion(&q, d.rotation.w, d.rotation.v.x, d.rotation.v.y,
                                            d.rotation.v.z);
    rtcQuaternionDecompositionSetTranslation(&q, d.translation.x, d.translation.y,
                                             d.translation.z);
    return q;
}

}  // namespace

struct EmbreeAggregate::Impl {
    RTCDevice device = nullptr;
    SceneData world;
    std::vector<SceneData> objects;
    std::vector<std::string> objectNames;
    std::vector<InstanceData> instances;
    // The interval of the moving instances' keyframes; a ray's time is mapped into it.
    std::optional<std::pair<Float, Float>> motionTimes;
    int openObject = -1;
    bool committed = false;
    RayLog *rayLog = nullptr;
    // Stable addresses for Embree's user pointers.
    std::tuple<std::deque<Sphere>, std::deque<Cylinder>, std::deque<Disk>> quadrics;
    std::vector<std::shared_ptr<const TriangleMesh>> triangleMeshes;
    std::vector<std::shared_ptr<const BilinearPatchMesh>> patchMeshes;
    std::vector<std::shared_ptr<const CurveMesh>> curveMeshes;
    std::deque<CallbackData> callbackData;

    Impl() {
        device = rtcNewDevice(nullptr);
        if (!device)
            throw std::runtime_error(std::string("Embree: cannot create a device (") +
                                     ErrorName(rtcGetDeviceError(nullptr)) + ")");
        rtcSetDeviceErrorFunction(device, ReportEmbreeError, nullptr);
        world.scene = NewScene();
    }
    ~Impl() {
        for (SceneData &object : objects) rtcReleaseScene(object.scene);
        rtcReleaseScene(world.scene);
        rtcReleaseDevice(device);
    }
    Impl(const Impl &) = delete;
    Impl &operator=(const Impl &) = delete;

    // Embree's queries on the world, which Intersect, IntersectP and Traverse share.
    RTCRayHit ClosestHit(const Ray &ray, Float tMax) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh;
        rh.ray = ToEmbree(ray, tMax, EmbreeTime(ray.time));
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(world.scene, &context, &rh);
        return rh;
    }
    bool Occluded(const Ray &ray, Float tMax) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay r = ToEmbree(ray, tMax, EmbreeTime(ray.time));
        rtcOccluded1(world.scene, &context, &r);
        return r.tfar < 0;
    }

    // Robust traversal keeps triangle edges watertight, as pbrt-v4's intersection test is;
    // high build quality (spatial splits) pays back over the many rays of a render.
    RTCScene NewScene() const {
        RTCScene scene = rtcNewScene(device);
        rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        return scene;
    }

    SceneData &Current() { return openObject >= 0 ? objects[openObject] : world; }

    int Attach(RTCGeometry geom, GeometryRecord record) {
        rtcCommitGeometry(geom);
        SceneData &sd = Current();
        unsigned id = unsigned(sd.geometries.size());
        rtcAttachGeometryByID(sd.scene, geom, id);
        rtcReleaseGeometry(geom);
        if (openObject >= 0 && record.attrs.areaLightBase >= 0) {
            Warning("object \"%s\": area lights in instanced objects are not supported; the "
                    "emission is ignored",
                    objectNames[openObject].c_str());
            record.attrs.areaLightBase = -1;
        }
        sd.geometries.push_back(record);
        return int(id);
    }

    // Where geometry's callbacks find the shape and its alpha texture.
    void *NewCallbackData(const void *shape, const PrimitiveAttributes &attrs) {
        callbackData.push_back({shape, attrs.alpha.get()});
        return &callbackData.back();
    }

    template <typename Callbacks>
    int AddUserGeometry(GeometryKind kind, const void *shape, unsigned count,
                        PrimitiveAttributes attrs) {
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, count);
        rtcSetGeometryUserData(geom, NewCallbackData(shape, attrs));
        rtcSetGeometryBoundsFunction(geom, Callbacks::Bounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, Callbacks::Intersect);
        rtcSetGeometryOccludedFunction(geom, Callbacks::Occluded);
        return Attach(geom, {kind, shape, attrs});
    }

    template <typename Quadric>
    int AddQuadric(const Quadric &shape, PrimitiveAttributes attrs) {
        auto &copies = std::get<std::deque<Quadric>>(quadrics);
        copies.push_back(shape);
        return AddUserGeometry<QuadricCallbacks<Quadric>>(kQuadricKind<Quadric>, &copies.back(),
                                                          1, attrs);
    }

    void SetMotionTimes(const KeyframedTransform &t) {
        std::pair<Float, Float> times{t.StartTime(), t.EndTime()};
        if (motionTimes && *motionTimes != times)
            throw std::runtime_error("moving instances with different time intervals");
        motionTimes = times;
    }
    // The ray's time as Embree's fraction of the moving instances' interval, clamped to it as
    // pbrt-v4 clamps.
    Float EmbreeTime(Float time) const {
        return motionTimes ? TimeFraction(time, motionTimes->first, motionTimes->second) : 0;
    }

    // A hit inside an instance, described in the instance's space at the ray's time, then
    // carried to the world.
    SurfaceInteraction InstanceInteraction(const InstanceData &instance, const GeometryRecord &g,
                                           const RTCRayHit &rh, Vector3f wo,
                                           const Ray &ray) const {
        Transform worldFromInstance = instance.worldFromInstance.Interpolate(ray.time);
        Ray local = g.kind == GeometryKind::Curves ? worldFromInstance.ApplyInverse(ray) : ray;
        return TransformInteraction(worldFromInstance, Interaction(g, rh, wo, local));
    }

    // Only geometry with alpha pays for a filter call per candidate hit.
    void SetAlphaFilter(RTCGeometry geom, const void *shape, const PrimitiveAttributes &attrs,
                        RTCFilterFunctionN filter) {
        if (!attrs.alpha) return;
        if (!rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
            throw std::runtime_error("Embree was built without filter functions: alpha cut-outs "
                                     "on meshes and curves need them");
        rtcSetGeometryUserData(geom, NewCallbackData(shape, attrs));
        rtcSetGeometryIntersectFilterFunction(geom, filter);
        rtcSetGeometryOccludedFilterFunction(geom, filter);
    }

    void Check(const char *what) const {
        RTCError code = rtcGetDeviceError(device);
        if (code != RTC_ERROR_NONE)
            throw std::runtime_error(std::string("Embree: ") + what + " failed (" +
                                     ErrorName(code) + ")");
    }

    // A quadric's hit record holds its object-space point where the normal would be. An
    // interface (no material, not emissive) is only passed through, so its hit gets the point
    // and normals alone: on a sphere bounding a medium, most hits are such crossings.
    template <typename Quadric>
    static SurfaceInteraction FromQuadricRecord(const GeometryRecord &g, const RTCRayHit &rh,
                                                 Vector3f wo) {
        const Quadric &shape = *static_cast<const Quadric *>(g.shape);
        QuadricIntersection isect{rh.ray.tfar, Point3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z)};
        bool boundary = g.attrs.materialIndex < 0 && g.attrs.areaLightBase < 0;
        return boundary ? shape.BoundaryFromIntersection(isect, wo)
                        : shape.InteractionFromIntersection(isect, wo);
    }

    // localRay: the ray in the space of the geometry's scene (an instance's, or the world).
    SurfaceInteraction Interaction(const GeometryRecord &g, const RTCRayHit &rh, Vector3f wo,
                                   const Ray &localRay) const {
        const RTCHit &hit = rh.hit;
        switch (g.kind) {
        case GeometryKind::Curves:
            return CurveInteraction(*static_cast<const CurveMesh *>(g.shape), int(hit.primID),
                                    hit.u, localRay, rh.ray.tfar);
        case GeometryKind::Triangles:
            return Triangle::InteractionFromIntersection(
                static_cast<const TriangleMesh *>(g.shape), int(hit.primID), Barycentrics(hit),
                wo);
        case GeometryKind::BilinearPatches:
            return BilinearPatch::InteractionFromIntersection(
                static_cast<const BilinearPatchMesh *>(g.shape), int(hit.primID),
                Point2f(hit.u, hit.v), wo);
        case GeometryKind::Sphere:
            return FromQuadricRecord<Sphere>(g, rh, wo);
        case GeometryKind::Cylinder:
            return FromQuadricRecord<Cylinder>(g, rh, wo);
        case GeometryKind::Disk:
            return FromQuadricRecord<Disk>(g, rh, wo);
        case GeometryKind::Instance:
            break;
        }
        assert(false);
        return {};
    }
};

EmbreeAggregate::EmbreeAggregate() : impl(std::make_unique<Impl>()) {}
EmbreeAggregate::~EmbreeAggregate() = default;
EmbreeAggregate::EmbreeAggregate(EmbreeAggregate &&) noexcept = default;
EmbreeAggregate &EmbreeAggregate::operator=(EmbreeAggregate &&) noexcept = default;

int EmbreeAggregate::AddTriangleMesh(std::shared_ptr<const TriangleMesh> mesh,
                                     PrimitiveAttributes attrs) {
    RTCGeometry geom = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads vertex buffers with 16-byte loads past the last vertex; its own buffer has
    // the padding that a std::vector need not have. Indices are shared as they are.
    size_t nVertices = mesh->p.size();
    float *vertices = static_cast<float *>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nVertices));
    for (size_t i = 0; i < nVertices; ++i)
        for (int c = 0; c < 3; ++c) vertices[3 * i + c] = mesh->p[i][c];
    static_assert(sizeof(int) == sizeof(unsigned));
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               mesh->indices.data(), 0, 3 * sizeof(unsigned),
                               size_t(mesh->NumTriangles()));
    impl->SetAlphaFilter(geom, mesh.get(), attrs, TriangleAlphaFilter);
    impl->triangleMeshes.push_back(mesh);
    return impl->Attach(geom, {GeometryKind::Triangles, mesh.get(), attrs});
}

int EmbreeAggregate::AddBilinearPatchMesh(std::shared_ptr<const BilinearPatchMesh> mesh,
                                          PrimitiveAttributes attrs) {
    impl->patchMeshes.push_back(mesh);
    return impl->AddUserGeometry<PatchCallbacks>(GeometryKind::BilinearPatches, mesh.get(),
                                                 unsigned(mesh->NumPatches()), attrs);
}

int EmbreeAggregate::AddCurves(std::shared_ptr<const CurveMesh> curves,
                               PrimitiveAttributes attrs) {
    static constexpr RTCGeometryType kTypes[] = {RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE,
                                                 RTC_GEOMETRY_TYPE_ROUND_BEZIER_CURVE,
                                                 RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE};
    RTCGeometry geom = rtcNewGeometry(impl->device, kTypes[int(curves->type)]);
    int n = curves->NumSegments();
    // Each segment's own four control points, with radii that make its width linear in u.
    float *vertices = static_cast<float *>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 4 * size_t(n)));
    unsigned *index = static_cast<unsigned *>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), size_t(n)));
    for (int s = 0; s < n; ++s) {
        index[s] = unsigned(4 * s);
        for (int i = 0; i < 4; ++i) {
            Point3f p = curves->cp[4 * s + i];
            float *v = &vertices[4 * (4 * s + i)];
            v[0] = p.x;
            v[1] = p.y;
            v[2] = p.z;
            v[3] = Lerp(i / 3.f, curves->width[2 * s], curves->width[2 * s + 1]) / 2;
        }
    }
    if (curves->type == CurveType::Ribbon) {
        float *normals = static_cast<float *>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * size_t(n)));
        for (int s = 0; s < n; ++s)
            for (int i = 0; i < 4; ++i) {
                // Evenly spaced on the chord, so that the normal spline is the linear
                // interpolation of the end normals, whose direction is their nlerp.
                Vector3f n0(curves->n[2 * s]), n1(curves->n[2 * s + 1]);
                Vector3f nv = (1 - i / 3.f) * n0 + (i / 3.f) * n1;
                for (int c = 0; c < 3; ++c)
                    normals[3 * (4 * s + i) + c] = nv[c];
            }
    }
    rtcSetGeometryTessellationRate(geom, FlatCurveTessellation(*curves));
    impl->SetAlphaFilter(geom, curves.get(), attrs, CurveAlphaFilter);
    impl->curveMeshes.push_back(curves);
    attrs.areaLightBase = -1;
    return impl->Attach(geom, {GeometryKind::Curves, curves.get(), attrs});
}

int EmbreeAggregate::AddSphere(const Sphere &sphere, PrimitiveAttributes attrs) {
    return impl->AddQuadric(sphere, std::move(attrs));
}

int EmbreeAggregate::AddCylinder(const Cylinder &cylinder, PrimitiveAttributes attrs) {
    return impl->AddQuadric(cylinder, std::move(attrs));
}

int EmbreeAggregate::AddDisk(const Disk &disk, PrimitiveAttributes attrs) {
    return impl->AddQuadric(disk, std::move(attrs));
}

int EmbreeAggregate::BeginObject(const std::string &name) {
    if (impl->openObject >= 0)
        throw std::runtime_error("object \"" + name + "\" begins inside object \"" +
                                 impl->objectNames[impl->openObject] + "\"");
    impl->objects.push_back({impl->NewScene(), {}});
    impl->objectNames.push_back(name);
    impl->openObject = int(impl->objects.size()) - 1;
    return impl->openObject;
}

void EmbreeAggregate::EndObject() {
    if (impl->openObject < 0)
        throw std::runtime_error("object end without a matching begin");
    rtcCommitScene(impl->objects[impl->openObject].scene);
    impl->Check("building an object");
    impl->openObject = -1;
}

int EmbreeAggregate::AddInstance(int objectId, const Transform &worldFromInstance) {
    return AddInstance(objectId, KeyframedTransform(AnimatedTransform(worldFromInstance)));
}

int EmbreeAggregate::AddInstance(int objectId, const AnimatedTransform &worldFromInstance) {
    return AddInstance(objectId, KeyframedTransform(worldFromInstance));
}

int EmbreeAggregate::AddInstance(int objectId, const KeyframedTransform &worldFromInstance) {
    if (objectId < 0 || objectId >= int(impl->objects.size()))
        throw std::runtime_error("instance of unknown object " + std::to_string(objectId));
    if (objectId == impl->openObject)
        throw std::runtime_error("instance of object \"" + impl->objectNames[objectId] +
                                 "\" before its end");
    if (impl->openObject >= 0)
        throw std::runtime_error("instance inside object \"" +
                                 impl->objectNames[impl->openObject] +
                                 "\": objects do not nest");
    if (worldFromInstance.IsAnimated())
        impl->SetMotionTimes(worldFromInstance);  // may throw: before Embree owns anything
    RTCGeometry geom = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geom, impl->objects[objectId].scene);
    if (worldFromInstance.IsAnimated()) {
        unsigned keyframes = unsigned(worldFromInstance.StepCount()) + 1;
        rtcSetGeometryTimeStepCount(geom, keyframes);
        for (unsigned k = 0; k < keyframes; ++k) {
            RTCQuaternionDecomposition q = ToEmbree(worldFromInstance.Keyframe(int(k)));
            rtcSetGeometryTransformQuaternion(geom, k, &q);
        }
    } else {
        const SquareMatrix<4> &m = worldFromInstance.Start().GetMatrix();
        float xfm[12];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) xfm[4 * r + c] = m[r][c];
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, xfm);
    }
    impl->instances.push_back({objectId, worldFromInstance});
    GeometryRecord record{GeometryKind::Instance, nullptr, {}, int(impl->instances.size()) - 1};
    return impl->Attach(geom, record);
}

void EmbreeAggregate::Commit() {
    if (impl->openObject >= 0)
        throw std::runtime_error("object \"" + impl->objectNames[impl->openObject] +
                                 "\" has no end");
    rtcCommitScene(impl->world.scene);
    impl->Check("building the scene");
    impl->committed = true;
}

pstd::optional<ShapeIntersection> EmbreeAggregate::Intersect(const Ray &ray, Float tMax) const {
    assert(impl->committed);
    if (impl->rayLog)
        impl->rayLog->Add(ray, tMax, false);
    RTCRayHit rh = impl->ClosestHit(ray, tMax);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return {};

    const SceneData *scene = &impl->world;
    const InstanceData *instance = nullptr;
    if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
        const GeometryRecord &inst = impl->world.geometries[rh.hit.instID[0]];
        instance = &impl->instances[inst.instanceIndex];
        scene = &impl->objects[instance->objectId];
    }
    const GeometryRecord &g = scene->geometries[rh.hit.geomID];
    Vector3f wo = -Normalize(ray.d);
    SurfaceInteraction si = instance ? impl->InstanceInteraction(*instance, g, rh, wo, ray)
                                     : impl->Interaction(g, rh, wo, ray);
    si.wo = wo;
    si.time = ray.time;
    si.materialIndex = g.attrs.materialIndex;
    si.mediumInterface = g.attrs.mediumInterface.IsMediumTransition()
                             ? g.attrs.mediumInterface
                             : MediumInterface(ray.medium);
    if (g.attrs.areaLightBase >= 0) {
        bool isMesh = g.kind == GeometryKind::Triangles || g.kind == GeometryKind::BilinearPatches;
        si.areaLightIndex = g.attrs.areaLightBase + (isMesh ? int(rh.hit.primID) : 0);
    }
    return ShapeIntersection{si, rh.ray.tfar};
}

bool EmbreeAggregate::IntersectP(const Ray &ray, Float tMax) const {
    assert(impl->committed);
    if (impl->rayLog)
        impl->rayLog->Add(ray, tMax, true);
    return impl->Occluded(ray, tMax);
}

void EmbreeAggregate::SetRayLog(RayLog *log) { impl->rayLog = log; }

bool EmbreeAggregate::Traverse(const LoggedRay &logged) const {
    assert(impl->committed);
    if (logged.shadow)
        return impl->Occluded(logged.ray, logged.tMax);
    return impl->ClosestHit(logged.ray, logged.tMax).hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

bool EmbreeAggregate::HasMotion() const { return impl->motionTimes.has_value(); }

Bounds3f EmbreeAggregate::WorldBound() const {
    if (!impl->committed || impl->world.geometries.empty())
        return Bounds3f();
    RTCBounds b;
    rtcGetSceneBounds(impl->world.scene, &b);
    return Bounds3f(Point3f(b.lower_x, b.lower_y, b.lower_z),
                    Point3f(b.upper_x, b.upper_y, b.upper_z));
}

}  // namespace pbrt
