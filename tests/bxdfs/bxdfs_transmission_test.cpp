// The transmissive BxDFs (DielectricBxDF smooth and rough, ThinDielectricBxDF,
// DiffuseTransmissionBxDF): chi-square of Sample_f against PDF where there is a density,
// the exact branch probabilities and weights where there is none (specular samples are
// skipped by the harness), Sample_f agreeing with f and PDF, reciprocity of reflection,
// pbrt-v4's non-reciprocity of transmission in radiance units, the energy bound, and
// Regularize.
#include "tests/support/bxdf_properties.h"
#include "tests/support/chi2.h"

#include "pbrt_ext/bxdfs/albedo.h"
#include "pbrt_ext/bxdfs/dielectric.h"
#include "pbrt_ext/bxdfs/diffusetransmission.h"
#include "pbrt_ext/bxdfs/thindielectric.h"
#include "pbrt_ext/util/spherequadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

using namespace pbrt;

namespace {

// Chi-square tests in this file (Šidák correction), α = 0.01 overall.
constexpr int kChi2Tests = 5 * 4 + 4 + 1 + 3;
constexpr Float kEta = 1.5f;

DielectricBxDF Rough(Float ax, Float ay, Float eta = kEta) {
    return DielectricBxDF(eta, TrowbridgeReitzDistribution(ax, ay));
}
DielectricBxDF Smooth(Float eta = kEta) { return DielectricBxDF(eta, TrowbridgeReitzDistribution(0, 0)); }

// Outside along the normal, oblique, grazing; inside oblique (past the critical angle for
// part of the microfacets).
std::vector<Vector3f> Outgoing() {
    return {Vector3f(0, 0, 1), Normalize(Vector3f(0.5f, 0.2f, 0.8f)),
            Normalize(Vector3f(-0.9f, 0.3f, 0.15f)), Normalize(Vector3f(0.4f, -0.3f, -0.7f))};
}

template <typename BxDF>
void ExpectChi2(const BxDF &bxdf, const std::vector<Vector3f> &wos,
                BxDFReflTransFlags flags = BxDFReflTransFlags::All) {
    Chi2Options opts;
    opts.numTests = kChi2Tests;
    opts.seed = 23;
    for (Vector3f wo : wos) {
        Chi2Result r = Chi2TestBxDF(bxdf, wo, opts, TransportMode::Radiance, flags);
        EXPECT_TRUE(r.passed) << r.message;
    }
}

template <typename BxDF>
void ExpectProperties(const BxDF &bxdf) {
    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
        BxDFCheckOptions opts;
        opts.mode = mode;
        for (Vector3f wo : PropertyTestDirections()) {
            PropertyResult sampled = CheckSampleMatchesEval(bxdf, wo, opts);
            EXPECT_TRUE(sampled.passed) << bxdf.ToString() << "\n" << sampled.message;
            PropertyResult finite = CheckFiniteNonNegative(bxdf, wo, opts);
            EXPECT_TRUE(finite.passed) << bxdf.ToString() << "\n" << finite.message;
        }
        // Fresnel reflectance near the critical angle is steep enough to turn the rounding
        // of the half vector into a few 1e-5 of f.
        opts.relTolerance = 1e-4f;
        PropertyResult reciprocal = CheckReflectionReciprocity(bxdf, opts);
        EXPECT_TRUE(reciprocal.passed) << bxdf.ToString() << "\n" << reciprocal.message;
    }
}

// f |cos| / pdf of every sample, the Monte Carlo weight an integrator would use.
template <typename BxDF>
std::vector<std::pair<BSDFSample, Float>> SampleWeights(const BxDF &bxdf, Vector3f wo,
                                                        TransportMode mode, int count,
                                                        uint64_t seed = 3) {
    std::vector<std::pair<BSDFSample, Float>> result;
    RNG rng(seed);
    for (int i = 0; i < count; ++i) {
        Float uc = rng.Uniform<Float>(), u0 = rng.Uniform<Float>();
        Point2f u(u0, rng.Uniform<Float>());
        if (pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, uc, u, mode))
            result.push_back({*bs, bs->f[0] * AbsCosTheta(bs->wi) / bs->pdf});
    }
    return result;
}

// Index of refraction on w's side of the interface.
Float IndexOnSide(Vector3f w, Float eta) { return w.z > 0 ? 1 : eta; }

}  // namespace

// ---------------------------------------------------------------------------------------
// Smooth dielectric: two deltas, tested through their probabilities and weights

