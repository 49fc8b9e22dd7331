// Triangles (pbrt-v4's Triangle): watertight intersection, the shading frame from uv and
// vertex normals, and sampling: by area, and from a reference point uniformly in the solid angle
// the triangle subtends (Arvo), warped toward the receiver's cosine, where the solid angle suits
// it, as pbrt-v4 samples.
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/shapes/shapes_internal.h"

#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/sphericalsampling.h"

#include <cstdio>

namespace pbrt {

using namespace shapedetail;

namespace {

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

// The corners of the spherical triangle's square map to v1, v1, v0, v2.
std::array<Float, 4> TriangleCosineWarp(const SphericalTriangle &spherical, Normal3f ns) {
    return CosineWarpWeights(ns, {spherical.VertexDirection(1), spherical.VertexDirection(1),
                                  spherical.VertexDirection(0), spherical.VertexDirection(2)});
}

// pbrt-v4's default parameterization when a mesh has no uv.
std::array<Point2f, 3> TriangleUV(const TriangleMesh *mesh, const int *v) {
    if (mesh->uv.empty())
        return {Point2f(0, 0), Point2f(1, 0), Point2f(1, 1)};
    return {mesh->uv[v[0]], mesh->uv[v[1]], mesh->uv[v[2]]};
}

// How the interpolated vertex normal turns with u and v (pbrt-v4's Triangle dndu, dndv): the
// normals' differences across the edges solved like dp/du and dp/dv; with degenerate uv, any
// two directions across the normals' change.
void NormalDerivatives(const TriangleMesh *mesh, const int *v, Vector2f duv02, Vector2f duv12,
                       bool degenerateUV, SurfaceInteraction *si) {
    Normal3f n0 = mesh->n[v[0]], n1 = mesh->n[v[1]], n2 = mesh->n[v[2]];
    if (degenerateUV) {
        Vector3f dn = Cross(Vector3f(n2 - n0), Vector3f(n1 - n0));
        if (LengthSquared(dn) == 0)
            return;
        Vector3f dnu, dnv;
        CoordinateSystem(dn, &dnu, &dnv);
        si->shading.dndu = Normal3f(dnu);
        si->shading.dndv = Normal3f(dnv);
        return;
    }
    Vector3f dn1(n0 - n2), dn2(n1 - n2);
    Float invDet = 1 / DifferenceOfProducts(duv02[0], duv12[1], duv02[1], duv12[0]);
    si->shading.dndu = Normal3f((dn1 * duv12[1] - dn2 * duv02[1]) * invDet);
    si->shading.dndv = Normal3f((dn2 * duv02[0] - dn1 * duv12[0]) * invDet);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Triangle

Bounds3f Triangle::Bounds() const {
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    return Union(Bounds3f(p0, p1), p2);
}

Triangle::Triangle(const TriangleMesh *mesh, int triIndex) : mesh(mesh), triIndex(triIndex) {
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    Vector3f n = Cross(p1 - p0, p2 - p0);
    area = Length(n) / 2;
    unitNormal = Normal3f(Normalize(n));
    centroid = (p0 + p1 + p2) / 3;
    radius2 = std::max({DistanceSquared(p0, centroid), DistanceSquared(p1, centroid),
                        DistanceSquared(p2, centroid)});
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

    if (!mesh->n.empty() || !mesh->s.empty()) {
        Normal3f ns = si.n;
        if (!mesh->n.empty()) {
            ns = Interpolate(b, mesh->n[v[0]], mesh->n[v[1]], mesh->n[v[2]]);
            ns = LengthSquared(ns) > 0 ? Normalize(ns) : si.n;
        }
        Vector3f ss = si.dpdu;
        if (!mesh->s.empty()) {
            ss = Interpolate(b, mesh->s[v[0]], mesh->s[v[1]], mesh->s[v[2]]);
            if (LengthSquared(ss) == 0)
                ss = si.dpdu;
        }
        Vector3f ts = Cross(ns, ss);
        if (LengthSquared(ts) > 0)
            ss = Cross(ts, ns);
        else
            CoordinateSystem(ns, &ss, &ts);
        si.SetShadingGeometry(ns, ss, ts, true);
        if (!mesh->n.empty())
            NormalDerivatives(mesh, v, duv02, duv12, degenerateUV, &si);
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
    return SampleAt(SampleUniformTriangle(u), 1 / Area());
}

// The point at barycentrics b, sampled with density pdf.
pstd::optional<ShapeSample> Triangle::SampleAt(std::array<Float, 3> b, Float pdf) const {
    const int *v = &mesh->indices[3 * triIndex];
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    Normal3f n = unitNormal;
    // Orient n as Intersect does.
    if (!mesh->n.empty())
        n = FaceForward(n, Interpolate(b, mesh->n[v[0]], mesh->n[v[1]], mesh->n[v[2]]));
    else if (mesh->reverseOrientation ^ mesh->transformSwapsHandedness)
        n = -n;
    std::array<Point2f, 3> uv = TriangleUV(mesh, v);
    return MakeSample(Interpolate(b, p0, p1, p2), n, Interpolate(b, uv[0], uv[1], uv[2]), pdf);
}

// Whether Sample(ctx, u) samples by area from p (shapedetail's SampledByAreaFrom, about the
// centroid).
bool Triangle::SampledByAreaFrom(Point3f p) const {
    return shapedetail::SampledByAreaFrom(p, centroid, radius2);
}

pstd::optional<ShapeSample> Triangle::Sample(const ShapeSampleContext &ctx, Point2f u) const {
    if (SampledByAreaFrom(ctx.p))
        return SampleBySolidAngle(*this, ctx, u);
    SphericalTriangle spherical(Vertices(mesh, triIndex), ctx.p);
    if (!SampledBySolidAngle(spherical.Area()))
        return SampleBySolidAngle(*this, ctx, u);
    Float pdf = 1 / spherical.Area();
    if (ctx.ns != Normal3f(0, 0, 0)) {
        std::array<Float, 4> w = TriangleCosineWarp(spherical, ctx.ns);
        u = SampleBilinear(u, w);
        pdf *= BilinearPDF(u, w);
    }
    pstd::optional<std::array<Float, 3>> b = spherical.Sample(u);
    if (!b || !(pdf > 0))
        return {};
    return SampleAt(*b, pdf);
}

Float Triangle::PDF(const ShapeSampleContext &ctx, Vector3f wi) const {
    Vector3f w = Normalize(wi);
    std::array<Point3f, 3> v = Vertices(mesh, triIndex);
    auto [p0, p1, p2] = v;
    pstd::optional<TriangleHit> hit = IntersectTriangle(SpawnRay(ctx, w), Infinity, p0, p1, p2);
    if (!hit)
        return 0;
    auto areaDensity = [&] {
        return AreaToSolidAngle(1 / area, ctx.p, Interpolate(hit->b, p0, p1, p2), unitNormal, w);
    };
    if (SampledByAreaFrom(ctx.p))
        return areaDensity();
    SphericalTriangle spherical(v, ctx.p);
    if (!SampledBySolidAngle(spherical.Area()))
        return areaDensity();
    Float pdf = 1 / spherical.Area();
    if (ctx.ns != Normal3f(0, 0, 0))
        pdf *= BilinearPDF(spherical.Invert(w), TriangleCosineWarp(spherical, ctx.ns));
    return pdf;
}

std::string Triangle::ToString() const {
    auto [p0, p1, p2] = Vertices(mesh, triIndex);
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ Triangle triIndex: %d p0: (%g, %g, %g) p1: (%g, %g, %g) p2: (%g, %g, %g) ]",
                  triIndex, p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, p2.x, p2.y, p2.z);
    return buf;
}

}  // namespace pbrt
