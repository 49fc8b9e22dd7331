#include "pbrt_ext/shapes/curves.h"

#include "pbrt_ext/shapes/shapes_internal.h"
#include "pbrt_ext/util/splines.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace pbrt {

namespace {

// The curve's segments as cubic Bézier control points (pbrt-v4's Curve::Create): a Bézier
// curve's segments share their end points, a uniform B-spline's overlap by all but one point.
std::vector<std::array<Point3f, 4>> BezierSegments(const CurveDescription &c) {
    const std::vector<Point3f> &p = c.p;
    int d = c.degree;
    std::vector<std::array<Point3f, 4>> segments;
    if (c.basis == "bezier") {
        if (p.size() < size_t(d + 1) || (p.size() - 1 - d) % d != 0)
            throw std::runtime_error(fmt::format(
                "curve: {} control points; the degree {} Bézier basis needs {} + n * {}, n >= 0",
                p.size(), d, d + 1, d));
        for (size_t i = 0; i + d < p.size(); i += d)
            segments.push_back(d == 3 ? std::array<Point3f, 4>{p[i], p[i + 1], p[i + 2], p[i + 3]}
                                      : ElevateQuadraticBezierToCubic({p[i], p[i + 1], p[i + 2]}));
        return segments;
    }
    if (p.size() < size_t(d + 1))
        throw std::runtime_error(fmt::format(
            "curve: {} control points; the degree {} B-spline basis needs at least {}", p.size(),
            d, d + 1));
    for (size_t i = 0; i + d < p.size(); ++i)
        segments.push_back(
            d == 3 ? CubicBSplineToBezier({p[i], p[i + 1], p[i + 2], p[i + 3]})
                   : ElevateQuadraticBezierToCubic(QuadraticBSplineToBezier({p[i], p[i + 1], p[i + 2]})));
    return segments;
}

void Check(const CurveDescription &c) {
    if (c.degree != 2 && c.degree != 3)
        throw std::runtime_error(fmt::format("curve \"degree\" {}; expected 2 or 3", c.degree));
    if (c.basis != "bezier" && c.basis != "bspline")
        throw std::runtime_error("curve \"basis\" \"" + c.basis +
                                 "\" is unknown; expected \"bezier\" or \"bspline\"");
    for (Float w : {c.width0, c.width1})
        if (!(w >= 0) || !IsFinite(w))
            throw std::runtime_error(
                fmt::format("curve width {}; expected a finite width >= 0", w));
}

// Spherical interpolation of unit normals, as pbrt-v4 turns a ribbon along a segment.
Normal3f SlerpNormal(Float u, Normal3f n0, Normal3f n1) {
    Float angle = std::acos(Clamp(Dot(n0, n1), -1, 1));
    if (angle < 1e-4f)
        return n0;
    Float s = std::sin(angle);
    return Normal3f(std::sin((1 - u) * angle) / s * Vector3f(n0) +
                    std::sin(u * angle) / s * Vector3f(n1));
}

// A unit vector perpendicular to w.
Vector3f AnyPerpendicular(Vector3f w) {
    return Normalize(std::abs(w.x) > std::abs(w.z) ? Vector3f(-w.y, w.x, 0)
                                                    : Vector3f(0, -w.z, w.y));
}

}  // namespace

CurveMesh MakeCurveMesh(const Transform &worldFromObject, bool reverseOrientation,
                        const CurveDescription &curve) {
    Check(curve);
    std::vector<std::array<Point3f, 4>> segments = BezierSegments(curve);
    int nSegments = int(segments.size());
    if (curve.type == CurveType::Ribbon && curve.n.size() != size_t(nSegments + 1))
        throw std::runtime_error(fmt::format(
            "ribbon curve: {} normals \"N\" for {} segments; expected one per segment end, {}",
            curve.n.size(), nSegments, nSegments + 1));
    CurveMesh mesh;
    mesh.type = curve.type;
    mesh.reverseOrientation = reverseOrientation;
    mesh.transformSwapsHandedness = worldFromObject.SwapsHandedness();
    Float scale = std::cbrt(shapedetail::AbsDeterminant(worldFromObject));
    for (int s = 0; s < nSegments; ++s) {
        for (Point3f p : segments[s])
            mesh.cp.push_back(worldFromObject(p));
        for (int end = 0; end < 2; ++end)
            mesh.width.push_back(
                scale * Lerp(Float(s + end) / Float(nSegments), curve.width0, curve.width1));
        if (curve.type == CurveType::Ribbon)
            for (int end = 0; end < 2; ++end) {
                Normal3f n = worldFromObject(curve.n[s + end]);
                if (LengthSquared(n) == 0)
                    throw std::runtime_error(fmt::format("ribbon curve: normal {} is zero", s + end));
                mesh.n.push_back(Normalize(n));
            }
    }
    return mesh;
}

SurfaceInteraction CurveInteraction(const CurveMesh &mesh, int segment, Float u, const Ray &ray,
                                    Float t) {
    std::array<Point3f, 4> cp = {mesh.cp[4 * segment], mesh.cp[4 * segment + 1],
                                 mesh.cp[4 * segment + 2], mesh.cp[4 * segment + 3]};
    u = Clamp(u, 0, 1);
    Vector3f dpdu;
    Point3f center = EvaluateCubicBezier(cp, u, &dpdu);
    Float width = Lerp(u, mesh.width[2 * segment], mesh.width[2 * segment + 1]);
    Point3f p = ray(t);
    // The direction across the curve: along the ribbon, or facing the ray (pbrt-v4's dpdv in
    // the plane perpendicular to the ray); v is the side and distance from the centre line.
    Vector3f across;
    if (mesh.type == CurveType::Ribbon) {
        Normal3f nHit = SlerpNormal(u, mesh.n[2 * segment], mesh.n[2 * segment + 1]);
        across = Cross(Vector3f(nHit), dpdu);
    } else {
        across = Cross(Normalize(ray.d), dpdu);
    }
    across = LengthSquared(across) > 0 ? Normalize(across) : AnyPerpendicular(Normalize(dpdu));
    Float v = width > 0 ? Clamp(0.5f + Dot(p - center, across) / width, 0, 1) : 0.5f;
    Vector3f dpdv = across * width;
    if (mesh.type == CurveType::Cylinder)
        dpdv = Rotate(-Lerp(v, -90, 90), dpdu)(dpdv);  // the round look of pbrt-v4's cylinders
    if (LengthSquared(dpdv) == 0)
        dpdv = across;  // a curve of zero width still has a frame
    SurfaceInteraction si = shapedetail::MakeInteraction(
        p, Point2f(u, v), -Normalize(ray.d), dpdu, dpdv,
        mesh.reverseOrientation ^ mesh.transformSwapsHandedness);
    si.errorBound = width;
    return si;
}

std::string CurveMesh::ToString() const {
    const char *names[] = {"flat", "cylinder", "ribbon"};
    return fmt::format("[ CurveMesh type: {} segments: {} reverseOrientation: {} "
                       "transformSwapsHandedness: {} ]",
                       names[int(type)], NumSegments(), reverseOrientation,
                       transformSwapsHandedness);
}

}  // namespace pbrt
