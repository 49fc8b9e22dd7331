// lights.h: radiometry against closed forms (point I/r^2, spot falloff and power, distant
// L cos, uniform environment pi L, sphere and disk irradiance), SampleLi directions against
// PDF_Li under the chi-square harness (area and infinite lights; alpha = 0.01 with the Sidak
// correction over kChi2Tests), agreement of SampleLi with L / Le / PDF_Li, pbrt-v4's
// allowIncompletePDF behaviour, and Phi.
// Monte Carlo estimates use fixed seeds and must lie within 5 standard errors (estimated
// from the same samples) of the exact value.
#include "tests/support/chi2.h"

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/lights/lights.h"
#include "pbrt_ext/shapes/shapes.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/equalarea.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/transform.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

using namespace pbrt;

namespace {

constexpr int kChi2Tests = 6;

// The rotation that sends +z to the unit vector w.
Transform FromZTo(Vector3f w) {
    Frame f = Frame::FromZ(w);
    return Transform(SquareMatrix<4>(f.x.x, f.y.x, f.z.x, 0, f.x.y, f.y.y, f.z.y, 0, f.x.z,
                                     f.y.z, f.z.z, 0, 0, 0, 0, 1));
}

LightSampleContext ContextAt(Point3f p, Normal3f n) { return LightSampleContext(p, n, n); }

// The wavelengths every check samples: 400, 500, 600 and 700 nm, integers, where a light's
// tabulated (1 nm) copy of a spectrum is the spectrum itself.
const SampledWavelengths kLambda = SampledWavelengths::SampleUniform(0, 400, 800);

// A spectrum through the four values v at kLambda's wavelengths (linear between them), so that
// a light's spectral values are known exactly, and differ per wavelength as RGB channels did.
Spectrum At4(SampledSpectrum v) {
    return Spectrum::PiecewiseLinear({400, 500, 600, 700}, {v[0], v[1], v[2], v[3]});
}


void ExpectSpectrumNear(SampledSpectrum a, SampledSpectrum b, Float relTol) {
    for (int c = 0; c < NSpectrumSamples; ++c)
        EXPECT_NEAR(a[c], b[c], relTol * std::max<Float>(1e-6f, std::abs(b[c]))) << "channel " << c;
}

// Mean and standard error of f over n draws of u.
struct Estimate {
    double mean, stdError;
};
Estimate MonteCarlo(int n, uint64_t seed, const std::function<double(Point2f)> &f) {
    RNG rng(seed);
    double sum = 0, sum2 = 0;
    for (int k = 0; k < n; ++k) {
        Float u0 = rng.Uniform<Float>();
        double v = f(Point2f(u0, rng.Uniform<Float>()));
        sum += v;
        sum2 += v * v;
    }
    double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

// Irradiance (at kLambda[1], 500 nm) at ctx from light sampling, as an integrator would estimate it.
Estimate IrradianceByLightSampling(const Light &light, LightSampleContext ctx,
                                   bool allowIncompletePDF = false) {
    return MonteCarlo(200000, 17, [&](Point2f u) -> double {
        pstd::optional<LightLiSample> ls = light.SampleLi(ctx, u, kLambda, allowIncompletePDF);
        if (!ls)
            return 0;
        return ls->L[1] * std::max<Float>(0, Dot(ls->wi, Vector3f(ctx.n))) / ls->pdf;
    });
}

void ExpectWithinFiveSigma(Estimate e, double exact) {
    EXPECT_NEAR(e.mean, exact, 5 * e.stdError + 1e-6 * std::abs(exact))
        << "estimate " << e.mean << " +- " << e.stdError;
}

// Chi-square of SampleLi's directions against PDF_Li, seen from ctx.
void ExpectSampleLiMatchesPDF(const Light &light, LightSampleContext ctx,
                              bool allowIncompletePDF, uint64_t seed) {
    Chi2Options opts;
    opts.numTests = kChi2Tests;
    opts.seed = seed;
    auto sample = [&](Point2f u, Float) -> pstd::optional<Vector3f> {
        pstd::optional<LightLiSample> ls = light.SampleLi(ctx, u, kLambda, allowIncompletePDF);
        if (!ls)
            return {};
        return ls->wi;
    };
    auto pdf = [&](Vector3f w) { return light.PDF_Li(ctx, Normalize(w), allowIncompletePDF); };
    Chi2Result r = Chi2TestSampler(sample, pdf, opts);
    EXPECT_TRUE(r.passed) << light.ToString() << "\n" << r.message;
}

// SampleLi's pdf and radiance agree with PDF_Li and with what a ray along wi finds.
template <typename Lookup>
void ExpectSampleLiConsistent(const Light &light, LightSampleContext ctx,
                              bool allowIncompletePDF, Lookup radianceAlong) {
    RNG rng(23);
    int samples = 0, mismatches = 0;
    for (int k = 0; k < 20000; ++k) {
        Float u0 = rng.Uniform<Float>();
        pstd::optional<LightLiSample> ls =
            light.SampleLi(ctx, Point2f(u0, rng.Uniform<Float>()), kLambda, allowIncompletePDF);
        if (!ls)
            continue;
        ++samples;
        ASSERT_NEAR(Length(ls->wi), 1, 1e-5f);
        ASSERT_GT(ls->pdf, 0);
        ASSERT_TRUE(ls->L.MinComponentValue() >= 0 && IsFinite(ls->L.MaxComponentValue()));
        Float pdf = light.PDF_Li(ctx, ls->wi, allowIncompletePDF);
        SampledSpectrum L = radianceAlong(*ls);
        // A direction on a pixel or shape boundary may round to the neighbour.
        if (std::abs(pdf - ls->pdf) > 1e-3f * ls->pdf || L != ls->L)
            ++mismatches;
    }
    EXPECT_GT(samples, 10000);
    EXPECT_LE(mismatches, samples / 1000) << light.ToString();
}

Bounds3f UnitCube() { return Bounds3f(Point3f(-1, -1, -1), Point3f(1, 1, 1)); }

// ---------------------------------------------------------------------------------------
// Delta lights

TEST(PointLight, InverseSquareLaw) {
    SampledSpectrum I(1, 2, 4, 3);
    Light light = PointLight(Translate(Vector3f(1, 2, 3)), At4(I), 2.5f);
    EXPECT_EQ(light.Type(), LightType::DeltaPosition);
    EXPECT_TRUE(IsDeltaLight(light.Type()));
    LightSampleContext ctx = ContextAt(Point3f(1, 2, 0), Normal3f(0, 0, 1));
    pstd::optional<LightLiSample> ls = light.SampleLi(ctx, Point2f(0.3f, 0.7f), kLambda);
    ASSERT_TRUE(ls.has_value());
    ExpectSpectrumNear(ls->L, 2.5f * I / 9, 1e-6f);
    EXPECT_EQ(ls->wi, Vector3f(0, 0, 1));
    EXPECT_EQ(ls->pdf, 1);
    EXPECT_EQ(ls->pLight, Point3f(1, 2, 3));
    EXPECT_EQ(light.PDF_Li(ctx, ls->wi), 0);
    ExpectSpectrumNear(light.Phi(kLambda), 4 * Pi * 2.5f * I, 1e-6f);
    EXPECT_FALSE(light.L(Point3f(0, 0, 0), Normal3f(0, 0, 1), Point2f(), Vector3f(0, 0, 1), kLambda));
    EXPECT_FALSE(light.Le(Ray(Point3f(0, 0, 0), Vector3f(0, 0, 1)), kLambda));
}

TEST(SpotLight, FalloffAndAxis) {
    Vector3f axis = Normalize(Vector3f(1, -2, 0.5f));
    Point3f pos(0.5f, 1, -1);
    Light light = SpotLight(Translate(Vector3f(pos)) * FromZTo(axis), Spectrum(3.f), 2, 30, 20);
    Frame f = Frame::FromZ(axis);
    auto irradianceAt = [&](Float thetaDeg) {
        Float t = Radians(thetaDeg);
        Vector3f d = std::cos(t) * f.z + std::sin(t) * f.x;
        Point3f p = pos + 4 * d;
        pstd::optional<LightLiSample> ls =
            light.SampleLi(ContextAt(p, Normal3f(-d)), Point2f(), kLambda);
        return ls ? ls->L[0] : Float(0);
    };
    EXPECT_NEAR(irradianceAt(0), 2 * 3 / 16.f, 1e-5f);
    EXPECT_NEAR(irradianceAt(19), 2 * 3 / 16.f, 1e-5f);
    Float c = std::cos(Radians(25.f)), c0 = std::cos(Radians(30.f)), c1 = std::cos(Radians(20.f));
    Float s = (c - c0) / (c1 - c0);
    EXPECT_NEAR(irradianceAt(25), 2 * 3 / 16.f * s * s * (3 - 2 * s), 1e-4f);
    EXPECT_EQ(irradianceAt(31), 0);
    EXPECT_EQ(irradianceAt(120), 0);
}

TEST(SpotLight, PhiIsIntensityIntegratedOverTheSphere) {
    SpotLight spot(Transform(), At4(SampledSpectrum(1, 2, 3, 4)), 1.5f, 40, 15);
    // I depends on cos theta only: integrate 2 pi I(cos theta) d cos theta by the midpoint rule.
    constexpr int n = 200000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        double cosTheta = -1 + 2 * (i + 0.5) / n;
        sum += spot.I(Vector3f(Float(std::sqrt(1 - cosTheta * cosTheta)), 0, Float(cosTheta)),
                      kLambda)[2];
    }
    EXPECT_NEAR(spot.Phi(kLambda)[2], 2 * Pi * sum * 2 / n, 1e-4 * spot.Phi(kLambda)[2]);
}

TEST(DistantLight, IrradianceIsLCosTheta) {
    Vector3f w = Normalize(Vector3f(1, 1, 1));
    Light light = DistantLight(FromZTo(w), At4(SampledSpectrum(1, 2, 3, 4)), 1.5f);
    EXPECT_EQ(light.Type(), LightType::DeltaDirection);
    light.Preprocess(UnitCube());
    Normal3f n = Normal3f(Normalize(Vector3f(0, 1, 2)));
    LightSampleContext ctx = ContextAt(Point3f(0.5f, 0, 0), n);
    pstd::optional<LightLiSample> ls = light.SampleLi(ctx, Point2f(0.5f, 0.5f), kLambda);
    ASSERT_TRUE(ls.has_value());
    EXPECT_LT(Length(ls->wi - w), 1e-6f);
    EXPECT_EQ(ls->pdf, 1);
    ExpectSpectrumNear(ls->L * Dot(ls->wi, Vector3f(n)),
                       1.5f * SampledSpectrum(1, 2, 3, 4) * Dot(w, Vector3f(n)), 1e-5f);
    // The shadow ray's end is outside the scene's bounding sphere.
    EXPECT_GT(Distance(ls->pLight, Point3f(0, 0, 0)), std::sqrt(3.f));
    ExpectSpectrumNear(light.Phi(kLambda), 1.5f * SampledSpectrum(1, 2, 3, 4) * Pi * 3, 1e-5f);
}

// ---------------------------------------------------------------------------------------
// Infinite lights

TEST(UniformInfiniteLight, IrradianceIsPiL) {
    Light light = UniformInfiniteLight(At4(SampledSpectrum(0.5f, 1, 2, 1.5f)), 2);
    EXPECT_EQ(light.Type(), LightType::Infinite);
    light.Preprocess(UnitCube());
    LightSampleContext ctx = ContextAt(Point3f(0.2f, 0.1f, 0), Normal3f(0, 1, 0));
    ExpectWithinFiveSigma(IrradianceByLightSampling(light, ctx), Pi * 2);
    ExpectSpectrumNear(light.Le(Ray(ctx.p, Vector3f(0, 1, 0)), kLambda), SampledSpectrum(1, 2, 4, 3),
                       0);
    ExpectSpectrumNear(light.Phi(kLambda), 4 * Pi * Pi * 3 * SampledSpectrum(1, 2, 4, 3), 1e-5f);
    pstd::optional<LightLiSample> ls = light.SampleLi(ctx, Point2f(0.3f, 0.3f), kLambda);
    ASSERT_TRUE(ls.has_value());
    EXPECT_NEAR(Distance(ls->pLight, ctx.p), 2 * std::sqrt(3.f), 1e-4f);
}

// pbrt-v4: under MIS, BSDF sampling handles a constant environment alone.
TEST(UniformInfiniteLight, DeclinesWhenPdfMayBeIncomplete) {
    UniformInfiniteLight light(Spectrum(1.f), 1);
    light.Preprocess(UnitCube());
    LightSampleContext ctx = ContextAt(Point3f(0, 0, 0), Normal3f(0, 0, 1));
    EXPECT_FALSE(light.SampleLi(ctx, Point2f(0.5f, 0.5f), kLambda, true).has_value());
    EXPECT_EQ(light.PDF_Li(ctx, Vector3f(0, 0, 1), true), 0);
    EXPECT_FLOAT_EQ(light.PDF_Li(ctx, Vector3f(0, 0, 1), false), Inv4Pi);
}

TEST(UniformInfiniteLight, ChiSquare) {
    Light light = UniformInfiniteLight(Spectrum(1.f), 1);
    light.Preprocess(UnitCube());
    ExpectSampleLiMatchesPDF(light, ContextAt(Point3f(0, 0, 0), Normal3f(0, 0, 1)), false, 1);
}

// A 16 x 16 equal-area map: dim sky, a bright 2 x 2 sun, a coloured gradient, one pixel with
// a negative channel (which must read as zero).
Image TestEnvironment() {
    constexpr int n = 16;
    Image image(Point2i(n, n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            bool sun = (x == 4 || x == 5) && (y == 10 || y == 11);
            Float base = sun ? 40 : 0.2f + 0.05f * x;
            image.SetChannel(Point2i(x, y), 0, base);
            image.SetChannel(Point2i(x, y), 1, base * (1 + 0.03f * y));
            image.SetChannel(Point2i(x, y), 2, base * 0.5f);
        }
    image.SetChannel(Point2i(12, 2), 0, -1);
    return image;
}

Transform EnvironmentRotation() { return RotateX(30) * RotateZ(70); }

TEST(ImageInfiniteLight, ChiSquare) {
    Light light = ImageInfiniteLight(EnvironmentRotation(), TestEnvironment(), 1);
    light.Preprocess(UnitCube());
    LightSampleContext ctx = ContextAt(Point3f(0, 0, 0), Normal3f(0, 0, 1));
    ExpectSampleLiMatchesPDF(light, ctx, false, 2);
    ExpectSampleLiMatchesPDF(light, ctx, true, 3);
}

TEST(ImageInfiniteLight, SampleLiAgreesWithLeAndPDF) {
    Light light = ImageInfiniteLight(EnvironmentRotation(), TestEnvironment(), 0.5f);
    light.Preprocess(UnitCube());
    LightSampleContext ctx = ContextAt(Point3f(0.1f, 0.2f, 0.3f), Normal3f(0, 0, 1));
    for (bool incomplete : {false, true})
        ExpectSampleLiConsistent(light, ctx, incomplete, [&](const LightLiSample &ls) {
            return light.Le(Ray(ctx.p, ls.wi), kLambda);
        });
}

// Exact irradiance: Le is constant per pixel and the map is equal-area, so a fine midpoint
// rule over the square (8 x 8 points per pixel) gives the integral of Le cos+ d omega.
TEST(ImageInfiniteLight, Irradiance) {
    Image image = TestEnvironment();
    Transform rotation = EnvironmentRotation();
    Light light = ImageInfiniteLight(rotation, image, 2);
    light.Preprocess(UnitCube());
    Normal3f n(Normalize(Vector3f(0.3f, -0.2f, 1)));
    LightSampleContext ctx = ContextAt(Point3f(0, 0, 0), n);
    constexpr int m = 16 * 8;
    double exact = 0;
    for (int y = 0; y < m; ++y)
        for (int x = 0; x < m; ++x) {
            Vector3f w = rotation(EqualAreaSquareToSphere(Point2f((x + 0.5f) / m, (y + 0.5f) / m)));
            exact += light.Le(Ray(ctx.p, w), kLambda)[1] * std::max<Float>(0, Dot(w, Vector3f(n)));
        }
    exact *= 4 * Pi / (m * m);
    ExpectWithinFiveSigma(IrradianceByLightSampling(light, ctx), exact);
}

// A pixel's radiance is the sRGB illuminant spectrum of its RGB, clamped at zero, times the scale.
SampledSpectrum PixelLe(RGB rgb, Float scale) {
    return scale * RGBIlluminantSpectrum(RGBColorSpace::sRGB(), ClampZero(rgb)).Sample(kLambda);
}

TEST(ImageInfiniteLight, PhiAndClampedNegativePixel) {
    Image image = TestEnvironment();
    Light light = ImageInfiniteLight(Transform(), image, 3);
    light.Preprocess(UnitCube());
    SampledSpectrum sum(0.f);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            sum += PixelLe(image.GetChannels(Point2i(x, y)), 1);
    ExpectSpectrumNear(light.Phi(kLambda), 4 * Pi * Pi * 3 * 3 * sum / 256, 1e-5f);
    // The pixel whose red is -1 emits as if its red were 0 (an RGB spectrum is positive at every
    // wavelength, so the check is against the clamped RGB's, not against 0 in one channel).
    RGB negative = image.GetChannels(Point2i(12, 2));
    ASSERT_EQ(negative[0], -1);
    Vector3f w = EqualAreaSquareToSphere(Point2f(12.5f / 16, 2.5f / 16));
    SampledSpectrum Le = light.Le(Ray(Point3f(0, 0, 0), w), kLambda);
    ExpectSpectrumNear(Le, PixelLe(RGB(0, negative[1], negative[2]), 3), 1e-6f);
    EXPECT_GT(Le.MinComponentValue(), 0);
    // Its red clamped to 0 makes the pixel bluer than its neighbour, whose red is 0.8: less
    // at 700 nm relative to 400 nm.
    SampledSpectrum neighbour = light.Le(
        Ray(Point3f(0, 0, 0), EqualAreaSquareToSphere(Point2f(12.5f / 16, 3.5f / 16))), kLambda);
    EXPECT_LT(Le[3] / Le[0], neighbour[3] / neighbour[0]);
}

// Compensation leaves pixels at or below the average to BSDF sampling; a constant map keeps
// its uniform density.
TEST(ImageInfiniteLight, CompensatedDistribution) {
    Light light = ImageInfiniteLight(Transform(), TestEnvironment(), 1);
    LightSampleContext ctx = ContextAt(Point3f(0, 0, 0), Normal3f(0, 0, 1));
    Vector3f dim = EqualAreaSquareToSphere(Point2f(0.5f / 16, 0.5f / 16));
    Vector3f sun = EqualAreaSquareToSphere(Point2f(4.5f / 16, 10.5f / 16));
    EXPECT_GT(light.PDF_Li(ctx, dim, false), 0);
    EXPECT_EQ(light.PDF_Li(ctx, dim, true), 0);
    // Map density of the sun pixel: (f - average)+ over the mean of (f - average)+, f being
    // the pixel's channel average.
    Image image = TestEnvironment();
    auto f = [&](int x, int y) { return ClampZero(image.GetChannels(Point2i(x, y))).Average(); };
    double average = 0, excess = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            average += f(x, y) / 256.0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            excess += std::max(0.0, f(x, y) - average) / 256.0;
    EXPECT_NEAR(light.PDF_Li(ctx, sun, true) * 4 * Pi, (f(4, 10) - average) / excess,
                1e-4 * (f(4, 10) - average) / excess);
    EXPECT_GT(light.PDF_Li(ctx, sun, true), light.PDF_Li(ctx, sun, false));

    Image flat(Point2i(4, 4));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c)
                flat.SetChannel(Point2i(x, y), c, 0.7f);
    Light constant = ImageInfiniteLight(Transform(), flat, 1);
    for (bool incomplete : {false, true})
        EXPECT_FLOAT_EQ(constant.PDF_Li(ctx, sun, incomplete), Inv4Pi);
}

TEST(ImageInfiniteLight, RejectsNonSquareImage) {
    EXPECT_THROW(ImageInfiniteLight(Transform(), Image(Point2i(8, 4)), 1), std::runtime_error);
}

// ---------------------------------------------------------------------------------------
// Area lights

TEST(DiffuseAreaLight, EmitsFromTheFrontUnlessTwoSided) {
    Disk disk(Transform(), false, 0, 1, 0, 360);  // normal +z
    Spectrum L = At4(SampledSpectrum(1, 2, 3, 4));
    Light oneSided = DiffuseAreaLight(disk, L, 2, false);
    Light twoSided = DiffuseAreaLight(disk, L, 2, true);
    EXPECT_EQ(oneSided.Type(), LightType::Area);
    Normal3f n(0, 0, 1);
    ExpectSpectrumNear(oneSided.L(Point3f(0, 0, 0), n, Point2f(), Vector3f(0, 0.6f, 0.8f), kLambda),
                       SampledSpectrum(2, 4, 6, 8), 0);
    EXPECT_FALSE(oneSided.L(Point3f(0, 0, 0), n, Point2f(), Vector3f(0, 0.6f, -0.8f), kLambda));
    ExpectSpectrumNear(twoSided.L(Point3f(0, 0, 0), n, Point2f(), Vector3f(0, 0.6f, -0.8f), kLambda),
                       SampledSpectrum(2, 4, 6, 8), 0);
    ExpectSpectrumNear(oneSided.Phi(kLambda), Pi * Pi * SampledSpectrum(2, 4, 6, 8), 1e-5f);
    ExpectSpectrumNear(twoSided.Phi(kLambda), 2 * Pi * Pi * SampledSpectrum(2, 4, 6, 8), 1e-5f);
    // Seen from behind, a one-sided light sends nothing.
    LightSampleContext below = ContextAt(Point3f(0, 0, -2), Normal3f(0, 0, 1));
    EXPECT_FALSE(oneSided.SampleLi(below, Point2f(0.3f, 0.6f), kLambda).has_value());
    EXPECT_TRUE(twoSided.SampleLi(below, Point2f(0.3f, 0.6f), kLambda).has_value());
}

// A sphere of radius R at distance d subtends a cone of sin alpha = R / d; facing it, the
// irradiance is pi L sin^2 alpha, and uniform cone sampling has pdf 1 / (2 pi (1 - cos alpha)).
TEST(DiffuseAreaLight, SphereIrradianceAndSolidAngle) {
    Float R = 1, d = 3;
    Sphere sphere(Translate(Vector3f(0, 0, d)), false, R, -R, R, 360);
    Light light = DiffuseAreaLight(sphere, At4(SampledSpectrum(1, 2, 3, 4)), 1.5f, false);
    LightSampleContext ctx = ContextAt(Point3f(0, 0, 0), Normal3f(0, 0, 1));
    Float sin2Alpha = Sqr(R / d), cosAlpha = std::sqrt(1 - sin2Alpha);
    EXPECT_NEAR(light.PDF_Li(ctx, Vector3f(0, 0, 1)), 1 / (2 * Pi * (1 - cosAlpha)), 1e-3f);
    EXPECT_EQ(light.PDF_Li(ctx, Vector3f(0, 1, 0)), 0);
    ExpectWithinFiveSigma(IrradianceByLightSampling(light, ctx), Pi * 1.5f * 2 * sin2Alpha);
    ExpectSpectrumNear(light.Phi(kLambda), Pi * 4 * Pi * R * R * 1.5f * SampledSpectrum(1, 2, 3, 4),
                       1e-5f);
    ExpectSampleLiMatchesPDF(light, ctx, false, 4);
    ExpectSampleLiConsistent(light, ctx, true, [&](const LightLiSample &ls) {
        return light.L(ls.pLight, ls.nLight, Point2f(), -ls.wi, kLambda);
    });
}

// On the axis of a disk of radius R at height h: E = pi L R^2 / (h^2 + R^2).
TEST(DiffuseAreaLight, DiskIrradiance) {
    Float R = 1.5f, h = 2;
    Disk disk(Translate(Vector3f(0, 0, h)), true, 0, R, 0, 360);  // reversed: faces -z
    Light light = DiffuseAreaLight(disk, At4(SampledSpectrum(1, 2, 3, 4)), 1, false);
    LightSampleContext ctx = ContextAt(Point3f(0, 0, 0), Normal3f(0, 0, 1));
    ExpectWithinFiveSigma(IrradianceByLightSampling(light, ctx), Pi * 2 * R * R / (h * h + R * R));
    ExpectSampleLiMatchesPDF(light, ctx, false, 5);
    ExpectSampleLiConsistent(light, ctx, false, [&](const LightLiSample &ls) {
        return light.L(ls.pLight, ls.nLight, Point2f(), -ls.wi, kLambda);
    });
}

TEST(DiffuseAreaLight, TriangleChiSquare) {
    TriangleMesh mesh = MakeTriangleMesh(Transform(), false, {0, 1, 2},
                                         {Point3f(-1, -1, 1), Point3f(2, -0.5f, 1.5f),
                                          Point3f(0, 1.5f, 0.5f)});
    Light light = DiffuseAreaLight(Triangle(&mesh, 0), Spectrum(1.f), 1, true);
    LightSampleContext ctx = ContextAt(Point3f(0.2f, 0.1f, -0.5f), Normal3f(0, 0, 1));
    ExpectSampleLiMatchesPDF(light, ctx, false, 6);
    ExpectSampleLiConsistent(light, ctx, false, [&](const LightLiSample &ls) {
        return light.L(ls.pLight, ls.nLight, Point2f(), -ls.wi, kLambda);
    });
}

// An image area light (pbrt-v4's "filename"): a 2x2 image, top row red and green, bottom row
// blue and white. t is flipped, so uv (0.25, 0.75) is the top-left texel's centre: red; uv
// (0.5, 0.5) is the mean of the four; RGB become the colour space's illuminant spectra.
TEST(DiffuseAreaLight, ImageEmissionFollowsUV) {
    Image image(Point2i(2, 2));
    RGB texels[4] = {RGB(1, 0, 0), RGB(0, 1, 0), RGB(0, 0, 1), RGB(1, 1, 1)};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(i % 2, i / 2), c, texels[i][c]);
    const RGBColorSpace &cs = RGBColorSpace::sRGB();
    auto emission = std::make_shared<const EmissionImage>(image, &cs);
    Disk disk(Transform(), false, 0, 1, 0, 360);
    Light light = DiffuseAreaLight(disk, Spectrum(1.f), 3, false, emission);
    Normal3f n(0, 0, 1);
    Vector3f w(0, 0.6f, 0.8f);
    auto spectrum = [&](RGB rgb) { return RGBIlluminantSpectrum(cs, rgb).Sample(kLambda); };
    ExpectSpectrumNear(light.L(Point3f(), n, Point2f(0.25f, 0.75f), w, kLambda), 3 * spectrum(RGB(1, 0, 0)), 1e-5f);
    ExpectSpectrumNear(light.L(Point3f(), n, Point2f(0.75f, 0.25f), w, kLambda), 3 * spectrum(RGB(1, 1, 1)), 1e-5f);
    ExpectSpectrumNear(light.L(Point3f(), n, Point2f(0.5f, 0.5f), w, kLambda), 3 * spectrum(RGB(0.5f, 0.5f, 0.5f)), 1e-5f);
    EXPECT_FALSE(light.L(Point3f(), n, Point2f(0.5f, 0.5f), -w, kLambda));
    // Power: pi area scale times the texels' mean spectrum (not the spectrum of their mean RGB).
    SampledSpectrum mean(0.f);
    for (RGB t : texels) mean += spectrum(t) / 4;
    ExpectSpectrumNear(light.Phi(kLambda), Pi * Pi * 3 * mean, 1e-4f);
    EXPECT_NEAR(emission->meanChannel, 0.5f, 1e-6f);
}

