// Transforms that move during the shutter interval (pbrt-v4's AnimatedTransform, for
// ActiveTransform/TransformTimes): two keyframes, each split into a translation, a rotation and
// an upper-triangular scale/shear, interpolated linearly, by slerp and linearly.
//
// Where this differs from pbrt-v4, and why: pbrt-v4 splits the linear part by the polar
// decomposition (rotation times a symmetric stretch), Embree's instance motion blur by rotation
// times an upper-triangular matrix (its RTCQuaternionDecomposition). The intersections are
// Embree's, so the interpolation here is Embree's, and shading sees the transform the ray was
// intersected with. Both agree at the keyframes, and in between for every motion whose stretch is
// a uniform scale (translations, rotations, uniform scales: the common cases); with non-uniform
// scale and rotation moving together, the in-between shapes differ slightly.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

#include <array>
#include <string>
#include <vector>

namespace pbrt {

// A unit quaternion w + v as a rotation.
struct Quaternion {
    Vector3f v = Vector3f(0, 0, 0);
    Float w = 1;
};

// M = Translate(translation) * Rotation(rotation) * scale, scale upper triangular (its last
// column zero): the form Embree interpolates.
struct TransformDecomposition {
    Vector3f translation;
    Quaternion rotation;
    SquareMatrix<3> scale;
};

// Splits the affine transform m (its last row 0 0 0 1). A mirroring m keeps a proper rotation and
// a negative scale.z. Throws std::invalid_argument for a singular or projective m.
TransformDecomposition Decompose(const Transform &m);
Transform Compose(const TransformDecomposition &d);

// Shortest-arc spherical interpolation between unit quaternions, t in [0, 1].
Quaternion Slerp(Float t, Quaternion q0, Quaternion q1);

// Where time falls in [startTime, endTime], clamped to [0, 1] as pbrt-v4 clamps (an empty
// interval: 0 before it, 1 from it on).
Float TimeFraction(Float time, Float startTime, Float endTime);

class AnimatedTransform {
  public:
    AnimatedTransform() = default;
    // The identity when start and end are equal, or the times are: then nothing moves.
    AnimatedTransform(const Transform &start, Float startTime, const Transform &end,
                      Float endTime);
    explicit AnimatedTransform(const Transform &t) : AnimatedTransform(t, 0, t, 1) {}

    bool IsAnimated() const { return actuallyAnimated; }
    const Transform &Start() const { return startTransform; }
    const Transform &End() const { return endTransform; }
    Float StartTime() const { return startTime; }
    Float EndTime() const { return endTime; }
    // Where time falls between the keyframes, clamped to [0, 1] as pbrt-v4 clamps.
    Float Fraction(Float time) const;
    // The keyframes as Embree takes them.
    const std::array<TransformDecomposition, 2> &Keyframes() const { return keys; }

    // The transform at `time` (the start one where nothing moves).
    Transform Interpolate(Float time) const;
    // r carried by the transform at r's time; without a copy of the transform where nothing
    // moves.
    Ray operator()(const Ray &r) const {
        return actuallyAnimated ? Interpolate(r.time)(r) : startTransform(r);
    }
    std::string ToString() const;

  private:
    Transform startTransform, endTransform;
    Float startTime = 0, endTime = 1;
    bool actuallyAnimated = false;
    std::array<TransformDecomposition, 2> keys;
};

// A motion through keyframes at equal steps of its interval, each step interpolated as an
// AnimatedTransform interpolates, which is what Embree's instance motion blur does with more than
// two time steps. It carries the product outer(t) * inner(t) of two motions: a moving shape
// inside an object instance (moving or not), which Embree's one level of instances cannot nest.
// pbrt-v4 composes the two interpolations per ray; that product is no AnimatedTransform, so it is
// sampled at the keyframes. Exact there, and between them wherever outer is a similarity (a
// static instance placed by rotation, translation and uniform scale: left factors commute with
// the interpolation) or both only translate; otherwise within the interpolation's error over a
// step (tests/util/animatedtransform_test.cpp measures it).
class KeyframedTransform {
  public:
    KeyframedTransform() = default;
    explicit KeyframedTransform(const AnimatedTransform &t) : steps{t} {}
    // outer(t) * inner(t) at stepCount + 1 equally spaced times over the interval of the one that
    // moves (both move over the scene's TransformTimes).
    KeyframedTransform(const AnimatedTransform &outer, const AnimatedTransform &inner,
                       int stepCount);

    bool IsAnimated() const;
    Float StartTime() const { return steps.front().StartTime(); }
    Float EndTime() const { return steps.back().EndTime(); }
    int StepCount() const { return int(steps.size()); }
    // Keyframe k of 0, ..., StepCount(), as Embree takes it.
    TransformDecomposition Keyframe(int k) const;
    const Transform &Start() const { return steps.front().Start(); }
    Transform Interpolate(Float time) const;

  private:
    std::vector<AnimatedTransform> steps;
};

}  // namespace pbrt
