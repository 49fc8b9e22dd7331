#include "pbrt_ext/samplers/samplers.h"

#include "pbrt_ext/util/log.h"

#include <fmt/format.h>

#include <bit>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

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

namespace {
// The extended Euclidean algorithm's x in a x + n y = gcd(a, n) = 1, taken mod n.
int64_t MultiplicativeInverse(int64_t a, int64_t n) {
    int64_t r0 = a, r1 = n, x0 = 1, x1 = 0;
    while (r1 != 0) {
        int64_t q = r0 / r1;
        std::tie(r0, r1) = std::pair(r1, r0 - q * r1);
        std::tie(x0, x1) = std::pair(x1, x0 - q * x1);
    }
    return Mod(x0, n);
}

void CheckCountAndResolution(const char *name, int samplesPerPixel, Point2i fullResolution) {
    if (samplesPerPixel < 1 || fullResolution.x < 1 || fullResolution.y < 1)
        throw std::runtime_error(fmt::format("{} sampler: samples per pixel and resolution must be "
                                             "positive", name));
}

void WarnUnlessPowerOfTwo(const char *name, int samplesPerPixel) {
    if (!std::has_single_bit(unsigned(samplesPerPixel)))
        Warning("%s sampler: %d samples per pixel is not a power of two; its samples do not "
                "form a net", name, samplesPerPixel);
}
}  // namespace

HaltonSampler::HaltonSampler(int samplesPerPixel, Point2i fullResolution, RandomizeStrategy randomize,
                             int seed)
    : samplesPerPixel(samplesPerPixel), seed(seed), randomize(randomize) {
    CheckCountAndResolution("halton", samplesPerPixel, fullResolution);
    if (randomize == RandomizeStrategy::FastOwen)
        throw std::runtime_error("halton sampler: fastowen is a base-2 scramble; expected none, "
                                 "permutedigits or owen");
    if (randomize == RandomizeStrategy::PermuteDigits)
        permutations = std::make_shared<const HaltonDigitPermutations>(uint32_t(seed));
    for (int i = 0; i < 2; ++i) {
        int base = i == 0 ? 2 : 3, scale = 1, exponent = 0;
        while (scale < std::min(fullResolution[i], kMaxHaltonResolution)) {
            scale *= base;
            ++exponent;
        }
        baseScales[i] = scale;
        baseExponents[i] = exponent;
    }
    sampleStride = baseScales[0] * baseScales[1];
    multInverse[0] = MultiplicativeInverse(baseScales[1], baseScales[0]);
    multInverse[1] = MultiplicativeInverse(baseScales[0], baseScales[1]);
}

// The index below the stride whose dimension 0 has the pixel's x digits (base 2) and whose
// dimension 1 has its y digits (base 3): the Chinese remainder theorem's combination of the
// two residues.
int64_t HaltonSampler::FirstIndexInPixel(Point2i p) const {
    if (sampleStride == 1) return 0;
    int64_t index = 0;
    for (int i = 0; i < 2; ++i) {
        uint64_t residue = InverseRadicalInverse(uint64_t(Mod(p[i], kMaxHaltonResolution)), i == 0 ? 2 : 3,
                                                 baseExponents[i]);
        index += int64_t(residue) * (sampleStride / baseScales[i]) * multInverse[i];
    }
    return index % sampleStride;
}

std::string HaltonSampler::ToString() const {
    return fmt::format("[ HaltonSampler samplesPerPixel: {} randomize: {} seed: {} baseScales: {} x {} ]",
                       samplesPerPixel, RandomizeName(randomize), seed, baseScales.x, baseScales.y);
}

SobolSampler::SobolSampler(int samplesPerPixel, Point2i fullResolution, RandomizeStrategy randomize, int seed)
    : samplesPerPixel(samplesPerPixel), randomize(randomize), dimensionHashes(seed) {
    CheckCountAndResolution("sobol", samplesPerPixel, fullResolution);
    WarnUnlessPowerOfTwo("sobol", samplesPerPixel);
    log2Scale = std::countr_zero(std::bit_ceil(unsigned(std::max(fullResolution.x, fullResolution.y))));
    int bits = 2 * log2Scale + std::bit_width(unsigned(samplesPerPixel - 1));
    if (bits > kSobolMatrixColumns)
        throw std::runtime_error(fmt::format(
            "sobol sampler: {} samples per pixel at resolution {} x {} need {}-bit indices; "
            "expected at most {}", samplesPerPixel, fullResolution.x, fullResolution.y, bits,
            kSobolMatrixColumns));
    // Column j of the system: dimension 1's top m bits from index bit m + j. Gauss-Jordan
    // elimination on [A | I] leaves A's inverse; A is invertible because every block of
    // 2^(2m) points is a (0, 2m, 2)-net, one point per pixel.
    int m = log2Scale;
    uint32_t rows[32] = {}, inverse[32] = {};
    for (int r = 0; r < m; ++r) {
        for (int j = 0; j < m; ++j)
            if ((SobolBits(1ull << (m + j), 1) >> (32 - m) >> r) & 1) rows[r] |= 1u << j;
        inverse[r] = 1u << r;
    }
    for (int col = 0; col < m; ++col) {
        int pivot = col;
        while (!((rows[pivot] >> col) & 1)) ++pivot;
        std::swap(rows[col], rows[pivot]);
        std::swap(inverse[col], inverse[pivot]);
        for (int r = 0; r < m; ++r)
            if (r != col && ((rows[r] >> col) & 1)) {
                rows[r] ^= rows[col];
                inverse[r] ^= inverse[col];
            }
    }
    // inverse[r] is row r of A^-1: bit c says whether rhs bit c enters unknown r. Transpose
    // it into the columns IndexOfPixelSample XORs.
    for (int r = 0; r < m; ++r)
        for (int c = 0; c < m; ++c)
            if ((inverse[r] >> c) & 1) yInverse[c] |= 1u << r;
}

