// AnimatedTransform: the decomposition Embree interpolates recomposes every affine transform
// (mirrors included), and interpolation between keyframes is what a translation, a rotation
// about one axis and a uniform scale make in closed form.
#include "pbrt_ext/util/animatedtransform.h"

#include "pbrt_ext/util/rng.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace pbrt
