#include "pbrt_ext/integrators/samplemoments.h"

#include "pbrt_ext/util/math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pbrt {

namespace {

// The mean of a and b's samples in the square of side 2 kRadius + 1 around each pixel: an
// estimate of the pixel's value that one sample far brighter than the rest (what path tracing's
// variance comes from where it struggles) does not raise in proportion, as its own pixel's mean
// would, which would weigh it down by its own square.
constexpr int kRadius = 3;

// The sums of values over the window of kRadius around each pixel along one axis: x where
// stride is 1, y where it is the width (separable: a box's sum is the sum of its rows' sums).
std::vector<float> WindowSums(const std::vector<float> &values, int width, int height, bool alongX) {
    std::vector<float> sums(values.size());
    const int length = alongX ? width : height, lines = alongX ? height : width;
    const size_t step = alongX ? 1 : size_t(width), lineStep = alongX ? size_t(width) : 1;
    for (int line = 0; line < lines; ++line)
        for (int i = 0; i < length; ++i) {
            float total = 0;
            for (int j = std::max(0, i - kRadius); j <= std::min(length - 1, i + kRadius); ++j)
                total += values[line * lineStep + j * step];
            sums[line * lineStep + i * step] = total;
        }
    return sums;
}

std::vector<float> NeighbourhoodMeans(int width, int height, std::vector<float> count, std::vector<float> sum) {
    count = WindowSums(WindowSums(count, width, height, true), width, height, false);
    sum = WindowSums(WindowSums(sum, width, height, true), width, height, false);
    for (size_t i = 0; i < sum.size(); ++i)
        sum[i] = count[i] > 0 ? sum[i] / count[i] : 0;
    return sum;
}

// How many standard errors the mean of the per-pixel differences is above 0, from the spread of
// their means over blocks of SampleMoments::kBlock pixels on a side.
double BlockZ(const std::vector<float> &difference, const std::vector<float> &counted, int width, int height) {
    const int kBlock = SampleMoments::kBlock;
    const int blocksX = (width + kBlock - 1) / kBlock, blocksY = (height + kBlock - 1) / kBlock;
    std::vector<double> blockSum(size_t(blocksX) * blocksY), blockPixels(blockSum.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * width + x, block = size_t(y / kBlock) * blocksX + x / kBlock;
            blockSum[block] += difference[i];
            blockPixels[block] += counted[i];
        }
    double blocks = 0, mean = 0, meanOfSquares = 0;
    for (size_t j = 0; j < blockSum.size(); ++j) {
        if (blockPixels[j] == 0)
            continue;
        const double m = blockSum[j] / blockPixels[j];
        ++blocks;
        mean += m;
        meanOfSquares += m * m;
    }
    if (blocks < 2)
        return 0;  // no spread to judge by
    mean /= blocks;
    meanOfSquares /= blocks;
    const double standardError = std::sqrt(std::max(0.0, meanOfSquares - mean * mean) / (blocks - 1));
    if (standardError > 0)
        return mean / standardError;
    if (mean == 0)
        return 0;
    return mean > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
}

}  // namespace

double SampleMoments::Comparison::Efficiency(double costA, double costB) const {
    const double a = varianceA * costA, b = varianceB * costB;
    if (a > 0)
        return b / a;
    return b > 0 ? std::numeric_limits<double>::infinity() : 1;
}

double SampleMoments::SampleVariance(size_t i) const {
    const double n = count[i];
    return (sumOfSquares[i] - double(sum[i]) * sum[i] / n) / (n - 1);
}

double SampleMoments::RelativeVariance(size_t i, double pixelValue) const {
    return std::max(0.0, SampleVariance(i)) / (Sqr(pixelValue) + 0.01);
}

double SampleMoments::PathRelativeVariance(size_t i, double pixelValue) const {
    const double n = count[i], mean = sum[i] / n;
    // E[Y^2] less an unbiased estimate of E[Y]^2: the mean's square less its variance.
    const double pathVariance = sumOfPathSecondMoments[i] / n - (mean * mean - SampleVariance(i) / n);
    return pathVariance / (Sqr(pixelValue) + 0.01);
}

