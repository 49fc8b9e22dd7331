// Participating media (pbrt_ext/media/media.h): transmittance by delta and ratio tracking against
// Beer-Lambert, majorant grids that bound every density, and the phase function's sampling.
// Every statistical test fixes its RNG seed; tolerances are stated in standard errors.
#include "pbrt_ext/media/media.h"

#include "pbrt_ext/spectra/colorspace.h"

#include "tests/support/chi2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

namespace pbrt {
namespace {

constexpr int kTrials = 200000;
// Standard errors a mean may miss by: with a fixed seed the test is deterministic, and 4.5
// sigma keeps a correct estimator from failing on an unlucky seed choice (p ~ 7e-6).
constexpr double kSigmas = 4.5;

// Sample mean and its standard error.
struct Estimate {
    double mean, stdError;
};
template <typename F>
Estimate Average(int n, F trial) {
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        double x = trial(i);
        sum += x;
        sum2 += x * x;
    }
    double mean = sum / n, var = std::max(0.0, sum2 / n - mean * mean);
    return {mean, std::sqrt(var / n)};
}

SampledWavelengths FixedWavelengths() { return SampledWavelengths::SampleUniform(0.3f); }

// Delta tracking: the path survives to tMax when no tentative collision is a real one (each
// is real with probability sigma_t / sigma_maj at the hero wavelength). Returns 1 or 0.
double DeltaTrackingSurvives(const Medium &m, const Ray &ray, Float tMax, RNG &rng) {
    SampledWavelengths lambda = FixedWavelengths();
    bool absorbed = false;
    m.SampleT_maj(ray, tMax, rng.Uniform<Float>(), rng, lambda,
                  [&](Point3f, const MediumProperties &mp, SampledSpectrum sigma_maj,
                      SampledSpectrum) {
                      Float pReal = (mp.sigma_a[0] + mp.sigma_s[0]) / sigma_maj[0];
                      absorbed = rng.Uniform<Float>() < pReal;
                      return !absorbed;
                  });
    return absorbed ? 0 : 1;
}

// Ratio tracking: the product of the null-collision fractions, times the majorant
// transmittance ratio past the last collision; each wavelength's transmittance.
SampledSpectrum RatioTracking(const Medium &m, const Ray &ray, Float tMax, RNG &rng) {
    SampledWavelengths lambda = FixedWavelengths();
    SampledSpectrum T(1.f);
    SampledSpectrum T_maj = m.SampleT_maj(
        ray, tMax, rng.Uniform<Float>(), rng, lambda,
        [&](Point3f, const MediumProperties &mp, SampledSpectrum sigma_maj, SampledSpectrum T_m) {
            SampledSpectrum sigma_n = ClampZero(sigma_maj - mp.sigma_a - mp.sigma_s);
            T *= T_m * sigma_n / (T_m[0] * sigma_maj[0]);
            return bool(T);
        });
    return T * T_maj / T_maj[0];
}

// The optical depth along ray to tMax by the midpoint rule on a fine grid of SamplePoint
// (the trilinear density is piecewise smooth: 20,000 steps leave an error below 1e-4), over
// the points where inside(p) holds: a grid medium is its box, though its interpolation
// reaches half a cell beyond (pbrt-v4's too; rays are clipped to the box first).
template <typename Inside>
double OpticalDepth(const Medium &m, const Ray &ray, Float tMax, int channel, Inside inside) {
    const int steps = 20000;
    SampledWavelengths lambda = FixedWavelengths();
    double dt = double(tMax) / steps, depth = 0;
    for (int i = 0; i < steps; ++i) {
        Point3f p = ray(Float((i + 0.5) * dt));
        if (!inside(p))
            continue;
        MediumProperties mp = m.SamplePoint(p, lambda);
        depth += (mp.sigma_a[channel] + mp.sigma_s[channel]) * dt;
    }
    return depth * Length(ray.d);
}
double OpticalDepth(const Medium &m, const Ray &ray, Float tMax, int channel) {
    return OpticalDepth(m, ray, tMax, channel, [](Point3f) { return true; });
}

// A homogeneous medium whose coefficients differ per wavelength: sigma_t from 0.5 to 2.
Medium ChromaticHomogeneous() {
    Spectrum sigma_a = Spectrum::PiecewiseLinear({360.f, 830.f}, {0.2f, 1.4f});
    Spectrum sigma_s = Spectrum::PiecewiseLinear({360.f, 830.f}, {0.3f, 0.6f});
    return HomogeneousMedium(sigma_a, sigma_s, 1, Spectrum(0.f), 0, 0);
}

// A 5x4x3 grid of densities in [0, 2] over a box, rotated and moved; sigma_t is 2.7 per
// unit density.
const Transform kGridPlacement = Translate(Vector3f(0.3f, -0.2f, 0.1f)) * RotateZ(25);
const Bounds3f kGridBox(Point3f(-1, -0.5f, -0.8f), Point3f(1, 0.5f, 0.8f));
GridMedium RandomGrid(uint64_t seed) {
    RNG rng(seed);
    std::vector<Float> density(5 * 4 * 3);
    for (Float &d : density)
        d = 2 * rng.Uniform<Float>();
    return GridMedium(kGridBox, kGridPlacement, Spectrum(0.7f), Spectrum(1.1f), 1.5f, 0,
                      SampledGrid<Float>(density, 5, 4, 3), GridEmission{});
}

TEST(Transmittance, BeerLambertThroughAHomogeneousSlabByDeltaTracking) {
    Medium m = HomogeneousMedium(Spectrum(0.4f), Spectrum(0.8f), 1.5f, Spectrum(0.f), 0, 0);
    // An unnormalized direction: distances must come out in units of length regardless.
    Ray ray(Point3f(0, 0, 0), Vector3f(0, 0, 2));
    const Float tMax = 0.6f;  // 1.2 units of length, optical depth 1.8 * 1.2
    double expected = std::exp(-1.8 * 1.2);
    RNG rng(1);
    Estimate e = Average(kTrials, [&](int) { return DeltaTrackingSurvives(m, ray, tMax, rng); });
    EXPECT_NEAR(e.mean, expected, kSigmas * e.stdError) << "stderr " << e.stdError;
}

TEST(Transmittance, BeerLambertPerWavelengthByRatioTracking) {
    Medium m = ChromaticHomogeneous();
    Ray ray(Point3f(1, 2, 3), Normalize(Vector3f(1, -1, 0.5f)));
    const Float tMax = 1.3f;
    SampledWavelengths lambda = FixedWavelengths();
    for (int c = 0; c < NSpectrumSamples; ++c) {
        RNG rng(2 + c);
        double expected = std::exp(-OpticalDepth(m, ray, tMax, c));
        Estimate e = Average(kTrials, [&](int) { return RatioTracking(m, ray, tMax, rng)[c]; });
        EXPECT_NEAR(e.mean, expected, kSigmas * e.stdError + 1e-6)
            << "wavelength " << lambda[c] << " nm";
    }
}

TEST(Transmittance, BeerLambertThroughAGridByBothEstimators) {
    Medium m = RandomGrid(7);
    // Rays that enter, cross and leave the box, one stopping inside it.
    struct Case {
        Ray ray;
        Float tMax;
    } cases[] = {{Ray(Point3f(-3, 0.1f, 0.2f), Vector3f(1, 0.05f, -0.02f)), 6},
                 {Ray(Point3f(0.2f, -2, -1), Vector3f(0.1f, 1, 0.6f)), 3.5f},
                 {Ray(Point3f(0.4f, 0.1f, -3), Vector3f(-0.2f, 0, 1)), 3.1f}};
    int seed = 10;
    for (const Case &c : cases) {
        double expected = std::exp(-OpticalDepth(m, c.ray, c.tMax, 0, [](Point3f p) {
            return Inside(kGridPlacement.ApplyInverse(p), kGridBox);
        }));
        ASSERT_GT(expected, 0.02) << "the case should see light through the grid";
        ASSERT_LT(expected, 0.9) << "the case should cross density";
        RNG rng(seed++);
        Estimate delta = Average(kTrials, [&](int) { return DeltaTrackingSurvives(m, c.ray, c.tMax, rng); });
        Estimate ratio = Average(kTrials, [&](int) { return RatioTracking(m, c.ray, c.tMax, rng)[0]; });
        EXPECT_NEAR(delta.mean, expected, kSigmas * delta.stdError);
        EXPECT_NEAR(ratio.mean, expected, kSigmas * ratio.stdError);
        // Ratio tracking has no binary outcome: it is the lower-variance estimator here.
        EXPECT_LT(ratio.stdError, delta.stdError);
    }
}

// Shadow rays take a homogeneous medium's transmittance in closed form: Beer-Lambert at every
// wavelength, which is what ratio tracking averages to there (its estimate is 0 or T / T[0]).
TEST(Transmittance, ClosedFormIsRatioTrackingsMeanInAHomogeneousMedium) {
    Medium m = ChromaticHomogeneous();
    Ray ray(Point3f(0.1f, 0.2f, -0.3f), Vector3f(0.6f, -0.3f, 0.5f));
    const Float tMax = 1.7f;
    SampledWavelengths lambda = FixedWavelengths();
    std::optional<SampledSpectrum> T = m.ClosedFormTransmittance(ray, tMax, lambda);
    ASSERT_TRUE(T.has_value());
    RNG rng(21);
    std::vector<SampledSpectrum> estimates(kTrials);
    for (SampledSpectrum &e : estimates)
        e = RatioTracking(m, ray, tMax, rng);
    for (int c = 0; c < NSpectrumSamples; ++c) {
        double expected = std::exp(-OpticalDepth(m, ray, tMax, c));
        EXPECT_NEAR((*T)[c], expected, 1e-5 * expected) << "wavelength " << lambda[c];
        Estimate ratio = Average(kTrials, [&](int i) { return estimates[size_t(i)][c]; });
        EXPECT_NEAR(ratio.mean, expected, kSigmas * ratio.stdError) << "wavelength " << lambda[c];
    }
    // Only a homogeneous medium has one: a grid's depends on the densities along the ray.
    EXPECT_FALSE(Medium(RandomGrid(3)).ClosedFormTransmittance(ray, tMax, lambda).has_value());
}

// Shadow rays ask for the coefficients without the emission: the same sigma_a and sigma_s,
// and none of the emission's lookups (here a grid of Le scales).
TEST(GridMedium, SamplesWithoutEmissionTheSameCoefficients) {
    RNG rng(8);
    std::vector<Float> scales(5 * 4 * 3);
    for (Float &v : scales)
        v = 0.5f + rng.Uniform<Float>();
    GridEmission emission{Spectrum(2.f), SampledGrid<Float>(scales, 5, 4, 3), std::nullopt};
    std::vector<Float> density(5 * 4 * 3, 1.f);
    Medium m = GridMedium(kGridBox, kGridPlacement, Spectrum(0.7f), Spectrum(1.1f), 1.5f, 0,
                          SampledGrid<Float>(density, 5, 4, 3), std::move(emission));
    SampledWavelengths lambda = FixedWavelengths();
    Point3f p = kGridPlacement(Point3f(0.2f, 0.1f, -0.3f));
    MediumProperties full = m.SamplePoint(p, lambda);
    MediumProperties noEmission = m.SamplePoint(p, lambda, MediumQuery::NoEmission);
    EXPECT_GT(full.Le[0], 0) << "the medium must emit for the test to mean anything";
    EXPECT_FALSE(bool(noEmission.Le));
    for (int c = 0; c < NSpectrumSamples; ++c) {
        EXPECT_EQ(full.sigma_a[c], noEmission.sigma_a[c]);
        EXPECT_EQ(full.sigma_s[c], noEmission.sigma_s[c]);
    }
}

// Counts the points where sigma_t exceeds sigmaPerUnit times the majorant grid's value in the
// voxel holding the point (box: the medium's bounds, in the grid's space).
template <typename M>
int MajorantViolations(const M &medium, const Bounds3f &box, const Transform &renderFromMedium,
                       Float sigmaPerUnit) {
    const MajorantGrid &g = medium.Majorants();
    RNG r(5);
    int violations = 0;
    for (int i = 0; i < 100000; ++i) {
        Point3f u(r.Uniform<Float>(), r.Uniform<Float>(), r.Uniform<Float>());
        SampledWavelengths lambda = SampledWavelengths::SampleUniform(r.Uniform<Float>());
        MediumProperties mp = medium.SamplePoint(renderFromMedium(box.Lerp(u)), lambda);
        Float majorant = sigmaPerUnit * g.Lookup(std::min(int(u.x * g.res.x), g.res.x - 1),
                                                 std::min(int(u.y * g.res.y), g.res.y - 1),
                                                 std::min(int(u.z * g.res.z), g.res.z - 1));
        for (int c = 0; c < NSpectrumSamples; ++c)
            violations += mp.sigma_a[c] + mp.sigma_s[c] > majorant * (1 + 1e-5f);
    }
    return violations;
}

TEST(MajorantGrid, BoundsEveryDensitySample) {
    EXPECT_EQ(MajorantViolations(RandomGrid(11), kGridBox, kGridPlacement, 2.7f), 0);

    std::vector<RGBUnboundedSpectrum> sigma_a;
    RNG rng(3);
    for (int i = 0; i < 4 * 3 * 5; ++i)
        sigma_a.push_back(RGBUnboundedSpectrum(
            RGBColorSpace::sRGB(),
            RGB(3 * rng.Uniform<Float>(), rng.Uniform<Float>(), 2 * rng.Uniform<Float>())));
    Bounds3f box(Point3f(0, 0, 0), Point3f(2, 1, 3));
    // sigma_s is 1 everywhere (no grid given); the majorant grid holds sigma_t itself.
    RGBGridMedium rgb(box, Transform(), 0, SampledGrid<RGBUnboundedSpectrum>(sigma_a, 4, 3, 5),
                      std::nullopt, 0.5f, std::nullopt, 0);
    EXPECT_EQ(MajorantViolations(rgb, box, Transform(), 1), 0);
}

TEST(MajorantGrid, IsTightWhereTheDensityIsConstant) {
    // A constant density: every voxel's majorant is that density, not more.
    GridMedium constant(kGridBox, Transform(), Spectrum(1.f), Spectrum(1.f), 1, 0,
                        SampledGrid<Float>(std::vector<Float>(27, 0.6f), 3, 3, 3), GridEmission{});
    for (Float v : constant.Majorants().voxels)
        EXPECT_FLOAT_EQ(v, 0.6f);
}

TEST(HGPhaseFunction, SamplesItsOwnDensity) {
    for (Float g : {-0.7f, 0.f, 0.4f, 0.95f}) {
        HGPhaseFunction phase(g);
        Vector3f wo = Normalize(Vector3f(0.3f, 0.5f, -0.8f));
        Chi2Options options;
        options.numTests = 4;
        options.seed = 42;
        Chi2Result r = Chi2TestSampler(
            [&](Point2f u, Float) -> pstd::optional<Vector3f> {
                std::optional<PhaseFunctionSample> ps = phase.Sample_p(wo, u);
                if (!ps || std::abs(ps->pdf - phase.PDF(wo, ps->wi)) > 1e-3f * ps->pdf)
                    return {};
                return ps->wi;
            },
            [&](Vector3f wi) { return phase.PDF(wo, Normalize(wi)); }, options);
        EXPECT_TRUE(r.passed) << "g = " << g << ": " << r.message;
    }
}

}  // namespace
}  // namespace pbrt