TEST(DielectricBxDF, SmoothBranchProbabilitiesAreFresnel) {
    DielectricBxDF glass = Smooth();
    for (Vector3f wo : Outgoing()) {
        Float R = FrDielectric(CosTheta(wo), kEta);
        // uc just below and at the reflection probability picks each branch.
        auto reflected = glass.Sample_f(wo, std::nextafter(R, 0.f), Point2f(0.5f, 0.5f),
                                        TransportMode::Importance);
        ASSERT_TRUE(reflected.has_value());
        EXPECT_EQ(reflected->flags, BxDFFlags::SpecularReflection);
        EXPECT_FLOAT_EQ(reflected->pdf, R);
        EXPECT_EQ(reflected->wi, Vector3f(-wo.x, -wo.y, wo.z));
        EXPECT_EQ(reflected->eta, 1);
        auto transmitted = glass.Sample_f(wo, R, Point2f(0.5f, 0.5f), TransportMode::Importance);
        ASSERT_TRUE(transmitted.has_value());
        EXPECT_EQ(transmitted->flags, BxDFFlags::SpecularTransmission);
        EXPECT_FLOAT_EQ(transmitted->pdf, 1 - R);
    }
}

TEST(DielectricBxDF, SmoothReflectedPlusTransmittedIsOne) {
    // In importance units the two branches carry f |cos| = R and T, which sum to one at
    // every angle (no absorption in a dielectric); each sample's weight is exactly one.
    DielectricBxDF glass = Smooth();
    for (Vector3f wo : Outgoing()) {
        double sum = 0;
        for (Float uc : {0.f, OneMinusEpsilon}) {
            auto bs = glass.Sample_f(wo, uc, Point2f(0.5f, 0.5f), TransportMode::Importance);
            ASSERT_TRUE(bs.has_value());
            sum += bs->f[0] * AbsCosTheta(bs->wi);
            EXPECT_NEAR(bs->f[0] * AbsCosTheta(bs->wi) / bs->pdf, 1, 1e-5);
        }
        EXPECT_NEAR(sum, 1, 1e-5) << "wo z " << wo.z;
    }
}

TEST(DielectricBxDF, SmoothTransmissionFollowsSnellAndScalesRadiance) {
    DielectricBxDF glass = Smooth();
    for (Vector3f wo : Outgoing()) {
        auto imp = glass.Sample_f(wo, OneMinusEpsilon, Point2f(0.5f, 0.5f), TransportMode::Importance);
        auto rad = glass.Sample_f(wo, OneMinusEpsilon, Point2f(0.5f, 0.5f), TransportMode::Radiance);
        ASSERT_TRUE(imp && rad);
        Float etap = IndexOnSide(imp->wi, kEta) / IndexOnSide(wo, kEta);
        EXPECT_FLOAT_EQ(imp->eta, etap);
        EXPECT_LT(imp->wi.z * wo.z, 0);
        // Snell: sin theta_t = sin theta_o / etap, and the azimuth turns by pi.
        EXPECT_NEAR(SinTheta(imp->wi), SinTheta(wo) / etap, 1e-5);
        EXPECT_NEAR(imp->wi.x * wo.y - imp->wi.y * wo.x, 0, 1e-6);
        EXPECT_LE(imp->wi.x * wo.x + imp->wi.y * wo.y, 0);
        EXPECT_NEAR(Length(imp->wi), 1, 1e-6);
        // Radiance is divided by etap^2 (pbrt-v4), importance is not.
        EXPECT_FLOAT_EQ(rad->f[0], imp->f[0] / Sqr(etap));
        EXPECT_FLOAT_EQ(rad->pdf, imp->pdf);
    }
}

TEST(DielectricBxDF, SmoothTotalInternalReflection) {
    DielectricBxDF glass = Smooth();
    Vector3f wo = Normalize(Vector3f(0.8f, 0, -0.4f));  // 63° inside; critical is 41.8°
    ASSERT_GT(SinTheta(wo), 1 / kEta);
    for (Float uc : {0.f, 0.5f, OneMinusEpsilon}) {
        auto bs = glass.Sample_f(wo, uc, Point2f(0.5f, 0.5f), TransportMode::Radiance);
        ASSERT_TRUE(bs.has_value());
        EXPECT_EQ(bs->flags, BxDFFlags::SpecularReflection);
        EXPECT_FLOAT_EQ(bs->f[0] * AbsCosTheta(bs->wi), 1);
    }
    EXPECT_FALSE(glass.Sample_f(wo, 0.5f, Point2f(0.5f, 0.5f), TransportMode::Radiance,
                                BxDFReflTransFlags::Transmission));
}

