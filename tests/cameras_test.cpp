// Cameras: pbrt-v4's raster/screen/camera conventions (fov on the shorter axis, raster y down),
// thin-lens focusing, and the camera sample built from sampler and filter.
#include "pbrt_ext/cameras.h"

#include "chi2.h"

#include <gtest/gtest.h>

#include <random>

namespace pbrt {
namespace {

void ExpectDirection(Vector3f d, Vector3f expected, Float tol = 1e-5f) {
    Vector3f e = Normalize(expected);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(d[i], e[i], tol) << "component " << i;
}

CameraRay Generate(const Camera &camera, Point2f pFilm, Point2f pLens = Point2f(0.5f, 0.5f)) {
    pstd::optional<CameraRay> cr = camera.GenerateRay(CameraSample{pFilm, pLens, 0, 1});
    EXPECT_TRUE(cr.has_value());
    EXPECT_EQ(cr->weight, SampledSpectrum(1));
    return *cr;
}

TEST(Cameras, DefaultScreenWindowFollowsAspect) {
    EXPECT_EQ(DefaultScreenWindow(Point2i(200, 100)), Bounds2f(Point2f(-2, -1), Point2f(2, 1)));
    EXPECT_EQ(DefaultScreenWindow(Point2i(100, 400)), Bounds2f(Point2f(-1, -4), Point2f(1, 4)));
}

TEST(Cameras, PerspectiveFovSpansShorterAxisAndRasterYIsDown) {
    Point2i res(200, 100);
    Camera wide = PerspectiveCamera(Transform(), res, DefaultScreenWindow(res), 90);
    Ray center = Generate(wide, Point2f(100, 50)).ray;
    EXPECT_EQ(center.o, Point3f(0, 0, 0));
    ExpectDirection(center.d, Vector3f(0, 0, 1));
    ExpectDirection(Generate(wide, Point2f(100, 0)).ray.d, Vector3f(0, 1, 1));    // top edge: +y
    ExpectDirection(Generate(wide, Point2f(100, 100)).ray.d, Vector3f(0, -1, 1));
    ExpectDirection(Generate(wide, Point2f(0, 50)).ray.d, Vector3f(-2, 0, 1));    // left: -x, aspect 2
    ExpectDirection(Generate(wide, Point2f(200, 100)).ray.d, Vector3f(2, -1, 1));

    Point2i tall(50, 100);
    Camera t = PerspectiveCamera(Transform(), tall, DefaultScreenWindow(tall), 60);
    ExpectDirection(Generate(t, Point2f(50, 50)).ray.d, Vector3f(std::tan(Radians(30)), 0, 1));
}

TEST(Cameras, WorldFromCameraPlacesRays) {
    Point3f eye(1, 2, 3), look(4, 2, 3);
    Transform worldFromCamera = Inverse(LookAt(eye, look, Vector3f(0, 0, 1)));
    Point2i res(64, 64);
    Camera camera = PerspectiveCamera(worldFromCamera, res, DefaultScreenWindow(res), 45);
    Ray r = Generate(camera, Point2f(32, 32)).ray;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.o[i], eye[i], 1e-5f);
    ExpectDirection(r.d, look - eye);
    // The image's top is toward up (+z); its right is Cross(up, viewing direction) = +y, pbrt's
    // left-handed convention.
    EXPECT_GT(Generate(camera, Point2f(32, 0)).ray.d.z, 0.3f);
    EXPECT_GT(Generate(camera, Point2f(64, 32)).ray.d.y, 0.3f);
}

// Every lens position's ray passes through the pinhole ray's point on the plane of focus.
TEST(Cameras, ThinLensFocusesOnThePlaneOfFocus) {
    Point2i res(100, 80);
    Float lensRadius = 0.3f, focalDistance = 7;
    std::vector<Camera> cameras = {
        PerspectiveCamera(Transform(), res, DefaultScreenWindow(res), 50, lensRadius, focalDistance),
        OrthographicCamera(Transform(), res, DefaultScreenWindow(res), lensRadius, focalDistance)};
    std::vector<Camera> pinholes = {PerspectiveCamera(Transform(), res, DefaultScreenWindow(res), 50),
                                    OrthographicCamera(Transform(), res, DefaultScreenWindow(res))};
    std::mt19937 rng(3);
    std::uniform_real_distribution<Float> u(0, 1);
    for (size_t k = 0; k < cameras.size(); ++k)
        for (int i = 0; i < 200; ++i) {
            Point2f pFilm(100 * u(rng), 80 * u(rng));
            Ray pin = Generate(pinholes[k], pFilm).ray;
            Point3f focus = pin(focalDistance / pin.d.z);
            Ray r = Generate(cameras[k], pFilm, Point2f(u(rng), u(rng))).ray;
            EXPECT_NEAR(r.o.z, pin.o.z, 1e-6f);
            EXPECT_LE(Length(r.o - pin.o), lensRadius * (1 + 1e-5f));
            EXPECT_NEAR(Length(r.d), 1, 1e-5f);
            Point3f hit = r((focalDistance - r.o.z) / r.d.z);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(hit[c], focus[c], 1e-4f * (1 + std::abs(focus[c]))) << k;
        }
}

TEST(Cameras, OrthographicRaysAreParallelOverTheScreenWindow) {
    Point2i res(200, 100);
    Camera ortho = OrthographicCamera(Transform(), res, DefaultScreenWindow(res));
    Ray corner = Generate(ortho, Point2f(0, 0)).ray;
    EXPECT_NEAR(corner.o.x, -2, 1e-5f);
    EXPECT_NEAR(corner.o.y, 1, 1e-5f);
    EXPECT_EQ(corner.d, Vector3f(0, 0, 1));
    Ray custom = Generate(OrthographicCamera(Transform(), res, Bounds2f(Point2f(0, 0), Point2f(4, 2))),
                          Point2f(200, 100)).ray;
    EXPECT_NEAR(custom.o.x, 4, 1e-5f);
    EXPECT_NEAR(custom.o.y, 0, 1e-5f);
    EXPECT_STREQ(ortho.Name(), "orthographic");
}

TEST(Cameras, CameraSampleStaysInItsPixelForTheBoxFilter) {
    Sampler sampler = IndependentSampler(16, 0);
    Filter box = BoxFilter();
    for (int i = 0; i < 16; ++i) {
        sampler.StartPixelSample(Point2i(7, 3), i);
        CameraSample cs = GetCameraSample(sampler, Point2i(7, 3), box);
        EXPECT_GE(cs.pFilm.x, 7);
        EXPECT_LE(cs.pFilm.x, 8);
        EXPECT_GE(cs.pFilm.y, 3);
        EXPECT_LE(cs.pFilm.y, 4);
        EXPECT_EQ(cs.filterWeight, 1);
        EXPECT_GE(cs.pLens.x, 0);
        EXPECT_LT(cs.pLens.x, 1);
    }
    // A wider filter reaches into the neighbours, centered on the pixel center.
    Filter tri = TriangleFilter();
    double meanX = 0;
    for (int i = 0; i < 16; ++i) {
        sampler.StartPixelSample(Point2i(7, 3), i);
        meanX += GetCameraSample(sampler, Point2i(7, 3), tri).pFilm.x / 16;
    }
    EXPECT_NEAR(meanX, 7.5, 0.5);
}

// The equirectangular map: longitude along x from the camera's -x through +z, latitude down y
// from the camera's up (+y) to its down.
TEST(SphericalCamera, EquirectangularDirections) {
    Point2i res(400, 200);
    Camera camera = SphericalCamera(Transform(), res, SphericalCamera::Mapping::EquiRectangular);
    ExpectDirection(Generate(camera, Point2f(200, 100)).ray.d, Vector3f(-1, 0, 0));
    ExpectDirection(Generate(camera, Point2f(100, 100)).ray.d, Vector3f(0, 0, 1));
    ExpectDirection(Generate(camera, Point2f(300, 100)).ray.d, Vector3f(0, 0, -1));
    ExpectDirection(Generate(camera, Point2f(123, 0)).ray.d, Vector3f(0, 1, 0));
    ExpectDirection(Generate(camera, Point2f(77, 200)).ray.d, Vector3f(0, -1, 0));
    EXPECT_EQ(Generate(camera, Point2f(10, 10)).ray.o, Point3f(0, 0, 0));
}

// Uniform film positions give directions with the map's density: uniform over the sphere for
// the equal-area map, 1 / (2 pi^2 sin theta) for the equirectangular one (chi-square, seeded).
TEST(SphericalCamera, FilmAreaMapsToSolidAngleAsTheMappingSays) {
    Point2i res(300, 300);
    for (auto mapping : {SphericalCamera::Mapping::EqualArea,
                         SphericalCamera::Mapping::EquiRectangular}) {
        SphericalCamera camera(Transform(), res, mapping);
        auto sample = [&](Point2f u, Float) -> pstd::optional<Vector3f> {
            CameraSample cs;
            cs.pFilm = Point2f(u.x * res.x, u.y * res.y);
            return camera.GenerateRay(cs)->ray.d;
        };
        auto pdf = [&](Vector3f w) -> Float {
            if (mapping == SphericalCamera::Mapping::EqualArea)
                return 1 / (4 * Pi);
            Float sinTheta = SafeSqrt(1 - Sqr(w.y));  // the polar axis is the camera's y
            return sinTheta > 0 ? 1 / (2 * Pi * Pi * sinTheta) : 0;
        };
        Chi2Options opts;
        opts.numTests = 2;
        opts.seed = 61;
        Chi2Result r = Chi2TestSampler(sample, pdf, opts);
        EXPECT_TRUE(r.passed) << r.message;
    }
}

}  // namespace
}  // namespace pbrt
