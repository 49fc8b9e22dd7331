// Reconstruction filters: pbrt-v4's shapes and closed-form integrals, and filter importance
// sampling that reproduces the filter's weighted averages (what the film computes).
#include "pbrt_ext/film/filters.h"

#include <gtest/gtest.h>

#include <functional>
#include <random>

namespace pbrt {
namespace {

// Midpoint-rule integral of filter * g over the filter's support.
double IntegrateFilter(const Filter &filter, const std::function<double(Point2f)> &g, int n = 800) {
    Vector2f r = filter.Radius();
    double sum = 0, cell = (2.0 * r.x / n) * (2.0 * r.y / n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Point2f p(-r.x + (i + 0.5f) * 2 * r.x / n, -r.y + (j + 0.5f) * 2 * r.y / n);
            sum += filter.Evaluate(p) * g(p) * cell;
        }
    return sum;
}

std::vector<Filter> AllFilters() {
    return {BoxFilter(), GaussianFilter(), MitchellFilter(), TriangleFilter(),
            BoxFilter(Vector2f(1.5f, 0.75f)), GaussianFilter(Vector2f(2, 1), 0.8f),
            MitchellFilter(Vector2f(1.5f, 2.5f), 0.f, 0.5f), TriangleFilter(Vector2f(0.5f, 1.25f))};
}

TEST(Filters, DefaultsArePbrtV4s) {
    Filter f;
    EXPECT_STREQ(f.Name(), "gaussian");
    EXPECT_EQ(f.Radius(), Vector2f(1.5f, 1.5f));
    EXPECT_EQ(f.ToString(), "[ GaussianFilter radius: [ 1.5, 1.5 ] sigma: 0.5 ]");
    EXPECT_EQ(Filter(BoxFilter()).Radius(), Vector2f(0.5f, 0.5f));
    EXPECT_EQ(Filter(MitchellFilter()).Radius(), Vector2f(2, 2));
    EXPECT_EQ(Filter(TriangleFilter()).Radius(), Vector2f(2, 2));
}

TEST(Filters, PointValues) {
    EXPECT_EQ(BoxFilter().Evaluate(Point2f(0.5f, -0.5f)), 1);
    EXPECT_EQ(BoxFilter().Evaluate(Point2f(0.51f, 0)), 0);
    EXPECT_NEAR(GaussianFilter().Evaluate(Point2f(1.5f, 0)), 0, 1e-7f);  // falls to zero at the radius
    EXPECT_EQ(GaussianFilter().Evaluate(Point2f(1.6f, 0)), 0);
    Float m0 = (6 - 2.f / 3) / 6;
    EXPECT_NEAR(MitchellFilter().Evaluate(Point2f(0, 0)), m0 * m0, 1e-6f);
    EXPECT_LT(MitchellFilter().Evaluate(Point2f(1.5f, 0)), 0);  // the negative lobe
    EXPECT_NEAR(MitchellFilter().Evaluate(Point2f(2, 0)), 0, 1e-6f);
    EXPECT_EQ(TriangleFilter().Evaluate(Point2f(1, -0.5f)), 1 * 1.5f);
}

TEST(Filters, IntegralMatchesQuadrature) {
    for (const Filter &f : AllFilters()) {
        double numeric = IntegrateFilter(f, [](Point2f) { return 1.0; });
        EXPECT_NEAR(f.Integral(), numeric, 2e-3 * std::abs(numeric)) << f.ToString();
    }
}

// The film's estimate at a pixel is sum(w g) / sum(w) over filter samples: it must converge to
// the filter-weighted average of g, for test functions g of different shapes.
TEST(Filters, SampledWeightedAveragesMatchTheFilter) {
    const int kSamples = 400000;
    std::vector<std::function<double(Point2f)>> tests = {
        [](Point2f p) { return double(p.x * p.x); },
        [](Point2f p) { return double(std::abs(p.y)); },
        [](Point2f p) { return (p.x > 0.2f && p.y < -0.1f) ? 1.0 : 0.0; },
        [](Point2f p) { return double(p.x + 0.5f * p.y + 2); },
    };
    std::mt19937 rng(1234);
    std::uniform_real_distribution<Float> u(0, 1);
    for (const Filter &f : AllFilters()) {
        std::vector<Point2f> ps(kSamples);
        std::vector<double> ws(kSamples);
        for (int i = 0; i < kSamples; ++i) {
            FilterSample s = f.Sample(Point2f(std::min(u(rng), OneMinusEpsilon), std::min(u(rng), OneMinusEpsilon)));
            ASSERT_LE(std::abs(s.p.x), f.Radius().x) << f.ToString();
            ASSERT_LE(std::abs(s.p.y), f.Radius().y) << f.ToString();
            ASSERT_TRUE(std::isfinite(s.weight));
            ps[i] = s.p;
            ws[i] = s.weight;
        }
        double integral = IntegrateFilter(f, [](Point2f) { return 1.0; });
        for (size_t t = 0; t < tests.size(); ++t) {
            double expected = IntegrateFilter(f, tests[t]) / integral;
            double sw = 0, swg = 0;
            for (int i = 0; i < kSamples; ++i) {
                sw += ws[i];
                swg += ws[i] * tests[t](ps[i]);
            }
            double estimate = swg / sw;
            // Standard error of the ratio estimator, from the residuals.
            double var = 0;
            for (int i = 0; i < kSamples; ++i) var += Sqr(ws[i] * (tests[t](ps[i]) - estimate));
            double se = std::sqrt(var) / std::abs(sw);
            // 5 sigma plus the tabulated samplers' discretization bias.
            EXPECT_NEAR(estimate, expected, 5 * se + 2e-3 * std::abs(expected) + 1e-4)
                << f.ToString() << " test " << t;
        }
    }
}

TEST(Filters, ExactSamplersHaveUnitWeightTabulatedOnesTheIntegral) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<Float> u(0, 1);
    for (int i = 0; i < 1000; ++i) {
        Point2f uu(u(rng), u(rng));
        EXPECT_EQ(BoxFilter().Sample(uu).weight, 1);
        EXPECT_EQ(TriangleFilter().Sample(uu).weight, 1);
        // |weight| is the integral of |f| over the table, so the estimator has no variance
        // from the weights where f > 0.
        GaussianFilter g;
        EXPECT_NEAR(g.Sample(uu).weight, g.Integral(), 5e-3f * g.Integral());
    }
    // Mitchell's negative lobes give negative weights.
    MitchellFilter m;
    int negative = 0;
    for (int i = 0; i < 10000; ++i) negative += m.Sample(Point2f(u(rng), u(rng))).weight < 0;
    EXPECT_GT(negative, 100);
}

}  // namespace
}  // namespace pbrt
