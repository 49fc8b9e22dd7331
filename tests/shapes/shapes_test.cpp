// Shapes: analytic hits (t, p, n, uv, dp/du), orientation rules, shading frames, areas, and
// sampling densities (area sampling by Monte Carlo; solid-angle sampling by chi-square).
#include "pbrt_ext/shapes/shapes.h"

#include "tests/support/chi2.h"

#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/sphericalsampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

namespace pbrt {
namespace {

constexpr Float kTol = 1e-4f;

void ExpectNear(Vector3f a, Vector3f b, Float tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
void ExpectNear(Point3f a, Point3f b, Float tol = kTol) {
    ExpectNear(Vector3f(a), Vector3f(b), tol);
}
void ExpectNear(Normal3f a, Normal3f b, Float tol = kTol) {
    ExpectNear(Vector3f(a), Vector3f(b), tol);
}

// The shading frame the BSDF builds must be orthonormal, and n on shading.n's side.
void ExpectConsistentFrame(const SurfaceInteraction &si) {
    EXPECT_NEAR(Length(si.n), 1, kTol);
    EXPECT_NEAR(Length(si.shading.n), 1, kTol);
    EXPECT_GT(Dot(si.n, si.shading.n), 0);
    Vector3f ss = Normalize(si.shading.dpdu);
    EXPECT_NEAR(Dot(ss, si.shading.n), 0, 1e-3f);
    EXPECT_NEAR(Length(si.wo), 1, kTol);
}

// ---------------------------------------------------------------------------------------
// Sphere

TEST(Sphere, HitOnTheAxisFacesTheRay) {
    Sphere s(Transform(), false, 1, -1, 1, 360);
    pstd::optional<ShapeIntersection> si = s.Intersect(Ray(Point3f(0, 0, -5), Vector3f(0, 0, 1)));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->tHit, 4, kTol);
    ExpectNear(si->intr.p, Point3f(0, 0, -1));
    ExpectNear(si->intr.n, Normal3f(0, 0, -1));
    ExpectNear(si->intr.wo, Vector3f(0, 0, -1));
    ExpectConsistentFrame(si->intr);
}

TEST(Sphere, EquatorParameterization) {
    Sphere s(Transform(), false, 1, -1, 1, 360);
    pstd::optional<ShapeIntersection> si = s.Intersect(Ray(Point3f(5, 0, 0), Vector3f(-1, 0, 0)));
    ASSERT_TRUE(si);
    ExpectNear(si->intr.p, Point3f(1, 0, 0));
    EXPECT_NEAR(si->intr.uv.x, 0, kTol);
    EXPECT_NEAR(si->intr.uv.y, 0.5f, kTol);
    ExpectNear(si->intr.dpdu, Vector3f(0, 2 * Pi, 0), 1e-3f);
    ExpectNear(si->intr.dpdv, Vector3f(0, 0, Pi), 1e-3f);
    ExpectNear(si->intr.n, Normal3f(1, 0, 0));
}

TEST(Sphere, NormalTurnsAsThePoint) {
    // n = (p - c) / r, so dn/du = dp/du / r (pbrt-v4's Weingarten equations for a sphere), and
    // the other way round for a sphere whose normal points inward.
    for (bool reverse : {false, true}) {
        Sphere s(Translate(Vector3f(1, 2, 3)), reverse, 2, -2, 2, 360);
        pstd::optional<ShapeIntersection> si =
            s.Intersect(Ray(Point3f(8, 2.5f, 3.7f), Vector3f(-1, 0, 0)));
        ASSERT_TRUE(si);
        Float sign = reverse ? -1 : 1;
        ExpectNear(si->intr.shading.dndu, Normal3f(sign * si->intr.shading.dpdu / 2), 1e-4f);
        ExpectNear(si->intr.shading.dndv, Normal3f(sign * si->intr.shading.dpdv / 2), 1e-4f);
    }
}

TEST(Sphere, ReverseOrientationPointsInward) {
    Sphere s(Transform(), true, 1, -1, 1, 360);
    pstd::optional<ShapeIntersection> si = s.Intersect(Ray(Point3f(5, 0, 0), Vector3f(-1, 0, 0)));
    ASSERT_TRUE(si);
    ExpectNear(si->intr.n, Normal3f(-1, 0, 0));
    ExpectConsistentFrame(si->intr);
}

// pbrt-v4 flips normals for reverseOrientation ^ transformSwapsHandedness.
TEST(Sphere, MirroringTransformFlipsTheNormal) {
    Sphere s(Scale(-1, 1, 1), false, 1, -1, 1, 360);
    pstd::optional<ShapeIntersection> si = s.Intersect(Ray(Point3f(5, 0, 0), Vector3f(-1, 0, 0)));
    ASSERT_TRUE(si);
    ExpectNear(si->intr.n, Normal3f(-1, 0, 0));
    pstd::optional<ShapeSample> ss = s.Sample(Point2f(0.3f, 0.6f));
    ASSERT_TRUE(ss);
    EXPECT_LT(Dot(ss->intr.n, Vector3f(ss->intr.p)), 0);  // Sample agrees with Intersect
}

TEST(Sphere, TransformedHit) {
    Sphere s(Translate(Vector3f(1, 2, 3)) * Scale(2, 2, 2), false, 1, -1, 1, 360);
    pstd::optional<ShapeIntersection> si = s.Intersect(Ray(Point3f(1, 2, -10), Vector3f(0, 0, 2)));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->tHit, 5.5f, kTol);
    ExpectNear(si->intr.p, Point3f(1, 2, 1));
    ExpectNear(si->intr.n, Normal3f(0, 0, -1));
    EXPECT_NEAR(s.Area(), 16 * Pi, 1e-3f);
}

TEST(Sphere, ClippedSphereShowsItsInside) {
    Sphere s(Transform(), false, 1, -1, 0.5f, 360);
    pstd::optional<ShapeIntersection> si = s.Intersect(Ray(Point3f(0, 0, 5), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->tHit, 6, kTol);
    EXPECT_FALSE(s.Intersect(Ray(Point3f(0, 0, 5), Vector3f(0, 0, -1)), 5.5f));
    Sphere quarter(Transform(), false, 1, -1, 1, 90);
    EXPECT_FALSE(quarter.Intersect(Ray(Point3f(-5, 0.1f, 0), Vector3f(1, 0, 0)), 5.5f));
    EXPECT_TRUE(quarter.IntersectP(Ray(Point3f(5, 0.1f, 0), Vector3f(-1, 0, 0))));
    EXPECT_NEAR(quarter.Area(), Pi, 1e-4f);
}

TEST(Sphere, MissesAndTMax) {
    Sphere s(Transform(), false, 1, -1, 1, 360);
    EXPECT_FALSE(s.Intersect(Ray(Point3f(0, 1.01f, -5), Vector3f(0, 0, 1))));
    EXPECT_FALSE(s.Intersect(Ray(Point3f(0, 0, -5), Vector3f(0, 0, 1)), 3.9f));
    EXPECT_FALSE(s.Intersect(Ray(Point3f(0, 0, 5), Vector3f(0, 0, 1))));
}

// The area of a prolate spheroid (semi-axes 1, 1, 2) in closed form.
TEST(Sphere, AreaUnderUnevenScale) {
    Sphere s(Scale(1, 1, 2), false, 1, -1, 1, 360);
    double e = std::sqrt(0.75);
    double expected = 2 * 3.14159265358979 * (1 + 2 / e * std::asin(e));
    EXPECT_NEAR(s.Area(), expected, 1e-3 * expected);
}

// ---------------------------------------------------------------------------------------
// Cylinder

TEST(Cylinder, HitParameterization) {
    Cylinder c(Transform(), false, 2, -1, 3, 360);
    pstd::optional<ShapeIntersection> si = c.Intersect(Ray(Point3f(5, 0, 1), Vector3f(-1, 0, 0)));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->tHit, 3, kTol);
    ExpectNear(si->intr.p, Point3f(2, 0, 1));
    ExpectNear(si->intr.n, Normal3f(1, 0, 0));
    EXPECT_NEAR(si->intr.uv.x, 0, kTol);
    EXPECT_NEAR(si->intr.uv.y, 0.5f, kTol);
    ExpectNear(si->intr.dpdu, Vector3f(0, 2 * Pi * 2, 0), 1e-3f);
    ExpectNear(si->intr.dpdv, Vector3f(0, 0, 4));
    ExpectConsistentFrame(si->intr);
    EXPECT_NEAR(c.Area(), 2 * Pi * 2 * 4, 1e-3f);
    // Open ends: along the axis nothing is hit, from inside the far wall is.
    EXPECT_FALSE(c.Intersect(Ray(Point3f(0.5f, 0, 10), Vector3f(0, 0, -1))));
    pstd::optional<ShapeIntersection> inside = c.Intersect(Ray(Point3f(0, 0, 0), Vector3f(0, 1, 0)));
    ASSERT_TRUE(inside);
    EXPECT_NEAR(inside->tHit, 2, kTol);
    ExpectNear(inside->intr.n, Normal3f(0, 1, 0));  // outward, whichever side is seen
}

TEST(Cylinder, NormalTurnsWithUOnly) {
    for (bool reverse : {false, true}) {
        Cylinder c(Translate(Vector3f(1, 2, 3)), reverse, 2, -2, 2, 360);
        pstd::optional<ShapeIntersection> si =
            c.Intersect(Ray(Point3f(8, 2.5f, 3.7f), Vector3f(-1, 0, 0)));
        ASSERT_TRUE(si);
        Float sign = reverse ? -1 : 1;
        EXPECT_NEAR(Dot(si->intr.n, Vector3f(1, 0, 0)), sign * std::sqrt(1 - Sqr(0.25f)), 1e-4f);
        ExpectNear(si->intr.shading.dndu, Normal3f(sign * si->intr.shading.dpdu / 2), 1e-4f);
        ExpectNear(si->intr.shading.dndv, Normal3f(0, 0, 0));
    }
}

// Partial sweeps and heights: the hit, or the miss, where the closed form puts it. The closed
// form here is the quadratic in long double, clipped by z and azimuth, over 10^5 random rays
// (seeded), through a transform.
TEST(Cylinder, RandomRaysAgreeWithTheClosedForm) {
    const Float radius = 1.5f, zMin = -0.5f, zMax = 2, phiMaxDegrees = 250;
    Transform worldFromObject = Translate(Vector3f(0.3f, -0.2f, 0.1f)) * RotateX(20);
    Cylinder c(worldFromObject, false, radius, zMin, zMax, phiMaxDegrees);
    Transform objectFromWorld = Inverse(worldFromObject);
    RNG rng(11);
    int hits = 0;
    for (int i = 0; i < 100000; ++i) {
        Point3f o(rng.Uniform<Float>() * 8 - 4, rng.Uniform<Float>() * 8 - 4,
                  rng.Uniform<Float>() * 8 - 4);
        Vector3f d = SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        Point3f oo = objectFromWorld(o);
        Vector3f dd = objectFromWorld(d);
        long double a = (long double)dd.x * dd.x + (long double)dd.y * dd.y;
        long double b = 2 * ((long double)dd.x * oo.x + (long double)dd.y * oo.y);
        long double cc = (long double)oo.x * oo.x + (long double)oo.y * oo.y -
                         (long double)radius * radius;
        long double disc = b * b - 4 * a * cc;
        long double expected = -1;
        if (a > 0 && disc >= 0)
            for (long double t : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)}) {
                long double z = oo.z + t * dd.z;
                long double phi = std::atan2((long double)oo.y + t * dd.y, (long double)oo.x + t * dd.x);
                if (phi < 0)
                    phi += 2 * 3.14159265358979323846L;
                if (t > 0 && z >= zMin && z <= zMax && phi <= phiMaxDegrees * 3.14159265358979323846L / 180) {
                    expected = t;
                    break;
                }
            }
        pstd::optional<ShapeIntersection> si = c.Intersect(Ray(o, d));
        // Rays that graze the clipping edges may go either way in float; they are skipped.
        if (expected > 0 && si) {
            ++hits;
            EXPECT_NEAR(si->tHit, double(expected), 1e-4 * (1 + double(expected)));
        } else if (bool(si) != (expected > 0)) {
            Point3f p = objectFromWorld(o + d * Float(si ? si->tHit : expected));
            Float phi = std::atan2(p.y, p.x);
            phi = phi < 0 ? phi + 2 * Pi : phi;
            Float edge = std::min({std::abs(p.z - zMin), std::abs(p.z - zMax),
                                   std::abs(phi - Radians(phiMaxDegrees)) * radius, phi * radius});
            EXPECT_LT(edge, 1e-3f) << "ray " << i << ": hit " << bool(si) << ", closed form " << double(expected);
        }
    }
    EXPECT_GT(hits, 5000);  // 6509 with this seed: the test does look at hits
}

