// Axis-aligned boxes in 2D and 3D (pbrt-v4's Bounds2/Bounds3 from util/vecmath.h, reduced).
//
// As in pbrt-v4, a default-constructed box is empty (pMin > pMax), so that Union with it is the
// identity; Inside treats pMax as included, InsideExclusive as excluded (integer pixel bounds
// are half-open: [pMin, pMax)).
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <limits>

namespace pbrt {

namespace detail {
// Component-wise extremes of points; kept local so that vecmath.h stays the only place that
// may later define pbrt-v4's general Min/Max.
template <template <typename> class P, typename T, int N>
PBRT_CPU_GPU constexpr P<T> ComponentMin(const Tuple<P, T, N> &a, const Tuple<P, T, N> &b) {
    P<T> r;
    for (int i = 0; i < N; ++i) r[i] = std::min(a[i], b[i]);
    return r;
}
template <template <typename> class P, typename T, int N>
PBRT_CPU_GPU constexpr P<T> ComponentMax(const Tuple<P, T, N> &a, const Tuple<P, T, N> &b) {
    P<T> r;
    for (int i = 0; i < N; ++i) r[i] = std::max(a[i], b[i]);
    return r;
}
}  // namespace detail

template <typename T>
class Bounds2 {
  public:
    PBRT_CPU_GPU Bounds2() {
        T minNum = std::numeric_limits<T>::lowest(), maxNum = std::numeric_limits<T>::max();
        pMin = Point2<T>(maxNum, maxNum);
        pMax = Point2<T>(minNum, minNum);
    }
    PBRT_CPU_GPU explicit Bounds2(Point2<T> p) : pMin(p), pMax(p) {}
    PBRT_CPU_GPU Bounds2(Point2<T> p1, Point2<T> p2)
        : pMin(detail::ComponentMin(p1, p2)), pMax(detail::ComponentMax(p1, p2)) {}
    template <typename U>
    PBRT_CPU_GPU explicit Bounds2(const Bounds2<U> &b) {
        if (b.IsEmpty()) {
            *this = Bounds2<T>();
        } else {
            pMin = Point2<T>(b.pMin);
            pMax = Point2<T>(b.pMax);
        }
    }

    PBRT_CPU_GPU Point2<T> operator[](int i) const { return i == 0 ? pMin : pMax; }
    PBRT_CPU_GPU Point2<T> &operator[](int i) { return i == 0 ? pMin : pMax; }
    PBRT_CPU_GPU Point2<T> Corner(int corner) const {
        return Point2<T>((*this)[corner & 1].x, (*this)[(corner & 2) ? 1 : 0].y);
    }

    PBRT_CPU_GPU Vector2<T> Diagonal() const { return pMax - pMin; }
    PBRT_CPU_GPU T Area() const {
        Vector2<T> d = Diagonal();
        return d.x * d.y;
    }
    PBRT_CPU_GPU int MaxDimension() const {
        Vector2<T> d = Diagonal();
        return d.x > d.y ? 0 : 1;
    }
    PBRT_CPU_GPU bool IsEmpty() const { return pMin.x >= pMax.x || pMin.y >= pMax.y; }
    PBRT_CPU_GPU bool IsDegenerate() const { return pMin.x > pMax.x || pMin.y > pMax.y; }

    // The point at fractional position t (0: pMin, 1: pMax) along each axis.
    PBRT_CPU_GPU Point2<T> Lerp(Point2f t) const {
        return Point2<T>(pbrt::Lerp(t.x, pMin.x, pMax.x), pbrt::Lerp(t.y, pMin.y, pMax.y));
    }
    // The inverse of Lerp: p's fractional position, 0 on degenerate axes.
    PBRT_CPU_GPU Vector2<T> Offset(Point2<T> p) const {
        Vector2<T> o = p - pMin;
        if (pMax.x > pMin.x) o.x /= pMax.x - pMin.x;
        if (pMax.y > pMin.y) o.y /= pMax.y - pMin.y;
        return o;
    }

    PBRT_CPU_GPU bool operator==(const Bounds2<T> &b) const { return b.pMin == pMin && b.pMax == pMax; }
    PBRT_CPU_GPU bool operator!=(const Bounds2<T> &b) const { return !(*this == b); }

