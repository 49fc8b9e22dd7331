// CIE daylight illuminants D from the S0, S1, S2 basis (pbrt-v4's Spectra::D, src/pbrt/util/spectrum.cpp).
//
// The basis functions are CIE 015:2018's S0, S1, S2 at 300-830 nm every 5 nm (the values at odd
// multiples of 5 nm are the means of their 10 nm neighbours), transcribed by a script, not by
// hand, from pbrt-v4's CIE_S0/CIE_S1/CIE_S2 (src/pbrt/util/spectrum.cpp), checked to be 107
// values each at 300, 305, ..., 830 nm.
#include "pbrt_ext/spectra/spectrum.h"

#include <vector>

namespace pbrt {

namespace {

constexpr int kDaylightSamples = 107;
constexpr Float kDaylightLambdaMin = 300, kDaylightLambdaStep = 5;

// clang-format off
constexpr float kS0[kDaylightSamples] = {
    0.04f, 3.02f, 6.0f, 17.8f, 29.6f, 42.45f, 55.3f, 56.3f, 57.3f, 59.55f,
    61.8f, 61.65f, 61.5f, 65.15f, 68.8f, 66.1f, 63.4f, 64.6f, 65.8f, 80.3f,
    94.8f, 99.8f, 104.8f, 105.35f, 105.9f, 101.35f, 96.8f, 105.35f, 113.9f, 119.75f,
    125.6f, 125.55f, 125.5f, 123.4f, 121.3f, 121.3f, 121.3f, 117.4f, 113.5f, 113.3f,
    113.1f, 111.95f, 110.8f, 108.65f, 106.5f, 107.65f, 108.8f, 107.05f, 105.3f, 104.85f,
    104.4f, 102.2f, 100.0f, 98.0f, 96.0f, 95.55f, 95.1f, 92.1f, 89.1f, 89.8f,
    90.5f, 90.4f, 90.3f, 89.35f, 88.4f, 86.2f, 84.0f, 84.55f, 85.1f, 83.5f,
    81.9f, 82.25f, 82.6f, 83.75f, 84.9f, 83.1f, 81.3f, 76.6f, 71.9f, 73.1f,
    74.3f, 75.35f, 76.4f, 69.85f, 63.3f, 67.5f, 71.7f, 74.35f, 77.0f, 71.1f,
    65.2f, 56.45f, 47.7f, 58.15f, 68.6f, 66.8f, 65.0f, 65.5f, 66.0f, 63.5f,
    61.0f, 57.15f, 53.3f, 56.1f, 58.9f, 60.4f, 61.9f,
};
constexpr float kS1[kDaylightSamples] = {
    0.02f, 2.26f, 4.5f, 13.45f, 22.4f, 32.2f, 42.0f, 41.3f, 40.6f, 41.1f,
    41.6f, 39.8f, 38.0f, 40.2f, 42.4f, 40.45f, 38.5f, 36.75f, 35.0f, 39.2f,
    43.4f, 44.85f, 46.3f, 45.1f, 43.9f, 40.5f, 37.1f, 36.9f, 36.7f, 36.3f,
    35.9f, 34.25f, 32.6f, 30.25f, 27.9f, 26.1f, 24.3f, 22.2f, 20.1f, 18.15f,
    16.2f, 14.7f, 13.2f, 10.9f, 8.6f, 7.35f, 6.1f, 5.15f, 4.2f, 3.05f,
    1.9f, 0.95f, -0.0f, -0.8f, -1.6f, -2.55f, -3.5f, -3.5f, -3.5f, -4.65f,
    -5.8f, -6.5f, -7.2f, -7.9f, -8.6f, -9.05f, -9.5f, -10.2f, -10.9f, -10.8f,
    -10.7f, -11.35f, -12.0f, -13.0f, -14.0f, -13.8f, -13.6f, -12.8f, -12.0f, -12.65f,
    -13.3f, -13.1f, -12.9f, -11.75f, -10.6f, -11.1f, -11.6f, -11.9f, -12.2f, -11.2f,
    -10.2f, -9.0f, -7.8f, -9.5f, -11.2f, -10.8f, -10.4f, -10.5f, -10.6f, -10.15f,
    -9.7f, -9.0f, -8.3f, -8.8f, -9.3f, -9.55f, -9.8f,
};
constexpr float kS2[kDaylightSamples] = {
    0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 6.25f, 8.5f, 8.15f, 7.8f, 7.25f,
    6.7f, 6.0f, 5.3f, 5.7f, 6.1f, 4.55f, 3.0f, 2.1f, 1.2f, 0.05f,
    -1.1f, -0.8f, -0.5f, -0.6f, -0.7f, -0.95f, -1.2f, -1.9f, -2.6f, -2.75f,
    -2.9f, -2.85f, -2.8f, -2.7f, -2.6f, -2.6f, -2.6f, -2.2f, -1.8f, -1.65f,
    -1.5f, -1.4f, -1.3f, -1.25f, -1.2f, -1.1f, -1.0f, -0.75f, -0.5f, -0.4f,
    -0.3f, -0.15f, 0.0f, 0.1f, 0.2f, 0.35f, 0.5f, 1.3f, 2.1f, 2.65f,
    3.2f, 3.65f, 4.1f, 4.4f, 4.7f, 4.9f, 5.1f, 5.9f, 6.7f, 7.0f,
    7.3f, 7.95f, 8.6f, 9.2f, 9.8f, 10.0f, 10.2f, 9.25f, 8.3f, 8.95f,
    9.6f, 9.05f, 8.5f, 7.75f, 7.0f, 7.3f, 7.6f, 7.8f, 8.0f, 7.35f,
    6.7f, 5.95f, 5.2f, 6.3f, 7.4f, 7.1f, 6.8f, 6.9f, 7.0f, 6.7f,
    6.4f, 5.95f, 5.5f, 5.8f, 6.1f, 6.3f, 6.5f,
};
// clang-format on

}  // namespace

// As pbrt-v4: the temperature is first rescaled by 1.4388 / 1.4380 (the CIE's D series was defined
// with the old second radiation constant c2 = 1.4380e-2 m K; "D65" is 6504 K under today's
// c2 = 1.4388e-2), so D(6500) is D65. Below 4000 K, where the CIE does not define D, it is the
// blackbody at that temperature (peak 1). Otherwise the chromaticity on the daylight locus gives
// the weights M1, M2 of S1, S2 (CIE 015:2018), and the result is (S0 + M1 S1 + M2 S2) / 100:
// about 1 at 560 nm, NOT scaled to luminance 1 (pbrt-v4 does not scale it; its only user,
// PixelSensor, depends on its shape alone).
Spectrum Spectra::D(Float T) {
    Float cct = T * 1.4388f / 1.4380f;
    if (cct < 4000) return Spectrum::DenselySampled(Spectrum(BlackbodySpectrum(cct)));

    // CIE 015:2018: x from the CCT, then y on the daylight locus.
    double t = cct, x;
    if (t <= 7000)
        x = -4.6070e9 / (t * t * t) + 2.9678e6 / (t * t) + 0.09911e3 / t + 0.244063;
    else
        x = -2.0064e9 / (t * t * t) + 1.9018e6 / (t * t) + 0.24748e3 / t + 0.237040;
    double y = -3 * x * x + 2.870 * x - 0.275;

    // The basis weights (CIE 015:2018), unrounded as in pbrt-v4.
    double M = 0.0241 + 0.2562 * x - 0.7341 * y;
    double M1 = (-1.3515 - 1.7703 * x + 5.9114 * y) / M;
    double M2 = (0.0300 - 31.4424 * x + 30.0717 * y) / M;

    std::vector<Float> lambdas(kDaylightSamples), values(kDaylightSamples);
    for (int i = 0; i < kDaylightSamples; ++i) {
        lambdas[size_t(i)] = kDaylightLambdaMin + kDaylightLambdaStep * Float(i);
        values[size_t(i)] = Float((kS0[i] + kS1[i] * M1 + kS2[i] * M2) * 0.01);
    }
    return Spectrum::DenselySampled(Spectrum::PiecewiseLinear(std::move(lambdas), std::move(values)));
}

}  // namespace pbrt
