#include "pbrt_ext/util/animatedtransform.h"

#include "pbrt_ext/util/math.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace pbrt {

namespace {

using Column = std::array<double, 3>;

double DotD(const Column &a, const Column &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The rotation matrix's quaternion (Shoemake's method: divide by the largest of the four
// candidates for accuracy).
Quaternion FromRotation(const std::array<Column, 3> &r) {  // r[row][col]
    double trace = r[0][0] + r[1][1] + r[2][2], x, y, z, w;
    if (trace > 0) {
        double s = std::sqrt(trace + 1);
        w = s / 2;
        s = 0.5 / s;
        x = (r[2][1] - r[1][2]) * s;
        y = (r[0][2] - r[2][0]) * s;
        z = (r[1][0] - r[0][1]) * s;
    } else if (r[0][0] >= r[1][1] && r[0][0] >= r[2][2]) {
        double s = std::sqrt(1 + r[0][0] - r[1][1] - r[2][2]);
        x = s / 2;
        s = 0.5 / s;
        y = (r[0][1] + r[1][0]) * s;
        z = (r[0][2] + r[2][0]) * s;
        w = (r[2][1] - r[1][2]) * s;
    } else if (r[1][1] >= r[2][2]) {
        double s = std::sqrt(1 + r[1][1] - r[0][0] - r[2][2]);
        y = s / 2;
        s = 0.5 / s;
        x = (r[0][1] + r[1][0]) * s;
        z = (r[1][2] + r[2][1]) * s;
        w = (r[0][2] - r[2][0]) * s;
    } else {
        double s = std::sqrt(1 + r[2][2] - r[0][0] - r[1][1]);
        z = s / 2;
        s = 0.5 / s;
        x = (r[0][2] + r[2][0]) * s;
        y = (r[1][2] + r[2][1]) * s;
        w = (r[1][0] - r[0][1]) * s;
    }
    double norm = std::sqrt(x * x + y * y + z * z + w * w);
    return Quaternion{Vector3f(Float(x / norm), Float(y / norm), Float(z / norm)), Float(w / norm)};
}

SquareMatrix<3> RotationMatrix(const Quaternion &q) {
    Float x = q.v.x, y = q.v.y, z = q.v.z, w = q.w;
    SquareMatrix<3> r;
    r[0][0] = 1 - 2 * (y * y + z * z);
    r[0][1] = 2 * (x * y - z * w);
    r[0][2] = 2 * (x * z + y * w);
    r[1][0] = 2 * (x * y + z * w);
    r[1][1] = 1 - 2 * (x * x + z * z);
    r[1][2] = 2 * (y * z - x * w);
    r[2][0] = 2 * (x * z - y * w);
    r[2][1] = 2 * (y * z + x * w);
    r[2][2] = 1 - 2 * (x * x + y * y);
    return r;
}

}  // namespace

// Gram-Schmidt on the linear part's columns, in double: A = Q U with Q a rotation and U upper
// triangular.
TransformDecomposition Decompose(const Transform &t) {
    const SquareMatrix<4> &m = t.GetMatrix();
    if (m[3][0] != 0 || m[3][1] != 0 || m[3][2] != 0 || m[3][3] != 1)
        throw std::invalid_argument("a projective transform cannot move over the shutter interval");
    std::array<Column, 3> a;  // a[j] = column j
    for (int j = 0; j < 3; ++j)
        a[j] = {m[0][j], m[1][j], m[2][j]};
    std::array<Column, 3> q;
    double u[3][3] = {};
    for (int j = 0; j < 3; ++j) {
        Column c = a[j];
        for (int k = 0; k < j; ++k) {
            u[k][j] = DotD(q[k], a[j]);
            for (int i = 0; i < 3; ++i)
                c[i] -= u[k][j] * q[k][i];
        }
        u[j][j] = std::sqrt(DotD(c, c));
        if (!(u[j][j] > 1e-12 * std::sqrt(DotD(a[j], a[j]))))
            throw std::invalid_argument("a singular transform cannot move over the shutter interval");
        for (int i = 0; i < 3; ++i)
            q[j][i] = c[i] / u[j][j];
    }
    // A mirror: turn Q into a rotation by flipping its last column, and U's last row with it.
    Column cross = {q[0][1] * q[1][2] - q[0][2] * q[1][1], q[0][2] * q[1][0] - q[0][0] * q[1][2],
                    q[0][0] * q[1][1] - q[0][1] * q[1][0]};
    if (DotD(cross, q[2]) < 0) {
        for (int i = 0; i < 3; ++i)
            q[2][i] = -q[2][i];
        u[2][2] = -u[2][2];
    }
    std::array<Column, 3> rotation;  // rows
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            rotation[i][j] = q[j][i];
    TransformDecomposition d;
    d.translation = Vector3f(m[0][3], m[1][3], m[2][3]);
    d.rotation = FromRotation(rotation);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            d.scale[i][j] = Float(u[i][j]);
    return d;
}

Transform Compose(const TransformDecomposition &d) {
    SquareMatrix<3> linear = RotationMatrix(d.rotation) * d.scale;
    SquareMatrix<4> m;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            m[i][j] = linear[i][j];
        m[i][3] = d.translation[i];
    }
    return Transform(m);
}

