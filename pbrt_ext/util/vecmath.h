// pbrt_ext: vectors, points, normals and frames (pbrt-v4's util/vecmath.h, reduced).
// As in pbrt-v4 the types are distinct so that the type algebra catches mistakes:
// Point - Point = Vector, Point + Vector = Point; converting between kinds is explicit.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"

#include <cmath>
#include <type_traits>

namespace pbrt {

namespace detail {
// The named members x, y (, z) of pbrt-v4's Tuple2/Tuple3; Tuple writes the arithmetic once
// for both sizes by indexing.
template <typename T, int N>
struct TupleStorage;

template <typename T>
struct TupleStorage<T, 2> {
    T x{}, y{};
    TupleStorage() = default;
    PBRT_CPU_GPU constexpr TupleStorage(T x0, T y0) : x(x0), y(y0) {}
    PBRT_CPU_GPU constexpr T &Component(int i) { return i == 0 ? x : y; }
    PBRT_CPU_GPU constexpr const T &Component(int i) const { return i == 0 ? x : y; }
};

template <typename T>
struct TupleStorage<T, 3> {
    T x{}, y{}, z{};
    TupleStorage() = default;
    PBRT_CPU_GPU constexpr TupleStorage(T x0, T y0, T z0) : x(x0), y(y0), z(z0) {}
    PBRT_CPU_GPU constexpr T &Component(int i) { return i == 0 ? x : (i == 1 ? y : z); }
    PBRT_CPU_GPU constexpr const T &Component(int i) const {
        return i == 0 ? x : (i == 1 ? y : z);
    }
};
}  // namespace detail

// Component-wise arithmetic shared by all kinds; Child is the concrete kind (CRTP), so that
// Vector + Vector is a Vector and Normal * Float a Normal.
template <template <typename> class Child, typename T, int N>
class Tuple : public detail::TupleStorage<T, N> {
  public:
    using ElementType = T;
    static constexpr int nDimensions = N;

    using detail::TupleStorage<T, N>::TupleStorage;
    Tuple() = default;
    // Changing the kind (or element type) is explicit, as in pbrt-v4's Vector3f(Point3f p).
    template <template <typename> class Other, typename U>
    PBRT_CPU_GPU constexpr explicit Tuple(const Tuple<Other, U, N> &other) {
        for (int i = 0; i < N; ++i) (*this)[i] = T(other[i]);
    }

    PBRT_CPU_GPU constexpr T operator[](int i) const { return this->Component(i); }
    PBRT_CPU_GPU constexpr T &operator[](int i) { return this->Component(i); }

    PBRT_CPU_GPU constexpr Child<T> &operator+=(const Child<T> &c) {
        for (int i = 0; i < N; ++i) (*this)[i] += c[i];
        return Self();
    }
    PBRT_CPU_GPU constexpr Child<T> &operator-=(const Child<T> &c) {
        for (int i = 0; i < N; ++i) (*this)[i] -= c[i];
        return Self();
    }
    PBRT_CPU_GPU constexpr Child<T> &operator*=(T s) {
        for (int i = 0; i < N; ++i) (*this)[i] *= s;
        return Self();
    }
    PBRT_CPU_GPU constexpr Child<T> &operator/=(T s) {
        for (int i = 0; i < N; ++i) (*this)[i] /= s;
        return Self();
    }

    PBRT_CPU_GPU constexpr Child<T> operator+(const Child<T> &c) const { return Child<T>(Self()) += c; }
    PBRT_CPU_GPU constexpr Child<T> operator-(const Child<T> &c) const { return Child<T>(Self()) -= c; }
    PBRT_CPU_GPU constexpr Child<T> operator*(T s) const { return Child<T>(Self()) *= s; }
    PBRT_CPU_GPU constexpr Child<T> operator/(T s) const { return Child<T>(Self()) /= s; }
    PBRT_CPU_GPU constexpr Child<T> operator-() const { return Child<T>(Self()) *= T(-1); }

