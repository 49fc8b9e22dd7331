#include "pbrt_ext/samplers.h"

#include "pbrt_ext/util/log.h"

#include <fmt/format.h>

#include <bit>
#include <limits>
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

StratifiedSampler::StratifiedSampler(int xPixelSamples, int yPixelSamples, bool jitter, int seed)
    : xPixelSamples(xPixelSamples), yPixelSamples(yPixelSamples), seed(seed), jitter(jitter) {
    if (xPixelSamples < 1 || yPixelSamples < 1)
        throw std::runtime_error("stratified sampler: xsamples and ysamples must be positive");
    int64_t spp = int64_t(xPixelSamples) * yPixelSamples;
    if (spp > std::numeric_limits<int>::max())
        throw std::runtime_error(fmt::format("stratified sampler: {} x {} = {} samples per pixel; "
                                             "expected at most {}", xPixelSamples, yPixelSamples,
                                             spp, std::numeric_limits<int>::max()));
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
    unsigned spp = std::bit_ceil(unsigned(samplesPerPixel));
    constexpr unsigned kMaxSpp = 1u << 30;
    if (spp > kMaxSpp)
        throw std::runtime_error(fmt::format("zsobol sampler: {} samples per pixel round up to {}; "
                                             "expected at most {}", samplesPerPixel, spp, kMaxSpp));
    log2SamplesPerPixel = std::countr_zero(spp);
    int log2Resolution =
        std::countr_zero(std::bit_ceil(unsigned(std::max(fullResolution.x, fullResolution.y))));
    int bits = log2SamplesPerPixel + 2 * log2Resolution;
    if (bits > kMaxSampleIndexBits)
        throw std::runtime_error(fmt::format(
            "zsobol sampler: {} samples per pixel at resolution {} x {} need {}-bit sample indices "
            "({} bits for the samples, 2 x {} for the pixels); expected at most {} bits",
            spp, fullResolution.x, fullResolution.y, bits, log2SamplesPerPixel, log2Resolution,
            kMaxSampleIndexBits));
    if (int(spp) != samplesPerPixel)
        Warning("zsobol sampler: %d samples per pixel is not a power of two; using %u",
                samplesPerPixel, spp);
    int log4SamplesPerPixel = (log2SamplesPerPixel + 1) / 2;
    nBase4Digits = log2Resolution + log4SamplesPerPixel;
}

std::string ZSobolSampler::ToString() const {
    return "[ ZSobolSampler samplesPerPixel: " + std::to_string(SamplesPerPixel()) +
           " randomize: " + RandomizeName(randomize) + " seed: " + std::to_string(seed) + " ]";
}

}  // namespace pbrt
