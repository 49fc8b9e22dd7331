// AnimatedTransform: the decomposition Embree interpolates recomposes every affine transform
// (mirrors included), and interpolation between keyframes is what a translation, a rotation
// about one axis and a uniform scale make in closed form.
#include "pbrt_ext/util/animatedtransform.h"

#include "pbrt_ext/util/rng.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

namespace pbrt {
namespace {

void ExpectSameTransform(const Transform &a, const Transform &b, Float tol = 1e-5f) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            EXPECT_NEAR(a.GetMatrix()[i][j], b.GetMatrix()[i][j], tol) << i << ", " << j;
}

TEST(AnimatedTransform, DecompositionRecomposesRandomAffineTransforms) {
    RNG rng(3);
    for (int n = 0; n < 1000; ++n) {
        auto u = [&] { return rng.Uniform<Float>() * 2 - 1; };
        Transform t = Translate(Vector3f(u(), u(), u()) * 10) *
                      Rotate(360 * u(), Normalize(Vector3f(u(), u(), u()) + Vector3f(0, 0, 2))) *
                      Scale(0.2f + std::abs(u()), 0.2f + std::abs(u()), n % 2 ? -1.f : 1.f) *
                      Rotate(360 * u(), Normalize(Vector3f(u(), 1, u())));
        TransformDecomposition d = Decompose(t);
        EXPECT_NEAR(LengthSquared(d.rotation.v) + Sqr(d.rotation.w), 1, 1e-5f);
        EXPECT_EQ(d.scale[1][0], 0);
        EXPECT_EQ(d.scale[2][0], 0);
        EXPECT_EQ(d.scale[2][1], 0);
        EXPECT_GT(d.scale[0][0], 0);
        EXPECT_GT(d.scale[1][1], 0);
        EXPECT_EQ(d.scale[2][2] < 0, t.SwapsHandedness()) << "a mirror keeps a proper rotation";
        ExpectSameTransform(Compose(d), t, 1e-4f);
    }
}

TEST(AnimatedTransform, SingularAndProjectiveTransformsCannotMove) {
    EXPECT_THROW(Decompose(Scale(1, 0, 1)), std::invalid_argument);
    EXPECT_THROW(Decompose(Perspective(60, 0.1f, 100)), std::invalid_argument);
}

TEST(AnimatedTransform, TranslationRotationAndUniformScaleInterpolateInClosedForm) {
    AnimatedTransform move(Translate(Vector3f(1, 2, 3)), 0, Translate(Vector3f(3, 2, -1)), 1);
    ExpectSameTransform(move.Interpolate(0.25f), Translate(Vector3f(1.5f, 2, 2)));
    // Slerp turns at a constant rate about the one axis.
    AnimatedTransform turn(Transform(), 2, Rotate(90, Vector3f(0, 0, 1)), 4);
    ExpectSameTransform(turn.Interpolate(3), Rotate(45, Vector3f(0, 0, 1)));
    ExpectSameTransform(turn.Interpolate(2.5f), Rotate(22.5f, Vector3f(0, 0, 1)));
    AnimatedTransform grow(Transform(), 0, Translate(Vector3f(4, 0, 0)) * Scale(3, 3, 3) *
                                               Rotate(120, Vector3f(1, 0, 0)), 1);
    ExpectSameTransform(grow.Interpolate(0.5f), Translate(Vector3f(2, 0, 0)) * Scale(2, 2, 2) *
                                                    Rotate(60, Vector3f(1, 0, 0)));
}

TEST(AnimatedTransform, ClampsOutsideItsTimesAndKeepsTheKeyframesExactly) {
    Transform a = Translate(Vector3f(1, 0, 0)) * Rotate(30, Vector3f(0, 1, 0));
    Transform b = Scale(2, 1, 1);
    AnimatedTransform at(a, 0.5f, b, 1.5f);
    EXPECT_TRUE(at.IsAnimated());
    EXPECT_TRUE(at.Interpolate(0.5f) == a);
    EXPECT_TRUE(at.Interpolate(-3) == a);
    EXPECT_TRUE(at.Interpolate(1.5f) == b);
    EXPECT_TRUE(at.Interpolate(7) == b);
    EXPECT_EQ(at.Fraction(1), 0.5f);
    AnimatedTransform still(a, 0, a, 1);
    EXPECT_FALSE(still.IsAnimated());
    EXPECT_TRUE(still.Interpolate(0.7f) == a);
}

// The largest distance between where two transforms put the corners of the cube [-1, 1]^3.
Float CornerDistance(const Transform &a, const Transform &b) {
    Float worst = 0;
    for (int i = 0; i < 8; ++i) {
        Point3f p(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        worst = std::max(worst, Distance(a(p), b(p)));
    }
    return worst;
}

// The largest CornerDistance between the keyframed product and the exact one, over 1001 times.
Float WorstDeviation(const AnimatedTransform &outer, const AnimatedTransform &inner, int steps) {
    KeyframedTransform product(outer, inner, steps);
    Float worst = 0;
    for (int i = 0; i <= 1000; ++i) {
        Float time = Lerp(i / 1000.f, inner.StartTime(), inner.EndTime());
        worst = std::max(worst, CornerDistance(product.Interpolate(time),
                                               outer.Interpolate(time) * inner.Interpolate(time)));
    }
    return worst;
}

// A moving shape inside a moving instance: the keyframes are the product exactly; between them
// too where the outer factor is a similarity or both only translate. Two turns of 90 degrees
// about different axes, with offsets, deviate from the exact product by as much as the square of
// the step (the cube's corners, up to 3.7 from the origin, measured: 0.93 with one step, 8.8e-4
// with 32, 5.5e-5 with the scene loader's 128).
TEST(KeyframedTransform, FollowsTheProductOfTwoMotions) {
    AnimatedTransform turnAboutZ(Translate(Vector3f(2, 0, 0)), 0,
                                 Translate(Vector3f(2, 1, 0)) * Rotate(90, Vector3f(0, 0, 1)), 1);
    AnimatedTransform turnAboutX(Translate(Vector3f(0, 1, 0)), 0,
                                 Rotate(90, Vector3f(1, 0, 0)) * Translate(Vector3f(0, 1, 0)), 1);
    KeyframedTransform product(turnAboutZ, turnAboutX, 128);
    ASSERT_EQ(product.StepCount(), 128);
    for (int k = 0; k <= 128; ++k) {
        Float time = k / 128.f;
        ExpectSameTransform(Compose(product.Keyframe(k)),
                            turnAboutZ.Interpolate(time) * turnAboutX.Interpolate(time), 1e-5f);
    }
    EXPECT_LT(WorstDeviation(turnAboutZ, turnAboutX, 128), 1e-4f);
    EXPECT_GT(WorstDeviation(turnAboutZ, turnAboutX, 1), 0.1f) << "one step is not enough";

    AnimatedTransform placed(Translate(Vector3f(1, 2, 3)) * Rotate(40, Vector3f(1, 1, 0)) *
                                 Scale(2, 2, 2));
    EXPECT_LT(WorstDeviation(placed, turnAboutX, 1), 1e-5f) << "a similarity commutes";
    AnimatedTransform slide(Translate(Vector3f(0, 0, 0)), 0, Translate(Vector3f(0, 3, 1)), 1);
    AnimatedTransform drift(Translate(Vector3f(1, 0, 0)), 0, Translate(Vector3f(-2, 0, 4)), 1);
    EXPECT_LT(WorstDeviation(slide, drift, 1), 1e-5f) << "translations add";
}

TEST(KeyframedTransform, OneMotionIsItself) {
    AnimatedTransform motion(Translate(Vector3f(1, 0, 0)), 0.5f,
                             Rotate(60, Vector3f(0, 1, 0)) * Scale(1, 2, 1), 1.5f);
    KeyframedTransform keyframed(motion);
    EXPECT_TRUE(keyframed.IsAnimated());
    EXPECT_EQ(keyframed.StepCount(), 1);
    for (Float time : {0.f, 0.5f, 0.8f, 1.5f, 2.f})
        EXPECT_TRUE(keyframed.Interpolate(time) == motion.Interpolate(time)) << time;
    EXPECT_FALSE(KeyframedTransform(AnimatedTransform(Translate(Vector3f(1, 0, 0)))).IsAnimated());
}

}  // namespace
}  // namespace pbrt