TEST(DielectricBxDF, SmoothHonoursSampleFlags) {
    DielectricBxDF glass = Smooth();
    Vector3f wo = Outgoing()[1];
    Float R = FrDielectric(CosTheta(wo), kEta);
    for (Float uc : {0.f, 0.5f, OneMinusEpsilon}) {
        auto r = glass.Sample_f(wo, uc, Point2f(0.5f, 0.5f), TransportMode::Importance,
                                BxDFReflTransFlags::Reflection);
        ASSERT_TRUE(r.has_value());
        EXPECT_TRUE(r->IsReflection());
        EXPECT_EQ(r->pdf, 1);
        EXPECT_FLOAT_EQ(r->f[0] * AbsCosTheta(r->wi), R);
        auto t = glass.Sample_f(wo, uc, Point2f(0.5f, 0.5f), TransportMode::Importance,
                                BxDFReflTransFlags::Transmission);
        ASSERT_TRUE(t.has_value());
        EXPECT_TRUE(t->IsTransmission());
        EXPECT_EQ(t->pdf, 1);
    }
    EXPECT_FALSE(glass.Sample_f(wo, 0.5f, Point2f(0.5f, 0.5f), TransportMode::Radiance,
                                BxDFReflTransFlags::Unset));
}

TEST(DielectricBxDF, SmoothHasNoDensity) {
    DielectricBxDF glass = Smooth();
    EXPECT_EQ(glass.Flags(), BxDFFlags::Reflection | BxDFFlags::Transmission | BxDFFlags::Specular);
    Vector3f wo = Outgoing()[1];
    ForEachSphereQuadratureNode(8, 16, [&](Vector3f wi, double) {
        EXPECT_FALSE(glass.f(wo, wi, TransportMode::Radiance));
        EXPECT_EQ(glass.PDF(wo, wi, TransportMode::Radiance), 0);
    });
    // A tangent wo has no side to scatter to.
    EXPECT_FALSE(glass.Sample_f(Vector3f(1, 0, 0), 0.5f, Point2f(0.5f, 0.5f), TransportMode::Radiance));
}

TEST(DielectricBxDF, SmoothRhoIsReflectancePlusScaledTransmittance) {
    RhoSamples in = MakeRhoSamples(1 << 14, 9);
    DielectricBxDF glass = Smooth();
    Vector3f wo = Outgoing()[1];
    Float R = FrDielectric(CosTheta(wo), kEta);
    // Radiance units, wo outside: the transmitted part is divided by eta^2.
    EXPECT_NEAR(glass.rho(wo, in.uc, in.u2)[0], R + (1 - R) / Sqr(kEta), 1e-4);
}

TEST(DielectricBxDF, IndexMatchedPassesStraightThrough) {
    for (Float alpha : {0.f, 0.4f}) {
        DielectricBxDF matched = Rough(alpha, alpha, 1);
        EXPECT_EQ(matched.Flags(), BxDFFlags::SpecularTransmission);
        for (Vector3f wo : Outgoing()) {
            auto bs = matched.Sample_f(wo, 0.3f, Point2f(0.2f, 0.7f), TransportMode::Radiance);
            ASSERT_TRUE(bs.has_value());
            EXPECT_EQ(bs->flags, BxDFFlags::SpecularTransmission);
            EXPECT_NEAR(Length(bs->wi + wo), 0, 1e-6);
            EXPECT_FLOAT_EQ(bs->f[0] * AbsCosTheta(bs->wi) / bs->pdf, 1);
            EXPECT_FALSE(matched.f(wo, -wo, TransportMode::Radiance));
        }
        matched.Regularize();
        EXPECT_EQ(matched.Flags(), BxDFFlags::SpecularTransmission);
    }
}

// ---------------------------------------------------------------------------------------
// Rough dielectric

TEST(DielectricBxDF, RoughSamplingFollowsItsDensity) {
    for (auto [ax, ay] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {0.8f, 0.8f}, {0.1f, 0.5f}})
        ExpectChi2(Rough(ax, ay), Outgoing());
    // The interface seen from the denser side (eta < 1: the outside is the denser medium).
    ExpectChi2(Rough(0.3f, 0.3f, 1 / 1.33f), Outgoing());
}