    Point2<T> pMin, pMax;
};

template <typename T>
class Bounds3 {
  public:
    PBRT_CPU_GPU Bounds3() {
        T minNum = std::numeric_limits<T>::lowest(), maxNum = std::numeric_limits<T>::max();
        pMin = Point3<T>(maxNum, maxNum, maxNum);
        pMax = Point3<T>(minNum, minNum, minNum);
    }
    PBRT_CPU_GPU explicit Bounds3(Point3<T> p) : pMin(p), pMax(p) {}
    PBRT_CPU_GPU Bounds3(Point3<T> p1, Point3<T> p2)
        : pMin(detail::ComponentMin(p1, p2)), pMax(detail::ComponentMax(p1, p2)) {}

    PBRT_CPU_GPU Point3<T> operator[](int i) const { return i == 0 ? pMin : pMax; }
    PBRT_CPU_GPU Point3<T> &operator[](int i) { return i == 0 ? pMin : pMax; }
    // Corner bits: 1 selects pMax.x, 2 pMax.y, 4 pMax.z.
    PBRT_CPU_GPU Point3<T> Corner(int corner) const {
        return Point3<T>((*this)[corner & 1].x, (*this)[(corner & 2) ? 1 : 0].y,
                         (*this)[(corner & 4) ? 1 : 0].z);
    }

    PBRT_CPU_GPU Vector3<T> Diagonal() const { return pMax - pMin; }
    PBRT_CPU_GPU T SurfaceArea() const {
        Vector3<T> d = Diagonal();
        return 2 * (d.x * d.y + d.x * d.z + d.y * d.z);
    }
    PBRT_CPU_GPU T Volume() const {
        Vector3<T> d = Diagonal();
        return d.x * d.y * d.z;
    }
    PBRT_CPU_GPU int MaxDimension() const {
        Vector3<T> d = Diagonal();
        if (d.x > d.y && d.x > d.z) return 0;
        return d.y > d.z ? 1 : 2;
    }
    PBRT_CPU_GPU bool IsEmpty() const {
        return pMin.x >= pMax.x || pMin.y >= pMax.y || pMin.z >= pMax.z;
    }
    PBRT_CPU_GPU bool IsDegenerate() const {
        return pMin.x > pMax.x || pMin.y > pMax.y || pMin.z > pMax.z;
    }

    PBRT_CPU_GPU Point3<T> Lerp(Point3f t) const {
        return Point3<T>(pbrt::Lerp(t.x, pMin.x, pMax.x), pbrt::Lerp(t.y, pMin.y, pMax.y),
                         pbrt::Lerp(t.z, pMin.z, pMax.z));
    }
    PBRT_CPU_GPU Vector3<T> Offset(Point3<T> p) const {
        Vector3<T> o = p - pMin;
        for (int i = 0; i < 3; ++i)
            if (pMax[i] > pMin[i]) o[i] /= pMax[i] - pMin[i];
        return o;
    }

    // The parametric range [*hitt0, *hitt1] within [0, tMax] where the ray o + t d is inside the
    // box (the slab test, as pbrt-v4's Bounds3::IntersectP); false if it misses. Division by a
    // zero direction component gives infinities that the comparisons handle.
    PBRT_CPU_GPU bool IntersectP(Point3f o, Vector3f d, Float tMax, Float *hitt0,
                                 Float *hitt1) const {
        Float t0 = 0, t1 = tMax;
        for (int i = 0; i < 3; ++i) {
            Float invD = 1 / d[i];
            Float tNear = (pMin[i] - o[i]) * invD, tFar = (pMax[i] - o[i]) * invD;
            if (tNear > tFar) std::swap(tNear, tFar);
            // pbrt-v4's 1 + 2 gamma(3): keeps a ray grazing a face from missing it by rounding.
            tFar *= 1 + 2 * 3 * std::numeric_limits<Float>::epsilon() * 0.5f;
            t0 = tNear > t0 ? tNear : t0;
            t1 = tFar < t1 ? tFar : t1;
            if (t0 > t1) return false;
        }
        *hitt0 = t0;
        *hitt1 = t1;
        return true;
    }

    // The sphere through the corners (used to size infinite lights, as pbrt-v4).
    PBRT_CPU_GPU void BoundingSphere(Point3<T> *center, Float *radius) const {
        *center = pMin + (pMax - pMin) / T(2);
        *radius = Inside(*center, *this) ? Distance(*center, pMax) : 0;
    }

    PBRT_CPU_GPU bool operator==(const Bounds3<T> &b) const { return b.pMin == pMin && b.pMax == pMax; }
    PBRT_CPU_GPU bool operator!=(const Bounds3<T> &b) const { return !(*this == b); }

