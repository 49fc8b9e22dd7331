// EmbreeAggregate: hits agree with the shapes' own intersection routines, attributes and light
// indices reach the interaction, instances are placed and oriented, and rays spawned from hits
// inside a closed box neither re-hit their surface nor leak.
#include "pbrt_ext/shapes/aggregate.h"

#include "pbrt_ext/util/log.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"

#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

namespace pbrt {
namespace {

constexpr Float kTol = 1e-4f;

void ExpectNear(Vector3f a, Vector3f b, Float tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

void ExpectSameHit(const ShapeIntersection &a, const ShapeIntersection &b) {
    EXPECT_NEAR(a.tHit, b.tHit, 1e-4f * (1 + b.tHit));
    ExpectNear(Vector3f(a.intr.p), Vector3f(b.intr.p));
    ExpectNear(Vector3f(a.intr.n), Vector3f(b.intr.n));
    ExpectNear(Vector3f(a.intr.shading.n), Vector3f(b.intr.shading.n));
    ExpectNear(a.intr.dpdu, b.intr.dpdu, 1e-3f);
    EXPECT_NEAR(a.intr.uv.x, b.intr.uv.x, kTol);
    EXPECT_NEAR(a.intr.uv.y, b.intr.uv.y, kTol);
    ExpectNear(a.intr.wo, b.intr.wo);
}

// Two unit quads (z = 0, facing +z) as one mesh: triangles 0-1 and 2-3 at x in [0,1] and [2,3].
std::shared_ptr<TriangleMesh> TwoQuads() {
    return std::make_shared<TriangleMesh>(MakeTriangleMesh(
        Transform(), false, {0, 1, 2, 2, 1, 3, 4, 5, 6, 6, 5, 7},
        {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0), Point3f(1, 1, 0), Point3f(2, 0, 0),
         Point3f(3, 0, 0), Point3f(2, 1, 0), Point3f(3, 1, 0)},
        {}, {Point2f(0, 0), Point2f(1, 0), Point2f(0, 1), Point2f(1, 1), Point2f(0, 0),
             Point2f(1, 0), Point2f(0, 1), Point2f(1, 1)}));
}

TEST(EmbreeAggregate, HitsMatchTheShapes) {
    auto mesh = TwoQuads();
    auto patches = std::make_shared<BilinearPatchMesh>(MakeBilinearPatchMesh(
        Translate(Vector3f(0, 5, 0)), false, {0, 1, 2, 3},
        {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(0, 1, 0), Point3f(1, 1, 1)}));
    Sphere sphere(Translate(Vector3f(5, 0, 0)), false, 1, -1, 1, 360);
    Disk disk(Translate(Vector3f(10, 0, 0)), true, 0, 1, 0.25f, 360);

    EmbreeAggregate agg;
    agg.AddTriangleMesh(mesh, {3, 10});
    agg.AddBilinearPatchMesh(patches, {4, -1});
    agg.AddSphere(sphere, {5, 20});
    agg.AddDisk(disk, {6, -1});
    Cylinder cylinder(Translate(Vector3f(15, 0, 0)), false, 1, -1, 1, 270);
    agg.AddCylinder(cylinder, {9, 30});
    agg.Commit();

    struct Case {
        Ray ray;
        Shape shape;
        int material, light;
    };
    std::vector<Case> cases = {
        {Ray(Point3f(0.7f, 0.6f, 2), Vector3f(0, 0, -1)), Triangle(mesh.get(), 1), 3, 11},
        {Ray(Point3f(2.2f, 0.1f, -2), Vector3f(0.01f, 0, 1)), Triangle(mesh.get(), 2), 3, 12},
        {Ray(Point3f(0.4f, 5.3f, 3), Vector3f(0, 0, -2)), BilinearPatch(patches.get(), 0), 4, -1},
        {Ray(Point3f(5.2f, -0.1f, 4), Vector3f(0, 0, -1)), sphere, 5, 20},
        {Ray(Point3f(10.5f, 0.1f, 1), Vector3f(0, 0.1f, -1)), disk, 6, -1},
        // Through the missing quarter (phi in 270..360) onto the inside of the far wall.
        {Ray(Point3f(15.5f, -3, 0.2f), Vector3f(0, 1, 0)), cylinder, 9, 30},
    };
    for (const Case &c : cases) {
        pstd::optional<ShapeIntersection> got = agg.Intersect(c.ray);
        pstd::optional<ShapeIntersection> want = c.shape.Intersect(c.ray);
        ASSERT_TRUE(got && want) << c.shape.ToString();
        ExpectSameHit(*got, *want);
        EXPECT_EQ(got->intr.materialIndex, c.material);
        EXPECT_EQ(got->intr.areaLightIndex, c.light);
        EXPECT_TRUE(agg.IntersectP(c.ray, Infinity));
        EXPECT_FALSE(agg.IntersectP(c.ray, got->tHit * 0.99f));
        EXPECT_FALSE(agg.Intersect(c.ray, got->tHit * 0.99f));
    }
    EXPECT_FALSE(agg.Intersect(Ray(Point3f(0.5f, 0.5f, 1), Vector3f(0, 0, 1))));

    Bounds3f b = agg.WorldBound();
    EXPECT_LE(b.pMin.x, -0.0f + 1e-4f);
    EXPECT_GE(b.pMax.x, 16 - 1e-4f);
    EXPECT_GE(b.pMax.y, 6 - 1e-4f);
}

TEST(EmbreeAggregate, InstancesArePlacedAndOriented) {
    auto mesh = TwoQuads();
    EmbreeAggregate agg;
    int object = agg.BeginObject("thing");
    agg.AddTriangleMesh(mesh, {7, -1});
    agg.AddSphere(Sphere(Translate(Vector3f(0, 0, 3)), false, 0.5f, -1, 1, 360), {8, -1});
    agg.EndObject();
    agg.AddInstance(object, Translate(Vector3f(0, 0, 10)));
    // Rotated to face -z and scaled by 2.
    agg.AddInstance(object, Translate(Vector3f(0, 0, -10)) * RotateX(180) * Scale(2, 2, 2));
    agg.Commit();

    pstd::optional<ShapeIntersection> a = agg.Intersect(Ray(Point3f(0.5f, 0.5f, 11), Vector3f(0, 0, -1)));
    ASSERT_TRUE(a);
    EXPECT_NEAR(a->tHit, 1, kTol);
    ExpectNear(Vector3f(a->intr.n), Vector3f(0, 0, 1));
    EXPECT_EQ(a->intr.materialIndex, 7);

    pstd::optional<ShapeIntersection> s = agg.Intersect(Ray(Point3f(0, 0, 20), Vector3f(0, 0, -1)));
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->tHit, 6.5f, kTol);
    ExpectNear(Vector3f(s->intr.n), Vector3f(0, 0, 1));
    EXPECT_EQ(s->intr.materialIndex, 8);