TEST(DielectricBxDF, RoughSamplingHonoursSampleFlags) {
    DielectricBxDF glass = Rough(0.3f, 0.3f);
    std::vector<Vector3f> wos{Outgoing()[1], Outgoing()[3]};
    ExpectChi2(glass, wos, BxDFReflTransFlags::Reflection);
    ExpectChi2(glass, wos, BxDFReflTransFlags::Transmission);
}

TEST(DielectricBxDF, RoughProperties) {
    for (auto [ax, ay] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {0.1f, 0.5f}})
        ExpectProperties(Rough(ax, ay));
    ExpectProperties(Rough(0.3f, 0.3f, 1 / 1.33f));
}

TEST(DielectricBxDF, RoughTransmissionIsAdjointNotReciprocal) {
    // pbrt-v4's rule: radiance-mode f(wo, wi) is importance-mode f(wi, wo), and
    // f(wo, wi) / eta_o^2 is symmetric, eta_o being the index on wo's side.
    DielectricBxDF glass = Rough(0.3f, 0.2f);
    RNG rng(41);
    int checked = 0;
    for (int i = 0; i < 4096; ++i) {
        Vector3f wo = SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        Vector3f wi = SampleUniformHemisphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        if (wo.z > 0)
            wi = -wi;  // across the surface
        Float fRad = glass.f(wo, wi, TransportMode::Radiance)[0];
        Float fImpSwapped = glass.f(wi, wo, TransportMode::Importance)[0];
        Float fRadSwapped = glass.f(wi, wo, TransportMode::Radiance)[0];
        if (fRad == 0 && fRadSwapped == 0)
            continue;
        ++checked;
        EXPECT_NEAR(fRad, fImpSwapped, 1e-5f * std::max(fRad, 1.f)) << propertydetail::Str(wo) << " " << propertydetail::Str(wi);
        Float a = fRad / Sqr(IndexOnSide(wo, kEta)), b = fRadSwapped / Sqr(IndexOnSide(wi, kEta));
        EXPECT_NEAR(a, b, 2e-5f * std::max(a, 1.f)) << propertydetail::Str(wo) << " " << propertydetail::Str(wi);
    }
    EXPECT_GT(checked, 500);
    // The scaling itself: from outside, radiance-mode transmission is importance / eta^2.
    Vector3f wo = Outgoing()[1], wi = Normalize(Vector3f(-0.2f, -0.1f, -0.9f));
    Float fImp = glass.f(wo, wi, TransportMode::Importance)[0];
    ASSERT_GT(fImp, 0);
    EXPECT_FLOAT_EQ(glass.f(wo, wi, TransportMode::Radiance)[0], fImp / Sqr(kEta));
}

TEST(DielectricBxDF, RoughSampleWeightsNeverExceedOne) {
    // With visible-normal sampling and Fresnel branch selection, a sample's weight is the
    // masking ratio G / G1 <= 1 in importance units (the energy bound per sample); in
    // radiance units transmission is further divided by etap^2.
    for (auto [ax, ay] : {std::pair{0.05f, 0.05f}, {0.3f, 0.3f}, {0.8f, 0.8f}, {0.1f, 0.5f}})
        for (Vector3f wo : Outgoing())
            for (TransportMode mode : {TransportMode::Importance, TransportMode::Radiance}) {
                DielectricBxDF glass = Rough(ax, ay);
                double sum = 0;
                auto samples = SampleWeights(glass, wo, mode, 4096);
                for (auto &[bs, weight] : samples) {
                    Float bound = (mode == TransportMode::Radiance) ? 1 / Sqr(bs.eta) : 1;
                    EXPECT_LE(weight, bound * (1 + 1e-4f)) << glass.ToString() << bs.ToString();
                    sum += weight;
                }
                if (mode == TransportMode::Importance) {
                    EXPECT_LE(sum / 4096, 1);
                }
            }
}

TEST(DielectricBxDF, RoughRhoAgreesWithQuadrature) {
    // rho() (sampling) against quadrature of f() |cos| over both hemispheres.
    RhoSamples in = MakeRhoSamples(1 << 16, 5);
    DielectricBxDF glass = Rough(0.4f, 0.4f);
    for (Vector3f wo : Outgoing()) {
        double expected = DirectionalAlbedo(glass, wo, Frame::FromZ(Vector3f(0, 0, 1)), {0.0}, 512, 512);
        EXPECT_NEAR(glass.rho(wo, in.uc, in.u2)[0], expected, 0.01 * expected) << propertydetail::Str(wo);
        if (wo.z > 0) {
            EXPECT_LE(expected, 1);
        }
    }
}

