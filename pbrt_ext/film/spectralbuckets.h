// The spectral channels of pbrt-v4's SpectralFilm: per pixel, radiance averaged over nBuckets
// equal bands of [lambdaMin, lambdaMax], beside the film's RGB. Wavelengths are then sampled
// uniformly over that range, so that each band's samples average its radiance without a
// division by their density; the values carry pbrt-v4's factor CIE_Y_integral, which undoes the
// photometric normalization of the lights (a light of 1 nit becomes its spectral radiance).
// The EXR channels are named as pbrt-v4 names them (OpenEXR's spectral layout, "S0.<nm>nm"
// with a decimal comma).
#pragma once

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/util/spectrum.h"

#include <cstddef>
#include <string>
#include <vector>

namespace pbrt {

class SpectralBuckets {
  public:
    // Throws std::invalid_argument unless 360 <= lambdaMin < lambdaMax <= 830 and count >= 1.
    SpectralBuckets(Float lambdaMin, Float lambdaMax, int count, size_t nPixels);

    SampledWavelengths SampleWavelengths(Float u) const {
        return SampledWavelengths::SampleUniform(u, lambdaMin, lambdaMax);
    }
    int BucketOf(Float lambda) const;
    Float BucketCenter(int b) const { return Lerp((b + 0.5f) / count, lambdaMin, lambdaMax); }
    int Count() const { return count; }

    // A camera sample's radiance (scaled so that no wavelength exceeds maxComponentValue) with
    // its filter weight, into the pixel's bands.
    void AddSample(size_t pixel, SampledSpectrum L, const SampledWavelengths &lambda,
                   Float weight, Float maxComponentValue);
    // A splat's radiance (clamped as a sample's) times the pixel's filter weight over the
    // filter's integral: its estimate of each band's average is L over the chance that one of
    // the wavelengths falls in the band. Thread-safe.
    void AddSplat(size_t pixel, SampledSpectrum L, const SampledWavelengths &lambda,
                  Float weight, Float maxComponentValue);
    // The band's average at the pixel: black where no sample fell in it.
    Float Value(size_t pixel, int b, double splatScale) const;
    // Every band as a channel of the pixels in order, named "S0.<centre>nm".
    std::vector<ImageExtraChannel> Channels(double splatScale) const;
    std::string ChannelName(int b) const;

  private:
    Float lambdaMin, lambdaMax;
    int count;
    size_t nPixels;
    std::vector<double> sums, weights, splats;  // count per pixel; splats added atomically
};

}  // namespace pbrt
