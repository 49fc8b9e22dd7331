// Blue-noise textures (pbrt-v4's util/bluenoise.h): kNumBlueNoiseTextures tileable
// kBlueNoiseResolution^2 textures whose values are uniformly distributed and whose every
// threshold is a blue-noise pattern. Generated at build time by cmd/sampletables_gen (void and
// cluster, Ulichney 1993); each texel stores its rank.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/vecmath.h"

#include <cstdint>

namespace pbrt {

constexpr int kBlueNoiseResolution = 128;
constexpr int kNumBlueNoiseTextures = 48;

using BlueNoiseTable = uint16_t[kNumBlueNoiseTextures][kBlueNoiseResolution][kBlueNoiseResolution];

}  // namespace pbrt

// Defined in the generated source (<build>/pbrt_ext/generated/sampletables.cpp); [texture][y][x].
extern "C" const pbrt::BlueNoiseTable pbrt_ext_BlueNoiseTextures;

namespace pbrt {

// The value of texture textureIndex (modulo the count) at pixel p (tiled), in (0, 1): the
// texel's rank, centred in its 1/res^2 interval. textureIndex and p must not be negative.
inline float BlueNoise(int textureIndex, Point2i p) {
    constexpr int n = kBlueNoiseResolution * kBlueNoiseResolution;
    uint16_t rank = pbrt_ext_BlueNoiseTextures[textureIndex % kNumBlueNoiseTextures]
                                              [p.y % kBlueNoiseResolution][p.x % kBlueNoiseResolution];
    return (rank + 0.5f) / n;
}

}  // namespace pbrt
