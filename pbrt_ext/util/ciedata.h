// pbrt_ext: the CIE 1931 standard observer and illuminant D65 as tabulated data, pbrt-v4's
// (util/cietables.h), shared by the spectra, the RGB-to-spectrum table and its generator,
// cmd/rgb2spec_opt, so that all of them see one observer.
//
// The matching functions are tabulated every nm over 360-830 nm, D65 every 5 nm over 300-830 nm;
// both are linearly interpolated between their samples and zero outside them, as pbrt-v4's
// PiecewiseLinearSpectrum.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/cietables.h"
#include "pbrt_ext/util/math.h"

namespace pbrt {

// xbar, ybar, zbar and D65 at one wavelength.
struct CIESample {
    float x, y, z, d65;
};
PBRT_CONST Float kCIELambdaMin = 360, kCIELambdaMax = 830;

namespace detail {
// The table t of n samples, the first at t = 0, linearly interpolated; zero outside (and NaN).
template <typename Get>
PBRT_CPU_GPU constexpr float Interpolate(Float t, int n, Get get) {
    if (!(t >= 0) || t > n - 1) return 0;
    int i = int(t) < n - 1 ? int(t) : n - 2;
    Float f = t - Float(i);
    return float((1 - f) * get(i) + f * get(i + 1));
}
}  // namespace detail

// The tables at lambda (nm).
PBRT_CPU_GPU constexpr CIESample CIEAt(Float lambda) {
    Float t = lambda - kCIELambdaMin;
    auto cmf = [t](int c) {
        return detail::Interpolate(t, 471, [c](int i) { return kCIEMatching[i][c]; });
    };
    float d65 = detail::Interpolate((lambda - 300) / 5, 107, [](int i) { return kCIED65[i]; });
    return {cmf(0), cmf(1), cmf(2), d65};
}

namespace detail {
// Sum over lambda = 360, 361, ..., 830 nm of CIEAt(lambda).y, times D65 if weighted.
constexpr double SumCIEY(bool weighted) {
    double sum = 0;
    for (int lambda = 360; lambda <= 830; ++lambda) {
        CIESample c = CIEAt(Float(lambda));
        sum += double(c.y) * (weighted ? double(c.d65) : 1.0);
    }
    return sum;
}
}  // namespace detail

// pbrt-v4's CIE_Y_integral (106.856895): ybar summed at 1 nm steps over 360-830 nm, the
// normalisation that gives a spectrum's Y as sum(s * ybar) / CIE_Y_integral at 1 nm steps.
PBRT_CONST Float CIE_Y_integral = Float(detail::SumCIEY(false));
// The same sum of D65 * ybar: a reflectance s under D65 has Y = sum(s * D65 * ybar) / this, so
// that the perfect white has Y = 1.
PBRT_CONST Float CIE_D65_Y_integral = Float(detail::SumCIEY(true));

}  // namespace pbrt
