#include "pbrt_ext/film/film.h"

#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace pbrt {

namespace {
std::string BoundsString(const Bounds2i &b) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "[ %d, %d ] - [ %d, %d ]", b.pMin.x, b.pMin.y, b.pMax.x, b.pMax.y);
    return buf;
}
}  // namespace

Bounds2i PixelBoundsFromCropWindow(Point2i fullResolution, Bounds2f cropWindow) {
    Bounds2f crop(Point2f(Clamp(cropWindow.pMin.x, 0, 1), Clamp(cropWindow.pMin.y, 0, 1)),
                  Point2f(Clamp(cropWindow.pMax.x, 0, 1), Clamp(cropWindow.pMax.y, 0, 1)));
    Bounds2i bounds(Point2i(int(std::ceil(fullResolution.x * crop.pMin.x)), int(std::ceil(fullResolution.y * crop.pMin.y))),
                    Point2i(int(std::ceil(fullResolution.x * crop.pMax.x)), int(std::ceil(fullResolution.y * crop.pMax.y))));
    if (bounds.IsEmpty())
        throw std::runtime_error("film: the crop window covers no pixel (pixel bounds " + BoundsString(bounds) + ")");
    return bounds;
}

RGBFilm::RGBFilm(Point2i fullResolution, Bounds2i pixelBounds, Filter filter, std::string filename,
                 Float maxComponentValue, std::optional<PixelSensor> sensor,
                 const RGBColorSpace *colorSpace, Float diagonal)
    : fullResolution(fullResolution), pixelBounds(pixelBounds), filter(std::move(filter)),
      filename(std::move(filename)), maxComponentValue(maxComponentValue), diagonal(diagonal),
      sensor(sensor ? *sensor : PixelSensor::Create("cie1931", 100, 0, 1, RGBColorSpace::sRGB())),
      colorSpace(colorSpace ? colorSpace : &RGBColorSpace::sRGB()),
      outputRGBFromSensorRGB(this->colorSpace->RGBFromXYZ * this->sensor.XYZFromSensorRGB),
      invFilterIntegral(1 / this->filter.Integral()) {
    if (fullResolution.x < 1 || fullResolution.y < 1)
        throw std::runtime_error("film: the resolution must be positive, not " + std::to_string(fullResolution.x) +
                                 "x" + std::to_string(fullResolution.y));
    Bounds2i full(Point2i(0, 0), fullResolution);
    if (pixelBounds.IsEmpty() || Intersect(pixelBounds, full) != pixelBounds)
        throw std::runtime_error("film: pixel bounds " + BoundsString(pixelBounds) +
                                 " are empty or outside the image " + BoundsString(full));
    pixels.resize(size_t(pixelBounds.Area()));
}

void RGBFilm::EnableSplats(bool perThreadSums) {
    size_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    threadSplatsEnabled = perThreadSums && 3 * sizeof(double) * pixels.size() * threads <= kThreadSplatBytes;
    if (!threadSplatsEnabled) splats.resize(3 * pixels.size());
}

// The pixels whose centers lie within the filter's radius of pFilm.
Bounds2i RGBFilm::SplatBounds(Point2f pFilm) const {
    Point2f pDiscrete = pFilm + Vector2f(0.5f, 0.5f);
    Vector2f radius = filter.Radius();
    Bounds2i splatBounds(Point2i(int(std::floor(pDiscrete.x - radius.x)), int(std::floor(pDiscrete.y - radius.y))),
                         Point2i(int(std::floor(pDiscrete.x + radius.x)) + 1,
                                 int(std::floor(pDiscrete.y + radius.y)) + 1));
    return Intersect(splatBounds, pixelBounds);
}

double *RGBFilm::ThreadSplatSums() {
    if (!threadSplatsEnabled)
        return nullptr;
    std::vector<double> &sums = threadSplats.local();
    if (sums.empty()) sums.resize(3 * pixels.size());
    return sums.data();
}

void RGBFilm::PrefetchSplat(Point2f pFilm) {
    Bounds2i splatBounds = SplatBounds(pFilm);
    if (splatBounds.IsEmpty())
        return;
    const double *own = ThreadSplatSums();
    constexpr size_t kDoublesPerCacheLine = 64 / sizeof(double);
    for (int y = splatBounds.pMin.y; y < splatBounds.pMax.y; ++y) {
        size_t first = 3 * PixelIndex(Point2i(splatBounds.pMin.x, y));
        size_t last = 3 * PixelIndex(Point2i(splatBounds.pMax.x - 1, y)) + 2;
        for (size_t i = first; i <= last; i += kDoublesPerCacheLine)
            __builtin_prefetch(own ? &own[i] : static_cast<const void *>(&splats[i]), 1);
        __builtin_prefetch(own ? &own[last] : static_cast<const void *>(&splats[last]), 1);
    }
}

