// The film's sensor: how radiance at a path's wavelengths becomes an RGB (pbrt-v4's PixelSensor,
// src/pbrt/film.h/.cpp).
//
// A sensor integrates radiance against three response curves. "cie1931" uses the CIE matching
// functions, so its RGB is XYZ; a camera model uses its measured curves (sensordata.h), and a
// 3x3 matrix fitted on the 24 ColorChecker swatches takes its RGB to XYZ. The film then applies
// XYZFromSensorRGB and the output colour space's RGBFromXYZ.
//
// Units, as pbrt-v4: ToSensorRGB returns imagingRatio times the Monte Carlo estimate of
// integral(response * L) over wavelength; it does not divide by CIE_Y_integral. The lights have
// already divided their spectra by their photometric integral (SpectrumToPhotometric), so an
// emitter of "scale" 1 seen directly by the cie1931 sensor gives Y = 1.
//
// White balance: for cie1931 it is off unless asked for (a von Kries adaptation from daylight D
// at the given temperature to the output colour space's white, util/whitebalance.h); a camera is
// always balanced, by fitting its matrix with the swatches lit by D at the given temperature
// (6500 K by default) on the sensor side and by the output colour space's illuminant on the XYZ
// side, so that a grey under that daylight comes out as the output space's grey.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/squarematrix.h"

#include <string>
#include <string_view>
#include <vector>

namespace pbrt {

class PixelSensor {
  public:
    // pbrt-v4's PixelSensor::Create from the film's parameters: "sensor" (default "cie1931"),
    // "iso" (default 100), "whitebalance" (K; default 0, which means none for cie1931 and 6500
    // for a camera), and the camera's exposure time (pbrt-v4's default 1). imagingRatio =
    // exposureTime * iso / 100, so the defaults record radiance unscaled. Throws
    // std::invalid_argument for an unknown sensor (naming the known ones) or a negative or
    // non-finite white balance.
    static PixelSensor Create(std::string_view sensorName, Float iso, Float whiteBalance,
                              Float exposureTime, const RGBColorSpace &outputColorSpace);
    // Create("cie1931", 100, 0, 1, sRGB): XYZ, no white balance, imaging ratio 1.
    static PixelSensor CreateDefault();

    // A camera with responses r, g, b; its XYZFromSensorRGB is the least-squares fit described
    // above, with the swatches under sensorIllum. Throws std::invalid_argument if the fit is
    // singular.
    PixelSensor(const Spectrum &r, const Spectrum &g, const Spectrum &b,
                const RGBColorSpace &outputColorSpace, const Spectrum &sensorIllum,
                Float imagingRatio);
    // The CIE 1931 observer. With a sensorIllum, XYZFromSensorRGB white-balances from its
    // chromaticity to the output colour space's white; without, it is the identity.
    PixelSensor(const RGBColorSpace &outputColorSpace, const pstd::optional<Spectrum> &sensorIllum,
                Float imagingRatio);

    // The sensor's RGB for radiance L carried at wavelengths lambda: imagingRatio times the
    // average over the samples of response * L / pdf (channels with pdf 0 contribute 0).
    // The three responses are read from one interleaved table: one lookup per wavelength on the
    // film's path instead of three.
    RGB ToSensorRGB(SampledSpectrum L, const SampledWavelengths &lambda) const {
        L = SafeDiv(L, lambda.PDF());
        RGB sum(0, 0, 0);
        for (int i = 0; i < NSpectrumSamples; ++i) sum += Response(lambda[i]) * L[i];
        return imagingRatio / NSpectrumSamples * sum;
    }

    Float ImagingRatio() const { return imagingRatio; }
    std::string ToString() const;

    SquareMatrix<3> XYZFromSensorRGB;

  private:
    // (r_bar, g_bar, b_bar) at the nearest integer wavelength, zero outside the table.
    RGB Response(Float lambda) const {
        if (!(lambda >= 0)) return RGB(0, 0, 0);
        size_t offset = size_t(int(lambda + 0.5f)) - size_t(r_bar.lambdaMin);
        return offset < response.size() ? response[offset] : RGB(0, 0, 0);
    }
    void InterleaveResponse();

    DenselySampledSpectrum r_bar, g_bar, b_bar;
    std::vector<RGB> response;  // r_bar, g_bar, b_bar interleaved
    Float imagingRatio;
};

}  // namespace pbrt
