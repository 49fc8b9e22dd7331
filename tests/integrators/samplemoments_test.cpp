// The per-pixel moments that guiding's trial compares estimators by (integrators/guiding.h): the
// relative variances are the unbiased sample variances over the squared pixel value plus 0.01;
// a single sample far brighter than its pixel's others counts with its whole square, not weighed
// down by the mean it raised; how sure the comparison is follows the spread over blocks (certain
// where every block agrees, undecided where half the image says one thing and half the other);
// and two sets of moments of different pixels are refused. Compared with the path tracer as guided
// samples estimate it (integrators/unguidedmoment.h), the path tracer's variance is the mean of
// the estimates of its second moment less an unbiased estimate of the squared mean: the sample
// variance where each estimate is its own sample's square (no guiding). The sums are floats:
// expected values hold to their rounding (1e-6 relative).
#include "pbrt_ext/integrators/samplemoments.h"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace pbrt;

namespace {

const Bounds2i kPixels(Point2i(0, 0), Point2i(32, 32));

// Every pixel of kPixels takes the samples values.
SampleMoments Uniform(std::initializer_list<double> values) {
    SampleMoments moments(kPixels);
    for (Point2i p : kPixels)
        for (double v : values) moments.Add(p, v);
    return moments;
}

TEST(SampleMoments, RelativeVariancesAreSampleVariancesOverTheSquaredMean) {
    // Both have mean 1 everywhere; the sums of squared deviations are 1 and 4 over 3 degrees of
    // freedom.
    SampleMoments::Comparison c = SampleMoments::Compare(Uniform({0.5, 1.5, 0.5, 1.5}), 1, Uniform({0, 2, 0, 2}), 1);
    EXPECT_NEAR(c.varianceA, (1.0 / 3) / 1.01, 1e-6);
    EXPECT_NEAR(c.varianceB, (4.0 / 3) / 1.01, 1e-6);
    EXPECT_NEAR(c.Efficiency(1, 1), 4, 1e-5);
    EXPECT_NEAR(c.Efficiency(5, 1), 0.8, 1e-6);
}

TEST(SampleMoments, PixelsThatDoNotVaryAreEquallyEfficient) {
    // A crop window's pixels (not from (0, 0)), constant: no variance, an efficiency of 1, no z.
    const Bounds2i crop(Point2i(5, 7), Point2i(37, 39));
    SampleMoments a(crop), b(crop);
    for (Point2i p : crop)
        for (int i = 0; i < 2; ++i) {
            a.Add(p, 0.25f);
            b.Add(p, 0.25f);
        }
    SampleMoments::Comparison c = SampleMoments::Compare(a, 2, b, 1);
    EXPECT_EQ(c.varianceA, 0);
    EXPECT_EQ(c.varianceB, 0);
    EXPECT_EQ(c.Efficiency(2, 1), 1);
    EXPECT_EQ(c.z, 0);
}

TEST(SampleMoments, EveryBlockAgreeingMakesTheComparisonCertain) {
    const SampleMoments a = Uniform({0.5, 1.5, 0.5, 1.5}), b = Uniform({0, 2, 0, 2});
    // The same difference of variance times cost in every block: no spread but rounding's, a z
    // of the sign of a's excess beyond any threshold.
    EXPECT_LT(SampleMoments::Compare(a, 1, b, 1).z, -1e6);
    EXPECT_GT(SampleMoments::Compare(a, 5, b, 1).z, 1e6);
}

TEST(SampleMoments, HalvesThatDisagreeLeaveTheComparisonUndecided) {
    // a is the noisier on the left half, b on the right, by the same amounts.
    SampleMoments a(kPixels), b(kPixels);
    for (Point2i p : kPixels) {
        const bool left = p.x < 16;
        for (double v : {0.5, 1.5, 0.5, 1.5}) a.Add(p, left ? 2 * v - 1 : v);
        for (double v : {0.5, 1.5, 0.5, 1.5}) b.Add(p, left ? v : 2 * v - 1);
    }
    SampleMoments::Comparison c = SampleMoments::Compare(a, 1, b, 1);
    EXPECT_NEAR(c.varianceA, c.varianceB, 1e-6);
    EXPECT_NEAR(c.z, 0, 1e-3);
}

TEST(SampleMoments, ABrightSampleCountsWithItsWholeSquare) {
    SampleMoments dark = Uniform({0.1, 0.1, 0.1, 0.1}), firefly(kPixels);
    for (Point2i p : kPixels)
        for (int i = 0; i < 4; ++i) firefly.Add(p, p == Point2i(16, 16) && i == 3 ? 100 : 0.1);
    SampleMoments::Comparison c = SampleMoments::Compare(dark, 1, firefly, 1);
    EXPECT_NEAR(c.varianceA, 0, 1e-6);  // a constant's sums in floats: 2.6e-8, not 0
    // The pixel's sample variance over (the square of the mean of the 7 x 7 pixels around it,
    // 8 samples each, plus 0.01), averaged over the 1024 pixels. Weighed by its own pixel's mean
    // (12.59) instead, it would be 0.015.
    const double mean = 0.1 + (100 - 0.1) / (49 * 8), sampleMean = (3 * 0.1 + 100) / 4;
    const double variance = (3 * (0.1 - sampleMean) * (0.1 - sampleMean) + (100 - sampleMean) * (100 - sampleMean)) / 3;
    const double expected = variance / (mean * mean + 0.01) / 1024;
    EXPECT_NEAR(c.varianceB, expected, 1e-6 * expected);
    EXPECT_GT(c.varianceB, 10);
}

// Every pixel of kPixels takes the samples values, each with the estimate pathSecondMoment of
// the path tracer's second moment.
SampleMoments UniformGuided(std::initializer_list<double> values, double pathSecondMoment) {
    SampleMoments moments(kPixels, true);
    for (Point2i p : kPixels)
        for (double v : values) moments.Add(p, v, pathSecondMoment);
    return moments;
}

TEST(SampleMoments, ThePathTracersVarianceIsItsSecondMomentLessTheSquaredMean) {
    // Mean 1, sample variance 1/3: the squared mean's unbiased estimate is 1 - (1/3) / 4.
    const SampleMoments guided = UniformGuided({0.5, 1.5, 0.5, 1.5}, 4);
    SampleMoments::Comparison c = SampleMoments::CompareWithPath(guided, 2, 1);
    EXPECT_NEAR(c.varianceA, (1.0 / 3) / 1.01, 1e-6);
    EXPECT_NEAR(c.varianceB, (4 - (1 - 1.0 / 12)) / 1.01, 1e-6);
    EXPECT_LT(c.z, -1e6);  // every block agrees that path is the less efficient at these costs
}

TEST(SampleMoments, WithoutGuidingThePathTracersVarianceIsTheSamples) {
    SampleMoments own(kPixels, true);
    for (Point2i p : kPixels)
        for (double v : {0.2, 0.9, 0.4, 1.7}) own.Add(p, v, v * v);
    SampleMoments::Comparison c = SampleMoments::CompareWithPath(own, 1, 1);
    EXPECT_NEAR(c.varianceB, c.varianceA, 1e-6 * c.varianceA);
    EXPECT_GT(c.varianceA, 0.1);
}

TEST(SampleMoments, MomentsWithoutEstimatesOfThePathTracerAreRefused) {
    EXPECT_THROW(SampleMoments::CompareWithPath(Uniform({1, 2}), 1, 1), std::invalid_argument);
    // Samples without estimates, added to those with, leave none.
    SampleMoments merged = UniformGuided({1, 2}, 3);
    merged.Add(Uniform({1, 2}));
    EXPECT_FALSE(merged.EstimatesPath());
}

TEST(SampleMoments, RefusesMomentsOfOtherPixels) {
    SampleMoments other(Bounds2i(Point2i(0, 0), Point2i(16, 32)));
    EXPECT_THROW(SampleMoments::Compare(Uniform({1, 2}), 1, other, 1), std::invalid_argument);
}

}  // namespace
