// Sample generators for the pixel integrals (pbrt-v4's samplers.h, reduced to the independent,
// stratified and zsobol samplers).
//
// Every value is a pure function of (pixel, sample index, dimension, seed): StartPixelSample
// resets the state, so an image does not depend on which thread renders which pixel, or in
// which order. Values lie in [0, 1). A sampler is a small value type; each thread uses its own
// copy.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace pbrt {

// ---- Bit manipulation (pbrt-v4's util/lowdiscrepancy.h); hashing is in util/hash.h ----------

PBRT_CPU_GPU inline uint32_t ReverseBits32(uint32_t n) {
    n = (n << 16) | (n >> 16);
    n = ((n & 0x00ff00ffu) << 8) | ((n & 0xff00ff00u) >> 8);
    n = ((n & 0x0f0f0f0fu) << 4) | ((n & 0xf0f0f0f0u) >> 4);
    n = ((n & 0x33333333u) << 2) | ((n & 0xccccccccu) >> 2);
    n = ((n & 0x55555555u) << 1) | ((n & 0xaaaaaaaau) >> 1);
    return n;
}

// Spreads the low 32 bits of x to the even bit positions.
PBRT_CPU_GPU inline uint64_t LeftShift2(uint64_t x) {
    x &= 0xffffffff;
    x = (x ^ (x << 16)) & 0x0000ffff0000ffffULL;
    x = (x ^ (x << 8)) & 0x00ff00ff00ff00ffULL;
    x = (x ^ (x << 4)) & 0x0f0f0f0f0f0f0f0fULL;
    x = (x ^ (x << 2)) & 0x3333333333333333ULL;
    x = (x ^ (x << 1)) & 0x5555555555555555ULL;
    return x;
}
// The Morton (Z-order) code of (x, y): x in the even bits, y in the odd ones.
PBRT_CPU_GPU inline uint64_t EncodeMorton2(uint32_t x, uint32_t y) {
    return (LeftShift2(y) << 1) | LeftShift2(x);
}

// Element i of a pseudo-random permutation of [0, l) selected by p, without storing it
// (Kensler 2013, "Correlated Multi-Jittered Sampling"): a bijective hash on the next power of
// two, cycle-walked until it lands inside [0, l).
PBRT_CPU_GPU inline int PermutationElement(uint32_t i, uint32_t l, uint32_t p) {
    uint32_t w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    do {
        i ^= p;
        i *= 0xe170893d;
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i *= 0x0929eb3f;
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i *= 1 | p >> 27;
        i *= 0x6935fa69;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3;
        i ^= (i & w) >> 2;
        i *= 0xc860a3df;
        i &= w;
        i ^= i >> 5;
    } while (i >= l);
    return int((i + p) % l);
}

// ---- Sobol' points and their scrambles ----------------------------------------------------

// How the Sobol' digits are randomized (pbrt-v4's RandomizeStrategy).
enum class RandomizeStrategy { None, PermuteDigits, FastOwen, Owen };

// The 32-bit Sobol' value of index a in dimension 0 or 1, the only two the zsobol sampler
// uses. Their generator matrices follow from the primitive polynomials x and x + 1: column k
// of dimension 0 is 2^(31-k) (the van der Corput sequence); dimension 1's columns obey
// c_k = c_(k-1) ^ (c_(k-1) >> 1) from c_0 = 2^31 (Pascal's triangle mod 2), so no table is needed.
PBRT_CPU_GPU inline uint32_t SobolBits(uint64_t a, int dimension) {
    uint32_t v = 0, column = 0x80000000u;
    for (; a != 0; a >>= 1) {
        if (a & 1) v ^= column;
        column = (dimension == 0) ? (column >> 1) : (column ^ (column >> 1));
    }
    return v;
}

// Nested uniform (Owen) scrambling: each bit is flipped by a hash of the bits above it, which
// keeps every elementary interval's point count (the net property) while decorrelating.
PBRT_CPU_GPU inline uint32_t OwenScramble(uint32_t v, uint32_t seed) {
    if (seed & 1) v ^= 1u << 31;
    for (int b = 1; b < 32; ++b) {
        uint32_t mask = (~0u) << (32 - b);
        if (uint32_t(MixBits((v & mask) ^ seed)) & (1u << b)) v ^= 1u << (31 - b);
    }
    return v;
}
// The Laine-Karras style approximation of Owen scrambling (Vegdahl's constants, as pbrt-v4's
// FastOwenScrambler): a hash in reversed bit order, where each bit only mixes into the ones
// below it.
PBRT_CPU_GPU inline uint32_t FastOwenScramble(uint32_t v, uint32_t seed) {
    v = ReverseBits32(v);
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return ReverseBits32(v);
}