    PBRT_CPU_GPU friend constexpr Child<T> operator*(T s, const Child<T> &c) { return c * s; }
    // Hidden friends with symmetric parameters, so C++20's reversed candidates are not ambiguous.
    PBRT_CPU_GPU friend constexpr bool operator==(const Child<T> &a, const Child<T> &b) {
        for (int i = 0; i < N; ++i)
            if (a[i] != b[i]) return false;
        return true;
    }
    PBRT_CPU_GPU friend constexpr bool operator!=(const Child<T> &a, const Child<T> &b) { return !(a == b); }

  private:
    PBRT_CPU_GPU constexpr Child<T> &Self() { return static_cast<Child<T> &>(*this); }
    PBRT_CPU_GPU constexpr const Child<T> &Self() const { return static_cast<const Child<T> &>(*this); }
};

// Points add the affine operations with their vector kind V on top of Tuple's.
template <template <typename> class P, template <typename> class V, typename T, int N>
class PointTuple : public Tuple<P, T, N> {
    using Base = Tuple<P, T, N>;

  public:
    using Base::Base;
    using Base::operator+;
    using Base::operator+=;
    using Base::operator-;
    using Base::operator-=;

    PBRT_CPU_GPU constexpr P<T> &operator+=(const V<T> &v) { return Base::operator+=(P<T>(v)); }
    PBRT_CPU_GPU constexpr P<T> &operator-=(const V<T> &v) { return Base::operator-=(P<T>(v)); }
    PBRT_CPU_GPU constexpr P<T> operator+(const V<T> &v) const { return Base::operator+(P<T>(v)); }
    PBRT_CPU_GPU constexpr P<T> operator-(const V<T> &v) const { return Base::operator-(P<T>(v)); }
    PBRT_CPU_GPU constexpr V<T> operator-(const P<T> &p) const { return V<T>(Base::operator-(p)); }
};

template <typename T>
class Vector2 : public Tuple<Vector2, T, 2> {
  public:
    using Tuple<Vector2, T, 2>::Tuple;
};
template <typename T>
class Point2 : public PointTuple<Point2, Vector2, T, 2> {
  public:
    using PointTuple<Point2, Vector2, T, 2>::PointTuple;
};
template <typename T>
class Vector3 : public Tuple<Vector3, T, 3> {
  public:
    using Tuple<Vector3, T, 3>::Tuple;
};
template <typename T>
class Point3 : public PointTuple<Point3, Vector3, T, 3> {
  public:
    using PointTuple<Point3, Vector3, T, 3>::PointTuple;
};
template <typename T>
class Normal3 : public Tuple<Normal3, T, 3> {
  public:
    using Tuple<Normal3, T, 3>::Tuple;
};

using Vector2f = Vector2<Float>;
using Vector2i = Vector2<int>;
using Point2f = Point2<Float>;
using Point2i = Point2<int>;
using Vector3f = Vector3<Float>;
using Vector3i = Vector3<int>;
using Point3f = Point3<Float>;
using Point3i = Point3<int>;
using Normal3f = Normal3<Float>;

// Directions (vectors and normals) take dot products and lengths; points do not.
template <typename V>
inline constexpr bool IsDirection = false;
template <typename T>
inline constexpr bool IsDirection<Vector2<T>> = true;
template <typename T>
inline constexpr bool IsDirection<Vector3<T>> = true;
template <typename T>
inline constexpr bool IsDirection<Normal3<T>> = true;

template <typename V>
concept Direction = IsDirection<V>;
template <typename V>
concept Direction3 = Direction<V> && V::nDimensions == 3;

template <template <typename> class C, typename T, int N>
PBRT_CPU_GPU constexpr C<T> Abs(const Tuple<C, T, N> &t) {
    C<T> result;
    for (int i = 0; i < N; ++i) result[i] = std::abs(t[i]);
    return result;
}

template <Direction A, Direction B>
    requires(A::nDimensions == B::nDimensions)
PBRT_CPU_GPU constexpr auto Dot(const A &a, const B &b) {
    decltype(a[0] * b[0]) sum = 0;
    for (int i = 0; i < A::nDimensions; ++i) sum += a[i] * b[i];
    return sum;
}
template <Direction A, Direction B>
PBRT_CPU_GPU constexpr auto AbsDot(const A &a, const B &b) {
    return std::abs(Dot(a, b));
}

template <Direction V>
PBRT_CPU_GPU constexpr auto LengthSquared(const V &v) {
    return Dot(v, v);
}
template <Direction V>
PBRT_CPU_GPU auto Length(const V &v) {
    return std::sqrt(LengthSquared(v));
}
// Always inlined: GCC keeps an out-of-line copy for the BxDFs' many calls, and a call around
// its square root and division costs more than they do (2 % on Veach's MIS scene).
template <Direction V>
[[gnu::always_inline]] PBRT_CPU_GPU inline V Normalize(const V &v) {
    return v / Length(v);
}

template <typename T>
PBRT_CPU_GPU auto DistanceSquared(const Point3<T> &p1, const Point3<T> &p2) {
    return LengthSquared(p1 - p2);
}
template <typename T>
PBRT_CPU_GPU auto Distance(const Point3<T> &p1, const Point3<T> &p2) {
    return Length(p1 - p2);
}

// Compensated products keep the result accurate for nearly parallel inputs.
template <Direction3 A, Direction3 B>
PBRT_CPU_GPU constexpr auto Cross(const A &a, const B &b) {
    using T = typename A::ElementType;
    return Vector3<T>(DifferenceOfProducts<T>(a.y, b.z, a.z, b.y),
                      DifferenceOfProducts<T>(a.z, b.x, a.x, b.z),
                      DifferenceOfProducts<T>(a.x, b.y, a.y, b.x));
}

// n flipped, if needed, into the hemisphere around v.
template <Direction3 A, Direction3 B>
PBRT_CPU_GPU constexpr A FaceForward(const A &n, const B &v) {
    return (Dot(n, v) < 0) ? -n : n;
}

// Two unit vectors completing unit v1 to an orthonormal basis, without a branch or a
// singular direction (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
template <Direction3 A>
PBRT_CPU_GPU void CoordinateSystem(const A &v1, Vector3<typename A::ElementType> *v2,
                                   Vector3<typename A::ElementType> *v3) {
    using T = typename A::ElementType;
    T sign = std::copysign(T(1), v1.z);
    T a = -1 / (sign + v1.z);
    T b = v1.x * v1.y * a;
    *v2 = Vector3<T>(1 + sign * Sqr(v1.x) * a, sign * b, -sign * v1.x);
    *v3 = Vector3<T>(b, sign + Sqr(v1.y) * a, -v1.y);
}

// v with its component along unit w removed.
template <typename T>
PBRT_CPU_GPU constexpr Vector3<T> GramSchmidt(const Vector3<T> &v, const Vector3<T> &w) {
    return v - Dot(v, w) * w;
}

// Spherical coordinates: theta from +z, phi from +x toward +y in [0, 2pi).
PBRT_CPU_GPU inline Vector3f SphericalDirection(Float sinTheta, Float cosTheta, Float phi) {
    Float s = Clamp(sinTheta, -1, 1);
    return Vector3f(s * std::cos(phi), s * std::sin(phi), Clamp(cosTheta, -1, 1));
}
PBRT_CPU_GPU inline Float SphericalTheta(const Vector3f &v) {
    return SafeACos(v.z);
}
PBRT_CPU_GPU inline Float SphericalPhi(const Vector3f &v) {
    Float p = std::atan2(v.y, v.x);
    return (p < 0) ? (p + 2 * Pi) : p;
}

// Trigonometry of a unit direction in the local shading frame (z = normal).
PBRT_CPU_GPU inline Float CosTheta(const Vector3f &w) {
    return w.z;
}
PBRT_CPU_GPU inline Float Cos2Theta(const Vector3f &w) {
    return Sqr(w.z);
}
PBRT_CPU_GPU inline Float AbsCosTheta(const Vector3f &w) {
    return std::abs(w.z);
}
PBRT_CPU_GPU inline Float Sin2Theta(const Vector3f &w) {
    return std::max<Float>(0, 1 - Cos2Theta(w));
}
PBRT_CPU_GPU inline Float SinTheta(const Vector3f &w) {
    return std::sqrt(Sin2Theta(w));
}
PBRT_CPU_GPU inline Float TanTheta(const Vector3f &w) {
    return SinTheta(w) / CosTheta(w);
}
PBRT_CPU_GPU inline Float Tan2Theta(const Vector3f &w) {
    return Sin2Theta(w) / Cos2Theta(w);
}
// At the pole phi is undefined; phi = 0 is the convention.
PBRT_CPU_GPU inline Float CosPhi(const Vector3f &w) {
    Float sinTheta = SinTheta(w);
    return (sinTheta == 0) ? 1 : Clamp(w.x / sinTheta, -1, 1);
}
PBRT_CPU_GPU inline Float SinPhi(const Vector3f &w) {
    Float sinTheta = SinTheta(w);
    return (sinTheta == 0) ? 0 : Clamp(w.y / sinTheta, -1, 1);
}

template <Direction3 A, Direction3 B>
PBRT_CPU_GPU constexpr bool SameHemisphere(const A &w, const B &wp) {
    return w.z * wp.z > 0;
}

// An orthonormal basis; ToLocal/FromLocal change coordinates between world and frame.
struct Frame {
    Vector3f x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};

