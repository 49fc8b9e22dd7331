// Image means and their differences, for end-to-end tests that compare estimators.
#pragma once

#include "pbrt_ext/film/film.h"

#include <cmath>

namespace pbrt {

// The per-channel mean over the pixels of film a minus film b, and its standard error with the
// pixels taken as independent: of the same scene, two unbiased estimators differ by noise alone,
// and the difference's mean is then within a few standard errors of 0.
struct ChannelDifference {
    double mean[3] = {0, 0, 0}, standardError[3] = {0, 0, 0};

    // |mean| / standardError for channel c.
    double Z(int c) const { return std::abs(mean[c]) / standardError[c]; }
};

inline ChannelDifference MeanDifference(const RGBFilm &a, const RGBFilm &b) {
    ChannelDifference d;
    double sum[3] = {0, 0, 0}, sumSquares[3] = {0, 0, 0}, n = 0;
    for (Point2i p : a.PixelBounds()) {
        RGB ra = a.GetPixelRGB(p), rb = b.GetPixelRGB(p);
        for (int c = 0; c < 3; ++c) {
            double x = double(ra[c]) - double(rb[c]);
            sum[c] += x;
            sumSquares[c] += x * x;
        }
        ++n;
    }
    for (int c = 0; c < 3; ++c) {
        d.mean[c] = sum[c] / n;
        double variance = (sumSquares[c] - n * d.mean[c] * d.mean[c]) / (n - 1);
        d.standardError[c] = std::sqrt(variance / n);
    }
    return d;
}

// The standard error of channel c's mean over the pixels, the pixels taken as independent.
inline double StandardErrorOfMean(const RGBFilm &film, int c) {
    double sum = 0, sumSquares = 0, n = 0;
    for (Point2i p : film.PixelBounds()) {
        double x = film.GetPixelRGB(p)[c];
        sum += x;
        sumSquares += x * x;
        ++n;
    }
    double mean = sum / n;
    return std::sqrt((sumSquares - n * mean * mean) / (n - 1) / n);
}

// The per-channel mean over the pixels.
inline RGB MeanRGB(const RGBFilm &film) {
    double sum[3] = {0, 0, 0}, n = 0;
    for (Point2i p : film.PixelBounds()) {
        RGB rgb = film.GetPixelRGB(p);
        for (int c = 0; c < 3; ++c) sum[c] += rgb[c];
        ++n;
    }
    return RGB(Float(sum[0] / n), Float(sum[1] / n), Float(sum[2] / n));
}

}  // namespace pbrt
