// Uniform sampling of the solid angle a triangle or a rectangle subtends (pbrt-v4's
// SampleSphericalTriangle/InvertSphericalTriangleSample, after Arvo, "Stratified Sampling of
// Spherical Triangles", SIGGRAPH 1995; and SampleSphericalRectangle/InvertSphericalRectangleSample,
// after Urena, Fajardo and King, "An Area-Preserving Parametrization for Spherical Rectangles",
// EGSR 2013), each as one class. The arithmetic is in double: the spherical excess of a small
// polygon is the difference of nearly equal angles, and sample and inverse must agree.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"
#include "pbrt_ext/util/pstd.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace pbrt {

namespace spherical {

// Directions in double; vecmath.h's operations serve them as they serve Vector3f.
using Vector3d = Vector3<double>;

// v's component orthogonal to unit w, normalized.
inline Vector3d Orthogonal(Vector3d v, Vector3d w) { return Normalize(GramSchmidt(v, w)); }
// The sum of the angles a-b and c-d, each in [0, pi], with one atan2: the argument of the
// product of (cos, sin) pairs, taken in [0, 2 pi).
inline double SumOfAngles(Vector3d a, Vector3d b, Vector3d c, Vector3d d) {
    double cos0 = Dot(a, b), sin0 = Length(Cross(a, b)), cos1 = Dot(c, d), sin1 = Length(Cross(c, d));
    double angle = std::atan2(sin0 * cos1 + cos0 * sin1, cos0 * cos1 - sin0 * sin1);
    return angle < 0 ? angle + 2 * Pi : angle;
}

// The solid angle of the spherical triangle with unit vertices a, b, c (Van Oosterom and
// Strackee's formula: no cancellation for small triangles).
inline double TriangleArea(Vector3d a, Vector3d b, Vector3d c) {
    return std::abs(2 * std::atan2(Dot(a, Cross(b, c)), 1 + Dot(a, b) + Dot(a, c) + Dot(b, c)));
}

}  // namespace spherical

// Triangle v as seen from p: the unit directions to its vertices and the solid angle they
// enclose, computed once for the sample, its density and the receiver's cosine warp.
class SphericalTriangle {
  public:
    SphericalTriangle(const std::array<Point3f, 3> &v, Point3f p) : v(v), p(p) {
        using namespace spherical;
        for (int i = 0; i < 3; ++i) {
            d[i] = Vector3d(v[i] - p);
            double length = Length(d[i]);
            if (length == 0) return;  // p on a vertex: area stays 0
            d[i] /= length;
        }
        area = TriangleArea(d[0], d[1], d[2]);
    }

    // The solid angle, 0 for a degenerate triangle or a p on a vertex.
    Float Area() const { return Float(area); }
    // The unit direction from p to vertex i, valid where Area() > 0.
    Vector3f VertexDirection(int i) const { return Vector3f(d[i]); }

