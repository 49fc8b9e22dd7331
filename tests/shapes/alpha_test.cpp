// Alpha cut-outs (pbrt-v4's "alpha" shape parameter): alpha 0 removes a shape for closest-hit and
// shadow rays, alpha 1 changes nothing, a fractional alpha keeps a hit with that probability
// (independently for every surface along a ray), a texture cuts holes where it is 0, and the
// scene loader wires "float alpha" and "texture alpha" through to the aggregate. Curves are cut
// out too, each crossing of a round curve once.
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/shapes/aggregate.h"
#include "pbrt_ext/shapes/curves.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace pbrt {
namespace {

// The square [x0, x0 + 1] x [0, 1] at height z, facing +z, with uv = (x - x0, y).
std::shared_ptr<TriangleMesh> Quad(Float z, Float x0 = 0) {
    return std::make_shared<TriangleMesh>(MakeTriangleMesh(
        Transform(), false, {0, 1, 2, 2, 1, 3},
        {Point3f(x0, 0, z), Point3f(x0 + 1, 0, z), Point3f(x0, 1, z), Point3f(x0 + 1, 1, z)}, {},
        {Point2f(0, 0), Point2f(1, 0), Point2f(0, 1), Point2f(1, 1)}));
}

// The same square as a bilinear patch.
std::shared_ptr<BilinearPatchMesh> Patch(Float z, Float x0) {
    return std::make_shared<BilinearPatchMesh>(MakeBilinearPatchMesh(
        Transform(), false, {0, 1, 2, 3},
        {Point3f(x0, 0, z), Point3f(x0 + 1, 0, z), Point3f(x0, 1, z), Point3f(x0 + 1, 1, z)}));
}

PrimitiveAttributes WithAlpha(FloatTexture alpha, int material = 1) {
    return {material, -1, std::make_shared<const FloatTexture>(std::move(alpha))};
}

Ray Down(Float x, Float y) { return Ray(Point3f(x, y, 5), Vector3f(0, 0, -1)); }

// A fixed n x n grid of downward rays through (x0, 0)..(x0 + 1, 1), a ray per cell centre.
std::vector<Ray> Grid(int n, Float x0 = 0) {
    std::vector<Ray> rays;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) rays.push_back(Down(x0 + (i + 0.5f) / n, (j + 0.5f) / n));
    return rays;
}

double HitFraction(const std::vector<Ray> &rays, const std::function<bool(const Ray &)> &hits) {
    int count = 0;
    for (const Ray &ray : rays) count += hits(ray);
    return double(count) / rays.size();
}

TEST(Alpha, ZeroRemovesEveryKindOfShapeForBothQueries) {
    FloatTexture zero(0.f);
    EmbreeAggregate agg;
    agg.AddTriangleMesh(Quad(1), WithAlpha(zero));
    agg.AddBilinearPatchMesh(Patch(1, 2), WithAlpha(zero));
    agg.AddSphere(Sphere(Translate(Vector3f(4.5f, 0.5f, 1)), false, 0.5f, -0.5f, 0.5f, 360),
                  WithAlpha(zero));
    agg.AddDisk(Disk(Translate(Vector3f(6.5f, 0.5f, 1)), false, 0, 0.5f, 0, 360),
                WithAlpha(zero));
    agg.AddTriangleMesh(Quad(0, 0), {7, -1});  // an opaque floor under the first quad only
    agg.Commit();

    pstd::optional<ShapeIntersection> si = agg.Intersect(Down(0.3f, 0.6f));
    ASSERT_TRUE(si);
    EXPECT_EQ(si->intr.materialIndex, 7);  // the floor, through the cut-out
    EXPECT_NEAR(si->tHit, 5, 1e-4f);
    for (Float x : {2.5f, 4.5f, 6.5f}) {
        EXPECT_FALSE(agg.Intersect(Down(x, 0.5f))) << x;
        EXPECT_FALSE(agg.IntersectP(Down(x, 0.5f))) << x;
    }
    // A shadow ray from the floor up through the quad reaches the sky.
    EXPECT_FALSE(agg.IntersectP(Ray(Point3f(0.3f, 0.6f, 0.01f), Vector3f(0, 0, 1))));
}

