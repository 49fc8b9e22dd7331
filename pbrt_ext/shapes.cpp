// Shapes (pbrt-v4's src/pbrt/shapes.h/.cpp). Where this differs from pbrt-v4, and why:
//   - Partial spheres and disks (zMin/zMax/phiMax, innerRadius) are sampled over the part that
//     exists, and area densities account for a scaling transform (Nanson's formula), so that
//     Sample and PDF agree with Intersect; pbrt-v4 samples the whole shape in object units.
//   - Sphere and disk samples orient n exactly as their intersections do (reverseOrientation ^
//     transformSwapsHandedness); pbrt-v4's samples use reverseOrientation alone, which disagrees
//     with its own intersections under a mirroring transform.
//   - Triangles and bilinear patches are sampled by area from a reference point (pbrt-v4 adds
//     spherical triangle/rectangle sampling): the same expectation, more noise for large,
//     close emitters.
#include "pbrt_ext/shapes.h"

#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spherequadrature.h"

#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>

namespace pbrt {

namespace {

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

Float Azimuth(Float x, Float y) {
    Float phi = std::atan2(y, x);
    return phi < 0 ? phi + 2 * Pi : phi;
}

// pbrt-v4's SurfaceInteraction constructor: n from the parametric tangents, negated on request.
SurfaceInteraction MakeInteraction(Point3f p, Point2f uv, Vector3f wo, Vector3f dpdu,
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

// pbrt-v4's SetShadingGeometry with an authoritative shading normal: the geometric normal moves
// to its side. Huge tangents are scaled down so that later products cannot overflow.
void SetShadingGeometry(SurfaceInteraction *si, Normal3f ns, Vector3f dpdus, Vector3f dpdvs) {
    si->shading.n = ns;
    si->n = FaceForward(si->n, ns);
    while (LengthSquared(dpdus) > 1e16f || LengthSquared(dpdvs) > 1e16f) {
        dpdus /= 1e8f;
        dpdvs /= 1e8f;
    }
    si->shading.dpdu = dpdus;
    si->shading.dpdv = dpdvs;
}

// A point sampled on a shape, as ShapeSample carries it.
ShapeSample MakeSample(Point3f p, Normal3f n, Point2f uv, Float pdf) {
    SurfaceInteraction si;
    si.p = p;
    si.n = si.shading.n = n;
    si.uv = uv;
    return ShapeSample{si, pdf};
}

Ray SpawnRay(const ShapeSampleContext &ctx, Vector3f w) {
    return Ray(OffsetRayOrigin(ctx.p, ctx.n, w), w);
}

// An area density at p (normal n) as a density per solid angle seen from pRef along unit w;
// 0 where the conversion is singular (grazing, or p at pRef).
Float AreaToSolidAngle(Float pdfArea, Point3f pRef, Point3f p, Normal3f n, Vector3f w) {
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

// ---------------------------------------------------------------------------------------
// Triangles

struct TriangleHit {
    std::array<Float, 3> b;
    Float t;
};

std::array<Point3f, 3> Vertices(const TriangleMesh *mesh, int triIndex) {
    const int *v = &mesh->indices[3 * triIndex];
    return {mesh->p[v[0]], mesh->p[v[1]], mesh->p[v[2]]};
}

// Watertight ray/triangle intersection (Woop, Benthin and Wald 2013), as pbrt-v4: in a frame
// where the ray runs along +z from the origin, the signs of the 2D edge functions decide the
// hit exactly, so rays cannot slip through shared edges; t must exceed its rounding error.
pstd::optional<TriangleHit> IntersectTriangle(const Ray &ray, Float tMax, Point3f p0, Point3f p1,
                                              Point3f p2) {
    if (LengthSquared(Cross(p2 - p0, p1 - p0)) == 0)
        return {};
    Vector3f ad = Abs(ray.d);
    int kz = (ad.x > ad.y) ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    auto permute = [&](Vector3f v) { return Vector3f(v[kx], v[ky], v[kz]); };
    Vector3f d = permute(ray.d);
    Vector3f p0t = permute(p0 - ray.o), p1t = permute(p1 - ray.o), p2t = permute(p2 - ray.o);
    Float sx = -d.x / d.z, sy = -d.y / d.z, sz = 1 / d.z;
    for (Vector3f *pt : {&p0t, &p1t, &p2t}) {
        pt->x += sx * pt->z;
        pt->y += sy * pt->z;
    }
    Float e0 = DifferenceOfProducts(p1t.x, p2t.y, p1t.y, p2t.x);
    Float e1 = DifferenceOfProducts(p2t.x, p0t.y, p2t.y, p0t.x);
    Float e2 = DifferenceOfProducts(p0t.x, p1t.y, p0t.y, p1t.x);
    // An edge function of exactly zero may be a rounding artifact: decide it in double.
    if (e0 == 0 || e1 == 0 || e2 == 0) {
        e0 = Float(double(p1t.x) * p2t.y - double(p1t.y) * p2t.x);
        e1 = Float(double(p2t.x) * p0t.y - double(p2t.y) * p0t.x);
        e2 = Float(double(p0t.x) * p1t.y - double(p0t.y) * p1t.x);
    }
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0))
        return {};
    Float det = e0 + e1 + e2;
    if (det == 0)
        return {};
    p0t.z *= sz;
    p1t.z *= sz;
    p2t.z *= sz;
    Float tScaled = e0 * p0t.z + e1 * p1t.z + e2 * p2t.z;
    if (det < 0 && (tScaled >= 0 || tScaled < tMax * det))
        return {};
    if (det > 0 && (tScaled <= 0 || tScaled > tMax * det))
        return {};
    Float invDet = 1 / det;
    Float t = tScaled * invDet;
    if (!(t < tMax))
        return {};

    // Conservative bound on t's rounding error (pbrt-v4, section 6.8.7).
    Float maxZt = std::max({std::abs(p0t.z), std::abs(p1t.z), std::abs(p2t.z)});
    Float maxXt = std::max({std::abs(p0t.x), std::abs(p1t.x), std::abs(p2t.x)});
    Float maxYt = std::max({std::abs(p0t.y), std::abs(p1t.y), std::abs(p2t.y)});
    Float deltaZ = Gamma(3) * maxZt;
    Float deltaX = Gamma(5) * (maxXt + maxZt), deltaY = Gamma(5) * (maxYt + maxZt);
    Float deltaE = 2 * (Gamma(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
    Float maxE = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
    Float deltaT = 3 * (Gamma(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) *
                   std::abs(invDet);
    if (t <= deltaT)
        return {};
    return TriangleHit{{e0 * invDet, e1 * invDet, e2 * invDet}, t};
}

// pbrt-v4's default parameterization when a mesh has no uv.
std::array<Point2f, 3> TriangleUV(const TriangleMesh *mesh, const int *v) {
    if (mesh->uv.empty())
        return {Point2f(0, 0), Point2f(1, 0), Point2f(1, 1)};
    return {mesh->uv[v[0]], mesh->uv[v[1]], mesh->uv[v[2]]};
}

// ---------------------------------------------------------------------------------------
// Bilinear patches

// Density on [0,1]^2 proportional to the bilinear interpolation of corner weights w (00, 10,
// 01, 11): v from its marginal, then u given v (pbrt-v4's SampleBilinear/BilinearPDF).
Point2f SampleBilinear(Point2f u, const std::array<Float, 4> &w) {
    Float y = SampleLinear(u[1], w[0] + w[1], w[2] + w[3]);
    Float x = SampleLinear(u[0], Lerp(y, w[0], w[2]), Lerp(y, w[1], w[3]));
    return Point2f(x, y);
}
Float BilinearPDF(Point2f p, const std::array<Float, 4> &w) {
    if (p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1)
        return 0;
    Float sum = w[0] + w[1] + w[2] + w[3];
    if (sum == 0)
        return 1;
    return 4 * Bilerp(p, w[0], w[1], w[2], w[3]) / sum;
}

// A planar patch whose corners are equidistant from their centroid is a rectangle: uniform
// (u, v) is then uniform by area.
bool IsRectangle(Point3f p00, Point3f p10, Point3f p01, Point3f p11) {
    if (p00 == p01 || p01 == p11 || p11 == p10 || p10 == p00)
        return false;
    Vector3f n = Normalize(Cross(p10 - p00, p01 - p00));
    if (AbsDot(Normalize(p11 - p00), n) > 1e-5f)
        return false;
    Point3f c = (p00 + p10 + p01 + p11) / 4;
    Float d2[4] = {DistanceSquared(p00, c), DistanceSquared(p10, c), DistanceSquared(p01, c),
                   DistanceSquared(p11, c)};
    for (int i = 1; i < 4; ++i)
        if (std::abs(d2[i] - d2[0]) / d2[0] > 1e-4f)
            return false;
    return true;
}

struct PatchTangents {
    Vector3f dpdu, dpdv;
};
PatchTangents PatchDerivatives(Point2f uv, Point3f p00, Point3f p10, Point3f p01, Point3f p11) {
    return {LerpT(uv[1], p10, p11) - LerpT(uv[1], p00, p01),
            LerpT(uv[0], p01, p11) - LerpT(uv[0], p00, p10)};
}

// Corner weights that make the bilinear warp follow the patch's area element (pbrt-v4).
std::array<Float, 4> AreaWeights(Point3f p00, Point3f p10, Point3f p01, Point3f p11) {
    return {Length(Cross(p10 - p00, p01 - p00)), Length(Cross(p10 - p00, p11 - p10)),
            Length(Cross(p01 - p00, p11 - p01)), Length(Cross(p11 - p10, p11 - p01))};
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

// ---------------------------------------------------------------------------------------
// Meshes

template <typename Mesh>
Mesh MakeMesh(const char *name, int verticesPerPrimitive, const Transform &worldFromObject,
              bool reverseOrientation, std::vector<int> indices, std::vector<Point3f> p,
              std::vector<Normal3f> n, std::vector<Point2f> uv) {
    auto fail = [&](const std::string &what) {
        throw std::runtime_error(std::string(name) + ": " + what);
    };
    if (indices.size() % verticesPerPrimitive != 0)
        fail("the number of indices, " + std::to_string(indices.size()) +
             ", is not a multiple of " + std::to_string(verticesPerPrimitive));
    for (int i : indices)
        if (i < 0 || size_t(i) >= p.size())
            fail("vertex index " + std::to_string(i) + " is out of range (" +
                 std::to_string(p.size()) + " vertices)");
    if (!n.empty() && n.size() != p.size())
        fail(std::to_string(n.size()) + " normals for " + std::to_string(p.size()) + " vertices");
    if (!uv.empty() && uv.size() != p.size())
        fail(std::to_string(uv.size()) + " uvs for " + std::to_string(p.size()) + " vertices");

    Mesh mesh;
    for (Point3f &pi : p) pi = worldFromObject(pi);
    for (Normal3f &ni : n) ni = reverseOrientation ? -worldFromObject(ni) : worldFromObject(ni);
    mesh.p = std::move(p);
    mesh.indices = std::move(indices);
    mesh.n = std::move(n);
    mesh.uv = std::move(uv);
    mesh.reverseOrientation = reverseOrientation;
    mesh.transformSwapsHandedness = worldFromObject.SwapsHandedness();
    return mesh;
}

std::string Describe(const char *kind, size_t prims, size_t vertices, bool hasN, bool hasUV,
                     bool reverseOrientation, bool swaps) {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ %s primitives: %zu vertices: %zu n: %s uv: %s reverseOrientation: %s "
                  "transformSwapsHandedness: %s ]",
                  kind, prims, vertices, hasN ? "yes" : "no", hasUV ? "yes" : "no",
                  reverseOrientation ? "true" : "false", swaps ? "true" : "false");
    return buf;
}

}  // namespace

std::string TriangleMesh::ToString() const {
    return Describe("TriangleMesh", indices.size() / 3, p.size(), !n.empty(), !uv.empty(),
                    reverseOrientation, transformSwapsHandedness);
}
std::string BilinearPatchMesh::ToString() const {
    return Describe("BilinearPatchMesh", indices.size() / 4, p.size(), !n.empty(), !uv.empty(),
                    reverseOrientation, transformSwapsHandedness);
}

TriangleMesh MakeTriangleMesh(const Transform &worldFromObject, bool reverseOrientation,
                              std::vector<int> indices, std::vector<Point3f> p,
                              std::vector<Normal3f> n, std::vector<Point2f> uv) {
    return MakeMesh<TriangleMesh>("trianglemesh", 3, worldFromObject, reverseOrientation,
                                  std::move(indices), std::move(p), std::move(n),
                                  std::move(uv));
}
BilinearPatchMesh MakeBilinearPatchMesh(const Transform &worldFromObject,
                                        bool reverseOrientation, std::vector<int> indices,
                                        std::vector<Point3f> p, std::vector<Normal3f> n,
                                        std::vector<Point2f> uv) {
    return MakeMesh<BilinearPatchMesh>("bilinearmesh", 4, worldFromObject, reverseOrientation,
                                       std::move(indices), std::move(p), std::move(n),
                                       std::move(uv));
}

SurfaceInteraction TransformInteraction(const Transform &t, const SurfaceInteraction &si) {
    SurfaceInteraction r = si;
    r.p = t(si.p);
    r.n = Normalize(t(si.n));
    r.dpdu = t(si.dpdu);
    r.dpdv = t(si.dpdv);
    r.shading.n = FaceForward(Normalize(t(si.shading.n)), r.n);
    r.shading.dpdu = t(si.shading.dpdu);
    r.shading.dpdv = t(si.shading.dpdv);
    if (LengthSquared(si.wo) > 0)
        r.wo = Normalize(t(si.wo));
    return r;
}

// ---------------------------------------------------------------------------------------
// Triangle

Bounds3f Triangle::Bounds() const {
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    return Union(Bounds3f(p0, p1), p2);
}

Float Triangle::Area() const {
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    return Length(Cross(p1 - p0, p2 - p0)) / 2;
}

SurfaceInteraction Triangle::InteractionFromIntersection(const TriangleMesh *mesh, int triIndex,
                                                         std::array<Float, 3> b, Vector3f wo) {
    const int *v = &mesh->indices[3 * triIndex];
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    std::array<Point2f, 3> uv = TriangleUV(mesh, v);

    // dp/du and dp/dv from the uv parameterization, solving the 2x2 system of the two edges.
    Vector2f duv02 = uv[0] - uv[2], duv12 = uv[1] - uv[2];
    Vector3f dp02 = p0 - p2, dp12 = p1 - p2;
    Float determinant = DifferenceOfProducts(duv02[0], duv12[1], duv02[1], duv12[0]);
    Vector3f dpdu, dpdv;
    bool degenerateUV = std::abs(determinant) < 1e-9f;
    if (!degenerateUV) {
        Float invDet = 1 / determinant;
        dpdu = (dp02 * duv12[1] - dp12 * duv02[1]) * invDet;
        dpdv = (dp12 * duv02[0] - dp02 * duv12[0]) * invDet;
    }
    // Without usable uv, any frame in the triangle's plane will do; CoordinateSystem gives the
    // same one for every point of the triangle.
    if (degenerateUV || LengthSquared(Cross(dpdu, dpdv)) == 0) {
        Vector3f ng = Cross(p2 - p0, p1 - p0);
        ng = LengthSquared(ng) > 0 ? Normalize(ng) : Vector3f(0, 0, 1);
        CoordinateSystem(ng, &dpdu, &dpdv);
    }

    bool flip = mesh->reverseOrientation ^ mesh->transformSwapsHandedness;
    SurfaceInteraction si =
        MakeInteraction(Interpolate(b, p0, p1, p2), Interpolate(b, uv[0], uv[1], uv[2]), wo,
                        dpdu, dpdv, flip);
    // The winding, not the uv mapping, orients a triangle's normal.
    si.n = si.shading.n = Normal3f(Normalize(Cross(dp02, dp12)));
    if (flip)
        si.n = si.shading.n = -si.n;

    if (!mesh->n.empty()) {
        Normal3f ns = Interpolate(b, mesh->n[v[0]], mesh->n[v[1]], mesh->n[v[2]]);
        ns = LengthSquared(ns) > 0 ? Normalize(ns) : si.n;
        Vector3f ss = si.dpdu;
        Vector3f ts = Cross(ns, ss);
        if (LengthSquared(ts) > 0)
            ss = Cross(ts, ns);
        else
            CoordinateSystem(ns, &ss, &ts);
        SetShadingGeometry(&si, ns, ss, ts);
    }
    return si;
}

pstd::optional<ShapeIntersection> Triangle::Intersect(const Ray &ray, Float tMax) const {
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    pstd::optional<TriangleHit> hit = IntersectTriangle(ray, tMax, p0, p1, p2);
    if (!hit)
        return {};
    return ShapeIntersection{
        InteractionFromIntersection(mesh, triIndex, hit->b, -Normalize(ray.d)), hit->t};
}

bool Triangle::IntersectP(const Ray &ray, Float tMax) const {
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    return IntersectTriangle(ray, tMax, p0, p1, p2).has_value();
}

pstd::optional<ShapeSample> Triangle::Sample(Point2f u) const {
    const int *v = &mesh->indices[3 * triIndex];
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    std::array<Float, 3> b = SampleUniformTriangle(u);
    Normal3f n = Normal3f(Normalize(Cross(p1 - p0, p2 - p0)));
    // Orient n as Intersect does.
    if (!mesh->n.empty())
        n = FaceForward(n, Interpolate(b, mesh->n[v[0]], mesh->n[v[1]], mesh->n[v[2]]));
    else if (mesh->reverseOrientation ^ mesh->transformSwapsHandedness)
        n = -n;
    std::array<Point2f, 3> uv = TriangleUV(mesh, v);
    return MakeSample(Interpolate(b, p0, p1, p2), n, Interpolate(b, uv[0], uv[1], uv[2]),
                      1 / Area());
}

pstd::optional<ShapeSample> Triangle::Sample(const ShapeSampleContext &ctx, Point2f u) const {
    return SampleBySolidAngle(*this, ctx, u);
}

Float Triangle::PDF(const ShapeSampleContext &ctx, Vector3f wi) const {
    Vector3f w = Normalize(wi);
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    pstd::optional<TriangleHit> hit = IntersectTriangle(SpawnRay(ctx, w), Infinity, p0, p1, p2);
    if (!hit)
        return 0;
    Normal3f n(Cross(p1 - p0, p2 - p0));
    return AreaToSolidAngle(1 / Area(), ctx.p, Interpolate(hit->b, p0, p1, p2),
                            Normalize(n), w);
}

std::string Triangle::ToString() const {
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ Triangle triIndex: %d p0: (%g, %g, %g) p1: (%g, %g, %g) p2: (%g, %g, %g) ]",
                  triIndex, p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, p2.x, p2.y, p2.z);
    return buf;
}

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
    Vector3f ax = worldFromObject(Vector3f(1, 0, 0)), ay = worldFromObject(Vector3f(0, 1, 0)),
             az = worldFromObject(Vector3f(0, 0, 1));
    absDet = std::abs(Dot(ax, Cross(ay, az)));
    objectArea = phiMax * radius * (zMax - zMin);
    // The object-space area element is radius dz dphi; the transform scales it pointwise.
    worldArea = objectArea * Float(IntegrateUnitSquare([&](Float s, Float t) {
                    Float z = Lerp(s, zMin, zMax), phi = t * phiMax;
                    Float r = SafeSqrt(Sqr(radius) - Sqr(z));
                    return AreaScale(Point3f(r * std::cos(phi), r * std::sin(phi), z));
                }));

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
    // Nanson's formula: a linear map M scales area at unit normal n by |det M| |M^-T n|.
    Normal3f nObj(pObj.x / radius, pObj.y / radius, pObj.z / radius);
    return absDet * Length(worldFromObject(nObj));
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
    // In double, with the discriminant written as 4a (r + l)(r - l), l the distance from the
    // centre to the line: no cancellation for rays far from the sphere (pbrt-v4 6.8.3).
    double ox = oi.x, oy = oi.y, oz = oi.z, dx = di.x, dy = di.y, dz = di.z;
    double a = dx * dx + dy * dy + dz * dz, b = 2 * (dx * ox + dy * oy + dz * oz);
    double c = ox * ox + oy * oy + oz * oz - double(radius) * radius;
    if (a == 0)
        return {};
    double f = b / (2 * a);
    double vx = ox - f * dx, vy = oy - f * dy, vz = oz - f * dz;
    double len = std::sqrt(vx * vx + vy * vy + vz * vz);
    double discrim = 4 * a * (radius + len) * (radius - len);
    if (discrim < 0)
        return {};
    double rootDiscrim = std::sqrt(discrim);
    double q = (b < 0) ? -0.5 * (b - rootDiscrim) : -0.5 * (b + rootDiscrim);
    if (q == 0)
        return {};
    double t0 = q / a, t1 = c / q;
    if (t0 > t1)
        std::swap(t0, t1);