    // The barycentrics of the point seen from p in a direction uniform over the solid angle
    // (density 1 / Area()). u0 picks the sub-triangle (v0, v1, c') of area u0 times the whole,
    // c' on the arc from v0 to v2; u1 the point on the arc from v1 (u1 = 0) to c' (u1 = 1) by
    // the cosine of its angle to v1. Empty where Area() is 0.
    pstd::optional<std::array<Float, 3>> Sample(Point2f u) const {
        using namespace spherical;
        Vector3d a = d[0], b = d[1], c = d[2];
        Vector3d nab = Cross(a, b), nac = Cross(a, c);
        if (!(area > 0) || Length(nab) == 0 || Length(nac) == 0) return {};
        // The triangle's angle alpha at a, between the planes of its two edges there, as its
        // cosine and sine.
        double normAlpha = Length(nab) * Length(nac);
        double cosAlpha = Dot(nab, nac) / normAlpha, sinAlpha = Length(Cross(nab, nac)) / normAlpha;
        // Arvo's closed form for c': the sub-triangle's excess fixes the angle at b, and with
        // it the cosine q of the arc from a to c'. s and t are the sine and cosine of
        // u0 area - alpha, by the difference formulas (one sincos instead of an atan2 and two).
        double sinPhi = std::sin(u[0] * area), cosPhi = std::cos(u[0] * area);
        double s = sinPhi * cosAlpha - cosPhi * sinAlpha, t = cosPhi * cosAlpha + sinPhi * sinAlpha;
        double k1 = t - cosAlpha, k2 = s + sinAlpha * Dot(a, b);
        double q = ((k2 * t - k1 * s) * cosAlpha - k2) / ((k2 * s + k1 * t) * sinAlpha);
        q = std::clamp(std::isfinite(q) ? q : 1.0, -1.0, 1.0);
        Vector3d cPrime = q * a + std::sqrt(std::max(0.0, 1 - q * q)) * Orthogonal(c, a);

        double z = 1 - u[1] * (1 - Dot(cPrime, b));
        Vector3d w = z * b + std::sqrt(std::max(0.0, 1 - z * z)) * Orthogonal(cPrime, b);
        if (!std::isfinite(w.x + w.y + w.z)) w = b;

        // Where the ray p + t w meets the triangle's plane (Cramer's rule on its edges).
        Vector3d e1 = Vector3d(v[1] - v[0]), e2 = Vector3d(v[2] - v[0]), sp = Vector3d(p - v[0]);
        Vector3d s1 = Cross(w, e2);
        double divisor = Dot(s1, e1);
        if (divisor == 0) return {};
        double b1 = std::clamp(Dot(sp, s1) / divisor, 0.0, 1.0);
        double b2 = std::clamp(Dot(w, Cross(sp, e1)) / divisor, 0.0, 1.0);
        if (b1 + b2 > 1) {
            double sum = b1 + b2;
            b1 /= sum;
            b2 /= sum;
        }
        return std::array<Float, 3>{Float(1 - b1 - b2), Float(b1), Float(b2)};
    }

    // The u that Sample maps to direction wi (toward the triangle from p): c' is where the
    // great circle through v1 and wi crosses the arc from v0 to v2.
    Point2f Invert(Vector3f wi) const {
        using namespace spherical;
        Vector3d a = d[0], b = d[1], c = d[2], w = Normalize(Vector3d(wi));
        if (!(area > 0)) return {};
        Vector3d cPrime = Cross(Cross(b, w), Cross(c, a));
        if (Length(cPrime) == 0) return {};
        cPrime = Normalize(cPrime);
        if (Dot(cPrime, a + c) < 0) cPrime = -cPrime;
        double u0 = TriangleArea(a, b, cPrime) / area;
        double denominator = 1 - Dot(cPrime, b);
        double u1 = denominator > 0 ? (1 - Dot(w, b)) / denominator : 0;
        return Point2f(Float(std::clamp(u0, 0.0, 1.0)), Float(std::clamp(u1, 0.0, 1.0)));
    }

  private:
    std::array<Point3f, 3> v;
    Point3f p;
    spherical::Vector3d d[3];
    double area = 0;
};

