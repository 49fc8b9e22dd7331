// pbrt_ext: RGB and XYZ triples and the sigmoid-polynomial spectrum that an RGB reflectance
// becomes (pbrt-v4's util/color.h, reduced: no colour encodings, no white balance).
//
// RGBSigmoidPolynomial is the function space of Jakob and Hanika, "A Low-Dimensional Function
// Space for Efficient Spectral Upsampling", Computer Graphics Forum 38(2), 2019: a quadratic
// polynomial in the wavelength mapped into (0, 1) by an algebraic sigmoid, so that a smooth,
// bounded reflectance spectrum has three parameters. As in pbrt-v4 the polynomial is in
// wavelength in nm (the paper's optimizer uses a normalized wavelength; cmd/rgb2spec_opt
// converts) and MaxValue() looks at 360-830 nm, the visible range pbrt-v4 samples.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/spectrum.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <string>

namespace pbrt {

// ---- RGB ---------------------------------------------------------------------------------------

// Three coefficients in some RGB colour space (linear sRGB unless a caller says otherwise).
struct RGB {
    Float r = 0, g = 0, b = 0;

    RGB() = default;
    PBRT_CPU_GPU RGB(Float r, Float g, Float b) : r(r), g(g), b(b) {}

    PBRT_CPU_GPU Float operator[](int c) const {
        assert(c >= 0 && c < 3);
        return c == 0 ? r : (c == 1 ? g : b);
    }
    PBRT_CPU_GPU Float &operator[](int c) {
        assert(c >= 0 && c < 3);
        return c == 0 ? r : (c == 1 ? g : b);
    }

    PBRT_CPU_GPU RGB &operator+=(const RGB &s) { r += s.r; g += s.g; b += s.b; return *this; }
    PBRT_CPU_GPU RGB &operator-=(const RGB &s) { r -= s.r; g -= s.g; b -= s.b; return *this; }
    PBRT_CPU_GPU RGB &operator*=(const RGB &s) { r *= s.r; g *= s.g; b *= s.b; return *this; }
    PBRT_CPU_GPU RGB &operator/=(const RGB &s) { r /= s.r; g /= s.g; b /= s.b; return *this; }
    PBRT_CPU_GPU RGB &operator+=(Float a) { return *this += RGB(a, a, a); }
    PBRT_CPU_GPU RGB &operator-=(Float a) { return *this -= RGB(a, a, a); }
    PBRT_CPU_GPU RGB &operator*=(Float a) { return *this *= RGB(a, a, a); }
    PBRT_CPU_GPU RGB &operator/=(Float a) { return *this /= RGB(a, a, a); }
    PBRT_CPU_GPU RGB operator-() const { return RGB(-r, -g, -b); }

    PBRT_CPU_GPU friend RGB operator+(RGB a, const RGB &b) { return a += b; }
    PBRT_CPU_GPU friend RGB operator-(RGB a, const RGB &b) { return a -= b; }
    PBRT_CPU_GPU friend RGB operator*(RGB a, const RGB &b) { return a *= b; }
    PBRT_CPU_GPU friend RGB operator/(RGB a, const RGB &b) { return a /= b; }
    PBRT_CPU_GPU friend RGB operator+(RGB s, Float a) { return s += a; }
    PBRT_CPU_GPU friend RGB operator-(RGB s, Float a) { return s -= a; }
    PBRT_CPU_GPU friend RGB operator*(RGB s, Float a) { return s *= a; }
    PBRT_CPU_GPU friend RGB operator/(RGB s, Float a) { return s /= a; }
    PBRT_CPU_GPU friend RGB operator+(Float a, const RGB &s) { return RGB(a, a, a) += s; }
    PBRT_CPU_GPU friend RGB operator-(Float a, const RGB &s) { return RGB(a, a, a) -= s; }
    PBRT_CPU_GPU friend RGB operator*(Float a, const RGB &s) { return RGB(a, a, a) *= s; }
    PBRT_CPU_GPU friend RGB operator/(Float a, const RGB &s) { return RGB(a, a, a) /= s; }
    PBRT_CPU_GPU friend bool operator==(const RGB &a, const RGB &b) {
        return a.r == b.r && a.g == b.g && a.b == b.b;
    }
    PBRT_CPU_GPU friend bool operator!=(const RGB &a, const RGB &b) { return !(a == b); }

