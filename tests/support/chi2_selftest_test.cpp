// The chi-square harness itself: its distribution function against known quantiles, and
// proof that it accepts correct samplers (including hard ones) and rejects wrong ones.
#include "tests/support/chi2.h"

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/vecmath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace pbrt;

namespace {

// Upper-hemisphere cosine density, the reference every test below perturbs.
Float CosinePdf(Vector3f w) { return w.z > 0 ? CosineHemispherePDF(w.z) : 0; }

auto CosineSampler() {
    return [](Point2f u, Float) -> pstd::optional<Vector3f> {
        return SampleCosineHemisphere(u);
    };
}

// A density whose integral over the sphere is exactly 1, altered by the factor `scale` in
// the quadrant 0 <= phi < pi / 2.
auto ScaledInFirstQuadrant(Float scale) {
    return [scale](Vector3f w) {
        bool inQuadrant = w.x >= 0 && w.y >= 0;
        return CosinePdf(w) * (inQuadrant ? scale : 1);
    };
}

}  // namespace

TEST(Chi2Distribution, SurvivalProbabilityAtKnownQuantiles) {
    // (statistic, dof, upper tail probability), from scipy.stats.chi2.sf.
    struct Case {
        double x;
        int dof;
        double p;
    } cases[] = {{6.634896601021214, 1, 0.010000000000000005},
                 {23.209251158954356, 10, 0.010000000000000005},
                 {1.0, 3, 0.8012519569012009},
                 {0.5, 1, 0.47950012218695337},
                 {1106.9692935618077, 1000, 0.009999833326755898},
                 {8000.0, 8000, 0.4978973866463206},
                 {8400.0, 8000, 0.0009156555871932195},
                 {300.0, 200, 5.924540335483916e-06}};
    for (const Case &c : cases)
        EXPECT_NEAR(Chi2SurvivalProbability(c.x, c.dof), c.p, 1e-9 + 1e-6 * c.p)
            << "x = " << c.x << ", dof = " << c.dof;
    // dof = 2 has a closed form.
    for (double x : {0.1, 1.0, 4.0, 30.0})
        EXPECT_NEAR(Chi2SurvivalProbability(x, 2), std::exp(-x / 2), 1e-12);
}

TEST(Chi2Distribution, SidakLevel) {
    EXPECT_NEAR(SidakCorrectedLevel(0.01, 1), 0.01, 1e-15);
    for (int n : {2, 5, 40}) {
        double level = SidakCorrectedLevel(0.01, n);
        EXPECT_NEAR(1 - std::pow(1 - level, n), 0.01, 1e-12);
        EXPECT_LT(level, 0.01 / n * 1.01);
    }
}

TEST(SphereQuadrature, IntegratesPolynomialsAndHorizonSteps) {
    double area = 0, z2 = 0, upperZ = 0;
    ForEachSphereQuadratureNode(8, 16, [&](Vector3f w, double weight) {
        area += weight;
        z2 += weight * w.z * w.z;
        upperZ += weight * std::max<Float>(w.z, 0);
    });
    EXPECT_NEAR(area, 4 * 3.14159265358979, 1e-9);
    EXPECT_NEAR(z2, 4 * 3.14159265358979 / 3, 1e-6);
    EXPECT_NEAR(upperZ, 3.14159265358979, 1e-6);  // exact: the rule splits at z = 0
}

TEST(Chi2Harness, AcceptsCosineSampler) {
    Chi2Result r = Chi2TestSampler(CosineSampler(), CosinePdf, Chi2Options{});
    EXPECT_TRUE(r.passed) << r.message;
    EXPECT_NEAR(r.integralPdf, 1, 1e-4);
    EXPECT_EQ(r.acceptedFraction, 1);
    EXPECT_GT(r.degreesOfFreedom, 1000);  // every upper-hemisphere cell
}

TEST(Chi2Harness, SameSeedSameResult) {
    Chi2Options opts;
    opts.sampleCount = 100000;
    Chi2Result a = Chi2TestSampler(CosineSampler(), CosinePdf, opts);
    Chi2Result b = Chi2TestSampler(CosineSampler(), CosinePdf, opts);
    EXPECT_EQ(a.statistic, b.statistic);
    opts.seed = 7;
    Chi2Result c = Chi2TestSampler(CosineSampler(), CosinePdf, opts);
    EXPECT_NE(a.statistic, c.statistic);
}

