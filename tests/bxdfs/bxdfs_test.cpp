// The comparison BxDFs (DiffuseBxDF, ConductorBxDF) under the same proofs as the fabric: chi-square of
// Sample_f against PDF, Sample_f agreeing with f and PDF, reciprocity, finite output, energy bound,
// rho against quadrature, and Regularize.
#include "tests/support/bxdf_properties.h"
#include "tests/support/chi2.h"

#include "pbrt_ext/bxdfs/albedo.h"
#include "pbrt_ext/bxdfs/conductor.h"
#include "pbrt_ext/bxdfs/diffuse.h"
#include "pbrt_ext/util/spherequadrature.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace pbrt;

namespace {

// Chi-square tests in this file (Šidák correction), α = 0.01 overall, 1e6 samples each.
constexpr int kChi2Tests = 3 * 4 + 3;
// Copper-like eta and k at four wavelengths (about 450, 550, 650 and 700 nm); the furnace bound
// holds for any conductor.
const SampledSpectrum kEta(1.22f, 0.95f, 0.27f, 0.21f), kK(2.4f, 2.6f, 3.6f, 4.2f);

ConductorBxDF Conductor(Float ax, Float ay) {
    return ConductorBxDF(TrowbridgeReitzDistribution(ax, ay), kEta, kK);
}

std::vector<Vector3f> Outgoing() {
    return {Vector3f(0, 0, 1), Normalize(Vector3f(0.5f, 0.2f, 0.8f)),
            Normalize(Vector3f(-0.9f, 0.3f, 0.15f))};
}

template <typename BxDF>
void ExpectChi2(const BxDF &bxdf) {
    Chi2Options opts;
    opts.numTests = kChi2Tests;
    opts.seed = 17;
    for (Vector3f wo : Outgoing()) {
        Chi2Result r = Chi2TestBxDF(bxdf, wo, opts);
        EXPECT_TRUE(r.passed) << r.message;
    }
}

template <typename BxDF>
void ExpectProperties(const BxDF &bxdf) {
    BxDFCheckOptions opts;
    for (Vector3f wo : PropertyTestDirections()) {
        PropertyResult sampled = CheckSampleMatchesEval(bxdf, wo, opts);
        EXPECT_TRUE(sampled.passed) << bxdf.ToString() << "\n" << sampled.message;
        PropertyResult finite = CheckFiniteNonNegative(bxdf, wo, opts);
        EXPECT_TRUE(finite.passed) << bxdf.ToString() << "\n" << finite.message;
    }
    PropertyResult reciprocal = CheckReflectionReciprocity(bxdf, opts);
    EXPECT_TRUE(reciprocal.passed) << bxdf.ToString() << "\n" << reciprocal.message;
}

double Albedo(const ConductorBxDF &bxdf, Vector3f wo, int channel) {
    return DirectionalAlbedo(bxdf, wo, Frame::FromZ(Vector3f(0, 0, 1)), {0.0}, 512, 512, channel);
}

}  // namespace

TEST(DiffuseBxDF, SamplingFollowsItsDensity) { ExpectChi2(DiffuseBxDF(SampledSpectrum(0.7f))); }

TEST(DiffuseBxDF, Properties) { ExpectProperties(DiffuseBxDF(SampledSpectrum(0.3f, 0.5f, 0.9f, 0.7f))); }

TEST(DiffuseBxDF, AlbedoIsReflectance) {
    const double expected[NSpectrumSamples] = {0.25, 0.5, 1.0, 0.75};
    DiffuseBxDF bxdf(SampledSpectrum(0.25f, 0.5f, 1, 0.75f));
    for (Vector3f wo : Outgoing())
        for (int c = 0; c < NSpectrumSamples; ++c)
            EXPECT_NEAR(DirectionalAlbedo(bxdf, wo, Frame::FromZ(Vector3f(0, 0, 1)), {0.0}, 64, 64, c),
                        expected[c], 1e-5);
}

TEST(ConductorBxDF, SamplingFollowsItsDensity) {
    for (auto [ax, ay] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {0.8f, 0.8f}, {0.1f, 0.5f}})
        ExpectChi2(Conductor(ax, ay));
}

TEST(ConductorBxDF, Properties) {
    for (auto [ax, ay] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {0.1f, 0.5f}})
        ExpectProperties(Conductor(ax, ay));
}

TEST(ConductorBxDF, AlbedoNeverExceedsOne) {
    // Single-scattering microfacets lose energy; with |F| <= 1 the albedo stays below 1 (+ quadrature).
    for (Float alpha : {0.1f, 0.3f, 0.8f})
        for (Vector3f wo : Outgoing())
            for (int c = 0; c < NSpectrumSamples; ++c)
                EXPECT_LE(Albedo(Conductor(alpha, alpha), wo, c), 1 + 1e-3)
                    << "alpha " << alpha << " channel " << c;
}

TEST(ConductorBxDF, RhoAgreesWithQuadrature) {
    RhoSamples in = MakeRhoSamples(1 << 16, 5);
    ConductorBxDF bxdf = Conductor(0.4f, 0.4f);
    for (Vector3f wo : Outgoing()) {
        double expected = Albedo(bxdf, wo, 0);
        // Visible-normal sampling: weight F·G1-ratio <= 1, so 2^16 samples give < 0.5 % error.
        EXPECT_NEAR(bxdf.rho(wo, in.uc, in.u2)[0], expected, 0.01 * expected);
    }
}

TEST(ConductorBxDF, RegularizeRoughensOnlyNearSpecularLobes) {
    // pbrt-v4's rule: alpha < 0.3 becomes clamp(2 alpha, 0.1, 0.3).
    Vector3f wo = Normalize(Vector3f(0.3f, 0, 1)), mirror(-wo.x, -wo.y, wo.z);
    Vector3f offMirror = Normalize(mirror + Vector3f(0.3f, 0, 0));  // ~17° off: f grows 12.7x
    ConductorBxDF glossy = Conductor(0.02f, 0.02f), regularized = glossy;
    regularized.Regularize();  // alpha 0.02 -> 0.1: a lower peak, a wider lobe
    auto f = [&](const ConductorBxDF &c, Vector3f wi) {
        return c.f(wo, wi, TransportMode::Radiance)[0];
    };
    EXPECT_LT(f(regularized, mirror), f(glossy, mirror) / 10);
    EXPECT_GT(f(regularized, offMirror), 10 * f(glossy, offMirror));
    // A perfect mirror becomes glossy, which is the point: paths through it can be connected.
    ConductorBxDF specular = Conductor(0, 0);
    ASSERT_TRUE(IsSpecular(specular.Flags()));
    specular.Regularize();
    EXPECT_TRUE(IsGlossy(specular.Flags()));
    // Rough lobes are left alone.
    ConductorBxDF rough = Conductor(0.5f, 0.5f), roughRegularized = rough;
    roughRegularized.Regularize();
    EXPECT_EQ(f(rough, offMirror), f(roughRegularized, offMirror));
}
