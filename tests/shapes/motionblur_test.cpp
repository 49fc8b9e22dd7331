// Motion blur end to end: a black sphere moving across a pixel in front of a white sky leaves
// the sky showing for the analytic fraction of the shutter interval, whether the sphere, an
// instance of it or the camera moves; the aggregate finds a moving instance where its
// interpolated transform puts it; a CTM that does not change renders bit for bit as none.
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/shapes/aggregate.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace pbrt {
namespace {

std::string WriteScene(const std::string &name, const std::string &text) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "pbrt_ext_motion_test";
    std::filesystem::create_directories(dir);
    std::filesystem::path file = dir / name;
    std::ofstream(file) << text;
    return file.string();
}

// One pixel seeing a 0.02-wide square of the plane z = 0 from above (orthographic), under a
// white sky of radiance 1 (which renders to rgb 1).
std::string OnePixel(const std::string &beforeCamera) {
    return "LookAt 0 0 5  0 0 0  0 1 0\n" + beforeCamera + R"(
Camera "orthographic" "float screenwindow" [-0.01 0.01 -0.01 0.01]
Film "rgb" "integer xresolution" 1 "integer yresolution" 1 "string filename" "one.exr"
PixelFilter "box" "float xradius" 0.5 "float yradius" 0.5
Sampler "zsobol" "integer pixelsamples" 1024 "integer seed" 3
Integrator "path" "integer maxdepth" 1
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "diffuse" "rgb reflectance" [0 0 0]
)";
}

Float RenderedRed(const std::string &file) {
    RenderOverrides overrides;
    overrides.quiet = true;
    std::unique_ptr<Scene> scene = LoadScene(file, overrides);
    Render(*scene, {2, true});
    return scene->film.GetPixelRGB(Point2i(0, 0))[0];
}

// A unit sphere moving from x = -3 to x = 3 covers the pixel (to within its 0.02 width) while
// |x| < 1: a third of the interval. Threshold: 0.01 (the pixel's width moves the edges by
// 0.003 of the interval; 1024 zsobol samples stratify time far below that).
constexpr Float kSkyShowing = 2.f / 3.f, kTolerance = 0.01f;

// The CTM moving along x from `from` at the start of the motion to 3 at its end.
std::string MoveAlongX(int from) {
    return "\nActiveTransform StartTime\nTranslate " + std::to_string(from) +
           " 0 0\nActiveTransform EndTime\nTranslate 3 0 0\nActiveTransform All\n";
}

TEST(MotionBlur, MovingSphereCoversThePixelForItsAnalyticFraction) {
    std::string file =
        WriteScene("sphere.pbrt", OnePixel("") + MoveAlongX(-3) + "Shape \"sphere\"\n");
    EXPECT_NEAR(RenderedRed(file), kSkyShowing, kTolerance);
}

TEST(MotionBlur, MovingInstanceAndMovingCameraGiveTheSameFraction) {
    std::string instance = WriteScene("instance.pbrt", OnePixel("") + R"(
ObjectBegin "ball"
  Shape "sphere"
ObjectEnd
)" + MoveAlongX(-3) + "ObjectInstance \"ball\"\n");
    EXPECT_NEAR(RenderedRed(instance), kSkyShowing, kTolerance);
    // The camera moves from x = 3 to -3 past a still sphere (cameraFromWorld moves the other way).
    std::string camera =
        WriteScene("camera.pbrt", OnePixel(MoveAlongX(-3)) + "Shape \"sphere\"\n");
    EXPECT_NEAR(RenderedRed(camera), kSkyShowing, kTolerance);
}

// A moving shape inside an object moves in every instance, by its own motion after the
// instance's (Embree nests one level: each instance places the shape with the product).
TEST(MotionBlur, MovingShapeInsideAnObjectMovesInEachInstance) {
    const std::string ball = "ObjectBegin \"ball\"\n" + MoveAlongX(-3) + "Shape \"sphere\"\nObjectEnd\n";
    std::string still = WriteScene("nested-still.pbrt", OnePixel("") + ball + "ObjectInstance \"ball\"\n");
    EXPECT_NEAR(RenderedRed(still), kSkyShowing, kTolerance);
    // The instance moves from x = 0 to -3 while the sphere moves from -3 to 3 within it: x runs
    // from -3 to 0, over the pixel for the last third.
    std::string moving = WriteScene("nested-moving.pbrt", OnePixel("") + ball + R"(
ActiveTransform StartTime
Translate 0 0 0
ActiveTransform EndTime
Translate -3 0 0
ActiveTransform All
ObjectInstance "ball"
)");
    EXPECT_NEAR(RenderedRed(moving), kSkyShowing, kTolerance);
    // Placed 10 to the side, the instance keeps the sphere away from the pixel.
    std::string aside = WriteScene("nested-aside.pbrt", OnePixel("") + ball +
                                                            "Translate 0 10 0\nObjectInstance \"ball\"\n");
    EXPECT_NEAR(RenderedRed(aside), 1, kTolerance);
}