TEST(Chi2Harness, RejectsUniformPdfForCosineSamples) {
    auto uniformPdf = [](Vector3f w) { return w.z > 0 ? UniformHemispherePDF() : 0; };
    Chi2Result r = Chi2TestSampler(CosineSampler(), uniformPdf, Chi2Options{});
    EXPECT_FALSE(r.passed);
    EXPECT_LT(r.pValue, r.level);
    // The failure message carries the tables.
    EXPECT_NE(r.message.find("observed counts"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("expected counts"), std::string::npos) << r.message;
}

TEST(Chi2Harness, RejectsPdfMissingFivePercentInOneQuadrant) {
    Chi2Result r = Chi2TestSampler(CosineSampler(), ScaledInFirstQuadrant(0.95f), Chi2Options{});
    EXPECT_FALSE(r.passed) << r.message;
    EXPECT_LT(r.pValue, r.level) << r.message;
    EXPECT_NEAR(r.integralPdf, 1 - 0.25 * 0.05, 1e-4);
}

// Mass moved between two quadrants leaves the integral right: only the statistic can
// see it.
TEST(Chi2Harness, RejectsFivePercentMassMovedBetweenQuadrants) {
    auto pdf = [](Vector3f w) {
        Float scale = w.y < 0 ? 1 : (w.x >= 0 ? 0.95f : 1.05f);
        return CosinePdf(w) * scale;
    };
    Chi2Result r = Chi2TestSampler(CosineSampler(), pdf, Chi2Options{});
    EXPECT_FALSE(r.passed) << r.message;
    EXPECT_LT(r.pValue, r.level) << r.message;
    EXPECT_NEAR(r.integralPdf, 1, 1e-4);
}

TEST(Chi2Harness, ReportsSamplesWherePdfIsZero) {
    // One sample in 1e5 is mirrored below the horizon, where the pdf is zero.
    auto sampler = [](Point2f u, Float uc) -> pstd::optional<Vector3f> {
        Vector3f w = SampleCosineHemisphere(u);
        return uc < 1e-5f ? -w : w;
    };
    Chi2Result r = Chi2TestSampler(sampler, CosinePdf, Chi2Options{});
    EXPECT_FALSE(r.passed);
    EXPECT_GT(r.zeroPdfCellSamples, 0);
    EXPECT_NE(r.message.find("pdf integrates to zero"), std::string::npos) << r.message;
}

TEST(Chi2Harness, AcceptsSubProbabilitySampler) {
    auto sampler = [](Point2f u, Float uc) -> pstd::optional<Vector3f> {
        if (uc < 0.3f)
            return {};
        return SampleCosineHemisphere(u);
    };
    auto pdf = [](Vector3f w) { return 0.7f * CosinePdf(w); };
    Chi2Result r = Chi2TestSampler(sampler, pdf, Chi2Options{});
    EXPECT_TRUE(r.passed) << r.message;
    EXPECT_NEAR(r.acceptedFraction, 0.7, 0.003);
    EXPECT_NEAR(r.integralPdf, 0.7, 1e-4);
}

TEST(Chi2Harness, RejectsDeclinesThePdfDoesNotAccountFor) {
    auto sampler = [](Point2f u, Float uc) -> pstd::optional<Vector3f> {
        if (uc < 0.02f)
            return {};
        return SampleCosineHemisphere(u);
    };
    Chi2Result r = Chi2TestSampler(sampler, CosinePdf, Chi2Options{});
    EXPECT_FALSE(r.passed) << r.message;
    EXPECT_NE(r.message.find("accepted fraction"), std::string::npos);
}

TEST(Chi2Harness, RejectsInvalidPdfValues) {
    auto pdf = [](Vector3f w) { return w.z > 0.99f ? -1.f : CosinePdf(w); };
    Chi2Result r = Chi2TestSampler(CosineSampler(), pdf, Chi2Options{});
    EXPECT_FALSE(r.passed);
    EXPECT_GT(r.invalidPdfValues, 0);
}

// A density with an integrable point singularity, p ~ 1 / angle to a tilted axis, on the
// tilted hemisphere around that axis (so it also jumps along a tilted great circle).
TEST(Chi2Harness, AcceptsPointSingularity) {
    Frame frame = Frame::FromZ(Normalize(Vector3f(0.3f, 0.2f, 0.9f)));
    auto sampler = [&](Point2f u, Float) -> pstd::optional<Vector3f> {
        // 1 - cos = u0^2 inverts the CDF of 1 / (4 pi sqrt(1 - cos)).
        Float oneMinusCos = Sqr(u[0]), cosTheta = 1 - oneMinusCos;
        Float sinTheta = SafeSqrt(oneMinusCos * (2 - oneMinusCos));
        Float phi = 2 * Pi * u[1];
        return frame.FromLocal(SphericalDirection(sinTheta, cosTheta, phi));
    };
    auto pdf = [&](Vector3f w) -> Float {
        Vector3f l = frame.ToLocal(w);
        if (l.z < 0)
            return 0;
        // 1 - cos theta without cancellation near the axis.
        double oneMinusCos = (double(l.x) * l.x + double(l.y) * l.y) / (1 + double(l.z));
        return Float(1 / (4 * 3.14159265358979 * std::sqrt(std::max(oneMinusCos, 1e-300))));
    };
    Chi2Result r = Chi2TestSampler(sampler, pdf, Chi2Options{});
    EXPECT_TRUE(r.passed) << r.message;
    EXPECT_NEAR(r.integralPdf, 1, 1e-3);
}

// A Phong lobe about as wide as one cell, around a tilted axis.
TEST(Chi2Harness, AcceptsNarrowLobe) {
    constexpr Float exponent = 1000;
    Frame frame = Frame::FromZ(Normalize(Vector3f(-0.4f, 0.25f, 0.8f)));
    auto sampler = [&](Point2f u, Float) -> pstd::optional<Vector3f> {
        Float cosTheta = std::pow(u[0], 1 / (exponent + 1));
        Float sinTheta = SafeSqrt(1 - Sqr(cosTheta));
        return frame.FromLocal(SphericalDirection(sinTheta, cosTheta, 2 * Pi * u[1]));
    };
    auto pdf = [&](Vector3f w) -> Float {
        Float cosTheta = frame.ToLocal(w).z;
        return cosTheta > 0 ? (exponent + 1) * Inv2Pi * std::pow(cosTheta, exponent) : 0;
    };
    Chi2Result r = Chi2TestSampler(sampler, pdf, Chi2Options{});
    EXPECT_TRUE(r.passed) << r.message;
}

// A lobe around the normal 10% too narrow. Bins with their pole at the normal would hold
// the whole lobe in one ring of wedges and miss this; the harness's pole is +y.
TEST(Chi2Harness, RejectsWrongWidthOfLobeAtTheNormal) {
    auto sampler = [](Point2f u, Float) -> pstd::optional<Vector3f> {
        Float cosTheta = std::pow(u[0], 1 / 1001.f);
        return SphericalDirection(SafeSqrt(1 - Sqr(cosTheta)), cosTheta, 2 * Pi * u[1]);
    };
    auto pdf = [](Vector3f w) -> Float {
        return w.z > 0 ? 1101 * Inv2Pi * std::pow(w.z, 1100.f) : 0;
    };
    Chi2Result r = Chi2TestSampler(sampler, pdf, Chi2Options{});
    EXPECT_FALSE(r.passed);
    EXPECT_LT(r.pValue, r.level) << r.message;
}

namespace {

// A minimal BxDF: a mirror picked with probability 1/4, else a cosine lobe that reports
// its pdf as the density of the mixture (0.75 cos / pi); the mirror is specular.
struct MirrorAndDiffuseBxDF {
    pstd::optional<BSDFSample> Sample_f(Vector3f wo, Float uc, Point2f u, TransportMode,
                                        BxDFReflTransFlags) const {
        if (uc < 0.25f)
            return BSDFSample(SampledSpectrum(1.f), Vector3f(-wo.x, -wo.y, wo.z), 0.25f,
                              BxDFFlags::SpecularReflection);
        Vector3f wi = SampleCosineHemisphere(u);
        return BSDFSample(SampledSpectrum(InvPi), wi, 0.75f * CosinePdf(wi),
                          BxDFFlags::DiffuseReflection);
    }
    Float PDF(Vector3f, Vector3f wi, TransportMode, BxDFReflTransFlags) const {
        return 0.75f * CosinePdf(wi);
    }
};

}  // namespace

TEST(Chi2Harness, BxDFSpecularSamplesAreSkipped) {
    MirrorAndDiffuseBxDF bxdf;
    Chi2Options opts;
    opts.sampleCount = 400000;
    Chi2Result r = Chi2TestBxDF(bxdf, Normalize(Vector3f(0.2f, 0.1f, 1)), opts);
    EXPECT_TRUE(r.passed) << r.message;
    EXPECT_NEAR(double(r.specularSkipped) / opts.sampleCount, 0.25, 0.005);
    EXPECT_NEAR(r.acceptedFraction, 0.75, 0.005);
}