// The rectangle with corner s and orthogonal edges ex and ey as seen from p, in the frame of its
// edges (x along ex, y along ey, z toward p's side, the rectangle at height z0 < 0 below p).
// Points are given as fractions (s, t) along ex and ey: a rectangular bilinear patch's (u, v).
class SphericalRectangle {
  public:
    SphericalRectangle(Point3f s, Vector3f ex, Vector3f ey, Point3f p) {
        using namespace spherical;
        double exLength = Length(Vector3d(ex)), eyLength = Length(Vector3d(ey));
        if (exLength == 0 || eyLength == 0) return;
        Vector3d x = Vector3d(ex) / exLength, y = Vector3d(ey) / eyLength, z = Cross(x, y);
        Vector3d d(s - p);
        z0 = -std::abs(Dot(d, z));
        if (z0 == 0) return;  // p in the rectangle's plane: it subtends nothing
        x0 = Dot(d, x);
        y0 = Dot(d, y);
        x1 = x0 + exLength;
        y1 = y0 + eyLength;
        // The planes through p and each edge, and the angles between neighbouring ones.
        Vector3d v00{x0, y0, z0}, v01{x0, y1, z0}, v10{x1, y0, z0}, v11{x1, y1, z0};
        Vector3d n0 = Normalize(Cross(v00, v10)), n1 = Normalize(Cross(v10, v11));
        Vector3d n2 = Normalize(Cross(v11, v01)), n3 = Normalize(Cross(v01, v00));
        // Sample needs only the sums g0 + g1 and g2 + g3 of the four angles.
        double g01 = SumOfAngles(-n0, n1, -n1, n2), g23 = SumOfAngles(-n2, n3, -n3, n0);
        b0 = n0.z;
        b1 = n2.z;
        k = 2 * Pi - g23;
        area = std::max(0.0, g01 - k);
    }

    // The solid angle, 0 for a degenerate rectangle or a p in its plane.
    Float Area() const { return Float(area); }

    // The point, as edge fractions, seen from p in a direction uniform over the solid angle
    // (density 1 / Area()): u0 picks the column x whose left part [x0, x] subtends u0 times the
    // whole, u1 the height along it uniformly in the sine of its elevation.
    Point2f Sample(Point2f u) const {
        double au = u[0] * area + k;
        double fu = (std::cos(au) * b0 - b1) / std::sin(au);
        double cu = std::clamp(std::copysign(1.0, fu) / std::sqrt(fu * fu + b0 * b0), -1.0, 1.0);
        double sinCu = std::sqrt(std::max(0.0, 1 - cu * cu));
        double xu = sinCu > 0 ? std::clamp(-cu * z0 / sinCu, x0, x1) : (cu < 0 ? x0 : x1);
        double dd = std::sqrt(xu * xu + z0 * z0);
        double h0 = y0 / std::sqrt(dd * dd + y0 * y0), h1 = y1 / std::sqrt(dd * dd + y1 * y1);
        double hv = h0 + u[1] * (h1 - h0), hv2 = hv * hv;
        double yv = hv2 < 1 ? std::clamp(hv * dd / std::sqrt(1 - hv2), y0, y1) : y1;
        return Point2f(Float((xu - x0) / (x1 - x0)), Float((yv - y0) / (y1 - y0)));
    }

    // The u that Sample maps to the point at edge fractions st: u0 from the solid angle of the
    // part left of its column (two spherical triangles), u1 from its elevation.
    Point2f Invert(Point2f st) const {
        using namespace spherical;
        if (!(area > 0)) return {};
        double xu = x0 + st[0] * (x1 - x0), yv = y0 + st[1] * (y1 - y0);
        double dd = std::sqrt(xu * xu + z0 * z0);
        double h0 = y0 / std::sqrt(dd * dd + y0 * y0), h1 = y1 / std::sqrt(dd * dd + y1 * y1);
        double hv = yv / std::sqrt(dd * dd + yv * yv);
        double u1 = h1 != h0 ? (hv - h0) / (h1 - h0) : 0;
        Vector3d a = Normalize(Vector3d(x0, y0, z0)), b = Normalize(Vector3d(xu, y0, z0));
        Vector3d c = Normalize(Vector3d(xu, y1, z0)), e = Normalize(Vector3d(x0, y1, z0));
        double u0 = (TriangleArea(a, b, c) + TriangleArea(a, c, e)) / area;
        return Point2f(Float(std::clamp(u0, 0.0, 1.0)), Float(std::clamp(u1, 0.0, 1.0)));
    }

  private:
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0, z0 = 0, b0 = 0, b1 = 0, k = 0, area = 0;
};

}  // namespace pbrt
