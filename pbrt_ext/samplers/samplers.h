// Sample generators for the pixel integrals (pbrt-v4's samplers.h): independent, stratified,
// Halton, Sobol', padded Sobol', zsobol and pmj02bn.
//
// Every value is a pure function of (pixel, sample index, dimension, seed): StartPixelSample
// resets the state, so an image does not depend on which thread renders which pixel, or in
// which order. Values lie in [0, 1). A sampler is a small value type; each thread uses its own
// copy.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/samplers/mltsampler.h"
#include "pbrt_ext/util/bluenoise.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/lowdiscrepancy.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pmj02tables.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace pbrt {

// ---- The samplers ----------------------------------------------------------------------------

// Independent uniform values: each (pixel, sample) pair owns a PCG32 stream position, so the
// sequence needs no state beyond the current offset.
class IndependentSampler {
  public:
    explicit IndependentSampler(int samplesPerPixel, int seed = 0)
        : samplesPerPixel(samplesPerPixel), seed(seed) {
        if (samplesPerPixel < 1) throw std::runtime_error("independent sampler: pixelsamples must be positive");
    }

    static constexpr const char *Name() { return "independent"; }
    PBRT_CPU_GPU int SamplesPerPixel() const { return samplesPerPixel; }

    // 65536 values are reserved per sample, far more than a path consumes.
    PBRT_CPU_GPU void StartPixelSample(Point2i p, int sampleIndex, int dimension = 0) {
        rng.SetSequence(Hash(p, seed));
        rng.Advance(sampleIndex * 65536ull + dimension);
    }
    PBRT_CPU_GPU Float Get1D() { return rng.Uniform<Float>(); }
    PBRT_CPU_GPU Point2f Get2D() { return {rng.Uniform<Float>(), rng.Uniform<Float>()}; }
    PBRT_CPU_GPU Point2f GetPixel2D() { return Get2D(); }

    std::string ToString() const;

  private:
    int samplesPerPixel, seed;
    RNG rng;
};

// Jittered strata: in each dimension the pixel's samples visit the xPixelSamples * yPixelSamples
// strata in a permuted order that differs per pixel and dimension (Kensler's hash permutation),
// so that dimensions are not correlated with each other.
class StratifiedSampler {
  public:
    // Throws std::runtime_error unless both counts are positive and their product, the samples
    // per pixel, fits an int.
    StratifiedSampler(int xPixelSamples, int yPixelSamples, bool jitter, int seed = 0);

    static constexpr const char *Name() { return "stratified"; }
    PBRT_CPU_GPU int SamplesPerPixel() const { return xPixelSamples * yPixelSamples; }

    PBRT_CPU_GPU void StartPixelSample(Point2i p, int index, int dim = 0) {
        pixel = p;
        sampleIndex = index;
        dimension = dim;
        rng.SetSequence(Hash(p, seed));
        rng.Advance(sampleIndex * 65536ull + dimension);
    }

    PBRT_CPU_GPU Float Get1D() {
        uint64_t hash = Hash(pixel, dimension, seed);
        int stratum = PermutationElement(sampleIndex, SamplesPerPixel(), uint32_t(hash));
        ++dimension;
        Float delta = jitter ? rng.Uniform<Float>() : 0.5f;
        return std::min((stratum + delta) / SamplesPerPixel(), OneMinusEpsilon);
    }
    PBRT_CPU_GPU Point2f Get2D() {
        uint64_t hash = Hash(pixel, dimension, seed);
        int stratum = PermutationElement(sampleIndex, SamplesPerPixel(), uint32_t(hash));
        dimension += 2;
        int x = stratum % xPixelSamples, y = stratum / xPixelSamples;
        Float dx = jitter ? rng.Uniform<Float>() : 0.5f;
        Float dy = jitter ? rng.Uniform<Float>() : 0.5f;
        return {std::min((x + dx) / xPixelSamples, OneMinusEpsilon),
                std::min((y + dy) / yPixelSamples, OneMinusEpsilon)};
    }
    PBRT_CPU_GPU Point2f GetPixel2D() { return Get2D(); }

