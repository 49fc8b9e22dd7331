// pbrt_ext: SampledSpectrum and SampledWavelengths (pbrt-v4's util/spectrum.h, the GPU-clean part).
// A path carries NSpectrumSamples = 4 wavelengths, as in pbrt-v4; every spectral quantity along it
// (throughput, radiance, reflectance) is a SampledSpectrum holding its value at those wavelengths.
// The operator set is pbrt-v4's, so a BxDF written against one compiles unchanged against the other.
// The host-side spectra that are sampled into these (constant, tabulated, blackbody, RGB) are in
// pbrt_ext/spectra/spectrum.h.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <string>

namespace pbrt {

PBRT_CONST int NSpectrumSamples = 4;

// The wavelength range (nm) that rendering samples and that spectra are tabulated over.
PBRT_CONST Float Lambda_min = 360, Lambda_max = 830;

class SampledSpectrum {
  public:
    SampledSpectrum() = default;
    PBRT_CPU_GPU explicit SampledSpectrum(Float c) : values{c, c, c, c} {}
    // One value per wavelength sample.
    PBRT_CPU_GPU SampledSpectrum(Float v0, Float v1, Float v2, Float v3) : values{v0, v1, v2, v3} {}
    PBRT_CPU_GPU explicit SampledSpectrum(pstd::span<const Float> v) {
        assert(v.size() == NSpectrumSamples);
        for (int i = 0; i < NSpectrumSamples; ++i) values[i] = v[i];
    }

    PBRT_CPU_GPU Float operator[](int i) const { return values[i]; }
    PBRT_CPU_GPU Float &operator[](int i) { return values[i]; }

    // True when any channel is nonzero: "does this path still carry energy".
    PBRT_CPU_GPU explicit operator bool() const {
        for (Float v : values)
            if (v != 0) return true;
        return false;
    }

    PBRT_CPU_GPU SampledSpectrum &operator+=(const SampledSpectrum &s) {
        for (int i = 0; i < NSpectrumSamples; ++i) values[i] += s.values[i];
        return *this;
    }
    PBRT_CPU_GPU SampledSpectrum &operator-=(const SampledSpectrum &s) {
        for (int i = 0; i < NSpectrumSamples; ++i) values[i] -= s.values[i];
        return *this;
    }
    PBRT_CPU_GPU SampledSpectrum &operator*=(const SampledSpectrum &s) {
        for (int i = 0; i < NSpectrumSamples; ++i) values[i] *= s.values[i];
        return *this;
    }
    PBRT_CPU_GPU SampledSpectrum &operator/=(const SampledSpectrum &s) {
        for (int i = 0; i < NSpectrumSamples; ++i) values[i] /= s.values[i];
        return *this;
    }
    PBRT_CPU_GPU SampledSpectrum &operator+=(Float a) { return *this += SampledSpectrum(a); }
    PBRT_CPU_GPU SampledSpectrum &operator-=(Float a) { return *this -= SampledSpectrum(a); }
    PBRT_CPU_GPU SampledSpectrum &operator*=(Float a) { return *this *= SampledSpectrum(a); }
    PBRT_CPU_GPU SampledSpectrum &operator/=(Float a) { return *this /= SampledSpectrum(a); }

    PBRT_CPU_GPU SampledSpectrum operator-() const { return SampledSpectrum(0.f) -= *this; }

    // Binary operators in terms of the compound ones; a Float operand acts on every channel.
    PBRT_CPU_GPU friend SampledSpectrum operator+(SampledSpectrum a, const SampledSpectrum &b) { return a += b; }
    PBRT_CPU_GPU friend SampledSpectrum operator-(SampledSpectrum a, const SampledSpectrum &b) { return a -= b; }
    PBRT_CPU_GPU friend SampledSpectrum operator*(SampledSpectrum a, const SampledSpectrum &b) { return a *= b; }
    PBRT_CPU_GPU friend SampledSpectrum operator/(SampledSpectrum a, const SampledSpectrum &b) { return a /= b; }
    PBRT_CPU_GPU friend SampledSpectrum operator+(SampledSpectrum s, Float a) { return s += a; }
    PBRT_CPU_GPU friend SampledSpectrum operator-(SampledSpectrum s, Float a) { return s -= a; }
    PBRT_CPU_GPU friend SampledSpectrum operator*(SampledSpectrum s, Float a) { return s *= a; }
    PBRT_CPU_GPU friend SampledSpectrum operator/(SampledSpectrum s, Float a) { return s /= a; }
    PBRT_CPU_GPU friend SampledSpectrum operator+(Float a, const SampledSpectrum &s) { return SampledSpectrum(a) += s; }
    PBRT_CPU_GPU friend SampledSpectrum operator-(Float a, const SampledSpectrum &s) { return SampledSpectrum(a) -= s; }
    PBRT_CPU_GPU friend SampledSpectrum operator*(Float a, const SampledSpectrum &s) { return SampledSpectrum(a) *= s; }
    PBRT_CPU_GPU friend SampledSpectrum operator/(Float a, const SampledSpectrum &s) { return SampledSpectrum(a) /= s; }