PBRT_CPU_GPU inline Float SobolSample(uint64_t a, int dimension, RandomizeStrategy randomize,
                                      uint32_t seed) {
    uint32_t v = SobolBits(a, dimension);
    switch (randomize) {
    case RandomizeStrategy::PermuteDigits:
        v ^= seed;
        break;
    case RandomizeStrategy::FastOwen:
        v = FastOwenScramble(v, seed);
        break;
    case RandomizeStrategy::Owen:
        v = OwenScramble(v, seed);
        break;
    case RandomizeStrategy::None:
        break;
    }
    return std::min(v * 0x1p-32f, OneMinusEpsilon);
}

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
    StratifiedSampler(int xPixelSamples, int yPixelSamples, bool jitter, int seed = 0)
        : xPixelSamples(xPixelSamples), yPixelSamples(yPixelSamples), seed(seed), jitter(jitter) {
        if (xPixelSamples < 1 || yPixelSamples < 1)
            throw std::runtime_error("stratified sampler: xsamples and ysamples must be positive");
    }

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

// Ahmed and Wonka's screen-space blue-noise Sobol' sampler (SIGGRAPH Asia 2020), as pbrt-v4:
// pixels are ordered along a Morton curve, and the base-4 digits of (Morton index, sample index)
// are shuffled by per-level hashed permutations before indexing a scrambled 2D Sobol' sequence;
// each dimension (or pair) gets its own shuffle and scramble. Neighbouring pixels thereby get
// well-distributed, decorrelated subsets of one low-discrepancy sequence.
class ZSobolSampler {
  public:
    // A samplesPerPixel that is not a power of two is rounded up (with a warning), as the
    // construction needs whole base-2 digits. Throws std::runtime_error for a non-positive
    // count or resolution.
    ZSobolSampler(int samplesPerPixel, Point2i fullResolution,
                  RandomizeStrategy randomize = RandomizeStrategy::FastOwen, int seed = 0);

    static constexpr const char *Name() { return "zsobol"; }
    PBRT_CPU_GPU int SamplesPerPixel() const { return 1 << log2SamplesPerPixel; }

    PBRT_CPU_GPU void StartPixelSample(Point2i p, int index, int dim = 0) {
        dimension = dim;
        mortonIndex = (EncodeMorton2(uint32_t(p.x), uint32_t(p.y)) << log2SamplesPerPixel) | uint64_t(index);
    }

    PBRT_CPU_GPU Float Get1D() {
        uint64_t sampleIndex = GetSampleIndex();
        ++dimension;
        uint32_t sampleHash = uint32_t(Hash(dimension, seed));
        return SobolSample(sampleIndex, 0, randomize, sampleHash);
    }
    PBRT_CPU_GPU Point2f Get2D() {
        uint64_t sampleIndex = GetSampleIndex();
        dimension += 2;
        uint64_t bits = Hash(dimension, seed);
        return {SobolSample(sampleIndex, 0, randomize, uint32_t(bits)),
                SobolSample(sampleIndex, 1, randomize, uint32_t(bits >> 32))};
    }
    PBRT_CPU_GPU Point2f GetPixel2D() { return Get2D(); }

    std::string ToString() const;

  private:
    // Digit d of a 4-element permutation chosen by index 0..23: the permutations are generated
    // by three swaps of the identity (positions 0, 1, 2 with later ones), enumerating all 24.
    PBRT_CPU_GPU static int PermuteDigit(int permutation, int digit) {
        int perm[4] = {0, 1, 2, 3};
        int swaps[3] = {permutation / 6, 1 + (permutation / 2) % 3, 2 + permutation % 2};
        for (int i = 0; i < 3; ++i) {
            int t = perm[i];
            perm[i] = perm[swaps[i]];
            perm[swaps[i]] = t;
        }
        return perm[digit];
    }

    PBRT_CPU_GPU uint64_t GetSampleIndex() const {
        uint64_t sampleIndex = 0;
        // With an odd log2(spp) the last base-4 digit is half a digit: one base-2 digit.
        bool pow2Samples = log2SamplesPerPixel & 1;
        int lastDigit = pow2Samples ? 1 : 0;
        for (int i = nBase4Digits - 1; i >= lastDigit; --i) {
            int digitShift = 2 * i - (pow2Samples ? 1 : 0);
            int digit = int((mortonIndex >> digitShift) & 3);
            uint64_t higherDigits = mortonIndex >> (digitShift + 2);
            int p = int((MixBits(higherDigits ^ (0x55555555u * uint32_t(dimension))) >> 24) % 24);
            sampleIndex |= uint64_t(PermuteDigit(p, digit)) << digitShift;
        }
        if (pow2Samples) {
            int digit = int(mortonIndex & 1);
            sampleIndex |= digit ^ (MixBits((mortonIndex >> 1) ^ (0x55555555u * uint32_t(dimension))) & 1);
        }
        return sampleIndex;
    }

    RandomizeStrategy randomize;
    int seed, log2SamplesPerPixel, nBase4Digits;
    uint64_t mortonIndex = 0;
    int dimension = 0;
};

// The closed set of samplers.
class Sampler {
    using Variant = std::variant<IndependentSampler, StratifiedSampler, ZSobolSampler>;

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

  private:
    Variant sampler;
};

}  // namespace pbrt
