// The pmj02bn point sets (pbrt-v4's util/pmj02tables.h): kPMJ02bnSets progressive
// multi-jittered (0,2) sequences with blue-noise selection, kPMJ02bnSamples points each, every
// prefix of 2^m points a (0, m, 2)-net. Generated at build time by cmd/sampletables_gen
// (Christensen, Kensler and Kilpatrick 2018), in 32-bit fixed point.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/vecmath.h"

#include <cstdint>

namespace pbrt {

constexpr int kPMJ02bnSets = 5;
constexpr int kPMJ02bnSamples = 65536;

using PMJ02bnTable = uint32_t[kPMJ02bnSets][kPMJ02bnSamples][2];

}  // namespace pbrt

// Defined in the generated source (<build>/pbrt_ext/generated/sampletables.cpp).
extern "C" const pbrt::PMJ02bnTable pbrt_ext_PMJ02bnSamples;

namespace pbrt {

// Point sampleIndex of set setIndex (taken modulo the set count), in double: the pixel
// samples are sorted into pixels by their leading bits, which a float would round away.
inline Point2<double> GetPMJ02BNSample(int setIndex, int sampleIndex) {
    const uint32_t *p = pbrt_ext_PMJ02bnSamples[setIndex % kPMJ02bnSets][sampleIndex];
    return {p[0] * 0x1p-32, p[1] * 0x1p-32};
}

}  // namespace pbrt
