// util/sampling.h and util/rng.h: every warp inverts, its density integrates to one and
// matches the samples (chi-square); the MIS heuristics; the RNG's determinism and range.
#include "tests/support/chi2.h"

#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spherequadrature.h"
#include "pbrt_ext/util/vecmath.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

// Every warp, seen as a map from [0,1)^2 onto the sphere with a density per solid angle,
// so that one chi-square harness tests them all. Disk points are lifted onto the upper
// hemisphere (Malley): a density p on the disk becomes p cos(theta) per solid angle.
// The 1D linear warp becomes cos theta = 2 x - 1 with phi uniform: density p(x) / (4 pi);
// its histogram has a single phi bin, which keeps the test's power on a 1D density.
struct SphereWarp {
    std::string name;  // a gtest parameter name: letters, digits, underscores
    std::function<Vector3f(Point2f)> sample;
    std::function<Float(Vector3f)> pdf;
    int phiBins = Chi2Options{}.phiBins;
};

Vector3f LiftToHemisphere(Point2f p) {
    return Vector3f(p.x, p.y, SafeSqrt(1 - Sqr(p.x) - Sqr(p.y)));
}

Float UpperHemisphere(Vector3f w, Float pdf) { return w.z > 0 ? pdf : 0; }

SphereWarp LinearWarp(const char *name, Float a, Float b) {
    return {name,
            [=](Point2f u) {
                Float cosTheta = 2 * SampleLinear(u[0], a, b) - 1;
                return SphericalDirection(SafeSqrt(1 - Sqr(cosTheta)), cosTheta,
                                          2 * Pi * u[1]);
            },
            [=](Vector3f w) { return LinearPDF((w.z + 1) / 2, a, b) * Inv4Pi; }, 1};
}

std::vector<SphereWarp> AllWarps() {
    return {
        {"UniformHemisphere", SampleUniformHemisphere,
         [](Vector3f w) { return UpperHemisphere(w, UniformHemispherePDF()); }},
        {"UniformSphere", SampleUniformSphere, [](Vector3f) { return UniformSpherePDF(); }},
        {"CosineHemisphere", SampleCosineHemisphere,
         [](Vector3f w) { return UpperHemisphere(w, CosineHemispherePDF(w.z)); }},
        {"UniformDiskConcentric",
         [](Point2f u) { return LiftToHemisphere(SampleUniformDiskConcentric(u)); },
         [](Vector3f w) { return UpperHemisphere(w, InvPi * w.z); }},
        {"UniformDiskPolar",
         [](Point2f u) { return LiftToHemisphere(SampleUniformDiskPolar(u)); },
         [](Vector3f w) { return UpperHemisphere(w, InvPi * w.z); }},
        LinearWarp("Linear_1_3", 1, 3),
        LinearWarp("Linear_2_0p5", 2, 0.5f),
        LinearWarp("Linear_0_1", 0, 1),
    };
}

// Interior grid points of [0,1)^2, away from the seams where the azimuth wraps and the
// poles where it is undefined.
std::vector<Point2f> InteriorGrid(int n) {
    std::vector<Point2f> points;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            points.push_back(Point2f(0.005f + 0.99f * (i + 0.5f) / n,
                                     0.005f + 0.99f * (j + 0.5f) / n));
    return points;
}

template <typename Sample, typename Invert>
void ExpectRoundTrip(Sample sample, Invert invert, const char *name) {
    int failures = 0;
    for (Point2f u : InteriorGrid(64)) {
        Point2f back = invert(sample(u));
        if (std::abs(back.x - u.x) > 1e-4f || std::abs(back.y - u.y) > 1e-4f)
            if (failures++ < 5)
                ADD_FAILURE() << name << ": u = (" << u.x << ", " << u.y << ") came back as ("
                              << back.x << ", " << back.y << ")";
    }
    EXPECT_EQ(failures, 0) << name;
}

}  // namespace

TEST(Warps, RoundTrip) {
    ExpectRoundTrip(SampleUniformHemisphere, InvertUniformHemisphereSample,
                    "UniformHemisphere");
    ExpectRoundTrip(SampleUniformSphere, InvertUniformSphereSample, "UniformSphere");
    ExpectRoundTrip(SampleCosineHemisphere, InvertCosineHemisphereSample, "CosineHemisphere");
    ExpectRoundTrip(SampleUniformDiskConcentric, InvertUniformDiskConcentricSample,
                    "UniformDiskConcentric");
    ExpectRoundTrip(SampleUniformDiskPolar, InvertUniformDiskPolarSample, "UniformDiskPolar");
}