    Point3<T> pMin, pMax;
};

using Bounds2f = Bounds2<Float>;
using Bounds2i = Bounds2<int>;
using Bounds3f = Bounds3<Float>;
using Bounds3i = Bounds3<int>;

// Set operations; B is Bounds2 or Bounds3 where one template serves both.
template <typename T>
PBRT_CPU_GPU Bounds2<T> Union(const Bounds2<T> &b, Point2<T> p) {
    Bounds2<T> r;
    r.pMin = detail::ComponentMin(b.pMin, p);
    r.pMax = detail::ComponentMax(b.pMax, p);
    return r;
}
template <typename T>
PBRT_CPU_GPU Bounds3<T> Union(const Bounds3<T> &b, Point3<T> p) {
    Bounds3<T> r;
    r.pMin = detail::ComponentMin(b.pMin, p);
    r.pMax = detail::ComponentMax(b.pMax, p);
    return r;
}
template <template <typename> class B, typename T>
PBRT_CPU_GPU B<T> Union(const B<T> &b1, const B<T> &b2) {
    B<T> r;
    r.pMin = detail::ComponentMin(b1.pMin, b2.pMin);
    r.pMax = detail::ComponentMax(b1.pMax, b2.pMax);
    return r;
}
// Empty (IsEmpty) when the boxes do not overlap.
template <template <typename> class B, typename T>
PBRT_CPU_GPU B<T> Intersect(const B<T> &b1, const B<T> &b2) {
    B<T> r;
    r.pMin = detail::ComponentMax(b1.pMin, b2.pMin);
    r.pMax = detail::ComponentMin(b1.pMax, b2.pMax);
    return r;
}
template <template <typename> class B, typename T>
PBRT_CPU_GPU bool Overlaps(const B<T> &b1, const B<T> &b2) {
    for (int i = 0; i < decltype(b1.pMin)::nDimensions; ++i)
        if (b1.pMax[i] < b2.pMin[i] || b1.pMin[i] > b2.pMax[i]) return false;
    return true;
}
template <typename P, template <typename> class B, typename T>
PBRT_CPU_GPU bool Inside(const P &p, const B<T> &b) {
    for (int i = 0; i < P::nDimensions; ++i)
        if (!(p[i] >= b.pMin[i] && p[i] <= b.pMax[i])) return false;
    return true;
}
template <typename P, template <typename> class B, typename T>
PBRT_CPU_GPU bool InsideExclusive(const P &p, const B<T> &b) {
    for (int i = 0; i < P::nDimensions; ++i)
        if (!(p[i] >= b.pMin[i] && p[i] < b.pMax[i])) return false;
    return true;
}
template <template <typename> class B, typename T, typename U>
PBRT_CPU_GPU B<T> Expand(const B<T> &b, U delta) {
    B<T> r;
    for (int i = 0; i < decltype(b.pMin)::nDimensions; ++i) {
        r.pMin[i] = b.pMin[i] - delta;
        r.pMax[i] = b.pMax[i] + delta;
    }
    return r;
}

// Iteration over the pixels of a half-open Bounds2i, x fastest, as pbrt-v4's
// `for (Point2i p : bounds)`.
class Bounds2iIterator {
  public:
    PBRT_CPU_GPU Bounds2iIterator(const Bounds2i &b, Point2i pt) : p(pt), bounds(&b) {}
    PBRT_CPU_GPU Bounds2iIterator &operator++() {
        if (++p.x == bounds->pMax.x) {
            p.x = bounds->pMin.x;
            ++p.y;
        }
        return *this;
    }
    PBRT_CPU_GPU bool operator==(const Bounds2iIterator &b) const { return p == b.p && bounds == b.bounds; }
    PBRT_CPU_GPU bool operator!=(const Bounds2iIterator &b) const { return !(*this == b); }
    PBRT_CPU_GPU Point2i operator*() const { return p; }

  private:
    Point2i p;
    const Bounds2i *bounds;
};

PBRT_CPU_GPU inline Bounds2iIterator begin(const Bounds2i &b) {
    return Bounds2iIterator(b, b.pMin);
}
// An empty box ends where it begins, so the loop body never runs.
PBRT_CPU_GPU inline Bounds2iIterator end(const Bounds2i &b) {
    Point2i pEnd(b.pMin.x, b.pMax.y);
    if (b.pMin.x >= b.pMax.x || b.pMin.y >= b.pMax.y) pEnd = b.pMin;
    return Bounds2iIterator(b, pEnd);
}

}  // namespace pbrt
