// The sampling.h additions: PiecewiseConstant1D/2D (exact densities, inverses, histograms
// against the tabulated function), the uniform cone and the uniform triangle warps.
// Statistical tests use a fixed seed, 1e6 samples and Pearson's test at alpha = 0.01 with
// the Sidak correction over the kStatisticalTests tests of this file.
#include "tests/support/chi2.h"

#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/vecmath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

using namespace pbrt;

namespace {

constexpr int kStatisticalTests = 6;  // three histograms and three cones
constexpr int kSamples = 1000000;

// Pearson's test of observed counts against expected ones (cells below 5 pooled).
void ExpectCountsMatch(const std::vector<double> &expected, const std::vector<double> &observed) {
    std::vector<std::pair<double, double>> cells;
    for (size_t i = 0; i < expected.size(); ++i) {
        if (expected[i] == 0)
            EXPECT_EQ(observed[i], 0) << "samples in zero-density cell " << i;
        else
            cells.push_back({expected[i], observed[i]});
    }
    chi2detail::Pearson p = chi2detail::PooledPearson(cells, 5);
    double pValue = Chi2SurvivalProbability(p.statistic, p.dof);
    EXPECT_GE(pValue, SidakCorrectedLevel(0.01, kStatisticalTests))
        << "chi2 = " << p.statistic << ", dof = " << p.dof;
}

// Positive values with a zero run and a large dynamic range, as an environment map has.
std::vector<Float> TestFunction(int n, uint64_t seed) {
    RNG rng(seed);
    std::vector<Float> f(n);
    for (int i = 0; i < n; ++i)
        f[i] = (i % 7 == 3) ? 0 : std::exp(8 * rng.Uniform<Float>() - 4);
    return f;
}

TEST(PiecewiseConstant1D, IntegralAndPdfOverADomain) {
    std::vector<Float> f = {1, 3, 0, -4};  // magnitudes are sampled: -4 counts as 4
    PiecewiseConstant1D d(f, -1, 3);        // pieces of width 1
    EXPECT_FLOAT_EQ(d.Integral(), 8);
    EXPECT_EQ(d.size(), 4u);
    for (Float u : {0.01f, 0.2f, 0.49f, 0.51f, 0.99f}) {
        Float pdf;
        int offset;
        Float x = d.Sample(u, &pdf, &offset);
        EXPECT_GE(x, -1);
        EXPECT_LE(x, 3);
        EXPECT_EQ(offset, Clamp(int(std::floor(x + 1)), 0, 3));
        EXPECT_FLOAT_EQ(pdf, std::abs(f[offset]) / 8);
        EXPECT_GT(pdf, 0) << "a zero piece was sampled";
    }
}

TEST(PiecewiseConstant1D, ZeroFunctionSamplesUniformlyWithZeroPdf) {
    std::vector<Float> f(5, 0);
    PiecewiseConstant1D d(f);
    Float pdf = 1;
    EXPECT_NEAR(d.Sample(0.3f, &pdf), 0.3f, 1e-6f);
    EXPECT_EQ(pdf, 0);
    EXPECT_EQ(d.Integral(), 0);
}

TEST(PiecewiseConstant1D, InvertRoundTrips) {
    PiecewiseConstant1D d(TestFunction(37, 1), 2, 5);
    RNG rng(7);
    for (int i = 0; i < 10000; ++i) {
        Float u = rng.Uniform<Float>();
        Float x = d.Sample(u);
        pstd::optional<Float> back = d.Invert(x);
        ASSERT_TRUE(back.has_value());
        EXPECT_NEAR(*back, u, 2e-5f) << "x = " << x;
    }
    EXPECT_FALSE(d.Invert(1.99f).has_value());
    EXPECT_FALSE(d.Invert(5.01f).has_value());
}

TEST(PiecewiseConstant1D, HistogramMatchesFunction) {
    // Four bins per piece: the density must also be flat within each piece.
    constexpr int n = 50, sub = 4;
    std::vector<Float> f = TestFunction(n, 2);
    PiecewiseConstant1D d(f);
    std::vector<double> expected(n * sub), observed(n * sub, 0);
    for (int i = 0; i < n * sub; ++i)
        expected[i] = double(kSamples) * f[i / sub] / (d.Integral() * n * sub);
    RNG rng(3);
    for (int k = 0; k < kSamples; ++k) {
        Float x = d.Sample(rng.Uniform<Float>());
        observed[Clamp(int(x * n * sub), 0, n * sub - 1)] += 1;
    }
    ExpectCountsMatch(expected, observed);
}

TEST(PiecewiseConstant2D, PdfMatchesSampleAndIntegratesToOne) {
    constexpr int nu = 13, nv = 9;
    std::vector<Float> f = TestFunction(nu * nv, 4);
    Bounds2f domain(Point2f(-1, 2), Point2f(3, 4));
    PiecewiseConstant2D d(f, nu, nv, domain);
    EXPECT_EQ(d.ResolutionU(), nu);
    EXPECT_EQ(d.ResolutionV(), nv);
    EXPECT_EQ(d.Domain(), domain);
    double integral = 0, cellArea = domain.Area() / (nu * nv);
    for (int v = 0; v < nv; ++v)
        for (int u = 0; u < nu; ++u)
            integral += d.PDF(domain.Lerp(Point2f((u + 0.5f) / nu, (v + 0.5f) / nv))) * cellArea;
    EXPECT_NEAR(integral, 1, 1e-5);

    RNG rng(5);
    for (int k = 0; k < 10000; ++k) {
        Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
        Float pdf;
        Point2i offset;
        Point2f p = d.Sample(u, &pdf, &offset);
        ASSERT_TRUE(Inside(p, domain));
        EXPECT_FLOAT_EQ(pdf, d.PDF(p));
        EXPECT_GT(pdf, 0);
        EXPECT_FLOAT_EQ(pdf, f[offset.y * nu + offset.x] / d.Integral());
    }
}

TEST(PiecewiseConstant2D, InvertRoundTrips) {
    constexpr int nu = 16, nv = 11;
    Bounds2f domain(Point2f(0, -2), Point2f(2, 2));
    PiecewiseConstant2D d(TestFunction(nu * nv, 6), nu, nv, domain);
    RNG rng(8);
    for (int k = 0; k < 10000; ++k) {
        Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
        Point2f p = d.Sample(u);
        pstd::optional<Point2f> back = d.Invert(p);
        ASSERT_TRUE(back.has_value());
        EXPECT_NEAR(back->x, u.x, 1e-4f);
        EXPECT_NEAR(back->y, u.y, 1e-4f);
    }
    EXPECT_FALSE(d.Invert(Point2f(1, 2.5f)).has_value());
    EXPECT_FALSE(d.Invert(Point2f(-0.5f, 0)).has_value());
}

TEST(PiecewiseConstant2D, HistogramMatchesFunction) {
    constexpr int nu = 24, nv = 12;
    std::vector<Float> f = TestFunction(nu * nv, 9);
    PiecewiseConstant2D d(f, nu, nv);
    std::vector<double> expected(nu * nv), observed(nu * nv, 0);
    for (int i = 0; i < nu * nv; ++i)
        expected[i] = double(kSamples) * f[i] / (d.Integral() * nu * nv);
    RNG rng(10);
    for (int k = 0; k < kSamples; ++k) {
        Float u0 = rng.Uniform<Float>();
        Point2f p = d.Sample(Point2f(u0, rng.Uniform<Float>()));
        int iu = Clamp(int(p.x * nu), 0, nu - 1), iv = Clamp(int(p.y * nv), 0, nv - 1);
        observed[iv * nu + iu] += 1;
    }
    ExpectCountsMatch(expected, observed);
}

TEST(UniformCone, ChiSquareAndRoundTrip) {
    for (Float cosThetaMax : {0.95f, 0.3f, -0.5f}) {
        Chi2Options opts;
        opts.numTests = kStatisticalTests;
        opts.seed = 11;
        auto sample = [&](Point2f u, Float) -> pstd::optional<Vector3f> {
            return SampleUniformCone(u, cosThetaMax);
        };
        auto pdf = [&](Vector3f w) {
            return Normalize(w).z >= cosThetaMax ? UniformConePDF(cosThetaMax) : 0;
        };
        Chi2Result r = Chi2TestSampler(sample, pdf, opts);
        EXPECT_TRUE(r.passed) << "cos theta max = " << cosThetaMax << "\n" << r.message;

        RNG rng(12);
        for (int k = 0; k < 1000; ++k) {
            Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
            Vector3f w = SampleUniformCone(u, cosThetaMax);
            EXPECT_NEAR(Length(w), 1, 1e-5f);
            Point2f back = InvertUniformConeSample(w, cosThetaMax);
            EXPECT_NEAR(back.x, u.x, 1e-3f);
            EXPECT_NEAR(back.y, u.y, 1e-4f);
        }
    }
}

TEST(UniformTriangle, BarycentricsValidAndRoundTrip) {
    RNG rng(13);
    for (int k = 0; k < 10000; ++k) {
        Point2f u(rng.Uniform<Float>(), rng.Uniform<Float>());
        std::array<Float, 3> b = SampleUniformTriangle(u);
        for (Float bi : b)
            EXPECT_GE(bi, 0);
        EXPECT_NEAR(b[0] + b[1] + b[2], 1, 1e-6f);
        Point2f back = InvertUniformTriangleSample(b);
        EXPECT_NEAR(back.x, u.x, 1e-6f);
        EXPECT_NEAR(back.y, u.y, 1e-6f);
    }
}

TEST(UniformTriangle, HistogramIsUniform) {
    // Cells of the (b0, b1) grid: a cell inside the triangle expects 2 N cellArea, one cut by
    // the hypotenuse half of that, one beyond it nothing.
    constexpr int n = 20;
    std::vector<double> expected(n * n), observed(n * n, 0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double share = i + j + 2 <= n ? 1 : (i + j + 1 == n ? 0.5 : 0);
            expected[i * n + j] = 2.0 * kSamples * share / (n * n);
        }
    RNG rng(14);
    for (int k = 0; k < kSamples; ++k) {
        Float u0 = rng.Uniform<Float>();
        std::array<Float, 3> b = SampleUniformTriangle(Point2f(u0, rng.Uniform<Float>()));
        int i = Clamp(int(b[0] * n), 0, n - 1), j = Clamp(int(b[1] * n), 0, n - 1);
        observed[i * n + j] += 1;
    }
    ExpectCountsMatch(expected, observed);
}

}  // namespace