// An elliptic cylinder: semi-axes 2 and 1 (the perimeter 4 a E(e), E the complete elliptic
// integral of the second kind, e^2 = 3/4), height 3.
TEST(Cylinder, AreaUnderUnevenScale) {
    Cylinder c(Scale(2, 1, 3), false, 1, 0, 1, 360);
    double expected = 4 * 2 * std::comp_ellint_2(std::sqrt(0.75)) * 3;
    EXPECT_NEAR(c.Area(), expected, 1e-6 * expected);
    Cylinder quarter(Transform(), false, 2, 0, 1, 90);
    EXPECT_NEAR(quarter.Area(), Pi, 1e-5f);
}

// ---------------------------------------------------------------------------------------
// Disk

TEST(Disk, HitParameterization) {
    Disk d(Transform(), false, 0.5f, 2, 1, 360);
    pstd::optional<ShapeIntersection> si = d.Intersect(Ray(Point3f(1.5f, 0, 5), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->tHit, 4.5f, kTol);
    ExpectNear(si->intr.p, Point3f(1.5f, 0, 0.5f));
    ExpectNear(si->intr.n, Normal3f(0, 0, 1));
    EXPECT_NEAR(si->intr.uv.x, 0, kTol);
    EXPECT_NEAR(si->intr.uv.y, 0.5f, kTol);
    ExpectNear(si->intr.dpdu, Vector3f(0, 2 * Pi * 1.5f, 0), 1e-3f);
    ExpectNear(si->intr.dpdv, Vector3f(-1, 0, 0));
    ExpectConsistentFrame(si->intr);
    EXPECT_FALSE(d.Intersect(Ray(Point3f(0.5f, 0, 5), Vector3f(0, 0, -1))));  // the hole
    EXPECT_FALSE(d.Intersect(Ray(Point3f(2.5f, 0, 5), Vector3f(0, 0, -1))));
    EXPECT_NEAR(d.Area(), Pi * 3, 1e-4f);
}

TEST(Disk, ReverseOrientationAndScale) {
    Disk d(Scale(2, 2, 2), true, 0, 1, 0, 360);
    pstd::optional<ShapeIntersection> si = d.Intersect(Ray(Point3f(1, 1, 1), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    ExpectNear(si->intr.n, Normal3f(0, 0, -1));
    EXPECT_NEAR(d.Area(), 4 * Pi, 1e-4f);
}

// An interface's hit (no material) is built by BoundaryFromIntersection: p and the normals
// only. They must be InteractionFromIntersection's bit for bit, or rays crossing a medium's
// boundary would start on another side of it than the full hit says.
template <typename Quadric>
void ExpectBoundaryIsTheFullHits(const Quadric &shape, RNG &rng) {
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        Point3f o(8 * (rng.Uniform<Float>() - 0.5f), 8 * (rng.Uniform<Float>() - 0.5f),
                  8 * (rng.Uniform<Float>() - 0.5f));
        Vector3f d = Normalize(Vector3f(0.3f, -0.2f, 0.1f) - Vector3f(o) +
                               Vector3f(rng.Uniform<Float>(), rng.Uniform<Float>(), 0));
        pstd::optional<QuadricIntersection> isect = shape.BasicIntersect(Ray(o, d), Infinity);
        if (!isect)
            continue;
        ++hits;
        SurfaceInteraction full = shape.InteractionFromIntersection(*isect, -d);
        SurfaceInteraction boundary = shape.BoundaryFromIntersection(*isect, -d);
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(boundary.p[c], full.p[c]);
            EXPECT_EQ(boundary.n[c], full.n[c]);
            EXPECT_EQ(boundary.shading.n[c], full.shading.n[c]);
            EXPECT_EQ(boundary.wo[c], full.wo[c]);
        }
        EXPECT_EQ(boundary.errorBound, full.errorBound);
    }
    EXPECT_GT(hits, 50);
}

TEST(Quadrics, BoundaryHitsAreTheFullHitsPointAndNormals) {
    RNG rng(11);
    Transform mirrored = Translate(Vector3f(0.2f, -0.1f, 0.3f)) * Scale(-1, 1.5f, 1) *
                         Rotate(30, Vector3f(1, 1, 0));
    for (bool reverse : {false, true})
        for (const Transform &t : {Transform(), mirrored}) {
            ExpectBoundaryIsTheFullHits(Sphere(t, reverse, 1.5f, -1.2f, 1.5f, 300), rng);
            ExpectBoundaryIsTheFullHits(Cylinder(t, reverse, 1.5f, -1, 1, 300), rng);
            ExpectBoundaryIsTheFullHits(Disk(t, reverse, 0.2f, 2, 0.3f, 300), rng);
        }
}

// ---------------------------------------------------------------------------------------
// Triangle

std::shared_ptr<TriangleMesh> OneTriangle(std::vector<Normal3f> n = {},
                                          std::vector<Point2f> uv = {}, bool reverse = false) {
    return std::make_shared<TriangleMesh>(MakeTriangleMesh(
        Transform(), reverse, {0, 1, 2}, {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)},
        std::move(n), std::move(uv)));
}

