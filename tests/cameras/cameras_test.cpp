// Cameras: pbrt-v4's raster/screen/camera conventions (fov on the shorter axis, raster y down),
// thin-lens focusing, and the camera sample built from sampler and filter.
#include "pbrt_ext/cameras/cameras.h"
#include "pbrt_ext/interaction.h"

#include "tests/support/chi2.h"

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

// A camera ray's differentials are its neighbours one pixel over (for the perspective camera
// exactly, for the others pbrt-v4's finite difference over a twentieth of a pixel,
// extrapolated): for a pinhole they start where the ray does and point where the rays through
// the next pixels do, for every camera.
TEST(RayDifferentials, CameraRaysCarryTheirNeighbours) {
    Point2i res(64, 48);
    Transform worldFromCamera = Translate(Vector3f(1, 2, 3)) * RotateY(30);
    std::vector<Camera> cameras = {
        PerspectiveCamera(worldFromCamera, res, DefaultScreenWindow(res), 50),
        OrthographicCamera(worldFromCamera, res, DefaultScreenWindow(res)),
        SphericalCamera(worldFromCamera, res, SphericalCamera::Mapping::EquiRectangular)};
    for (const Camera &camera : cameras) {
        Point2f pFilm(20.3f, 30.6f);
        CameraSample cs;
        cs.pFilm = pFilm;
        pstd::optional<CameraRayDifferential> crd = camera.GenerateRayDifferential(cs);
        ASSERT_TRUE(crd && crd->ray.hasDifferentials) << camera.Name();
        CameraRay x = Generate(camera, pFilm + Vector2f(1, 0)), y = Generate(camera, pFilm + Vector2f(0, 1));
        EXPECT_LT(Distance(crd->ray.rxOrigin, x.ray.o), 1e-3f) << camera.Name();
        EXPECT_LT(Distance(crd->ray.ryOrigin, y.ray.o), 1e-3f) << camera.Name();
        // Directions agree to first order: within 5 % of a pixel's turn (the rest is second
        // order; the equirectangular map's pixels, 5.6 degrees here, bend the most).
        Float turnX = Length(x.ray.d - crd->ray.d), turnY = Length(y.ray.d - crd->ray.d);
        EXPECT_LT(Length(crd->ray.rxDirection - x.ray.d), 0.05f * turnX + 1e-6f) << camera.Name();
        EXPECT_LT(Length(crd->ray.ryDirection - y.ray.d), 0.05f * turnY + 1e-6f) << camera.Name();
    }
}

// The perspective camera's own differentials (pbrt-v4's PerspectiveCamera): exactly the rays
// through the film one pixel over, through the same point of the lens, pinhole and thin lens.
TEST(RayDifferentials, PerspectiveNeighboursAreTheNextPixelsRays) {
    Point2i res(64, 48);
    Transform worldFromCamera = Translate(Vector3f(1, 2, 3)) * RotateY(30);
    for (Float lensRadius : {0.f, 0.2f}) {
        Camera camera = PerspectiveCamera(worldFromCamera, res, DefaultScreenWindow(res), 50, lensRadius, 4);
        CameraSample cs;
        cs.pFilm = Point2f(20.3f, 30.6f);
        cs.pLens = Point2f(0.3f, 0.8f);
        RayDifferential ray = camera.GenerateRayDifferential(cs)->ray;
        CameraSample sx = cs, sy = cs;
        sx.pFilm.x += 1;
        sy.pFilm.y += 1;
        Ray x = camera.GenerateRay(sx)->ray, y = camera.GenerateRay(sy)->ray;
        EXPECT_LT(Distance(ray.rxOrigin, x.o), 1e-5f) << lensRadius;
        EXPECT_LT(Distance(ray.ryOrigin, y.o), 1e-5f) << lensRadius;
        EXPECT_LT(Length(ray.rxDirection - x.d), 1e-5f) << lensRadius;
        EXPECT_LT(Length(ray.ryDirection - y.d), 1e-5f) << lensRadius;
        EXPECT_EQ(Ray(ray).d, camera.GenerateRay(cs)->ray.d);  // the ray itself is unchanged
    }
}

