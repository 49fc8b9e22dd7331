// Goniometric and projection lights (imagepointlights.h): radiance at test points against
// hand-computed values, and their power.
#include "pbrt_ext/lights/imagepointlights.h"

#include "pbrt_ext/spectra/colorspace.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pbrt {
namespace {

const SampledWavelengths kLambda = SampledWavelengths::SampleUniform(0, 400, 800);  // 400..700 nm

LightSampleContext At(Point3f p) { return LightSampleContext(p, Normal3f(0, 0, 1), Normal3f(0, 0, 1)); }

// An 8x8 goniometric diagram whose texel (x, y) is 1 + x + 8 y (grey).
Image Diagram() {
    Image image(Point2i(8, 8));
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, Float(1 + x + 8 * y));
    return image;
}

// The equal-area octahedral square puts light-space +z at its centre, the equator on the
// diamond through the edges' midpoints (+x at (1, 1/2), +y at (1/2, 1)) and -z at the corners.
// With a light at (1, 2, 3) and identity transform, the point d away along each of those
// directions receives texel / d^2 at scale 2.
TEST(GoniometricLight, RadianceIsTheDiagramsTexelOverDistanceSquared) {
    GoniometricLight light(Translate(Vector3f(1, 2, 3)), Spectrum(1.f), 2, Diagram());
    struct Case {
        Vector3f dir;
        int texelX, texelY;
    } cases[] = {{{0, 0, 1}, 4, 4},           // the centre texel (4, 4): the upper-right one of the four
                 {{1, 0, 0.01f}, 7, 4},       // +x, just above the equator: the right edge's middle
                 {{0, 1, 0.01f}, 4, 7},       // +y: the bottom edge's middle
                 {{0.01f, 0.01f, -1}, 7, 7}};  // -z near its (1, 1) corner
    for (const Case &c : cases) {
        Float d = 2.5f;
        Point3f p = Point3f(1, 2, 3) + d * Normalize(c.dir);
        pstd::optional<LightLiSample> ls = light.SampleLi(At(p), Point2f(0.5f, 0.5f), kLambda);
        ASSERT_TRUE(ls.has_value());
        Float expected = 2 * Float(1 + c.texelX + 8 * c.texelY) / Sqr(d);
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(ls->L[i], expected, 1e-4f * expected) << c.dir.x << c.dir.y << c.dir.z;
        EXPECT_NEAR(Dot(ls->wi, -Normalize(c.dir)), 1, 1e-6f);
        EXPECT_EQ(ls->pdf, 1);
    }
    // Power: 4 pi times the scale times the diagram's mean, 32.5.
    EXPECT_NEAR(light.Phi(kLambda)[0], 4 * Pi * 2 * 32.5f, 1e-3f);
}

// A 4x2 slide (aspect 2) at fov 90: light-space direction (x, y, 1) hits the screen at (x, y),
// the image spans [-2, 2] x [-1, 1], so the texel is (floor((x + 2)), floor((y + 1))) with row 0
// at y = -1 (the creator flips y so that row 0 is up).
TEST(ProjectionLight, RadianceIsTheSlidesTexelOverDistanceSquared) {
    Image slide(Point2i(4, 2));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) {
            slide.SetChannel(Point2i(x, y), 0, 0.1f * Float(1 + x));
            slide.SetChannel(Point2i(x, y), 1, 0.5f * Float(y));
            slide.SetChannel(Point2i(x, y), 2, 0.2f);
        }
    const RGBColorSpace &cs = RGBColorSpace::sRGB();
    ProjectionLight light(Transform(), slide, &cs, 3, 90);
    struct Case {
        Float x, y;
        int texelX, texelY;
    } cases[] = {{1.5f, -0.5f, 3, 0}, {-1.7f, 0.4f, 0, 1}, {0.2f, 0.9f, 2, 1}};
    for (const Case &c : cases) {
        Vector3f w(c.x, c.y, 1);
        Float d = 1.7f;
        Point3f p = Point3f(0, 0, 0) + d * Normalize(w);
        pstd::optional<LightLiSample> ls = light.SampleLi(At(p), Point2f(0.5f, 0.5f), kLambda);
        ASSERT_TRUE(ls.has_value());
        RGB rgb = slide.GetChannels(Point2i(c.texelX, c.texelY));
        SampledSpectrum expected = 3 * RGBIlluminantSpectrum(cs, rgb).Sample(kLambda) / Sqr(d);
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(ls->L[i], expected[i], 1e-4f * expected[i]) << c.x << " " << c.y;
    }
    // Behind the projector and outside the slide: nothing.
    EXPECT_FALSE(light.SampleLi(At(Point3f(0.1f, 0, -1)), Point2f(), kLambda).has_value());
    EXPECT_FALSE(light.SampleLi(At(Point3f(2.5f, 0, 1)), Point2f(), kLambda).has_value());
}

// A white slide's power is its illuminant times the solid angle of the screen rectangle
// [-a, a] x [-b, b] at distance 1: 4 asin(a b / sqrt((1 + a^2)(1 + b^2))) (a = 2, b = 1 at
// fov 90 and aspect 2); the texel-centre sum over 128x64 texels is within 1e-3 of it.
TEST(ProjectionLight, PowerIsTheSolidAngleOfTheSlide) {
    Image white(Point2i(128, 64));
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 128; ++x)
            for (int c = 0; c < 3; ++c) white.SetChannel(Point2i(x, y), c, 1);
    const RGBColorSpace &cs = RGBColorSpace::sRGB();
    ProjectionLight light(Transform(), white, &cs, 1, 90);
    Float omega = 4 * std::asin(2 / std::sqrt(5.f * 2));
    SampledSpectrum illum = RGBIlluminantSpectrum(cs, RGB(1, 1, 1)).Sample(kLambda);
    SampledSpectrum phi = light.Phi(kLambda);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(phi[i] / illum[i], omega, 1e-3f * omega);
}

}  // namespace
}  // namespace pbrt
