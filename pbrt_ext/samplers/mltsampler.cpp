#include "pbrt_ext/samplers/mltsampler.h"

#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/sampling.h"

#include <cmath>
#include <fmt/format.h>

namespace pbrt {

MLTSampler::MLTSampler(int mutationsPerPixel, int64_t rngSequenceIndex, Float sigma,
                       Float largeStepProbability, int streamCount, int seed)
    : mutationsPerPixel(mutationsPerPixel),
      rng(MixBits(uint64_t(rngSequenceIndex)) ^ MixBits(uint64_t(seed))),
      sigma(sigma),
      largeStepProbability(largeStepProbability),
      streamCount(streamCount) {}

void MLTSampler::StartIteration() {
    ++currentIteration;
    largeStep = rng.Uniform<Float>() < largeStepProbability;
}

void MLTSampler::Accept() {
    if (largeStep)
        lastLargeStepIteration = currentIteration;
}

void MLTSampler::Reject() {
    for (PrimarySample &Xi : X)
        if (Xi.lastModificationIteration == currentIteration)
            Xi.Restore();
    --currentIteration;
}

void MLTSampler::StartStream(int index) {
    streamIndex = index;
    sampleIndex = 0;
}

void MLTSampler::StartPixelSample(Point2i p, int sampleIndex, int dimension) {
    rng.SetSequence(Hash(p));
    rng.Advance(int64_t(sampleIndex) * 65536 + int64_t(dimension) * 8192);
}

Float MLTSampler::Get1D() {
    int index = NextIndex();
    EnsureReady(index);
    return X[size_t(index)].value;
}

void MLTSampler::EnsureReady(int index) {
    if (size_t(index) >= X.size())
        X.resize(size_t(index) + 1);
    PrimarySample &Xi = X[size_t(index)];
    // A large step since the value was last read replaced it: draw it afresh.
    if (Xi.lastModificationIteration < lastLargeStepIteration) {
        Xi.value = rng.Uniform<Float>();
        Xi.lastModificationIteration = lastLargeStepIteration;
    }
    Xi.Backup();
    if (largeStep) {
        Xi.value = rng.Uniform<Float>();
    } else {
        // The small steps it missed, at once: n normal steps of sigma sum to one of sigma sqrt(n).
        int64_t nSmall = currentIteration - Xi.lastModificationIteration;
        Float effectiveSigma = sigma * std::sqrt(Float(nSmall));
        Xi.value += SampleNormal(rng.Uniform<Float>(), 0, effectiveSigma);
        // Wrapped around [0, 1); a value just below 0 would round to 1.
        Xi.value = std::min(Xi.value - std::floor(Xi.value), OneMinusEpsilon);
    }
    Xi.lastModificationIteration = currentIteration;
}

std::string MLTSampler::ToString() const {
    return fmt::format("[ MLTSampler sigma: {} largeStepProbability: {} streamCount: {} values: {} "
                       "currentIteration: {} largeStep: {} lastLargeStepIteration: {} ]",
                       sigma, largeStepProbability, streamCount, X.size(), currentIteration,
                       largeStep, lastLargeStepIteration);
}

}  // namespace pbrt
