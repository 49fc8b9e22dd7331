// Shapes: triangles, spheres, cylinders, disks and bilinear patches (pbrt-v4's src/pbrt/shapes.h,
// reduced: no curves, no time, no ray differentials, no rounding-error intervals).
//
// Conventions, as in pbrt-v4:
//   - Render space = world space. Mesh vertices are stored in world space; spheres and disks keep
//     their worldFromObject transform and intersect in object space.
//   - The geometric normal n is Normalize(Cross(dpdu, dpdv)) (triangles: the winding's normal),
//     flipped when reverseOrientation ^ transformSwapsHandedness; with per-vertex normals the
//     shading normal is authoritative and n is turned to its side.
//   - Sample(u) returns a point with an area density; Sample(ctx, u) and PDF(ctx, wi) work with a
//     density per unit solid angle as seen from ctx.p. PDF intersects the shape along wi and is 0
//     where the ray misses it.
//   - Failure (a degenerate configuration) is an empty optional, never NaN or Inf.
// Host code: meshes own std::vectors. The Embree aggregate (aggregate.h) intersects meshes from
// their flat arrays; these classes serve area lights, user geometry and tests.
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

#include <array>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace pbrt {

// The point a shape is sampled from (pbrt-v4's ShapeSampleContext): n and ns are zero for a point
// in free space, otherwise rays leave it offset along n.
using ShapeSampleContext = LightSampleContext;

struct ShapeIntersection {
    SurfaceInteraction intr;
    Float tHit;
};

// A point sampled on a shape: its position, the normal its intersections would have there, and
// its (u, v). Three fields rather than pbrt-v4's whole Interaction: every light sample built and
// copied a SurfaceInteraction of 60 floats, 40 % of Triangle::SampleAt's time.
struct ShapeSamplePoint {
    Point3f p;
    Normal3f n;
    Point2f uv;
};

struct ShapeSample {
    ShapeSamplePoint intr;
    Float pdf;
};

// Triangles in world space. indices holds 3 per triangle; n, uv and s are empty or hold one entry
// per vertex. n is in world space and already negated when reverseOrientation is set (as pbrt-v4's
// TriangleMesh stores it); MakeTriangleMesh does both. s: per-vertex shading tangents (pbrt-v4's
// "S"), which the shading frame's dp/du follows instead of the uv mapping's.
struct TriangleMesh {
    std::vector<Point3f> p;
    std::vector<int> indices;
    std::vector<Normal3f> n;
    std::vector<Point2f> uv;
    std::vector<Vector3f> s;
    bool reverseOrientation = false, transformSwapsHandedness = false;

    int NumTriangles() const { return int(indices.size() / 3); }
    std::string ToString() const;
};

// Bilinear patches in world space: indices holds 4 per patch, in pbrt-v4's order p00, p10, p01,
// p11 (the patch is Lerp(u, Lerp(v, p00, p01), Lerp(v, p10, p11))). n and uv as for TriangleMesh.
struct BilinearPatchMesh {
    std::vector<Point3f> p;
    std::vector<int> indices;
    std::vector<Normal3f> n;
    std::vector<Point2f> uv;
    bool reverseOrientation = false, transformSwapsHandedness = false;
    // pbrt-v4's "emissionfilename": the patches' (u, v) are sampled in proportion to this
    // distribution (an emission image's, t flipped as the area light reads it) instead of by area.
    std::shared_ptr<const PiecewiseConstant2D> imageDistribution;

    int NumPatches() const { return int(indices.size() / 4); }
    std::string ToString() const;
};

// Meshes from object-space data: positions and normals go to world space, normals are negated for
// reverseOrientation. Throws std::runtime_error for an index out of range, an index count that is
// not a multiple of 3 (4), or n/uv sizes that differ from the vertex count.
TriangleMesh MakeTriangleMesh(const Transform &worldFromObject, bool reverseOrientation,
                              std::vector<int> indices, std::vector<Point3f> p,
                              std::vector<Normal3f> n = {}, std::vector<Point2f> uv = {},
                              std::vector<Vector3f> s = {});
BilinearPatchMesh MakeBilinearPatchMesh(const Transform &worldFromObject, bool reverseOrientation,
                                        std::vector<int> indices, std::vector<Point3f> p,
                                        std::vector<Normal3f> n = {}, std::vector<Point2f> uv = {});