TEST(DielectricBxDF, RegularizeRoughensOnlyNearSpecularInterfaces) {
    DielectricBxDF glass = Smooth();
    ASSERT_TRUE(IsSpecular(glass.Flags()));
    glass.Regularize();
    EXPECT_EQ(glass.Flags(), BxDFFlags::GlossyReflection | BxDFFlags::GlossyTransmission);
    // Now a density exists, and its sampling is exact.
    ExpectChi2(glass, {Outgoing()[1]});
    DielectricBxDF rough = Rough(0.5f, 0.5f), roughRegularized = rough;
    roughRegularized.Regularize();
    Vector3f wo = Outgoing()[1], wi = Normalize(Vector3f(-0.3f, 0.1f, -0.8f));
    EXPECT_EQ(rough.f(wo, wi, TransportMode::Radiance), roughRegularized.f(wo, wi, TransportMode::Radiance));
}

// ---------------------------------------------------------------------------------------
// Thin dielectric

TEST(ThinDielectricBxDF, SlabReflectanceSumsInterReflections) {
    ThinDielectricBxDF pane(kEta);
    EXPECT_EQ(pane.Flags(), BxDFFlags::Reflection | BxDFFlags::Transmission | BxDFFlags::Specular);
    for (Vector3f wo : Outgoing()) {
        Float r = FrDielectric(AbsCosTheta(wo), kEta), t = 1 - r;
        // R = r + t^2 r (1 + r^2 + r^4 + ...)
        Float R = r + Sqr(t) * r / (1 - Sqr(r));
        auto refl = pane.Sample_f(wo, 0, Point2f(0.5f, 0.5f), TransportMode::Radiance);
        auto trans = pane.Sample_f(wo, OneMinusEpsilon, Point2f(0.5f, 0.5f), TransportMode::Radiance);
        ASSERT_TRUE(refl && trans);
        EXPECT_EQ(refl->flags, BxDFFlags::SpecularReflection);
        EXPECT_EQ(refl->wi, Vector3f(-wo.x, -wo.y, wo.z));
        EXPECT_FLOAT_EQ(refl->pdf, R);
        EXPECT_FLOAT_EQ(refl->f[0] * AbsCosTheta(refl->wi), R);
        // Straight through, into the same medium: no bending, no eta, no radiance scaling.
        EXPECT_EQ(trans->flags, BxDFFlags::SpecularTransmission);
        EXPECT_EQ(trans->wi, -wo);
        EXPECT_EQ(trans->eta, 1);
        EXPECT_FLOAT_EQ(trans->pdf, 1 - R);
        EXPECT_NEAR(refl->f[0] * AbsCosTheta(refl->wi) + trans->f[0] * AbsCosTheta(trans->wi), 1, 1e-6);
    }
}

TEST(ThinDielectricBxDF, RhoIsOneAndNoDensity) {
    ThinDielectricBxDF pane(kEta);
    RhoSamples in = MakeRhoSamples(1 << 16, 4);
    for (Vector3f wo : Outgoing()) {
        EXPECT_NEAR(pane.rho(wo, in.uc, in.u2)[0], 1, 1e-5);
        EXPECT_FALSE(pane.f(wo, -wo, TransportMode::Radiance));
        EXPECT_EQ(pane.PDF(wo, -wo, TransportMode::Radiance), 0);
    }
    // Directional albedo is exactly one; averaging it over wo drawn uniformly adds the
    // estimator's own noise (each sample contributes 2 |cos theta_o|): 5 sigma here.
    EXPECT_NEAR(pane.rho(in.u1, in.uc, in.u2)[0], 1, 0.012);
    EXPECT_FALSE(pane.Sample_f(Vector3f(0, 1, 0), 0.5f, Point2f(0.5f, 0.5f), TransportMode::Radiance));
}

