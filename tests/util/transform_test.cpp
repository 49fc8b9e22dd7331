// Transformations: pbrt-v4's conventions (column points, inverse-transpose normals, left-handed
// rotations in degrees) and the projective matrices the cameras are built from.
#include "pbrt_ext/util/transform.h"

#include <gtest/gtest.h>

#include <random>

namespace pbrt {
namespace {

constexpr Float kTol = 1e-5f;

void ExpectNear(Point3f a, Point3f b, Float tol = kTol) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "component " << i;
}
void ExpectNear(Vector3f a, Vector3f b, Float tol = kTol) { ExpectNear(Point3f(a), Point3f(b), tol); }
void ExpectNear(Normal3f a, Normal3f b, Float tol = kTol) { ExpectNear(Point3f(a), Point3f(b), tol); }

// A fixed-seed generic affine transform: rotation, non-uniform scale and translation.
Transform RandomAffine(std::mt19937 &rng) {
    std::uniform_real_distribution<Float> u(-1, 1);
    Vector3f axis(u(rng), u(rng), u(rng) + 2);
    return Translate(Vector3f(u(rng), u(rng), u(rng))) * Rotate(180 * u(rng), axis) *
           Scale(1.5f + u(rng), 2 + u(rng), 0.5f + 0.25f * u(rng));
}

TEST(Transform, TranslateMovesPointsNotVectors) {
    Transform t = Translate(Vector3f(1, 2, 3));
    ExpectNear(t(Point3f(1, 1, 1)), Point3f(2, 3, 4));
    ExpectNear(t(Vector3f(1, 1, 1)), Vector3f(1, 1, 1));
    ExpectNear(t(Normal3f(0, 0, 1)), Normal3f(0, 0, 1));
    ExpectNear(t.ApplyInverse(Point3f(2, 3, 4)), Point3f(1, 1, 1));
}

TEST(Transform, RotationsFollowPbrtHandedness) {
    // pbrt-v4: RotateZ(90) takes +x to +y, RotateX(90) +y to +z, RotateY(90) +z to +x.
    ExpectNear(RotateZ(90)(Vector3f(1, 0, 0)), Vector3f(0, 1, 0));
    ExpectNear(RotateX(90)(Vector3f(0, 1, 0)), Vector3f(0, 0, 1));
    ExpectNear(RotateY(90)(Vector3f(0, 0, 1)), Vector3f(1, 0, 0));
}

TEST(Transform, RotateAboutAxisMatchesAxisRotations) {
    for (Float theta : {-130.f, -45.f, 10.f, 90.f, 200.f}) {
        Vector3f v(0.3f, -0.7f, 0.2f);
        ExpectNear(Rotate(theta, Vector3f(2, 0, 0))(v), RotateX(theta)(v));
        ExpectNear(Rotate(theta, Vector3f(0, 1, 0))(v), RotateY(theta)(v));
        ExpectNear(Rotate(theta, Vector3f(0, 0, 0.5f))(v), RotateZ(theta)(v));
    }
}

TEST(Transform, InverseRoundTripsAndComposes) {
    std::mt19937 rng(7);
    for (int i = 0; i < 100; ++i) {
        Transform a = RandomAffine(rng), b = RandomAffine(rng);
        Point3f p(0.3f * i, -1.f, 2.f);
        ExpectNear(Inverse(a)(a(p)), p, 1e-4f);
        ExpectNear((a * b)(p), a(b(p)), 1e-4f);
        ExpectNear(Inverse(a * b)(p), Inverse(b)(Inverse(a)(p)), 1e-4f);
        // The stored inverse agrees with a fresh inversion of the matrix.
        Transform fresh(a.GetMatrix());
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(fresh.GetInverseMatrix()[r][c], a.GetInverseMatrix()[r][c], 1e-4f);
    }
}

TEST(Transform, NormalsStayPerpendicularToTangents) {
    std::mt19937 rng(11);
    for (int i = 0; i < 100; ++i) {
        Transform t = RandomAffine(rng);
        Vector3f dpdu(1, 0.2f, -0.3f), dpdv(-0.1f, 1, 0.4f);
        Normal3f n(Cross(dpdu, dpdv));
        Normal3f nt = t(n);
        EXPECT_NEAR(Dot(nt, t(dpdu)) / (Length(nt) * Length(t(dpdu))), 0, 1e-5f);
        EXPECT_NEAR(Dot(nt, t(dpdv)) / (Length(nt) * Length(t(dpdv))), 0, 1e-5f);
    }
}

TEST(Transform, RayKeepsParametricDistance) {
    Transform t = Translate(Vector3f(1, 0, 0)) * Scale(2, 3, 4);
    Ray r(Point3f(0.5f, 0.5f, 0.5f), Vector3f(1, -1, 2));
    Ray rt = t(r);
    ExpectNear(rt(0.7f), t(r(0.7f)));
    ExpectNear(t.ApplyInverse(rt)(0.7f), r(0.7f));
}

TEST(Transform, SingularMatrixHasNoInverse) {
    SquareMatrix<4> flat(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1);
    EXPECT_FALSE(Inverse(flat).has_value());
    EXPECT_TRUE(IsNaN(Transform(flat).GetInverseMatrix()[0][0]));
    EXPECT_TRUE(Inverse(SquareMatrix<4>()).has_value());
}

TEST(Transform, Predicates) {
    EXPECT_TRUE(Transform().IsIdentity());
    EXPECT_FALSE(Translate(Vector3f(0, 0, 1)).IsIdentity());
    EXPECT_FALSE(RotateY(30).HasScale());
    EXPECT_FALSE(Translate(Vector3f(4, 5, 6)).HasScale());
    EXPECT_TRUE(Scale(1, 1, 1.1f).HasScale());
    EXPECT_TRUE(Scale(1, -1, 1).SwapsHandedness());
    EXPECT_FALSE(Scale(-1, -1, 1).SwapsHandedness());
    EXPECT_FALSE(Rotate(77, Vector3f(1, 2, 3)).SwapsHandedness());
    Transform t = Translate(Vector3f(1, 2, 3)) * RotateX(20);
    EXPECT_EQ(Transpose(Transpose(t)), t);
}

TEST(Transform, LookAtBuildsCameraFromWorld) {
    // Camera at (0,0,-5) looking at the origin with +y up: world +z is camera +z, world +x is
    // camera +x (pbrt-v4's left-handed camera space).
    Transform cameraFromWorld = LookAt(Point3f(0, 0, -5), Point3f(0, 0, 0), Vector3f(0, 1, 0));
    ExpectNear(cameraFromWorld(Point3f(0, 0, 0)), Point3f(0, 0, 5));
    ExpectNear(cameraFromWorld(Vector3f(1, 0, 0)), Vector3f(1, 0, 0));
    ExpectNear(cameraFromWorld(Vector3f(0, 1, 0)), Vector3f(0, 1, 0));
    // A general view: the look point lies on camera +z, at its distance.
    Point3f pos(1, 2, 3), look(-2, 0.5f, 7);
    Transform cfw = LookAt(pos, look, Vector3f(0.1f, 1, 0));
    ExpectNear(cfw(look), Point3f(0, 0, Distance(pos, look)), 1e-4f);
    EXPECT_FALSE(cfw.HasScale());
}

TEST(Transform, LookAtRejectsDegenerateViews) {
    EXPECT_THROW(LookAt(Point3f(0, 0, 0), Point3f(0, 0, 0), Vector3f(0, 1, 0)), std::runtime_error);
    EXPECT_THROW(LookAt(Point3f(0, 0, 0), Point3f(0, 3, 0), Vector3f(0, 1, 0)), std::runtime_error);
    EXPECT_THROW(LookAt(Point3f(0, 0, 0), Point3f(0, 0, 1), Vector3f(0, 0, 0)), std::runtime_error);
}

TEST(Transform, PerspectiveMapsFrustumToUnitScreen) {
    Float n = 0.01f, f = 1000;
    Transform persp = Perspective(90, n, f);
    // At 90 degrees the frustum edge x = z maps to screen x = 1; z = near, far map to 0, 1.
    ExpectNear(persp(Point3f(2, 0, 2)), Point3f(1, 0, persp(Point3f(0, 0, 2)).z));
    EXPECT_NEAR(persp(Point3f(0, 0, n)).z, 0, 1e-5f);
    EXPECT_NEAR(persp(Point3f(0, 0, f)).z, 1, 1e-5f);
    Transform p60 = Perspective(60, n, f);
    EXPECT_NEAR(p60(Point3f(std::tan(Radians(30)), 0, 1)).x, 1, 1e-5f);
}

TEST(Transform, OrthographicMapsDepthRange) {
    Transform o = Orthographic(2, 6);
    ExpectNear(o(Point3f(3, -1, 2)), Point3f(3, -1, 0));
    ExpectNear(o(Point3f(3, -1, 6)), Point3f(3, -1, 1));
}

TEST(Transform, BoundsEncloseTransformedCorners) {
    Bounds3f b(Point3f(-1, -1, -1), Point3f(1, 1, 1));
    Bounds3f bt = RotateZ(45)(b);
    EXPECT_NEAR(bt.pMax.x, Sqrt2, 1e-5f);
    EXPECT_NEAR(bt.pMin.y, -Sqrt2, 1e-5f);
    EXPECT_NEAR(bt.pMax.z, 1, 1e-6f);
}

}  // namespace
}  // namespace pbrt