TEST(Alpha, OneIsOpaque) {
    EmbreeAggregate agg;
    agg.AddTriangleMesh(Quad(1), WithAlpha(FloatTexture(1.f), 3));
    agg.AddSphere(Sphere(Translate(Vector3f(4.5f, 0.5f, 1)), false, 0.5f, -0.5f, 0.5f, 360),
                  WithAlpha(FloatTexture(1.f), 4));
    agg.Commit();
    for (const Ray &ray : Grid(8)) {
        pstd::optional<ShapeIntersection> si = agg.Intersect(ray);
        ASSERT_TRUE(si);
        EXPECT_EQ(si->intr.materialIndex, 3);
        EXPECT_NEAR(si->tHit, 4, 1e-4f);
        EXPECT_TRUE(agg.IntersectP(ray));
    }
    pstd::optional<ShapeIntersection> si = agg.Intersect(Down(4.5f, 0.5f));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->tHit, 3.5f, 1e-4f);  // the sphere's top
}

// 100 x 100 fixed rays: a hit fraction p has a standard error of at most 0.005; the thresholds
// are 0.03 (6 of them).
constexpr int kGrid = 100;
constexpr double kTolerance = 0.03;

TEST(Alpha, HalfIsHitAboutHalfTheTimeByBothQueries) {
    EmbreeAggregate agg;
    agg.AddTriangleMesh(Quad(1), WithAlpha(FloatTexture(0.5f)));
    agg.AddBilinearPatchMesh(Patch(1, 2), WithAlpha(FloatTexture(0.5f)));
    agg.Commit();
    for (Float x0 : {0.f, 2.f}) {
        std::vector<Ray> rays = Grid(kGrid, x0);
        double closest = HitFraction(rays, [&](const Ray &r) { return bool(agg.Intersect(r)); });
        double shadow = HitFraction(rays, [&](const Ray &r) { return agg.IntersectP(r); });
        EXPECT_NEAR(closest, 0.5, kTolerance) << x0;
        EXPECT_NEAR(shadow, 0.5, kTolerance) << x0;
        // The decision is a function of the ray: both queries agree on every ray.
        for (const Ray &r : rays) EXPECT_EQ(bool(agg.Intersect(r)), agg.IntersectP(r));
    }
}

// A straight round curve along x at height 1, 0.4 wide, under rays across its middle.
std::shared_ptr<const CurveMesh> Curve() {
    CurveDescription d;
    d.p = {Point3f(0, 0, 1), Point3f(1 / 3.f, 0, 1), Point3f(2 / 3.f, 0, 1), Point3f(1, 0, 1)};
    d.type = CurveType::Cylinder;
    d.width0 = d.width1 = 0.4f;
    return std::make_shared<const CurveMesh>(MakeCurveMesh(Transform(), false, d));
}

std::vector<Ray> AcrossTheCurve() {
    std::vector<Ray> rays;
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < 20; ++j) rays.push_back(Down(0.1f + 0.8f * (i + 0.5f) / kGrid, -0.1f + 0.2f * (j + 0.5f) / 20));
    return rays;
}

TEST(Alpha, CurvesAreCutOutLikeEveryOtherShape) {
    std::vector<Ray> rays = AcrossTheCurve();
    for (float alpha : {0.f, 0.5f, 1.f}) {
        EmbreeAggregate agg;
        agg.AddCurves(Curve(), WithAlpha(FloatTexture(alpha)));
        agg.Commit();
        double closest = HitFraction(rays, [&](const Ray &r) { return bool(agg.Intersect(r)); });
        double shadow = HitFraction(rays, [&](const Ray &r) { return agg.IntersectP(r); });
        EXPECT_NEAR(closest, alpha, kTolerance) << alpha;
        EXPECT_NEAR(shadow, alpha, kTolerance) << alpha;
    }
}