TEST(MotionBlur, ShutterAndTransformTimesSelectThePartOfTheMotionSeen) {
    // The motion spans times 0..2; the shutter sees 0..1, x from -3 to 0: the sphere covers
    // the pixel while x > -1, the last third of the shutter.
    std::string file = WriteScene("times.pbrt", "TransformTimes 0 2\n" + OnePixel("") +
                                                    MoveAlongX(-3) + "Shape \"sphere\"\n");
    EXPECT_NEAR(RenderedRed(file), kSkyShowing, kTolerance);
    std::string late = WriteScene("late.pbrt", "TransformTimes 0 2\n" + OnePixel("") +
                                                   MoveAlongX(-9) + "Shape \"sphere\"\n");
    // x from -9 to -3 during the shutter: never over the pixel.
    EXPECT_NEAR(RenderedRed(late), 1, kTolerance);
}

TEST(MotionBlur, AggregateFindsAMovingInstanceWhereItsTransformIsThen) {
    EmbreeAggregate aggregate;
    int ball = aggregate.BeginObject("ball");
    aggregate.AddSphere(Sphere(Transform(), false, 0.5f, -0.5f, 0.5f, 360), {1, -1});
    aggregate.EndObject();
    AnimatedTransform motion(Translate(Vector3f(0, 0, 0)), 0, 
                             Translate(Vector3f(0, 4, 0)) * Rotate(90, Vector3f(0, 0, 1)), 1);
    aggregate.AddInstance(ball, motion);
    aggregate.Commit();
    for (Float time : {0.f, 0.3f, 0.5f, 0.9f, 1.f}) {
        Point3f center = motion.Interpolate(time)(Point3f(0, 0, 0));
        Ray ray(center + Vector3f(0, 0, 5), Vector3f(0, 0, -1), -1, time);
        pstd::optional<ShapeIntersection> hit = aggregate.Intersect(ray);
        ASSERT_TRUE(hit) << "time " << time;
        EXPECT_NEAR(hit->tHit, 4.5f, 1e-4f);
        EXPECT_NEAR(Distance(hit->intr.p, center + Vector3f(0, 0, 0.5f)), 0, 1e-4f);
        EXPECT_EQ(hit->intr.time, time);
        // A ray through where the ball is at another time misses it now.
        Ray elsewhere(motion.Interpolate(1 - time)(Point3f(0, 0, 0)) + Vector3f(0, 0, 5),
                      Vector3f(0, 0, -1), -1, time);
        if (std::abs(1 - 2 * time) > 0.3f) {
            EXPECT_FALSE(aggregate.IntersectP(elsewhere)) << "time " << time;
        }
    }
    // Another time interval in the same aggregate is refused.
    EmbreeAggregate mixed;
    int object = mixed.BeginObject("o");
    mixed.EndObject();
    mixed.AddInstance(object, motion);
    EXPECT_THROW(mixed.AddInstance(object, AnimatedTransform(Transform(), 0,
                                                             Translate(Vector3f(1, 0, 0)), 2)),
                 std::runtime_error);
}

TEST(MotionBlur, ACTMThatDoesNotMoveRendersBitForBitAsNone) {
    const std::string scene = R"(LookAt 0 -4 2  0 0 0.5  0 0 1
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 24 "integer yresolution" 16 "string filename" "still.exr"
Sampler "zsobol" "integer pixelsamples" 8
WorldBegin
LightSource "distant" "point3 from" [1 -1 3] "rgb L" [2 2 2]
Shape "trianglemesh" "integer indices" [0 1 2 0 2 3] "point3 P" [-5 -5 0 5 -5 0 5 5 0 -5 5 0]
)";
    std::string plain = WriteScene("plain.pbrt", scene + "Translate 0 0 0.5\nShape \"sphere\" \"float radius\" 0.5\n");
    std::string still = WriteScene("still.pbrt", scene + R"(ActiveTransform EndTime
Translate 0 0 0.5
ActiveTransform StartTime
Translate 0 0 0.5
ActiveTransform All
Shape "sphere" "float radius" 0.5
)");
    RenderOverrides overrides;
    overrides.quiet = true;
    std::unique_ptr<Scene> a = LoadScene(plain, overrides), b = LoadScene(still, overrides);
    Render(*a, {2, true});
    Render(*b, {2, true});
    for (Point2i p : a->film.PixelBounds())
        for (int c = 0; c < 3; ++c)
            ASSERT_EQ(a->film.GetPixelRGB(p)[c], b->film.GetPixelRGB(p)[c]) << p.x << ", " << p.y;
}

}  // namespace
}  // namespace pbrt
