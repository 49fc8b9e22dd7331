// pbrt_ext: the PCG32 random number generator (O'Neill 2014, pcg-random.org), with pbrt-v4's
// RNG interface (util/rng.h): independent sequences selected by index, and O(log n) skipping.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/math.h"

#include <algorithm>
#include <cstdint>

namespace pbrt {

class RNG {
  public:
    PBRT_CPU_GPU RNG() : state(DefaultState), inc(DefaultStream) {}
    PBRT_CPU_GPU RNG(uint64_t seqIndex, uint64_t offset) { SetSequence(seqIndex, offset); }
    PBRT_CPU_GPU explicit RNG(uint64_t seqIndex) { SetSequence(seqIndex); }

    // Each sequence index selects a different LCG increment, i.e. a different stream; offset
    // (the seed) selects the starting point within it.
    PBRT_CPU_GPU void SetSequence(uint64_t seqIndex, uint64_t offset);
    // Nearby sequence indices would otherwise also start from nearby seeds.
    PBRT_CPU_GPU void SetSequence(uint64_t seqIndex) { SetSequence(seqIndex, MixBits(seqIndex)); }

    // Float: uniform in [0, 1), never 1. double likewise. Unsigned: uniform over all values.
    template <typename T>
    PBRT_CPU_GPU T Uniform();

    // Moves the sequence delta steps forward (backward if negative) in O(log |delta|): the
    // composition of k LCG steps x -> a x + c is again affine, and is built by squaring.
    PBRT_CPU_GPU void Advance(int64_t idelta) {
        uint64_t curMult = Multiplier, curPlus = inc, accMult = 1u, accPlus = 0u;
        for (uint64_t delta = uint64_t(idelta); delta > 0; delta /= 2) {
            if (delta & 1) {
                accMult *= curMult;
                accPlus = accPlus * curMult + curPlus;
            }
            curPlus = (curMult + 1) * curPlus;
            curMult *= curMult;
        }
        state = accMult * state + accPlus;
    }

  private:
    static constexpr uint64_t DefaultState = 0x853c49e6748fea9bULL;
    static constexpr uint64_t DefaultStream = 0xda3e39cb94b95bdbULL;
    static constexpr uint64_t Multiplier = 0x5851f42d4c957f2dULL;

    uint64_t state, inc;
};

// PCG's XSH-RR output: a 64-bit LCG step, then a xorshift of the old state's high bits rotated
// by its top five bits.
template <>
PBRT_CPU_GPU inline uint32_t RNG::Uniform<uint32_t>() {
    uint64_t oldState = state;
    state = oldState * Multiplier + inc;
    uint32_t xorShifted = uint32_t(((oldState >> 18u) ^ oldState) >> 27u);
    uint32_t rot = uint32_t(oldState >> 59u);
    return (xorShifted >> rot) | (xorShifted << ((~rot + 1u) & 31));
}
template <>
PBRT_CPU_GPU inline uint64_t RNG::Uniform<uint64_t>() {
    uint64_t high = Uniform<uint32_t>(), low = Uniform<uint32_t>();
    return (high << 32) | low;
}
// 2^-32 u can round up to 1 for u near 2^32; clamping keeps the interval half-open.
template <>
PBRT_CPU_GPU inline float RNG::Uniform<float>() {
    return std::min<float>(OneMinusEpsilon, float(Uniform<uint32_t>()) * 0x1p-32f);
}
template <>
PBRT_CPU_GPU inline double RNG::Uniform<double>() {
    return std::min<double>(0x1.fffffffffffffp-1, double(Uniform<uint64_t>()) * 0x1p-64);
}

// Out of line: it uses Uniform<uint32_t>, whose specialization must come first.
PBRT_CPU_GPU inline void RNG::SetSequence(uint64_t seqIndex, uint64_t offset) {
    state = 0u;
    inc = (seqIndex << 1u) | 1u;  // the increment must be odd for a full period
    Uniform<uint32_t>();
    state += offset;
    Uniform<uint32_t>();
}

}  // namespace pbrt
