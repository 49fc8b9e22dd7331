// pbrt_ext: SampledSpectrum (pbrt-v4's util/spectrum.h, reduced to RGB).
// pbrt-v4 carries NSpectrumSamples wavelengths; here the three samples are linear RGB, with
// pbrt-v4's operator set, so a BxDF written against one compiles unchanged against the other.
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

PBRT_CONST int NSpectrumSamples = 3;

class SampledSpectrum {
  public:
    SampledSpectrum() = default;
    PBRT_CPU_GPU explicit SampledSpectrum(Float c) : values{c, c, c} {}
    PBRT_CPU_GPU SampledSpectrum(Float r, Float g, Float b) : values{r, g, b} {}
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
        return std::min(values[0], std::min(values[1], values[2]));
    }
    PBRT_CPU_GPU Float MaxComponentValue() const {
        return std::max(values[0], std::max(values[1], values[2]));
    }
    PBRT_CPU_GPU Float Average() const {
        return (values[0] + values[1] + values[2]) / NSpectrumSamples;
    }

    // Host-only: "[ SampledSpectrum r g b ]".
    std::string ToString() const {
        char buf[96];
        std::snprintf(buf, sizeof(buf), "[ SampledSpectrum %g %g %g ]", values[0], values[1], values[2]);
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
PBRT_CPU_GPU inline SampledSpectrum Exp(const SampledSpectrum &s) {
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

}  // namespace pbrt