SampleMoments::Comparison SampleMoments::CompareBy(const SampleMoments &a, RelativeVarianceOf varianceA, double costA,
                                                  const SampleMoments &b, RelativeVarianceOf varianceB, double costB,
                                                  const std::vector<float> &values) {
    Comparison comparison;
    std::vector<float> difference(values.size()), counted(values.size());
    double pixelsCounted = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        if (a.count[i] < 2 || b.count[i] < 2)
            continue;
        const double va = (a.*varianceA)(i, values[i]), vb = (b.*varianceB)(i, values[i]);
        comparison.varianceA += va;
        comparison.varianceB += vb;
        difference[i] = float(costA * va - costB * vb);
        counted[i] = 1;
        ++pixelsCounted;
    }
    if (pixelsCounted == 0)
        return comparison;
    comparison.varianceA /= pixelsCounted;
    comparison.varianceB /= pixelsCounted;
    comparison.z = BlockZ(difference, counted, a.Width(), a.Height());
    return comparison;
}

SampleMoments::Comparison SampleMoments::Compare(const SampleMoments &a, double costA, const SampleMoments &b,
                                                double costB) {
    if (a.pixels != b.pixels)
        throw std::invalid_argument("SampleMoments::Compare: the two cover different pixels");
    std::vector<float> count(a.count.size()), sum(a.count.size());
    for (size_t i = 0; i < count.size(); ++i) {
        count[i] = a.count[i] + b.count[i];
        sum[i] = a.sum[i] + b.sum[i];
    }
    return CompareBy(a, &SampleMoments::RelativeVariance, costA, b, &SampleMoments::RelativeVariance, costB,
                     NeighbourhoodMeans(a.Width(), a.Height(), std::move(count), std::move(sum)));
}

SampleMoments::Comparison SampleMoments::CompareWithPath(const SampleMoments &guided, double costGuided,
                                                        double costPath) {
    if (!guided.EstimatesPath())
        throw std::invalid_argument("SampleMoments::CompareWithPath: no estimates of the path tracer's moments");
    return CompareBy(guided, &SampleMoments::RelativeVariance, costGuided, guided,
                     &SampleMoments::PathRelativeVariance, costPath,
                     NeighbourhoodMeans(guided.Width(), guided.Height(), guided.count, guided.sum));
}

std::array<std::optional<double>, 2> SampleMoments::RelativeVarianceByBlockParity() const {
    const std::vector<float> values = NeighbourhoodMeans(Width(), Height(), count, sum);
    std::array<double, 2> total{0, 0}, pixelsCounted{0, 0};
    for (int y = 0; y < Height(); ++y)
        for (int x = 0; x < Width(); ++x) {
            const size_t i = size_t(y) * Width() + x;
            if (count[i] < 2)
                continue;
            const int parity = BlockParity(x, y);
            total[parity] += RelativeVariance(i, values[i]);
            ++pixelsCounted[parity];
        }
    std::array<std::optional<double>, 2> variances;
    for (int parity = 0; parity < 2; ++parity)
        if (pixelsCounted[parity] > 0)
            variances[parity] = total[parity] / pixelsCounted[parity];
    return variances;
}

double SampleMoments::MeanCount() const {
    double total = 0;
    for (float n : count) total += n;
    return count.empty() ? 0 : total / double(count.size());
}

void SampleMoments::Add(const SampleMoments &other) {
    if (other.pixels != pixels)
        throw std::invalid_argument("SampleMoments::Add: the two cover different pixels");
    sumOfPathSecondMoments.clear();
    for (size_t i = 0; i < count.size(); ++i) {
        count[i] += other.count[i];
        sum[i] += other.sum[i];
        sumOfSquares[i] += other.sumOfSquares[i];
    }
}

}  // namespace pbrt