// pbrt-v4's Transform::operator()(SurfaceInteraction): positions, tangents and normals mapped by
// t, normals renormalized, shading.n kept on n's side.
SurfaceInteraction TransformInteraction(const Transform &t, const SurfaceInteraction &si);

class Triangle {
  public:
    Triangle(const TriangleMesh *mesh, int triIndex);

    Bounds3f Bounds() const;
    Float Area() const { return area; }
    pstd::optional<ShapeIntersection> Intersect(const Ray &ray, Float tMax = Infinity) const;
    bool IntersectP(const Ray &ray, Float tMax = Infinity) const;
    pstd::optional<ShapeSample> Sample(Point2f u) const;
    pstd::optional<ShapeSample> Sample(const ShapeSampleContext &ctx, Point2f u) const;
    Float PDF(const ShapeSampleContext &ctx, Vector3f wi) const;
    Float PDF(Point3f, Point2f) const { return 1 / Area(); }
    std::string ToString() const;

    // The full interaction at barycentrics b (p = b0 p0 + b1 p1 + b2 p2), seen from direction wo
    // (unit, toward the viewer). Shared by Intersect and the Embree aggregate's triangle hits.
    static SurfaceInteraction InteractionFromIntersection(const TriangleMesh *mesh, int triIndex,
                                                          std::array<Float, 3> b, Vector3f wo);

  private:
    pstd::optional<ShapeSample> SampleAt(std::array<Float, 3> b, Float pdf) const;
    bool SampledByAreaFrom(Point3f p) const;

    const TriangleMesh *mesh;
    int triIndex;
    // What sampling the triangle as an emitter asks for at every shading point, computed once:
    // only emitters and tests make Triangle objects (the aggregate's hits go to
    // InteractionFromIntersection).
    Float area;
    Normal3f unitNormal;  // the winding's, before any orientation
    Point3f centroid;
    Float radius2;  // the largest squared distance from the centroid to a vertex
};

// Where a ray meets a sphere or disk, in the shape's object space: what Intersect needs to build
// the interaction, small enough to travel through an Embree hit record.
struct QuadricIntersection {
    Float tHit;
    Point3f pObj;
};

// A quadric's dp/du and dp/dv at an object-space point; their cross product is its normal.
struct QuadricTangents {
    Vector3f dpdu, dpdv;
};

// A sphere of the given radius around the object-space origin, clipped to z in [zMin, zMax] and
// azimuth in [0, phiMax] (degrees).
class Sphere {
  public:
    Sphere(const Transform &worldFromObject, bool reverseOrientation, Float radius, Float zMin,
           Float zMax, Float phiMaxDegrees);

    Float Area() const;
    pstd::optional<QuadricIntersection> BasicIntersect(const Ray &ray, Float tMax) const;
    SurfaceInteraction InteractionFromIntersection(const QuadricIntersection &isect,
                                                   Vector3f wo) const;
    // The same hit's p and normals only, bit for bit, for a surface that only bounds media.
    SurfaceInteraction BoundaryFromIntersection(const QuadricIntersection &isect,
                                                Vector3f wo) const;
    pstd::optional<ShapeIntersection> Intersect(const Ray &ray, Float tMax = Infinity) const;
    bool IntersectP(const Ray &ray, Float tMax = Infinity) const;
    pstd::optional<ShapeSample> Sample(Point2f u) const;
    // Outside the sphere: uniform over the cone of directions that can see it (pbrt-v4).
    pstd::optional<ShapeSample> Sample(const ShapeSampleContext &ctx, Point2f u) const;
    Float PDF(const ShapeSampleContext &ctx, Vector3f wi) const;
    std::string ToString() const;
    Float PDF(Point3f p, Point2f) const { return AreaPDF(objectFromWorld(p)); }

    Bounds3f Bounds() const;

  private:
    bool FlipNormal() const { return reverseOrientation ^ transformSwapsHandedness; }
    QuadricTangents Tangents(Point3f pObj) const;
    Point2f UV(Point3f pObj) const;
    // How the transform scales area at pObj; the area density of uniform object-space
    // sampling there, per unit world-space area.
    Float AreaScale(Point3f pObj) const;
    Float AreaPDF(Point3f pObj) const;