    PBRT_CPU_GPU Float Average() const { return (r + g + b) / 3; }
    PBRT_CPU_GPU Float MaxComponentValue() const { return std::max({r, g, b}); }
    PBRT_CPU_GPU Float MinComponentValue() const { return std::min({r, g, b}); }

    std::string ToString() const {
        char buf[96];
        std::snprintf(buf, sizeof(buf), "[ RGB r: %g g: %g b: %g ]", r, g, b);
        return buf;
    }
};

// Each component clamped at zero (image filtering can ring below it).
PBRT_CPU_GPU inline RGB ClampZero(RGB rgb) {
    return RGB(rgb.r > 0 ? rgb.r : 0, rgb.g > 0 ? rgb.g : 0, rgb.b > 0 ? rgb.b : 0);
}

// ---- XYZ ---------------------------------------------------------------------------------------

// A chromaticity (x, y) = (X, Y) / (X + Y + Z).
struct Chromaticity {
    Float x = 0, y = 0;
};

// CIE 1931 tristimulus values.
struct XYZ {
    Float X = 0, Y = 0, Z = 0;

    XYZ() = default;
    PBRT_CPU_GPU XYZ(Float X, Float Y, Float Z) : X(X), Y(Y), Z(Z) {}

    // The colour with chromaticity xy and luminance Y; black when y is 0 (no finite X, Z).
    PBRT_CPU_GPU static XYZ FromxyY(Chromaticity xy, Float Y = 1) {
        if (xy.y == 0) return XYZ(0, 0, 0);
        return XYZ(xy.x * Y / xy.y, Y, (1 - xy.x - xy.y) * Y / xy.y);
    }

    // (0, 0) for black rather than 0/0.
    PBRT_CPU_GPU Chromaticity xy() const {
        Float sum = X + Y + Z;
        if (sum == 0) return {0, 0};
        return {X / sum, Y / sum};
    }

    PBRT_CPU_GPU Float operator[](int c) const {
        assert(c >= 0 && c < 3);
        return c == 0 ? X : (c == 1 ? Y : Z);
    }
    PBRT_CPU_GPU Float &operator[](int c) {
        assert(c >= 0 && c < 3);
        return c == 0 ? X : (c == 1 ? Y : Z);
    }

    PBRT_CPU_GPU XYZ &operator+=(const XYZ &s) { X += s.X; Y += s.Y; Z += s.Z; return *this; }
    PBRT_CPU_GPU XYZ &operator-=(const XYZ &s) { X -= s.X; Y -= s.Y; Z -= s.Z; return *this; }
    PBRT_CPU_GPU XYZ &operator*=(Float a) { X *= a; Y *= a; Z *= a; return *this; }
    PBRT_CPU_GPU XYZ &operator/=(Float a) { X /= a; Y /= a; Z /= a; return *this; }
    PBRT_CPU_GPU friend XYZ operator+(XYZ a, const XYZ &b) { return a += b; }
    PBRT_CPU_GPU friend XYZ operator-(XYZ a, const XYZ &b) { return a -= b; }
    PBRT_CPU_GPU friend XYZ operator*(XYZ s, Float a) { return s *= a; }
    PBRT_CPU_GPU friend XYZ operator*(Float a, XYZ s) { return s *= a; }
    PBRT_CPU_GPU friend XYZ operator/(XYZ s, Float a) { return s /= a; }
    PBRT_CPU_GPU friend bool operator==(const XYZ &a, const XYZ &b) {
        return a.X == b.X && a.Y == b.Y && a.Z == b.Z;
    }
    PBRT_CPU_GPU friend bool operator!=(const XYZ &a, const XYZ &b) { return !(a == b); }