void RGBFilm::AddSplat(Point2f pFilm, const SampledSpectrum &L, const SampledWavelengths &lambda) {
    SplatInto(pFilm, L, lambda, ThreadSplatSums());
}

void RGBFilm::AddSplat(Point2f pFilm, const SampledSpectrum &L, const SampledWavelengths &lambda,
                       std::vector<double> &sums) {
    if (sums.empty()) sums.resize(3 * pixels.size());
    SplatInto(pFilm, L, lambda, sums.data());
}

void RGBFilm::AddSplatSums(const std::vector<double> &sums) {
    if (sums.empty())
        return;
    double *own = ThreadSplatSums();
    for (size_t i = 0; i < sums.size(); ++i) {
        if (own)
            own[i] += sums[i];
        else
            splats[i].Add(sums[i]);
    }
}

void RGBFilm::SplatInto(Point2f pFilm, const SampledSpectrum &L, const SampledWavelengths &lambda,
                        double *own) {
    Bounds2i splatBounds = SplatBounds(pFilm);
    if (splatBounds.IsEmpty())
        return;
    RGB rgb = ClampedSensorRGB(L, lambda);
    // The filter is separable: its values along each axis, once (on the stack unless the filter
    // is very wide).
    constexpr int kStackWidth = 16;
    Vector2i extent = splatBounds.Diagonal();
    Float wxStack[kStackWidth], wyStack[kStackWidth];
    std::vector<Float> wxHeap, wyHeap;
    Float *wx = wxStack, *wy = wyStack;
    if (extent.x > kStackWidth) wx = (wxHeap.resize(size_t(extent.x)), wxHeap.data());
    if (extent.y > kStackWidth) wy = (wyHeap.resize(size_t(extent.y)), wyHeap.data());
    for (int i = 0; i < extent.x; ++i)
        wx[i] = filter.Evaluate1D(0, pFilm.x - (splatBounds.pMin.x + i) - 0.5f);
    for (int j = 0; j < extent.y; ++j)
        wy[j] = filter.Evaluate1D(1, pFilm.y - (splatBounds.pMin.y + j) - 0.5f) * invFilterIntegral;
    for (int j = 0; j < extent.y; ++j)
        for (int i = 0; i < extent.x; ++i) {
            Float wt = wx[i] * wy[j];
            if (wt == 0)
                continue;
            size_t index = PixelIndex(Point2i(splatBounds.pMin.x + i, splatBounds.pMin.y + j));
            for (int c = 0; c < 3; ++c) {
                double value = double(wt) * double(rgb[c]);
                if (own)
                    own[3 * index + c] += value;
                else
                    splats[3 * index + c].Add(value);
            }
            if (buckets) buckets->AddSplat(index, L, lambda, wt, maxComponentValue);
        }
}

Image RGBFilm::GetImage() const {
    Vector2i size = pixelBounds.Diagonal();
    Image image(Point2i(size.x, size.y));
    for (Point2i p : pixelBounds) {
        RGB rgb = GetPixelRGB(p);
        Point2i q(p.x - pixelBounds.pMin.x, p.y - pixelBounds.pMin.y);
        for (int c = 0; c < 3; ++c) image.SetChannel(q, c, rgb[c]);
    }
    return image;
}

void RGBFilm::WriteImage(ImageMetadata metadata) const {
    metadata.fullResolution = fullResolution;
    metadata.pixelBounds = pixelBounds;
    metadata.colorSpace = colorSpace;
    std::vector<ImageExtraChannel> channels;
    if (buckets) {
        // pbrt-v4's spectral film's attributes (OpenEXR's spectral layout).
        metadata.extra["spectralLayoutVersion"] = "1.0";
        metadata.extra["emissiveUnits"] = "W.m^-2.sr^-1";
        channels = buckets->Channels(splatScale);
    }
    if (gbuffer) {
        std::vector<double> weightSums(pixels.size());
        for (size_t i = 0; i < pixels.size(); ++i) weightSums[i] = pixels[i].weightSum;
        channels = gbuffer->Channels(weightSums);
    }
    GetImage().Write(filename, metadata, channels);
}

std::string RGBFilm::ToString() const {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%g", maxComponentValue);
    return "[ RGBFilm fullResolution: [ " + std::to_string(fullResolution.x) + ", " +
           std::to_string(fullResolution.y) + " ] pixelBounds: " + BoundsString(pixelBounds) +
           " filter: " + filter.ToString() + " filename: \"" + filename + "\" maxComponentValue: " + buf + " ]";
}

}  // namespace pbrt