    Transform worldFromObject, objectFromWorld;
    bool reverseOrientation, transformSwapsHandedness;
    Float radius, zMin, zMax, thetaZMin, thetaZMax, phiMax;
    Float absDet, objectArea, worldArea;
    // Cone sampling needs the whole sphere, round in world space (no shear or uneven scale).
    bool sampleCone;
    Float worldRadius;
};

// The side of a cylinder of the given radius about the object-space z axis, from zMin to zMax,
// with azimuth in [0, phiMax] (degrees); open at both ends, as pbrt-v4's.
class Cylinder {
  public:
    Cylinder(const Transform &worldFromObject, bool reverseOrientation, Float radius, Float zMin,
             Float zMax, Float phiMaxDegrees);

    Float Area() const { return worldArea; }
    pstd::optional<QuadricIntersection> BasicIntersect(const Ray &ray, Float tMax) const;
    SurfaceInteraction InteractionFromIntersection(const QuadricIntersection &isect,
                                                   Vector3f wo) const;
    // The same hit's p and normals only, bit for bit, for a surface that only bounds media.
    SurfaceInteraction BoundaryFromIntersection(const QuadricIntersection &isect,
                                                Vector3f wo) const;
    pstd::optional<ShapeIntersection> Intersect(const Ray &ray, Float tMax = Infinity) const;
    bool IntersectP(const Ray &ray, Float tMax = Infinity) const;
    // Uniform in z and phi: uniform in area in object space; AreaPDF accounts for the transform.
    pstd::optional<ShapeSample> Sample(Point2f u) const;
    pstd::optional<ShapeSample> Sample(const ShapeSampleContext &ctx, Point2f u) const;
    Float PDF(const ShapeSampleContext &ctx, Vector3f wi) const;
    std::string ToString() const;
    Float PDF(Point3f p, Point2f) const { return AreaPDF(objectFromWorld(p)); }

    Bounds3f Bounds() const;

  private:
    bool FlipNormal() const { return reverseOrientation ^ transformSwapsHandedness; }
    QuadricTangents Tangents(Point3f pObj) const;
    Point2f UV(Point3f pObj) const;
    Float AreaPDF(Point3f pObj) const;

    Transform worldFromObject, objectFromWorld;
    bool reverseOrientation, transformSwapsHandedness;
    Float radius, zMin, zMax, phiMax;
    Float absDet, objectArea, worldArea;
};

// An annulus (innerRadius..radius) at z = height in object space, with azimuth in [0, phiMax]
// (degrees); its normal is +z.
class Disk {
  public:
    Disk(const Transform &worldFromObject, bool reverseOrientation, Float height, Float radius,
         Float innerRadius, Float phiMaxDegrees);

    Float Area() const;
    pstd::optional<QuadricIntersection> BasicIntersect(const Ray &ray, Float tMax) const;
    SurfaceInteraction InteractionFromIntersection(const QuadricIntersection &isect,
                                                   Vector3f wo) const;
    // The same hit's p and normals only, bit for bit, for a surface that only bounds media.
    SurfaceInteraction BoundaryFromIntersection(const QuadricIntersection &isect,
                                                Vector3f wo) const;
    pstd::optional<ShapeIntersection> Intersect(const Ray &ray, Float tMax = Infinity) const;
    bool IntersectP(const Ray &ray, Float tMax = Infinity) const;
    pstd::optional<ShapeSample> Sample(Point2f u) const;
    pstd::optional<ShapeSample> Sample(const ShapeSampleContext &ctx, Point2f u) const;
    Float PDF(const ShapeSampleContext &ctx, Vector3f wi) const;
    std::string ToString() const;
    Float PDF(Point3f, Point2f) const { return 1 / Area(); }

    Bounds3f Bounds() const;

  private:
    bool FlipNormal() const { return reverseOrientation ^ transformSwapsHandedness; }
    QuadricTangents Tangents(Point3f pObj) const;
    Point2f UV(Point3f pObj) const;

    Transform worldFromObject, objectFromWorld;
    bool reverseOrientation, transformSwapsHandedness;
    Float height, radius, innerRadius, phiMax;
    Float worldArea;  // the transform may scale the disk
};

// Where a ray meets a bilinear patch: the patch parameters (u, v) and the ray parameter.
struct BilinearIntersection {
    Point2f uv;
    Float t;
};