    std::string ToString() const;

  private:
    int xPixelSamples, yPixelSamples, seed;
    bool jitter;
    RNG rng;
    Point2i pixel;
    int sampleIndex = 0, dimension = 0;
};

// Hash(dimension, seed) for a sampler's first kTabled dimensions, computed once: the Sobol'
// samplers scramble every value of a dimension with it, the same for every pixel and sample.
class DimensionHashes {
  public:
    static constexpr int kTabled = 64;
    explicit DimensionHashes(int seed) : seed(seed) {
        for (int d = 0; d < kTabled; ++d) hashes[d] = Hash(d, seed);
    }
    uint64_t operator()(int dimension) const {
        return dimension < kTabled ? hashes[dimension] : Hash(dimension, seed);
    }
    int Seed() const { return seed; }

  private:
    int seed;
    uint64_t hashes[kTabled];
};

// Ahmed and Wonka's screen-space blue-noise Sobol' sampler (SIGGRAPH Asia 2020), as pbrt-v4:
// pixels are ordered along a Morton curve, and the base-4 digits of (Morton index, sample index)
// are shuffled by per-level hashed permutations before indexing a scrambled 2D Sobol' sequence;
// each dimension (or pair) gets its own shuffle and scramble. Neighbouring pixels thereby get
// well-distributed, decorrelated subsets of one low-discrepancy sequence.
class ZSobolSampler {
  public:
    // A samplesPerPixel that is not a power of two is rounded up (with a warning), as the
    // construction needs whole base-2 digits. Throws std::runtime_error for a non-positive
    // count or resolution, a rounded count above 2^30 (SamplesPerPixel is an int), or one whose
    // sample indices, with the pixels' Morton codes above them, need more than
    // kMaxSampleIndexBits bits.
    ZSobolSampler(int samplesPerPixel, Point2i fullResolution,
                  RandomizeStrategy randomize = RandomizeStrategy::FastOwen, int seed = 0);

    // mortonIndex holds the sample index below the pixel's Morton code in 64 bits, and
    // GetSampleIndex shifts it right by as many bits as the two take, which must stay below 64.
    static constexpr int kMaxSampleIndexBits = 63;

    static constexpr const char *Name() { return "zsobol"; }
    PBRT_CPU_GPU int SamplesPerPixel() const { return 1 << log2SamplesPerPixel; }

    PBRT_CPU_GPU void StartPixelSample(Point2i p, int index, int dim = 0) {
        dimension = dim;
        uint64_t pixelCode = EncodeMorton2(uint32_t(p.x), uint32_t(p.y));
        if (pixelCode != cachedPixelCode) {
            cachedPixelCode = pixelCode;
            cachedDimensions = 0;
        }
        mortonIndex = (pixelCode << log2SamplesPerPixel) | uint64_t(index);
    }

    PBRT_CPU_GPU Float Get1D() {
        uint64_t sampleIndex = GetSampleIndex();
        ++dimension;
        uint32_t sampleHash = uint32_t(dimensionHashes(dimension));
        return SobolSample(sampleIndex, 0, randomize, sampleHash);
    }
    PBRT_CPU_GPU Point2f Get2D() {
        uint64_t sampleIndex = GetSampleIndex();
        dimension += 2;
        uint64_t bits = dimensionHashes(dimension);
        return {SobolSample(sampleIndex, 0, randomize, uint32_t(bits)),
                SobolSample(sampleIndex, 1, randomize, uint32_t(bits >> 32))};
    }
    PBRT_CPU_GPU Point2f GetPixel2D() { return Get2D(); }

    std::string ToString() const;

  private:
    // Digit d of the 4-element permutation with index 0..23 (a compile-time table).
    PBRT_CPU_GPU static int PermuteDigit(int permutation, int digit) {
        return kDigitPermutations.p[permutation][digit];
    }

