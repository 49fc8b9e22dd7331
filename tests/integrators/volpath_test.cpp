// The volumetric path tracer (pbrt_ext/integrators/volpath.h) against closed forms: single scattering and
// emission in a slab, a white furnace, spectral MIS; and the path tracer's handling of
// interfaces, which it crosses without rendering their media (pbrt-v4's PathIntegrator).
// Radiance is estimated by calling Li directly, so that no film or sensor stands between the
// estimate and the closed form. Seeds are fixed; tolerances are stated in standard errors.
#include "pbrt_ext/integrators/volpath.h"

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/integrators/transmittance.h"
#include "pbrt_ext/scene.h"
#include "tests/support/scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

namespace pbrt {
namespace {

using testscenes::Rectangle;
using testscenes::UnitSphereAt;

constexpr double kPi = 3.14159265358979323846;
// Standard errors an estimate may miss its closed form by (p ~ 7e-6 for a correct estimator).
constexpr double kSigmas = 4.5;

SceneBuilder MakeBuilder() {
    Point2i res(8, 8);
    return SceneBuilder(testscenes::LookingAt(Point3f(0, 0, 5), Point3f(0, 0, 0), 30, res),
                        testscenes::BoxFilteredFilm(res), IndependentSampler(1, 0));
}

// Mean and standard error of n samples.
struct Moments {
    double sum = 0, sum2 = 0;
    int n = 0;
    void Add(double x) {
        sum += x;
        sum2 += x * x;
        ++n;
    }
    double Mean() const { return sum / n; }
    double Variance() const { return std::max(0.0, sum2 / n - Mean() * Mean()); }
    double StdError() const { return std::sqrt(Variance() / n); }
};

struct Estimate {
    double mean, stdError;  // of the first wavelength's radiance
    // With random wavelengths: the spectrum's average and its tilt (the slope of radiance
    // against wavelength), and the variance of single wavelengths' radiance.
    Moments average, tilt;
    double channelVariance = 0;
};

// n estimates of the radiance along ray, each with its own independent sample stream, at fixed
// wavelengths (hero 0.3 of the way through the visible range) or at wavelengths sampled as the
// film samples them (then the hero is each of the four with equal probability, which spectral
// MIS needs to be unbiased).
template <typename Integrator>
Estimate EstimateLi(const Integrator &integrator, const Ray &ray, int n, int seed = 0,
                    bool randomWavelengths = false) {
    Sampler sampler = IndependentSampler(1, seed);
    Moments first, channels;
    Estimate e;
    RayCounts rays;
    for (int i = 0; i < n; ++i) {
        sampler.StartPixelSample(Point2i(0, 0), i);
        Float u = sampler.Get1D();
        SampledWavelengths lambda = SampledWavelengths::SampleUniform(randomWavelengths ? u : 0.3f);
        SampledSpectrum L = integrator.Li(ray, lambda, sampler, rays);
        first.Add(L[0]);
        e.average.Add(L.Average());
        double tilt = 0;
        for (int c = 0; c < NSpectrumSamples; ++c) {
            tilt += L[c] * (lambda[c] - 595) / 235 / NSpectrumSamples;
            channels.Add(L[c]);
        }
        e.tilt.Add(tilt);
    }
    e.mean = first.Mean();
    e.stdError = first.StdError();
    e.channelVariance = channels.Variance();
    return e;
}

IntegratorOptions VolPath(int maxDepth) {
    IntegratorOptions options;
    options.maxDepth = maxDepth;
    options.type = IntegratorType::VolPath;
    return options;
}

// A slab 0 <= z <= d of medium between two interfaces (no surface), normals facing out, seen
// from above along -z.
struct Slab {
    std::unique_ptr<Scene> scene;
    Ray cameraRay = Ray(Point3f(0.1f, -0.2f, 3), Vector3f(0, 0, -1));
};
Slab MakeSlab(Medium medium, Float d, std::function<void(SceneBuilder &)> addLights,
              IntegratorOptions options) {
    SceneBuilder builder = MakeBuilder();
    int m = builder.AddMedium(std::move(medium));
    builder.SetMediumInterface(MediumInterface(m, -1));
    builder.AddTriangleMesh(Rectangle(-1000, 1000, -1000, 1000, d), -1);
    builder.AddTriangleMesh(Rectangle(-1000, 1000, -1000, 1000, 0, true), -1);
    addLights(builder);
    builder.SetIntegrator(options);
    return {builder.Build()};
}

Float HG(Float cosTheta, Float g) {
    return Float((1 - g * g) / (4 * kPi * std::pow(1 + g * g + 2 * g * cosTheta, 1.5)));
}

TEST(VolPath, SingleScatteringInASlabMatchesItsClosedForm) {
    const Float sigma_a = 0.5f, sigma_s = 1.0f, d = 0.4f, g = 0.3f, thetaDegrees = 40;
    const Float mu = std::cos(Radians(thetaDegrees)), sigma_t = sigma_a + sigma_s;
    // maxdepth 1: one scattering event, lit by the distant light through the top.
    Slab slab = MakeSlab(HomogeneousMedium(Spectrum(sigma_a), Spectrum(sigma_s), 1, Spectrum(0.f),
                                           0, g),
                         d,
                         [&](SceneBuilder &b) {
                             b.AddLight(DistantLight(RotateY(thetaDegrees), Spectrum(1.f), 1));
                         },
                         VolPath(1));
    VolPathIntegrator integrator(*slab.scene, slab.scene->integratorOptions);
    Estimate e = EstimateLi(integrator, slab.cameraRay, 200000);
    // Scattering at depth s below the top: the camera ray and the light each cross s (the
    // light s / mu of it); wo = +z, wi = the light's direction.
    Float k = sigma_t * (1 + 1 / mu);
    double expected = HG(mu, g) * sigma_s * (1 - std::exp(-k * d)) / k;
    EXPECT_NEAR(e.mean, expected, kSigmas * e.stdError) << "stderr " << e.stdError;
    EXPECT_NEAR(e.mean, expected, 0.02 * expected);
}

TEST(VolPath, EmissionOfAnAbsorbingSlabMatchesItsClosedForm) {
    const Float sigma_a = 1.3f, d = 0.7f, Le = 2.5f;
    Slab slab = MakeSlab(HomogeneousMedium(Spectrum(sigma_a), Spectrum(0.f), 1, Spectrum(Le), 1, 0),
                         d, [](SceneBuilder &) {}, VolPath(5));
    VolPathIntegrator integrator(*slab.scene, slab.scene->integratorOptions);
    Estimate e = EstimateLi(integrator, slab.cameraRay, 100000);
    double expected = Le * (1 - std::exp(-sigma_a * d));
    EXPECT_NEAR(e.mean, expected, kSigmas * e.stdError + 1e-6) << "stderr " << e.stdError;
}

// An albedo-1 medium in a unit sphere with no surface, under a uniform environment: every
// path that leaves carries the environment's radiance, so every pixel is the environment.
TEST(VolPath, WhiteFurnaceReturnsTheEnvironment) {
    for (Float g : {0.f, 0.7f}) {
        SceneBuilder builder = MakeBuilder();
        int m = builder.AddMedium(HomogeneousMedium(Spectrum(0.f), Spectrum(3.f), 1,
                                                    Spectrum(0.f), 0, g));
        builder.SetMediumInterface(MediumInterface(m, -1));
        builder.AddSphere(UnitSphereAt(Point3f(0, 0, 0)), -1);
        builder.AddLight(UniformInfiniteLight(Spectrum(0.8f), 1));
        builder.SetIntegrator(VolPath(1000));
        std::unique_ptr<Scene> scene = builder.Build();
        VolPathIntegrator integrator(*scene, scene->integratorOptions);
        for (Ray ray : {Ray(Point3f(0, 0, 4), Vector3f(0, 0, -1)),
                        Ray(Point3f(0.7f, 0, 4), Vector3f(0, 0, -1))}) {
            Estimate e = EstimateLi(integrator, ray, 20000);
            // Exactly 0.8 except where Russian roulette or the depth limit ends a path.
            EXPECT_NEAR(e.mean, 0.8, std::max(kSigmas * e.stdError, 1e-3)) << "g " << g;
        }
    }
}

// A chromatic medium: sigma_s rising fivefold over the visible range. Homogeneous, or as a
// grid of constant density over a box around the unit sphere: the same medium, but only the
// homogeneous one has a closed-form transmittance; the grid's is tracked.
Medium ChromaticMedium(bool asGrid) {
    Spectrum sigma_a(0.2f), sigma_s = Spectrum::PiecewiseLinear({360.f, 830.f}, {0.6f, 3.f});
    if (!asGrid)
        return HomogeneousMedium(sigma_a, sigma_s, 1, Spectrum(0.f), 0, 0.2f);
    Bounds3f box(Point3f(-1.5f, -1.5f, -1.5f), Point3f(1.5f, 1.5f, 1.5f));
    return GridMedium(box, Transform(), sigma_a, sigma_s, 1, 0.2f,
                      SampledGrid<Float>(std::vector<Float>(8, 1.f), 2, 2, 2), GridEmission{});
}

// n estimates, at random wavelengths, of the chromatic medium in the unit sphere lit by a
// distant light and the environment.
Estimate EstimateChromaticSphere(bool asGrid, bool spectralMIS, int seed) {
    SceneBuilder builder = MakeBuilder();
    builder.SetMediumInterface(MediumInterface(builder.AddMedium(ChromaticMedium(asGrid)), -1));
    builder.AddSphere(UnitSphereAt(Point3f(0, 0, 0)), -1);
    builder.AddLight(DistantLight(RotateY(30), Spectrum(1.f), 1));
    builder.AddLight(UniformInfiniteLight(Spectrum(0.3f), 1));
    IntegratorOptions options = VolPath(20);
    options.spectralMIS = spectralMIS;
    builder.SetIntegrator(options);
    std::unique_ptr<Scene> scene = builder.Build();
    VolPathIntegrator integrator(*scene, scene->integratorOptions);
    return EstimateLi(integrator, Ray(Point3f(0.3f, 0, 4), Vector3f(0, 0, -1)), 100000, seed, true);
}

// Two estimates agree in brightness and in colour (the spectrum's tilt).
void ExpectSameBrightnessAndColour(const Estimate &a, const Estimate &b) {
    EXPECT_NEAR(a.average.Mean(), b.average.Mean(),
                kSigmas * std::hypot(a.average.StdError(), b.average.StdError()));
    EXPECT_NEAR(a.tilt.Mean(), b.tilt.Mean(),
                kSigmas * std::hypot(a.tilt.StdError(), b.tilt.StdError()));
}

// With spectral MIS and without it (the hero wavelength's probabilities alone) the estimates
// agree, and spectral MIS has less variance per wavelength.
TEST(VolPath, SpectralMISKeepsTheMeanAndLowersChromaticNoise) {
    Estimate with = EstimateChromaticSphere(false, true, 1);
    Estimate without = EstimateChromaticSphere(false, false, 2);
    ExpectSameBrightnessAndColour(with, without);
    // The medium must be chromatic for the test to mean anything.
    EXPECT_GT(std::abs(with.tilt.Mean()), 5 * with.tilt.StdError());
    EXPECT_LT(with.channelVariance, 0.8 * without.channelVariance)
        << with.channelVariance << " vs " << without.channelVariance;
}

// Shadow rays take a homogeneous medium's transmittance in closed form, ratio tracking's
// expectation, with the MIS densities tracking would give them (so that next-event estimation
// and paths that reach the sky weigh each other as before). Against the same medium tracked,
// the estimates agree, with less variance.
TEST(VolPath, ClosedFormShadowRaysKeepTheMeanOfRatioTracking) {
    Estimate closed = EstimateChromaticSphere(false, true, 1);
    Estimate tracked = EstimateChromaticSphere(true, true, 2);
    ExpectSameBrightnessAndColour(closed, tracked);
    EXPECT_LT(closed.channelVariance, tracked.channelVariance)
        << closed.channelVariance << " vs " << tracked.channelVariance;
}

// The transmittance between two points of bdpt's connections: through a homogeneous slab,
// Beer-Lambert at every wavelength, exactly (no distance is drawn); through the same medium
// as a grid, a tracked estimate with that mean once the hero wavelength is random (spectral
// MIS is unbiased over the choice of hero, not for a fixed one).
TEST(Transmittance, BetweenTwoPointsAcrossAHomogeneousSlabIsBeerLambert) {
    const Float d = 0.8f;
    auto makeSlab = [&](bool asGrid) {
        return MakeSlab(ChromaticMedium(asGrid), d, [](SceneBuilder &) {}, VolPath(5));
    };
    Slab homogeneous = makeSlab(false), grid = makeSlab(true);
    Point3f from(0.2f, 0.1f, 1.3f), to(-0.3f, 0.4f, -0.6f);
    Float pathInSlab = d * Length(to - from) / (from.z - to.z);
    RayCounts rays;
    auto closedForm = [&](Point3f p, Point3f q, const SampledWavelengths &lambda) {
        return Transmittance(*homogeneous.scene, Ray(p, q - p), q, lambda, rays);
    };
    SampledWavelengths lambda = SampledWavelengths::SampleUniform(0.3f);
    SampledSpectrum T = closedForm(from, to, lambda);
    MediumProperties mp = ChromaticMedium(false).SamplePoint(from, lambda);
    for (int c = 0; c < NSpectrumSamples; ++c) {
        double expected = std::exp(-(mp.sigma_a[c] + mp.sigma_s[c]) * pathInSlab);
        // Within 1e-3: the rays leave the slab's faces (rectangles 2000 wide) from points
        // offset by their float error bounds, about 1e-4 of the path here.
        EXPECT_NEAR(T[c], expected, 1e-3 * expected) << "wavelength " << lambda[c];
        EXPECT_EQ(closedForm(from, to, lambda)[c], T[c]) << "nothing is drawn";
    }
    // The tracked estimate less the closed form, over random wavelengths and endpoints (ratio
    // tracking seeds its RNG from the endpoints).
    RNG rng(4);
    Moments difference;
    for (int i = 0; i < 200000; ++i) {
        SampledWavelengths random = SampledWavelengths::SampleUniform(rng.Uniform<Float>());
        Vector3f jitter(0.01f * rng.Uniform<Float>(), 0.01f * rng.Uniform<Float>(), 0);
        SampledSpectrum tracked =
            Transmittance(*grid.scene, Ray(from + jitter, to - from), to + jitter, random, rays);
        difference.Add((tracked - closedForm(from + jitter, to + jitter, random)).Average());
    }
    EXPECT_NEAR(difference.Mean(), 0, kSigmas * difference.StdError());
    EXPECT_GT(difference.StdError(), 0) << "the grid must be tracked";
}

// pbrt-v4's path tracer crosses an interface without rendering its medium; shadow rays stop at
// it, so what lies behind is found by the path alone and counted in full. A light enclosed in
// an interface sphere then lights a floor as it does without the sphere.
TEST(PathIntegrator, AnEmitterBehindAnInterfaceCountsInFull) {
    auto render = [](bool enclosed) {
        SceneBuilder builder = MakeBuilder();
        int white = builder.AddMaterial(DiffuseMaterial{Spectrum(0.5f)});
        builder.AddTriangleMesh(Rectangle(-10, 10, -10, 10, 0), white);
        AreaLightDescription light{Spectrum(1.f), 4, false};
        builder.AddSphere(UnitSphereAt(Point3f(0, 0, 2), 0.3f), white, light);
        if (enclosed)
            builder.AddSphere(UnitSphereAt(Point3f(0, 0, 2), 0.6f), -1);
        IntegratorOptions options;
        options.maxDepth = 1;
        builder.SetIntegrator(options);
        std::unique_ptr<Scene> scene = builder.Build();
        PathIntegrator integrator(*scene, scene->integratorOptions);
        return EstimateLi(integrator, Ray(Point3f(0.5f, 0.2f, 1), Vector3f(0, 0, -1)), 100000,
                          enclosed);
    };
    Estimate open = render(false), enclosed = render(true);
    ASSERT_GT(open.mean, 0);
    EXPECT_NEAR(enclosed.mean, open.mean,
                kSigmas * std::hypot(open.stdError, enclosed.stdError));
}

}  // namespace
}  // namespace pbrt