    PBRT_CPU_GPU friend bool operator==(const SampledSpectrum &a, const SampledSpectrum &b) {
        for (int i = 0; i < NSpectrumSamples; ++i)
            if (a.values[i] != b.values[i]) return false;
        return true;
    }
    PBRT_CPU_GPU friend bool operator!=(const SampledSpectrum &a, const SampledSpectrum &b) { return !(a == b); }

    PBRT_CPU_GPU Float MinComponentValue() const {
        Float m = values[0];
        for (int i = 1; i < NSpectrumSamples; ++i) m = std::min(m, values[i]);
        return m;
    }
    PBRT_CPU_GPU Float MaxComponentValue() const {
        Float m = values[0];
        for (int i = 1; i < NSpectrumSamples; ++i) m = std::max(m, values[i]);
        return m;
    }
    PBRT_CPU_GPU Float Average() const {
        Float sum = 0;
        for (Float v : values) sum += v;
        return sum / NSpectrumSamples;
    }

    // Host-only: "[ SampledSpectrum v0 v1 v2 v3 ]".
    std::string ToString() const {
        char buf[128];
        std::snprintf(buf, sizeof(buf), "[ SampledSpectrum %g %g %g %g ]", values[0], values[1],
                      values[2], values[3]);
        return buf;
    }

  private:
    Float values[NSpectrumSamples] = {};
};

// Channel-wise functions, named as pbrt-v4's.
namespace detail {
template <typename F>
PBRT_CPU_GPU SampledSpectrum Map(SampledSpectrum s, F f) {
    for (int i = 0; i < NSpectrumSamples; ++i) s[i] = f(s[i]);
    return s;
}
}  // namespace detail

// a / b, with 0 wherever b is 0 (e.g. f / pdf on a channel that cannot be sampled).
PBRT_CPU_GPU inline SampledSpectrum SafeDiv(SampledSpectrum a, const SampledSpectrum &b) {
    for (int i = 0; i < NSpectrumSamples; ++i) a[i] = (b[i] != 0) ? a[i] / b[i] : 0;
    return a;
}
PBRT_CPU_GPU inline SampledSpectrum Sqrt(const SampledSpectrum &s) {
    return detail::Map(s, [](Float v) { return std::sqrt(v); });
}
// One exponential where every wavelength has the same value (a grey medium's optical depth),
// which gives the same result as four.
PBRT_CPU_GPU inline SampledSpectrum Exp(const SampledSpectrum &s) {
    if (s[0] == s[1] && s[0] == s[2] && s[0] == s[3])
        return SampledSpectrum(std::exp(s[0]));
    return detail::Map(s, [](Float v) { return std::exp(v); });
}
PBRT_CPU_GPU inline SampledSpectrum Pow(const SampledSpectrum &s, Float e) {
    return detail::Map(s, [e](Float v) { return std::pow(v, e); });
}
PBRT_CPU_GPU inline SampledSpectrum ClampZero(const SampledSpectrum &s) {
    return detail::Map(s, [](Float v) { return std::max<Float>(0, v); });
}
PBRT_CPU_GPU inline SampledSpectrum Clamp(const SampledSpectrum &s, Float low, Float high) {
    return detail::Map(s, [low, high](Float v) { return pbrt::Clamp(v, low, high); });
}
PBRT_CPU_GPU inline SampledSpectrum Lerp(Float t, const SampledSpectrum &a, const SampledSpectrum &b) {
    return (1 - t) * a + t * b;
}

// pbrt-v4's importance density over visible wavelengths: proportional to 1 / cosh^2(0.0072
// (lambda - 538)) on [360, 830] nm, which follows the luminance response closely, so that the
// wavelengths the eye sees best are sampled most (Radziszewski et al. 2009, as used by pbrt-v4).
PBRT_CPU_GPU inline Float VisibleWavelengthsPDF(Float lambda) {
    if (lambda < Lambda_min || lambda > Lambda_max) return 0;
    return 0.0039398042f / Sqr(std::cosh(0.0072f * (lambda - 538)));
}

// The inverse of that density's cumulative distribution at u in [0, 1].
PBRT_CPU_GPU inline Float SampleVisibleWavelengths(Float u) {
    return 538 - 138.888889f * std::atanh(0.85691062f - 1.82750197f * u);
}

// The wavelengths a camera sample carries and their densities. Secondary wavelengths (all but
// the first) are terminated where a path's scattering depends on wavelength (dispersion): their
// density becomes 0, so they no longer contribute, and the first one's is divided by
// NSpectrumSamples so that the estimate stays unbiased.
class SampledWavelengths {
  public:
    // pbrt-v4's stratified visible sampling: one uniform u, shifted by i / NSpectrumSamples per
    // sample, each warped by SampleVisibleWavelengths.
    // The density needs no cosh: with x = 0.85691062 - 1.82750197 u the sample is 538 - atanh(x)
    // / 0.0072, so cosh^2(0.0072 (lambda - 538)) = 1 / (1 - x^2). atanh(x) is taken as
    // log((1 + x) / (1 - x)) / 2: |x| < 0.98 here, where that is as accurate in absolute terms
    // (1e-7, i.e. 1e-5 nm) and far cheaper than atanhf.
    PBRT_CPU_GPU static SampledWavelengths SampleVisible(Float u) {
        SampledWavelengths swl;
        for (int i = 0; i < NSpectrumSamples; ++i) {
            Float up = u + Float(i) / NSpectrumSamples;
            if (up > 1) up -= 1;
            Float x = 0.85691062f - 1.82750197f * up;
            swl.lambda[i] = 538 - 69.4444444f * std::log((1 + x) / (1 - x));
            swl.pdf[i] = 0.0039398042f * (1 - x * x);
        }
        return swl;
    }