    // The sample's index after the digits' permutations. The base-4 digits above the sample's
    // own bits, and their permutations, depend only on the pixel and the dimension: they are
    // kept for each dimension while the pixel's samples follow one another (the same bits).
    PBRT_CPU_GPU uint64_t GetSampleIndex() {
        const int firstPixelDigit = (log2SamplesPerPixel + 1) / 2;
        uint64_t pixelDigits;
        if (dimension < kCachedDimensions && ((cachedDimensions >> dimension) & 1))
            pixelDigits = pixelDigitsCache[dimension];
        else {
            pixelDigits = PermutedDigits(firstPixelDigit, nBase4Digits);
            if (dimension < kCachedDimensions) {
                pixelDigitsCache[dimension] = pixelDigits;
                cachedDimensions |= uint64_t(1) << dimension;
            }
        }
        // With an odd log2(spp) the last base-4 digit is half a digit: one base-2 digit.
        bool pow2Samples = log2SamplesPerPixel & 1;
        uint64_t sampleIndex = pixelDigits | PermutedDigits(pow2Samples ? 1 : 0, firstPixelDigit);
        if (pow2Samples) {
            int digit = int(mortonIndex & 1);
            sampleIndex |= digit ^ (MixBits((mortonIndex >> 1) ^ (0x55555555u * uint32_t(dimension))) & 1);
        }
        return sampleIndex;
    }

    // Base-4 digits [first, last) of the index, each permuted by one of the 24 permutations,
    // chosen by a hash of the digits above it and the dimension.
    PBRT_CPU_GPU uint64_t PermutedDigits(int first, int last) const {
        uint64_t digits = 0;
        int shiftBias = log2SamplesPerPixel & 1;
        for (int i = first; i < last; ++i) {
            int digitShift = 2 * i - shiftBias;
            int digit = int((mortonIndex >> digitShift) & 3);
            uint64_t higherDigits = mortonIndex >> (digitShift + 2);
            int p = int((MixBits(higherDigits ^ (0x55555555u * uint32_t(dimension))) >> 24) % 24);
            digits |= uint64_t(PermuteDigit(p, digit)) << digitShift;
        }
        return digits;
    }

    RandomizeStrategy randomize;
    int log2SamplesPerPixel, nBase4Digits;
    DimensionHashes dimensionHashes;  // and the seed
    uint64_t mortonIndex = 0;
    int dimension = 0;
    // The pixel digits of GetSampleIndex for the dimensions below kCachedDimensions: bit d of
    // cachedDimensions says whether pixelDigitsCache[d] holds dimension d's for the pixel whose
    // Morton code is cachedPixelCode.
    static constexpr int kCachedDimensions = 64;
    uint64_t cachedPixelCode = 0, cachedDimensions = 0;
    uint64_t pixelDigitsCache[kCachedDimensions] = {};
};

// The first of the next n dimensions of a sampler that has `count`, advancing past them; when
// they run out it starts over at dimension 2, past the pixel's, as pbrt-v4's samplers do.
inline int NextDimensions(int &dimension, int n, int count) {
    if (dimension + n > count) dimension = 2;
    int first = dimension;
    dimension += n;
    return first;
}

// Halton points (pbrt-v4's HaltonSampler): dimension d is the radical inverse in the d-th
// prime base. The first two dimensions span the image in tiles of 2^j x 3^k pixels (j and k
// the smallest with 2^j, 3^k >= the resolution, at most 128): by the Chinese remainder
// theorem, exactly one of every 2^j 3^k consecutive indices lands in each pixel of a tile,
// and a pixel's samples are that index plus multiples of the stride 2^j 3^k. The stride is
// coprime to every other base, so each dimension is stratified within every pixel.
class HaltonSampler {
  public:
    // Throws std::runtime_error for a non-positive count or resolution, and for fastowen,
    // which is a base-2 scramble (pbrt-v4 refuses it for Halton too).
    HaltonSampler(int samplesPerPixel, Point2i fullResolution,
                  RandomizeStrategy randomize = RandomizeStrategy::PermuteDigits, int seed = 0);