TEST(ThinDielectricBxDF, HonoursSampleFlagsAndRegularizeKeepsIt) {
    ThinDielectricBxDF pane(kEta);
    Vector3f wo = Outgoing()[2];
    auto r = pane.Sample_f(wo, OneMinusEpsilon, Point2f(0.5f, 0.5f), TransportMode::Radiance,
                           BxDFReflTransFlags::Reflection);
    ASSERT_TRUE(r.has_value());
    EXPECT_TRUE(r->IsReflection());
    EXPECT_EQ(r->pdf, 1);
    auto t = pane.Sample_f(wo, 0, Point2f(0.5f, 0.5f), TransportMode::Radiance,
                           BxDFReflTransFlags::Transmission);
    ASSERT_TRUE(t.has_value());
    EXPECT_TRUE(t->IsTransmission());
    pane.Regularize();
    EXPECT_EQ(pane.ToString(), "[ ThinDielectricBxDF eta: 1.5 ]");
}

// ---------------------------------------------------------------------------------------
// Diffuse transmission

TEST(DiffuseTransmissionBxDF, SamplingFollowsItsDensity) {
    DiffuseTransmissionBxDF leaf(SampledSpectrum(0.2f, 0.5f, 0.3f, 0.4f),
                                 SampledSpectrum(0.6f, 0.3f, 0.1f, 0.2f));
    ExpectChi2(leaf, {Outgoing()[1], Outgoing()[3]});
    ExpectChi2(leaf, {Outgoing()[2]}, BxDFReflTransFlags::Transmission);
}

TEST(DiffuseTransmissionBxDF, Properties) {
    DiffuseTransmissionBxDF leaf(SampledSpectrum(0.2f, 0.5f, 0.3f, 0.4f),
                                 SampledSpectrum(0.6f, 0.3f, 0.1f, 0.2f));
    ExpectProperties(leaf);
    // Nothing bends or changes medium: transmission is reciprocal too.
    RNG rng(5);
    for (int i = 0; i < 256; ++i) {
        Vector3f wo = SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        Vector3f wi = SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        PropertyResult r = CheckReciprocity(leaf, wo, wi);
        EXPECT_TRUE(r.passed) << r.message;
    }
}

TEST(DiffuseTransmissionBxDF, AlbedoIsReflectancePlusTransmittance) {
    DiffuseTransmissionBxDF leaf(SampledSpectrum(0.25f, 0.5f, 0.1f, 0.4f),
                                 SampledSpectrum(0.5f, 0.25f, 0.9f, 0.2f));
    RhoSamples in = MakeRhoSamples(1 << 16, 8);
    const double expected[NSpectrumSamples] = {0.75, 0.75, 1.0, 0.6};
    for (Vector3f wo : Outgoing())
        for (int c = 0; c < NSpectrumSamples; ++c) {
            EXPECT_NEAR(DirectionalAlbedo(leaf, wo, Frame::FromZ(Vector3f(0, 0, 1)), {0.0}, 64, 64, c),
                        expected[c], 1e-5);
            // Sampling picks a side by the largest channel, so other channels' weights
            // vary; the mean still converges.
            EXPECT_NEAR(leaf.rho(wo, in.uc, in.u2)[c], expected[c], 0.01);
        }
}

TEST(DiffuseTransmissionBxDF, FlagsFollowTheSpectra) {
    SampledSpectrum black(0.f), grey(0.5f);
    EXPECT_EQ(DiffuseTransmissionBxDF(grey, grey).Flags(),
              BxDFFlags::DiffuseReflection | BxDFFlags::DiffuseTransmission);
    EXPECT_EQ(DiffuseTransmissionBxDF(black, grey).Flags(), BxDFFlags::DiffuseTransmission);
    EXPECT_EQ(DiffuseTransmissionBxDF(grey, black).Flags(), BxDFFlags::DiffuseReflection);
    EXPECT_EQ(DiffuseTransmissionBxDF(black, black).Flags(), BxDFFlags::Unset);
    EXPECT_FALSE(DiffuseTransmissionBxDF(black, black)
                     .Sample_f(Vector3f(0, 0, 1), 0.5f, Point2f(0.5f, 0.5f), TransportMode::Radiance));
    // Only the transmitted side when reflection is excluded: PDF integrates to one there.
    DiffuseTransmissionBxDF leaf(grey, grey);
    Vector3f wo = Outgoing()[1];
    double integral = IntegrateSphere(
        [&](Vector3f wi) {
            return leaf.PDF(wo, wi, TransportMode::Radiance, BxDFReflTransFlags::Transmission);
        },
        Frame::FromZ(Vector3f(0, 0, 1)), {0.0}, 64, 64);
    EXPECT_NEAR(integral, 1, 1e-5);
}