    // Uniform over [lambdaMin, lambdaMax], stratified as SampleVisible.
    PBRT_CPU_GPU static SampledWavelengths SampleUniform(Float u, Float lambdaMin = Lambda_min,
                                                         Float lambdaMax = Lambda_max) {
        SampledWavelengths swl;
        Float delta = (lambdaMax - lambdaMin) / NSpectrumSamples;
        swl.lambda[0] = Lerp(u, lambdaMin, lambdaMax);
        for (int i = 1; i < NSpectrumSamples; ++i) {
            swl.lambda[i] = swl.lambda[i - 1] + delta;
            if (swl.lambda[i] > lambdaMax) swl.lambda[i] = lambdaMin + (swl.lambda[i] - lambdaMax);
        }
        for (int i = 0; i < NSpectrumSamples; ++i) swl.pdf[i] = 1 / (lambdaMax - lambdaMin);
        return swl;
    }

    PBRT_CPU_GPU Float operator[](int i) const { return lambda[i]; }
    PBRT_CPU_GPU SampledSpectrum PDF() const { return SampledSpectrum(pdf[0], pdf[1], pdf[2], pdf[3]); }

    PBRT_CPU_GPU void TerminateSecondary() {
        if (SecondaryTerminated()) return;
        for (int i = 1; i < NSpectrumSamples; ++i) pdf[i] = 0;
        pdf[0] /= NSpectrumSamples;
    }
    PBRT_CPU_GPU bool SecondaryTerminated() const {
        for (int i = 1; i < NSpectrumSamples; ++i)
            if (pdf[i] != 0) return false;
        return true;
    }

    PBRT_CPU_GPU friend bool operator==(const SampledWavelengths &a, const SampledWavelengths &b) {
        for (int i = 0; i < NSpectrumSamples; ++i)
            if (a.lambda[i] != b.lambda[i] || a.pdf[i] != b.pdf[i]) return false;
        return true;
    }

    // Host-only.
    std::string ToString() const {
        char buf[192];
        std::snprintf(buf, sizeof(buf), "[ SampledWavelengths lambda: %g %g %g %g pdf: %g %g %g %g ]",
                      lambda[0], lambda[1], lambda[2], lambda[3], pdf[0], pdf[1], pdf[2], pdf[3]);
        return buf;
    }

  private:
    Float lambda[NSpectrumSamples] = {}, pdf[NSpectrumSamples] = {};
};

static_assert(NSpectrumSamples == 4, "PDF() and ToString() list four samples");

}  // namespace pbrt
