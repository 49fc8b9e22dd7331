// End to end: analytic scenes through every integrator strategy, the strategies against each other,
// thread-count invariance, and no NaN anywhere.
#include "tests/support/imagestats.h"
#include "tests/support/scenes.h"

#include "pbrt_ext/bxdfs/albedo.h"
#include "pbrt_ext/bxdfs/fabric_albedo.h"
#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/render.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pbrt;
using namespace pbrt::testscenes;

namespace {

constexpr PathStrategy kStrategies[] = {PathStrategy::MIS, PathStrategy::BSDF, PathStrategy::Light};
// Estimates within this many standard errors of the analytic value pass (two-sided 3σ: a wrong
// implementation biased by more than the noise fails; a correct one fails 0.3 % of the time per
// check, and the seeds are fixed).
constexpr double kSigmas = 3;
// Float arithmetic along a path: the floor of the tolerance where the estimator has no variance.
constexpr double kFloatFloor = 1e-5;
// The RGB -> spectrum -> RGB round trip of the sigmoid table, per channel for an RGB in [0, 1]
// (tests/spectra/rgbtospectrum_test.cpp). An "rgb" emitter's spectrum is the table's fit to rgb / (2 max
// rgb) times that scale, so its round trip is within kRGBRoundTrip * 2 max(rgb) (times the light's
// scale).
constexpr double kRGBRoundTrip = 1e-3;

struct Estimate {
    double mean, standardError;
};

// Li along one ray at one of the sample's wavelengths (drawn as the renderer draws them), averaged
// over n independent samples, with its standard error. The analytic scenes it is used on have
// constant spectra, so the value is the same at every wavelength.
Estimate EstimateLi(const Scene &scene, IntegratorOptions options, const Ray &ray, int n,
                    int channel = 0) {
    PathIntegrator integrator(scene, options);
    Sampler sampler = IndependentSampler(n, 7);
    RayCounts rays;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        sampler.StartPixelSample(Point2i(3, 5), i);
        SampledWavelengths lambda = SampledWavelengths::SampleVisible(sampler.Get1D());
        double L = integrator.Li(ray, lambda, sampler, rays)[channel];
        sum += L;
        sum2 += L * L;
    }
    double mean = sum / n, variance = std::max(0.0, sum2 / n - mean * mean);
    return {mean, std::sqrt(variance / (n - 1))};
}

void ExpectNear(Estimate e, double expected, const std::string &what) {
    EXPECT_NEAR(e.mean, expected, kSigmas * e.standardError + kFloatFloor * std::abs(expected))
        << what << ": standard error " << e.standardError;
}

// The mean of channel c over the film's pixels, with its standard error from the pixels' spread.
// For images whose pixels are independent estimates of one value (an emitter or a plane filling
// the view): the noise is then the wavelength sampling's, the film's spectral-to-RGB estimate.
Estimate ImageMean(const RGBFilm &film, int c) {
    ChannelStatistics s = ImageStatistics(film);
    return {s.mean[c], s.standardError[c]};
}

// A sphere of material m alone in a uniform white environment.
std::unique_ptr<Scene> SphereInFurnace(Material m, Float environment) {
    SceneBuilder builder(LookingAt(Point3f(0, 0, 5), Point3f(0, 0, 0), 30, Point2i(8, 8)),
                         BoxFilteredFilm(Point2i(8, 8)), IndependentSampler(1));
    builder.AddSphere(UnitSphereAt(Point3f(0, 0, 0)), builder.AddMaterial(std::move(m)));
    builder.AddLight(UniformInfiniteLight(Spectrum(environment), 1));
    return builder.Build();
}

// Rays from a camera position toward several points of the unit sphere at the origin.
std::vector<Ray> RaysAtUnitSphere() {
    std::vector<Ray> rays;
    Point3f eye(0.3f, 0.2f, 5);
    for (Point3f target : {Point3f(0, 0, 1), Point3f(0.6f, 0, 0.8f), Point3f(-0.5f, 0.7f, 0.5f),
                           Point3f(0.9f, 0.3f, 0.31f)})
        rays.push_back(Ray(eye, Normalize(target - eye)));
    return rays;
}

