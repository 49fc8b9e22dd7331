// The first two moments of each pixel's sample values (imagetile.h), for comparing two estimators
// of the same image by their variance (guiding.h's trial of guiding against path tracing). Sums
// are floats: a trial adds a few samples per pixel, and at 4K each set is 100 MB. A pixel
// belongs to one tile, which one thread renders at a time, so no two threads add to an entry at
// once, and each pixel's sums are taken in sample order: the same for any thread count.
#pragma once

#include "pbrt_ext/util/bounds.h"

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace pbrt {

class SampleMoments {
  public:
    // Where estimatesPath, also the sums of each sample's estimate of the path tracer's second
    // moment (unguidedmoment.h), for CompareWithPath.
    explicit SampleMoments(const Bounds2i &pixels, bool estimatesPath = false)
        : pixels(pixels), count(size_t(pixels.Area())), sum(count.size()), sumOfSquares(count.size()),
          sumOfPathSecondMoments(estimatesPath ? count.size() : 0) {}

    void Add(Point2i p, float y) {
        const size_t i = Index(p);
        ++count[i];
        sum[i] += y;
        sumOfSquares[i] += y * y;
    }
    void Add(Point2i p, float y, float pathSecondMoment) {
        Add(p, y);
        sumOfPathSecondMoments[Index(p)] += pathSecondMoment;
    }
    bool EstimatesPath() const { return !sumOfPathSecondMoments.empty(); }

    // How estimator a compares with estimator b of the same image, given the cost of a sample of
    // each: the variance of one sample of each, relative to the square of the pixel's value
    // (estimated by the mean of both around it: samplemoments.cpp says why) plus 0.01, as relMSE
    // weighs errors, averaged over the pixels where each took at least two samples; and how sure
    // it is that a is the less efficient (the larger variance times cost): the mean difference
    // of the two products over its standard error, from the spread of its means over blocks of
    // kBlock × kBlock pixels (0 with fewer than two blocks). a and b must cover the same pixels.
    struct Comparison {
        double varianceA = 0, varianceB = 0;
        double z = 0;
        // a's efficiency (1 / (variance × cost)) over b's: 1 where neither varies.
        double Efficiency(double costA, double costB) const;
    };
    static constexpr int kBlock = 8;
    // The parity of the block of the pixel at offset (x, y) from the first: the checkerboard
    // RelativeVarianceByBlockParity splits the pixels by.
    static int BlockParity(int x, int y) { return (x / kBlock + y / kBlock) % 2; }
    static Comparison Compare(const SampleMoments &a, double costA, const SampleMoments &b, double costB);
    // As Compare, a: the guided samples of these moments, b: the path tracer, its variance from
    // the guided samples' estimates of its second moment (EstimatesPath) less the square of the
    // pixel's mean (estimated without bias from the guided samples). That difference is unbiased,
    // not clamped: a pixel's can be negative, and so, with few pixels, can varianceB.
    static Comparison CompareWithPath(const SampleMoments &guided, double costGuided, double costPath);

    // The variance of one sample relative to the pixel's value as Compare's (the value estimated
    // by these moments alone), averaged over the pixels that took two or more samples in the
    // blocks of kBlock × kBlock pixels of each parity (the block's x plus y index, even or odd: a
    // checkerboard); none where a parity has no such pixel.
    std::array<std::optional<double>, 2> RelativeVarianceByBlockParity() const;
    // The samples a pixel took, on average.
    double MeanCount() const;
    // Adds other's samples, of the same pixels, to these; these no longer estimate the path
    // tracer's moments (the trial compares one render's samples, never a sum of renders').
    void Add(const SampleMoments &other);
    const Bounds2i &Pixels() const { return pixels; }

  private:
    size_t Index(Point2i p) const {
        return size_t(p.y - pixels.pMin.y) * size_t(Width()) + size_t(p.x - pixels.pMin.x);
    }
    // Pixel i's unbiased sample variance; i took two or more.
    double SampleVariance(size_t i) const;
    // Pixel i's variance of one sample over (its value squared plus 0.01); i took two or more.
    double RelativeVariance(size_t i, double pixelValue) const;
    // The same for the path tracer, from the estimates of its second moment.
    double PathRelativeVariance(size_t i, double pixelValue) const;
    // The relative variance of one sample at pixel i whose value is given.
    using RelativeVarianceOf = double (SampleMoments::*)(size_t i, double pixelValue) const;
    // a's and b's relative variance (by varianceA of a's moments, varianceB of b's) over the pixels
    // where both took two or more samples, each pixel's value given, and the z of their
    // difference times cost (see Comparison).
    static Comparison CompareBy(const SampleMoments &a, RelativeVarianceOf varianceA, double costA,
                                const SampleMoments &b, RelativeVarianceOf varianceB, double costB,
                                const std::vector<float> &pixelValues);
    int Width() const { return pixels.pMax.x - pixels.pMin.x; }
    int Height() const { return pixels.pMax.y - pixels.pMin.y; }

    Bounds2i pixels;
    std::vector<float> count, sum, sumOfSquares, sumOfPathSecondMoments;
};

}  // namespace pbrt
