// The RGB film (pbrt-v4's RGBFilm).
//
// A sample's spectral radiance becomes the sensor's RGB (pbrt_ext/film/sensor.h: the CIE 1931 XYZ
// observer by default, or a measured camera, scaled by the imaging ratio exposure time x ISO /
// 100); each pixel accumulates the filter-weighted sum of those and the weight sum; its value is
// their ratio (filter importance sampling, pbrt-v4) taken to the output colour space. Only the
// pixels in pixelBounds (the crop window) exist. AddSample needs no locks as long as concurrent
// threads write distinct pixels, as tiles do.
//
// Splats are what paths traced from the lights contribute (bdpt's and lightpath's t = 1
// strategies): they land wherever their ray meets the film, from any thread, so they go to
// separate sums, added to the pixel's value times the splat scale (pbrt-v4's splatScale: one over
// the light paths per pixel). Each thread adds to sums of its own where all threads' fit in
// kThreadSplatBytes (atomic adds were 3 % of a bdpt render of the Cornell box), else all
// threads to one set of atomic sums; reading a pixel adds the threads' sums up.
#pragma once

#include "pbrt_ext/film/filters.h"
#include "pbrt_ext/film/gbuffer.h"
#include "pbrt_ext/film/sensor.h"
#include "pbrt_ext/film/spectralbuckets.h"
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/atomicsum.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cassert>
#include <optional>
#include <string>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

namespace pbrt {

// The pixels a crop window (fractions of the full resolution) covers, rounded as pbrt-v4 does:
// both corners round up. The window is clamped to [0, 1]^2; an empty result throws
// std::runtime_error.
Bounds2i PixelBoundsFromCropWindow(Point2i fullResolution, Bounds2f cropWindow);

class RGBFilm {
  public:
    // Throws std::runtime_error for a non-positive resolution or pixel bounds that are empty or
    // not inside the full resolution.
    // sensor and colorSpace default to pbrt-v4's: the cie1931 sensor at ISO 100 and exposure 1,
    // and sRGB; diagonal, the sensor's physical diagonal in metres (the realistic camera's),
    // its 35 mm.
    RGBFilm(Point2i fullResolution, Bounds2i pixelBounds, Filter filter, std::string filename,
            Float maxComponentValue = Infinity, std::optional<PixelSensor> sensor = {},
            const RGBColorSpace *colorSpace = nullptr, Float diagonal = 0.035f);

    Point2i FullResolution() const { return fullResolution; }
    Bounds2i PixelBounds() const { return pixelBounds; }
    const Filter &GetFilter() const { return filter; }
    const std::string &GetFilename() const { return filename; }
    const RGBColorSpace &ColorSpace() const { return *colorSpace; }
    const PixelSensor &Sensor() const { return sensor; }
    Float MaxComponentValue() const { return maxComponentValue; }
    Float Diagonal() const { return diagonal; }
    // The output colour space's RGB of the sensor's (GetPixelRGB's last step).
    const SquareMatrix<3> &OutputRGBFromSensorRGB() const { return outputRGBFromSensorRGB; }

    // The wavelengths a camera sample carries (pbrt-v4: visible-importance sampled; uniform over
    // the bands' range where the film has them).
    SampledWavelengths SampleWavelengths(Float u) const {
        return buckets ? buckets->SampleWavelengths(u) : SampledWavelengths::SampleVisible(u);
    }
    // pbrt-v4's spectral film: count bands of [lambdaMin, lambdaMax] nm beside the RGB, written
    // as the EXR's spectral channels; before rendering. Throws std::invalid_argument for a
    // range outside [360, 830] or no band.
    void EnableSpectralBuckets(Float lambdaMin, Float lambdaMax, int count) {
        buckets.emplace(lambdaMin, lambdaMax, count, pixels.size());
    }
    const SpectralBuckets *Buckets() const { return buckets ? &*buckets : nullptr; }
    // pbrt-v4's g-buffer film: geometric channels beside the RGB, from the VisibleSurface each
    // camera sample passes to AddSample; before rendering.
    void EnableGBuffer(bool cameraSpace) { gbuffer.emplace(pixels.size(), cameraSpace); }
    const GBufferChannels *GBuffer() const { return gbuffer ? &*gbuffer : nullptr; }

