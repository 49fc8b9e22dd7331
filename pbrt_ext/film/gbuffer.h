// The geometric channels of pbrt-v4's GBufferFilm, beside the film's RGB: per pixel, the
// filter-weighted averages over the camera samples that saw a surface of its position P, normal
// N, shading normal Ns, (u, v), the depth slopes dzdx and dzdy, the albedo, and the variance of
// the samples' sensor RGB, written as pbrt-v4 names the EXR channels. Geometry is in camera
// space (pbrt-v4's default "coordinatesystem") or world space.
#pragma once

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <cstddef>
#include <span>
#include <vector>

namespace pbrt {

// The first surface a camera ray sees that has a material (pbrt-v4's VisibleSurface), in the
// g-buffer's output space; normals face the ray's origin.
struct VisibleSurface {
    Point3f p;
    Normal3f n, ns;
    Point2f uv;
    Vector3f dpdx, dpdy;
    SampledSpectrum albedo = SampledSpectrum(0.f);  // the BSDF's directional albedo toward wo
};

// pbrt-v4's VarianceEstimator (Welford's running mean and sum of squared deviations).
struct VarianceEstimator {
    void Add(double x) {
        ++n;
        double delta = x - mean;
        mean += delta / double(n);
        s += delta * (x - mean);
    }
    double Variance() const { return n > 1 ? s / double(n - 1) : 0; }
    double RelativeVariance() const { return n < 1 || mean == 0 ? 0 : Variance() / mean; }
    int64_t n = 0;
    double mean = 0, s = 0;
};

class GBufferChannels {
  public:
    GBufferChannels(size_t nPixels, bool cameraSpace) : pixels(nPixels), cameraSpace(cameraSpace) {}
    static constexpr size_t BytesPerPixel();
    bool CameraSpace() const { return cameraSpace; }

    // A camera sample's clamped sensor RGB and filter weight, and what it saw; the albedo as RGB
    // in colorSpace under its illuminant, as pbrt-v4 converts it.
    void Add(size_t pixel, RGB sensorRGB, Float weight, const VisibleSurface &surface,
             const SampledWavelengths &lambda, const RGBColorSpace &colorSpace);
    // Every channel of the pixels in order. weightSums: each pixel's filter weights over all its
    // samples, which pbrt-v4 divides the albedo by.
    std::vector<ImageExtraChannel> Channels(std::span<const double> weightSums) const;

  private:
    struct Pixel {
        double gBufferWeight = 0;
        double p[3] = {0, 0, 0}, n[3] = {0, 0, 0}, ns[3] = {0, 0, 0}, uv[2] = {0, 0};
        double dzdx = 0, dzdy = 0, albedo[3] = {0, 0, 0};
        VarianceEstimator variance[3];
    };
    std::vector<Pixel> pixels;
    bool cameraSpace;
};

constexpr size_t GBufferChannels::BytesPerPixel() { return sizeof(Pixel); }

}  // namespace pbrt