// Reshetov's ray/bilinear-patch intersection ("Cool Patches", Ray Tracing Gems, 2019), as in
// pbrt-v4: the nearest hit with 0 < t < tMax and (u, v) in [0, 1]^2.
pstd::optional<BilinearIntersection> IntersectBilinearPatch(const Ray &ray, Float tMax,
                                                            Point3f p00, Point3f p10,
                                                            Point3f p01, Point3f p11);

class SphericalRectangle;  // util/sphericalsampling.h

class BilinearPatch {
  public:
    BilinearPatch(const BilinearPatchMesh *mesh, int patchIndex);

    Bounds3f Bounds() const;
    Float Area() const { return area; }
    pstd::optional<ShapeIntersection> Intersect(const Ray &ray, Float tMax = Infinity) const;
    bool IntersectP(const Ray &ray, Float tMax = Infinity) const;
    // By area: rectangles uniformly in (u, v), other patches by a bilinear warp whose corner
    // weights follow the area element; from a point, rectangles by solid angle. As pbrt-v4.
    pstd::optional<ShapeSample> Sample(Point2f u) const;
    pstd::optional<ShapeSample> Sample(const ShapeSampleContext &ctx, Point2f u) const;
    Float PDF(const ShapeSampleContext &ctx, Vector3f wi) const;
    Float PDF(Point3f, Point2f uv) const { return AreaPDF(uv); }
    std::string ToString() const;

    // The full interaction at patch parameters uv; shared with the Embree aggregate.
    static SurfaceInteraction InteractionFromIntersection(const BilinearPatchMesh *mesh,
                                                          int patchIndex, Point2f uv,
                                                          Vector3f wo);

  private:
    std::array<Point3f, 4> Corners() const;
    // Area density of the (u, v) sampling at uv, per unit area of the surface.
    Float AreaPDF(Point2f uv) const;
    pstd::optional<ShapeSample> SampleAt(Point2f uv) const;
    pstd::optional<SphericalRectangle> SphericalFrom(Point3f p) const;
    std::array<Float, 4> CosineWarp(const ShapeSampleContext &ctx) const;

    const BilinearPatchMesh *mesh;
    int patchIndex;
    bool isRectangle;
    Float area;
};

// Closed dispatch over the shape kinds (pbrt-v4's Shape, reduced to what area lights and tests
// use). Meshes must outlive the triangles and patches that point into them.
class Shape {
  public:
    template <typename T>
        requires(!std::is_same_v<std::decay_t<T>, Shape>)
    Shape(T shape) : shape(std::move(shape)) {}

    Bounds3f Bounds() const {
        return std::visit([](const auto &s) { return s.Bounds(); }, shape);
    }
    Float Area() const {
        return std::visit([](const auto &s) { return s.Area(); }, shape);
    }
    pstd::optional<ShapeIntersection> Intersect(const Ray &ray, Float tMax = Infinity) const {
        return std::visit([&](const auto &s) { return s.Intersect(ray, tMax); }, shape);
    }
    bool IntersectP(const Ray &ray, Float tMax = Infinity) const {
        return std::visit([&](const auto &s) { return s.IntersectP(ray, tMax); }, shape);
    }
    pstd::optional<ShapeSample> Sample(Point2f u) const {
        return std::visit([&](const auto &s) { return s.Sample(u); }, shape);
    }
    pstd::optional<ShapeSample> Sample(const ShapeSampleContext &ctx, Point2f u) const {
        return std::visit([&](const auto &s) { return s.Sample(ctx, u); }, shape);
    }
    Float PDF(const ShapeSampleContext &ctx, Vector3f wi) const {
        return std::visit([&](const auto &s) { return s.PDF(ctx, wi); }, shape);
    }
    // The area density with which Sample(u) draws the surface point p whose parameters are uv.
    Float PDF(Point3f p, Point2f uv) const {
        return std::visit([&](const auto &s) { return s.PDF(p, uv); }, shape);
    }
    std::string ToString() const {
        return std::visit([](const auto &s) { return s.ToString(); }, shape);
    }

    template <typename T>
    const T *CastOrNullptr() const {
        return std::get_if<T>(&shape);
    }

  private:
    std::variant<Triangle, Sphere, Cylinder, Disk, BilinearPatch> shape;
};

}  // namespace pbrt