// pbrt-v4's "emissionfilename": a patch that samples its (u, v) in proportion to its emission
// image. Its irradiance is the one area or solid-angle sampling gives (within 5 sigma of their
// difference, near the patch and far from it); far away, where the geometry barely varies, it
// has less than half their noise; SampleLi's density is PDF_Li's (chi-square, and pointwise).
// (On a 4 x 4 image it had more noise than solid-angle sampling: the emission is bilinear, the
// density constant per texel, and their ratio runs up to 3 beside a bright texel.)
TEST(DiffuseAreaLight, EmissionImageSamplingIsUnbiasedAndLessNoisy) {
    // A dim 64 x 64 panel with a bright 8 x 8 block: the block's bilinear edges, where the
    // piecewise-constant density and the bilinear emission differ, are a small part of it.
    constexpr int n = 64;
    Image image(Point2i(n, n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            for (int c = 0; c < 3; ++c)
                image.SetChannel(Point2i(x, y), c, (x >= 20 && x < 28 && y >= 36 && y < 44) ? 50 : 1);
    auto emission = std::make_shared<const EmissionImage>(image, &RGBColorSpace::sRGB());
    std::vector<Float> f(n * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) f[size_t(j * n + i)] = emission->Lookup(Point2f((i + 0.5f) / n, (j + 0.5f) / n)).Average();
    auto makeMesh = [] {
        return MakeBilinearPatchMesh(Transform(), false, {0, 1, 2, 3},
                                     {Point3f(-1, -1, 1), Point3f(1, -1, 1), Point3f(-1, 1, 1), Point3f(1, 1, 1)});
    };
    BilinearPatchMesh byArea = makeMesh(), byImage = makeMesh();
    byImage.imageDistribution = std::make_shared<const PiecewiseConstant2D>(f, n, n);
    Light areaSampled = DiffuseAreaLight(BilinearPatch(&byArea, 0), Spectrum(1.f), 1, true, emission);
    Light imageSampled = DiffuseAreaLight(BilinearPatch(&byImage, 0), Spectrum(1.f), 1, true, emission);
    LightSampleContext near = ContextAt(Point3f(0.2f, -0.1f, 0), Normal3f(0, 0, 1));
    LightSampleContext far = ContextAt(Point3f(0.2f, -0.1f, -9), Normal3f(0, 0, 1));
    for (const LightSampleContext &ctx : {near, far}) {
        Estimate a = IrradianceByLightSampling(areaSampled, ctx), b = IrradianceByLightSampling(imageSampled, ctx);
        EXPECT_NEAR(a.mean, b.mean, 5 * std::hypot(a.stdError, b.stdError)) << a.mean << " " << b.mean;
        if (ctx.p.z < 0) {
            EXPECT_LT(b.stdError, 0.5 * a.stdError);
        }
    }
    ExpectSampleLiMatchesPDF(imageSampled, near, false, 9);
    RNG rng(11);
    for (int k = 0; k < 2000; ++k) {
        pstd::optional<LightLiSample> ls =
            imageSampled.SampleLi(near, Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()), kLambda);
        ASSERT_TRUE(ls.has_value());
        EXPECT_NEAR(imageSampled.PDF_Li(near, ls->wi), ls->pdf, 1e-3f * ls->pdf);
    }
}

// ---------------------------------------------------------------------------------------
// Portal light

// A 2 x 1 portal in the plane z = 2, centred over the origin, facing +z (corners in order).
std::array<Point3f, 4> TestPortal() {
    return {Point3f(-1, -0.5f, 2), Point3f(-1, 0.5f, 2), Point3f(1, 0.5f, 2), Point3f(1, -0.5f, 2)};
}

// Whether the ray from p along w crosses the portal.
bool ThroughTestPortal(Point3f p, Vector3f w) {
    if (w.z <= 0) return false;
    Point3f q = p + (2 - p.z) / w.z * w;
    return std::abs(q.x) <= 1 + 1e-4f && std::abs(q.y) <= 0.5f + 1e-4f;
}

// Seen from points below it, the portal light samples only directions through the portal, with
// the density PDF_Li gives (chi-square), and its radiance is what a ray through the portal finds.
TEST(PortalImageInfiniteLight, SamplesThroughThePortalAsPDFSays) {
    Light light = PortalImageInfiniteLight(EnvironmentRotation(), TestEnvironment(), 1,
                                           &RGBColorSpace::sRGB(), TestPortal());
    light.Preprocess(UnitCube());
    for (Point3f p : {Point3f(0, 0, 0), Point3f(0.7f, -0.4f, 1.2f)}) {
        LightSampleContext ctx = ContextAt(p, Normal3f(0, 0, 1));
        ExpectSampleLiMatchesPDF(light, ctx, false, 7);
        RNG rng(5);
        for (int k = 0; k < 2000; ++k) {
            pstd::optional<LightLiSample> ls =
                light.SampleLi(ctx, Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()), kLambda);
            ASSERT_TRUE(ls.has_value());
            EXPECT_TRUE(ThroughTestPortal(p, ls->wi)) << ls->wi.x << " " << ls->wi.y << " " << ls->wi.z;
        }
        ExpectSampleLiConsistent(light, ctx, false, [&](const LightLiSample &ls) {
            return light.Le(Ray(ctx.p, ls.wi), kLambda);
        });
        // Nothing arrives from outside the portal.
        EXPECT_EQ(light.PDF_Li(ctx, Normalize(Vector3f(3, 0, 1))), 0);
        EXPECT_FALSE(light.Le(Ray(ctx.p, Normalize(Vector3f(3, 0, 1))), kLambda));
    }
}

