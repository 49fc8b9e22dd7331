// The scene's ray-intersection acceleration structure, on Embree 3 (in the place of pbrt-v4's
// BVHAggregate and its primitives: GeometricPrimitive, TransformedPrimitive).
//
// Triangle meshes are Embree's native triangles; spheres, cylinders, disks and bilinear patches are Embree
// user geometry that calls the shapes' own intersection routines; object instances are Embree
// instances of a shared sub-scene. Every geometry carries PrimitiveAttributes, which Intersect
// copies into the SurfaceInteraction, and may carry an alpha texture that cuts the surface out
// (pbrt-v4's "alpha" shape parameter; see PrimitiveAttributes::alpha). Build the aggregate on one thread (Add..., then Commit);
// Intersect and IntersectP may then be called from any number of threads.
//
// Performance: Embree wants denormals flushed to zero; each rendering thread should set
// _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON) and _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON).
#pragma once

#include "pbrt_ext/base/medium.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/shapes/curves.h"
#include "pbrt_ext/shapes/raylog.h"
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/textures/textures.h"
#include "pbrt_ext/util/animatedtransform.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/transform.h"

#include <memory>
#include <string>

namespace pbrt {

struct PrimitiveAttributes {
    PrimitiveAttributes(int materialIndex = -1, int areaLightBase = -1,
                        std::shared_ptr<const FloatTexture> alpha = nullptr,
                        MediumInterface mediumInterface = {})
        : materialIndex(materialIndex), areaLightBase(areaLightBase), alpha(std::move(alpha)),
          mediumInterface(mediumInterface) {}

    int materialIndex = -1;
    // The area light of the geometry's first primitive: primitive i of a mesh emits as light
    // areaLightBase + i. -1: not emissive. Ignored (with a warning) inside an object, since
    // every instance would share one light, as pbrt-v4 also refuses.
    int areaLightBase = -1;
    // pbrt-v4's alpha test, for closest-hit and shadow rays alike: a hit where alpha(p, n, uv)
    // = a < 1 is kept with probability a, decided by a hash of the ray and the hit distance, so
    // that the same query always gives the same answer. Null: opaque, and no cost at all.
    std::shared_ptr<const FloatTexture> alpha = nullptr;
    // The media inside and outside the shape; used only where they differ (a boundary).
    MediumInterface mediumInterface;
};

class EmbreeAggregate {
  public:
    // Creates the Embree device; throws std::runtime_error if Embree cannot start.
    EmbreeAggregate();
    ~EmbreeAggregate();
    EmbreeAggregate(const EmbreeAggregate &) = delete;
    EmbreeAggregate &operator=(const EmbreeAggregate &) = delete;
    EmbreeAggregate(EmbreeAggregate &&) noexcept;
    EmbreeAggregate &operator=(EmbreeAggregate &&) noexcept;

    // Geometry goes into the world, or into the object opened by BeginObject. The aggregate
    // shares ownership of meshes and copies quadrics. Each returns the geometry's id
    // within its scene (the world or the object).
    int AddTriangleMesh(std::shared_ptr<const TriangleMesh> mesh, PrimitiveAttributes attrs);
    int AddBilinearPatchMesh(std::shared_ptr<const BilinearPatchMesh> mesh,
                             PrimitiveAttributes attrs);
    // Curves are Embree's curve primitives (curves.h); their attributes carry no area light.
    int AddCurves(std::shared_ptr<const CurveMesh> curves, PrimitiveAttributes attrs);
    int AddSphere(const Sphere &sphere, PrimitiveAttributes attrs);
    int AddCylinder(const Cylinder &cylinder, PrimitiveAttributes attrs);
    int AddDisk(const Disk &disk, PrimitiveAttributes attrs);

    // Object instancing (pbrt-v4's ObjectBegin/ObjectEnd/ObjectInstance): geometry added between
    // BeginObject and EndObject forms an object, returned as an id; AddInstance places it in the
    // world. Objects do not nest; an instance may only refer to an ended object. Both throw
    // std::runtime_error when misused.
    int BeginObject(const std::string &name);
    void EndObject();
    int AddInstance(int objectId, const Transform &worldFromInstance);
    // A moving instance: Embree's instance motion blur between the two keyframes, a ray at
    // ray.time meeting the object where it is then. Every moving instance of an aggregate
    // shares one time interval (TransformTimes); another one throws std::runtime_error.
    int AddInstance(int objectId, const AnimatedTransform &worldFromInstance);
    // The same through every keyframe, each a time step of Embree's.
    int AddInstance(int objectId, const KeyframedTransform &worldFromInstance);
    // Whether some instance moves.
    bool HasMotion() const;

    // Builds the acceleration structures; throws std::runtime_error if Embree reports an error.
    void Commit();

    // The closest hit with 0 < t < tMax, with materialIndex and areaLightIndex filled in.
    pstd::optional<ShapeIntersection> Intersect(const Ray &ray, Float tMax = Infinity) const;
    // Whether anything lies along the ray with 0 < t < tMax.
    bool IntersectP(const Ray &ray, Float tMax = Infinity) const;
    Bounds3f WorldBound() const;

    // For the traversal-limit benchmark. While a log is attached (null detaches), Intersect and
    // IntersectP record each query in it; unattached, they pay one test of a pointer.
    void SetRayLog(RayLog *log);
    // Embree's traversal alone: rtcIntersect1 (or rtcOccluded1 for a shadow ray), with the
    // geometry's own intersection and alpha callbacks but without building the interaction.
    // Returns whether the ray hit something.
    bool Traverse(const LoggedRay &ray) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl;
};

}  // namespace pbrt