TEST(Alpha, StackedSurfacesDecideIndependently) {
    // pbrt-v4 follows a rejected hit with a new ray: two half-transparent layers (two quads, or a
    // sphere's near and far side) let 1/4 of the rays through, not 1/2.
    EmbreeAggregate agg;
    agg.AddTriangleMesh(Quad(1), WithAlpha(FloatTexture(0.5f)));
    agg.AddTriangleMesh(Quad(2), WithAlpha(FloatTexture(0.5f)));
    agg.AddSphere(Sphere(Translate(Vector3f(10.5f, 0.5f, 0)), false, 2, -2, 2, 360),
                  WithAlpha(FloatTexture(0.5f)));
    agg.Commit();
    for (Float x0 : {0.f, 10.f}) {
        std::vector<Ray> rays = Grid(kGrid, x0);
        EXPECT_NEAR(HitFraction(rays, [&](const Ray &r) { return bool(agg.Intersect(r)); }), 0.75,
                    kTolerance)
            << x0;
        EXPECT_NEAR(HitFraction(rays, [&](const Ray &r) { return agg.IntersectP(r); }), 0.75,
                    kTolerance)
            << x0;
    }
    // Where the sphere is kept, the near or the far side is hit, about equally often.
    int near = 0, far = 0;
    for (const Ray &r : Grid(kGrid, 10))
        if (pstd::optional<ShapeIntersection> si = agg.Intersect(r))
            ++(si->intr.p.z > 0 ? near : far);
    EXPECT_NEAR(double(near) / (near + far), 2 / 3., kTolerance);
}

// 1 where floor(4u) + floor(4v) is even, 0 elsewhere.
FloatTexture Checks() {
    return FloatCheckerboardTexture(UVMapping{4, 4, 0, 0}, FloatTexture(1.f), FloatTexture(0.f));
}

void ExpectCheckerHoles(const std::function<bool(const Ray &)> &hits, Float x0,
                        const Transform &worldFromObject = Transform()) {
    for (const Ray &ray : Grid(4, x0)) {
        Point3f pObj = Inverse(worldFromObject)(ray.o);
        int cell = int(std::floor(4 * (pObj.x - x0))) + int(std::floor(4 * pObj.y));
        EXPECT_EQ(hits(ray), cell % 2 == 0) << pObj.x << ", " << pObj.y;
    }
}

TEST(Alpha, CheckerboardCutsHolesWhereItIsZero) {
    EmbreeAggregate agg;
    agg.AddTriangleMesh(Quad(1), WithAlpha(Checks()));
    agg.AddBilinearPatchMesh(Patch(1, 2), WithAlpha(Checks()));
    agg.Commit();
    for (Float x0 : {0.f, 2.f}) {
        ExpectCheckerHoles([&](const Ray &r) { return bool(agg.Intersect(r)); }, x0);
        ExpectCheckerHoles([&](const Ray &r) { return agg.IntersectP(r); }, x0);
    }
}

TEST(Alpha, InstancesCutTheirHolesInObjectSpace) {
    EmbreeAggregate agg;
    int object = agg.BeginObject("checks");
    agg.AddTriangleMesh(Quad(1), WithAlpha(Checks()));
    agg.EndObject();
    Transform worldFromObject = Translate(Vector3f(10, 0, -3));
    agg.AddInstance(object, worldFromObject);
    agg.Commit();
    ExpectCheckerHoles([&](const Ray &r) { return bool(agg.Intersect(r)); }, 10, worldFromObject);
    ExpectCheckerHoles([&](const Ray &r) { return agg.IntersectP(r); }, 10, worldFromObject);
}

