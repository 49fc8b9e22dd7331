// Affine and projective transformations (pbrt-v4's util/transform.h and the SquareMatrix of
// util/math.h, reduced: no animated transforms, no rounding-error bounds).
//
// Conventions as in pbrt-v4: points are column vectors, t(p) = m * p; a Transform stores its
// inverse so that normals (transformed by the inverse transpose) and inverse applications cost
// no inversion; rotations are in degrees and follow the left-handed coordinate system.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/vecmath.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace pbrt {

template <int N>
class SquareMatrix {
  public:
    PBRT_CPU_GPU static SquareMatrix Zero() {
        SquareMatrix m;
        for (int i = 0; i < N; ++i) m.m[i][i] = 0;
        return m;
    }

    PBRT_CPU_GPU SquareMatrix() {
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) m[i][j] = (i == j) ? 1 : 0;
    }
    PBRT_CPU_GPU SquareMatrix(const Float mat[N][N]) {
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) m[i][j] = mat[i][j];
    }
    // N * N values in row-major order.
    template <typename... Args>
        requires(sizeof...(Args) == N * N)
    PBRT_CPU_GPU SquareMatrix(Args... args) {
        Float values[N * N] = {Float(args)...};
        for (int i = 0; i < N * N; ++i) m[i / N][i % N] = values[i];
    }

    PBRT_CPU_GPU bool IsIdentity() const {
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j)
                if (m[i][j] != ((i == j) ? 1 : 0)) return false;
        return true;
    }

    PBRT_CPU_GPU const Float *operator[](int i) const { return m[i]; }
    PBRT_CPU_GPU Float *operator[](int i) { return m[i]; }

    PBRT_CPU_GPU bool operator==(const SquareMatrix &o) const {
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j)
                if (m[i][j] != o.m[i][j]) return false;
        return true;
    }
    PBRT_CPU_GPU bool operator!=(const SquareMatrix &o) const { return !(*this == o); }

    // Accumulated in double: matrices are composed on the host at scene setup, and chains of
    // products (camera and instance transforms) should not drift.
    PBRT_CPU_GPU SquareMatrix operator*(const SquareMatrix &o) const {
        SquareMatrix r;
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) {
                double sum = 0;
                for (int k = 0; k < N; ++k) sum += double(m[i][k]) * double(o.m[k][j]);
                r.m[i][j] = Float(sum);
            }
        return r;
    }

  private:
    Float m[N][N];
};

template <int N>
PBRT_CPU_GPU SquareMatrix<N> Transpose(const SquareMatrix<N> &m) {
    SquareMatrix<N> r;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) r[i][j] = m[j][i];
    return r;
}

// Gauss-Jordan elimination with partial pivoting, in double; empty for a singular matrix.
template <int N>
PBRT_CPU_GPU pstd::optional<SquareMatrix<N>> Inverse(const SquareMatrix<N> &m) {
    double a[N][2 * N];
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            a[i][j] = m[i][j];
            a[i][N + j] = (i == j) ? 1 : 0;
        }
    for (int col = 0; col < N; ++col) {
        int pivot = col;
        for (int r = col + 1; r < N; ++r)
            if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
        if (a[pivot][col] == 0 || !std::isfinite(a[pivot][col])) return {};
        for (int j = 0; j < 2 * N; ++j) {
            double t = a[col][j];
            a[col][j] = a[pivot][j];
            a[pivot][j] = t;
        }
        double inv = 1 / a[col][col];
        for (int j = 0; j < 2 * N; ++j) a[col][j] *= inv;
        for (int r = 0; r < N; ++r) {
            if (r == col || a[r][col] == 0) continue;
            double f = a[r][col];
            for (int j = 0; j < 2 * N; ++j) a[r][j] -= f * a[col][j];
        }
    }
    SquareMatrix<N> r;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) r[i][j] = Float(a[i][N + j]);
    return r;
}

