// Axis-aligned boxes: pbrt-v4's empty-box convention, set operations, half-open pixel iteration.
#include "pbrt_ext/util/bounds.h"

#include <gtest/gtest.h>

#include <vector>

namespace pbrt {
namespace {

TEST(Bounds, DefaultIsEmptyAndUnionIdentity) {
    Bounds2f empty;
    EXPECT_TRUE(empty.IsEmpty());
    EXPECT_TRUE(empty.IsDegenerate());
    Bounds2f b(Point2f(1, 2), Point2f(-1, 5));  // corners in any order
    EXPECT_EQ(b.pMin, Point2f(-1, 2));
    EXPECT_EQ(b.pMax, Point2f(1, 5));
    EXPECT_EQ(Union(empty, b), b);
    EXPECT_FLOAT_EQ(b.Area(), 6);
    EXPECT_TRUE(Bounds2i(Point2i(1, 1)).IsEmpty());   // a point has no area
    EXPECT_FALSE(Bounds2i(Point2i(1, 1)).IsDegenerate());
}

TEST(Bounds, InsideVersusInsideExclusive) {
    Bounds2i b(Point2i(0, 0), Point2i(4, 3));
    EXPECT_TRUE(Inside(Point2i(4, 3), b));
    EXPECT_FALSE(InsideExclusive(Point2i(4, 3), b));
    EXPECT_TRUE(InsideExclusive(Point2i(3, 2), b));
    EXPECT_FALSE(Inside(Point2i(-1, 0), b));
    Bounds3f c(Point3f(0, 0, 0), Point3f(1, 1, 1));
    EXPECT_TRUE(Inside(Point3f(0.5f, 1, 0), c));
    EXPECT_FALSE(InsideExclusive(Point3f(0.5f, 1, 0), c));
}

TEST(Bounds, UnionIntersectOverlap) {
    Bounds2i a(Point2i(0, 0), Point2i(4, 4)), b(Point2i(2, 3), Point2i(6, 8));
    EXPECT_EQ(Intersect(a, b), Bounds2i(Point2i(2, 3), Point2i(4, 4)));
    EXPECT_EQ(Union(a, b), Bounds2i(Point2i(0, 0), Point2i(6, 8)));
    EXPECT_TRUE(Overlaps(a, b));
    Bounds2i far(Point2i(10, 10), Point2i(12, 12));
    EXPECT_FALSE(Overlaps(a, far));
    EXPECT_TRUE(Intersect(a, far).IsEmpty());
    Bounds3f u = Union(Bounds3f(Point3f(0, 0, 0)), Point3f(1, -2, 3));
    EXPECT_EQ(u.pMin, Point3f(0, -2, 0));
    EXPECT_EQ(u.pMax, Point3f(1, 0, 3));
    EXPECT_FLOAT_EQ(u.Volume(), 6);
    EXPECT_FLOAT_EQ(u.SurfaceArea(), 2 * (2 + 3 + 6));
    EXPECT_EQ(u.MaxDimension(), 2);
    EXPECT_EQ(Expand(a, 1), Bounds2i(Point2i(-1, -1), Point2i(5, 5)));
}

TEST(Bounds, LerpAndOffsetAreInverse) {
    Bounds2f b(Point2f(-2, 1), Point2f(2, 5));
    Point2f p = b.Lerp(Point2f(0.25f, 0.75f));
    EXPECT_EQ(p, Point2f(-1, 4));
    EXPECT_EQ(b.Offset(p), Vector2f(0.25f, 0.75f));
}

TEST(Bounds, BoundingSphereReachesCorners) {
    Bounds3f b(Point3f(0, 0, 0), Point3f(2, 2, 2));
    Point3f c;
    Float r;
    b.BoundingSphere(&c, &r);
    EXPECT_EQ(c, Point3f(1, 1, 1));
    EXPECT_NEAR(r, std::sqrt(3.f), 1e-6f);
}

TEST(Bounds, IteratesPixelsRowMajorHalfOpen) {
    Bounds2i b(Point2i(1, 2), Point2i(4, 4));
    std::vector<Point2i> seen;
    for (Point2i p : b) seen.push_back(p);
    ASSERT_EQ(seen.size(), 6u);
    EXPECT_EQ(seen.front(), Point2i(1, 2));
    EXPECT_EQ(seen[1], Point2i(2, 2));
    EXPECT_EQ(seen[3], Point2i(1, 3));
    EXPECT_EQ(seen.back(), Point2i(3, 3));
    int n = 0;
    for (Point2i p : Bounds2i(Point2i(3, 0), Point2i(3, 5))) n += p.x;  // zero width
    EXPECT_EQ(n, 0);
}

}  // namespace
}  // namespace pbrt
