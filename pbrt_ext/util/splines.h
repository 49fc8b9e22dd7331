// Bézier and uniform B-spline curves (pbrt-v4's src/pbrt/util/splines.h): evaluation of a cubic
// Bézier segment and the conversions that turn every curve pbrt-v4 reads into cubic Bézier
// segments.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/vecmath.h"

#include <array>

namespace pbrt {

// The point at u of the cubic Bézier cp (de Casteljau) and, if deriv is given, dp/du. Where the
// derivative vanishes (an end whose neighbouring control point coincides with it), the
// direction toward the next distinct control point stands in for it, as in pbrt-v4.
inline Point3f EvaluateCubicBezier(const std::array<Point3f, 4> &cp, Float u,
                                   Vector3f *deriv = nullptr) {
    auto lerp = [](Float t, Point3f a, Point3f b) { return a + t * (b - a); };
    Point3f a = lerp(u, cp[0], cp[1]), b = lerp(u, cp[1], cp[2]), c = lerp(u, cp[2], cp[3]);
    Point3f d = lerp(u, a, b), e = lerp(u, b, c);
    if (deriv) {
        *deriv = 3 * (e - d);
        if (LengthSquared(*deriv) == 0)
            *deriv = u < 0.5f ? cp[2] - cp[0] : cp[3] - cp[1];
        if (LengthSquared(*deriv) == 0)
            *deriv = cp[3] - cp[0];
    }
    return lerp(u, d, e);
}

// The same curve as Bézier control points.
inline std::array<Point3f, 4> CubicBSplineToBezier(const std::array<Point3f, 4> &p) {
    auto w = [](Float a, Point3f x, Float b, Point3f y, Float c, Point3f z) {
        return Point3f(a * x.x + b * y.x + c * z.x, a * x.y + b * y.y + c * z.y,
                       a * x.z + b * y.z + c * z.z);
    };
    return {w(1.f / 6, p[0], 4.f / 6, p[1], 1.f / 6, p[2]), w(0, p[0], 2.f / 3, p[1], 1.f / 3, p[2]),
            w(0, p[0], 1.f / 3, p[1], 2.f / 3, p[2]), w(1.f / 6, p[1], 4.f / 6, p[2], 1.f / 6, p[3])};
}

inline std::array<Point3f, 3> QuadraticBSplineToBezier(const std::array<Point3f, 3> &p) {
    return {p[0] + (p[1] - p[0]) / 2, p[1], p[1] + (p[2] - p[1]) / 2};
}

// Degree elevation: the same parabola as a cubic.
inline std::array<Point3f, 4> ElevateQuadraticBezierToCubic(const std::array<Point3f, 3> &b) {
    return {b[0], b[0] + (b[1] - b[0]) * (2.f / 3), b[2] + (b[1] - b[2]) * (2.f / 3), b[2]};
}

}  // namespace pbrt
