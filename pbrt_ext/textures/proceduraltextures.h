// Procedural textures (pbrt-v4's bilerp, fbm, wrinkled, windy and marble): patterns computed at
// the shading point, made of pbrt-v4's Perlin noise (util/noise.h) so that they match pbrt-v4's
// at every point. The noise textures drop the octaves finer than the pixel's footprint.
#pragma once

#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/textures/texturemappings.h"
#include "pbrt_ext/util/spectrum.h"

#include <array>

namespace pbrt {

// The weights of v00, v10, v01, v11 at st (bilinear over the unit square, unclamped).
inline std::array<Float, 4> BilerpWeights(Point2f st) {
    Float s = st[0], t = st[1];
    return {(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t};
}

// v00 at (s, t) = (0, 0), v10 at (1, 0), v01 at (0, 1), v11 at (1, 1), bilinear between.
struct FloatBilerpTexture {
    TextureMapping2D mapping;
    Float v00 = 0, v01 = 1, v10 = 0, v11 = 1;
    Float Evaluate(const TextureEvalContext &ctx) const {
        std::array<Float, 4> w = BilerpWeights(mapping.Map(ctx).st);
        return w[0] * v00 + w[1] * v10 + w[2] * v01 + w[3] * v11;
    }
};

struct SpectrumBilerpTexture {
    TextureMapping2D mapping;
    Spectrum v00, v01, v10, v11;
    SampledSpectrum Evaluate(const TextureEvalContext &ctx, const SampledWavelengths &lambda) const {
        std::array<Float, 4> w = BilerpWeights(mapping.Map(ctx).st);
        return w[0] * v00.Sample(lambda) + w[1] * v10.Sample(lambda) + w[2] * v01.Sample(lambda) +
               w[3] * v11.Sample(lambda);
    }
};

// Fractional Brownian motion in texture space ("fbm": octaves, roughness = omega).
struct FBmTexture {
    TextureMapping3D mapping;
    int octaves = 8;
    Float omega = 0.5f;
    Float Evaluate(const TextureEvalContext &ctx) const;
};

// Turbulence, the sum of |noise| ("wrinkled").
struct WrinkledTexture {
    TextureMapping3D mapping;
    int octaves = 8;
    Float omega = 0.5f;
    Float Evaluate(const TextureEvalContext &ctx) const;
};

// Waves whose height is FBm scaled by a slowly varying wind strength ("windy").
struct WindyTexture {
    TextureMapping3D mapping;
    Float Evaluate(const TextureEvalContext &ctx) const;
};

// Veins: a sine of y perturbed by FBm, coloured through pbrt-v4's marble spline ("marble"; an
// albedo in sRGB).
struct MarbleTexture {
    TextureMapping3D mapping;
    int octaves = 8;
    Float omega = 0.5f, scale = 1, variation = 0.2f;
    SampledSpectrum Evaluate(const TextureEvalContext &ctx, const SampledWavelengths &lambda) const;
};

// Whether st lies in a polka dot: a cell of the unit lattice holds one where the noise says so,
// of radius 0.35, shifted by the noise (pbrt-v4's InsidePolkaDot).
bool InsidePolkaDot(Point2f st);

}  // namespace pbrt
