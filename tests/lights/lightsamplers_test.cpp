// lightsamplers.h: the power sampler's PMF is proportional to the lights' power, Sample
// agrees with PMF and its frequencies match it (Pearson, 1e6 draws, alpha = 0.01); zero
// power lights are never chosen; the uniform sampler; empty light lists.
#include "tests/support/chi2.h"

#include "pbrt_ext/lights/lights.h"
#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/transform.h"

#include <gtest/gtest.h>

#include <vector>

using namespace pbrt;

namespace {

std::vector<Light> TestLights() {
    std::vector<Light> lights;
    // A spectrum that varies with wavelength (blackbody, peak 1), so that its power depends on
    // how the wavelengths are weighted.
    lights.push_back(PointLight(Translate(Vector3f(1, 2, 3)), BlackbodySpectrum(3000), 1));
    lights.push_back(PointLight(Transform(), Spectrum(0.f), 5));  // no power
    lights.push_back(SpotLight(Transform(), Spectrum(4.f), 2, 30, 25));
    lights.push_back(PointLight(Transform(), Spectrum(0.5f), 0.1f));
    return lights;
}

// pbrt-v4's power of a light for the power sampler: Phi at four visible wavelengths (stratified
// at u = 0.5) divided by their densities, averaged, as the film weights radiance.
double Power(const Light &light) {
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    return SafeDiv(light.Phi(lambda), lambda.PDF()).Average();
}

TEST(PowerLightSampler, PMFProportionalToPower) {
    std::vector<Light> lights = TestLights();
    PowerLightSampler sampler(lights);
    double total = 0;
    for (const Light &l : lights)
        total += Power(l);
    double sum = 0;
    for (int i = 0; i < int(lights.size()); ++i) {
        EXPECT_NEAR(sampler.PMF(i), Power(lights[i]) / total, 1e-6);
        sum += sampler.PMF(i);
    }
    EXPECT_NEAR(sum, 1, 1e-6);
    EXPECT_EQ(sampler.PMF(1), 0);
    EXPECT_EQ(sampler.PMF(-1), 0);
    EXPECT_EQ(sampler.PMF(4), 0);
}

TEST(PowerLightSampler, SampleMatchesPMF) {
    std::vector<Light> lights = TestLights();
    PowerLightSampler sampler(lights);
    constexpr int n = 1000000;
    std::vector<double> counts(lights.size(), 0);
    RNG rng(1);
    for (int k = 0; k < n; ++k) {
        pstd::optional<SampledLight> s = sampler.Sample(rng.Uniform<Float>());
        ASSERT_TRUE(s.has_value());
        ASSERT_NE(s->lightIndex, 1) << "a light without power was chosen";
        EXPECT_NEAR(s->p, sampler.PMF(s->lightIndex), 1e-6f);
        counts[s->lightIndex] += 1;
    }
    std::vector<std::pair<double, double>> cells;
    for (size_t i = 0; i < lights.size(); ++i)
        if (sampler.PMF(int(i)) > 0)
            cells.push_back({n * double(sampler.PMF(int(i))), counts[i]});
    chi2detail::Pearson p = chi2detail::PooledPearson(cells, 5);
    EXPECT_GE(Chi2SurvivalProbability(p.statistic, p.dof), 0.01) << "chi2 = " << p.statistic;
}

TEST(PowerLightSampler, NoPowerAnywhereIsUniform) {
    std::vector<Light> lights(3, Light(PointLight(Transform(), Spectrum(0.f), 1)));
    PowerLightSampler sampler(lights);
    for (int i = 0; i < 3; ++i)
        EXPECT_FLOAT_EQ(sampler.PMF(i), 1.f / 3);
    EXPECT_EQ(sampler.Sample(0.5f)->lightIndex, 1);
}

TEST(LightSamplers, EmptyListSamplesNothing) {
    std::vector<Light> none;
    EXPECT_FALSE(PowerLightSampler(none).Sample(0.3f).has_value());
    EXPECT_FALSE(UniformLightSampler(none).Sample(0.3f).has_value());
    EXPECT_EQ(PowerLightSampler(none).PMF(0), 0);
    EXPECT_EQ(UniformLightSampler(none).PMF(0), 0);
}

TEST(UniformLightSampler, EqualProbabilities) {
    std::vector<Light> lights = TestLights();
    UniformLightSampler sampler(lights);
    for (Float u : {0.f, 0.2f, 0.26f, 0.5f, 0.99999994f}) {
        pstd::optional<SampledLight> s = sampler.Sample(u);
        ASSERT_TRUE(s.has_value());
        EXPECT_EQ(s->lightIndex, int(u * 4));
        EXPECT_FLOAT_EQ(s->p, 0.25f);
        EXPECT_FLOAT_EQ(sampler.PMF(s->lightIndex), 0.25f);
    }
    LightSampleContext ctx(Point3f(0, 0, 0), Normal3f(0, 0, 1), Normal3f(0, 0, 1));
    EXPECT_EQ(sampler.Sample(ctx, 0.6f)->lightIndex, 2);
    EXPECT_FLOAT_EQ(sampler.PMF(ctx, 3), 0.25f);
}

}  // namespace
