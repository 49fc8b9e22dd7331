// Spectra (pbrt-v4's Spectrum and its implementations in src/pbrt/util/spectrum.h, host side).
//
// A Spectrum is a function of wavelength (nm) that a path samples at its SampledWavelengths.
// The closed set is pbrt-v4's: constant, densely sampled (1 nm steps), piecewise linear,
// blackbody, and the three RGB spectra (albedo, unbounded, illuminant) that the sigmoid
// polynomials of Jakob and Hanika (2019) turn RGB values into. A Spectrum is cheap to copy:
// tabulated data is shared and immutable.
//
// Pay for what is used: a constant spectrum samples without any table, and IsConstant() lets a
// material know that its index of refraction does not disperse.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/ciedata.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/spectrum.h"

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace pbrt {

class RGBColorSpace;

// pbrt-v4's SpectrumType: how an RGB value is turned into a spectrum.
enum class SpectrumType { Albedo, Unbounded, Illuminant };

// A spectrum's values at each of the wavelengths.
template <typename S>
SampledSpectrum SampleEach(const S &s, const SampledWavelengths &lambda) {
    SampledSpectrum v;
    for (int i = 0; i < NSpectrumSamples; ++i) v[i] = s(lambda[i]);
    return v;
}

struct ConstantSpectrum {
    Float c;
    Float operator()(Float) const { return c; }
    SampledSpectrum Sample(const SampledWavelengths &) const { return SampledSpectrum(c); }
    Float MaxValue() const { return c; }
};

// Values at every integer wavelength in [lambdaMin, lambdaMax], zero outside.
struct DenselySampledSpectrum {
    int lambdaMin = int(Lambda_min), lambdaMax = int(Lambda_max);
    std::vector<Float> values;

    // The nearest tabulated wavelength (rounding by adding 1/2 and truncating, which is exact
    // for the positive wavelengths used and much cheaper than std::lround on the film's path).
    Float operator()(Float lambda) const {
        if (!(lambda >= 0)) return 0;
        int offset = int(lambda + 0.5f) - lambdaMin;
        if (offset < 0 || offset >= int(values.size())) return 0;
        return values[size_t(offset)];
    }
    SampledSpectrum Sample(const SampledWavelengths &lambda) const { return SampleEach(*this, lambda); }
    Float MaxValue() const;
};

// Linear between (lambda, value) samples with increasing lambda; zero outside them.
struct PiecewiseLinearSpectrum {
    PiecewiseLinearSpectrum(std::vector<Float> lambdas, std::vector<Float> values);

    std::vector<Float> lambdas, values;

    Float operator()(Float lambda) const;
    SampledSpectrum Sample(const SampledWavelengths &lambda) const { return SampleEach(*this, lambda); }
    Float MaxValue() const;

  private:
    // The segment holding lambda, within the nodes' range: the last node at or below it.
    size_t Segment(Float lambda) const;
    // firstSegment[k]: Segment(lambdas.front() + k) for each whole nm of the range, so that a
    // lookup starts at most a node or two from its segment (a conductor's eta and k are looked
    // up at four wavelengths per hit); empty for a range too wide to tabulate.
    std::vector<int> firstSegment;
};

// Planck's law at temperature T, scaled to a peak of 1 (at Wien's displacement wavelength).
struct BlackbodySpectrum {
    explicit BlackbodySpectrum(Float T);
    Float operator()(Float lambda) const;
    SampledSpectrum Sample(const SampledWavelengths &lambda) const { return SampleEach(*this, lambda); }
    Float MaxValue() const { return 1; }

    Float T, normalizationFactor;
};

// A reflectance in [0, 1]: the sigmoid polynomial of an RGB in [0, 1]^3.
struct RGBAlbedoSpectrum {
    RGBAlbedoSpectrum(const RGBColorSpace &cs, RGB rgb);
    Float operator()(Float lambda) const { return rsp(lambda); }
    SampledSpectrum Sample(const SampledWavelengths &lambda) const { return rsp.Sample(lambda); }
    Float MaxValue() const { return rsp.MaxValue(); }

    RGBSigmoidPolynomial rsp;
};

// Any RGB >= 0: scale times the sigmoid polynomial of rgb / scale, with scale = 2 max(rgb) (so
// that the polynomial's target stays at most 1/2, where sigmoids fit best).
struct RGBUnboundedSpectrum {
    RGBUnboundedSpectrum(const RGBColorSpace &cs, RGB rgb);
    Float operator()(Float lambda) const { return scale * rsp(lambda); }
    SampledSpectrum Sample(const SampledWavelengths &lambda) const { return scale * rsp.Sample(lambda); }
    Float MaxValue() const { return scale * rsp.MaxValue(); }

    Float scale = 1;
    RGBSigmoidPolynomial rsp;
};

// Emission: an unbounded RGB spectrum times the colour space's illuminant, so that "rgb L"
// [1 1 1] is the colour space's white.
struct RGBIlluminantSpectrum {
    RGBIlluminantSpectrum(const RGBColorSpace &cs, RGB rgb);
    Float operator()(Float lambda) const { return scale * rsp(lambda) * (*illuminant)(lambda); }
    SampledSpectrum Sample(const SampledWavelengths &lambda) const {
        return scale * rsp.Sample(lambda) * illuminant->Sample(lambda);
    }
    Float MaxValue() const { return scale * rsp.MaxValue() * illuminant->MaxValue(); }

    Float scale = 1;
    RGBSigmoidPolynomial rsp;
    const DenselySampledSpectrum *illuminant;  // the colour space's; lives as long as it
};

class Spectrum {
  public:
    using Variant =
        std::variant<ConstantSpectrum, std::shared_ptr<const DenselySampledSpectrum>,
                     std::shared_ptr<const PiecewiseLinearSpectrum>, BlackbodySpectrum,
                     RGBAlbedoSpectrum, RGBUnboundedSpectrum, RGBIlluminantSpectrum>;

    Spectrum() : spectrum(ConstantSpectrum{0}) {}
    explicit Spectrum(Float c) : spectrum(ConstantSpectrum{c}) {}
    template <typename T>
        requires std::is_constructible_v<Variant, T>
    Spectrum(T s) : spectrum(std::move(s)) {}

    // pbrt-v4's PiecewiseLinearSpectrum::FromInterleaved: (lambda, value) pairs with increasing
    // lambda, the end values held out to the rendered range (as pbrt-v4 does for files and
    // named spectra). normalize scales the result to luminance 1: InnerProduct(s, Y) =
    // CIE_Y_integral.
    static Spectrum PiecewiseLinear(std::span<const Float> interleaved, bool normalize);
    static Spectrum PiecewiseLinear(std::vector<Float> lambdas, std::vector<Float> values);
    // s tabulated at every integer wavelength in [Lambda_min, Lambda_max].
    static Spectrum DenselySampled(const Spectrum &s);
    static Spectrum DenselySampled(const DenselySampledSpectrum &s) {
        return Spectrum(std::make_shared<const DenselySampledSpectrum>(s));
    }

    Float operator()(Float lambda) const {
        return std::visit([lambda](const auto &s) { return Deref(s)(lambda); }, spectrum);
    }
    SampledSpectrum Sample(const SampledWavelengths &lambda) const {
        return std::visit([&lambda](const auto &s) { return Deref(s).Sample(lambda); }, spectrum);
    }
    Float MaxValue() const {
        return std::visit([](const auto &s) { return Deref(s).MaxValue(); }, spectrum);
    }

    bool IsConstant() const { return std::holds_alternative<ConstantSpectrum>(spectrum); }
    template <typename T>
    const T *Get() const { return std::get_if<T>(&spectrum); }

    std::string ToString() const;

  private:
    template <typename T>
    static const T &Deref(const T &s) { return s; }
    template <typename T>
    static const T &Deref(const std::shared_ptr<const T> &s) { return *s; }

    Variant spectrum;
};

// s at every integer wavelength in [Lambda_min, Lambda_max] (pbrt-v4's DenselySampledSpectrum
// constructor).
DenselySampledSpectrum DenselySample(const Spectrum &s);

// s as a spectrum looked up many times (a light's emission): tabulated at 1 nm unless it is a
// constant or already a table, which is then shared, not copied. A table with one value at
// every wavelength becomes that constant (a grey medium's "rgb sigma_s [1 1 1]"): the same
// value at every rendered wavelength without a lookup.
Spectrum TabulatedForLookup(const Spectrum &s);

// The CIE 1931 colour matching functions, densely sampled (CIE_Y_integral, the sum of Y at 1 nm
// steps, is in util/ciedata.h).
namespace Spectra {
const DenselySampledSpectrum &X();
const DenselySampledSpectrum &Y();
const DenselySampledSpectrum &Z();
// CIE daylight illuminant D at correlated colour temperature T (K), from the S0, S1, S2
// basis functions (CIE 015:2018), about 1 at 560 nm; a blackbody below 4000 K (pbrt-v4's).
Spectrum D(Float T);
}  // namespace Spectra

// The sum over integer wavelengths in [Lambda_min, Lambda_max] of f(lambda) g(lambda).
Float InnerProduct(const Spectrum &f, const Spectrum &g);
// XYZ of an emission spectrum, scaled so that luminance 1 gives Y = 1.
XYZ SpectrumToXYZ(const Spectrum &s);
// The luminance of radiance sampled at the wavelengths lambda (pbrt-v4's SampledSpectrum::y):
// each sample weighted by Y over its density, averaged, over CIE_Y_integral.
Float Luminance(const SampledSpectrum &L, const SampledWavelengths &lambda);

// pbrt-v4's SpectrumToPhotometric: the inner product with Y of the spectrum, or of its
// illuminant for an RGBIlluminantSpectrum (the RGB only colours the light).
Float SpectrumToPhotometric(const Spectrum &s);

// Planck's law: emitted radiance of a blackbody at lambda (nm), temperature T (K); 0 for
// T <= 0. pbrt-v4's Blackbody().
Float Blackbody(Float lambda, Float T);

// pbrt-v4's named spectra: glasses ("glass-BK7", ...), metals ("metal-Au-eta", ...), standard
// illuminants ("stdillum-D65", "stdillum-A"), camera sensor responses ("canon_eos_100d_r", ...).
// Empty for another name.
pstd::optional<Spectrum> GetNamedSpectrum(std::string_view name);
// The names GetNamedSpectrum knows, comma-separated, for error messages.
std::string NamedSpectrumNames();

}  // namespace pbrt
