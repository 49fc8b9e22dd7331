#include "pbrt_ext/film/sensor.h"

#include "pbrt_ext/spectra/sensordata.h"
#include "pbrt_ext/util/whitebalance.h"

#include <array>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pbrt {

namespace {

// The responses b1, b2, b3 to reflectance refl lit by illum, relative to b2's response to illum
// itself (pbrt-v4's PixelSensor::ProjectReflectance): a white reflector gives 1 in the middle
// channel whatever the illuminant's scale. Sums over integer wavelengths in [Lambda_min,
// Lambda_max].
template <typename Illum, typename B1, typename B2, typename B3>
std::array<Float, 3> ProjectReflectance(const Spectrum &refl, const Illum &illum, const B1 &b1,
                                        const B2 &b2, const B3 &b3) {
    double sum[3] = {}, b2Integral = 0;
    for (int lambda = int(Lambda_min); lambda <= int(Lambda_max); ++lambda) {
        Float l = Float(lambda);
        double i = illum(l), ri = refl(l) * i;
        b2Integral += b2(l) * i;
        sum[0] += b1(l) * ri;
        sum[1] += b2(l) * ri;
        sum[2] += b3(l) * ri;
    }
    return {Float(sum[0] / b2Integral), Float(sum[1] / b2Integral), Float(sum[2] / b2Integral)};
}

}  // namespace

PixelSensor::PixelSensor(const Spectrum &r, const Spectrum &g, const Spectrum &b,
                         const RGBColorSpace &outputColorSpace, const Spectrum &sensorIllum,
                         Float imagingRatio)
    : r_bar(DenselySample(r)), g_bar(DenselySample(g)), b_bar(DenselySample(b)), imagingRatio(imagingRatio) {
    InterleaveResponse();
    std::span<const Spectrum, NSwatchReflectances> swatches = SwatchReflectances();

    // The camera's view of each swatch under the sensor's illuminant.
    Float rgbCamera[NSwatchReflectances][3];
    for (int i = 0; i < NSwatchReflectances; ++i) {
        std::array<Float, 3> rgb = ProjectReflectance(swatches[size_t(i)], sensorIllum, r_bar,
                                                      g_bar, b_bar);
        for (int c = 0; c < 3; ++c) rgbCamera[i][c] = rgb[size_t(c)];
    }

    // The swatches' XYZ under the output illuminant, as the targets. Both projections are
    // relative (to the camera's green and to Y respectively, each of its own illuminant), so
    // the targets are rescaled by Y / green of the sensor illuminant: then the fitted matrix
    // maps absolute camera RGB to absolute XYZ, and a sensor of any gain keeps luminance.
    double sensorWhiteG = 0, sensorWhiteY = 0;
    for (int lambda = int(Lambda_min); lambda <= int(Lambda_max); ++lambda) {
        Float l = Float(lambda), i = sensorIllum(l);
        sensorWhiteG += double(i) * g_bar(l);
        sensorWhiteY += double(i) * Spectra::Y()(l);
    }
    Float xyzOutput[NSwatchReflectances][3];
    for (int i = 0; i < NSwatchReflectances; ++i) {
        std::array<Float, 3> xyz = ProjectReflectance(swatches[size_t(i)], outputColorSpace.illuminant,
                                                      Spectra::X(), Spectra::Y(), Spectra::Z());
        for (int c = 0; c < 3; ++c)
            xyzOutput[i][c] = Float(xyz[size_t(c)] * (sensorWhiteY / sensorWhiteG));
    }

    pstd::optional<SquareMatrix<3>> m =
        LinearLeastSquares(rgbCamera, xyzOutput, NSwatchReflectances);
    if (!m)
        throw std::invalid_argument(
            "PixelSensor: the sensor's XYZ-from-RGB matrix could not be fitted (its responses "
            "are linearly dependent on the swatches)");
    XYZFromSensorRGB = *m;
}

PixelSensor::PixelSensor(const RGBColorSpace &outputColorSpace,
                         const pstd::optional<Spectrum> &sensorIllum, Float imagingRatio)
    : r_bar(Spectra::X()), g_bar(Spectra::Y()), b_bar(Spectra::Z()), imagingRatio(imagingRatio) {
    InterleaveResponse();
    if (sensorIllum)
        XYZFromSensorRGB = WhiteBalance(SpectrumToXYZ(*sensorIllum).xy(), outputColorSpace.w);
}

void PixelSensor::InterleaveResponse() {
    assert(r_bar.lambdaMin == g_bar.lambdaMin && r_bar.lambdaMin == b_bar.lambdaMin);
    response.resize(r_bar.values.size());
    for (size_t i = 0; i < response.size(); ++i)
        response[i] = RGB(r_bar.values[i], g_bar.values[i], b_bar.values[i]);
}

PixelSensor PixelSensor::Create(std::string_view sensorName, Float iso, Float whiteBalance,
                                Float exposureTime, const RGBColorSpace &outputColorSpace) {
    if (!(whiteBalance >= 0) || std::isinf(whiteBalance))
        throw std::invalid_argument("PixelSensor: \"whitebalance\" must be a temperature in K "
                                    "(or 0 for none), not " + std::to_string(whiteBalance));
    // A camera is always white balanced; 0 means the pbrt-v4 default of 6500 K for it.
    bool xyz = sensorName == "cie1931";
    if (!xyz && whiteBalance == 0) whiteBalance = 6500;
    Float imagingRatio = exposureTime * iso / 100;

    pstd::optional<Spectrum> sensorIllum;
    if (whiteBalance != 0) sensorIllum = Spectra::D(whiteBalance);
    if (xyz) return PixelSensor(outputColorSpace, sensorIllum, imagingRatio);

    std::string name(sensorName);
    pstd::optional<Spectrum> r = GetSensorResponse(name + "_r"), g = GetSensorResponse(name + "_g"),
                             b = GetSensorResponse(name + "_b");
    if (!r || !g || !b) {
        std::string known = "cie1931";
        for (std::string_view model : SensorModels()) known += ", " + std::string(model);
        throw std::invalid_argument("unknown sensor \"" + name + "\"; expected one of: " + known);
    }
    return PixelSensor(*r, *g, *b, outputColorSpace, *sensorIllum, imagingRatio);
}

PixelSensor PixelSensor::CreateDefault() {
    return Create("cie1931", 100, 0, 1, RGBColorSpace::sRGB());
}

std::string PixelSensor::ToString() const {
    const SquareMatrix<3> &m = XYZFromSensorRGB;
    char buf[320];
    std::snprintf(buf, sizeof(buf),
                  "[ PixelSensor imagingRatio: %g XYZFromSensorRGB: [ [ %g %g %g ] [ %g %g %g ] "
                  "[ %g %g %g ] ] ]",
                  imagingRatio, m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0],
                  m[2][1], m[2][2]);
    return buf;
}

}  // namespace pbrt
