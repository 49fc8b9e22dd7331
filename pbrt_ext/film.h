// The RGB film (pbrt-v4's RGBFilm, reduced: the sensor is the identity on RGB, no splats, no
// output color-space conversion, no imaging-ratio exposure).
//
// Each pixel accumulates the filter-weighted radiance sum and the weight sum of its samples;
// its value is their ratio (filter importance sampling, pbrt-v4). Only the pixels in
// pixelBounds (the crop window) exist. AddSample needs no locks as long as concurrent threads
// write distinct pixels, as tiles do.
#pragma once

#include "pbrt_ext/filters.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/image.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <cassert>
#include <string>
#include <vector>

namespace pbrt {

// The pixels a crop window (fractions of the full resolution) covers, rounded as pbrt-v4 does:
// both corners round up. The window is clamped to [0, 1]^2; an empty result throws
// std::runtime_error.
Bounds2i PixelBoundsFromCropWindow(Point2i fullResolution, Bounds2f cropWindow);

class RGBFilm {
  public:
    // Throws std::runtime_error for a non-positive resolution or pixel bounds that are empty or
    // not inside the full resolution.
    RGBFilm(Point2i fullResolution, Bounds2i pixelBounds, Filter filter, std::string filename,
            Float maxComponentValue = Infinity);

    Point2i FullResolution() const { return fullResolution; }
    Bounds2i PixelBounds() const { return pixelBounds; }
    const Filter &GetFilter() const { return filter; }
    const std::string &GetFilename() const { return filename; }

    // L is scaled down, keeping its hue, so that no channel exceeds maxComponentValue: a rare
    // very bright path then costs bias instead of a firefly. weight is the filter sample's.
    void AddSample(Point2i pPixel, SampledSpectrum L, Float weight) {
        assert(InsideExclusive(pPixel, pixelBounds));
        Float m = L.MaxComponentValue();
        if (m > maxComponentValue) L *= maxComponentValue / m;
        Pixel &pixel = pixels[PixelIndex(pPixel)];
        for (int c = 0; c < 3; ++c) pixel.rgbSum[c] += double(weight) * double(L[c]);
        pixel.weightSum += weight;
    }

    // The weighted average; black where no sample landed.
    SampledSpectrum GetPixelRGB(Point2i p) const {
        const Pixel &pixel = pixels[PixelIndex(p)];
        if (pixel.weightSum == 0) return SampledSpectrum(0.f);
        return SampledSpectrum(Float(pixel.rgbSum[0] / pixel.weightSum), Float(pixel.rgbSum[1] / pixel.weightSum),
                               Float(pixel.rgbSum[2] / pixel.weightSum));
    }

    // The pixels of pixelBounds; its (0, 0) is pixelBounds.pMin.
    Image GetImage() const;
    // To GetFilename(), with metadata's crop fields set from the film (EXR data window).
    void WriteImage(ImageMetadata metadata) const;

    std::string ToString() const;

  private:
    // Sums in double: a pixel may gather millions of samples.
    struct Pixel {
        double rgbSum[3] = {0, 0, 0};
        double weightSum = 0;
    };

    size_t PixelIndex(Point2i p) const {
        Vector2i o = p - pixelBounds.pMin;
        return size_t(o.y) * size_t(pixelBounds.pMax.x - pixelBounds.pMin.x) + size_t(o.x);
    }

    Point2i fullResolution;
    Bounds2i pixelBounds;
    Filter filter;
    std::string filename;
    Float maxComponentValue;
    std::vector<Pixel> pixels;
};

}  // namespace pbrt
