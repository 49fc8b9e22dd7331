// Combining renders by inverse variance (integrators/inversevariance.h): each render's samples
// weigh the inverse of its relative variance of one sample, so that a quiet render outweighs a
// noisy one however many samples each took, its variance never counted below a later render's;
// the film keeps its weight sums; a render of one sample per pixel joins the next; each parity of
// the checkerboard of blocks is weighed by the other's variance; renders that do not vary count
// by sample count. The moments are float sums: expected values hold to 1e-5 relative.
#include "pbrt_ext/integrators/inversevariance.h"

#include <gtest/gtest.h>

#include <initializer_list>

using namespace pbrt;

namespace {

// 2 × 2 blocks of SampleMoments::kBlock pixels: two of each parity.
const Point2i kResolution(16, 16);

RGBFilm MakeFilm() {
    return RGBFilm(kResolution, Bounds2i(Point2i(0, 0), kResolution), BoxFilter(), "unused.exr");
}

bool EvenParity(Point2i p) { return (p.x / SampleMoments::kBlock + p.y / SampleMoments::kBlock) % 2 == 0; }

// Renders into film the samples values to the pixels of even blocks, odd to the others (grey,
// weight 1 each), and ends the render in combination.
void Render(RGBFilm &film, InverseVarianceCombination &combination, std::initializer_list<double> even,
            std::initializer_list<double> odd) {
    SampleMoments moments(film.PixelBounds());
    for (Point2i p : film.PixelBounds())
        for (double v : EvenParity(p) ? even : odd) {
            film.AddSensorRGB(p, RGB(v, v, v), 1);
            moments.Add(p, float(v));
        }
    combination.EndRender(moments);
}

double PixelValue(const RGBFilm &film, Point2i p) {
    const RGBFilm::PixelSums sums = film.GetPixelSums(p);
    return sums.rgb[0] / sums.weight;
}

void ExpectEveryPixel(const RGBFilm &film, double expected, double tolerance) {
    for (Point2i p : film.PixelBounds()) EXPECT_NEAR(PixelValue(film, p), expected, tolerance) << p.x << "," << p.y;
}

// The variance of one sample of a pixel whose samples are values, over its mean squared plus 0.01.
double RelativeVariance(std::initializer_list<double> values) {
    double mean = 0, squares = 0;
    for (double v : values) mean += v / values.size();
    for (double v : values) squares += (v - mean) * (v - mean);
    return squares / (values.size() - 1) / (mean * mean + 0.01);
}

TEST(InverseVarianceCombination, AQuietRenderOutweighsANoisyOne) {
    RGBFilm film = MakeFilm();
    InverseVarianceCombination combination(film);
    const auto noisy = {0.5, 1.5}, quiet = {1.9, 2.1, 2.1, 1.9};
    Render(film, combination, noisy, noisy);
    Render(film, combination, quiet, quiet);
    combination.Finish();
    // Each sample weighs 1 / its render's relative variance: by sample count the pixels would be 5/3.
    const double a = 1 / RelativeVariance(noisy), b = 1 / RelativeVariance(quiet);
    const double expected = (a * (0.5 + 1.5) + b * (1.9 + 2.1 + 2.1 + 1.9)) / (2 * a + 4 * b);
    ASSERT_GT(expected, 1.95);
    for (Point2i p : film.PixelBounds()) {
        EXPECT_NEAR(PixelValue(film, p), expected, 1e-5 * expected) << p.x << "," << p.y;
        EXPECT_EQ(film.GetPixelSums(p).weight, 6) << p.x << "," << p.y;  // the g-buffer's divisor stays the filter weights'
    }
    ASSERT_EQ(combination.Renders().size(), 2u);
    EXPECT_NEAR(combination.Renders()[0].relativeVariance, RelativeVariance(noisy), 1e-6);
    EXPECT_EQ(combination.Renders()[1].samplesPerPixel, 4);
}

TEST(InverseVarianceCombination, EachParityIsWeighedByTheOthersVariance) {
    RGBFilm film = MakeFilm();
    InverseVarianceCombination combination(film);
    const auto noisy = {0.5, 1.5}, quiet = {0.9, 1.1}, second = {1.9, 2.1};
    Render(film, combination, noisy, quiet);
    Render(film, combination, second, second);
    combination.Finish();
    // The first render's even pixels are weighed by the quiet odd pixels' variance, and the odd
    // by the noisy even ones'.
    const double c = 1 / RelativeVariance(second);
    auto expected = [&](double first) { return (first * 2 * 1 + c * 2 * 2) / (first * 2 + c * 2); };
    const double even = expected(1 / RelativeVariance(quiet)), odd = expected(1 / RelativeVariance(noisy));
    ASSERT_GT(odd - even, 0.15);
    for (Point2i p : film.PixelBounds())
        EXPECT_NEAR(PixelValue(film, p), EvenParity(p) ? even : odd, 1e-5) << p.x << "," << p.y;
}

TEST(InverseVarianceCombination, ARendersVarianceIsAtLeastALaterOnes) {
    // A quiet small render, then a noisy larger one (a small render that saw none of the rare
    // bright paths): both weigh the later's variance, that is, by sample count.
    RGBFilm film = MakeFilm();
    InverseVarianceCombination combination(film);
    Render(film, combination, {0.9, 1.1}, {0.9, 1.1});
    Render(film, combination, {1, 3, 1, 3}, {1, 3, 1, 3});
    combination.Finish();
    ExpectEveryPixel(film, 10.0 / 6, 1e-6);
    ASSERT_EQ(combination.Renders().size(), 2u);
    EXPECT_LT(combination.Renders()[0].relativeVariance, combination.Renders()[1].relativeVariance);
}

TEST(InverseVarianceCombination, ARenderOfOneSamplePerPixelJoinsTheNext) {
    RGBFilm film = MakeFilm();
    InverseVarianceCombination combination(film);
    Render(film, combination, {10}, {10});
    EXPECT_TRUE(combination.Renders().empty());
    Render(film, combination, {0.9, 1.1, 1}, {0.9, 1.1, 1});
    combination.Finish();
    // One render of four samples: by count.
    ASSERT_EQ(combination.Renders().size(), 1u);
    EXPECT_EQ(combination.Renders()[0].samplesPerPixel, 4);
    ExpectEveryPixel(film, 3.25, 1e-9);
}

TEST(InverseVarianceCombination, RendersThatDoNotVaryCountBySamples) {
    RGBFilm film = MakeFilm();
    InverseVarianceCombination combination(film);
    Render(film, combination, {1, 1}, {1, 1});
    Render(film, combination, {3, 3, 3, 3}, {3, 3, 3, 3});
    combination.Finish();
    ExpectEveryPixel(film, 7.0 / 3, 1e-9);
}

TEST(InverseVarianceCombination, AFinishWithoutRendersLeavesTheFilmBlack) {
    RGBFilm film = MakeFilm();
    InverseVarianceCombination combination(film);
    combination.Finish();
    for (Point2i p : film.PixelBounds()) EXPECT_EQ(film.GetPixelSums(p).weight, 0) << p.x << "," << p.y;
    EXPECT_EQ(film.GetPixelRGB(Point2i(3, 3)), RGB(0, 0, 0));
}

}  // namespace
