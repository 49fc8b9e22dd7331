// pbrt_ext: the CIE 1931 standard observer and illuminant D65 as tabulated data (the part of
// pbrt-v4's util/spectrum.cpp CIE tables this renderer needs), shared by the spectra, the
// RGB-to-spectrum table and its generator, cmd/rgb2spec_opt, so that all of them see one observer.
//
// Range 380-780 nm (pbrt-v4 tabulates 360-830 nm; the matching functions outside this range add
// less than 1e-4 of Y). Linearly interpolated between the 5 nm samples and zero outside them, as
// pbrt-v4's PiecewiseLinearSpectrum.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"

namespace pbrt {

// CIE 1931 2-degree colour matching functions (xbar, ybar, zbar) and CIE standard illuminant D65
// (relative, 100 at 560 nm), 380-780 nm every 5 nm: the CIE data tables
// https://cie.co.at/datatable/cie-1931-colour-matching-functions-2-degree-observer and
// https://cie.co.at/datatable/cie-standard-illuminant-d65 (CIE 015:2018), transcribed from the
// copy in aschet/olfarve, py/olfarve.py.
struct CIESample {
    float x, y, z, d65;
};
PBRT_CONST Float kCIELambdaMin = 380, kCIELambdaMax = 780, kCIELambdaStep = 5;
PBRT_CONST CIESample kCIE[] = {
    {0.001368, 3.9e-05, 0.006450001, 49.9755},  // 380 nm
    {0.002236, 6.4e-05, 0.01054999, 52.3118},
    {0.004243, 0.00012, 0.02005001, 54.6482},
    {0.00765, 0.000217, 0.03621, 68.7015},
    {0.01431, 0.000396, 0.06785001, 82.7549},
    {0.02319, 0.00064, 0.1102, 87.1204},
    {0.04351, 0.00121, 0.2074, 91.486},
    {0.07763, 0.00218, 0.3713, 92.4589},
    {0.13438, 0.004, 0.6456, 93.4318},
    {0.21477, 0.0073, 1.03905, 90.057},
    {0.2839, 0.0116, 1.3856, 86.6823},  // 430 nm
    {0.3285, 0.01684, 1.62296, 95.7736},
    {0.34828, 0.023, 1.74706, 104.865},
    {0.34806, 0.0298, 1.7826, 110.936},
    {0.3362, 0.038, 1.77211, 117.008},
    {0.3187, 0.048, 1.7441, 117.41},
    {0.2908, 0.06, 1.6692, 117.812},
    {0.2511, 0.0739, 1.5281, 116.336},
    {0.19536, 0.09098, 1.28764, 114.861},
    {0.1421, 0.1126, 1.0419, 115.392},
    {0.09564, 0.13902, 0.8129501, 115.923},  // 480 nm
    {0.05795001, 0.1693, 0.6162, 112.367},
    {0.03201, 0.20802, 0.46518, 108.811},
    {0.0147, 0.2586, 0.3533, 109.082},
    {0.0049, 0.323, 0.272, 109.354},
    {0.0024, 0.4073, 0.2123, 108.578},
    {0.0093, 0.503, 0.1582, 107.802},
    {0.0291, 0.6082, 0.1117, 106.296},
    {0.06327, 0.71, 0.07824999, 104.79},
    {0.1096, 0.7932, 0.05725001, 106.239},
    {0.1655, 0.862, 0.04216, 107.689},  // 530 nm
    {0.2257499, 0.9148501, 0.02984, 106.047},
    {0.2904, 0.954, 0.0203, 104.405},
    {0.3597, 0.9803, 0.0134, 104.225},
    {0.4334499, 0.9949501, 0.008749999, 104.046},
    {0.5120501, 1, 0.005749999, 102.023},
    {0.5945, 0.995, 0.0039, 100},
    {0.6784, 0.9786, 0.002749999, 98.1671},
    {0.7621, 0.952, 0.0021, 96.3342},
    {0.8425, 0.9154, 0.0018, 96.0611},
    {0.9163, 0.87, 0.001650001, 95.788},  // 580 nm
    {0.9786, 0.8163, 0.0014, 92.2368},
    {1.0263, 0.757, 0.0011, 88.6856},
    {1.0567, 0.6949, 0.001, 89.3459},
    {1.0622, 0.631, 0.0008, 90.0062},
    {1.0456, 0.5668, 0.0006, 89.8026},
    {1.0026, 0.503, 0.00034, 89.5991},
    {0.9384, 0.4412, 0.00024, 88.6489},
    {0.8544499, 0.381, 0.00019, 87.6987},
    {0.7514, 0.321, 0.0001, 85.4936},
    {0.6424, 0.265, 4.999999e-05, 83.2886},  // 630 nm
    {0.5419, 0.217, 3e-05, 83.4939},
    {0.4479, 0.175, 2e-05, 83.6992},
    {0.3608, 0.1382, 1e-05, 81.863},
    {0.2835, 0.107, 0, 80.0268},
    {0.2187, 0.0816, 0, 80.1207},
    {0.1649, 0.061, 0, 80.2146},
    {0.1212, 0.04458, 0, 81.2462},
    {0.0874, 0.032, 0, 82.2778},
    {0.0636, 0.0232, 0, 80.281},
    {0.04677, 0.017, 0, 78.2842},  // 680 nm
    {0.0329, 0.01192, 0, 74.0027},
    {0.0227, 0.00821, 0, 69.7213},
    {0.01584, 0.005723, 0, 70.6652},
    {0.01135916, 0.004102, 0, 71.6091},
    {0.008110916, 0.002929, 0, 72.979},
    {0.005790346, 0.002091, 0, 74.349},
    {0.004109457, 0.001484, 0, 67.9765},
    {0.002899327, 0.001047, 0, 61.604},
    {0.00204919, 0.00074, 0, 65.7448},
    {0.001439971, 0.00052, 0, 69.8856},  // 730 nm
    {0.0009999493, 0.0003611, 0, 72.4863},
    {0.0006900786, 0.0002492, 0, 75.087},
    {0.0004760213, 0.0001719, 0, 69.3398},
    {0.0003323011, 0.00012, 0, 63.5927},
    {0.0002348261, 8.48e-05, 0, 55.0054},
    {0.0001661505, 6e-05, 0, 46.4182},
    {0.000117413, 4.24e-05, 0, 56.6118},
    {8.307527e-05, 3e-05, 0, 66.8054},
    {5.870652e-05, 2.12e-05, 0, 65.0941},
    {4.150994e-05, 1.499e-05, 0, 63.3828},  // 780 nm
};
PBRT_CONST int kCIESamples = int(sizeof(kCIE) / sizeof(kCIE[0]));
static_assert(kCIESamples == 81 && kCIELambdaMin + (kCIESamples - 1) * kCIELambdaStep == kCIELambdaMax);

// The table linearly interpolated at lambda (nm); zero outside [380, 780] nm (and for NaN).
PBRT_CPU_GPU constexpr CIESample CIEAt(Float lambda) {
    Float t = (lambda - kCIELambdaMin) / kCIELambdaStep;
    if (!(t >= 0) || t > kCIESamples - 1) return {0, 0, 0, 0};
    int i = int(t) < kCIESamples - 1 ? int(t) : kCIESamples - 2;
    Float f = t - Float(i);
    const CIESample &a = kCIE[i], &b = kCIE[i + 1];
    auto lerp = [f](float u, float v) { return float((1 - f) * u + f * v); };
    return {lerp(a.x, b.x), lerp(a.y, b.y), lerp(a.z, b.z), lerp(a.d65, b.d65)};
}

namespace detail {
// Sum over lambda = 380, 381, ..., 780 nm of CIEAt(lambda).y, times D65 if weighted.
constexpr double SumCIEY(bool weighted) {
    double sum = 0;
    for (int lambda = 380; lambda <= 780; ++lambda) {
        CIESample c = CIEAt(Float(lambda));
        sum += double(c.y) * (weighted ? double(c.d65) : 1.0);
    }
    return sum;
}
}  // namespace detail

// pbrt-v4's CIE_Y_integral: ybar summed at 1 nm steps over the table's range (380-780 nm), the
// normalisation that gives a spectrum's Y as sum(s * ybar) / CIE_Y_integral at 1 nm steps. It
// exceeds the exact integral of the interpolated ybar by half the two end samples (by 2.4e-5):
// 106.8565 here, against pbrt-v4's 106.856895 over 360-830 nm.
PBRT_CONST Float CIE_Y_integral = Float(detail::SumCIEY(false));
// The same sum of D65 * ybar: a reflectance s under D65 has Y = sum(s * D65 * ybar) / this, so
// that the perfect white has Y = 1.
PBRT_CONST Float CIE_D65_Y_integral = Float(detail::SumCIEY(true));

}  // namespace pbrt