    // The sensor's RGB of L is scaled down, keeping its hue, so that no channel exceeds
    // maxComponentValue: a rare very bright path then costs bias instead of a firefly. weight
    // is the filter sample's.
    // visibleSurface: what the sample's camera ray saw, for the g-buffer (none: a miss).
    void AddSample(Point2i pPixel, const SampledSpectrum &L, const SampledWavelengths &lambda,
                   Float weight, const VisibleSurface *visibleSurface = nullptr) {
        RGB rgb = ClampedSensorRGB(L, lambda);
        AddSensorRGB(pPixel, rgb, weight);
        if (buckets) buckets->AddSample(PixelIndex(pPixel), L, lambda, weight, maxComponentValue);
        if (gbuffer && visibleSurface)
            gbuffer->Add(PixelIndex(pPixel), rgb, weight, *visibleSurface, lambda, *colorSpace);
    }
    // The sensor's RGB of L, scaled down to maxComponentValue keeping its hue: what AddSample
    // adds.
    RGB ClampedSensorRGB(const SampledSpectrum &L, const SampledWavelengths &lambda) const {
        RGB rgb = sensor.ToSensorRGB(L, lambda);
        Float m = std::max({rgb.r, rgb.g, rgb.b});
        if (m > maxComponentValue) rgb *= maxComponentValue / m;
        return rgb;
    }
    // A sample already in the sensor's RGB (sppm's pixel estimates; not into the bands).
    void AddSensorRGB(Point2i pPixel, RGB rgb, Float weight) {
        assert(InsideExclusive(pPixel, pixelBounds));
        Pixel &pixel = pixels[PixelIndex(pPixel)];
        for (int c = 0; c < 3; ++c) pixel.rgbSum[c] += double(weight) * double(rgb[c]);
        pixel.weightSum += weight;
    }

    // Makes room for splats (24 bytes a pixel, per rendering thread where perThreadSums and they
    // fit); before rendering, from one thread.
    void EnableSplats(bool perThreadSums = true);
    bool HasSplats() const { return !splats.empty() || threadSplatsEnabled; }
    // Spreads L, arriving at the film position pFilm (raster coordinates), over the pixels the
    // filter covers, each by the filter's value there over its integral (pbrt-v4 divides by the
    // integral when it reads the pixel), so that a splat adds what a camera sample of the same
    // radiance would. Thread-safe.
    void AddSplat(Point2f pFilm, const SampledSpectrum &L, const SampledWavelengths &lambda);
    // The same into sums of the caller's own (3 a pixel, sized on first use; not thread-safe),
    // for a render whose splats must add up in one order whatever the threads run: mlt's chains,
    // split into parts that each keep their own sums, which AddSplatSums then adds to the
    // film's in a fixed order, from one thread.
    void AddSplat(Point2f pFilm, const SampledSpectrum &L, const SampledWavelengths &lambda,
                  std::vector<double> &sums);
    void AddSplatSums(const std::vector<double> &sums);
    // Bytes of one set of splat sums (24 a pixel).
    size_t SplatSumsBytes() const { return 3 * sizeof(double) * pixels.size(); }
    // Starts fetching the sums AddSplat(pFilm, ...) will add to. Splats land anywhere on the
    // film, so their sums are rarely cached (at 240x240, bdpt waited on them for two thirds of
    // AddSplat's time): a caller that knows where a splat lands before it has its value (a
    // connection to the camera, before its shadow ray) calls this first to overlap the misses
    // with that work. Only a hint; thread-safe.
    void PrefetchSplat(Point2f pFilm);
    void SetSplatScale(Float scale) { splatScale = scale; }

