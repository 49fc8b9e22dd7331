#include "pbrt_ext/spectra/spectrum.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/ciedata.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pbrt {

namespace {

template <typename F>
std::shared_ptr<const DenselySampledSpectrum> Tabulate(F f) {
    auto s = std::make_shared<DenselySampledSpectrum>();
    for (int lambda = s->lambdaMin; lambda <= s->lambdaMax; ++lambda)
        s->values.push_back(f(Float(lambda)));
    return s;
}

// The matching functions at integer wavelengths, built once.
struct CIEMatching {
    std::shared_ptr<const DenselySampledSpectrum> x, y, z;
};
const CIEMatching &Matching() {
    static const CIEMatching m = [] {
        CIEMatching c;
        c.x = Tabulate([](Float l) { return Float(CIEAt(l).x); });
        c.y = Tabulate([](Float l) { return Float(CIEAt(l).y); });
        c.z = Tabulate([](Float l) { return Float(CIEAt(l).z); });
        return c;
    }();
    return m;
}

}  // namespace

// ---- The implementations ---------------------------------------------------------------------

Float DenselySampledSpectrum::MaxValue() const {
    return values.empty() ? 0 : *std::max_element(values.begin(), values.end());
}

PiecewiseLinearSpectrum::PiecewiseLinearSpectrum(std::vector<Float> lambdas0, std::vector<Float> values0)
    : lambdas(std::move(lambdas0)), values(std::move(values0)) {
    constexpr Float kMaxTabulatedRange = 10000;  // nm
    if (lambdas.size() < 2 || !(lambdas.back() - lambdas.front() <= kMaxTabulatedRange)) return;
    std::vector<int> table(size_t(lambdas.back() - lambdas.front()) + 1);
    for (size_t k = 0; k < table.size(); ++k) table[k] = int(Segment(lambdas.front() + Float(k)));
    firstSegment = std::move(table);
}

// The same index as FindInterval's bisection: the steps from the table's entry only act where
// lambda - lambdas.front() rounded across a whole nm.
size_t PiecewiseLinearSpectrum::Segment(Float lambda) const {
    auto atOrBelow = [&](int k) { return lambdas[size_t(k)] <= lambda; };
    int size = int(lambdas.size());
    if (firstSegment.empty())
        return size_t(detail::FindInterval(size, atOrBelow));
    size_t k = std::min(size_t(lambda - lambdas.front()), firstSegment.size() - 1);
    return size_t(detail::FindIntervalFrom(firstSegment[k], size, atOrBelow));
}

Float PiecewiseLinearSpectrum::operator()(Float lambda) const {
    // (A NaN lambda is outside too: Segment's table index needs a number.)
    if (lambdas.empty() || !(lambda >= lambdas.front() && lambda <= lambdas.back())) return 0;
    if (lambda == lambdas.back()) return values.back();
    // The last node at or below lambda; the one after it lies above.
    size_t i = Segment(lambda);
    Float t = (lambda - lambdas[i]) / (lambdas[i + 1] - lambdas[i]);
    return Lerp(t, values[i], values[i + 1]);
}

Float PiecewiseLinearSpectrum::MaxValue() const {
    return values.empty() ? 0 : *std::max_element(values.begin(), values.end());
}

Float Blackbody(Float lambda, Float T) {
    if (T <= 0) return 0;
    constexpr double c = 299792458., h = 6.62606957e-34, kb = 1.3806488e-23;
    double l = lambda * 1e-9;
    return Float((2 * h * c * c) / (std::pow(l, 5) * std::expm1((h * c) / (l * kb * T))));
}

BlackbodySpectrum::BlackbodySpectrum(Float T) : T(T) {
    Float lambdaMax = Float(2.8977721e-3 / T * 1e9);  // Wien's displacement law
    normalizationFactor = 1 / Blackbody(lambdaMax, T);
}

Float BlackbodySpectrum::operator()(Float lambda) const {
    return Blackbody(lambda, T) * normalizationFactor;
}

RGBAlbedoSpectrum::RGBAlbedoSpectrum(const RGBColorSpace &cs, RGB rgb) {
    assert(std::max({rgb.r, rgb.g, rgb.b}) <= 1 && std::min({rgb.r, rgb.g, rgb.b}) >= 0);
    rsp = cs.ToRGBCoeffs(rgb);
}

RGBUnboundedSpectrum::RGBUnboundedSpectrum(const RGBColorSpace &cs, RGB rgb) {
    Float m = std::max({rgb.r, rgb.g, rgb.b});
    scale = 2 * m;
    rsp = cs.ToRGBCoeffs(scale ? rgb / scale : RGB(0, 0, 0));
}

RGBIlluminantSpectrum::RGBIlluminantSpectrum(const RGBColorSpace &cs, RGB rgb)
    : illuminant(&cs.illuminant) {
    Float m = std::max({rgb.r, rgb.g, rgb.b});
    scale = 2 * m;
    rsp = cs.ToRGBCoeffs(scale ? rgb / scale : RGB(0, 0, 0));
}

// ---- Spectrum ---------------------------------------------------------------------------------

Spectrum Spectrum::PiecewiseLinear(std::vector<Float> lambdas, std::vector<Float> values) {
    assert(lambdas.size() == values.size());
    return Spectrum(std::shared_ptr<const PiecewiseLinearSpectrum>(
        std::make_shared<PiecewiseLinearSpectrum>(std::move(lambdas), std::move(values))));
}