Quaternion Slerp(Float t, Quaternion q0, Quaternion q1) {
    Float cosTheta = Dot(q0.v, q1.v) + q0.w * q1.w;
    if (cosTheta < 0) {
        q1 = Quaternion{-q1.v, -q1.w};
        cosTheta = -cosTheta;
    }
    Float w0, w1;
    if (cosTheta > 0.9995f) {
        w0 = 1 - t;  // nearly parallel: normalized lerp, where sin(theta) loses precision
        w1 = t;
    } else {
        Float theta = std::acos(Clamp(cosTheta, -1, 1));
        w0 = std::sin((1 - t) * theta) / std::sin(theta);
        w1 = std::sin(t * theta) / std::sin(theta);
    }
    Quaternion q{w0 * q0.v + w1 * q1.v, w0 * q0.w + w1 * q1.w};
    Float norm = std::sqrt(LengthSquared(q.v) + Sqr(q.w));
    return Quaternion{q.v / norm, q.w / norm};
}

AnimatedTransform::AnimatedTransform(const Transform &start, Float startTime,
                                     const Transform &end, Float endTime)
    : startTransform(start), endTransform(end), startTime(startTime), endTime(endTime),
      actuallyAnimated(!(start == end)) {
    if (actuallyAnimated)
        keys = {Decompose(start), Decompose(end)};
}

Float TimeFraction(Float time, Float startTime, Float endTime) {
    if (!(endTime > startTime))
        return time < startTime ? 0 : 1;
    return Clamp((time - startTime) / (endTime - startTime), 0, 1);
}

Float AnimatedTransform::Fraction(Float time) const {
    return TimeFraction(time, startTime, endTime);
}

Transform AnimatedTransform::Interpolate(Float time) const {
    if (!actuallyAnimated)
        return startTransform;
    Float f = Fraction(time);
    if (f == 0)
        return startTransform;
    if (f == 1)
        return endTransform;
    TransformDecomposition d;
    d.translation = (1 - f) * keys[0].translation + f * keys[1].translation;
    d.rotation = Slerp(f, keys[0].rotation, keys[1].rotation);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            d.scale[i][j] = Lerp(f, keys[0].scale[i][j], keys[1].scale[i][j]);
    return Compose(d);
}

KeyframedTransform::KeyframedTransform(const AnimatedTransform &outer,
                                       const AnimatedTransform &inner, int stepCount) {
    const AnimatedTransform &timing = inner.IsAnimated() ? inner : outer;
    Float t0 = timing.StartTime(), t1 = timing.EndTime();
    auto at = [&](int k) {
        Float time = k == stepCount ? t1 : Lerp(Float(k) / stepCount, t0, t1);
        return std::pair{time, outer.Interpolate(time) * inner.Interpolate(time)};
    };
    auto [startTime, start] = at(0);
    for (int k = 1; k <= stepCount; ++k) {
        auto [endTime, end] = at(k);
        steps.emplace_back(start, startTime, end, endTime);
        startTime = endTime;
        start = end;
    }
}

bool KeyframedTransform::IsAnimated() const {
    for (const AnimatedTransform &step : steps)
        if (step.IsAnimated())
            return true;
    return false;
}

TransformDecomposition KeyframedTransform::Keyframe(int k) const {
    return Decompose(k < StepCount() ? steps[size_t(k)].Start() : steps.back().End());
}

Transform KeyframedTransform::Interpolate(Float time) const {
    Float f = TimeFraction(time, StartTime(), EndTime());
    int k = std::min(StepCount() - 1, int(f * StepCount()));
    return steps[size_t(k)].Interpolate(time);
}

std::string AnimatedTransform::ToString() const {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "[ AnimatedTransform startTime: %g endTime: %g animated: %s ]",
                  startTime, endTime, actuallyAnimated ? "true" : "false");
    return buf;
}

}  // namespace pbrt