    Frame() = default;
    PBRT_CPU_GPU Frame(const Vector3f &x0, const Vector3f &y0, const Vector3f &z0)
        : x(x0), y(y0), z(z0) {}

    PBRT_CPU_GPU static Frame FromXZ(const Vector3f &x, const Vector3f &z) {
        return Frame(x, Cross(z, x), z);
    }
    PBRT_CPU_GPU static Frame FromXY(const Vector3f &x, const Vector3f &y) {
        return Frame(x, y, Cross(x, y));
    }
    // The remaining two axes are CoordinateSystem's, in right-handed order.
    PBRT_CPU_GPU static Frame FromZ(const Vector3f &z) {
        Vector3f x, y;
        CoordinateSystem(z, &x, &y);
        return Frame(x, y, z);
    }
    PBRT_CPU_GPU static Frame FromX(const Vector3f &x) {
        Vector3f y, z;
        CoordinateSystem(x, &y, &z);
        return Frame(x, y, z);
    }
    PBRT_CPU_GPU static Frame FromY(const Vector3f &y) {
        Vector3f x, z;
        CoordinateSystem(y, &z, &x);
        return Frame(x, y, z);
    }
    PBRT_CPU_GPU static Frame FromZ(const Normal3f &z) { return FromZ(Vector3f(z)); }
    PBRT_CPU_GPU static Frame FromX(const Normal3f &x) { return FromX(Vector3f(x)); }
    PBRT_CPU_GPU static Frame FromY(const Normal3f &y) { return FromY(Vector3f(y)); }

    PBRT_CPU_GPU Vector3f ToLocal(const Vector3f &v) const {
        return Vector3f(Dot(v, x), Dot(v, y), Dot(v, z));
    }
    PBRT_CPU_GPU Normal3f ToLocal(const Normal3f &n) const {
        return Normal3f(Dot(n, x), Dot(n, y), Dot(n, z));
    }
    PBRT_CPU_GPU Vector3f FromLocal(const Vector3f &v) const {
        return v.x * x + v.y * y + v.z * z;
    }
    PBRT_CPU_GPU Normal3f FromLocal(const Normal3f &n) const {
        return Normal3f(FromLocal(Vector3f(n)));
    }
};

}  // namespace pbrt