TEST(Warps, LinearRoundTrip) {
    for (auto [a, b] : {std::pair<Float, Float>{1, 3}, {2, 0.5f}, {0, 1}, {1, 0}, {1, 1}})
        for (int i = 0; i <= 100; ++i) {
            Float u = i / 100.f * OneMinusEpsilon;
            Float x = SampleLinear(u, a, b);
            EXPECT_GE(x, 0);
            EXPECT_LT(x, 1);
            EXPECT_NEAR(InvertLinearSample(x, a, b), u, 1e-4f) << "a = " << a << ", b = " << b;
        }
}

// The normal warp inverts, its values are finite at u = 0 (where erf^-1 has its pole: the
// MLT sampler draws u = 0 once in 2^24 steps), and erf^-1 inverts std::erf to 2e-6.
TEST(Warps, NormalRoundTrip) {
    for (int i = 1; i < 1000; ++i) {
        Float u = i / 1000.f;
        Float x = SampleNormal(u, 0.5f, 0.25f);
        EXPECT_NEAR(InvertNormalSample(x, 0.5f, 0.25f), u, 2e-6f) << "u = " << u;
    }
    EXPECT_TRUE(std::isfinite(SampleNormal(0)));
    EXPECT_LT(SampleNormal(0), -5);
    for (int i = -9999; i <= 9999; i += 7) {
        Float x = i / 10000.f;
        EXPECT_NEAR(std::erf(ErfInv(x)), x, 2e-6f) << "x = " << x;
    }
}

// The density integrates to one, and 100000 samples match its mean and deviation (within 4
// standard errors: 0.0013 and 0.0009 for sigma 0.1).
TEST(Warps, NormalSamplesFollowTheDensity) {
    double integral = 0;
    for (int i = -6000; i < 6000; ++i) integral += 1e-3 * NormalPDF((i + 0.5f) * 1e-3f, 0, 1);
    EXPECT_NEAR(integral, 1, 1e-6);
    RNG rng;
    double sum = 0, sum2 = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        double x = SampleNormal(rng.Uniform<Float>(), 1, 0.1f);
        sum += x;
        sum2 += x * x;
    }
    double mean = sum / n;
    EXPECT_NEAR(mean, 1, 4 * 0.1 / std::sqrt(n));
    EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), 0.1, 4 * 0.1 / std::sqrt(2.0 * n));
}

TEST(Warps, DiskWarpsStayInTheDisk) {
    for (Point2f u : InteriorGrid(32))
        for (Point2f p : {SampleUniformDiskConcentric(u), SampleUniformDiskPolar(u)})
            EXPECT_LE(Sqr(p.x) + Sqr(p.y), 1 + 1e-6f);
    EXPECT_EQ(SampleUniformDiskConcentric(Point2f(0.5f, 0.5f)), Point2f(0, 0));
}

class WarpTest : public testing::TestWithParam<SphereWarp> {};

TEST_P(WarpTest, PdfIntegratesToOne) {
    const SphereWarp &warp = GetParam();
    double integral = 0;
    ForEachSphereQuadratureNode(64, 64, [&](Vector3f w, double weight) {
        integral += weight * warp.pdf(w);
    });
    EXPECT_NEAR(integral, 1, 1e-5);
}

TEST_P(WarpTest, ChiSquare) {
    const SphereWarp &warp = GetParam();
    Chi2Options opts;
    opts.phiBins = warp.phiBins;
    opts.numTests = int(AllWarps().size());
    auto sample = [&](Point2f u, Float) -> pstd::optional<Vector3f> { return warp.sample(u); };
    Chi2Result r = Chi2TestSampler(sample, warp.pdf, opts);
    EXPECT_TRUE(r.passed) << r.message;
}

INSTANTIATE_TEST_SUITE_P(AllWarps, WarpTest, testing::ValuesIn(AllWarps()),
                         [](const testing::TestParamInfo<SphereWarp> &param) {
                             return param.param.name;
                         });

// The linear density on its own domain, [0, 1].
TEST(Warps, LinearPdfIntegratesToOne) {
    for (auto [a, b] : {std::pair<Float, Float>{1, 3}, {0, 1}, {5, 5}}) {
        double integral = 0;
        for (auto [x, w] : GaussLegendre(8))
            integral += 0.5 * w * LinearPDF(Float((x + 1) / 2), a, b);
        EXPECT_NEAR(integral, 1, 1e-6) << "a = " << a << ", b = " << b;
    }
}