    static constexpr const char *Name() { return "halton"; }
    int SamplesPerPixel() const { return samplesPerPixel; }

    void StartPixelSample(Point2i p, int sampleIndex, int dim = 0) {
        // A pixel's samples are drawn one after another: its first index (two inverse
        // radical inverses and 64-bit divisions) is computed once.
        if (p != indexedPixel) {
            indexedPixel = p;
            pixelFirstIndex = FirstIndexInPixel(p);
        }
        haltonIndex = pixelFirstIndex + int64_t(sampleIndex) * sampleStride;
        dimension = std::max(2, dim);
    }
    Float Get1D() { return SampleDimension(NextDimensions(dimension, 1, kPrimeTableSize)); }
    Point2f Get2D() {
        int dim = NextDimensions(dimension, 2, kPrimeTableSize);
        return {SampleDimension(dim), SampleDimension(dim + 1)};
    }
    RandomizeStrategy GetRandomizeStrategy() const { return randomize; }
    // The digits below the pixel's: the sample's position inside its pixel.
    Point2f GetPixel2D() const {
        return {RadicalInverse(0, uint64_t(haltonIndex) >> baseExponents[0]),
                RadicalInverse(1, uint64_t(haltonIndex) / uint64_t(baseScales[1]))};
    }

    std::string ToString() const;

  private:
    static constexpr int kMaxHaltonResolution = 128;

    int64_t FirstIndexInPixel(Point2i p) const;

    Float SampleDimension(int dim) const {
        switch (randomize) {
        case RandomizeStrategy::PermuteDigits:
            return ScrambledRadicalInverse(dim, uint64_t(haltonIndex), *permutations);
        case RandomizeStrategy::Owen:
            return OwenScrambledRadicalInverse(dim, uint64_t(haltonIndex), uint32_t(Hash(dim, seed)));
        default:
            return RadicalInverse(dim, uint64_t(haltonIndex));
        }
    }

    int samplesPerPixel, seed;
    RandomizeStrategy randomize;
    std::shared_ptr<const HaltonDigitPermutations> permutations;  // shared by every thread's copy
    Point2i baseScales, baseExponents;
    int sampleStride;
    int64_t multInverse[2];
    int64_t haltonIndex = 0;
    int dimension = 0;
    Point2i indexedPixel{std::numeric_limits<int>::min(), std::numeric_limits<int>::min()};
    int64_t pixelFirstIndex = 0;
};

// Global Sobol' points (pbrt-v4's SobolSampler): the first two dimensions span the image,
// scaled to the next power of two 2^m of its larger side, and every other dimension is a
// randomized Sobol' dimension of the same index. Each block of 2^(2m) consecutive indices puts
// one point in every pixel, so a pixel's n-th sample is the one of block n that lands in it.
class SobolSampler {
  public:
    // Throws std::runtime_error for a non-positive count or resolution, or when 2m plus the
    // sample count's bits exceed the generator matrices' kSobolMatrixColumns.
    SobolSampler(int samplesPerPixel, Point2i fullResolution,
                 RandomizeStrategy randomize = RandomizeStrategy::FastOwen, int seed = 0);

    static constexpr const char *Name() { return "sobol"; }
    int SamplesPerPixel() const { return samplesPerPixel; }

    void StartPixelSample(Point2i p, int sampleIndex, int dim = 0) {
        sobolIndex = IndexOfPixelSample(p, uint64_t(sampleIndex));
        dimension = std::max(2, dim);
    }
    Float Get1D() { return SampleDimension(NextDimensions(dimension, 1, kSobolDimensions)); }
    Point2f Get2D() {
        int dim = NextDimensions(dimension, 2, kSobolDimensions);
        return {SampleDimension(dim), SampleDimension(dim + 1)};
    }
    // The bits below the pixel's (the top m of dimensions 0 and 1), unscrambled as pbrt-v4's.
    Point2f GetPixel2D() const {
        return {BitsToUnitFloat(SobolBits(sobolIndex, 0) << log2Scale),
                BitsToUnitFloat(SobolBits(sobolIndex, 1) << log2Scale)};
    }

