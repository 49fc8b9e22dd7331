// The primary sample space of Metropolis light transport (MLTSampler): values in [0, 1); a large
// step draws them uniformly anew; a small step moves each by a normal of deviation sigma, and a
// value left unread for n iterations catches up by one of deviation sigma sqrt(n); a rejected
// proposal leaves the state it was made from; streams interleave without shifting each other.
// Seeds are fixed; statistical thresholds are stated at each test.
#include "pbrt_ext/samplers/mltsampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace pbrt;

namespace {

constexpr Float kSigma = 0.01f;
constexpr int kValues = 4000;

MLTSampler Make(Float largeStepProbability, int seed = 0) {
    return MLTSampler(100, 7, kSigma, largeStepProbability, 1, seed);
}

std::vector<Float> Read(MLTSampler &sampler, int n) {
    sampler.StartStream(0);
    std::vector<Float> v(static_cast<size_t>(n));
    for (Float &x : v) x = sampler.Get1D();
    return v;
}

// b - a wrapped to [-0.5, 0.5): the step that took a to b on the circle [0, 1).
double Step(Float a, Float b) {
    double d = double(b) - double(a);
    return d - std::floor(d + 0.5);
}

struct Moments {
    double mean = 0, deviation = 0;
};
Moments StepMoments(const std::vector<Float> &before, const std::vector<Float> &after) {
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < before.size(); ++i) {
        double d = Step(before[i], after[i]);
        sum += d;
        sum2 += d * d;
    }
    double n = double(before.size()), mean = sum / n;
    return {mean, std::sqrt(sum2 / n - mean * mean)};
}

TEST(MLTSampler, ValuesLieInTheUnitInterval) {
    MLTSampler sampler = Make(0.3f);
    for (int iteration = 0; iteration < 200; ++iteration) {
        sampler.StartIteration();
        for (Float x : Read(sampler, 100)) {
            ASSERT_GE(x, 0);
            ASSERT_LT(x, 1);
        }
        sampler.Accept();
    }
}

// 4000 uniform values: mean 0.5 and variance 1/12 within 4 standard errors (0.0183 and 0.0053).
TEST(MLTSampler, LargeStepsAreUniform) {
    MLTSampler sampler = Make(1);
    Read(sampler, kValues);
    sampler.StartIteration();
    std::vector<Float> v = Read(sampler, kValues);
    double sum = 0, sum2 = 0;
    for (Float x : v) {
        sum += x;
        sum2 += double(x) * x;
    }
    double mean = sum / kValues, variance = sum2 / kValues - mean * mean;
    EXPECT_NEAR(mean, 0.5, 4 * std::sqrt(1.0 / 12 / kValues));
    EXPECT_NEAR(variance, 1.0 / 12, 4 * std::sqrt(1.0 / 180 / kValues));
}

// Steps of deviation sigma (within 5 %: 4000 steps give a 1.1 % standard error), mean 0 within
// 4 standard errors; a value unread for 16 iterations moves by 4 sigma.
TEST(MLTSampler, SmallStepsAreNormalOfDeviationSigmaPerIteration) {
    MLTSampler sampler = Make(0);
    std::vector<Float> before = Read(sampler, kValues);
    sampler.StartIteration();
    std::vector<Float> after = Read(sampler, kValues);
    sampler.Accept();
    Moments m = StepMoments(before, after);
    EXPECT_NEAR(m.deviation, kSigma, 0.05 * kSigma);
    EXPECT_NEAR(m.mean, 0, 4 * kSigma / std::sqrt(double(kValues)));
    for (int i = 0; i < 16; ++i) sampler.StartIteration(), sampler.Accept();
    std::vector<Float> later = Read(sampler, kValues);
    EXPECT_NEAR(StepMoments(after, later).deviation, 4 * kSigma, 0.05 * 4 * kSigma);
}

// After a rejection the next proposal starts from the state before the rejected one: its steps
// from that state are of deviation sigma, not sigma sqrt(2).
TEST(MLTSampler, RejectRestoresTheState) {
    MLTSampler sampler = Make(0);
    std::vector<Float> state = Read(sampler, kValues);
    sampler.StartIteration();
    std::vector<Float> rejected = Read(sampler, kValues);
    sampler.Reject();
    sampler.StartIteration();
    std::vector<Float> proposal = Read(sampler, kValues);
    EXPECT_NEAR(StepMoments(state, proposal).deviation, kSigma, 0.05 * kSigma);
    EXPECT_NE(rejected, proposal);
}

// Each stream reads its own values: after a small step, stream 0's values are near their
// previous ones however many values stream 1 read before (a light subpath that grew or shrank).
TEST(MLTSampler, StreamsInterleaveWithoutShiftingEachOther) {
    MLTSampler sampler(100, 3, 1e-4f, 0, 3, 0);
    auto read = [&](int stream, int n) {
        sampler.StartStream(stream);
        std::vector<Float> v(static_cast<size_t>(n));
        for (Float &x : v) x = sampler.Get1D();
        return v;
    };
    read(1, 7);
    std::vector<Float> before = read(0, 5);
    sampler.StartIteration();
    read(1, 2);
    std::vector<Float> after = read(0, 5);
    for (size_t i = 0; i < before.size(); ++i) EXPECT_LT(std::abs(Step(before[i], after[i])), 1e-3) << i;
}

}  // namespace
