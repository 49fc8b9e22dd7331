// Helpers shared by the shape families' files (triangles.cpp, quadrics.cpp, bilinearpatches.cpp,
// shapes.cpp); not part of the shapes' interface.
#pragma once

#include "pbrt_ext/shapes/shapes.h"

#include "pbrt_ext/util/spherequadrature.h"

#include <limits>
#include <utility>
#include <vector>

namespace pbrt::shapedetail {

// Bound on the relative rounding error of n floating-point operations (pbrt-v4's gamma).
constexpr Float Gamma(int n) {
    constexpr Float eps = std::numeric_limits<Float>::epsilon() * Float(0.5);
    return (n * eps) / (1 - n * eps);
}

template <typename T>
T Interpolate(const std::array<Float, 3> &b, const T &a0, const T &a1, const T &a2) {
    return a0 * b[0] + a1 * b[1] + a2 * b[2];
}

// Lerp(u, Lerp(v, a00, a01), Lerp(v, a10, a11)): the bilinear patch's own parameterization.
template <typename T>
T Bilerp(Point2f uv, const T &a00, const T &a10, const T &a01, const T &a11) {
    return (a00 * (1 - uv[1]) + a01 * uv[1]) * (1 - uv[0]) +
           (a10 * (1 - uv[1]) + a11 * uv[1]) * uv[0];
}

template <typename T>
T LerpT(Float t, const T &a, const T &b) {
    return a * (1 - t) + b * t;
}

inline Float Azimuth(Float x, Float y) {
    Float phi = std::atan2(y, x);
    return phi < 0 ? phi + 2 * Pi : phi;
}

// Whether p lies past a partial quadric's last azimuth. Azimuth() never exceeds 2 Pi, so a whole
// one (phiMax >= 2 Pi) needs no arctangent.
inline bool PastAzimuth(Point3f p, Float phiMax) {
    return phiMax < 2 * Pi && Azimuth(p.x, p.y) > phiMax;
}

// pbrt-v4's SurfaceInteraction constructor: n from the parametric tangents, negated on request.
inline SurfaceInteraction MakeInteraction(Point3f p, Point2f uv, Vector3f wo, Vector3f dpdu,
                                   Vector3f dpdv, bool flipNormal) {
    SurfaceInteraction si;
    si.p = p;
    si.uv = uv;
    si.wo = wo;
    si.dpdu = dpdu;
    si.dpdv = dpdv;
    si.n = Normal3f(Normalize(Cross(dpdu, dpdv)));
    if (flipNormal)
        si.n = -si.n;
    si.shading.n = si.n;
    si.shading.dpdu = dpdu;
    si.shading.dpdv = dpdv;
    return si;
}

// How a quadric's normal turns across it (the Weingarten equations' dn/du and dn/dv).
struct QuadricNormalDerivatives {
    Normal3f dndu, dndv;
};

// A quadric's full hit from its object-space point, uv and tangents, carried to the world.
inline SurfaceInteraction QuadricInteraction(const Transform &worldFromObject, Point3f pObj,
                                             Point2f uv, QuadricTangents t, bool flipNormal,
                                             QuadricNormalDerivatives dn, Vector3f wo) {
    SurfaceInteraction local = MakeInteraction(pObj, uv, Vector3f(), t.dpdu, t.dpdv, flipNormal);
    local.shading.dndu = dn.dndu;
    local.shading.dndv = dn.dndv;
    SurfaceInteraction si = TransformInteraction(worldFromObject, local);
    si.wo = wo;
    return si;
}

// What passing through an interface needs of a quadric's hit: p and the normals, computed as
// QuadricInteraction computes them (MakeInteraction, then TransformInteraction), bit for bit,
// without the uv (its atan2 and acos), derivatives and shading frame it also builds.
inline SurfaceInteraction QuadricBoundary(const Transform &worldFromObject, Point3f pObj,
                                          QuadricTangents t, bool flipNormal, Vector3f wo) {
    Normal3f n(Normalize(Cross(t.dpdu, t.dpdv)));
    SurfaceInteraction si;
    si.p = worldFromObject(pObj);
    si.n = si.shading.n = Normalize(worldFromObject(flipNormal ? -n : n));
    si.wo = wo;
    return si;
}

// |det| of the transform's linear part: how it scales volume.
inline Float AbsDeterminant(const Transform &t) {
    Vector3f ax = t(Vector3f(1, 0, 0)), ay = t(Vector3f(0, 1, 0)), az = t(Vector3f(0, 0, 1));
    return std::abs(Dot(ax, Cross(ay, az)));
}

// Nanson's formula: a linear map M scales area at unit normal n by |det M| |M^-T n|.
inline Float AreaScale(const Transform &t, Float absDet, Normal3f unitNormal) {
    return absDet * Length(t(unitNormal));
}

// A point sampled on a shape, as ShapeSample carries it.
inline ShapeSample MakeSample(Point3f p, Normal3f n, Point2f uv, Float pdf) {
    return ShapeSample{{p, n, uv}, pdf};
}

inline Ray SpawnRay(const ShapeSampleContext &ctx, Vector3f w) {
    return Ray(OffsetRayOrigin(ctx.p, ctx.n, w), w);
}

// An area density at p (normal n) as a density per solid angle seen from pRef along unit w;
// 0 where the conversion is singular (grazing, or p at pRef).
inline Float AreaToSolidAngle(Float pdfArea, Point3f pRef, Point3f p, Normal3f n, Vector3f w) {
    Float pdf = pdfArea * DistanceSquared(pRef, p) / AbsDot(n, w);
    return IsFinite(pdf) ? pdf : 0;
}

// Samples a shape by area and converts the density to solid angle (pbrt-v4's default Sample).
template <typename S>
pstd::optional<ShapeSample> SampleBySolidAngle(const S &shape, const ShapeSampleContext &ctx,
                                               Point2f u) {
    pstd::optional<ShapeSample> ss = shape.Sample(u);
    if (!ss)
        return {};
    Vector3f wi = ss->intr.p - ctx.p;
    if (LengthSquared(wi) == 0)
        return {};
    ss->pdf = AreaToSolidAngle(ss->pdf, ctx.p, ss->intr.p, ss->intr.n, Normalize(wi));
    if (ss->pdf == 0)
        return {};
    return ss;
}

// Nodes of the product Gauss-Legendre rule on [0, 1]^2, for areas of curved surfaces.
template <typename F>
double IntegrateUnitSquare(F f) {
    static const std::vector<std::pair<double, double>> rule = GaussLegendre(12);
    double sum = 0;
    for (auto [x, wx] : rule)
        for (auto [y, wy] : rule) sum += wx * wy * f(Float((x + 1) / 2), Float((y + 1) / 2));
    return sum / 4;
}

// Whether a triangle or rectangle subtending this solid angle is sampled uniformly in it, as
// pbrt-v4 decides: below 3e-4 sr the spherical construction loses precision and area sampling
// is as good, and near a whole hemisphere it becomes unstable.
inline bool SampledBySolidAngle(Float solidAngle) {
    constexpr Float kMinSphericalSampleArea = 3e-4f, kMaxSphericalSampleArea = 6.22f;
    return solidAngle >= kMinSphericalSampleArea && solidAngle <= kMaxSphericalSampleArea;
}

// Whether a flat emitter lying within the ball of squared radius radius2 about c looks small
// enough from p to be sampled by area rather than by solid angle: the ball, and so the emitter,
// fits in a cone of half-angle asin(sqrt(0.1)), 18 degrees. There the area density's conversion
// to solid angle varies little over the emitter, so area sampling's noise is close to spherical
// sampling's, at a quarter of its cost (spherical sampling normalizes three directions and takes
// an arctangent in double, and warps for the receiver's cosine). Measured at 8 spp on pbrt-v4's
// Cornell boxes, each of whose two light triangles fits in a cone of half-angle 10 degrees from
// the floor: 13 % less time for 3 to 4 % more seed-to-seed error (docs/benchmarks.md, "Stop
// 39"). A cheap bound comes first so that
// the spherical construction is not paid for just to decide against it; the caller then applies
// SampledBySolidAngle's limits to what remains.
inline bool SampledByAreaFrom(Point3f p, Point3f c, Float radius2) {
    constexpr Float kMaxSin2HalfAngle = 0.1f;
    return radius2 < kMaxSin2HalfAngle * DistanceSquared(p, c);
}

// The bilinear warp that approximates the receiver's cosine across a spherical sample's square
// (pbrt-v4): the cosines toward what the square's corners (0, 0), (1, 0), (0, 1), (1, 1) map to,
// floored at 0.01 so that no direction the light reaches gets density 0.
inline std::array<Float, 4> CosineWarpWeights(Normal3f ns, const std::array<Vector3f, 4> &cornerDirections) {
    std::array<Float, 4> w;
    for (int i = 0; i < 4; ++i) w[size_t(i)] = std::max<Float>(0.01f, AbsDot(ns, cornerDirections[size_t(i)]));
    return w;
}

}  // namespace pbrt::shapedetail