    std::string ToString() const;

  private:
    // The index in block `frame` whose first two dimensions fall in pixel p: its low m bits
    // are p.x's bits reversed (dimension 0 is the van der Corput sequence), and the next m
    // solve a linear system over GF(2) for p.y, through the inverse precomputed in yInverse.
    uint64_t IndexOfPixelSample(Point2i p, uint64_t frame) const {
        if (log2Scale == 0) return frame;
        uint64_t known = (frame << (2 * log2Scale)) | (ReverseBits32(uint32_t(p.x)) >> (32 - log2Scale));
        uint32_t rhs = uint32_t(p.y) ^ (SobolBits(known, 1) >> (32 - log2Scale));
        uint64_t middle = 0;
        for (int r = 0; r < log2Scale; ++r)
            if ((rhs >> r) & 1) middle ^= yInverse[r];
        return known | (middle << log2Scale);
    }

    Float SampleDimension(int dim) const {
        uint32_t v = SobolBitsFromMatrix(sobolIndex, SobolMatrix(dim));
        return BitsToUnitFloat(Scramble(v, randomize, uint32_t(dimensionHashes(dim))));
    }

    int samplesPerPixel, log2Scale;
    RandomizeStrategy randomize;
    DimensionHashes dimensionHashes;  // and the seed
    uint32_t yInverse[32] = {};
    uint64_t sobolIndex = 0;
    int dimension = 0;
};

// Padded 2D Sobol' points (pbrt-v4's PaddedSobolSampler): every dimension pair is a
// scrambled (0, 2)-sequence of its own, the pixel's samples visiting it in an order permuted
// by a hash of (pixel, dimension), so that pairs are not correlated with each other. Each
// pixel's 2^k samples form a (0, k, 2)-net in every pair.
class PaddedSobolSampler {
  public:
    // Throws std::runtime_error for a non-positive count; warns when it is not a power of two.
    PaddedSobolSampler(int samplesPerPixel, RandomizeStrategy randomize = RandomizeStrategy::FastOwen,
                       int seed = 0);

    static constexpr const char *Name() { return "paddedsobol"; }
    int SamplesPerPixel() const { return samplesPerPixel; }
    RandomizeStrategy GetRandomizeStrategy() const { return randomize; }

    void StartPixelSample(Point2i p, int index, int dim = 0) {
        pixel = p;
        sampleIndex = index;
        dimension = dim;
    }
    Float Get1D() {
        uint64_t hash = Hash(pixel, dimension++, seed);
        uint32_t index = uint32_t(PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash)));
        return SobolSample(index, 0, randomize, uint32_t(hash >> 32));
    }
    Point2f Get2D() {
        uint64_t hash = Hash(pixel, dimension, seed);
        dimension += 2;
        uint32_t index = uint32_t(PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash)));
        return {SobolSample(index, 0, randomize, uint32_t(hash)),
                SobolSample(index, 1, randomize, uint32_t(hash >> 32))};
    }
    Point2f GetPixel2D() { return Get2D(); }

    std::string ToString() const;

  private:
    int samplesPerPixel, seed;
    RandomizeStrategy randomize;
    Point2i pixel;
    int sampleIndex = 0, dimension = 0;
};

// Progressive multi-jittered (0,2) points with blue noise (pbrt-v4's PMJ02BNSampler): dimension
// pairs 2-11 each read one of the generated pmj02bn sets (util/pmj02tables.h) by sample index,
// shifted per pixel by blue-noise textures (a Cranley-Patterson rotation, util/bluenoise.h);
// later pairs read them at a hashed permutation of the index. The pixel samples tile the first
// set over pixelTileSize^2 pixels, each pixel taking the points inside it, so neighbouring
// pixels' samples are one net. 1D values are jittered strata in a permuted order.
class PMJ02BNSampler {
  public:
    // Throws std::runtime_error for a non-positive count or one above kPMJ02bnSamples; warns
    // when it is not a power of 4 (the pixel samples then are a subset of a net).
    explicit PMJ02BNSampler(int samplesPerPixel, int seed = 0);