// Under a uniform sky L, the irradiance at a point a height h below the centre of an a x b
// portal parallel to it is L times the projected solid angle of the rectangle:
// 4 * (X / sqrt(1 + X^2) atan(Y / sqrt(1 + X^2)) + Y / sqrt(1 + Y^2) atan(X / sqrt(1 + Y^2))) / 2
// with X = a / 2h, Y = b / 2h (four corner rectangles of the differential-area form factor).
TEST(PortalImageInfiniteLight, IrradianceUnderAUniformSky) {
    Image sky(Point2i(8, 8));
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) sky.SetChannel(Point2i(x, y), c, 1);
    const RGBColorSpace &cs = RGBColorSpace::sRGB();
    Light light = PortalImageInfiniteLight(Transform(), sky, 1, &cs, TestPortal());
    light.Preprocess(UnitCube());
    LightSampleContext ctx = ContextAt(Point3f(0, 0, 0), Normal3f(0, 0, 1));
    Float L = RGBIlluminantSpectrum(cs, RGB(1, 1, 1)).Sample(kLambda)[1];
    double X = 1.0 / 2, Y = 0.5 / 2;
    double projected = 2 * (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
                            Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y)));
    ExpectWithinFiveSigma(IrradianceByLightSampling(light, ctx), L * projected);
}

}  // namespace
