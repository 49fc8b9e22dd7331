// Spectra as a scene file writes them, reduced to the renderer's linear sRGB (pbrt-v4's
// src/pbrt/util/spectrum.h and its named spectra, reduced to RGB; host only).
//
// pbrt-v4 renders wavelength samples; this renderer renders RGB, so every spectrum is turned
// into the RGB that pbrt-v4's default film would record for it: XYZ by integrating against the
// CIE 1931 2-degree colour matching functions, then linear sRGB (D65 white). What is weighted
// by what follows the spectrum's use (pbrt-v4's SpectrumType):
//  - Illuminant: emitted power as given; XYZ = integral of s * cmf / integral of ybar, so a
//    spectrum with luminance 1 has Y = 1 (and "stdillum-D65" is exactly (1, 1, 1)).
//  - Reflectance (pbrt-v4's Albedo) and Unbounded (eta, k, scattering coefficients): seen
//    under D65, the white of linear sRGB, so a constant spectrum c is exactly (c, c, c).
//    Reflectance results are clamped to [0, 1], Unbounded ones to >= 0 (a saturated spectrum
//    can fall outside the sRGB gamut; pbrt-v4 keeps these ranges too).
// An "rgb" parameter is already in this space and passes through (checked as pbrt-v4 checks
// it). Samples and .spd files are piecewise linear and zero outside their range, as pbrt-v4's
// PiecewiseLinearSpectrum. Bad input throws ParseError at the parameter's location.
#pragma once

#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/spectrum.h"

#include <string>

namespace pbrt {

struct SpectrumParam;  // paramdict.h

enum class SpectrumKind { Reflectance, Unbounded, Illuminant };

// Relative paths in a File spectrum are resolved against baseDir (the directory of the scene
// file, as pbrt-v4 resolves them against its search directory).
SampledSpectrum SpectrumToRGB(const SpectrumParam &param, SpectrumKind kind,
                              const std::string &baseDir);

// pbrt-v4's SpectrumToPhotometric: the luminance Y of an emission spectrum, by which lights
// divide their scale so that "scale" means luminance. For an "rgb" parameter it is the
// luminance of the colour space's illuminant, 1, as in pbrt-v4 (which ignores the RGB here).
Float SpectrumToPhotometric(const SpectrumParam &param, const std::string &baseDir);

// Planck's law: emitted radiance of a blackbody at lambda (nm), temperature T (K); 0 for
// T <= 0. pbrt-v4's Blackbody().
Float Blackbody(Float lambda, Float T);

// The index of refraction at lambda (nm) of a named glass ("glass-BK7", ...); empty for
// another name. A dielectric that needs one number rather than a spectrum can use this at
// 550 nm.
pstd::optional<Float> NamedGlassIOR(const std::string &name, Float lambda);

}  // namespace pbrt