bool AllPixelsFinite(const RGBFilm &film) {
    for (Point2i p : film.PixelBounds()) {
        RGB rgb = film.GetPixelRGB(p);
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(rgb[c]))
                return false;
    }
    return true;
}

}  // namespace

TEST(RenderFurnace, DiffuseSphereReflectsAlbedoTimesEnvironment) {
    // A convex diffuse surface sees only the environment: Lo = ρ L exactly.
    constexpr Float rho = 0.6f, L = 1.5f;
    auto scene = SphereInFurnace(DiffuseMaterial{Spectrum(rho)}, L);
    for (PathStrategy strategy : kStrategies)
        for (const Ray &ray : RaysAtUnitSphere())
            ExpectNear(EstimateLi(*scene, PathTracer(5, strategy), ray, 20000), rho * L,
                       "diffuse, strategy " + ToString(strategy));
}

TEST(RenderFurnace, FabricSphereReflectsItsDirectionalAlbedoTimesEnvironment) {
    // Lo(wo) = a(wo) L with a the directional albedo at the hit, by quadrature (docs/fabric.md).
    constexpr Float L = 2;
    FabricMaterial fabric;
    fabric.reflectance = Spectrum(0.9f);
    fabric.roughness = 0.3f;
    fabric.threadAngle = 30;
    auto scene = SphereInFurnace(fabric, L);
    for (const Ray &ray : RaysAtUnitSphere()) {
        pstd::optional<ShapeIntersection> hit = scene->Intersect(ray);
        ASSERT_TRUE(hit);
        const SurfaceInteraction &si = hit->intr;
        // The same BxDF the material makes, in the same shading frame.
        BSDF frame(si.shading.n, si.shading.dpdu, DiffuseBxDF(SampledSpectrum(1)));
        FabricBxDF bxdf(SampledSpectrum(0.9f), 0.3f, FabricBxDF::ThreadDirection(30, 0));
        double expected = FabricDirectionalAlbedo(bxdf, frame.RenderToLocal(si.wo)) * L;
        for (PathStrategy strategy : kStrategies)
            ExpectNear(EstimateLi(*scene, PathTracer(5, strategy), ray, 20000), expected,
                       "fabric, strategy " + ToString(strategy));
    }
}

TEST(RenderFurnace, LosslessGlassIsInvisibleInAWhiteFurnace) {
    // Every path through a non-absorbing dielectric eventually leaves it and sees the environment:
    // Lo = L along every ray, for smooth and thin glass. This checks the 1/eta² radiance scaling
    // on the way in and out, and Russian roulette on the eta-free throughput. (Rough microfacet
    // glass is not lossless: single scattering drops the inter-reflection between facets, 34 % of
    // the light through this sphere at roughness 0.3.)
    constexpr Float L = 1;
    for (Material glass : {Material(DielectricMaterial{}), Material(ThinDielectricMaterial{})}) {
        auto scene = SphereInFurnace(glass, L);
        for (const Ray &ray : RaysAtUnitSphere())
            ExpectNear(EstimateLi(*scene, PathTracer(100), ray, 20000), L,
                       "glass");
    }
}

