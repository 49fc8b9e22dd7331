// Measured data behind PixelSensor (sensor.h): camera spectral sensitivities and the ColorChecker
// reflectances the sensor's colour matrix is fitted on (pbrt-v4's sensor curves in
// src/pbrt/util/spectrum.cpp and PixelSensor::swatchReflectances in src/pbrt/film.cpp).
#pragma once

#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/pstd.h"

#include <span>
#include <string>
#include <string_view>

namespace pbrt {

// The response of a camera's red, green or blue channel by pbrt-v4's name, "<model>_r", "_g" or
// "_b" (e.g. "canon_eos_100d_g"); empty for any other name. As in pbrt-v4 the curves are used
// as measured (not rescaled; the data set gives them relative to the peak of green) and, like
// pbrt-v4's PiecewiseLinearSpectrum::FromInterleaved, held at their end values below 380 nm and
// above 720 nm instead of dropping to zero.
pstd::optional<Spectrum> GetSensorResponse(std::string_view name);

// The camera models GetSensorResponse knows ("canon_eos_100d", ...), in pbrt-v4's order.
std::span<const std::string_view> SensorModels();

// Every response name GetSensorResponse knows, comma-separated (for error messages).
std::string SensorNames();

// The 24 ColorChecker swatch reflectances in chart order (index 0 "dark skin" ... 18 "white 9.5",
// ... 23 "black 2"), held at their end values outside 380-730 nm as pbrt-v4's are.
constexpr int NSwatchReflectances = 24;
std::span<const Spectrum, NSwatchReflectances> SwatchReflectances();

}  // namespace pbrt
