#include "pbrt_ext/integrators/samplemoments.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pbrt {

namespace {

// The mean of a and b's samples in the square of side 2 kRadius + 1 around each pixel: an estimate of
// the pixel's value that one sample far brighter than the rest (what path tracing's variance comes
// from where it struggles) does not raise in proportion, as its own pixel's mean would, which would
// weigh it down by its own square.
constexpr int kRadius = 3;

std::vector<double> NeighbourhoodMeans(const Bounds2i &pixels, const std::vector<double> &count,
                                       const std::vector<double> &sum) {
    const int width = pixels.pMax.x - pixels.pMin.x, height = pixels.pMax.y - pixels.pMin.y;
    std::vector<double> means(count.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double n = 0, total = 0;
            for (int v = std::max(0, y - kRadius); v <= std::min(height - 1, y + kRadius); ++v)
                for (int u = std::max(0, x - kRadius); u <= std::min(width - 1, x + kRadius); ++u) {
                    n += count[size_t(v) * width + u];
                    total += sum[size_t(v) * width + u];
                }
            means[size_t(y) * width + x] = n > 0 ? total / n : 0;
        }
    return means;
}

}  // namespace

SampleMoments::Comparison SampleMoments::Compare(const SampleMoments &a, double costA, const SampleMoments &b,
                                                double costB) {
    if (a.pixels != b.pixels)
        throw std::invalid_argument("SampleMoments::Compare: the two cover different pixels");
    std::vector<double> count(a.count.size()), sum(a.count.size());
    for (size_t i = 0; i < count.size(); ++i) {
        count[i] = a.count[i] + b.count[i];
        sum[i] = a.sum[i] + b.sum[i];
    }
    const std::vector<double> means = NeighbourhoodMeans(a.pixels, count, sum);
    const int width = a.pixels.pMax.x - a.pixels.pMin.x, height = a.pixels.pMax.y - a.pixels.pMin.y;
    const int blocksX = (width + kBlock - 1) / kBlock, blocksY = (height + kBlock - 1) / kBlock;
    // Per block: the sum of a's variance times cost less b's, and the pixels counted.
    std::vector<double> blockDifference(size_t(blocksX) * blocksY), blockPixels(blockDifference.size());
    Comparison comparison;
    double pixelsCounted = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x;
            const double na = a.count[i], nb = b.count[i];
            if (na < 2 || nb < 2)
                continue;
            const double weight = 1 / (means[i] * means[i] + 0.01);
            // The unbiased sample variance of each.
            const double va = weight * (a.sumOfSquares[i] - a.sum[i] * a.sum[i] / na) / (na - 1);
            const double vb = weight * (b.sumOfSquares[i] - b.sum[i] * b.sum[i] / nb) / (nb - 1);
            comparison.varianceA += va;
            comparison.varianceB += vb;
            ++pixelsCounted;
            const size_t block = size_t(y / kBlock) * blocksX + x / kBlock;
            blockDifference[block] += costA * va - costB * vb;
            ++blockPixels[block];
        }
    if (pixelsCounted == 0)
        return comparison;
    comparison.varianceA /= pixelsCounted;
    comparison.varianceB /= pixelsCounted;
    double blocks = 0, mean = 0, meanOfSquares = 0;
    for (size_t j = 0; j < blockDifference.size(); ++j) {
        if (blockPixels[j] == 0)
            continue;
        const double m = blockDifference[j] / blockPixels[j];
        ++blocks;
        mean += m;
        meanOfSquares += m * m;
    }
    mean /= blocks;
    meanOfSquares /= blocks;
    if (blocks < 2)
        return comparison;  // z = 0: no spread to judge by
    const double standardError = std::sqrt(std::max(0.0, meanOfSquares - mean * mean) * blocks / (blocks - 1) / blocks);
    comparison.z = standardError > 0 ? mean / standardError
                                     : (mean > 0 ? std::numeric_limits<double>::infinity()
                                                 : mean < 0 ? -std::numeric_limits<double>::infinity() : 0);
    return comparison;
}

}  // namespace pbrt