TEST(RenderDirect, EmitterSeenDirectlyIsItsRadiance) {
    // An emitter of "rgb L [2 3 4]" at scale 1.5 fills the view: every pixel estimates its RGB,
    // 1.5 (2, 3, 4). Spectral transport makes each sample an estimate (the film integrates the
    // emission spectrum against the sensor's curves at the sample's four wavelengths), so the
    // image mean is compared within kSigmas standard errors plus the RGB -> spectrum -> RGB round
    // trip of the sigmoid table (kRGBRoundTrip: 2 max(rgb) = 8, times the scale).
    SceneBuilder builder(LookingAt(Point3f(0, 0, 3), Point3f(0, 0, 0), 20, Point2i(8, 8)),
                         BoxFilteredFilm(Point2i(8, 8)), IndependentSampler(4096));
    int black = builder.AddMaterial(DiffuseMaterial{Spectrum(0.f)});
    builder.AddTriangleMesh(Rectangle(-5, 5, -5, 5, 0), black, RGBAreaLight(2, 3, 4, 1.5f));
    auto scene = builder.Build();
    for (PathStrategy strategy : kStrategies) {
        scene->integratorOptions.strategy = strategy;
        scene->film = BoxFilteredFilm(Point2i(8, 8));
        Render(*scene, {1, true});
        for (int c = 0; c < 3; ++c) {
            double expected = 1.5 * (2 + c), roundTrip = kRGBRoundTrip * 2 * 4 * 1.5;
            Estimate e = ImageMean(scene->film, c);
            EXPECT_NEAR(e.mean, expected, kSigmas * e.standardError + roundTrip)
                << "strategy " << ToString(strategy) << ", channel " << c << ": standard error "
                << e.standardError;
        }
    }
}

TEST(RenderDirect, OneSidedEmitterIsDarkFromBehind) {
    SceneBuilder builder(LookingAt(Point3f(0, 0, 3), Point3f(0, 0, 0), 20, Point2i(4, 4)),
                         BoxFilteredFilm(Point2i(4, 4)), IndependentSampler(4));
    int black = builder.AddMaterial(DiffuseMaterial{Spectrum(0.f)});
    builder.AddTriangleMesh(Rectangle(-5, 5, -5, 5, 0, true), black, RGBAreaLight(1, 1, 1));
    auto scene = builder.Build();
    Render(*scene, {1, true});
    for (Point2i p : scene->film.PixelBounds())
        EXPECT_EQ(scene->film.GetPixelRGB(p)[0], 0);
}

TEST(RenderDirect, DiffusePlaneUnderDistantLightIsReflectanceTimesIrradianceOverPi) {
    // Lo = R E / π, E = L cos θ: the light comes from 40° off the normal; nothing else is visible.
    // The light is white (D65 of luminance L) and the plane grey, so the image is the grey
    // Lo (1, 1, 1) exactly in expectation (sRGB's white is D65's chromaticity); each sample carries
    // the film's wavelength-sampling noise, hence the image mean within kSigmas standard errors.
    constexpr Float R = 0.5f, L = 3, theta = 40;
    SceneBuilder builder(LookingAt(Point3f(0, 0, 4), Point3f(0, 0, 0), 20, Point2i(8, 8)),
                         BoxFilteredFilm(Point2i(8, 8)), IndependentSampler(256));
    builder.AddTriangleMesh(Rectangle(-20, 20, -20, 20, 0),
                            builder.AddMaterial(DiffuseMaterial{Spectrum(R)}));
    // DistantLight sends light from worldFromLight(0, 0, 1): tilt +z by θ about x.
    Emission white = WhiteEmission(L);
    builder.AddLight(DistantLight(RotateX(theta), white.spectrum, white.scale));
    auto scene = builder.Build();
    // A delta light is found only by light sampling: the mis and light strategies.
    for (PathStrategy strategy : {PathStrategy::MIS, PathStrategy::Light}) {
        scene->integratorOptions.strategy = strategy;
        scene->film = BoxFilteredFilm(Point2i(8, 8));
        RenderStatistics stats = Render(*scene, {2, true});
        EXPECT_EQ(stats.discardedSamples, 0);
        double expected = R * L * std::cos(Radians(theta)) / Pi;
        for (int c = 0; c < 3; ++c) {
            Estimate e = ImageMean(scene->film, c);
            EXPECT_NEAR(e.mean, expected, kSigmas * e.standardError + kFloatFloor * expected)
                << "strategy " << ToString(strategy) << ", channel " << c << ": standard error "
                << e.standardError;
        }
    }
}

