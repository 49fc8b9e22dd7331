// The perspective camera's importance (cameraimportance.h), for paths traced from the lights:
// PDF_We's directions integrate to one over the sphere and We cos to one (the film's
// normalization); a lens point sampled from a point on the plane of focus sees it at the
// film position whose camera ray passes through it; and the crop window bounds the film.
#include "pbrt_ext/cameras/cameraimportance.h"

#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace pbrt;

namespace {

const Point2i kRes(64, 48);
const Transform kWorldFromCamera = Translate(Vector3f(1, 2, -3)) * RotateY(25);

RGBFilm Film(Bounds2i pixels = Bounds2i(Point2i(0, 0), kRes)) {
    return RGBFilm(kRes, pixels, BoxFilter(), "unused.exr");
}

Camera Perspective(Float lensRadius = 0, Float focalDistance = 1e6f) {
    return PerspectiveCamera(kWorldFromCamera, kRes, DefaultScreenWindow(kRes), 45, lensRadius,
                             focalDistance);
}

// Monte Carlo over the sphere of directions from the lens center: mean and standard error of
// f(ray) times 4 pi.
template <typename F>
std::pair<double, double> OverTheSphere(F f) {
    RNG rng(11);
    const int n = 400000;
    double sum = 0, sum2 = 0;
    Point3f o = kWorldFromCamera(Point3f(0, 0, 0));
    for (int i = 0; i < n; ++i) {
        Vector3f w = SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        double v = f(Ray(o, w)) * 4 * Pi;
        sum += v;
        sum2 += v * v;
    }
    double mean = sum / n;
    return {mean, std::sqrt((sum2 / n - mean * mean) / n)};
}

TEST(CameraImportance, DensitiesAndImportanceIntegrateToOne) {
    RGBFilm film = Film();
    CameraImportance camera(Perspective(), film);
    auto [pdf, pdfError] = OverTheSphere([&](const Ray &r) { return camera.PDF_We(r).dir; });
    EXPECT_NEAR(pdf, 1, 5 * pdfError);
    Vector3f forward = Normalize(kWorldFromCamera(Vector3f(0, 0, 1)));
    auto [we, weError] = OverTheSphere([&](const Ray &r) {
        return camera.We(r)[0] * std::max<Float>(0, Dot(r.d, forward));
    });
    EXPECT_NEAR(we, 1, 5 * weError);
    EXPECT_LT(pdfError, 0.02);
}

TEST(CameraImportance, SampledLensPointSeesTheFilmPositionOfTheCameraRay) {
    const Float focalDistance = 6;
    for (Float lensRadius : {0.f, 0.2f}) {
        Camera camera = Perspective(lensRadius, focalDistance);
        RGBFilm film = Film();
        CameraImportance importance(camera, film);
        RNG rng(13);
        for (int i = 0; i < 500; ++i) {
            Point2f pFilm(kRes.x * rng.Uniform<Float>(), kRes.y * rng.Uniform<Float>());
            Ray r = camera.GenerateRay(CameraSample{pFilm, Point2f(0.5f, 0.5f), 0, 1})->ray;
            // A point on the plane of focus (any point along a pinhole's ray).
            Vector3f forward = Normalize(kWorldFromCamera(Vector3f(0, 0, 1)));
            Point3f p = r(focalDistance / Dot(r.d, forward));
            Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
            pstd::optional<CameraWiSample> cs = importance.SampleWi(p, 0, u);
            ASSERT_TRUE(cs.has_value()) << pFilm.x << ", " << pFilm.y;
            EXPECT_NEAR(cs->pRaster.x, pFilm.x, 2e-3f);
            EXPECT_NEAR(cs->pRaster.y, pFilm.y, 2e-3f);
            EXPECT_LE(Length(cs->pLens - kWorldFromCamera(Point3f(0, 0, 0))), lensRadius + 1e-4f);
            EXPECT_GT(cs->pdf, 0);
            EXPECT_GT(cs->Wi[0], 0);
        }
    }
}

TEST(CameraImportance, OnlyTheCropWindowCarriesImportance) {
    RGBFilm film = Film(Bounds2i(Point2i(16, 12), Point2i(32, 24)));
    Camera camera = Perspective();
    CameraImportance importance(camera, film);
    auto through = [&](Point2f pFilm) {
        return camera.GenerateRay(CameraSample{pFilm, Point2f(0.5f, 0.5f), 0, 1})->ray;
    };
    Point2f pRaster;
    EXPECT_GT(importance.We(through(Point2f(20.5f, 15.5f)), &pRaster)[0], 0);
    EXPECT_NEAR(pRaster.x, 20.5f, 1e-3f);
    EXPECT_NEAR(pRaster.y, 15.5f, 1e-3f);
    EXPECT_EQ(importance.We(through(Point2f(5.5f, 15.5f)))[0], 0);
    EXPECT_EQ(importance.PDF_We(through(Point2f(20.5f, 30.5f))).dir, 0);
    // Behind the camera: nothing.
    Ray back = through(Point2f(20.5f, 15.5f));
    back.d = -back.d;
    EXPECT_EQ(importance.We(back)[0], 0);
}

TEST(CameraImportance, OtherCamerasHaveNoneAsInPbrtV4) {
    RGBFilm film = Film();
    Camera orthographic = OrthographicCamera(Transform(), kRes, DefaultScreenWindow(kRes));
    EXPECT_THROW(CameraImportance(orthographic, film), std::invalid_argument);
}

}  // namespace
