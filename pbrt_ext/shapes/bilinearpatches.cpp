// Bilinear patches (pbrt-v4's BilinearPatch): the ray/patch intersection, the shading frame,
// areas by quadrature, and sampling: by area through the bilinear warp of the area element, and
// from a reference point, for rectangles, uniformly in their solid angle (Urena et al.) warped
// toward the receiver's cosine, as pbrt-v4 samples.
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/shapes/shapes_internal.h"

#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spherequadrature.h"
#include "pbrt_ext/util/sphericalsampling.h"

#include <cstdio>
#include <utility>
#include <vector>

namespace pbrt {

using namespace shapedetail;

namespace {

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


}  // namespace

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
                si.SetShadingGeometry(ns, sdpdu, sdpdv, true);
            } else {
                si.SetShadingGeometry(ns, dpdu, dpdv, true);
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
    Float pdf = mesh->imageDistribution ? mesh->imageDistribution->PDF(uv)
                : isRectangle          ? 1
                                       : BilinearPDF(uv, AreaWeights(p00, p10, p01, p11));
    PatchTangents d = PatchDerivatives(uv, p00, p10, p01, p11);
    return pdf / Length(Cross(d.dpdu, d.dpdv));
}

pstd::optional<ShapeSample> BilinearPatch::Sample(Point2f u) const {
    if (mesh->imageDistribution) return SampleAt(mesh->imageDistribution->Sample(u));
    auto [p00, p10, p01, p11] = Corners();
    return SampleAt(isRectangle ? u : SampleBilinear(u, AreaWeights(p00, p10, p01, p11)));
}

// The point at patch parameters uv, with the density of area sampling.
pstd::optional<ShapeSample> BilinearPatch::SampleAt(Point2f uv) const {
    const int *v = &mesh->indices[4 * patchIndex];
    auto [p00, p10, p01, p11] = Corners();
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

// A rectangle's spherical rectangle from the receiver, or nothing where area sampling serves
// (a patch that is not a rectangle or samples an emission image, a rectangle that looks small
// from p, or a solid angle outside SampledBySolidAngle's range).
pstd::optional<SphericalRectangle> BilinearPatch::SphericalFrom(Point3f p) const {
    if (!isRectangle || mesh->imageDistribution)
        return {};
    auto [p00, p10, p01, p11] = Corners();
    Point3f center = (p00 + p11) / 2;
    if (SampledByAreaFrom(p, center, DistanceSquared(p00, center)))
        return {};
    SphericalRectangle rectangle(p00, p10 - p00, p01 - p00, p);
    if (!SampledBySolidAngle(rectangle.Area()))
        return {};
    return rectangle;
}

// The corners of the spherical rectangle's square are the patch's p00, p10, p01, p11.
std::array<Float, 4> BilinearPatch::CosineWarp(const ShapeSampleContext &ctx) const {
    auto [p00, p10, p01, p11] = Corners();
    return CosineWarpWeights(ctx.ns, {Normalize(p00 - ctx.p), Normalize(p10 - ctx.p), Normalize(p01 - ctx.p),
                                      Normalize(p11 - ctx.p)});
}

pstd::optional<ShapeSample> BilinearPatch::Sample(const ShapeSampleContext &ctx,
                                                  Point2f u) const {
    pstd::optional<SphericalRectangle> rectangle = SphericalFrom(ctx.p);
    if (!rectangle)
        return SampleBySolidAngle(*this, ctx, u);
    Float pdf = 1 / rectangle->Area();
    if (ctx.ns != Normal3f(0, 0, 0)) {
        std::array<Float, 4> w = CosineWarp(ctx);
        u = SampleBilinear(u, w);
        pdf *= BilinearPDF(u, w);
    }
    pstd::optional<ShapeSample> ss = SampleAt(rectangle->Sample(u));
    if (!ss || !(pdf > 0))
        return {};
    ss->pdf = pdf;
    return ss;
}

Float BilinearPatch::PDF(const ShapeSampleContext &ctx, Vector3f wi) const {
    Vector3f w = Normalize(wi);
    auto [p00, p10, p01, p11] = Corners();
    pstd::optional<BilinearIntersection> hit =
        IntersectBilinearPatch(SpawnRay(ctx, w), Infinity, p00, p10, p01, p11);
    if (!hit)
        return 0;
    if (pstd::optional<SphericalRectangle> rectangle = SphericalFrom(ctx.p)) {
        Float pdf = 1 / rectangle->Area();
        if (ctx.ns != Normal3f(0, 0, 0))
            pdf *= BilinearPDF(rectangle->Invert(hit->uv), CosineWarp(ctx));
        return pdf;
    }
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