    // The nearer root first; the farther one when clipping removes the nearer.
    for (double t : {t0, t1}) {
        if (t <= 0)
            continue;
        if (!(t < tMax))
            return {};
        Point3f pHit(Float(ox + t * dx), Float(oy + t * dy), Float(oz + t * dz));
        pHit *= radius / Length(Vector3f(pHit));
        if (pHit.x == 0 && pHit.y == 0)
            pHit.x = 1e-5f * radius;  // keeps phi and dp/du defined at the poles
        bool clipped = (zMin > -radius && pHit.z < zMin) || (zMax < radius && pHit.z > zMax) ||
                       Azimuth(pHit.x, pHit.y) > phiMax;
        if (!clipped)
            return QuadricIntersection{Float(t), pHit};
    }
    return {};
}

SurfaceInteraction Sphere::InteractionFromIntersection(const QuadricIntersection &isect,
                                                       Vector3f wo) const {
    Point3f p = isect.pObj;
    Float zRadius = std::sqrt(Sqr(p.x) + Sqr(p.y));
    Float cosPhi = p.x / zRadius, sinPhi = p.y / zRadius;
    Float sinTheta = SafeSqrt(1 - Sqr(p.z / radius));
    Vector3f dpdu(-phiMax * p.y, phiMax * p.x, 0);
    Vector3f dpdv = (thetaZMax - thetaZMin) *
                    Vector3f(p.z * cosPhi, p.z * sinPhi, -radius * sinTheta);
    SurfaceInteraction si = TransformInteraction(
        worldFromObject, MakeInteraction(p, UV(p), Vector3f(), dpdu, dpdv, FlipNormal()));
    si.wo = wo;
    return si;
}

pstd::optional<ShapeIntersection> Sphere::Intersect(const Ray &ray, Float tMax) const {
    pstd::optional<QuadricIntersection> isect = BasicIntersect(ray, tMax);
    if (!isect)
        return {};
    return ShapeIntersection{InteractionFromIntersection(*isect, -Normalize(ray.d)),
                             isect->tHit};
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
    if (Azimuth(pHit.x, pHit.y) > phiMax)
        return {};
    pHit.z = height;
    return QuadricIntersection{tShapeHit, pHit};
}

SurfaceInteraction Disk::InteractionFromIntersection(const QuadricIntersection &isect,
                                                     Vector3f wo) const {
    Point3f p = isect.pObj;
    Float rHit = std::sqrt(Sqr(p.x) + Sqr(p.y));
    Vector3f dpdu(-phiMax * p.y, phiMax * p.x, 0);
    Vector3f dpdv = Vector3f(p.x, p.y, 0) * ((innerRadius - radius) / rHit);
    SurfaceInteraction si = TransformInteraction(
        worldFromObject, MakeInteraction(p, UV(p), Vector3f(), dpdu, dpdv, FlipNormal()));
    si.wo = wo;
    return si;
}

pstd::optional<ShapeIntersection> Disk::Intersect(const Ray &ray, Float tMax) const {
    pstd::optional<QuadricIntersection> isect = BasicIntersect(ray, tMax);
    if (!isect)
        return {};
    return ShapeIntersection{InteractionFromIntersection(*isect, -Normalize(ray.d)),
                             isect->tHit};
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

// ---------------------------------------------------------------------------------------
// Bilinear patch

pstd::optional<BilinearIntersection> IntersectBilinearPatch(const Ray &ray, Float tMax,
                                                            Point3f p00, Point3f p10,
                                                            Point3f p01, Point3f p11) {
    // The distance from the ray to the patch's v-isoline at u is zero where
    // a + b u + c u^2 = 0; for each root in [0, 1], the ray meets that segment at (v, t).
    Vector3f q00 = p00 - ray.o, q10 = p10 - ray.o;
    Vector3f e00 = p01 - p00, e11 = p11 - p10;
    Float a = Dot(Cross(q00, ray.d), e00);
    Float c = Dot(Cross(p10 - p00, p01 - p11), ray.d);
    Float b = Dot(Cross(q10, ray.d), e11) - (a + c);
    Float discrim = DifferenceOfProducts(b, b, 4 * a, c);
    if (discrim < 0)
        return {};
    Float root = std::sqrt(discrim);
    Float u1, u2;
    if (c == 0) {  // a trapezoid: the quadratic is linear
        if (b == 0)
            return {};
        u1 = -a / b;
        u2 = -1;
    } else {
        Float q = -(b + std::copysign(root, b)) / 2;  // the root without cancellation
        u1 = q / c;
        u2 = (q != 0) ? a / q : u1;
    }

    Float t = tMax, u = 0, v = 0;
    for (Float ui : {u1, u2}) {
        if (!(ui >= 0 && ui <= 1))
            continue;
        Vector3f pa = q00 * (1 - ui) + q10 * ui;  // the isoline's start, from the origin
        Vector3f pb = e00 * (1 - ui) + e11 * ui;  // and its direction
        Vector3f n = Cross(ray.d, pb);
        Float det = Dot(n, n);
        if (det == 0)
            continue;
        n = Cross(n, pa);
        Float ti = Dot(n, pb) / det, vi = Dot(n, ray.d);
        if (vi >= 0 && vi <= det && ti > 0 && ti < t) {
            t = ti;
            u = ui;
            v = vi / det;
        }
    }
    if (!(t < tMax))
        return {};
    return BilinearIntersection{Point2f(u, v), t};
}

namespace {
std::array<Point3f, 4> PatchCorners(const BilinearPatchMesh *mesh, int patchIndex) {
    const int *v = &mesh->indices[4 * patchIndex];
    return {mesh->p[v[0]], mesh->p[v[1]], mesh->p[v[2]], mesh->p[v[3]]};
}
}  // namespace

BilinearPatch::BilinearPatch(const BilinearPatchMesh *mesh, int patchIndex)
    : mesh(mesh), patchIndex(patchIndex) {
    // Named copies, not a structured binding: clang 14 cannot capture bindings in the lambda below.
    std::array<Point3f, 4> corners = Corners();
    Point3f p00 = corners[0], p10 = corners[1], p01 = corners[2], p11 = corners[3];
    isRectangle = IsRectangle(p00, p10, p01, p11);
    if (isRectangle) {
        area = Distance(p00, p01) * Distance(p00, p10);
    } else {
        area = Float(IntegrateUnitSquare([&](Float s, Float t) {
            PatchTangents d = PatchDerivatives(Point2f(s, t), p00, p10, p01, p11);
            return Length(Cross(d.dpdu, d.dpdv));
        }));
    }
}

std::array<Point3f, 4> BilinearPatch::Corners() const {
    return PatchCorners(mesh, patchIndex);
}

Bounds3f BilinearPatch::Bounds() const {
    auto [p00, p10, p01, p11] = Corners();
    return Union(Bounds3f(p00, p10), Bounds3f(p01, p11));
}

SurfaceInteraction BilinearPatch::InteractionFromIntersection(const BilinearPatchMesh *mesh,
                                                              int patchIndex, Point2f uv,
                                                              Vector3f wo) {
    const int *v = &mesh->indices[4 * patchIndex];
    auto [p00, p10, p01, p11] = PatchCorners(mesh, patchIndex);
    Point3f p = Bilerp(uv, p00, p10, p01, p11);
    auto [dpdu, dpdv] = PatchDerivatives(uv, p00, p10, p01, p11);

    // With texture coordinates (s, t), the tangents become dp/ds and dp/dt, through the
    // inverse of the (s, t) mapping's partial derivatives, kept on the side of dp/du x dp/dv.
    Point2f st = uv;
    if (!mesh->uv.empty()) {
        Point2f uv00 = mesh->uv[v[0]], uv10 = mesh->uv[v[1]], uv01 = mesh->uv[v[2]],
                uv11 = mesh->uv[v[3]];
        st = Bilerp(uv, uv00, uv10, uv01, uv11);
        Vector2f dstdu = LerpT(uv[1], uv10, uv11) - LerpT(uv[1], uv00, uv01);
        Vector2f dstdv = LerpT(uv[0], uv01, uv11) - LerpT(uv[0], uv00, uv10);
        auto inv = [](Float x) { return std::abs(x) < 1e-8f ? 0 : 1 / x; };
        Vector3f dpds = dpdu * inv(dstdu[0]) + dpdv * inv(dstdv[0]);
        Vector3f dpdt = dpdu * inv(dstdu[1]) + dpdv * inv(dstdv[1]);
        if (LengthSquared(Cross(dpds, dpdt)) > 0) {
            if (Dot(Cross(dpdu, dpdv), Cross(dpds, dpdt)) < 0)
                dpdt = -dpdt;
            dpdu = dpds;
            dpdv = dpdt;
        }
    }
    SurfaceInteraction si = MakeInteraction(
        p, st, wo, dpdu, dpdv, mesh->reverseOrientation ^ mesh->transformSwapsHandedness);

    // A shading normal rotates the tangent frame by the rotation taking n to ns.
    if (!mesh->n.empty()) {
        Normal3f ns = Bilerp(uv, mesh->n[v[0]], mesh->n[v[1]], mesh->n[v[2]], mesh->n[v[3]]);
        if (LengthSquared(ns) > 0) {
            ns = Normalize(ns);
            Vector3f axis = Cross(Vector3f(si.n), Vector3f(ns));
            if (LengthSquared(axis) > 1e-14f) {
                Float cosTheta = Dot(si.n, ns), sinTheta = SafeSqrt(1 - Sqr(cosTheta));
                Transform r = Rotate(sinTheta, cosTheta, axis);
                Vector3f sdpdu = r(dpdu), sdpdv = r(dpdv);
                sdpdu = GramSchmidt(sdpdu, Vector3f(ns));
                SetShadingGeometry(&si, ns, sdpdu, sdpdv);
            } else {
                SetShadingGeometry(&si, ns, dpdu, dpdv);
            }
        }
    }
    return si;
}

pstd::optional<ShapeIntersection> BilinearPatch::Intersect(const Ray &ray, Float tMax) const {
    auto [p00, p10, p01, p11] = Corners();
    pstd::optional<BilinearIntersection> hit =
        IntersectBilinearPatch(ray, tMax, p00, p10, p01, p11);
    if (!hit)
        return {};
    return ShapeIntersection{
        InteractionFromIntersection(mesh, patchIndex, hit->uv, -Normalize(ray.d)), hit->t};
}

bool BilinearPatch::IntersectP(const Ray &ray, Float tMax) const {
    auto [p00, p10, p01, p11] = Corners();
    return IntersectBilinearPatch(ray, tMax, p00, p10, p01, p11).has_value();
}

Float BilinearPatch::AreaPDF(Point2f uv) const {
    auto [p00, p10, p01, p11] = Corners();
    Float pdf = isRectangle ? 1 : BilinearPDF(uv, AreaWeights(p00, p10, p01, p11));
    PatchTangents d = PatchDerivatives(uv, p00, p10, p01, p11);
    return pdf / Length(Cross(d.dpdu, d.dpdv));
}

pstd::optional<ShapeSample> BilinearPatch::Sample(Point2f u) const {
    const int *v = &mesh->indices[4 * patchIndex];
    auto [p00, p10, p01, p11] = Corners();
    Point2f uv = isRectangle ? u : SampleBilinear(u, AreaWeights(p00, p10, p01, p11));
    PatchTangents d = PatchDerivatives(uv, p00, p10, p01, p11);
    Vector3f ng = Cross(d.dpdu, d.dpdv);
    if (LengthSquared(ng) == 0)
        return {};
    Normal3f n(Normalize(ng));
    // Orient n as Intersect does.
    if (!mesh->n.empty())
        n = FaceForward(n, Bilerp(uv, mesh->n[v[0]], mesh->n[v[1]], mesh->n[v[2]],
                                  mesh->n[v[3]]));
    else if (mesh->reverseOrientation ^ mesh->transformSwapsHandedness)
        n = -n;
    Point2f st = mesh->uv.empty()
                     ? uv
                     : Bilerp(uv, mesh->uv[v[0]], mesh->uv[v[1]], mesh->uv[v[2]], mesh->uv[v[3]]);
    Float pdf = AreaPDF(uv);
    if (!IsFinite(pdf))
        return {};
    return MakeSample(Bilerp(uv, p00, p10, p01, p11), n, st, pdf);
}

pstd::optional<ShapeSample> BilinearPatch::Sample(const ShapeSampleContext &ctx,
                                                  Point2f u) const {
    return SampleBySolidAngle(*this, ctx, u);
}

Float BilinearPatch::PDF(const ShapeSampleContext &ctx, Vector3f wi) const {
    Vector3f w = Normalize(wi);
    auto [p00, p10, p01, p11] = Corners();
    pstd::optional<BilinearIntersection> hit =
        IntersectBilinearPatch(SpawnRay(ctx, w), Infinity, p00, p10, p01, p11);
    if (!hit)
        return 0;
    PatchTangents d = PatchDerivatives(hit->uv, p00, p10, p01, p11);
    Vector3f ng = Cross(d.dpdu, d.dpdv);
    if (LengthSquared(ng) == 0)
        return 0;
    return AreaToSolidAngle(AreaPDF(hit->uv), ctx.p, Bilerp(hit->uv, p00, p10, p01, p11),
                            Normal3f(Normalize(ng)), w);
}

std::string BilinearPatch::ToString() const {
    auto [p00, p10, p01, p11] = Corners();
    char buf[320];
    std::snprintf(buf, sizeof(buf),
                  "[ BilinearPatch patchIndex: %d p00: (%g, %g, %g) p10: (%g, %g, %g) p01: (%g, "
                  "%g, %g) p11: (%g, %g, %g) area: %g ]",
                  patchIndex, p00.x, p00.y, p00.z, p10.x, p10.y, p10.z, p01.x, p01.y, p01.z,
                  p11.x, p11.y, p11.z, area);
    return buf;
}

}  // namespace pbrt
