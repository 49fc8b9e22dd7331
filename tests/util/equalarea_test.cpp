// util/equalarea.h: the octahedral map and its inverse round-trip, preserve area (Jacobian
// 4 pi everywhere, uniform squares give uniform directions), and the edge wrap continues the
// sphere across the square's edges.
#include "tests/support/chi2.h"

#include "pbrt_ext/util/equalarea.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/vecmath.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pbrt;

namespace {

Float AngleOf(Vector3f a, Vector3f b) {
    return SafeACos(Dot(Normalize(a), Normalize(b)));
}

TEST(EqualArea, SquareToSphereToSquare) {
    RNG rng(1);
    for (int k = 0; k < 100000; ++k) {
        Point2f p(rng.Uniform<Float>(), rng.Uniform<Float>());
        Vector3f w = EqualAreaSquareToSphere(p);
        ASSERT_NEAR(Length(w), 1, 1e-5f) << p.x << " " << p.y;
        Point2f back = EqualAreaSphereToSquare(w);
        EXPECT_NEAR(back.x, p.x, 2e-5f);
        EXPECT_NEAR(back.y, p.y, 2e-5f);
    }
}

TEST(EqualArea, SphereToSquareToSphere) {
    RNG rng(2);
    for (int k = 0; k < 100000; ++k) {
        Float u0 = rng.Uniform<Float>();
        Vector3f w = SampleUniformSphere(Point2f(u0, rng.Uniform<Float>()));
        Point2f p = EqualAreaSphereToSquare(w);
        ASSERT_TRUE(p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1);
        EXPECT_LT(AngleOf(EqualAreaSquareToSphere(p), w), 1e-3f);
    }
    // Poles, equator and axes, where the folds meet.
    for (Vector3f w : {Vector3f(0, 0, 1), Vector3f(0, 0, -1), Vector3f(1, 0, 0),
                       Vector3f(0, -1, 0), Normalize(Vector3f(1, 1, 0))})
        EXPECT_LT(AngleOf(EqualAreaSquareToSphere(EqualAreaSphereToSquare(w)), w), 1e-5f);
}

// |dw/du x dw/dv| = 4 pi away from the creases (|u|+|v| = 1, the axes and the square's edges,
// where the map is only piecewise smooth), by central differences.
TEST(EqualArea, JacobianIsFourPi) {
    RNG rng(3);
    const Float h = 1e-3f;
    int checked = 0;
    for (int k = 0; k < 2000; ++k) {
        Point2f p(rng.Uniform<Float>(), rng.Uniform<Float>());
        Float u = 2 * p.x - 1, v = 2 * p.y - 1;
        if (std::abs(std::abs(u) + std::abs(v) - 1) < 8 * h || std::abs(u) < 8 * h ||
            std::abs(v) < 8 * h || std::abs(u) > 1 - 8 * h || std::abs(v) > 1 - 8 * h)
            continue;
        Vector3f du = (EqualAreaSquareToSphere(Point2f(p.x + h, p.y)) -
                       EqualAreaSquareToSphere(Point2f(p.x - h, p.y))) / (2 * h);
        Vector3f dv = (EqualAreaSquareToSphere(Point2f(p.x, p.y + h)) -
                       EqualAreaSquareToSphere(Point2f(p.x, p.y - h))) / (2 * h);
        EXPECT_NEAR(Length(Cross(du, dv)), 4 * Pi, 0.02f * 4 * Pi) << p.x << " " << p.y;
        ++checked;
    }
    EXPECT_GT(checked, 1000);
}

// Uniform points of the square are uniform directions: density 1 / (4 pi).
TEST(EqualArea, UniformSquareGivesUniformSphere) {
    Chi2Options opts;
    opts.seed = 4;
    Chi2Result r = Chi2TestSampler(
        [](Point2f u, Float) -> pstd::optional<Vector3f> { return EqualAreaSquareToSphere(u); },
        [](Vector3f) { return Inv4Pi; }, opts);
    EXPECT_TRUE(r.passed) << r.message;
}

TEST(EqualArea, WrapLeavesInsidePixelsAlone) {
    Point2i res(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            EXPECT_EQ(WrapEqualAreaSquare(Point2i(x, y), res), Point2i(x, y));
}

// A pixel one step outside an edge wraps to the pixel that borders it on the sphere: their
// centres are about one pixel apart, not across the map.
TEST(EqualArea, WrapContinuesAcrossEdges) {
    constexpr int n = 16;
    Point2i res(n, n);
    Float pixelAngle = std::sqrt(4 * Pi / (n * n));
    auto center = [&](Point2i p) {
        return EqualAreaSquareToSphere(Point2f((p.x + 0.5f) / n, (p.y + 0.5f) / n));
    };
    for (int i = 0; i < n; ++i) {
        struct Step {
            Point2i inside, outside;
        } steps[] = {{{0, i}, {-1, i}}, {{n - 1, i}, {n, i}}, {{i, 0}, {i, -1}},
                     {{i, n - 1}, {i, n}}};
        for (const Step &s : steps) {
            Point2i w = WrapEqualAreaSquare(s.outside, res);
            ASSERT_TRUE(w.x >= 0 && w.x < n && w.y >= 0 && w.y < n);
            EXPECT_LT(AngleOf(center(w), center(s.inside)), 2.5f * pixelAngle)
                << "outside (" << s.outside.x << ", " << s.outside.y << ") -> (" << w.x << ", "
                << w.y << ")";
        }
    }
}

}  // namespace
