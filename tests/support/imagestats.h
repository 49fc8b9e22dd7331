// Image means and their differences, for end-to-end tests that compare estimators.
#pragma once

#include "pbrt_ext/film/film.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace pbrt {

// A per-channel mean over the pixels and its standard error, with the pixels taken as
// independent estimates.
struct ChannelStatistics {
    double mean[3] = {0, 0, 0}, standardError[3] = {0, 0, 0};

    // |mean| / standardError for channel c.
    double Z(int c) const { return std::abs(mean[c]) / standardError[c]; }
};

// The statistics of value(p), three channels (an RGB, or doubles) per pixel of bounds.
template <typename PixelValue>
ChannelStatistics PixelStatistics(const Bounds2i &bounds, PixelValue value) {
    ChannelStatistics s;
    double sum[3] = {0, 0, 0}, sumSquares[3] = {0, 0, 0}, n = 0;
    for (Point2i p : bounds) {
        const auto rgb = value(p);
        for (int c = 0; c < 3; ++c) {
            sum[c] += double(rgb[c]);
            sumSquares[c] += double(rgb[c]) * double(rgb[c]);
        }
        ++n;
    }
    for (int c = 0; c < 3; ++c) {
        s.mean[c] = sum[c] / n;
        double variance = std::max(0.0, (sumSquares[c] - n * s.mean[c] * s.mean[c]) / (n - 1));
        s.standardError[c] = std::sqrt(variance / n);
    }
    return s;
}

// The film's per-channel means and their standard errors.
inline ChannelStatistics ImageStatistics(const RGBFilm &film) {
    return PixelStatistics(film.PixelBounds(), [&](Point2i p) { return film.GetPixelRGB(p); });
}

// The per-channel mean over the pixels of film a minus film b, and its standard error: of the
// same scene, two unbiased estimators differ by noise alone, and the difference's mean is then
// within a few standard errors of 0.
using ChannelDifference = ChannelStatistics;

inline ChannelDifference MeanDifference(const RGBFilm &a, const RGBFilm &b) {
    return PixelStatistics(a.PixelBounds(), [&](Point2i p) {
        RGB ra = a.GetPixelRGB(p), rb = b.GetPixelRGB(p);
        return std::array<double, 3>{double(ra[0]) - double(rb[0]), double(ra[1]) - double(rb[1]),
                                     double(ra[2]) - double(rb[2])};
    });
}

// The standard error of channel c's mean over the pixels, the pixels taken as independent.
inline double StandardErrorOfMean(const RGBFilm &film, int c) {
    return ImageStatistics(film).standardError[c];
}

// The per-channel mean over the pixels.
inline RGB MeanRGB(const RGBFilm &film) {
    ChannelStatistics s = ImageStatistics(film);
    return RGB(Float(s.mean[0]), Float(s.mean[1]), Float(s.mean[2]));
}

}  // namespace pbrt
