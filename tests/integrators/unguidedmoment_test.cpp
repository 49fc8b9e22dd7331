// The path tracer's second moment estimated from guided paths (integrators/unguidedmoment.h):
// exact in expectation. On a toy estimator of two scattering vertices and a roulette between them,
// whose outcomes are few enough to enumerate, the guided estimate's expectation over the guided
// choices equals the path tracer's second moment over its own (to the rounding of the spectra's
// floats, 1e-6 relative); without guiding it is the square of the sample; it weighs wavelengths
// as the path left them (a dispersive surface keeps one); the path tracer's throughput is the
// guided one over the ratio of densities; and a path the path tracer cannot take adds nothing.
#include "pbrt_ext/integrators/unguidedmoment.h"

#include <gtest/gtest.h>

#include <array>

using namespace pbrt;

namespace {

// Each contribution is a constant spectrum; a unit of it adds 1 to the value.
const SampledSpectrum kToValue(1.f / NSpectrumSamples);

// The toy path: a contribution c0 before any choice; a first direction i with probability
// path1[i] under the path tracer, guided1[i] guided, and its contribution c1[i] (the path
// tracer's); a roulette survived with probability survivePath[i] or surviveGuided[i]; a second
// direction j (path2[j], guided2[j]) and its contribution before the roulette's division, c2[i][j].
constexpr double c0 = 0.3;
constexpr std::array<double, 2> path1{0.8, 0.2}, guided1{0.4, 0.6}, c1{1, 5};
constexpr std::array<double, 2> survivePath{1, 0.5}, surviveGuided{0.5, 1};
constexpr std::array<double, 2> path2{0.5, 0.5}, guided2{0.9, 0.1};
constexpr std::array<std::array<double, 2>, 2> c2{{{2, 0}, {1, 10}}};

// The guided estimate along the path that chose i, then (if it survived) j.
double GuidedEstimate(int i, int j, bool survived) {
    UnguidedMoment moment;
    double ratio = 1;  // the path tracer's density over the guided one, so far
    moment.Add(SampledSpectrum(float(ratio * c0)));
    moment.Scattered(float(path1[i]), float(guided1[i]));
    ratio *= path1[i] / guided1[i];
    moment.Add(SampledSpectrum(float(ratio * c1[i])));
    if (!survived)
        return moment.SecondMoment(kToValue);
    moment.Survived(float(survivePath[i]), float(surviveGuided[i]));
    moment.Scattered(float(path2[j]), float(guided2[j]));
    ratio *= survivePath[i] / surviveGuided[i] * path2[j] / guided2[j];
    moment.Add(SampledSpectrum(float(ratio * c2[i][j] / survivePath[i])));
    return moment.SecondMoment(kToValue);
}

TEST(UnguidedMoment, ItsExpectationOverGuidedPathsIsThePathTracersSecondMoment) {
    double pathTracer = 0, guided = 0;
    for (int i = 0; i < 2; ++i) {
        const double first = c0 + c1[i];
        pathTracer += path1[i] * (1 - survivePath[i]) * first * first;
        guided += guided1[i] * (1 - surviveGuided[i]) * GuidedEstimate(i, 0, false);
        for (int j = 0; j < 2; ++j) {
            const double all = first + c2[i][j] / survivePath[i];
            pathTracer += path1[i] * survivePath[i] * path2[j] * all * all;
            guided += guided1[i] * surviveGuided[i] * guided2[j] * GuidedEstimate(i, j, true);
        }
    }
    EXPECT_NEAR(guided, pathTracer, 1e-6 * pathTracer);  // the floats of the spectra: 1e-7 each
    EXPECT_GT(pathTracer, 10);
}

TEST(UnguidedMoment, WithoutGuidingItIsTheSamplesSquare) {
    UnguidedMoment moment;
    moment.Add(SampledSpectrum(0.5f));
    moment.Scattered(0.7f, 0.7f);
    moment.Add(SampledSpectrum(2.f));
    moment.Survived(0.4f, 0.4f);
    moment.Add(SampledSpectrum(1.f));
    EXPECT_NEAR(moment.SecondMoment(kToValue), 3.5 * 3.5, 1e-6);
}

TEST(UnguidedMoment, WeighsTheWavelengthsAsThePathLeftThem) {
    UnguidedMoment moment;
    moment.Add(SampledSpectrum(1, 2, 3, 4));
    moment.Scattered(0.5f, 1);
    moment.Add(SampledSpectrum(2, 0, 0, 0));
    // Weighed by the first wavelength alone, 4 times (as once the secondary ones end): the guided
    // path's contributions are worth 4 and 8, the second on a path the path tracer takes half as
    // often (worth 16 to it): 4 · 4 + 8 · (16 + 2 · 4).
    const double got = moment.SecondMoment(SampledSpectrum(4, 0, 0, 0));
    EXPECT_NEAR(got, 4 * 4 + 8 * (16 + 2 * 4), 1e-9);
}

TEST(UnguidedMoment, ThePathTracersThroughputIsTheGuidedOneOverTheRatio) {
    UnguidedMoment moment;
    moment.Scattered(0.2f, 0.8f);
    moment.Survived(1, 0.5f);
    EXPECT_NEAR(moment.PathThroughput(0.25f), 0.25f / (0.25f * 2), 1e-6f);
}

TEST(UnguidedMoment, APathThePathTracerCannotTakeAddsNothing) {
    UnguidedMoment moment;
    moment.Add(SampledSpectrum(1.f));
    moment.Scattered(0, 0.5f);  // a direction the BSDF does not sample
    moment.Add(SampledSpectrum(3.f));
    EXPECT_EQ(moment.SecondMoment(kToValue), 1);
}

}  // namespace
