// Spectra as a scene file writes them (pbrt-v4's ParameterDictionary::GetOneSpectrum; host only).
//
// An "rgb" value becomes the RGB spectrum its use asks for (pbrt-v4's SpectrumType): an albedo
// for reflectances (checked to lie in [0, 1]), an unbounded spectrum for eta, k and scattering
// coefficients, an illuminant (RGB times the colour space's white) for emission. "blackbody"
// is the normalized Planck spectrum; sample pairs are piecewise linear and zero outside their
// range, .spd files hold their end values out to the rendered range (both as pbrt-v4); a name is
// one of GetNamedSpectrum's or else a file. Bad input throws
// ParseError at the parameter's location.
#pragma once

#include "pbrt_ext/spectra/spectrum.h"

#include <string>

namespace pbrt {

struct SpectrumParam;  // paramdict.h
class RGBColorSpace;

// Relative paths in a File spectrum are resolved against baseDir (the directory of the scene
// file, as pbrt-v4 resolves them against its search directory).
Spectrum CreateSpectrum(const SpectrumParam &param, SpectrumType type, const RGBColorSpace &cs,
                        const std::string &baseDir);

}  // namespace pbrt