TEST(Alpha, ConcurrentQueriesAgreeWithSerialOnes) {
    EmbreeAggregate agg;
    agg.AddTriangleMesh(Quad(1), WithAlpha(FloatTexture(0.5f)));
    agg.AddSphere(Sphere(Translate(Vector3f(10.5f, 0.5f, 0)), false, 2, -2, 2, 360),
                  WithAlpha(FloatTexture(0.5f)));
    agg.Commit();
    std::vector<Ray> rays = Grid(kGrid, 0), more = Grid(kGrid, 10);
    rays.insert(rays.end(), more.begin(), more.end());
    std::vector<char> serial(rays.size()), parallel(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) serial[i] = agg.IntersectP(rays[i]);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (size_t i = t; i < rays.size(); i += 4) parallel[i] = agg.IntersectP(rays[i]);
        });
    for (std::thread &thread : threads) thread.join();
    EXPECT_EQ(serial, parallel);
}

// ---- Through the scene loader ------------------------------------------------------------------

// A white floor at z = 0 seen from above, lit straight down by a distant light, with `occluder`
// written above the camera: it can only cast shadows.
std::string WriteScene(const std::string &name, const std::string &occluder) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "pbrt_ext_alpha_test";
    std::filesystem::create_directories(dir);
    std::filesystem::path file = dir / name;
    std::ofstream(file) << R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 16 "integer yresolution" 16 "string filename" "out.exr"
Sampler "independent" "integer pixelsamples" 4
WorldBegin
LightSource "distant" "point3 from" [0 0 1] "point3 to" [0 0 0] "rgb L" [1 1 1]
Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-10 -10 0  10 -10 0  -10 10 0  10 10 0]
    "integer indices" [0 1 2  2 1 3]
)" << occluder << "\n";
    return file.string();
}

// The mean of the image's red channel.
double RenderMean(const std::string &file) {
    RenderOverrides overrides;
    overrides.quiet = true;
    std::unique_ptr<Scene> scene = LoadScene(file, overrides);
    Render(*scene, {0, true});
    double sum = 0;
    int n = 0;
    for (Point2i p : scene->film.PixelBounds()) {
        sum += scene->film.GetPixelRGB(p)[0];
        ++n;
    }
    return sum / n;
}

const char *kOccluder = R"(Shape "trianglemesh" "point3 P" [-10 -10 6  10 -10 6  -10 10 6  10 10 6]
    "integer indices" [0 1 2  2 1 3] "point2 uv" [0 0  1 0  0 1  1 1])";

TEST(AlphaScene, FloatAlphaZeroQuadCastsNoShadow) {
    double lit = RenderMean(WriteScene("lit.pbrt", ""));
    double opaque = RenderMean(WriteScene("opaque.pbrt", kOccluder));
    double cutOut =
        RenderMean(WriteScene("cutout.pbrt", std::string(kOccluder) + " \"float alpha\" 0"));
    ASSERT_GT(lit, 0.05);
    EXPECT_EQ(opaque, 0);
    // No hit is ever kept, so no sample differs from the unoccluded render.
    EXPECT_NEAR(cutOut, lit, 1e-6 * lit);
}

TEST(AlphaScene, TextureAlphaShadowsWhereItIsOne) {
    // A checkerboard of 0.25-unit cells (80 over the quad's 20 units): the floor in view (about
    // 2.7 units across) gets close to half of the unoccluded light.
    std::string texture =
        "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" 80 \"float vscale\" 80 "
        "\"float tex1\" 1 \"float tex2\" 0\n";
    double lit = RenderMean(WriteScene("lit.pbrt", ""));
    double checked = RenderMean(WriteScene(
        "checked.pbrt", texture + kOccluder + " \"texture alpha\" \"checks\""));
    EXPECT_NEAR(checked / lit, 0.5, 0.1);
}

}  // namespace
}  // namespace pbrt