// View factor from a point to a parallel rectangle of sides a x b at height h, the point below one
// corner (Howell's catalogue, configuration B-3).
double CornerViewFactor(double a, double b, double h) {
    double X = a / h, Y = b / h, x = std::sqrt(1 + X * X), y = std::sqrt(1 + Y * Y);
    return (X / x * std::atan(Y / x) + Y / y * std::atan(X / y)) / (2 * M_PI);
}

// A diffuse plane of reflectance R at z = 0 and, 0.5 above the origin, a 2 x 2 emitter of
// radiance Le facing down.
void AddPlaneUnderEmitter(SceneBuilder &builder, Float R, Float Le) {
    builder.AddTriangleMesh(Rectangle(-20, 20, -20, 20, 0),
                            builder.AddMaterial(DiffuseMaterial{Spectrum(R)}));
    int black = builder.AddMaterial(DiffuseMaterial{Spectrum(0.f)});
    builder.AddTriangleMesh(Rectangle(-1, 1, -1, 1, 0.5f, true), black,
                            AreaLightDescription{Spectrum(Le), 1, false});
}

TEST(RenderDirect, DiffusePointUnderRectangularEmitterIsReflectanceTimesViewFactor) {
    // A 2 x 2 emitter 0.5 above the point: E = π Le F, Lo = R E / π = R Le F, F from four corner
    // rectangles of 1 x 1. Close and large, both estimators carry weight: MIS must split it right.
    constexpr Float R = 0.7f, Le = 2;
    SceneBuilder builder(LookingAt(Point3f(0, 0, 4), Point3f(0, 0, 0), 20, Point2i(4, 4)),
                         BoxFilteredFilm(Point2i(4, 4)), IndependentSampler(1));
    AddPlaneUnderEmitter(builder, R, Le);
    auto scene = builder.Build();
    double expected = R * Le * 4 * CornerViewFactor(1, 1, 0.5);
    Ray down(Point3f(0, 0, 0.25f), Vector3f(0, 0, -1));
    for (PathStrategy strategy : kStrategies)
        ExpectNear(EstimateLi(*scene, PathTracer(1, strategy), down, 40000), expected,
                   "strategy " + ToString(strategy));
}

// The point of the test above under the same emitter, a uniform sky and a sun 75° off the normal
// (it passes beside the emitter): Lo = R (Le F + Lsky (1 - F) + Lsun cos 75° / π), the sky seen
// through all but the emitter's view factor F. Four lights, two of them without bounds: both ways
// of choosing those against the tree (light sampler "bvh" and "bvh-pbrt-v4") must reach it, with
// MIS (where the sky is left to BSDF sampling by "bvh") and with light sampling alone (the sun is
// a delta light, which BSDF sampling alone cannot find).
TEST(RenderDirect, DiffusePointUnderEmitterSkyAndSunForEitherChoiceOfInfiniteLights) {
    constexpr Float R = 0.7f, Le = 2, Lsky = 0.4f, Lsun = 3, sunTheta = 75;
    double F = 4 * CornerViewFactor(1, 1, 0.5);
    double expected = R * (Le * F + Lsky * (1 - F) + Lsun * std::cos(Radians(sunTheta)) / Pi);
    Ray down(Point3f(0, 0, 0.25f), Vector3f(0, 0, -1));
    for (const char *lightSampler : {"bvh", "bvh-pbrt-v4"})
        for (PathStrategy strategy : {PathStrategy::MIS, PathStrategy::Light}) {
            SceneBuilder builder(LookingAt(Point3f(0, 0, 4), Point3f(0, 0, 0), 20, Point2i(4, 4)),
                                 BoxFilteredFilm(Point2i(4, 4)), IndependentSampler(1));
            AddPlaneUnderEmitter(builder, R, Le);
            builder.AddLight(UniformInfiniteLight(Spectrum(Lsky), 1));
            builder.AddLight(DistantLight(RotateX(sunTheta), Spectrum(Lsun), 1));
            builder.SetLightSampler(lightSampler);
            builder.SetIntegrator({1, false, strategy});
            auto scene = builder.Build();
            ExpectNear(EstimateLi(*scene, PathTracer(1, strategy), down, 40000), expected,
                       std::string(lightSampler) + ", strategy " + ToString(strategy));
        }
}