TEST(MISHeuristics, Identities) {
    for (auto [f, g] : {std::pair<Float, Float>{1, 1}, {3, 1}, {0.2f, 7}, {1e-3f, 1e3f}}) {
        EXPECT_NEAR(PowerHeuristic(1, f, 1, g) + PowerHeuristic(1, g, 1, f), 1, 1e-6f);
        EXPECT_NEAR(BalanceHeuristic(1, f, 1, g) + BalanceHeuristic(1, g, 1, f), 1, 1e-6f);
        EXPECT_NEAR(BalanceHeuristic(1, f, 1, g), f / (f + g), 1e-6f);
        EXPECT_NEAR(PowerHeuristic(1, f, 1, g), f * f / (f * f + g * g), 1e-6f);
        // Sample counts scale the densities.
        EXPECT_NEAR(PowerHeuristic(3, f, 2, g), PowerHeuristic(1, 3 * f, 1, 2 * g), 1e-6f);
        EXPECT_NEAR(BalanceHeuristic(3, f, 2, g), BalanceHeuristic(1, 3 * f, 1, 2 * g), 1e-6f);
    }
    EXPECT_EQ(PowerHeuristic(1, 1, 1, 1), 0.5f);
    EXPECT_NEAR(PowerHeuristic(1, 3, 1, 1), 0.9f, 1e-6f);
    EXPECT_EQ(BalanceHeuristic(1, 3, 1, 1), 0.75f);
    // The other strategy cannot produce the sample: all the weight goes to this one.
    EXPECT_EQ(PowerHeuristic(1, 2, 1, 0), 1);
    EXPECT_EQ(BalanceHeuristic(1, 2, 1, 0), 1);
    // A delta (infinite) density takes all the weight, even when squaring overflows.
    EXPECT_EQ(PowerHeuristic(1, Infinity, 1, 1), 1);
    EXPECT_EQ(PowerHeuristic(1, 1e30f, 1, 1), 1);
    EXPECT_EQ(BalanceHeuristic(1, Infinity, 1, 1), 1);
}

TEST(RNG, SameSequenceAndOffsetGiveTheSameStream) {
    RNG a(42, 7), b(42, 7), c(43, 7), d;
    d.SetSequence(42, 7);
    int differences = 0;
    for (int i = 0; i < 1000; ++i) {
        uint32_t va = a.Uniform<uint32_t>();
        EXPECT_EQ(va, b.Uniform<uint32_t>());
        EXPECT_EQ(va, d.Uniform<uint32_t>());
        differences += va != c.Uniform<uint32_t>();
    }
    EXPECT_GT(differences, 990);
    RNG e(5), f(5);
    for (int i = 0; i < 100; ++i)
        EXPECT_EQ(e.Uniform<Float>(), f.Uniform<Float>());
}

TEST(RNG, AdvanceSkipsExactly) {
    RNG stepped(3, 11), skipped(3, 11);
    for (int i = 0; i < 1234; ++i)
        stepped.Uniform<uint32_t>();
    skipped.Advance(1234);
    EXPECT_EQ(stepped.Uniform<uint32_t>(), skipped.Uniform<uint32_t>());
    // And back again.
    uint32_t first = RNG(3, 11).Uniform<uint32_t>();
    skipped.Advance(-1235);
    EXPECT_EQ(skipped.Uniform<uint32_t>(), first);
}

TEST(RNG, UniformRangeAndMean) {
    RNG rng(9);
    double sumF = 0, sumD = 0;
    constexpr int n = 1000000;
    for (int i = 0; i < n; ++i) {
        Float f = rng.Uniform<Float>();
        double d = rng.Uniform<double>();
        ASSERT_TRUE(f >= 0 && f < 1) << f;
        ASSERT_TRUE(d >= 0 && d < 1) << d;
        sumF += f;
        sumD += d;
    }
    // The standard deviation of a mean of n uniforms is 1 / sqrt(12 n) = 2.9e-4.
    EXPECT_NEAR(sumF / n, 0.5, 1.5e-3);
    EXPECT_NEAR(sumD / n, 0.5, 1.5e-3);
}

// FindInterval is the largest i in [0, size - 2] with pred(i), clamped, for every table size
// and every split point of a monotone predicate (all true and all false included): checked
// against std::partition_point, which the branch-free bisection must agree with exactly. It
// asks pred only of indices inside the table.
TEST(FindInterval, AgreesWithPartitionPointForEverySizeAndSplit) {
    for (int size = 2; size <= 70; ++size) {
        std::vector<int> indices(static_cast<size_t>(size));
        for (int i = 0; i < size; ++i) indices[size_t(i)] = i;
        for (int split = 0; split <= size; ++split) {
            auto below = [&](int i) { return i < split; };
            int firstFalse = int(std::partition_point(indices.begin() + 1, indices.end() - 1, below) -
                                 indices.begin());
            int asked = 0;
            int found = detail::FindInterval(size, [&](int i) {
                EXPECT_TRUE(i >= 0 && i < size) << i;
                ++asked;
                return below(i);
            });
            EXPECT_EQ(found, Clamp(firstFalse - 1, 0, size - 2)) << "size " << size << " split " << split;
            EXPECT_LE(asked, int(std::ceil(std::log2(double(size)))) + 1);
        }
    }
}