    static constexpr const char *Name() { return "pmj02bn"; }
    int SamplesPerPixel() const { return samplesPerPixel; }

    void StartPixelSample(Point2i p, int index, int dim = 0) {
        pixel = p;
        sampleIndex = index;
        dimension = std::max(2, dim);
    }
    Float Get1D() {
        uint64_t hash = Hash(pixel, dimension, seed);
        int stratum = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash));
        Float delta = BlueNoise(dimension, pixel);
        ++dimension;
        return std::min((stratum + delta) / samplesPerPixel, OneMinusEpsilon);
    }
    Point2f Get2D() {
        int index = sampleIndex, set = dimension / 2;
        if (set >= kPMJ02bnSets) {
            uint64_t hash = Hash(pixel, dimension, seed);
            index = PermutationElement(uint32_t(sampleIndex), uint32_t(samplesPerPixel), uint32_t(hash));
        }
        Point2<double> u = GetPMJ02BNSample(set, index);
        Float x = WrapShift(u.x, BlueNoise(dimension, pixel)), y = WrapShift(u.y, BlueNoise(dimension + 1, pixel));
        dimension += 2;
        return {x, y};
    }
    Point2f GetPixel2D() const {
        int px = pixel.x % pixelTileSize, py = pixel.y % pixelTileSize;
        return (*pixelSamples)[size_t((px + py * pixelTileSize) * samplesPerPixel + sampleIndex)];
    }

    std::string ToString() const;

  private:
    // u + shift, modulo 1, kept below 1.
    static Float WrapShift(double u, Float shift) {
        Float v = Float(u) + shift;
        if (v >= 1) v -= 1;
        return std::min(v, OneMinusEpsilon);
    }

    int samplesPerPixel, seed, pixelTileSize;
    std::shared_ptr<const std::vector<Point2f>> pixelSamples;  // shared by every thread's copy
    Point2i pixel;
    int sampleIndex = 0, dimension = 0;
};

// The closed set of samplers.
class Sampler {
    using Variant = std::variant<IndependentSampler, StratifiedSampler, HaltonSampler, SobolSampler,
                                 PaddedSobolSampler, ZSobolSampler, PMJ02BNSampler, MLTSampler>;

  public:
    template <typename S>
        requires std::is_constructible_v<Variant, S> && (!std::is_same_v<std::remove_cvref_t<S>, Sampler>)
    Sampler(S &&s) : sampler(std::forward<S>(s)) {}

    int SamplesPerPixel() const {
        return std::visit([](const auto &s) { return s.SamplesPerPixel(); }, sampler);
    }
    void StartPixelSample(Point2i p, int sampleIndex, int dimension = 0) {
        std::visit([&](auto &s) { s.StartPixelSample(p, sampleIndex, dimension); }, sampler);
    }
    Float Get1D() {
        return std::visit([](auto &s) { return s.Get1D(); }, sampler);
    }
    Point2f Get2D() {
        return std::visit([](auto &s) { return s.Get2D(); }, sampler);
    }
    Point2f GetPixel2D() {
        return std::visit([](auto &s) { return s.GetPixel2D(); }, sampler);
    }
    const char *Name() const {
        return std::visit([](const auto &s) { return s.Name(); }, sampler);
    }
    std::string ToString() const {
        return std::visit([](const auto &s) { return s.ToString(); }, sampler);
    }
    // The sampler as a T, or nullptr if it is another kind.
    template <typename T>
    const T *Get() const { return std::get_if<T>(&sampler); }
    template <typename T>
    T *Get() { return std::get_if<T>(&sampler); }

  private:
    Variant sampler;
};

}  // namespace pbrt