TEST(RenderDirect, LightSamplingAloneRefusesASceneBuiltForMISThatLeavesItsSkyToBSDFs) {
    SceneBuilder builder(LookingAt(Point3f(0, 0, 4), Point3f(0, 0, 0), 20, Point2i(4, 4)),
                         BoxFilteredFilm(Point2i(4, 4)), IndependentSampler(1));
    builder.AddTriangleMesh(Rectangle(-20, 20, -20, 20, 0),
                            builder.AddMaterial(DiffuseMaterial{Spectrum(0.5f)}));
    builder.AddLight(UniformInfiniteLight(Spectrum(0.4f), 1));
    builder.AddLight(DistantLight(Transform(), Spectrum(1.f), 1));
    auto scene = builder.Build();  // for MIS, the default
    EXPECT_NO_THROW(PathIntegrator(*scene, PathTracer(1)));
    EXPECT_THROW(PathIntegrator(*scene, PathTracer(1, PathStrategy::Light)), std::invalid_argument);
}

TEST(RenderStrategies, AgreeWithinNoiseWithAnAreaLightAndFabric) {
    // The Cornell box with fabric boxes: the image mean of each strategy, against MIS's. The
    // difference of two independent renders' means has the standard error σ_d/√pixels, estimated
    // from the per-pixel differences; 4 of them is the threshold (pixels are nearly independent).
    FabricMaterial fabric;
    fabric.reflectance = RGBReflectance(0.8f, 0.7f, 0.5f);
    fabric.roughness = 0.4f;
    auto render = [&](PathStrategy strategy) {
        auto scene = CornellBox(Point2i(32, 32), 256, {5, false, strategy}, fabric);
        Render(*scene, {0, true});
        EXPECT_TRUE(AllPixelsFinite(scene->film));
        return scene;
    };
    auto mis = render(PathStrategy::MIS);
    for (PathStrategy strategy : {PathStrategy::BSDF, PathStrategy::Light}) {
        auto other = render(strategy);
        double sum = 0, sum2 = 0, n = 0;
        for (Point2i p : mis->film.PixelBounds()) {
            double d = mis->film.GetPixelRGB(p).Average() - other->film.GetPixelRGB(p).Average();
            sum += d;
            sum2 += d * d;
            ++n;
        }
        double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / (n - 1));
        EXPECT_LT(std::abs(mean), 4 * se) << "mis vs " << ToString(strategy);
    }
}

TEST(RenderDeterminism, SameImageForOneAndTwoThreads) {
    auto one = CornellBox(Point2i(32, 32), 8, {});
    auto two = CornellBox(Point2i(32, 32), 8, {});
    Render(*one, {1, true});
    Render(*two, {2, true});
    int lit = 0;
    for (Point2i p : one->film.PixelBounds()) {
        ASSERT_EQ(one->film.GetPixelRGB(p), two->film.GetPixelRGB(p)) << p.x << ", " << p.y;
        lit += one->film.GetPixelRGB(p).MaxComponentValue() > 0;
    }
    EXPECT_GT(lit, 32 * 32 / 2);  // the light does light the box
}