    std::string ToString() const {
        char buf[96];
        std::snprintf(buf, sizeof(buf), "[ XYZ X: %g Y: %g Z: %g ]", X, Y, Z);
        return buf;
    }
};

// ---- RGBSigmoidPolynomial ----------------------------------------------------------------------

// s(c0 lambda^2 + c1 lambda + c2), lambda in nm, with the algebraic sigmoid
// s(x) = 1/2 + x / (2 sqrt(1 + x^2)): smooth, in [0, 1], and cheap (no exp). Coefficients of
// +-infinity are allowed (the constant spectra 0 and 1 that RGBToSpectrumTable gives black and
// white): s(+-inf) is 1 or 0.
class RGBSigmoidPolynomial {
  public:
    RGBSigmoidPolynomial() = default;
    PBRT_CPU_GPU RGBSigmoidPolynomial(Float c0, Float c1, Float c2) : c0(c0), c1(c1), c2(c2) {}

    PBRT_CPU_GPU Float operator()(Float lambda) const { return s(Polynomial(lambda)); }
    // The same values at each sampled wavelength, in three passes without branches, so that
    // compilers evaluate the wavelengths together (one sqrtps and one divps for four): every RGB
    // texture, light and grid-medium lookup samples a sigmoid.
    PBRT_CPU_GPU SampledSpectrum Sample(const SampledWavelengths &lambda) const {
        Float x[NSpectrumSamples], sigmoid[NSpectrumSamples];
        for (int i = 0; i < NSpectrumSamples; ++i) x[i] = Polynomial(lambda[i]);
        for (int i = 0; i < NSpectrumSamples; ++i) sigmoid[i] = Sigmoid(x[i]);
        SampledSpectrum v;
        for (int i = 0; i < NSpectrumSamples; ++i) v[i] = Limited(x[i], sigmoid[i]);
        return v;
    }

    // An upper bound of the spectrum over 360-830 nm: the larger end, or the vertex of the
    // polynomial where it lies inside (s is increasing, so the polynomial's maximum is the
    // spectrum's).
    PBRT_CPU_GPU Float MaxValue() const {
        Float result = std::max((*this)(360), (*this)(830));
        if (c0 != 0) {
            Float lambda = -c1 / (2 * c0);
            if (lambda >= 360 && lambda <= 830) result = std::max(result, (*this)(lambda));
        }
        return result;
    }

    // The coefficients of lambda^2, lambda and 1 (public, unlike pbrt-v4's, for printing and
    // for tests that compare them).
    Float c0 = 0, c1 = 0, c2 = 0;

    std::string ToString() const {
        char buf[128];
        std::snprintf(buf, sizeof(buf), "[ RGBSigmoidPolynomial c0: %.9g c1: %.9g c2: %.9g ]", c0,
                      c1, c2);
        return buf;
    }

  private:
    // Horner's rule without std::fma, which is a library call on x86-64 without -mfma.
    PBRT_CPU_GPU Float Polynomial(Float lambda) const { return (c0 * lambda + c1) * lambda + c2; }
    PBRT_CPU_GPU static Float Sigmoid(Float x) { return Float(0.5) + x / (2 * std::sqrt(1 + Sqr(x))); }
    // Beyond |x| = 1e18, 1 + x^2 overflows and x / sqrt(...) would be 0 (a spectrum of 1/2),
    // so the limit replaces the sigmoid; NaN (0 * inf in the polynomial) is treated as -inf, so
    // the spectrum is never NaN.
    PBRT_CPU_GPU static Float Limited(Float x, Float sigmoid) {
        return std::abs(x) < Float(1e18) ? sigmoid : (x > 0 ? Float(1) : Float(0));
    }
    PBRT_CPU_GPU static Float s(Float x) { return Limited(x, Sigmoid(x)); }
};

}  // namespace pbrt