class Transform {
  public:
    Transform() = default;
    // A singular m (a projection onto a plane) gets a NaN inverse, as in pbrt-v4: applying it
    // is a bug that shows up in the output instead of passing silently.
    PBRT_CPU_GPU explicit Transform(const SquareMatrix<4> &m) : m(m) {
        pstd::optional<SquareMatrix<4>> inv = pbrt::Inverse(m);
        if (inv) {
            mInv = *inv;
        } else {
            Float nan = std::numeric_limits<Float>::quiet_NaN();
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) mInv[i][j] = nan;
        }
    }
    PBRT_CPU_GPU explicit Transform(const Float mat[4][4]) : Transform(SquareMatrix<4>(mat)) {}
    PBRT_CPU_GPU Transform(const SquareMatrix<4> &m, const SquareMatrix<4> &mInv) : m(m), mInv(mInv) {}

    PBRT_CPU_GPU const SquareMatrix<4> &GetMatrix() const { return m; }
    PBRT_CPU_GPU const SquareMatrix<4> &GetInverseMatrix() const { return mInv; }

    PBRT_CPU_GPU bool operator==(const Transform &t) const { return t.m == m; }
    PBRT_CPU_GPU bool operator!=(const Transform &t) const { return t.m != m; }
    PBRT_CPU_GPU bool IsIdentity() const { return m.IsIdentity(); }

    // Whether the upper 3x3 changes lengths along some axis (beyond a relative tolerance).
    PBRT_CPU_GPU bool HasScale(Float tolerance = 1e-3f) const {
        for (int axis = 0; axis < 3; ++axis) {
            Vector3f a(axis == 0, axis == 1, axis == 2);
            if (std::abs(LengthSquared((*this)(a)) - 1) > tolerance) return true;
        }
        return false;
    }
    // A negative determinant of the linear part mirrors space: pbrt-v4 flips normals for it.
    PBRT_CPU_GPU bool SwapsHandedness() const {
        Float det = m[0][0] * DifferenceOfProducts(m[1][1], m[2][2], m[1][2], m[2][1]) -
                    m[0][1] * DifferenceOfProducts(m[1][0], m[2][2], m[1][2], m[2][0]) +
                    m[0][2] * DifferenceOfProducts(m[1][0], m[2][1], m[1][1], m[2][0]);
        return det < 0;
    }

    PBRT_CPU_GPU Point3f operator()(Point3f p) const { return ApplyPoint(m, p); }
    PBRT_CPU_GPU Vector3f operator()(Vector3f v) const { return ApplyVector(m, v); }
    // Normals stay perpendicular to transformed tangents under the inverse transpose.
    PBRT_CPU_GPU Normal3f operator()(Normal3f n) const { return ApplyNormal(mInv, n); }
    // The direction is not normalized, so parametric distances along the ray are preserved.
    PBRT_CPU_GPU Ray operator()(const Ray &r) const {
        return Ray((*this)(r.o), (*this)(r.d), r.medium, r.time);
    }
    // The box around the eight transformed corners.
    PBRT_CPU_GPU Bounds3f operator()(const Bounds3f &b) const {
        Bounds3f bt;
        for (int i = 0; i < 8; ++i) bt = Union(bt, (*this)(b.Corner(i)));
        return bt;
    }

    PBRT_CPU_GPU Point3f ApplyInverse(Point3f p) const { return ApplyPoint(mInv, p); }
    PBRT_CPU_GPU Vector3f ApplyInverse(Vector3f v) const { return ApplyVector(mInv, v); }
    PBRT_CPU_GPU Normal3f ApplyInverse(Normal3f n) const { return ApplyNormal(m, n); }
    PBRT_CPU_GPU Ray ApplyInverse(const Ray &r) const {
        return Ray(ApplyInverse(r.o), ApplyInverse(r.d), r.medium, r.time);
    }

    // (t1 * t2)(p) = t1(t2(p)).
    PBRT_CPU_GPU Transform operator*(const Transform &t2) const {
        return Transform(m * t2.m, t2.mInv * mInv);
    }

  private:
    // The homogeneous divide is skipped when w is exactly 1, the affine case.
    PBRT_CPU_GPU static Point3f ApplyPoint(const SquareMatrix<4> &a, Point3f p) {
        Float xp = a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3];
        Float yp = a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3];
        Float zp = a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3];
        Float wp = a[3][0] * p.x + a[3][1] * p.y + a[3][2] * p.z + a[3][3];
        if (wp == 1) return Point3f(xp, yp, zp);
        return Point3f(xp, yp, zp) / wp;
    }
    PBRT_CPU_GPU static Vector3f ApplyVector(const SquareMatrix<4> &a, Vector3f v) {
        return Vector3f(a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z,
                        a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
                        a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z);
    }
    // Multiplies by the transpose of inv.
    PBRT_CPU_GPU static Normal3f ApplyNormal(const SquareMatrix<4> &inv, Normal3f n) {
        return Normal3f(inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z,
                        inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
                        inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z);
    }

    SquareMatrix<4> m, mInv;
};