TEST(Triangle, HitWithDefaultUV) {
    auto mesh = OneTriangle();
    Triangle tri(mesh.get(), 0);
    pstd::optional<ShapeIntersection> si =
        tri.Intersect(Ray(Point3f(0.25f, 0.25f, 1), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->tHit, 1, kTol);
    ExpectNear(si->intr.p, Point3f(0.25f, 0.25f, 0));
    ExpectNear(si->intr.n, Normal3f(0, 0, 1));
    EXPECT_NEAR(si->intr.uv.x, 0.5f, kTol);
    EXPECT_NEAR(si->intr.uv.y, 0.25f, kTol);
    ExpectConsistentFrame(si->intr);
    EXPECT_NEAR(tri.Area(), 0.5f, kTol);
}

TEST(Triangle, DerivativesFollowTheUVMapping) {
    auto mesh = OneTriangle({}, {Point2f(0, 0), Point2f(1, 0), Point2f(0, 1)});
    pstd::optional<ShapeIntersection> si =
        Triangle(mesh.get(), 0).Intersect(Ray(Point3f(0.2f, 0.3f, -1), Vector3f(0, 0, 1)));
    ASSERT_TRUE(si);
    ExpectNear(si->intr.dpdu, Vector3f(1, 0, 0));
    ExpectNear(si->intr.dpdv, Vector3f(0, 1, 0));
    EXPECT_NEAR(si->intr.uv.x, 0.2f, kTol);
    EXPECT_NEAR(si->intr.uv.y, 0.3f, kTol);
}

// Degenerate uv (all equal) still gives a frame in the triangle's plane.
TEST(Triangle, DegenerateUVGivesAPlanarFrame) {
    auto mesh = OneTriangle({}, {Point2f(0.5f, 0.5f), Point2f(0.5f, 0.5f), Point2f(0.5f, 0.5f)});
    pstd::optional<ShapeIntersection> si =
        Triangle(mesh.get(), 0).Intersect(Ray(Point3f(0.2f, 0.3f, 1), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->intr.dpdu.z, 0, kTol);
    EXPECT_NEAR(si->intr.dpdv.z, 0, kTol);
    EXPECT_GT(LengthSquared(Cross(si->intr.dpdu, si->intr.dpdv)), 0.5f);
    ExpectConsistentFrame(si->intr);
}

TEST(Triangle, ReverseOrientation) {
    auto mesh = OneTriangle({}, {}, true);
    pstd::optional<ShapeIntersection> si =
        Triangle(mesh.get(), 0).Intersect(Ray(Point3f(0.2f, 0.3f, 1), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    ExpectNear(si->intr.n, Normal3f(0, 0, -1));
}

// Vertex normals are authoritative: the geometric normal turns to their side, and the
// shading frame is orthonormal everywhere, including where the normals are tilted.
TEST(Triangle, ShadingNormalsAreAuthoritative) {
    Normal3f tilted = Normalize(Normal3f(0.3f, -0.2f, -1));
    auto mesh = OneTriangle({tilted, Normalize(Normal3f(-0.2f, 0.1f, -1)), Normal3f(0, 0, -1)});
    RNG rng(7);
    for (int i = 0; i < 1000; ++i) {
        Float a = rng.Uniform<Float>(), b = rng.Uniform<Float>() * (1 - a);
        Vector3f d = Normalize(Vector3f(0.1f, 0.05f, -1));
        pstd::optional<ShapeIntersection> si =
            Triangle(mesh.get(), 0).Intersect(Ray(Point3f(a, b, 0) - 2 * d, d));
        ASSERT_TRUE(si);
        EXPECT_LT(si->intr.n.z, 0);
        EXPECT_LT(si->intr.shading.n.z, 0);
        ExpectConsistentFrame(si->intr);
        EXPECT_NEAR(Dot(Normalize(si->intr.shading.dpdv), si->intr.shading.n), 0, 1e-3f);
    }
    pstd::optional<ShapeIntersection> si =
        Triangle(mesh.get(), 0).Intersect(Ray(Point3f(0, 0, 1), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    ExpectNear(si->intr.shading.n, tilted, 1e-3f);
}

// Per-vertex tangents (pbrt-v4's "S") turn the shading frame's dp/du, which carries a fabric's
// thread, away from the uv mapping's: here 45 degrees, interpolated, with or without normals,
// kept in the shading normal's plane; transformed with the mesh.
TEST(Triangle, PerVertexTangentsSetTheShadingDpdu) {
    Vector3f diagonal = Normalize(Vector3f(1, 1, 0.4f));
    std::vector<Vector3f> s(3, diagonal);
    for (bool withNormals : {false, true}) {
        std::vector<Normal3f> n;
        if (withNormals)
            n = {Normal3f(0, 0, 1), Normal3f(0, 0, 1), Normal3f(0, 0, 1)};
        auto mesh = std::make_shared<TriangleMesh>(MakeTriangleMesh(
            RotateZ(90), false, {0, 1, 2}, {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)},
            n, {}, s));
        pstd::optional<ShapeIntersection> si =
            Triangle(mesh.get(), 0).Intersect(Ray(Point3f(-0.2f, 0.2f, 1), Vector3f(0, 0, -1)));
        ASSERT_TRUE(si);
        ExpectConsistentFrame(si->intr);
        // RotateZ(90) maps (1, 1) to (-1, 1); the z part is projected out.
        ExpectNear(Normalize(si->intr.shading.dpdu), Normalize(Vector3f(-1, 1, 0)), 1e-4f);
        // The geometric dp/du still follows uv (rotated: +y).
        ExpectNear(Normalize(si->intr.dpdu), Vector3f(0, 1, 0), 1e-4f);
    }
    EXPECT_THROW(MakeTriangleMesh(Transform(), false, {0, 1, 2},
                                  {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)}, {}, {},
                                  {diagonal}),
                 std::runtime_error);
}

// With uv (0,0), (1,0), (0,1) the interpolated normal is n0 + u (n1 - n0) + v (n2 - n0): its
// derivatives are the normals' differences (pbrt-v4's dndu, dndv, unnormalized as there).
TEST(Triangle, NormalDerivativesFollowTheVertexNormals) {
    Normal3f n0(0, 0, 1), n1(0.3f, 0, 1), n2(0, -0.2f, 1);
    auto mesh = std::make_shared<TriangleMesh>(MakeTriangleMesh(
        Transform(), false, {0, 1, 2}, {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)},
        {n0, n1, n2}, {Point2f(0, 0), Point2f(1, 0), Point2f(0, 1)}));
    pstd::optional<ShapeIntersection> si =
        Triangle(mesh.get(), 0).Intersect(Ray(Point3f(0.2f, 0.3f, 1), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    ExpectNear(si->intr.shading.dndu, Normal3f(Vector3f(n1 - n0)), 1e-4f);
    ExpectNear(si->intr.shading.dndv, Normal3f(Vector3f(n2 - n0)), 1e-4f);
}

// Rays through the shared edge of two triangles hit at least one of them (no leaks).
TEST(Triangle, SharedEdgeIsWatertight) {
    auto mesh = std::make_shared<TriangleMesh>(MakeTriangleMesh(
        Transform(), false, {0, 1, 2, 2, 1, 3},
        {Point3f(0, 0, 0), Point3f(1, 0, 0.1f), Point3f(0, 1, 0.3f), Point3f(1, 1, 0)}));
    Triangle t0(mesh.get(), 0), t1(mesh.get(), 1);
    RNG rng(3);
    for (int i = 0; i < 10000; ++i) {
        Float s = rng.Uniform<Float>();
        Point3f onEdge = Point3f(1, 0, 0.1f) * (1 - s) + Point3f(0, 1, 0.3f) * s;
        Vector3f d = Normalize(Vector3f(rng.Uniform<Float>() - 0.5f, rng.Uniform<Float>() - 0.5f, -1));
        Ray ray(onEdge - d * 3, d);
        EXPECT_TRUE(t0.IntersectP(ray) || t1.IntersectP(ray)) << "leak at s = " << s;
    }
}

TEST(Triangle, MeshValidation) {
    EXPECT_THROW(MakeTriangleMesh(Transform(), false, {0, 1}, {Point3f(), Point3f()}),
                 std::runtime_error);
    EXPECT_THROW(MakeTriangleMesh(Transform(), false, {0, 1, 3}, {Point3f(), Point3f(), Point3f()}),
                 std::runtime_error);
    EXPECT_THROW(MakeTriangleMesh(Transform(), false, {0, 1, 2}, {Point3f(), Point3f(), Point3f()},
                                  {Normal3f(0, 0, 1)}),
                 std::runtime_error);
}

// pbrt-v4 stores world-space normals negated for ReverseOrientation.
TEST(Triangle, MakeMeshTransformsAndFlipsNormals) {
    TriangleMesh mesh = MakeTriangleMesh(Scale(-1, 1, 1), true, {0, 1, 2},
                                         {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)},
                                         {Normal3f(1, 0, 1), Normal3f(0, 0, 1), Normal3f(0, 0, 1)});
    ExpectNear(mesh.p[1], Point3f(-1, 0, 0));
    ExpectNear(mesh.n[0], Normal3f(1, 0, -1));
    EXPECT_TRUE(mesh.transformSwapsHandedness);
}

// ---------------------------------------------------------------------------------------
// Bilinear patch

std::shared_ptr<BilinearPatchMesh> OnePatch(Point3f p11, std::vector<Normal3f> n = {}) {
    return std::make_shared<BilinearPatchMesh>(MakeBilinearPatchMesh(
        Transform(), false, {0, 1, 2, 3},
        {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0), p11}, std::move(n)));
}

TEST(BilinearPatch, PlanarHit) {
    auto mesh = OnePatch(Point3f(1, 1, 0));
    BilinearPatch patch(mesh.get(), 0);
    pstd::optional<ShapeIntersection> si =
        patch.Intersect(Ray(Point3f(0.3f, 0.7f, 1), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->tHit, 1, kTol);
    EXPECT_NEAR(si->intr.uv.x, 0.3f, kTol);
    EXPECT_NEAR(si->intr.uv.y, 0.7f, kTol);
    ExpectNear(si->intr.n, Normal3f(0, 0, 1));
    ExpectNear(si->intr.dpdu, Vector3f(1, 0, 0));
    EXPECT_NEAR(patch.Area(), 1, kTol);
    ExpectConsistentFrame(si->intr);
}

// z = x y over the unit square: the hit lies on the ray and on the surface.
TEST(BilinearPatch, CurvedHitAndArea) {
    auto mesh = OnePatch(Point3f(1, 1, 1));
    BilinearPatch patch(mesh.get(), 0);
    RNG rng(11);
    for (int i = 0; i < 1000; ++i) {
        Float x = rng.Uniform<Float>(), y = rng.Uniform<Float>();
        Ray ray(Point3f(x, y, 5), Normalize(Vector3f(0.05f, -0.02f, -1)));
        pstd::optional<ShapeIntersection> si = patch.Intersect(ray);
        if (!si)
            continue;  // the tilted ray may leave the square
        Point3f p = si->intr.p;
        EXPECT_NEAR(p.z, p.x * p.y, 1e-4f);
        ExpectNear(ray(si->tHit), p, 1e-4f);
        EXPECT_NEAR(si->intr.uv.x, p.x, 1e-4f);
        ExpectConsistentFrame(si->intr);
    }
    // Integral of sqrt(1 + x^2 + y^2) over the unit square.
    EXPECT_NEAR(patch.Area(), 1.2807983f, 1e-4f);
}

TEST(BilinearPatch, ShadingNormals) {
    Normal3f n(0, 0, 1), t = Normalize(Normal3f(0.3f, 0, 1));
    auto mesh = OnePatch(Point3f(1, 1, 0.2f), {n, t, n, t});
    pstd::optional<ShapeIntersection> si = BilinearPatch(mesh.get(), 0).Intersect(
        Ray(Point3f(0.5f, 0.5f, 2), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    ExpectConsistentFrame(si->intr);
    EXPECT_GT(si->intr.shading.n.x, 0.05f);
}

// ---------------------------------------------------------------------------------------
// Sampling

// E[1/pdf] over area samples is the area; every sample lies on the surface (checked by
// intersecting along its normal).
template <typename S>
void CheckAreaSampling(const S &shape, int n = 200000) {
    RNG rng(5);
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        Float u0 = rng.Uniform<Float>();
        pstd::optional<ShapeSample> ss = shape.Sample(Point2f(u0, rng.Uniform<Float>()));
        ASSERT_TRUE(ss);
        ASSERT_GT(ss->pdf, 0);
        sum += 1 / ss->pdf;
        if (i % 1000 == 0) {
            Vector3f nv(ss->intr.n);
            EXPECT_TRUE(shape.IntersectP(Ray(ss->intr.p + nv * 0.01f, -nv), 0.02f) ||
                        shape.IntersectP(Ray(ss->intr.p - nv * 0.01f, nv), 0.02f));
        }
    }
    EXPECT_NEAR(sum / n, shape.Area(), 1e-3 * shape.Area());
}

TEST(ShapeSampling, AreaDensities) {
    CheckAreaSampling(Sphere(Translate(Vector3f(1, 0, 0)), false, 2, -2, 2, 360));
    CheckAreaSampling(Sphere(Scale(1, 2, 0.5f), false, 1, -0.5f, 0.8f, 270));
    CheckAreaSampling(Disk(Scale(1, 3, 1), false, 0.5f, 1, 0.3f, 300));
    CheckAreaSampling(Cylinder(Scale(1, 2, 0.5f) * RotateY(30), false, 1, -0.5f, 0.8f, 270));
    auto mesh = OneTriangle();
    CheckAreaSampling(Triangle(mesh.get(), 0));
    auto patch = OnePatch(Point3f(1.5f, 1, 1));
    CheckAreaSampling(BilinearPatch(patch.get(), 0));
}

TEST(ShapeSampling, SphereConePdf) {
    Sphere s(Translate(Vector3f(0, 0, 4)), false, 2, -2, 2, 360);
    ShapeSampleContext ctx(Point3f(0, 0, 0), Normal3f(), Normal3f());
    Float cosThetaMax = std::sqrt(1 - Sqr(0.5f));
    EXPECT_NEAR(s.PDF(ctx, Vector3f(0, 0, 1)), 1 / (2 * Pi * (1 - cosThetaMax)), 1e-3f);
    EXPECT_EQ(s.PDF(ctx, Normalize(Vector3f(0, 1, 1))), 0);
    pstd::optional<ShapeSample> ss = s.Sample(ctx, Point2f(0.3f, 0.8f));
    ASSERT_TRUE(ss);
    EXPECT_NEAR(Distance(ss->intr.p, Point3f(0, 0, 4)), 2, 1e-4f);
    EXPECT_LT(Dot(ss->intr.n, ss->intr.p - ctx.p), 0);  // the visible side
}

// Sample(ctx, u).pdf agrees with PDF(ctx, wi) where shapes sample by area.
TEST(ShapeSampling, SampleAndPdfAgree) {
    auto mesh = OneTriangle();
    auto patch = OnePatch(Point3f(1.5f, 1, 1));
    std::vector<Shape> shapes = {Triangle(mesh.get(), 0), BilinearPatch(patch.get(), 0),
                                 Disk(Transform(), false, 0, 1, 0.2f, 360),
                                 Sphere(Transform(), false, 1, -0.5f, 1, 360),
                                 Cylinder(Transform(), false, 1, -1, 1.5f, 300)};
    // A point in free space: no origin offset, so PDF's ray starts where the sample was seen
    // from (at grazing angles, an offset moves the hit noticeably).
    ShapeSampleContext ctx(Point3f(0.2f, 0.3f, 2), Normal3f(), Normal3f());
    RNG rng(9);
    for (const Shape &shape : shapes)
        for (int i = 0; i < 1000; ++i) {
            Float u0 = rng.Uniform<Float>();
            pstd::optional<ShapeSample> ss = shape.Sample(ctx, Point2f(u0, rng.Uniform<Float>()));
            if (!ss)
                continue;
            Vector3f wi = Normalize(ss->intr.p - ctx.p);
            // A clipped sphere's sample may hide behind its own front; PDF describes the front.
            pstd::optional<ShapeIntersection> front = shape.Intersect(Ray(ctx.p, wi));
            if (!front || Distance(front->intr.p, ss->intr.p) > 1e-5f)
                continue;
            Float pdf = shape.PDF(ctx, wi);
            EXPECT_NEAR(pdf, ss->pdf, 2e-3f * ss->pdf) << shape.ToString();
        }
}

// Chi-square: directions of Sample(ctx, u) against PDF(ctx, wi), for every kind of sampler.
struct ChiCase {
    const char *name;
    std::function<Shape()> make;
    Point3f ref;
    Normal3f ns = Normal3f(0, 0, 0);  // the receiver's shading normal: the cosine warp's
};

TEST(ShapeSampling, ChiSquare) {
    auto mesh = OneTriangle();
    auto patch = OnePatch(Point3f(1.5f, 1, 1));
    auto square = OnePatch(Point3f(1, 1, 0));
    std::vector<ChiCase> cases = {
        {"sphere cone", [] { return Shape(Sphere(Translate(Vector3f(0, 0, 3)), false, 1, -1, 1, 360)); },
         Point3f(0, 0, 0)},
        {"sphere inside", [] { return Shape(Sphere(Scale(2, 2, 2), false, 1, -1, 1, 360)); },
         Point3f(0.3f, 0.1f, -0.4f)},
        // From below, every direction crosses the clipped upper half at most once.
        {"sphere clipped", [] { return Shape(Sphere(Transform(), false, 1, 0, 0.9f, 250)); },
         Point3f(0.1f, 0.2f, -2)},
        {"disk", [] { return Shape(Disk(Transform(), false, 0, 1, 0.3f, 360)); },
         Point3f(0.2f, 0.3f, 0.7f)},
        // From inside the tube every direction meets the wall at most once.
        {"cylinder", [] { return Shape(Cylinder(Scale(1, 1.5f, 1), false, 1, -1, 0.5f, 290)); },
         Point3f(0.2f, -0.3f, 0.1f)},
        // Solid-angle sampling (0.9 sr), then warped toward a receiver's cosine (normals facing
        // the triangle, tilted, and edge-on to it). Area sampling is the "bilinear patch" case's.
        {"triangle", [&] { return Shape(Triangle(mesh.get(), 0)); }, Point3f(0.2f, 0.3f, 0.5f)},
        {"triangle, cosine warp", [&] { return Shape(Triangle(mesh.get(), 0)); }, Point3f(0.2f, 0.3f, 0.5f),
         Normal3f(0, 0, -1)},
        {"triangle, tilted receiver", [&] { return Shape(Triangle(mesh.get(), 0)); }, Point3f(-0.3f, 0.2f, 0.4f),
         Normal3f(Normalize(Vector3f(1, 0.5f, -0.3f)))},
        {"triangle, edge-on receiver", [&] { return Shape(Triangle(mesh.get(), 0)); }, Point3f(0.3f, 0.3f, 0.2f),
         Normal3f(1, 0, 0)},
        // A rectangular patch: by solid angle (0.6 sr), then warped (facing, tilted receivers).
        {"rectangle", [&] { return Shape(BilinearPatch(square.get(), 0)); }, Point3f(0.2f, 0.7f, 0.9f)},
        {"rectangle, cosine warp", [&] { return Shape(BilinearPatch(square.get(), 0)); }, Point3f(0.2f, 0.7f, 0.9f),
         Normal3f(0, 0, -1)},
        {"rectangle, tilted receiver", [&] { return Shape(BilinearPatch(square.get(), 0)); },
         Point3f(1.4f, -0.3f, 0.5f), Normal3f(Normalize(Vector3f(-1, 0.4f, -0.5f)))},
        // Both from far enough to look small (SampledByAreaFrom): by area, converted.
        {"triangle, small from afar", [&] { return Shape(Triangle(mesh.get(), 0)); }, Point3f(-1, 0.5f, 2.5f),
         Normal3f(0, 0, -1)},
        {"rectangle, small from afar", [&] { return Shape(BilinearPatch(square.get(), 0)); },
         Point3f(2, -1, 2.5f), Normal3f(0, 0, -1)},

        {"bilinear patch", [&] { return Shape(BilinearPatch(patch.get(), 0)); },
         Point3f(0.5f, 0.5f, 4)},
    };
    for (const ChiCase &c : cases) {
        Shape shape = c.make();
        ShapeSampleContext ctx(c.ref, c.ns, c.ns);
        auto sample = [&](Point2f u, Float) -> pstd::optional<Vector3f> {
            pstd::optional<ShapeSample> ss = shape.Sample(ctx, u);
            if (!ss || ss->pdf == 0)
                return {};
            return Normalize(ss->intr.p - ctx.p);
        };
        auto pdf = [&](Vector3f w) { return shape.PDF(ctx, w); };
        Chi2Options opts;
        opts.numTests = int(cases.size());
        opts.sampleCount = 500000;
        opts.seed = 17;
        Chi2Result r = Chi2TestSampler(sample, pdf, opts);
        EXPECT_TRUE(r.passed) << c.name << "\n" << r.message;
    }
}

// The solid angle of the octant's triangle seen from the origin is an eighth of the sphere;
// each uniform sample of a spherical triangle inverts to the u that made it.
TEST(SphericalTriangle, AreaAndInverse) {
    std::array<Point3f, 3> octant = {Point3f(1, 0, 0), Point3f(0, 1, 0), Point3f(0, 0, 1)};
    EXPECT_NEAR(SphericalTriangle(octant, Point3f(0, 0, 0)).Area(), Pi / 2, 1e-6f);
    std::array<Point3f, 3> far = {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)};
    // Small: far away it is the area over the squared distance.
    EXPECT_NEAR(SphericalTriangle(far, Point3f(0.3f, 0.3f, 100)).Area(), 0.5f / 1e4f, 1e-8f);
    RNG rng(5);
    for (Point3f p : {Point3f(0.2f, 0.3f, 0.5f), Point3f(-2, 1, 0.3f), Point3f(0.3f, 0.3f, 0.01f)})
        for (int i = 0; i < 2000; ++i) {
            Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
            SphericalTriangle spherical(far, p);
            pstd::optional<std::array<Float, 3>> b = spherical.Sample(u);
            ASSERT_TRUE(b);
            Point3f q = (*b)[0] * far[0] + (*b)[1] * far[1] + (*b)[2] * far[2];
            Point2f back = spherical.Invert(Normalize(q - p));
            EXPECT_NEAR(back.x, u.x, 2e-3f) << "p " << p.x << "," << p.y << "," << p.z;
            EXPECT_NEAR(back.y, u.y, 2e-3f) << "p " << p.x << "," << p.y << "," << p.z;
        }
}

// Uniform in solid angle where the triangle subtends between 3e-4 and 6.22 sr and does not look
// small (SampledByAreaFrom: within 18 degrees of its centroid); otherwise the area density
// converted to solid angle. Area sampling: a triangle 1e-5 sr small (too small for the spherical
// construction's precision), one 6.26 sr large (seen from just above it, where the construction
// is unstable), and one of 0.055 sr seen from 3 units away, inside a cone of 14 degrees (pbrt-v4
// samples that one by solid angle). Spherical: the same triangle from 2 units, 21 degrees.
// PDF gives the same density either way.
TEST(SphericalTriangle, AreaSamplingOutsideItsRange) {
    auto mesh = OneTriangle();
    Triangle tri(mesh.get(), 0);
    struct Case {
        Point3f p;
        bool spherical;
    };
    for (Case c : {Case{Point3f(0.2f, 0.3f, 0.5f), true}, Case{Point3f(0.2f, 0.3f, 150), false},
                   Case{Point3f(0.3f, 0.3f, 0.002f), false}, Case{Point3f(0.2f, 0.3f, 3), false},
                   Case{Point3f(0.2f, 0.3f, 2), true}}) {
        ShapeSampleContext ctx(c.p, Normal3f(), Normal3f());
        Float solidAngle = SphericalTriangle({Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)}, c.p).Area();
        RNG rng(8);
        for (int i = 0; i < 200; ++i) {
            pstd::optional<ShapeSample> ss = tri.Sample(ctx, Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
            ASSERT_TRUE(ss);
            Vector3f w = ss->intr.p - c.p;
            Float areaPdf = LengthSquared(w) / (tri.Area() * std::abs(Normalize(w).z));
            Float expected = c.spherical ? 1 / solidAngle : areaPdf;
            EXPECT_NEAR(ss->pdf, expected, 1e-3f * expected) << "solid angle " << solidAngle;
            EXPECT_NEAR(tri.PDF(ctx, Normalize(w)), ss->pdf, 1e-3f * ss->pdf) << "solid angle " << solidAngle;
        }
    }
}

// The unit square seen from above its centre at height h subtends 4 asin(1 / (1 + 4 h^2)); each
// uniform sample of a spherical rectangle inverts to the u that made it.
TEST(SphericalRectangle, AreaAndInverse) {
    for (Float h : {0.1f, 0.5f, 3.0f}) {
        SphericalRectangle rectangle(Point3f(0, 0, 0), Vector3f(1, 0, 0), Vector3f(0, 1, 0), Point3f(0.5f, 0.5f, h));
        EXPECT_NEAR(rectangle.Area(), 4 * std::asin(1 / (1 + 4 * h * h)), 1e-5f) << h;
    }
    RNG rng(6);
    for (Point3f p : {Point3f(0.2f, 0.7f, 0.9f), Point3f(-2, 1, 0.3f), Point3f(0.5f, 0.5f, -0.05f)}) {
        SphericalRectangle rectangle(Point3f(0, 0, 0), Vector3f(1, 0, 0), Vector3f(0, 2, 0), p);
        for (int i = 0; i < 2000; ++i) {
            Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
            Point2f back = rectangle.Invert(rectangle.Sample(u));
            EXPECT_NEAR(back.x, u.x, 2e-3f) << "p " << p.x << "," << p.y << "," << p.z;
            EXPECT_NEAR(back.y, u.y, 2e-3f) << "p " << p.x << "," << p.y << "," << p.z;
        }
    }
}

// Rectangular patches: uniform in solid angle within pbrt-v4's range where they do not look
// small, area sampling otherwise (the unit square from 3 above its centre fits a cone of 13
// degrees; from 1.2 above, 30 degrees) and for patches that are not rectangles; Sample's density
// is PDF's, with and without the warp.
TEST(SphericalRectangle, PatchSampleAndPdfAgree) {
    auto square = OnePatch(Point3f(1, 1, 0));
    BilinearPatch patch(square.get(), 0);
    RNG rng(4);
    enum class Density { Uniform, Warped, Area };
    struct Case {
        Point3f p;
        Normal3f ns;
        Density density;
    };
    for (Case c : {Case{Point3f(0.2f, 0.7f, 0.9f), Normal3f(0, 0, 0), Density::Uniform},
                   Case{Point3f(0.2f, 0.7f, 0.9f), Normal3f(0, 0, -1), Density::Warped},
                   Case{Point3f(0.5f, 0.5f, 200), Normal3f(0, 0, 0), Density::Area},
                   Case{Point3f(0.5f, 0.5f, 1.2f), Normal3f(0, 0, 0), Density::Uniform},
                   Case{Point3f(0.5f, 0.5f, 3), Normal3f(0, 0, 0), Density::Area}}) {
        ShapeSampleContext ctx(c.p, c.ns, c.ns);
        Float solidAngle = SphericalRectangle(Point3f(0, 0, 0), Vector3f(1, 0, 0), Vector3f(0, 1, 0), c.p).Area();
        for (int i = 0; i < 500; ++i) {
            pstd::optional<ShapeSample> ss = patch.Sample(ctx, Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
            ASSERT_TRUE(ss);
            Vector3f w = ss->intr.p - c.p;
            if (c.density == Density::Uniform) {
                EXPECT_NEAR(ss->pdf, 1 / solidAngle, 1e-4f / solidAngle);
            }
            Float areaPdf = LengthSquared(w) / std::abs(Normalize(w).z);  // the square's area is 1
            if (c.density == Density::Area) {
                EXPECT_NEAR(ss->pdf, areaPdf, 1e-4f * areaPdf);
            }
            EXPECT_NEAR(patch.PDF(ctx, Normalize(w)), ss->pdf, 5e-3f * ss->pdf) << "solid angle " << solidAngle;
        }
    }
}

// With a receiver's normal, Sample's density is the one PDF gives for the same direction.
TEST(SphericalTriangle, WarpedSampleAndPdfAgree) {
    auto mesh = OneTriangle();
    Triangle tri(mesh.get(), 0);
    ShapeSampleContext ctx(Point3f(0.1f, 0.4f, 0.6f), Normal3f(0, 0, -1), Normal3f(Normalize(Vector3f(0.3f, 0, -1))));
    RNG rng(3);
    for (int i = 0; i < 2000; ++i) {
        pstd::optional<ShapeSample> ss = tri.Sample(ctx, Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        ASSERT_TRUE(ss);
        EXPECT_NEAR(tri.PDF(ctx, Normalize(ss->intr.p - ctx.p)), ss->pdf, 5e-3f * ss->pdf);
    }
}

}  // namespace
}  // namespace pbrt
