#include "pbrt_ext/textures/proceduraltextures.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/noise.h"

#include <algorithm>
#include <cmath>

namespace pbrt {

Float FBmTexture::Evaluate(const TextureEvalContext &ctx) const {
    TexCoord3D c = mapping.Map(ctx);
    return FBm(c.p, c.dpdx, c.dpdy, omega, octaves);
}

Float WrinkledTexture::Evaluate(const TextureEvalContext &ctx) const {
    TexCoord3D c = mapping.Map(ctx);
    return Turbulence(c.p, c.dpdx, c.dpdy, omega, octaves);
}

Float WindyTexture::Evaluate(const TextureEvalContext &ctx) const {
    TexCoord3D c = mapping.Map(ctx);
    Float windStrength = FBm(.1f * c.p, .1f * c.dpdx, .1f * c.dpdy, .5f, 3);
    Float waveHeight = FBm(c.p, c.dpdx, c.dpdy, .5f, 6);
    return std::abs(windStrength) * waveHeight;
}

namespace {

// A cubic Bezier segment of RGB control points, by de Casteljau.
RGB CubicBezier(const RGB *cp, Float u) {
    RGB a[3] = {(1 - u) * cp[0] + u * cp[1], (1 - u) * cp[1] + u * cp[2], (1 - u) * cp[2] + u * cp[3]};
    RGB b[2] = {(1 - u) * a[0] + u * a[1], (1 - u) * a[1] + u * a[2]};
    return (1 - u) * b[0] + u * b[1];
}

}  // namespace

SampledSpectrum MarbleTexture::Evaluate(const TextureEvalContext &ctx, const SampledWavelengths &lambda) const {
    TexCoord3D c = mapping.Map(ctx);
    Point3f p = scale * c.p;
    Float marble = p.y + variation * FBm(p, scale * c.dpdx, scale * c.dpdy, omega, octaves);
    Float t = .5f + .5f * std::sin(marble);
    // pbrt-v4's marble colours, segments of a cubic spline through them.
    static const RGB colors[] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                                 {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                                 {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
    constexpr int nSeg = int(std::size(colors)) - 3;
    int first = std::min(int(std::floor(t * nSeg)), nSeg - 1);
    RGB rgb = 1.5f * CubicBezier(colors + first, t * nSeg - Float(first));
    return RGBAlbedoSpectrum(RGBColorSpace::sRGB(), rgb).Sample(lambda);
}

bool InsidePolkaDot(Point2f st) {
    int sCell = int(std::floor(st[0] + .5f)), tCell = int(std::floor(st[1] + .5f));
    if (Noise(sCell + .5f, tCell + .5f, .5f) <= 0) return false;
    constexpr Float radius = .35f, maxShift = 0.5f - radius;
    Float sCenter = sCell + maxShift * Noise(sCell + 1.5f, tCell + 2.8f, .5f);
    Float tCenter = tCell + maxShift * Noise(sCell + 4.5f, tCell + 9.8f, .5f);
    return Sqr(st[0] - sCenter) + Sqr(st[1] - tCenter) < Sqr(radius);
}

}  // namespace pbrt