std::string SobolSampler::ToString() const {
    return fmt::format("[ SobolSampler samplesPerPixel: {} randomize: {} seed: {} scale: {} ]",
                       samplesPerPixel, RandomizeName(randomize), dimensionHashes.Seed(), 1 << log2Scale);
}

PaddedSobolSampler::PaddedSobolSampler(int samplesPerPixel, RandomizeStrategy randomize, int seed)
    : samplesPerPixel(samplesPerPixel), seed(seed), randomize(randomize) {
    CheckCountAndResolution("paddedsobol", samplesPerPixel, Point2i(1, 1));
    WarnUnlessPowerOfTwo("paddedsobol", samplesPerPixel);
}

std::string PaddedSobolSampler::ToString() const {
    return fmt::format("[ PaddedSobolSampler samplesPerPixel: {} randomize: {} seed: {} ]", samplesPerPixel,
                       RandomizeName(randomize), seed);
}

PMJ02BNSampler::PMJ02BNSampler(int samplesPerPixel, int seed)
    : samplesPerPixel(samplesPerPixel), seed(seed) {
    if (samplesPerPixel < 1 || samplesPerPixel > kPMJ02bnSamples)
        throw std::runtime_error(fmt::format("pmj02bn sampler: {} samples per pixel; expected 1 to {}",
                                             samplesPerPixel, kPMJ02bnSamples));
    int log4Samples = (std::countr_zero(std::bit_ceil(unsigned(samplesPerPixel))) + 1) / 2;
    if (samplesPerPixel != 1 << (2 * log4Samples))
        Warning("pmj02bn sampler: %d samples per pixel is not a power of 4 (1, 4, 16, 64, ...); "
                "its pixel samples are then part of a net", samplesPerPixel);
    // A tile of pixelTileSize^2 pixels holds kPMJ02bnSamples points, a power of 4 per pixel
    // (a (0,2)-sequence puts as many in each square of that size); each pixel keeps its first
    // samplesPerPixel, in sequence order.
    int log4Points = std::countr_zero(unsigned(kPMJ02bnSamples)) / 2;
    pixelTileSize = 1 << (log4Points - log4Samples);
    auto samples = std::make_shared<std::vector<Point2f>>(size_t(pixelTileSize * pixelTileSize * samplesPerPixel));
    std::vector<int> stored(size_t(pixelTileSize * pixelTileSize), 0);
    for (int i = 0; i < kPMJ02bnSamples; ++i) {
        Point2<double> p = GetPMJ02BNSample(0, i);
        double x = p.x * pixelTileSize, y = p.y * pixelTileSize;
        int pixelOffset = int(x) + int(y) * pixelTileSize;
        if (stored[size_t(pixelOffset)] == samplesPerPixel) continue;
        (*samples)[size_t(pixelOffset * samplesPerPixel + stored[size_t(pixelOffset)]++)] =
            Point2f(std::min(Float(x - std::floor(x)), OneMinusEpsilon),
                    std::min(Float(y - std::floor(y)), OneMinusEpsilon));
    }
    pixelSamples = std::move(samples);
}

std::string PMJ02BNSampler::ToString() const {
    return fmt::format("[ PMJ02BNSampler samplesPerPixel: {} pixelTileSize: {} seed: {} ]", samplesPerPixel,
                       pixelTileSize, seed);
}

ZSobolSampler::ZSobolSampler(int samplesPerPixel, Point2i fullResolution, RandomizeStrategy randomize,
                             int seed)
    : randomize(randomize), dimensionHashes(seed) {
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
           " randomize: " + RandomizeName(randomize) + " seed: " + std::to_string(dimensionHashes.Seed()) +
           " ]";
}

}  // namespace pbrt