// A plane facing a pinhole camera at distance D, with uv = its (x, y): one pixel spans
// 2 D tan(fov / 2) / N in u, from the ray's differentials exactly and from the camera's
// approximation (the smallest differential over the film, scaled by 1 / sqrt(spp)) to within
// the film's edge-to-centre variation.
TEST(RayDifferentials, FootprintOnAPlaneFacingTheCamera) {
    Point2i res(100, 100);
    Float D = 4, fov = 40;
    Camera camera = PerspectiveCamera(Transform(), res, DefaultScreenWindow(res), fov);
    CameraDifferentials approx(camera, res);
    CameraSample cs;
    cs.pFilm = Point2f(50.5f, 50.5f);
    RayDifferential ray = camera.GenerateRayDifferential(cs)->ray;
    SurfaceInteraction si;
    si.p = ray(D / ray.d.z);
    si.n = si.shading.n = Normal3f(0, 0, -1);
    si.dpdu = Vector3f(1, 0, 0);
    si.dpdv = Vector3f(0, 1, 0);
    Float pixel = 2 * D * std::tan(Radians(fov / 2)) / res.x;
    ASSERT_TRUE(si.DifferentialsFrom(ray));
    EXPECT_NEAR(std::abs(si.dudx), pixel, 1e-3f * pixel);
    EXPECT_NEAR(std::abs(si.dvdy), pixel, 1e-3f * pixel);
    EXPECT_NEAR(si.dudy, 0, 1e-3f * pixel);
    EXPECT_NEAR(si.dvdx, 0, 1e-3f * pixel);
    // 16 spp: a quarter of the pixel; the corners' pixels subtend cos^2 of the centre's.
    Vector3f dpdx, dpdy;
    approx.Approximate_dp_dxy(camera, si.p, si.n, 0, 16, &dpdx, &dpdy);
    EXPECT_LE(Length(dpdx), 0.25f * pixel * 1.001f);
    EXPECT_GE(Length(dpdx), 0.25f * pixel * 0.75f);
    // Along x and y, to within the tilt of the corner's differential (taken in its own frame).
    EXPECT_NEAR(std::abs(Normalize(dpdx).x), 1, 1e-2f);
    EXPECT_NEAR(std::abs(Normalize(dpdy).y), 1, 1e-2f);
}

// Off a flat mirror the neighbours are the mirrored neighbours, leaving from where they met the
// mirror (Igehy's reflection with dn/dx = 0); a diffuse bounce keeps none.
TEST(RayDifferentials, FlatMirrorReflectsTheNeighbours) {
    Point2i res(80, 60);
    Camera camera = PerspectiveCamera(Translate(Vector3f(0, 0, 3)) * RotateX(150), res,
                                      DefaultScreenWindow(res), 45);
    CameraSample cs;
    cs.pFilm = Point2f(33.3f, 21.7f);
    RayDifferential ray = camera.GenerateRayDifferential(cs)->ray;
    ASSERT_LT(ray.d.z, 0);
    SurfaceInteraction si;
    si.p = ray(-ray.o.z / ray.d.z);
    si.n = si.shading.n = Normal3f(0, 0, 1);
    si.dpdu = si.shading.dpdu = Vector3f(1, 0, 0);
    si.dpdv = si.shading.dpdv = Vector3f(0, 1, 0);
    si.wo = -Normalize(ray.d);
    ASSERT_TRUE(si.DifferentialsFrom(ray));
    auto mirror = [](Vector3f v) { return Vector3f(v.x, v.y, -v.z); };
    Vector3f wi = mirror(-si.wo);
    RayDifferential out = si.SpawnRay(ray, wi, BxDFFlags::SpecularReflection, 1);
    ASSERT_TRUE(out.hasDifferentials);
    Vector3f expected = mirror(ray.rxDirection - ray.d) + wi;  // wi plus the mirrored change
    EXPECT_LT(Length(out.rxDirection - expected), 1e-4f);
    EXPECT_LT(Distance(out.rxOrigin, si.p + si.dpdx), 1e-5f);
    EXPECT_FALSE(si.SpawnRay(ray, wi, BxDFFlags::DiffuseReflection, 1).hasDifferentials);
}

}  // namespace
}  // namespace pbrt
