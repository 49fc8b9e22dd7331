// The realistic camera (pbrt-v4's lens systems): a thin lens focuses where the thin-lens
// equation says and images a point of the focus plane to a point; every ray that passes one
// of the lenses pbrt-v4's scenes use starts inside its tabulated exit pupil; the film measures
// the irradiance the lens's stop lets through, the same at every angle around the axis; the
// aperture shapes pass a circle's light in pbrt-v4's orientation; and bad lens input is an
// error at its parameter.
#include "pbrt_ext/cameras/realisticcamera.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/floatfile.h"

#include "tests/support/scenefolder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace pbrt {
namespace {

const std::filesystem::path kLenses =
    std::filesystem::path(PBRT_EXT_TEST_DATA_DIR) / "../../scenes/lenses";
constexpr int kPupilSamples = 1 << 16;  // per ring: a sixteenth of pbrt-v4's, for time

// A lens file's rows in metres, the stop opened to the lens's own diameter.
std::vector<LensElementInterface> ReadLens(const std::string &name) {
    std::string path = (kLenses / name).string();
    std::vector<double> v = ReadFloatFile(path, FileLoc{}, path, "a lens");
    std::vector<LensElementInterface> lens;
    for (size_t i = 0; i + 3 < v.size(); i += 4)
        lens.push_back({Float(v[i] / 1000), Float(v[i + 1] / 1000), Float(v[i + 2]),
                        Float(v[i + 3] / 2000)});
    return lens;
}

// A biconvex lens of n = 1.5, radii 100 mm, 3 mm thick at the centre (0.75 mm at its 30 mm
// rim), and 1 mm behind it, toward the film, a stop of 10 mm.
constexpr Float kR = 0.1f, kThickness = 0.003f, kEta = 1.5f, kStopGap = 0.001f, kStopRadius = 0.005f;
std::vector<LensElementInterface> BiconvexLens() {
    return {{kR, kThickness, kEta, 0.015f}, {-kR, kStopGap, 1, 0.015f}, {0, 0.1f, 0, kStopRadius}};
}

RealisticCamera Camera(std::vector<LensElementInterface> lens, Float focusDistance,
                       std::optional<ApertureShape> aperture = {}) {
    return RealisticCamera(Transform(), Point2i(64, 64), 0.035f, std::move(lens), focusDistance,
                           std::move(aperture), kPupilSamples);
}

// The thick lens's Gaussian optics in closed form: f from the lensmaker's equation, the
// principal planes d inside each vertex, and 1 / s_o + 1 / s_i = 1 / f between them.
TEST(RealisticCamera, FocusesWhereGaussianOpticsSays) {
    const Float F = 1;  // the focus plane 1 m from the film
    RealisticCamera camera = Camera(BiconvexLens(), F);
    double f = 1 / ((kEta - 1) * (2 / kR - (kEta - 1) * kThickness / (kEta * kR * kR)));
    double d = f * (kEta - 1) * kThickness / (kEta * kR);
    EXPECT_NEAR(camera.ThickLensApproximation().FocalLength(), f, 2e-5);
    // s_o + s_i = S, the object's distance from the film less the planes' separation.
    double S = F - kThickness + 2 * d;
    double sImage = (S - std::sqrt(S * S - 4 * S * f)) / 2;
    EXPECT_NEAR(camera.LensRearZ() + kStopGap, sImage - d, 5e-5);  // the rear vertex from the film
    // Rays from the axis point of the focus plane meet on the axis of the film: within 0.5 um
    // through the lens's middle millimetre, where 0.1 mm of defocus would spread them over
    // 0.44 um; within 25 um through the whole stop (the lens's spherical aberration, 19 um).
    Point3f object(0, 0, F);
    auto spread = [&](Float h) {
        Float widest = 0;
        for (Float x : {-1.f, -0.6f, -0.2f, 0.2f, 0.5f, 0.9f})
            for (Float y : {-0.4f, 0.f, 0.3f}) {
                Point3f pFront(x * h, y * h, camera.LensFrontZ());
                Ray out;
                if (camera.TraceLensesFromScene(Ray(object, pFront - object), &out) == 0)
                    return Infinity;
                Point3f pFilm = out(-out.o.z / out.d.z);
                widest = std::max(widest, std::hypot(pFilm.x, pFilm.y));
            }
        return widest;
    };
    EXPECT_LT(spread(0.0005f), 0.5e-6f);
    EXPECT_LT(spread(0.0045f), 25e-6f);
}

TEST(RealisticCamera, FocusingCloserMovesTheLensOut) {
    Float far = Camera(BiconvexLens(), 10).LensRearZ(), near = Camera(BiconvexLens(), 1).LensRearZ();
    EXPECT_GT(near, far);
    EXPECT_NEAR(far, 0.1f, 0.003f);  // nearly at f for a far focus
    // Nearer than four focal lengths no lens position focuses.
    EXPECT_THROW(Camera(BiconvexLens(), 0.35f), std::invalid_argument);
}

// Every ray from the film that the lens passes starts inside the exit pupil tabulated for its
// distance from the film's centre: otherwise sampling the pupil would miss light. 200000 rays
// per lens, from points of the film's radius to points of the rear element's square (seed 7).
TEST(RealisticCamera, ExitPupilBoundsHoldEveryRayThatPassesTheLens) {
    for (const char *name : {"dgauss.50mm.dat", "wide.22mm.dat", "fisheye.10mm.dat",
                             "telephoto.250mm.dat"}) {
        RealisticCamera camera = Camera(ReadLens(name), 10);
        std::mt19937 rng(7);
        std::uniform_real_distribution<Float> u(0, 1);
        Float rear = 1.5f * camera.RearElementRadius();
        int passed = 0, outside = 0;
        for (int i = 0; i < 200000; ++i) {
            Float r = u(rng) * 0.035f / 2;
            Point3f pFilm(r, 0, 0), pRear(rear * (2 * u(rng) - 1), rear * (2 * u(rng) - 1),
                                          camera.LensRearZ());
            if (camera.TraceLensesFromFilm(Ray(pFilm, pRear - pFilm), nullptr) == 0) continue;
            ++passed;
            if (!Inside(Point2f(pRear.x, pRear.y), camera.ExitPupilBounds(r))) ++outside;
        }
        EXPECT_GT(passed, 1000) << name;
        EXPECT_EQ(outside, 0) << name << ": " << passed << " rays passed";
    }
}

// The mean weight of the rays for a film point is the irradiance a radiance of 1 gives there:
// at the centre, before the lens's stop of radius a at distance d (the stop is nearest the
// film, so it is the exit pupil itself), the integral of cos^4 / d^2 over the stop,
// pi a^2 / (d^2 + a^2). Off the axis it depends only on the distance from the centre. 400000
// lens samples per point (seed 3), 1 % tolerance (the estimate's standard error is 0.1 %).
TEST(RealisticCamera, FilmMeasuresTheIrradianceTheStopPasses) {
    RealisticCamera camera = Camera(BiconvexLens(), 10);
    auto irradiance = [&](Point2f pRaster) {
        std::mt19937 rng(3);
        std::uniform_real_distribution<Float> u(0, 1);
        double sum = 0;
        const int n = 400000;
        for (int i = 0; i < n; ++i) {
            CameraSample sample{pRaster, Point2f(u(rng), u(rng)), 0.5f, 1};
            if (pstd::optional<CameraRay> cr = camera.GenerateRay(sample)) sum += cr->weight[0];
        }
        return sum / n;
    };
    Float a = kStopRadius, d = camera.LensRearZ();
    EXPECT_NEAR(irradiance(Point2f(32, 32)), Pi * a * a / (d * d + a * a), 0.01 * Pi * a * a / (d * d));
    // Film points at the same distance from the centre, along x, along y and diagonally.
    double alongX = irradiance(Point2f(56, 32));
    EXPECT_NEAR(irradiance(Point2f(32, 8)), alongX, 0.01 * alongX);
    EXPECT_NEAR(irradiance(Point2f(32 + 24 / std::sqrt(2.f), 32 - 24 / std::sqrt(2.f))), alongX,
                0.01 * alongX);
    EXPECT_LT(alongX, irradiance(Point2f(32, 32)));  // cos^4 falls off
}

TEST(RealisticCamera, RaysLeaveTheFrontElementTowardTheScene) {
    RealisticCamera camera = Camera(ReadLens("dgauss.50mm.dat"), 5);
    for (Point2f pRaster : {Point2f(32, 32), Point2f(2, 60), Point2f(60, 5)}) {
        pstd::optional<CameraRay> cr = camera.GenerateRay({pRaster, Point2f(0.5f, 0.5f), 0, 1});
        ASSERT_TRUE(cr.has_value());
        EXPECT_NEAR(cr->ray.o.z, camera.LensFrontZ(), 0.002f);
        EXPECT_GT(cr->ray.d.z, 0.5f);
        EXPECT_NEAR(Length(cr->ray.d), 1, 1e-5f);
    }
    // The lens turns the image: the film's right (raster +x) sees the scene's left (-x).
    pstd::optional<CameraRay> right = camera.GenerateRay({Point2f(60, 32), Point2f(0.5f, 0.5f), 0, 1});
    ASSERT_TRUE(right.has_value());
    EXPECT_GT(right->ray.d.x, 0.05f);
}

// Each built-in shape passes what the circle passes: its mean over the stop's square is pi/4.
TEST(ApertureShape, BuiltInShapesPassTheCirclesLightInPbrtV4sOrientation) {
    for (const char *name : {"gaussian", "square", "pentagon", "star"}) {
        std::optional<ApertureShape> shape = ApertureShape::BuiltIn(name);
        ASSERT_TRUE(shape.has_value()) << name;
        double sum = 0;
        const int n = 512;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                sum += shape->Transmission(Point2f(-1 + 2 * (x + 0.5f) / n, -1 + 2 * (y + 0.5f) / n));
        EXPECT_NEAR(sum / (n * n), Pi / 4, 2e-3) << name;
    }
    EXPECT_FALSE(ApertureShape::BuiltIn("hexagon").has_value());
    // The pentagon's vertex points to the stop's -y, its flat side to +y: pbrt-v4 flips its
    // aperture images in y before looking them up.
    std::optional<ApertureShape> pentagon = ApertureShape::BuiltIn("pentagon");
    EXPECT_GT(pentagon->Transmission(Point2f(0, -0.75f)), 0);
    EXPECT_EQ(pentagon->Transmission(Point2f(0, 0.75f)), 0);
    EXPECT_EQ(pentagon->Transmission(Point2f(0.95f, 0.95f)), 0);
}

TEST(ApertureShape, AnImagesTopRowIsTheStopsPlusY) {
    std::filesystem::path file = std::filesystem::temp_directory_path() / "pbrt_ext_aperture.exr";
    Image image(Point2i(8, 8));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, 1);
    image.Write(file.string());
    ApertureShape shape = ApertureShape::FromImage(file.string());
    EXPECT_GT(shape.Transmission(Point2f(0, 0.5f)), 0);
    EXPECT_EQ(shape.Transmission(Point2f(0, -0.5f)), 0);
    // Half the square passes: scaled by (pi/4) / (1/2).
    EXPECT_NEAR(shape.Transmission(Point2f(0.2f, 0.6f)), Pi / 2, 1e-5f);
    Image black(Point2i(4, 4));
    black.Write(file.string());
    EXPECT_THROW(ApertureShape::FromImage(file.string()), std::runtime_error);
    std::filesystem::remove(file);
}