    // What a pixel has gathered: the filter-weighted sum of the sensor's RGB, the weight sum,
    // and the unscaled splat sums. Samples add to these, so the sums of renders of disjoint
    // sample ranges add up to the sums of one render of them all (filmslice.h).
    struct PixelSums {
        double rgb[3] = {0, 0, 0};
        double weight = 0;
        double splat[3] = {0, 0, 0};

        // The pixel's value, for the film and for a slice alike: the weighted average (black
        // where nothing landed) plus the splats times splatScale, in the output colour space.
        RGB ToOutputRGB(double splatScale, const SquareMatrix<3> &outputRGBFromSensorRGB) const {
            RGB sensorRGB(0, 0, 0);
            if (weight != 0)
                sensorRGB = RGB(Float(rgb[0] / weight), Float(rgb[1] / weight), Float(rgb[2] / weight));
            for (int c = 0; c < 3; ++c) sensorRGB[c] += Float(splatScale * splat[c]);
            return Mul<RGB>(outputRGBFromSensorRGB, sensorRGB);
        }
    };
    PixelSums GetPixelSums(Point2i p) const {
        const size_t index = PixelIndex(p);
        PixelSums sums;
        for (int c = 0; c < 3; ++c) {
            sums.rgb[c] = pixels[index].rgbSum[c];
            if (!splats.empty()) sums.splat[c] = splats[3 * index + c].Load();
        }
        for (const std::vector<double> &own : threadSplats)
            if (!own.empty())
                for (int c = 0; c < 3; ++c) sums.splat[c] += own[3 * index + c];
        sums.weight = pixels[index].weightSum;
        return sums;
    }

    // Replaces the pixel's RGB and weight sums (not its splats): for an image whose samples count
    // otherwise than by their filter weights alone (integrators/inversevariance.h).
    void SetPixelSums(Point2i p, const PixelSums &sums) {
        Pixel &pixel = pixels[PixelIndex(p)];
        for (int c = 0; c < 3; ++c) pixel.rgbSum[c] = sums.rgb[c];
        pixel.weightSum = sums.weight;
    }

    // The weighted average in the output colour space, plus the scaled splats; black where
    // nothing landed.
    RGB GetPixelRGB(Point2i p) const { return GetPixelSums(p).ToOutputRGB(splatScale, outputRGBFromSensorRGB); }

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
    Bounds2i SplatBounds(Point2f pFilm) const;
    // This thread's splat sums (3 a pixel), allocated on first use; null where the splats go
    // to the shared atomic sums.
    double *ThreadSplatSums();
    // Spreads a splat over the pixels its filter covers, into own, or the shared sums if null.
    void SplatInto(Point2f pFilm, const SampledSpectrum &L, const SampledWavelengths &lambda, double *own);

    size_t PixelIndex(Point2i p) const {
        Vector2i o = p - pixelBounds.pMin;
        return size_t(o.y) * size_t(pixelBounds.pMax.x - pixelBounds.pMin.x) + size_t(o.x);
    }

    Point2i fullResolution;
    Bounds2i pixelBounds;
    Filter filter;
    std::string filename;
    Float maxComponentValue;
    Float diagonal;
    std::optional<SpectralBuckets> buckets;
    std::optional<GBufferChannels> gbuffer;
    PixelSensor sensor;
    const RGBColorSpace *colorSpace;
    SquareMatrix<3> outputRGBFromSensorRGB;
    std::vector<Pixel> pixels;
    Float invFilterIntegral;        // splats are spread by the filter's normalized weights
    std::vector<AtomicSum> splats;  // 3 per pixel, or none
    // Or each thread's own, 3 per pixel, made at its first splat.
    static constexpr size_t kThreadSplatBytes = size_t(1) << 28;
    bool threadSplatsEnabled = false;
    tbb::enumerable_thread_specific<std::vector<double>> threadSplats;
    double splatScale = 1;
};

}  // namespace pbrt
