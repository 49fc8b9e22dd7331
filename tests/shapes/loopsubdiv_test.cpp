// Loop subdivision: level-1 vertices and limit positions of a tetrahedron, a cube and a single
// triangle computed by hand from Loop's masks; limit normals along the symmetry axes; a closed
// control mesh stays closed (no ray from inside escapes); bad control meshes are errors.
#include "pbrt_ext/shapes/loopsubdiv.h"

#include "pbrt_ext/shapes/aggregate.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace pbrt {
namespace {

constexpr Float kTol = 1e-5f;

void ExpectNear(Point3f a, Point3f b, Float tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// The regular tetrahedron with vertices at alternate corners of the cube [-1, 1]^3, wound
// counter-clockwise seen from outside; its vertices sum to 0.
const std::vector<Point3f> kTetrahedronP = {Point3f(1, 1, 1), Point3f(1, -1, -1),
                                            Point3f(-1, 1, -1), Point3f(-1, -1, 1)};
const std::vector<int> kTetrahedronIndices = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};

// The cube [-1, 1]^3 (vertex i has x, y, z = +1 where bits 0, 1, 2 of i are set), each face
// split along the diagonal between two of the corners with x y z = -1 (0, 3, 5 and 6), so that
// those four have valence 6 and the other four valence 3; wound outward.
std::vector<Point3f> CubeP() {
    std::vector<Point3f> p;
    for (int i = 0; i < 8; ++i)
        p.push_back(Point3f(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    return p;
}
const std::vector<int> kCubeIndices = {
    0, 3, 1, 0, 2, 3,  // z = -1
    5, 6, 4, 5, 7, 6,  // z = +1
    0, 5, 4, 0, 1, 5,  // y = -1
    3, 6, 7, 3, 2, 6,  // y = +1
    0, 6, 2, 0, 4, 6,  // x = -1
    3, 5, 1, 3, 7, 5,  // x = +1
};

bool ContainsPoint(const std::vector<Point3f> &points, Point3f q) {
    return std::any_of(points.begin(), points.end(),
                       [&](Point3f p) { return Distance(p, q) < kTol; });
}

// Normalize(n) is +-axis, and the sign is the same for every vertex of a mesh (the caller
// compares the sign of Dot(n, axis) across vertices).
Float AxisSign(Normal3f n, Vector3f axis) {
    Float c = Dot(Normalize(Vector3f(n)), Normalize(axis));
    EXPECT_NEAR(std::abs(c), 1, 1e-5f) << "normal (" << n.x << ", " << n.y << ", " << n.z
                                       << ") off the axis (" << axis.x << ", " << axis.y << ", "
                                       << axis.z << ")";
    return c > 0 ? 1 : -1;
}

TEST(LoopSubdivide, TetrahedronLevelOneByHand) {
    // Even vertices: valence 3, beta = 3/16: 7/16 p + 3/16 (sum of the others) = 7/16 p - 3/16 p
    // = p / 4. Odd vertex on edge ab: 3/8 (a + b) + 1/8 (c + d) = 1/4 (a + b).
    SubdividedMesh level1 = LoopRefine(1, kTetrahedronIndices, kTetrahedronP);
    ASSERT_EQ(level1.p.size(), 4u + 6u);
    EXPECT_EQ(level1.indices.size(), 3u * 16u);
    EXPECT_TRUE(level1.n.empty());
    for (int i = 0; i < 4; ++i)
        ExpectNear(level1.p[i], kTetrahedronP[i] / 4);
    std::vector<Point3f> odd(level1.p.begin() + 4, level1.p.end());
    for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
            EXPECT_TRUE(ContainsPoint(odd, (kTetrahedronP[a] + Vector3f(kTetrahedronP[b])) / 4))
                << "edge " << a << "-" << b;
}

TEST(LoopSubdivide, TetrahedronLimitByHand) {
    // After level 1 a corner has valence 3 (gamma = 1/5) and its ring (the three odd vertices
    // around it) sums to (3a + b + c + d)/4 = a/2: limit 2/5 a/4 + 1/5 a/2 = a/5. An edge vertex
    // (a + b)/4 has valence 6 (gamma = 1/12) and its ring sums to (a + b)/4: limit (a + b) 7/48.
    SubdividedMesh limit = LoopSubdivide(1, kTetrahedronIndices, kTetrahedronP);
    ASSERT_EQ(limit.p.size(), 10u);
    ASSERT_EQ(limit.n.size(), 10u);
    Float sign = 0;
    for (int i = 0; i < 4; ++i) {
        ExpectNear(limit.p[i], kTetrahedronP[i] / 5);
        // The three-fold symmetry about the corner's axis leaves only the axis as its normal.
        Float s = AxisSign(limit.n[i], Vector3f(kTetrahedronP[i]));
        EXPECT_TRUE(sign == 0 || s == sign);
        sign = s;
    }
    std::vector<Point3f> edges(limit.p.begin() + 4, limit.p.end());
    for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) {
            Vector3f ab = Vector3f(kTetrahedronP[a]) + Vector3f(kTetrahedronP[b]);
            EXPECT_TRUE(ContainsPoint(edges, Point3f(ab * (7.f / 48.f))));
        }
    for (size_t i = 4; i < limit.p.size(); ++i)
        EXPECT_EQ(AxisSign(limit.n[i], Vector3f(limit.p[i])), sign);
}

TEST(LoopSubdivide, CubeLevelOneByHand) {
    // A valence-6 corner a (beta 1/16): its ring, three cube-edge and three diagonal neighbours,
    // sums to 0, so it moves to 10/16 a. A valence-3 corner b (beta 3/16): its three neighbours
    // sum to b, so it moves to 7/16 b + 3/16 b = 10/16 b as well. An odd vertex on a diagonal:
    // 3/8 of the diagonal's ends plus 1/8 of the face's other two corners, the face centre.
    // On the cube edge (1,1,1)-(1,1,-1), between faces whose other corners are (-1,1,1) and
    // (1,-1,1): 3/8 (2,2,0) + 1/8 (0,0,2) = (3/4, 3/4, 1/4); by symmetry every cube edge's odd
    // vertex is a permutation of (+-3/4, +-3/4, +-1/4).
    std::vector<Point3f> p = CubeP();
    SubdividedMesh level1 = LoopRefine(1, kCubeIndices, p);
    ASSERT_EQ(level1.p.size(), 8u + 18u);
    for (int i = 0; i < 8; ++i)
        ExpectNear(level1.p[i], p[i] * (10.f / 16.f));
    std::vector<Point3f> odd(level1.p.begin() + 8, level1.p.end());
    EXPECT_TRUE(ContainsPoint(odd, Point3f(0.75f, 0.75f, 0.25f)));
    int faceCentres = 0, edgePoints = 0;
    for (Point3f q : odd) {
        std::array<Float, 3> a = {std::abs(q.x), std::abs(q.y), std::abs(q.z)};
        std::sort(a.begin(), a.end());
        if (Distance(Point3f(a[0], a[1], a[2]), Point3f(0, 0, 1)) < kTol)
            ++faceCentres;
        else if (Distance(Point3f(a[0], a[1], a[2]), Point3f(0.25f, 0.75f, 0.75f)) < kTol)
            ++edgePoints;
    }
    EXPECT_EQ(faceCentres, 6);
    EXPECT_EQ(edgePoints, 12);
}

TEST(LoopSubdivide, CubeLimitAtLevelZeroByHand) {
    // Straight to the limit: valence 6, gamma = 1/12, ring sum 0: a/2; valence 3, gamma = 1/5,
    // ring sum b: 2/5 b + 1/5 b = 3/5 b. The cyclic permutation of the axes keeps the
    // triangulation, so each corner's normal is along its diagonal.
    std::vector<Point3f> p = CubeP();
    SubdividedMesh limit = LoopSubdivide(0, kCubeIndices, p);
    ASSERT_EQ(limit.p.size(), 8u);
    Float sign = AxisSign(limit.n[0], Vector3f(p[0]));
    for (int i = 0; i < 8; ++i) {
        bool valence6 = i == 0 || i == 3 || i == 5 || i == 6;
        ExpectNear(limit.p[i], p[i] * (valence6 ? 0.5f : 0.6f));
        EXPECT_EQ(AxisSign(limit.n[i], Vector3f(p[i])), sign) << "corner " << i;
    }
}

TEST(LoopSubdivide, OutwardWindingGivesInwardNormalsAsPbrtV4) {
    // pbrt-v4 walks a vertex's ring clockwise (seen from outside an outward-wound mesh) and
    // takes Cross(S, T): its limit normals point into the surface; a triangle's geometric normal
    // is turned to them.
    SubdividedMesh limit = LoopSubdivide(2, kTetrahedronIndices, kTetrahedronP);
    for (size_t i = 0; i < limit.p.size(); ++i)
        EXPECT_LT(Dot(limit.n[i], Vector3f(limit.p[i])), 0) << "vertex " << i;
}

TEST(LoopSubdivide, BoundaryRulesOnOneTriangle) {
    // Every vertex is on the boundary: corners by (1/8, 3/4, 1/8) along it, edges split at
    // their midpoints; at the limit, corners by (1/5, 3/5, 1/5). All stays in the plane z = 0,
    // and every limit normal is along z.
    std::vector<Point3f> p = {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0)};
    SubdividedMesh level1 = LoopRefine(1, {0, 1, 2}, p);
    ASSERT_EQ(level1.p.size(), 6u);
    ExpectNear(level1.p[0], Point3f(0.125f, 0.125f, 0));
    ExpectNear(level1.p[1], Point3f(0.75f, 0.125f, 0));
    std::vector<Point3f> odd(level1.p.begin() + 3, level1.p.end());
    for (Point3f m : {Point3f(0.5f, 0, 0), Point3f(0, 0.5f, 0), Point3f(0.5f, 0.5f, 0)})
        EXPECT_TRUE(ContainsPoint(odd, m));

    SubdividedMesh limit0 = LoopSubdivide(0, {0, 1, 2}, p);
    ExpectNear(limit0.p[0], Point3f(0.2f, 0.2f, 0));
    SubdividedMesh limit = LoopSubdivide(3, {0, 1, 2}, p);
    for (size_t i = 0; i < limit.p.size(); ++i) {
        EXPECT_EQ(limit.p[i].z, 0);
        AxisSign(limit.n[i], Vector3f(0, 0, 1));
    }
}

TEST(LoopSubdivide, UnusedVerticesAreDroppedAndOrderKept) {
    std::vector<Point3f> p = {Point3f(9, 9, 9), Point3f(0, 0, 0), Point3f(1, 0, 0),
                              Point3f(0, 1, 0)};
    SubdividedMesh level0 = LoopRefine(0, {2, 3, 1}, p);
    ASSERT_EQ(level0.p.size(), 3u);
    ExpectNear(level0.p[0], p[1]);
    ExpectNear(level0.p[2], p[3]);
    EXPECT_EQ(level0.indices, (std::vector<int>{1, 2, 0}));
}

// A closed control mesh refined to a closed surface: 10^6 rays from points inside, in uniform
// random directions, all hit it (seed fixed; threshold: no miss at all).
TEST(LoopSubdivide, ClosedMeshStaysWatertight) {
    SubdividedMesh limit = LoopSubdivide(3, kCubeIndices, CubeP());
    EXPECT_EQ(limit.indices.size(), 3u * 12u * 64u);
    EmbreeAggregate aggregate;
    aggregate.AddTriangleMesh(std::make_shared<TriangleMesh>(MakeTriangleMesh(
                                  Transform(), false, limit.indices, limit.p, limit.n)),
                              {0, -1});
    aggregate.Commit();
    RNG rng(7);
    int misses = 0;
    for (int i = 0; i < 1000000; ++i) {
        Point3f o(0.2f * (rng.Uniform<Float>() - 0.5f), 0.2f * (rng.Uniform<Float>() - 0.5f),
                  0.2f * (rng.Uniform<Float>() - 0.5f));
        Vector3f w = SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        misses += !aggregate.IntersectP(Ray(o, w));
    }
    EXPECT_EQ(misses, 0);
}

TEST(LoopSubdivide, BadControlMeshesAreErrors) {
    std::vector<Point3f> p = CubeP();
    EXPECT_THROW(LoopSubdivide(1, {0, 1}, p), std::runtime_error);
    EXPECT_THROW(LoopSubdivide(1, {0, 1, 8}, p), std::runtime_error);
    EXPECT_THROW(LoopSubdivide(1, {0, 1, -1}, p), std::runtime_error);
    EXPECT_THROW(LoopSubdivide(1, {0, 1, 1}, p), std::runtime_error);
    // Neighbours of opposite orientation share a directed edge.
    EXPECT_THROW(LoopSubdivide(1, {0, 1, 2, 0, 1, 3}, p), std::runtime_error);
    // Three triangles on one edge.
    EXPECT_THROW(LoopSubdivide(1, {0, 1, 2, 1, 0, 3, 1, 0, 4}, p), std::runtime_error);
}

}  // namespace
}  // namespace pbrt