// A scene with the realistic camera, in a fresh folder with lens.dat holding lensText.
std::string LoadError(const std::string &cameraParameters, const std::string &lensText,
                      const std::string &film = "") {
    std::filesystem::path dir = TestFolder("pbrt_ext_realistic_test");
    std::ofstream(dir / "lens.dat") << lensText;
    std::filesystem::path scene = dir / "scene.pbrt";
    std::ofstream(scene) << "Camera \"realistic\" " << cameraParameters << "\n"
                         << "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8 "
                         << film << "\nWorldBegin\n";
    return LoadErrorAfterPath(scene.string());
}

TEST(RealisticCamera, BadLensInputIsAnErrorAtItsParameter) {
    const std::string lens = "# a singlet\n0 0 0 10\n100 0.1 1.5 30\n-100 100 1 30\n";
    EXPECT_THAT(LoadError("", lens), testing::StartsWith(":1:1: error: Camera \"realistic\" needs "
                                                         "\"string lensfile\""));
    EXPECT_THAT(LoadError("\"string lensfile\" \"none.dat\"", lens),
                testing::AllOf(testing::StartsWith(":1:20: error: lens file \""),
                               testing::HasSubstr("none.dat\" cannot be read")));
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\"", lens + "1 2 x 4\n"),
                testing::HasSubstr("lens.dat\" line 5: \"x\" is not a number, expected rows of"));
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\"", lens + "1 2\n"),
                testing::HasSubstr("has 14 values, expected rows of curvature radius"));
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\"", "0 -1 0 10\n"),
                testing::HasSubstr("row 1: thickness -1"));
    std::string longLens;
    for (int i = 0; i < 257; ++i) longLens += "100 1 1.5 20\n";
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\"", longLens),
                testing::HasSubstr("has 257 element interfaces; expected at most 256"));
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\" \"float aperturediameter\" 0", lens),
                testing::StartsWith(":1:49: error: \"aperturediameter\" 0 is not positive"));
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\" \"float focusdistance\" -2", lens),
                testing::StartsWith(":1:49: error: \"focusdistance\" -2 is not positive"));
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\" \"float focusdistance\" 0.3", lens),
                testing::AllOf(testing::StartsWith(":1:20: error: lens file"),
                               testing::HasSubstr("cannot focus at 0.3 m")));
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\" \"string aperture\" \"hexagon\"", lens),
                testing::StartsWith(":1:49: error: aperture \"hexagon\" is neither a built-in shape"));
    EXPECT_THAT(LoadError("\"string lensfile\" \"lens.dat\"", lens, "\"float diagonal\" 0"),
                testing::HasSubstr("\"diagonal\" 0 mm is not positive"));
}

}  // namespace
}  // namespace pbrt