Spectrum Spectrum::PiecewiseLinear(std::span<const Float> interleaved, bool normalize) {
    if (interleaved.size() % 2 != 0)
        throw std::invalid_argument("PiecewiseLinear: an odd number of interleaved values");
    std::vector<Float> lambdas, values;
    for (size_t i = 0; i < interleaved.size(); i += 2) {
        lambdas.push_back(interleaved[i]);
        values.push_back(interleaved[i + 1]);
    }
    if (!lambdas.empty() && lambdas.front() > Lambda_min) {
        lambdas.insert(lambdas.begin(), Lambda_min - 1);
        values.insert(values.begin(), values.front());
    }
    if (!lambdas.empty() && lambdas.back() < Lambda_max) {
        lambdas.push_back(Lambda_max + 1);
        values.push_back(values.back());
    }
    Spectrum s = PiecewiseLinear(std::move(lambdas), std::move(values));
    if (!normalize) return s;
    Float scale = CIE_Y_integral / InnerProduct(s, Spectrum(Matching().y));
    auto scaled = std::make_shared<PiecewiseLinearSpectrum>(*s.Get<std::shared_ptr<const PiecewiseLinearSpectrum>>()->get());
    for (Float &v : scaled->values) v *= scale;
    return Spectrum(std::shared_ptr<const PiecewiseLinearSpectrum>(std::move(scaled)));
}

DenselySampledSpectrum DenselySample(const Spectrum &s) {
    return *Tabulate([&s](Float l) { return s(l); });
}

Spectrum Spectrum::DenselySampled(const Spectrum &s) {
    return Spectrum(Tabulate([&s](Float l) { return s(l); }));
}

Spectrum TabulatedForLookup(const Spectrum &s) {
    if (s.IsConstant()) return s;
    Spectrum table = s.Get<std::shared_ptr<const DenselySampledSpectrum>>() ? s : Spectrum::DenselySampled(s);
    const std::vector<Float> &values = (*table.Get<std::shared_ptr<const DenselySampledSpectrum>>())->values;
    bool flat = !values.empty() && std::all_of(values.begin(), values.end(),
                                               [&](Float v) { return v == values.front(); });
    return flat ? Spectrum(values.front()) : table;
}

std::string Spectrum::ToString() const {
    char buf[160];
    struct Describe {
        char *buf;
        void operator()(const ConstantSpectrum &s) const { std::snprintf(buf, 160, "[ ConstantSpectrum %g ]", s.c); }
        void operator()(const std::shared_ptr<const DenselySampledSpectrum> &s) const {
            std::snprintf(buf, 160, "[ DenselySampledSpectrum %d-%d nm max %g ]", s->lambdaMin, s->lambdaMax, s->MaxValue());
        }
        void operator()(const std::shared_ptr<const PiecewiseLinearSpectrum> &s) const {
            std::snprintf(buf, 160, "[ PiecewiseLinearSpectrum %zu samples ]", s->lambdas.size());
        }
        void operator()(const BlackbodySpectrum &s) const { std::snprintf(buf, 160, "[ BlackbodySpectrum T: %g ]", s.T); }
        void operator()(const RGBAlbedoSpectrum &s) const {
            std::snprintf(buf, 160, "[ RGBAlbedoSpectrum %g %g %g ]", s.rsp.c0, s.rsp.c1, s.rsp.c2);
        }
        void operator()(const RGBUnboundedSpectrum &s) const {
            std::snprintf(buf, 160, "[ RGBUnboundedSpectrum scale: %g %g %g %g ]", s.scale, s.rsp.c0, s.rsp.c1, s.rsp.c2);
        }
        void operator()(const RGBIlluminantSpectrum &s) const {
            std::snprintf(buf, 160, "[ RGBIlluminantSpectrum scale: %g %g %g %g ]", s.scale, s.rsp.c0, s.rsp.c1, s.rsp.c2);
        }
    };
    std::visit(Describe{buf}, spectrum);
    return buf;
}

// ---- Colorimetry ------------------------------------------------------------------------------

namespace Spectra {
const DenselySampledSpectrum &X() { return *Matching().x; }
const DenselySampledSpectrum &Y() { return *Matching().y; }
const DenselySampledSpectrum &Z() { return *Matching().z; }
}  // namespace Spectra

Float InnerProduct(const Spectrum &f, const Spectrum &g) {
    double sum = 0;
    for (int lambda = int(Lambda_min); lambda <= int(Lambda_max); ++lambda)
        sum += double(f(Float(lambda))) * double(g(Float(lambda)));
    return Float(sum);
}

XYZ SpectrumToXYZ(const Spectrum &s) {
    const CIEMatching &m = Matching();
    return XYZ(InnerProduct(Spectrum(m.x), s), InnerProduct(Spectrum(m.y), s),
               InnerProduct(Spectrum(m.z), s)) / CIE_Y_integral;
}

Float Luminance(const SampledSpectrum &L, const SampledWavelengths &lambda) {
    return SafeDiv(Spectra::Y().Sample(lambda) * L, lambda.PDF()).Average() / CIE_Y_integral;
}

Float SpectrumToPhotometric(const Spectrum &s) {
    if (const RGBIlluminantSpectrum *rgb = s.Get<RGBIlluminantSpectrum>()) {
        const DenselySampledSpectrum &illum = *rgb->illuminant;
        double sum = 0;
        for (int lambda = int(Lambda_min); lambda <= int(Lambda_max); ++lambda)
            sum += double(illum(Float(lambda))) * double(Spectra::Y()(Float(lambda)));
        return Float(sum);
    }
    return InnerProduct(Spectrum(Matching().y), s);
}

}  // namespace pbrt
