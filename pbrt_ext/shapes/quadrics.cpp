// Quadrics (pbrt-v4's Sphere, Cylinder and Disk). Where this differs from pbrt-v4, and why:
//   - Partial spheres and disks (zMin/zMax/phiMax, innerRadius) are sampled over the part that
//     exists, and area densities account for a scaling transform (Nanson's formula), so that
//     Sample and PDF agree with Intersect; pbrt-v4 samples the whole shape in object units
//     (its cylinder too, whose pdf is 1/Area in object units even under a scaling transform).
//   - Samples orient n exactly as their intersections do (reverseOrientation ^
//     transformSwapsHandedness); pbrt-v4's samples use reverseOrientation alone, which disagrees
//     with its own intersections under a mirroring transform.
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/shapes/shapes_internal.h"

#include "pbrt_ext/util/sampling.h"

#include <algorithm>
#include <array>
#include <cstdio>

namespace pbrt {

using namespace shapedetail;

namespace {

// The roots t0 <= t1 of |o + t d|^2 = radius^2 over the first N coordinates (3: a sphere about
// the origin; 2: a cylinder about z), in double. The discriminant is written as
// 4 (a r^2 - |o x d|^2), |o x d|^2 / a the squared distance from the centre or axis to the ray's
// line: the products of single-precision coordinates are exact in double, so there is no
// cancellation for rays far from the quadric (pbrt-v4 6.8.3 gets the same from
// 4a (r + l)(r - l), with a division and a square root more on the way to the roots). None where
// the line misses it, or has no direction in those coordinates.
template <int N>
pstd::optional<std::array<double, 2>> CenteredQuadraticRoots(Point3f o, Vector3f d,
                                                             Float radius) {
    double a = 0, b = 0, c = 0;
    for (int i = 0; i < N; ++i) {
        a += double(d[i]) * d[i];
        b += 2 * double(d[i]) * o[i];
        c += double(o[i]) * o[i];
    }
    double r2 = double(radius) * radius;
    c -= r2;
    if (a == 0)
        return {};
    double cross2 = Sqr(double(o.x) * d.y - double(o.y) * d.x);
    if constexpr (N == 3)
        cross2 += Sqr(double(o.y) * d.z - double(o.z) * d.y) + Sqr(double(o.z) * d.x - double(o.x) * d.z);
    double discrim = 4 * (a * r2 - cross2);
    if (discrim < 0)
        return {};
    double rootDiscrim = std::sqrt(discrim);
    double q = (b < 0) ? -0.5 * (b - rootDiscrim) : -0.5 * (b + rootDiscrim);
    if (q == 0)
        return {};
    double t0 = q / a, t1 = c / q;
    return std::array<double, 2>{std::min(t0, t1), std::max(t0, t1)};
}

Point3f PointAt(Point3f o, Vector3f d, double t) {
    return Point3f(Float(o.x + t * d.x), Float(o.y + t * d.y), Float(o.z + t * d.z));
}

// A quadric's full intersection from its BasicIntersect.
template <typename Quadric>
pstd::optional<ShapeIntersection> IntersectQuadric(const Quadric &q, const Ray &ray, Float tMax) {
    pstd::optional<QuadricIntersection> isect = q.BasicIntersect(ray, tMax);
    if (!isect)
        return {};
    return ShapeIntersection{q.InteractionFromIntersection(*isect, -Normalize(ray.d)),
                             isect->tHit};
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Sphere

Sphere::Sphere(const Transform &worldFromObject, bool reverseOrientation, Float radius,
               Float z0, Float z1, Float phiMaxDegrees)
    : worldFromObject(worldFromObject),
      objectFromWorld(Inverse(worldFromObject)),
      reverseOrientation(reverseOrientation),
      transformSwapsHandedness(worldFromObject.SwapsHandedness()),
      radius(radius),
      zMin(Clamp(std::min(z0, z1), -radius, radius)),
      zMax(Clamp(std::max(z0, z1), -radius, radius)),
      thetaZMin(std::acos(Clamp(std::min(z0, z1) / radius, -1, 1))),
      thetaZMax(std::acos(Clamp(std::max(z0, z1) / radius, -1, 1))),
      phiMax(Radians(Clamp(phiMaxDegrees, 0, 360))) {
    absDet = AbsDeterminant(worldFromObject);
    objectArea = phiMax * radius * (zMax - zMin);
    // The object-space area element is radius dz dphi; the transform scales it pointwise.
    worldArea = objectArea * Float(IntegrateUnitSquare([&](Float s, Float t) {
                    Float z = Lerp(s, zMin, zMax), phi = t * phiMax;
                    Float r = SafeSqrt(Sqr(radius) - Sqr(z));
                    return AreaScale(Point3f(r * std::cos(phi), r * std::sin(phi), z));
                }));

    Vector3f ax = worldFromObject(Vector3f(1, 0, 0)), ay = worldFromObject(Vector3f(0, 1, 0)),
             az = worldFromObject(Vector3f(0, 0, 1));
    Float l = Length(ax), tol = 1e-4f * Sqr(l);
    bool similarity = std::abs(LengthSquared(ay) - Sqr(l)) <= tol &&
                      std::abs(LengthSquared(az) - Sqr(l)) <= tol &&
                      std::abs(Dot(ax, ay)) <= tol && std::abs(Dot(ax, az)) <= tol &&
                      std::abs(Dot(ay, az)) <= tol;
    bool whole = zMin <= -radius && zMax >= radius && phiMax >= 2 * Pi;
    sampleCone = similarity && whole;
    worldRadius = radius * l;
}

Bounds3f Sphere::Bounds() const {
    return worldFromObject(Bounds3f(Point3f(-radius, -radius, zMin), Point3f(radius, radius, zMax)));
}

Float Sphere::Area() const {
    return worldArea;
}

Float Sphere::AreaScale(Point3f pObj) const {
    return shapedetail::AreaScale(worldFromObject, absDet,
                                  Normal3f(pObj.x / radius, pObj.y / radius, pObj.z / radius));
}

Float Sphere::AreaPDF(Point3f pObj) const {
    return 1 / (objectArea * AreaScale(pObj));
}

Point2f Sphere::UV(Point3f pObj) const {
    Float theta = SafeACos(pObj.z / radius);
    return Point2f(Azimuth(pObj.x, pObj.y) / phiMax, (theta - thetaZMin) / (thetaZMax - thetaZMin));
}

pstd::optional<QuadricIntersection> Sphere::BasicIntersect(const Ray &r, Float tMax) const {
    Point3f oi = objectFromWorld(r.o);
    Vector3f di = objectFromWorld(r.d);
    pstd::optional<std::array<double, 2>> roots = CenteredQuadraticRoots<3>(oi, di, radius);
    if (!roots)
        return {};
    // The nearer root first; the farther one when clipping removes the nearer.
    for (double t : *roots) {
        if (t <= 0)
            continue;
        if (!(t < tMax))
            return {};
        Point3f pHit = PointAt(oi, di, t);
        pHit *= radius / Length(Vector3f(pHit));
        if (pHit.x == 0 && pHit.y == 0)
            pHit.x = 1e-5f * radius;  // keeps phi and dp/du defined at the poles
        bool clipped = (zMin > -radius && pHit.z < zMin) || (zMax < radius && pHit.z > zMax) ||
                       PastAzimuth(pHit, phiMax);
        if (!clipped)
            return QuadricIntersection{Float(t), pHit};
    }
    return {};
}

QuadricTangents Sphere::Tangents(Point3f p) const {
    Float zRadius = std::sqrt(Sqr(p.x) + Sqr(p.y));
    Float cosPhi = p.x / zRadius, sinPhi = p.y / zRadius;
    Float sinTheta = SafeSqrt(1 - Sqr(p.z / radius));
    return {Vector3f(-phiMax * p.y, phiMax * p.x, 0),
            (thetaZMax - thetaZMin) * Vector3f(p.z * cosPhi, p.z * sinPhi, -radius * sinTheta)};
}

SurfaceInteraction Sphere::BoundaryFromIntersection(const QuadricIntersection &isect,
                                                    Vector3f wo) const {
    return QuadricBoundary(worldFromObject, isect.pObj, Tangents(isect.pObj), FlipNormal(), wo);
}

SurfaceInteraction Sphere::InteractionFromIntersection(const QuadricIntersection &isect,
                                                       Vector3f wo) const {
    Point3f p = isect.pObj;
    QuadricTangents t = Tangents(p);
    // The outward normal is p / r, so it turns as p does (the Weingarten equations' answer for a
    // sphere); a flipped normal turns the other way.
    Float sign = FlipNormal() ? -1 : 1;
    return QuadricInteraction(worldFromObject, p, UV(p), t, FlipNormal(),
                              {Normal3f(sign * t.dpdu / radius), Normal3f(sign * t.dpdv / radius)},
                              wo);
}

pstd::optional<ShapeIntersection> Sphere::Intersect(const Ray &ray, Float tMax) const {
    return IntersectQuadric(*this, ray, tMax);
}

bool Sphere::IntersectP(const Ray &ray, Float tMax) const {
    return BasicIntersect(ray, tMax).has_value();
}

pstd::optional<ShapeSample> Sphere::Sample(Point2f u) const {
    // Archimedes: uniform z and phi are uniform in area, also on a clipped zone.
    Float z = Lerp(u[0], zMin, zMax), phi = u[1] * phiMax;
    Float r = SafeSqrt(Sqr(radius) - Sqr(z));
    Point3f pObj(r * std::cos(phi), r * std::sin(phi), z);
    Normal3f n = Normalize(worldFromObject(Normal3f(pObj.x, pObj.y, pObj.z)));
    if (FlipNormal())
        n = -n;
    return MakeSample(worldFromObject(pObj), n, UV(pObj), AreaPDF(pObj));
}

namespace {
// Below sin^2(1.5 degrees) 1 - cos(thetaMax) loses all precision; its series takes over (pbrt-v4).
constexpr Float kSmallCone = 0.00068523f;
}  // namespace

pstd::optional<ShapeSample> Sphere::Sample(const ShapeSampleContext &ctx, Point2f u) const {
    Point3f pCenter = worldFromObject(Point3f(0, 0, 0));
    if (!sampleCone ||
        DistanceSquared(OffsetRayOrigin(ctx.p, ctx.n, pCenter - ctx.p), pCenter) <=
            Sqr(worldRadius))
        return SampleBySolidAngle(*this, ctx, u);

    // Uniform in the cone of directions toward the sphere; the sampled direction is turned
    // into the point it hits through the angle alpha at the centre (pbrt-v4 6.2.4).
    Float sinThetaMax = worldRadius / Distance(ctx.p, pCenter);
    Float sin2ThetaMax = Sqr(sinThetaMax);
    Float cosThetaMax = SafeSqrt(1 - sin2ThetaMax), oneMinusCosThetaMax = 1 - cosThetaMax;
    Float cosTheta = (cosThetaMax - 1) * u[0] + 1;
    Float sin2Theta = 1 - Sqr(cosTheta);
    if (sin2ThetaMax < kSmallCone) {
        sin2Theta = sin2ThetaMax * u[0];
        cosTheta = std::sqrt(1 - sin2Theta);
        oneMinusCosThetaMax = sin2ThetaMax / 2;
    }
    Float cosAlpha = sin2Theta / sinThetaMax +
                     cosTheta * SafeSqrt(1 - sin2Theta / Sqr(sinThetaMax));
    Float sinAlpha = SafeSqrt(1 - Sqr(cosAlpha));
    Vector3f w = SphericalDirection(sinAlpha, cosAlpha, u[1] * 2 * Pi);
    Frame frame = Frame::FromZ(Normalize(pCenter - ctx.p));
    Normal3f n(frame.FromLocal(-w));
    Point3f p = pCenter + worldRadius * Vector3f(n);
    if (FlipNormal())
        n = -n;
    return MakeSample(p, n, UV(objectFromWorld(p)), 1 / (2 * Pi * oneMinusCosThetaMax));
}

Float Sphere::PDF(const ShapeSampleContext &ctx, Vector3f wi) const {
    Vector3f w = Normalize(wi);
    Point3f pCenter = worldFromObject(Point3f(0, 0, 0));
    if (!sampleCone ||
        DistanceSquared(OffsetRayOrigin(ctx.p, ctx.n, pCenter - ctx.p), pCenter) <=
            Sqr(worldRadius)) {
        pstd::optional<QuadricIntersection> isect = BasicIntersect(SpawnRay(ctx, w), Infinity);
        if (!isect)
            return 0;
        Point3f pObj = isect->pObj;
        Normal3f n = worldFromObject(Normal3f(pObj.x, pObj.y, pObj.z));
        return AreaToSolidAngle(AreaPDF(pObj), ctx.p, worldFromObject(pObj), Normalize(n), w);
    }
    // The cone test works with sines, which stay accurate for small cones; the slack admits
    // directions that rounding put just outside the cone the sampler drew them from.
    Vector3f toCenter = pCenter - ctx.p;
    Float sin2ThetaMax = Sqr(worldRadius) / LengthSquared(toCenter);
    Vector3f axis = Normalize(toCenter);
    if (Dot(w, axis) <= 0 || LengthSquared(Cross(w, axis)) > sin2ThetaMax * (1 + 1e-4f))
        return 0;
    Float oneMinusCosThetaMax = sin2ThetaMax < kSmallCone ? sin2ThetaMax / 2
                                                          : 1 - SafeSqrt(1 - sin2ThetaMax);
    return 1 / (2 * Pi * oneMinusCosThetaMax);
}

std::string Sphere::ToString() const {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ Sphere radius: %g zMin: %g zMax: %g phiMax: %g reverseOrientation: %s "
                  "transformSwapsHandedness: %s ]",
                  radius, zMin, zMax, Degrees(phiMax), reverseOrientation ? "true" : "false",
                  transformSwapsHandedness ? "true" : "false");
    return buf;
}

// ---------------------------------------------------------------------------------------
// Cylinder

Cylinder::Cylinder(const Transform &worldFromObject, bool reverseOrientation, Float radius,
                   Float z0, Float z1, Float phiMaxDegrees)
    : worldFromObject(worldFromObject),
      objectFromWorld(Inverse(worldFromObject)),
      reverseOrientation(reverseOrientation),
      transformSwapsHandedness(worldFromObject.SwapsHandedness()),
      radius(radius),
      zMin(std::min(z0, z1)),
      zMax(std::max(z0, z1)),
      phiMax(Radians(Clamp(phiMaxDegrees, 0, 360))) {
    absDet = AbsDeterminant(worldFromObject);
    objectArea = (zMax - zMin) * radius * phiMax;
    // The object-space normal (cos phi, sin phi, 0) does not depend on z: a 1D integral over
    // phi, whose rule needs more nodes than the sphere's product rule has for an elliptic
    // cross-section to come out within 1e-6.
    static const std::vector<std::pair<double, double>> rule = GaussLegendre(64);
    double mean = 0;
    for (auto [x, w] : rule) {
        Float phi = Float((x + 1) / 2) * phiMax;
        mean += w / 2 * AreaScale(worldFromObject, absDet, Normal3f(std::cos(phi), std::sin(phi), 0));
    }
    worldArea = objectArea * Float(mean);
}

Bounds3f Cylinder::Bounds() const {
    return worldFromObject(Bounds3f(Point3f(-radius, -radius, zMin), Point3f(radius, radius, zMax)));
}

Point2f Cylinder::UV(Point3f pObj) const {
    return Point2f(Azimuth(pObj.x, pObj.y) / phiMax, (pObj.z - zMin) / (zMax - zMin));
}

Float Cylinder::AreaPDF(Point3f pObj) const {
    Normal3f n(pObj.x / radius, pObj.y / radius, 0);
    return 1 / (objectArea * AreaScale(worldFromObject, absDet, n));
}

pstd::optional<QuadricIntersection> Cylinder::BasicIntersect(const Ray &r, Float tMax) const {
    Point3f oi = objectFromWorld(r.o);
    Vector3f di = objectFromWorld(r.d);
    // The sphere's quadratic in the xy plane; a ray parallel to the axis has none (it runs
    // along the surface or never meets it).
    pstd::optional<std::array<double, 2>> roots = CenteredQuadraticRoots<2>(oi, di, radius);
    if (!roots)
        return {};
    for (double t : *roots) {
        if (t <= 0)
            continue;
        if (!(t < tMax))
            return {};
        Point3f pHit = PointAt(oi, di, t);
        Float hitRadius = std::sqrt(Sqr(pHit.x) + Sqr(pHit.y));
        pHit.x *= radius / hitRadius;
        pHit.y *= radius / hitRadius;
        if (pHit.z >= zMin && pHit.z <= zMax && Azimuth(pHit.x, pHit.y) <= phiMax)
            return QuadricIntersection{Float(t), pHit};
    }
    return {};
}

QuadricTangents Cylinder::Tangents(Point3f p) const {
    return {Vector3f(-phiMax * p.y, phiMax * p.x, 0), Vector3f(0, 0, zMax - zMin)};
}

SurfaceInteraction Cylinder::BoundaryFromIntersection(const QuadricIntersection &isect,
                                                      Vector3f wo) const {
    return QuadricBoundary(worldFromObject, isect.pObj, Tangents(isect.pObj), FlipNormal(), wo);
}

SurfaceInteraction Cylinder::InteractionFromIntersection(const QuadricIntersection &isect,
                                                         Vector3f wo) const {
    Point3f p = isect.pObj;
    QuadricTangents t = Tangents(p);
    // The outward normal (x, y, 0) / r turns with u as p does and not at all with v (the
    // Weingarten equations: dn/du = dp/du / r, dn/dv = 0).
    Float sign = FlipNormal() ? -1 : 1;
    return QuadricInteraction(worldFromObject, p, UV(p), t, FlipNormal(),
                              {Normal3f(sign * t.dpdu / radius), Normal3f(0, 0, 0)}, wo);
}

pstd::optional<ShapeIntersection> Cylinder::Intersect(const Ray &ray, Float tMax) const {
    return IntersectQuadric(*this, ray, tMax);
}

bool Cylinder::IntersectP(const Ray &ray, Float tMax) const {
    return BasicIntersect(ray, tMax).has_value();
}

pstd::optional<ShapeSample> Cylinder::Sample(Point2f u) const {
    Float z = Lerp(u[0], zMin, zMax), phi = u[1] * phiMax;
    Point3f pObj(radius * std::cos(phi), radius * std::sin(phi), z);
    Normal3f n = Normalize(worldFromObject(Normal3f(pObj.x, pObj.y, 0)));
    if (FlipNormal())
        n = -n;
    return MakeSample(worldFromObject(pObj), n, UV(pObj), AreaPDF(pObj));
}

pstd::optional<ShapeSample> Cylinder::Sample(const ShapeSampleContext &ctx, Point2f u) const {
    return SampleBySolidAngle(*this, ctx, u);
}

Float Cylinder::PDF(const ShapeSampleContext &ctx, Vector3f wi) const {
    Vector3f w = Normalize(wi);
    pstd::optional<QuadricIntersection> isect = BasicIntersect(SpawnRay(ctx, w), Infinity);
    if (!isect)
        return 0;
    Point3f pObj = isect->pObj;
    Normal3f n = Normalize(worldFromObject(Normal3f(pObj.x, pObj.y, 0)));
    return AreaToSolidAngle(AreaPDF(pObj), ctx.p, worldFromObject(pObj), n, w);
}

std::string Cylinder::ToString() const {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ Cylinder radius: %g zMin: %g zMax: %g phiMax: %g reverseOrientation: %s "
                  "transformSwapsHandedness: %s ]",
                  radius, zMin, zMax, Degrees(phiMax), reverseOrientation ? "true" : "false",
                  transformSwapsHandedness ? "true" : "false");
    return buf;
}

// ---------------------------------------------------------------------------------------
// Disk

Disk::Disk(const Transform &worldFromObject, bool reverseOrientation, Float height,
           Float radius, Float innerRadius, Float phiMaxDegrees)
    : worldFromObject(worldFromObject),
      objectFromWorld(Inverse(worldFromObject)),
      reverseOrientation(reverseOrientation),
      transformSwapsHandedness(worldFromObject.SwapsHandedness()),
      height(height),
      radius(radius),
      innerRadius(innerRadius),
      phiMax(Radians(Clamp(phiMaxDegrees, 0, 360))) {
    // The plane's area scales uniformly, by |M ex x M ey|.
    Float scale = Length(Cross(worldFromObject(Vector3f(1, 0, 0)),
                               worldFromObject(Vector3f(0, 1, 0))));
    worldArea = phiMax / 2 * (Sqr(radius) - Sqr(innerRadius)) * scale;
}

Bounds3f Disk::Bounds() const {
    return worldFromObject(
        Bounds3f(Point3f(-radius, -radius, height), Point3f(radius, radius, height)));
}

Float Disk::Area() const {
    return worldArea;
}

Point2f Disk::UV(Point3f pObj) const {
    Float rHit = std::sqrt(Sqr(pObj.x) + Sqr(pObj.y));
    Float v = radius > innerRadius ? (radius - rHit) / (radius - innerRadius) : 0;
    return Point2f(Azimuth(pObj.x, pObj.y) / phiMax, v);
}

pstd::optional<QuadricIntersection> Disk::BasicIntersect(const Ray &r, Float tMax) const {
    Point3f oi = objectFromWorld(r.o);
    Vector3f di = objectFromWorld(r.d);
    if (di.z == 0)
        return {};
    Float tShapeHit = (height - oi.z) / di.z;
    if (tShapeHit <= 0 || !(tShapeHit < tMax))
        return {};
    Point3f pHit = oi + tShapeHit * di;
    Float dist2 = Sqr(pHit.x) + Sqr(pHit.y);
    if (dist2 > Sqr(radius) || dist2 < Sqr(innerRadius))
        return {};
    if (dist2 == 0)
        pHit.x = 1e-5f * radius;  // keeps phi and the tangents defined at the centre
    if (PastAzimuth(pHit, phiMax))
        return {};
    pHit.z = height;
    return QuadricIntersection{tShapeHit, pHit};
}

QuadricTangents Disk::Tangents(Point3f p) const {
    Float rHit = std::sqrt(Sqr(p.x) + Sqr(p.y));
    return {Vector3f(-phiMax * p.y, phiMax * p.x, 0),
            Vector3f(p.x, p.y, 0) * ((innerRadius - radius) / rHit)};
}

SurfaceInteraction Disk::BoundaryFromIntersection(const QuadricIntersection &isect,
                                                  Vector3f wo) const {
    return QuadricBoundary(worldFromObject, isect.pObj, Tangents(isect.pObj), FlipNormal(), wo);
}

SurfaceInteraction Disk::InteractionFromIntersection(const QuadricIntersection &isect,
                                                     Vector3f wo) const {
    Point3f p = isect.pObj;
    return QuadricInteraction(worldFromObject, p, UV(p), Tangents(p), FlipNormal(), {}, wo);
}

pstd::optional<ShapeIntersection> Disk::Intersect(const Ray &ray, Float tMax) const {
    return IntersectQuadric(*this, ray, tMax);
}

bool Disk::IntersectP(const Ray &ray, Float tMax) const {
    return BasicIntersect(ray, tMax).has_value();
}

pstd::optional<ShapeSample> Disk::Sample(Point2f u) const {
    // The concentric map keeps strata compact on a whole disk; an annulus or sector takes the
    // polar map restricted to it.
    Point2f pd;
    if (innerRadius == 0 && phiMax >= 2 * Pi) {
        pd = SampleUniformDiskConcentric(u) * radius;
    } else {
        Float r = std::sqrt(Lerp(u[0], Sqr(innerRadius), Sqr(radius))), phi = u[1] * phiMax;
        pd = Point2f(r * std::cos(phi), r * std::sin(phi));
    }
    Point3f pObj(pd.x, pd.y, height);
    Normal3f n = Normalize(worldFromObject(Normal3f(0, 0, 1)));
    if (FlipNormal())
        n = -n;
    return MakeSample(worldFromObject(pObj), n, UV(pObj), 1 / Area());
}

pstd::optional<ShapeSample> Disk::Sample(const ShapeSampleContext &ctx, Point2f u) const {
    return SampleBySolidAngle(*this, ctx, u);
}

Float Disk::PDF(const ShapeSampleContext &ctx, Vector3f wi) const {
    Vector3f w = Normalize(wi);
    pstd::optional<QuadricIntersection> isect = BasicIntersect(SpawnRay(ctx, w), Infinity);
    if (!isect)
        return 0;
    Normal3f n = Normalize(worldFromObject(Normal3f(0, 0, 1)));
    return AreaToSolidAngle(1 / Area(), ctx.p, worldFromObject(isect->pObj), n, w);
}

std::string Disk::ToString() const {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ Disk height: %g radius: %g innerRadius: %g phiMax: %g reverseOrientation: "
                  "%s transformSwapsHandedness: %s ]",
                  height, radius, innerRadius, Degrees(phiMax),
                  reverseOrientation ? "true" : "false",
                  transformSwapsHandedness ? "true" : "false");
    return buf;
}

}  // namespace pbrt