    // The second instance: quads scaled to x in [0, 2] and [4, 6], y in [-2, 0], at z = -10
    // facing -z; the sphere (radius 1) centred at z = -16.
    pstd::optional<ShapeIntersection> b =
        agg.Intersect(Ray(Point3f(1, -1, -20), Vector3f(0, 0, 2)));
    ASSERT_TRUE(b);
    EXPECT_NEAR(b->tHit, 5, kTol);
    ExpectNear(Vector3f(b->intr.n), Vector3f(0, 0, -1));
    pstd::optional<ShapeIntersection> bs =
        agg.Intersect(Ray(Point3f(0, 0, -30), Vector3f(0, 0, 1)));
    ASSERT_TRUE(bs);
    EXPECT_NEAR(bs->tHit, 13, kTol);
    ExpectNear(Vector3f(bs->intr.n), Vector3f(0, 0, -1));
    pstd::optional<ShapeIntersection> q =
        agg.Intersect(Ray(Point3f(5, -1, -20), Vector3f(0, 0, 1)));
    ASSERT_TRUE(q);
    EXPECT_NEAR(q->tHit, 10, kTol);
    ExpectNear(Vector3f(q->intr.n), Vector3f(0, 0, -1));
    EXPECT_NEAR(Length(q->intr.dpdu), 2, 1e-3f);  // tangents carry the instance's scale
    ExpectNear(q->intr.wo, Vector3f(0, 0, -1));
}

TEST(EmbreeAggregate, AreaLightsInObjectsAreDropped) {
    Log().quiet = true;
    int before = Log().warnings;
    EmbreeAggregate agg;
    int object = agg.BeginObject("lamp");
    agg.AddSphere(Sphere(Transform(), false, 1, -1, 1, 360), {0, 5});
    agg.EndObject();
    agg.AddInstance(object, Transform());
    agg.Commit();
    Log().quiet = false;
    EXPECT_EQ(Log().warnings, before + 1);
    pstd::optional<ShapeIntersection> si = agg.Intersect(Ray(Point3f(0, 0, 5), Vector3f(0, 0, -1)));
    ASSERT_TRUE(si);
    EXPECT_EQ(si->intr.areaLightIndex, -1);
}

TEST(EmbreeAggregate, MisuseThrows) {
    EmbreeAggregate agg;
    EXPECT_THROW(agg.EndObject(), std::runtime_error);
    EXPECT_THROW(agg.AddInstance(0, Transform()), std::runtime_error);
    int object = agg.BeginObject("a");
    EXPECT_THROW(agg.BeginObject("b"), std::runtime_error);
    EXPECT_THROW(agg.AddInstance(object, Transform()), std::runtime_error);
    EXPECT_THROW(agg.Commit(), std::runtime_error);
}

// A closed box [-1, 1]^3 (triangles, normals inward by winding) holding a sphere and a disk.
EmbreeAggregate ClosedBox() {
    std::vector<Point3f> p;
    for (int i = 0; i < 8; ++i) p.push_back(Point3f(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    std::vector<int> idx = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                            2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
    EmbreeAggregate agg;
    agg.AddTriangleMesh(std::make_shared<TriangleMesh>(MakeTriangleMesh(Transform(), false, idx, p)),
                        {0, -1});
    agg.AddSphere(Sphere(Translate(Vector3f(0.4f, 0.3f, -0.2f)), false, 0.3f, -1, 1, 360), {1, -1});
    agg.AddDisk(Disk(RotateX(30), false, 0.5f, 0.4f, 0, 360), {2, -1});
    agg.Commit();
    return agg;
}

// Random walks inside the box: every reflected ray hits something at a distance (no self-hit,
// no leak); every ray sent through a box wall leaves (no self-hit from the far side).
TEST(EmbreeAggregate, NoSelfIntersectionInAClosedBox) {
    EmbreeAggregate agg = ClosedBox();
    RNG rng(42);
    int walls = 0;
    for (int walk = 0; walk < 2000; ++walk) {
        Ray ray(Point3f(-0.5f, -0.5f, 0.6f), SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>())));
        SurfaceInteraction previous;
        for (int bounce = 0; bounce < 20; ++bounce) {
            pstd::optional<ShapeIntersection> si = agg.Intersect(ray);
            ASSERT_TRUE(si) << "leak at walk " << walk << " bounce " << bounce;
            // Near a corner the next wall may be close, but never the surface just left.
            bool sameSurface = bounce > 0 && si->intr.materialIndex == previous.materialIndex &&
                               AbsDot(si->intr.n, previous.n) > 0.99f;
            ASSERT_FALSE(sameSurface && Distance(si->intr.p, previous.p) < 1e-3f)
                << "self-intersection at walk " << walk << " bounce " << bounce;
            previous = si->intr;
            Point3f p = si->intr.p;
            ASSERT_TRUE(std::abs(p.x) <= 1.0001f && std::abs(p.y) <= 1.0001f && std::abs(p.z) <= 1.0001f);
            Float u0 = rng.Uniform<Float>();
            Vector3f w = SampleUniformHemisphere(Point2f(u0, rng.Uniform<Float>()));
            Frame frame = Frame::FromZ(FaceForward(si->intr.n, si->intr.wo));
            if (si->intr.materialIndex == 0) {
                ++walls;
                // Through the wall: the spawned ray starts outside and must escape.
                EXPECT_FALSE(agg.Intersect(si->intr.SpawnRay(frame.FromLocal(-w))));
            }
            ray = si->intr.SpawnRay(frame.FromLocal(w));
        }
    }
    EXPECT_GT(walls, 1000);
}

TEST(EmbreeAggregate, ConcurrentQueriesAndMove) {
    EmbreeAggregate built = ClosedBox();
    EmbreeAggregate agg = std::move(built);
    auto trace = [&](uint64_t seed, std::vector<Float> *out) {
        RNG rng(seed);
        for (int i = 0; i < 20000; ++i) {
            Float u0 = rng.Uniform<Float>();
            Ray ray(Point3f(0, 0, 0.1f), SampleUniformSphere(Point2f(u0, rng.Uniform<Float>())));
            pstd::optional<ShapeIntersection> si = agg.Intersect(ray);
            out->push_back(si ? si->tHit : -1);
            EXPECT_EQ(agg.IntersectP(ray, Infinity), bool(si));
        }
    };
    std::vector<Float> serial, a, b;
    trace(1, &serial);
    std::thread t1(trace, 1, &a), t2(trace, 1, &b);
    t1.join();
    t2.join();
    EXPECT_EQ(serial, a);
    EXPECT_EQ(serial, b);
}

// The ray log of the traversal-limit benchmark: every query is kept, as asked, while a log is
// attached, none after; Traverse answers each kept ray as the query did; a full log counts the
// queries it could not keep.
TEST(EmbreeAggregate, RayLogKeepsEveryQueryAndTraverseAgrees) {
    EmbreeAggregate agg = ClosedBox();
    RayLog log(1000);
    agg.SetRayLog(&log);
    RNG rng(5);
    std::vector<bool> answers;
    for (int i = 0; i < 300; ++i) {
        Float u0 = rng.Uniform<Float>();
        Ray ray(Point3f(0, 0, 0.1f), SampleUniformSphere(Point2f(u0, rng.Uniform<Float>())));
        Float tMax = 2 * rng.Uniform<Float>();
        answers.push_back(i % 2 ? agg.IntersectP(ray, tMax) : bool(agg.Intersect(ray, tMax)));
    }
    agg.SetRayLog(nullptr);
    agg.Intersect(Ray(Point3f(0, 0, 0), Vector3f(1, 0, 0)));
    std::vector<LoggedRay> rays = log.Rays();
    ASSERT_EQ(rays.size(), answers.size());
    int hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        EXPECT_EQ(rays[i].shadow, i % 2 == 1);
        EXPECT_EQ(agg.Traverse(rays[i]), answers[i]) << "ray " << i;
        hits += answers[i];
    }
    EXPECT_GT(hits, 50);   // both answers occur: tMax cuts some rays short of the walls
    EXPECT_LT(hits, 250);

    RayLog small(10);
    agg.SetRayLog(&small);
    for (int i = 0; i < 25; ++i) agg.IntersectP(Ray(Point3f(0, 0, 0), Vector3f(0, 0, 1)), 1);
    EXPECT_EQ(small.Rays().size(), 10u);
    EXPECT_EQ(small.Queries(), 25u);
}

}  // namespace
}  // namespace pbrt
