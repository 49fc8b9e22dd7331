// The first two moments of each pixel's sample luminances, for comparing two estimators of the
// same image by their variance (guiding.h's trial of guiding against path tracing). A pixel
// belongs to one tile, which one thread renders at a time, so no two threads add to an entry at
// once, and each pixel's sums are taken in sample order: the same for any thread count.
#pragma once

#include "pbrt_ext/util/bounds.h"

#include <cstddef>
#include <vector>

namespace pbrt {

class SampleMoments {
  public:
    explicit SampleMoments(const Bounds2i &pixels)
        : pixels(pixels), count(size_t(pixels.Area())), sum(count.size()), sumOfSquares(count.size()) {}

    void Add(Point2i p, double y) {
        const size_t i = size_t(p.y - pixels.pMin.y) * size_t(pixels.pMax.x - pixels.pMin.x) +
                         size_t(p.x - pixels.pMin.x);
        ++count[i];
        sum[i] += y;
        sumOfSquares[i] += y * y;
    }

    // How estimator a compares with estimator b of the same image, given the cost of a sample of
    // each: the variance of one sample of each, relative to the square of the pixel's value
    // (estimated by the mean of both around it, SampleMoments.cpp says why) plus 0.01, as relMSE
    // weighs errors, averaged over the pixels where each took at least two samples; and how sure
    // it is that a is the less efficient (the larger variance times cost): the mean difference
    // of the two products over its standard error, from the spread of its means over blocks of
    // kBlock × kBlock pixels. a and b must cover the same pixels.
    struct Comparison {
        double varianceA = 0, varianceB = 0;
        double z = 0;
        // a's efficiency (1 / (variance × cost)) over b's.
        double Efficiency(double costA, double costB) const {
            return varianceB * costB / (varianceA * costA);
        }
    };
    static constexpr int kBlock = 8;
    static Comparison Compare(const SampleMoments &a, double costA, const SampleMoments &b, double costB);

  private:
    Bounds2i pixels;
    std::vector<double> count, sum, sumOfSquares;
};

}  // namespace pbrt
