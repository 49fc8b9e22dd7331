#include "pbrt_ext/samplers.h"

#include "pbrt_ext/util/log.h"

#include <bit>
#include <stdexcept>

namespace pbrt {

namespace {
const char *RandomizeName(RandomizeStrategy r) {
    switch (r) {
    case RandomizeStrategy::None:
        return "none";
    case RandomizeStrategy::PermuteDigits:
        return "permutedigits";
    case RandomizeStrategy::FastOwen:
        return "fastowen";
    case RandomizeStrategy::Owen:
        return "owen";
    }
    return "?";
}
}  // namespace

std::string IndependentSampler::ToString() const {
    return "[ IndependentSampler samplesPerPixel: " + std::to_string(samplesPerPixel) +
           " seed: " + std::to_string(seed) + " ]";
}

std::string StratifiedSampler::ToString() const {
    return "[ StratifiedSampler xPixelSamples: " + std::to_string(xPixelSamples) +
           " yPixelSamples: " + std::to_string(yPixelSamples) + " jitter: " + (jitter ? "true" : "false") +
           " seed: " + std::to_string(seed) + " ]";
}

ZSobolSampler::ZSobolSampler(int samplesPerPixel, Point2i fullResolution, RandomizeStrategy randomize,
                             int seed)
    : randomize(randomize), seed(seed) {
    if (samplesPerPixel < 1 || fullResolution.x < 1 || fullResolution.y < 1)
        throw std::runtime_error("ZSobolSampler: samples per pixel and resolution must be positive");
    unsigned spp = unsigned(samplesPerPixel);
    if (!std::has_single_bit(spp)) {
        Warning("zsobol sampler: %d samples per pixel is not a power of two; using %u", samplesPerPixel,
                std::bit_ceil(spp));
        spp = std::bit_ceil(spp);
    }
    log2SamplesPerPixel = std::countr_zero(spp);
    unsigned res = std::bit_ceil(unsigned(std::max(fullResolution.x, fullResolution.y)));
    int log4SamplesPerPixel = (log2SamplesPerPixel + 1) / 2;
    nBase4Digits = std::countr_zero(res) + log4SamplesPerPixel;
}

std::string ZSobolSampler::ToString() const {
    return "[ ZSobolSampler samplesPerPixel: " + std::to_string(SamplesPerPixel()) +
           " randomize: " + RandomizeName(randomize) + " seed: " + std::to_string(seed) + " ]";
}

}  // namespace pbrt
