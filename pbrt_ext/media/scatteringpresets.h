// pbrt_ext: the measured scattering coefficients that media ("preset") and subsurface materials
// ("name") take by name, pbrt-v4's GetMediumScatteringProperties: reduced scattering sigma_s' and
// absorption sigma_a in mm^-1, as sRGB unbounded spectra (as pbrt-v4 makes them).
#pragma once

#include "pbrt_ext/spectra/spectrum.h"

#include <optional>
#include <string>
#include <utility>

namespace pbrt {

// (sigma_a, sigma_s) of the named measurement; none for a name the table does not have.
std::optional<std::pair<Spectrum, Spectrum>> MeasuredScattering(const std::string &name);
// The names, quoted and comma-separated, for error messages.
std::string MeasuredScatteringNames();

}  // namespace pbrt
