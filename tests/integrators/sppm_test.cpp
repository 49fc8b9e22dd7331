// Stochastic progressive photon mapping: consistent, so its error against the path tracer's
// converged image falls as iterations grow, and its mean approaches it; and photons reach what
// only they can (a caustic seen on a diffuse floor).
#include "tests/support/scenes.h"

#include "pbrt_ext/render.h"

#include <memory>

#include <gtest/gtest.h>

#include <cmath>

using namespace pbrt;
using namespace pbrt::testscenes;

namespace {

IntegratorOptions Options(IntegratorType type, Float radius = 0.25f) {
    IntegratorOptions o;
    o.type = type;
    o.initialRadius = radius;
    o.photonsPerIteration = 4096;
    return o;
}

double Mean(const RGBFilm &film) {
    double sum = 0, n = 0;
    for (Point2i p : film.PixelBounds()) {
        sum += film.GetPixelRGB(p).Average();
        ++n;
    }
    return sum / n;
}

// Mean squared difference per pixel, relative to the reference's mean squared.
double RelativeError(const RGBFilm &film, const RGBFilm &reference) {
    double sum = 0, n = 0, mean = Mean(reference);
    for (Point2i p : film.PixelBounds()) {
        sum += Sqr(film.GetPixelRGB(p).Average() - reference.GetPixelRGB(p).Average());
        ++n;
    }
    return sum / n / Sqr(mean);
}

TEST(SPPM, ConvergesToThePathTracersImageAsIterationsGrow) {
    auto reference = CornellBox(Point2i(32, 32), 1024, Options(IntegratorType::Path));
    Render(*reference, {0, true});
    double previous = Infinity;
    for (int iterations : {4, 32, 256}) {
        auto sppm = CornellBox(Point2i(32, 32), iterations, Options(IntegratorType::SPPM));
        RenderStatistics stats = Render(*sppm, {0, true});
        EXPECT_EQ(stats.samplesPerPixel, iterations);
        double error = RelativeError(sppm->film, reference->film);
        EXPECT_LT(error, 0.6 * previous) << iterations << " iterations";
        previous = error;
        if (iterations == 256) {
            EXPECT_NEAR(Mean(sppm->film), Mean(reference->film), 0.02 * Mean(reference->film));
        }
    }
}

// A glass sphere over a diffuse floor under a point light, seen from above: the floor's
// caustic is light that only paths from the light find (a camera path cannot hit a point
// light). bdpt and sppm agree on it; the path tracer sees a darker floor.
std::unique_ptr<Scene> Caustic(IntegratorOptions options, int spp) {
    Point2i res(32, 32);
    SceneBuilder builder(LookingAt(Point3f(0, 4, -3), Point3f(0, 0, 0), 40, res),
                         RGBFilm(res, Bounds2i(Point2i(0, 0), res), BoxFilter(), "caustic.exr"),
                         ZSobolSampler(spp, res));
    builder.AddTriangleMesh(Quad(Point3f(-4, 0, -4), Point3f(-4, 0, 4), Point3f(4, 0, 4), Point3f(4, 0, -4)),
                            builder.AddMaterial(DiffuseMaterial{Spectrum(0.8f)}));
    builder.AddSphere(UnitSphereAt(Point3f(0, 1, 0), 0.5f), builder.AddMaterial(DielectricMaterial{}));
    builder.AddLight(PointLight(Translate(Vector3f(0.3f, 3, 0.2f)), Spectrum(10.f), 1));
    builder.SetIntegrator(options);
    auto scene = builder.Build();
    Render(*scene, {0, true});
    return scene;
}

TEST(SPPM, FindsTheCausticThatBDPTFinds) {
    auto sppm = Caustic(Options(IntegratorType::SPPM, 0.05f), 256);
    IntegratorOptions bdptOptions;
    bdptOptions.type = IntegratorType::BDPT;
    auto bdpt = Caustic(bdptOptions, 256);
    auto path = Caustic(IntegratorOptions{}, 256);
    EXPECT_NEAR(Mean(sppm->film), Mean(bdpt->film), 0.02 * Mean(bdpt->film));
    EXPECT_LT(Mean(path->film), 0.95 * Mean(bdpt->film));
}

TEST(SPPM, CountsTheSkyThatLightSamplingLeavesToBSDFSampling) {
    // A diffuse floor and wall under a uniform sky only: next-event estimation with MIS leaves
    // the uniform sky to BSDF sampling (pbrt-v4's allowIncompletePDF), so the camera path must
    // go one bounce past its visible point to find it, as in pbrt-v4; photons never count
    // direct light.
    auto render = [](IntegratorOptions options, int spp) {
        Point2i res(24, 24);
        SceneBuilder builder(LookingAt(Point3f(0, 2, -4), Point3f(0, 0.5f, 0), 50, res),
                             RGBFilm(res, Bounds2i(Point2i(0, 0), res), BoxFilter(), "sky.exr"),
                             ZSobolSampler(spp, res));
        int white = builder.AddMaterial(DiffuseMaterial{Spectrum(0.6f)});
        builder.AddTriangleMesh(Quad(Point3f(-4, 0, -4), Point3f(-4, 0, 4), Point3f(4, 0, 4), Point3f(4, 0, -4)), white);
        builder.AddTriangleMesh(Quad(Point3f(-4, 0, 1), Point3f(-4, 3, 1), Point3f(4, 3, 1), Point3f(4, 0, 1)), white);
        builder.AddLight(UniformInfiniteLight(Spectrum(1.f), 1));
        builder.SetIntegrator(options);
        auto scene = builder.Build();
        Render(*scene, {0, true});
        return scene;
    };
    auto sppm = render(Options(IntegratorType::SPPM, 0.1f), 64);
    auto path = render(IntegratorOptions{}, 256);
    EXPECT_NEAR(Mean(sppm->film), Mean(path->film), 0.02 * Mean(path->film));
}

}  // namespace