TEST(RenderInstancing, InstancesRenderAsExplicitCopies) {
    // Two instances of a sphere object against two spheres placed directly: the same image up to
    // float rounding in the instance transforms.
    auto render = [](bool instanced) {
        SceneBuilder builder(LookingAt(Point3f(0, 0, 8), Point3f(0, 0, 0), 40, Point2i(16, 16)),
                             BoxFilteredFilm(Point2i(16, 16)), IndependentSampler(16));
        int white = builder.AddMaterial(DiffuseMaterial{Spectrum(0.7f)});
        const Point3f centers[] = {Point3f(-1.2f, 0, 0), Point3f(1.2f, 0.3f, 0)};
        if (instanced) {
            builder.BeginObject("ball");
            builder.AddSphere(UnitSphereAt(Point3f(0, 0, 0)), white);
            builder.EndObject();
            for (Point3f c : centers)
                builder.AddObjectInstance("ball", Translate(Vector3f(c)));
        } else {
            for (Point3f c : centers)
                builder.AddSphere(UnitSphereAt(c), white);
        }
        Emission sun = WhiteEmission(2), sky = WhiteEmission(0.2f);
        builder.AddLight(DistantLight(RotateX(30), sun.spectrum, sun.scale));
        builder.AddLight(UniformInfiniteLight(sky.spectrum, sky.scale));
        auto scene = builder.Build();
        Render(*scene, {1, true});
        return scene;
    };
    auto instanced = render(true), copies = render(false);
    int lit = 0;
    for (Point2i p : copies->film.PixelBounds()) {
        Float a = instanced->film.GetPixelRGB(p)[0], b = copies->film.GetPixelRGB(p)[0];
        EXPECT_NEAR(a, b, 1e-3f * std::max<Float>(1, b)) << p.x << ", " << p.y;
        lit += b > 0.3f;
    }
    EXPECT_GT(lit, 10);  // the spheres are in view and lit
}

TEST(SceneBuilderErrors, ObjectMisuseIsReportedByName) {
    SceneBuilder builder(LookingAt(Point3f(0, 0, 8), Point3f(0, 0, 0), 40, Point2i(4, 4)),
                         BoxFilteredFilm(Point2i(4, 4)), IndependentSampler(1));
    EXPECT_THROW(builder.AddObjectInstance("nothing", Transform()), std::invalid_argument);
    EXPECT_THROW(builder.EndObject(), std::invalid_argument);
    builder.BeginObject("a");
    EXPECT_THROW(builder.BeginObject("b"), std::invalid_argument);
    builder.EndObject();
    EXPECT_THROW(builder.BeginObject("a"), std::invalid_argument);
    EXPECT_THROW(builder.SetLightSampler("kdtree"), std::invalid_argument);
}

TEST(RenderTimeLimit, StopsBetweenPassesWithEveryPixelAtTheSameSampleCount) {
    // Under a time limit the image holds samples 0 ... k-1 of every pixel: the same image as
    // asking for k samples (the independent sampler's samples do not depend on the count asked).
    auto scene = [](int spp) {
        SceneBuilder builder(LookingAt(Point3f(0, 0, 5), Point3f(0, 0, 0), 30, Point2i(32, 32)),
                             BoxFilteredFilm(Point2i(32, 32)), IndependentSampler(spp, 3));
        builder.AddSphere(UnitSphereAt(Point3f(0, 0, 0)),
                          builder.AddMaterial(DiffuseMaterial{Spectrum(0.5f)}));
        Emission white = WhiteEmission(1);
        builder.AddLight(UniformInfiniteLight(white.spectrum, white.scale));
        return builder.Build();
    };
    auto limited = scene(1 << 20);
    RenderStatistics stats = Render(*limited, {2, true, 0.2});
    ASSERT_GE(stats.samplesPerPixel, 1);
    ASSERT_LT(stats.samplesPerPixel, 1 << 20);
    EXPECT_EQ(stats.cameraSamples, int64_t(32 * 32) * stats.samplesPerPixel);
    auto exact = scene(stats.samplesPerPixel);
    Render(*exact, {2, true});
    for (Point2i p : exact->film.PixelBounds())
        ASSERT_EQ(limited->film.GetPixelRGB(p), exact->film.GetPixelRGB(p)) << p.x << ", " << p.y;
}
