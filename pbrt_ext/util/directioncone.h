// Cones of directions (pbrt-v4's DirectionCone): the normals an emitter can face, and the
// directions from a point toward a box; the BVH light sampler bounds lights with them.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cmath>

namespace pbrt {

// Every unit direction within acos(cosTheta) of the unit axis w. cosTheta = Infinity is the empty
// cone, -1 the whole sphere.
struct DirectionCone {
    Vector3f w;
    Float cosTheta = Infinity;

    DirectionCone() = default;
    DirectionCone(Vector3f w, Float cosTheta) : w(Normalize(w)), cosTheta(cosTheta) {}
    explicit DirectionCone(Vector3f w) : DirectionCone(w, 1) {}

    static DirectionCone EntireSphere() { return DirectionCone(Vector3f(0, 0, 1), -1); }
    bool IsEmpty() const { return cosTheta == Infinity; }
};

// The angle between unit vectors, accurate also when they are nearly (anti)parallel, where acos
// of the dot product loses every digit.
inline Float AngleBetween(Vector3f v1, Vector3f v2) {
    if (Dot(v1, v2) < 0)
        return Pi - 2 * SafeASin(Length(v1 + v2) / 2);
    return 2 * SafeASin(Length(v2 - v1) / 2);
}

// The cosine of the half-angle of the cone the sphere (center, radius) subtends from p; -1, the
// whole sphere of directions, for a p inside it.
inline Float SubtendedCosTheta(Point3f center, Float radius, Point3f p) {
    Float d2 = DistanceSquared(p, center);
    if (d2 < Sqr(radius))
        return -1;
    Float sin2ThetaMax = Sqr(radius) / d2;
    return SafeSqrt(1 - sin2ThetaMax);
}

// The directions from p toward the box b: the cone around its bounding sphere, or every direction
// when p is inside that sphere.
inline DirectionCone BoundSubtendedDirections(const Bounds3f &b, Point3f p) {
    Point3f center;
    Float radius;
    b.BoundingSphere(&center, &radius);
    Float cosTheta = SubtendedCosTheta(center, radius, p);
    return cosTheta == -1 ? DirectionCone::EntireSphere() : DirectionCone(center - p, cosTheta);
}

// A cone holding both: a's axis turned toward b's until the spread covers both.
inline DirectionCone Union(const DirectionCone &a, const DirectionCone &b) {
    if (a.IsEmpty())
        return b;
    if (b.IsEmpty())
        return a;
    Float thetaA = SafeACos(a.cosTheta), thetaB = SafeACos(b.cosTheta);
    Float thetaD = AngleBetween(a.w, b.w);
    if (std::min(thetaD + thetaB, Pi) <= thetaA)
        return a;
    if (std::min(thetaD + thetaA, Pi) <= thetaB)
        return b;
    Float thetaO = (thetaA + thetaD + thetaB) / 2;
    if (thetaO >= Pi)
        return DirectionCone::EntireSphere();
    Vector3f axis = Cross(a.w, b.w);
    if (LengthSquared(axis) == 0)
        return DirectionCone::EntireSphere();
    Vector3f w = Rotate(Degrees(thetaO - thetaA), axis)(a.w);
    return DirectionCone(w, std::cos(thetaO));
}

}  // namespace pbrt
