#include "pbrt_ext/scene/spectra.h"

#include "pbrt_ext/scene/paramdict.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/floatfile.h"

#include <algorithm>
#include <filesystem>
#include <span>
#include <sstream>
#include <vector>

namespace pbrt {

namespace {

// (lambda, value) pairs with strictly increasing wavelengths; `what` names their origin.
Spectrum FromPairs(std::span<const double> pairs, const FileLoc &loc, const std::string &what) {
    if (pairs.empty() || pairs.size() % 2 != 0)
        throw ParseError(loc, what + " has " + std::to_string(pairs.size()) +
                                  " values, expected (wavelength, value) pairs");
    std::vector<Float> lambdas, values;
    for (size_t i = 0; i < pairs.size(); i += 2) {
        if (!lambdas.empty() && pairs[i] <= lambdas.back()) {
            std::ostringstream msg;
            msg << what << ": wavelength " << pairs[i] << " after " << lambdas.back()
                << ", expected increasing wavelengths";
            throw ParseError(loc, msg.str());
        }
        lambdas.push_back(Float(pairs[i]));
        values.push_back(Float(pairs[i + 1]));
    }
    return Spectrum::PiecewiseLinear(std::move(lambdas), std::move(values));
}

// A .spd file (ReadFloatFile), read as (lambda, value) pairs.
Spectrum ReadSpectrumFile(const SpectrumParam &param, const std::string &baseDir) {
    std::filesystem::path path(param.name);
    if (path.is_relative() && !baseDir.empty()) path = std::filesystem::path(baseDir) / path;
    std::string what = "spectrum file \"" + path.string() + "\"";
    std::vector<double> numbers = ReadFloatFile(path.string(), param.loc, what, "(wavelength, value) pairs");
    FromPairs(numbers, param.loc, what);  // checks the pairs
    std::vector<Float> interleaved(numbers.begin(), numbers.end());
    return Spectrum::PiecewiseLinear(interleaved, false);  // end values held, as pbrt-v4 reads files
}

// The spectrum a non-RGB parameter describes. A Named parameter that names no built-in
// spectrum is read as a file, as pbrt-v4 does for any string-valued spectrum.
Spectrum Describe(const SpectrumParam &param, const std::string &baseDir) {
    switch (param.kind) {
    case SpectrumParamKind::Blackbody: {
        if (param.values.size() != 1 || !(param.values[0] > 0))
            throw ParseError(param.loc, "blackbody needs one temperature, expected a positive value in kelvin");
        return BlackbodySpectrum(Float(param.values[0]));
    }
    case SpectrumParamKind::Samples:
        return FromPairs(param.values, param.loc, "spectrum");
    case SpectrumParamKind::Named:
        if (pstd::optional<Spectrum> s = GetNamedSpectrum(param.name)) return *s;
        if (!std::filesystem::path(param.name).has_extension())
            throw ParseError(param.loc, "unknown named spectrum \"" + param.name +
                                            "\", expected one of " + NamedSpectrumNames() +
                                            " or a spectrum file");
        return ReadSpectrumFile(param, baseDir);
    case SpectrumParamKind::File:
        return ReadSpectrumFile(param, baseDir);
    default:
        throw ParseError(param.loc, "not a spectral description");
    }
}

// pbrt-v4's checks on an "rgb" value: no negative component, none above 1 for a reflectance.
RGB CheckedRGB(const SpectrumParam &param, SpectrumType type) {
    if (param.values.size() != 3)
        throw ParseError(param.loc, "rgb has " + std::to_string(param.values.size()) +
                                        " values, expected 3");
    RGB rgb(Float(param.values[0]), Float(param.values[1]), Float(param.values[2]));
    std::ostringstream values;
    values << "(" << rgb[0] << ", " << rgb[1] << ", " << rgb[2] << ")";
    if (std::min({rgb.r, rgb.g, rgb.b}) < 0)
        throw ParseError(param.loc, "rgb " + values.str() + " has a negative component, expected values >= 0");
    if (type == SpectrumType::Albedo && std::max({rgb.r, rgb.g, rgb.b}) > 1)
        throw ParseError(param.loc, "rgb reflectance " + values.str() +
                                        " has a component > 1, expected values in [0, 1]");
    return rgb;
}

}  // namespace

Spectrum CreateSpectrum(const SpectrumParam &param, SpectrumType type, const RGBColorSpace &cs,
                        const std::string &baseDir) {
    if (param.kind != SpectrumParamKind::RGB) return Describe(param, baseDir);
    RGB rgb = CheckedRGB(param, type);
    switch (type) {
    case SpectrumType::Albedo:
        return RGBAlbedoSpectrum(cs, rgb);
    case SpectrumType::Unbounded:
        return RGBUnboundedSpectrum(cs, rgb);
    case SpectrumType::Illuminant:
        return RGBIlluminantSpectrum(cs, rgb);
    }
    return {};
}

}  // namespace pbrt