PBRT_CPU_GPU inline Transform Inverse(const Transform &t) {
    return Transform(t.GetInverseMatrix(), t.GetMatrix());
}
PBRT_CPU_GPU inline Transform Transpose(const Transform &t) {
    return Transform(Transpose(t.GetMatrix()), Transpose(t.GetInverseMatrix()));
}

PBRT_CPU_GPU inline Transform Translate(Vector3f delta) {
    SquareMatrix<4> m(1, 0, 0, delta.x, 0, 1, 0, delta.y, 0, 0, 1, delta.z, 0, 0, 0, 1);
    SquareMatrix<4> minv(1, 0, 0, -delta.x, 0, 1, 0, -delta.y, 0, 0, 1, -delta.z, 0, 0, 0, 1);
    return Transform(m, minv);
}

PBRT_CPU_GPU inline Transform Scale(Float x, Float y, Float z) {
    SquareMatrix<4> m(x, 0, 0, 0, 0, y, 0, 0, 0, 0, z, 0, 0, 0, 0, 1);
    SquareMatrix<4> minv(1 / x, 0, 0, 0, 0, 1 / y, 0, 0, 0, 0, 1 / z, 0, 0, 0, 0, 1);
    return Transform(m, minv);
}

// Rotations are orthogonal: the inverse is the transpose, exactly.
PBRT_CPU_GPU inline Transform RotateX(Float theta) {
    Float s = std::sin(Radians(theta)), c = std::cos(Radians(theta));
    SquareMatrix<4> m(1, 0, 0, 0, 0, c, -s, 0, 0, s, c, 0, 0, 0, 0, 1);
    return Transform(m, Transpose(m));
}
PBRT_CPU_GPU inline Transform RotateY(Float theta) {
    Float s = std::sin(Radians(theta)), c = std::cos(Radians(theta));
    SquareMatrix<4> m(c, 0, s, 0, 0, 1, 0, 0, -s, 0, c, 0, 0, 0, 0, 1);
    return Transform(m, Transpose(m));
}
PBRT_CPU_GPU inline Transform RotateZ(Float theta) {
    Float s = std::sin(Radians(theta)), c = std::cos(Radians(theta));
    SquareMatrix<4> m(c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    return Transform(m, Transpose(m));
}

// Rotation about an arbitrary axis (Rodrigues' formula); the axis need not be unit length.
PBRT_CPU_GPU inline Transform Rotate(Float sinTheta, Float cosTheta, Vector3f axis) {
    Vector3f a = Normalize(axis);
    SquareMatrix<4> m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = a[i] * a[j] * (1 - cosTheta) + (i == j ? cosTheta : 0);
    m[0][1] -= a.z * sinTheta;
    m[0][2] += a.y * sinTheta;
    m[1][0] += a.z * sinTheta;
    m[1][2] -= a.x * sinTheta;
    m[2][0] -= a.y * sinTheta;
    m[2][1] += a.x * sinTheta;
    return Transform(m, Transpose(m));
}
// The rotation that turns the unit vector `from` into the unit vector `to` (pbrt-v4's
// RotateFromTo): the product of two reflections, through planes normal to refl - from and to
// refl - to, with refl an axis far from both.
PBRT_CPU_GPU inline Transform RotateFromTo(Vector3f from, Vector3f to) {
    Vector3f refl = (std::abs(from.x) < 0.72f && std::abs(to.x) < 0.72f)   ? Vector3f(1, 0, 0)
                    : (std::abs(from.y) < 0.72f && std::abs(to.y) < 0.72f) ? Vector3f(0, 1, 0)
                                                                           : Vector3f(0, 0, 1);
    Vector3f u = refl - from, v = refl - to;
    Float uu = Dot(u, u), vv = Dot(v, v), uv = Dot(u, v);
    SquareMatrix<4> r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[i][j] = (i == j ? 1 : 0) - 2 / uu * u[i] * u[j] - 2 / vv * v[i] * v[j] +
                      4 * uv / (uu * vv) * v[i] * u[j];
    return Transform(r, Transpose(r));
}

PBRT_CPU_GPU inline Transform Rotate(Float theta, Vector3f axis) {
    return Rotate(std::sin(Radians(theta)), std::cos(Radians(theta)), axis);
}

// cameraFromWorld for a camera at pos looking at look, with up projected to the image's
// vertical (pbrt-v4's LookAt: camera space looks down +z, +y up, +x to the right in the image).
// Host-only: a degenerate view is a scene-file error, reported by exception at scene setup.
inline Transform LookAt(Point3f pos, Point3f look, Vector3f up) {
    Vector3f toLook = look - pos;
    if (!(LengthSquared(toLook) > 0))
        throw std::runtime_error("LookAt: the eye and look-at points coincide");
    if (!(LengthSquared(up) > 0)) throw std::runtime_error("LookAt: the up vector is zero");
    Vector3f dir = Normalize(toLook);
    Vector3f rightUnnormalized = Cross(Normalize(up), dir);
    if (Length(rightUnnormalized) < 1e-6f)
        throw std::runtime_error("LookAt: the up vector and the viewing direction are parallel");
    Vector3f right = Normalize(rightUnnormalized);
    Vector3f newUp = Cross(dir, right);
    SquareMatrix<4> worldFromCamera(right.x, newUp.x, dir.x, pos.x,  //
                                    right.y, newUp.y, dir.y, pos.y,  //
                                    right.z, newUp.z, dir.z, pos.z,  //
                                    0, 0, 0, 1);
    pstd::optional<SquareMatrix<4>> cameraFromWorld = Inverse(worldFromCamera);
    return Transform(*cameraFromWorld, worldFromCamera);
}

// Maps camera space to screen space: [near, far] in z goes to [0, 1], and x, y are divided by
// z and scaled so that the field of view fovDeg spans [-1, 1].
PBRT_CPU_GPU inline Transform Perspective(Float fovDeg, Float n, Float f) {
    SquareMatrix<4> persp(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, f / (f - n), -f * n / (f - n), 0, 0, 1, 0);
    Float invTanAng = 1 / std::tan(Radians(fovDeg) / 2);
    return Scale(invTanAng, invTanAng, 1) * Transform(persp);
}

// Maps z in [zNear, zFar] to [0, 1], leaving x and y alone.
PBRT_CPU_GPU inline Transform Orthographic(Float zNear, Float zFar) {
    return Scale(1, 1, 1 / (zFar - zNear)) * Translate(Vector3f(0, 0, -zNear));
}

}  // namespace pbrt
