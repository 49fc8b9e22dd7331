// The stochastic layered BxDF (CoatedDiffuseBxDF, CoatedConductorBxDF) and the helpers it
// walks with (Henyey-Greenstein phase function, exponential distances, hashing).
//
// Sample_f's pdf is only proportional (pdfIsProportional), so the chi-square harness does
// not apply to it; instead:
//  - Sample_f and f are two independent random walks estimating the same integrals, so
//    the sample weights f |cos| / pdf binned by direction must agree with the integral of
//    f() |cos| over every bin (a z-test on both estimates' variances);
//  - a smooth coat over a Lambertian base has a closed-form albedo (the coat's Fresnel
//    reflectance plus the geometric series of inter-reflections under it);
//  - an index-matched clear coat leaves the base exactly as it was;
//  - rho <= 1 for every configuration, reciprocity of reflection in expectation, and
//    deterministic evaluation.
#include "tests/support/bxdf_properties.h"
#include "tests/support/chi2.h"

#include "pbrt_ext/bxdfs/albedo.h"
#include "pbrt_ext/bxdfs/layered.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/spherequadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

// Chi-square tests in this file (Šidák correction), α = 0.01 overall.
constexpr int kChi2Tests = 4;
constexpr Float kEta = 1.5f;
const SampledSpectrum kMetalEta(0.2f, 0.9f, 1.1f, 1.2f), kMetalK(3.9f, 2.4f, 2.2f, 2.1f);

DielectricBxDF Coat(Float alpha, Float eta = kEta) {
    return DielectricBxDF(eta, TrowbridgeReitzDistribution(alpha, alpha));
}

CoatedDiffuseBxDF CoatedDiffuse(Float coatAlpha, Float R, Float thickness, Float albedo,
                                Float g = 0, int maxDepth = 10, int nSamples = 1,
                                Float eta = kEta) {
    return CoatedDiffuseBxDF(Coat(coatAlpha, eta), DiffuseBxDF(SampledSpectrum(R)), thickness,
                             SampledSpectrum(albedo), g, maxDepth, nSamples);
}

CoatedConductorBxDF CoatedConductor(Float coatAlpha, Float metalAlpha, Float thickness,
                                    Float albedo, Float g = 0) {
    return CoatedConductorBxDF(
        Coat(coatAlpha),
        ConductorBxDF(TrowbridgeReitzDistribution(metalAlpha, metalAlpha), kMetalEta, kMetalK),
        thickness, SampledSpectrum(albedo), g, 10, 1);
}

std::vector<Vector3f> Outgoing() {
    return {Vector3f(0, 0, 1), Normalize(Vector3f(0.5f, 0.2f, 0.8f)),
            Normalize(Vector3f(-0.9f, 0.3f, 0.15f))};
}

// The cosine-weighted hemispherical average of the Fresnel reflectance seen from inside
// the coat (total internal reflection included): the fraction of diffuse light below the
// coat that the coat sends back down.
double InternalDiffuseReflectance(Float eta) {
    constexpr int n = 100000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        double mu = (i + 0.5) / n;
        sum += FrDielectric(Float(-mu), eta) * 2 * mu / n;
    }
    return sum;
}

// Albedo of a Lambertian base (reflectance R) under a smooth, non-absorbing dielectric
// coat: specular reflection F, plus what enters (1 - F), bounces between base and coat,
// and leaves through the coat with probability 1 - r_i each time it reaches it.
double CoatedLambertianAlbedo(Float cosTheta_o, double R, Float eta) {
    double F = FrDielectric(cosTheta_o, eta), ri = InternalDiffuseReflectance(eta);
    return F + (1 - F) * R * (1 - ri) / (1 - R * ri);
}

// Cells over the sphere: bands in cos theta on each side of the surface, halves in phi.
constexpr int kCosBands = 5, kPhiHalves = 2, kCells = 2 * kCosBands * kPhiHalves;

int CellOf(Vector3f w) {
    int band = std::min(kCosBands - 1, int(std::abs(w.z) * kCosBands));
    int side = w.z > 0 ? 0 : 1;
    int half = w.y >= 0 ? 0 : 1;
    return (side * kCosBands + band) * kPhiHalves + half;
}

// For every cell: Sample_f's weights binned by direction against the integral of
// f() |cos| estimated with uniform directions. Specular samples carry Dirac deltas that
// f() leaves out, so they are left out here too. Returns the failures, one per line.
template <typename BxDF>
std::string CompareSampledWithEvaluated(const BxDF &bxdf, Vector3f wo, int nSampled,
                                        int nEvaluated) {
    std::vector<MeanEstimate> sampled(kCells), evaluated(kCells);
    RNG rng(11);
    for (int i = 0; i < nSampled; ++i) {
        Float uc = rng.Uniform<Float>(), u0 = rng.Uniform<Float>();
        Point2f u(u0, rng.Uniform<Float>());
        pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, uc, u, TransportMode::Radiance);
        if (!bs || bs->IsSpecular())
            continue;
        double weight = bs->f[0] * AbsCosTheta(bs->wi) / bs->pdf;
        for (int c = 0; c < kCells; ++c)
            sampled[c].Add(c == CellOf(bs->wi) ? weight : 0);
    }
    for (int i = 0; i < nEvaluated; ++i) {
        Float u0 = rng.Uniform<Float>();
        Vector3f wi = SampleUniformSphere(Point2f(u0, rng.Uniform<Float>()));
        double value = bxdf.f(wo, wi, TransportMode::Radiance)[0] * AbsCosTheta(wi) /
                       UniformSpherePDF();
        for (int c = 0; c < kCells; ++c)
            evaluated[c].Add(c == CellOf(wi) ? value : 0);
    }
    std::string failures;
    for (int c = 0; c < kCells; ++c) {
        double a = sampled[c].Mean(nSampled), b = evaluated[c].Mean(nEvaluated);
        double sigma = std::sqrt(sampled[c].VarianceOfMean(nSampled) +
                                 evaluated[c].VarianceOfMean(nEvaluated));
        if (std::abs(a - b) > 5 * sigma + 1e-4)
            failures += "cell " + std::to_string(c) + ": Sample_f " + std::to_string(a) +
                        " vs f " + std::to_string(b) + " (sigma " + std::to_string(sigma) +
                        ")\n";
    }
    return failures;
}

// Where Sample_f() sends its samples and its energy, inside a cone of half-angle 10 degrees
// around wo's mirror direction (a coat of roughness 0.05 reflects nearly all of its
// highlight into it), against the integral of PDF() over the same cone.
struct HighlightShare {
    double samples = 0;  // fraction of Sample_f's samples in the cone
    double energy = 0;   // fraction of the sample weights f |cos| / pdf in the cone
    double pdf = 0;      // integral of PDF() over the cone
};

template <typename BxDF>
HighlightShare MeasureHighlight(const BxDF &bxdf, Vector3f wo) {
    const Float cosCone = std::cos(Radians(10.f));
    Vector3f mirror(-wo.x, -wo.y, wo.z);
    constexpr int nSamples = 1 << 16;
    HighlightShare share;
    double totalWeight = 0;
    RNG rng(17);
    for (int i = 0; i < nSamples; ++i) {
        Float uc = rng.Uniform<Float>(), u0 = rng.Uniform<Float>();
        pstd::optional<BSDFSample> bs =
            bxdf.Sample_f(wo, uc, Point2f(u0, rng.Uniform<Float>()), TransportMode::Radiance);
        if (!bs)
            continue;
        double weight = bs->f.Average() * AbsCosTheta(bs->wi) / bs->pdf;
        totalWeight += weight;
        if (Dot(bs->wi, mirror) > cosCone) {
            share.samples += 1.0 / nSamples;
            share.energy += weight;
        }
    }
    share.energy /= totalWeight;
    // PDF() averaged over a stratified grid of directions uniform in the cone.
    constexpr int n = 256;
    Frame frame = Frame::FromZ(mirror);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Vector3f w = SampleUniformCone(Point2f((i + 0.5f) / n, (j + 0.5f) / n), cosCone);
            share.pdf += bxdf.PDF(wo, frame.FromLocal(w), TransportMode::Radiance) /
                         (UniformConePDF(cosCone) * n * n);
        }
    return share;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Helpers: phase function, exponential distances, hashing

TEST(HenyeyGreenstein, IsNormalizedAndSampledExactly) {
    Vector3f wo = Normalize(Vector3f(0.3f, -0.5f, 0.7f));
    for (Float g : {-0.7f, 0.f, 0.3f, 0.9f}) {
        double integral = IntegrateSphere([&](Vector3f w) { return HenyeyGreenstein(Dot(wo, w), g); },
                                          Frame::FromZ(wo), {-0.9, -0.5}, 128, 16);
        EXPECT_NEAR(integral, 1, 1e-4) << "g " << g;

        Chi2Options opts;
        opts.numTests = kChi2Tests;
        opts.seed = 7;
        auto sample = [&](Point2f u, Float) -> pstd::optional<Vector3f> {
            Float pdf;
            Vector3f wi = SampleHenyeyGreenstein(wo, g, u, &pdf);
            if (std::abs(pdf - HenyeyGreenstein(Dot(wo, wi), g)) > 1e-4f * pdf)
                return Vector3f(NAN, NAN, NAN);  // counted as invalid: the pdf disagrees
            return wi;
        };
        auto pdf = [&](Vector3f wi) { return HenyeyGreenstein(Dot(wo, wi), g); };
        Chi2Result r = Chi2TestSampler(sample, pdf, opts);
        EXPECT_TRUE(r.passed) << "g " << g << "\n" << r.message;
    }
}

// pbrt-v4 clamps g to [-0.99, 0.99]: the scene's g = 1 (or beyond) scatters as g = 0.99
// instead of losing the energy (0 at |g| = 1) or going negative (|g| > 1).
TEST(HenyeyGreenstein, ClampsGAsPbrtV4) {
    Vector3f wo = Normalize(Vector3f(0.3f, -0.5f, 0.7f)), wi = Normalize(Vector3f(-0.2f, 0.6f, -0.6f));
    for (Float g : {1.f, 1.5f, -1.f, -3.f}) {
        Float clamped = g > 0 ? 0.99f : -0.99f;
        EXPECT_EQ(HenyeyGreenstein(Dot(wo, wi), g), HenyeyGreenstein(Dot(wo, wi), clamped)) << g;
        Float pdf, clampedPdf;
        Vector3f w = SampleHenyeyGreenstein(wo, g, Point2f(0.3f, 0.7f), &pdf);
        Vector3f wClamped = SampleHenyeyGreenstein(wo, clamped, Point2f(0.3f, 0.7f), &clampedPdf);
        EXPECT_EQ(w, wClamped) << g;
        EXPECT_EQ(pdf, clampedPdf) << g;
        EXPECT_GT(pdf, 0) << g;
    }
}

TEST(HenyeyGreenstein, MeanCosineIsMinusG) {
    // wo and wi both point away from the scattering point: forward scattering (g > 0)
    // sends wi along -wo, so the mean of Dot(wo, wi) is -g.
    Vector3f wo(0, 0, 1);
    RNG rng(3);
    for (Float g : {-0.5f, 0.2f, 0.8f}) {
        double sum = 0;
        constexpr int n = 100000;
        for (int i = 0; i < n; ++i) {
            Float u0 = rng.Uniform<Float>();
            Float pdf;
            sum += Dot(wo, SampleHenyeyGreenstein(wo, g, Point2f(u0, rng.Uniform<Float>()), &pdf));
        }
        EXPECT_NEAR(sum / n, -g, 0.01) << "g " << g;
    }
}

TEST(SampleExponential, InvertsAndMatchesItsDensity) {
    for (Float a : {0.5f, 1.f, 4.f}) {
        for (Float u : {0.f, 0.1f, 0.5f, 0.9f, 0.999f})
            EXPECT_NEAR(InvertExponentialSample(SampleExponential(u, a), a), u, 1e-5);
        // The density is the derivative of the inverted sample (the CDF).
        Float x = 0.7f, h = 1e-3f;
        EXPECT_NEAR((InvertExponentialSample(x + h, a) - InvertExponentialSample(x - h, a)) / (2 * h),
                    ExponentialPDF(x, a), 1e-3);
        double mean = 0;
        for (int i = 0; i < 10000; ++i)
            mean += SampleExponential((i + 0.5f) / 10000, a) / 10000;
        EXPECT_NEAR(mean, 1 / a, 1e-2 / a);
    }
}

TEST(Hash, IsDeterministicAndSpreadsValues) {
    Vector3f w(0.1f, 0.2f, 0.3f);
    EXPECT_EQ(Hash(w), Hash(Vector3f(0.1f, 0.2f, 0.3f)));
    EXPECT_NE(Hash(w), Hash(Vector3f(0.1f, 0.2f, std::nextafter(0.3f, 1.f))));
    EXPECT_NE(Hash(0.5f, Point2f(0.1f, 0.2f)), Hash(0.5f, Point2f(0.2f, 0.1f)));
    std::set<uint64_t> hashes, mixed;
    for (int i = 0; i < 1000; ++i) {
        hashes.insert(Hash(i));
        mixed.insert(MixBits(uint64_t(i)) >> 48);  // even the top bits differ
    }
    EXPECT_EQ(hashes.size(), 1000u);
    EXPECT_GT(mixed.size(), 990u);
    // Tails of every length take part.
    const unsigned char bytes[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    std::set<uint64_t> prefixes;
    for (size_t len = 0; len <= 9; ++len)
        prefixes.insert(MurmurHash64A(bytes, len, 0));
    EXPECT_EQ(prefixes.size(), 10u);
}

// ---------------------------------------------------------------------------------------
// The layered BxDF

TEST(LayeredBxDF, FlagsFollowTheLayers) {
    EXPECT_EQ(CoatedDiffuse(0, 0.5f, 0.01f, 0).Flags(),
              BxDFFlags::Reflection | BxDFFlags::Specular | BxDFFlags::Diffuse);
    EXPECT_EQ(CoatedConductor(0.3f, 0.2f, 0.01f, 0).Flags(), BxDFFlags::GlossyReflection);
    // A scattering slab makes any stack diffuse.
    EXPECT_EQ(CoatedConductor(0.3f, 0.2f, 0.01f, 0.5f).Flags(), BxDFFlags::DiffuseReflection);
    // Regularize() roughens the coat, so the specular part goes.
    CoatedConductorBxDF c = CoatedConductor(0, 0, 0.01f, 0);
    EXPECT_EQ(c.Flags(), BxDFFlags::SpecularReflection);
    c.Regularize();
    EXPECT_EQ(c.Flags(), BxDFFlags::GlossyReflection);
    EXPECT_STREQ(CoatedDiffuseBxDF::Name(), "CoatedDiffuseBxDF");
    EXPECT_STREQ(CoatedConductorBxDF::Name(), "CoatedConductorBxDF");
    EXPECT_EQ(CoatedDiffuse(0, 0.5f, 0.01f, 0).ToString().rfind("[ CoatedDiffuseBxDF top: [ DielectricBxDF", 0), 0u);
}

TEST(LayeredBxDF, EvaluationIsDeterministic) {
    CoatedDiffuseBxDF bxdf = CoatedDiffuse(0.3f, 0.6f, 0.1f, 0.4f, 0.3f);
    Vector3f wo = Outgoing()[1], wi = Normalize(Vector3f(-0.3f, 0.4f, 0.6f));
    SampledSpectrum f = bxdf.f(wo, wi, TransportMode::Radiance);
    Float pdf = bxdf.PDF(wo, wi, TransportMode::Radiance);
    auto bs = bxdf.Sample_f(wo, 0.6f, Point2f(0.3f, 0.8f), TransportMode::Radiance);
    ASSERT_TRUE(bs.has_value());
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(bxdf.f(wo, wi, TransportMode::Radiance), f);
        EXPECT_EQ(bxdf.PDF(wo, wi, TransportMode::Radiance), pdf);
        auto again = bxdf.Sample_f(wo, 0.6f, Point2f(0.3f, 0.8f), TransportMode::Radiance);
        ASSERT_TRUE(again.has_value());
        EXPECT_EQ(again->wi, bs->wi);
        EXPECT_EQ(again->f, bs->f);
        EXPECT_EQ(again->pdf, bs->pdf);
    }
    EXPECT_TRUE(bs->pdfIsProportional);
}

TEST(LayeredBxDF, SampledWeightsMatchEvaluation) {
    CoatedDiffuseBxDF roughCoatScattering = CoatedDiffuse(0.3f, 0.6f, 0.1f, 0.4f, 0.3f);
    CoatedDiffuseBxDF smoothCoat = CoatedDiffuse(0, 0.7f, 0.01f, 0);
    CoatedConductorBxDF coatedMetal = CoatedConductor(0.2f, 0.3f, 0.01f, 0);
    CoatedConductorBxDF coatedMetalScattering = CoatedConductor(0.4f, 0.1f, 0.05f, 0.7f, -0.3f);
    // A dark base, where Sample_f() reflects off the coat most often.
    CoatedDiffuseBxDF darkBase = CoatedDiffuse(0.05f, 0.05f, 0.01f, 0);
    // Above the surface, oblique and grazing, and below it (the layers are two-sided).
    for (Vector3f wo : {Outgoing()[1], Outgoing()[2], -Outgoing()[1]}) {
        std::string r = CompareSampledWithEvaluated(roughCoatScattering, wo, 1 << 17, 1 << 16);
        EXPECT_TRUE(r.empty()) << roughCoatScattering.ToString() << "\n" << r;
        r = CompareSampledWithEvaluated(smoothCoat, wo, 1 << 17, 1 << 16);
        EXPECT_TRUE(r.empty()) << smoothCoat.ToString() << "\n" << r;
        r = CompareSampledWithEvaluated(coatedMetal, wo, 1 << 17, 1 << 16);
        EXPECT_TRUE(r.empty()) << coatedMetal.ToString() << "\n" << r;
        r = CompareSampledWithEvaluated(coatedMetalScattering, wo, 1 << 17, 1 << 16);
        EXPECT_TRUE(r.empty()) << coatedMetalScattering.ToString() << "\n" << r;
        r = CompareSampledWithEvaluated(darkBase, wo, 1 << 17, 1 << 16);
        EXPECT_TRUE(r.empty()) << darkBase.ToString() << "\n" << r;
    }
}

TEST(LayeredBxDF, SamplesTheHighlightInProportionToItsEnergy) {
    // Veach's MIS plates: a glossy coat over a dark base, where the coat's highlight is half
    // of what the surface reflects. Choosing it by its Fresnel reflectance alone (pbrt-v4)
    // puts 5 % of the samples there for 51-54 % of the energy (measured: 49-52 % of the
    // samples here); the share of samples must be within a factor of 1.5 of the share of
    // energy for a dark, a grey and a white base.
    for (Float R : {0.05f, 0.5f, 0.95f})
        for (Vector3f wo : {Outgoing()[0], Outgoing()[1]}) {
            HighlightShare share = MeasureHighlight(CoatedDiffuse(0.05f, R, 0.01f, 0), wo);
            EXPECT_GT(share.samples, share.energy / 1.5) << "R " << R << " wo.z " << wo.z;
            EXPECT_LT(share.samples, share.energy * 1.5) << "R " << R << " wo.z " << wo.z;
        }
}

TEST(LayeredBxDF, PdfMatchesTheSampledDensityOfTheHighlight) {
    // The MIS weights of a highlight are as good as PDF() is there. Its coat reflection
    // term is exact, so over the highlight's cone PDF() integrates to 0.9 (the share left
    // by the uniform density) of Sample_f's fraction of samples, up to the estimated
    // inner term (measured: 0.87-0.99). pbrt-v4's PDF() counts the coat's reflection as
    // if it were always chosen: 12-15 times Sample_f's share here, which leaves light
    // sampling almost no weight in the highlight.
    for (Float R : {0.05f, 0.5f, 0.95f})
        for (Vector3f wo : {Outgoing()[0], Outgoing()[1]}) {
            HighlightShare share = MeasureHighlight(CoatedDiffuse(0.05f, R, 0.01f, 0), wo);
            EXPECT_NEAR(share.pdf / share.samples, 0.9, 0.15) << "R " << R << " wo.z " << wo.z;
        }
}

TEST(LayeredBxDF, SmoothCoatOverLambertianMatchesClosedForm) {
    // A very thin non-absorbing coat and a deep walk, so that the closed form applies.
    RhoSamples in = MakeRhoSamples(1 << 16, 21);
    for (Float R : {0.5f, 1.f}) {
        CoatedDiffuseBxDF bxdf = CoatedDiffuse(0, R, 1e-5f, 0, 0, 100);
        for (Vector3f wo : Outgoing()) {
            double expected = CoatedLambertianAlbedo(CosTheta(wo), R, kEta);
            EXPECT_NEAR(bxdf.rho(wo, in.uc, in.u2)[0], expected, 0.01) << "R " << R << " wo.z " << wo.z;
            // f() leaves out the coat's mirror reflection.
            double evaluated = DirectionalAlbedo(bxdf, wo, Frame::FromZ(Vector3f(0, 0, 1)), {0.0}, 64, 128);
            EXPECT_NEAR(evaluated, expected - FrDielectric(CosTheta(wo), kEta), 0.01)
                << "R " << R << " wo.z " << wo.z;
        }
    }
}

TEST(LayeredBxDF, IndexMatchedClearCoatIsTheBase) {
    // eta = 1, no scattering, (almost) no thickness: light passes the coat untouched.
    CoatedDiffuseBxDF bxdf = CoatedDiffuse(0, 0.4f, 1e-7f, 0, 0, 10, 1, 1);
    RNG rng(2);
    for (int i = 0; i < 200; ++i) {
        Float u0 = rng.Uniform<Float>(), u1 = rng.Uniform<Float>();
        Vector3f wo = SampleUniformHemisphere(Point2f(u0, u1));
        u0 = rng.Uniform<Float>();
        Vector3f wi = SampleUniformHemisphere(Point2f(u0, rng.Uniform<Float>()));
        if (wo.z < 1e-2f || wi.z < 1e-2f)
            continue;
        EXPECT_NEAR(bxdf.f(wo, wi, TransportMode::Radiance)[0], 0.4f * InvPi, 1e-4);
        EXPECT_FALSE(bxdf.f(wo, -wi, TransportMode::Radiance));
    }
    RhoSamples in = MakeRhoSamples(1 << 12, 6);
    for (Vector3f wo : Outgoing())
        EXPECT_NEAR(bxdf.rho(wo, in.uc, in.u2)[0], 0.4f, 1e-3);
}

TEST(LayeredBxDF, RhoNeverExceedsOne) {
    RhoSamples in = MakeRhoSamples(1 << 15, 13);
    std::vector<CoatedDiffuseBxDF> diffuse{
        CoatedDiffuse(0, 1, 0.01f, 0), CoatedDiffuse(0.3f, 1, 0.01f, 0),
        CoatedDiffuse(0, 1, 0.1f, 1, 0.5f), CoatedDiffuse(0.5f, 0.8f, 1, 0.9f, -0.4f),
        CoatedDiffuse(0.2f, 1, 0.01f, 0, 0, 100)};
    std::vector<CoatedConductorBxDF> conductor{
        CoatedConductor(0, 0, 0.01f, 0), CoatedConductor(0.3f, 0.05f, 0.01f, 0),
        CoatedConductor(0.1f, 0.6f, 0.2f, 1, 0.7f)};
    auto check = [&](const auto &bxdf) {
        for (Vector3f wo : Outgoing()) {
            SampledSpectrum rho = bxdf.rho(wo, in.uc, in.u2);
            // 1 + the estimate's noise (weights stay O(1); 2^15 samples).
            for (int c = 0; c < NSpectrumSamples; ++c)
                EXPECT_LE(rho[c], 1.01) << bxdf.ToString() << " wo.z " << wo.z;
        }
        SampledSpectrum rhoHH = bxdf.rho(in.u1, in.uc, in.u2);
        for (int c = 0; c < NSpectrumSamples; ++c)
            EXPECT_LE(rhoHH[c], 1.01) << bxdf.ToString();
    };
    for (const auto &b : diffuse)
        check(b);
    for (const auto &b : conductor)
        check(b);
}

TEST(LayeredBxDF, FiniteNonNegativeEverywhere) {
    BxDFCheckOptions opts;
    opts.sampleCount = 1024;
    for (const CoatedDiffuseBxDF &bxdf :
         {CoatedDiffuse(0, 0.5f, 0.01f, 0), CoatedDiffuse(0.3f, 0.6f, 0.1f, 0.4f, 0.3f)})
        for (Vector3f wo : PropertyTestDirections()) {
            PropertyResult r = CheckFiniteNonNegative(bxdf, wo, opts);
            EXPECT_TRUE(r.passed) << bxdf.ToString() << "\n" << r.message;
        }
    CoatedConductorBxDF metal = CoatedConductor(0.2f, 0.3f, 0.01f, 0.5f);
    for (Vector3f wo : PropertyTestDirections()) {
        PropertyResult r = CheckFiniteNonNegative(metal, wo, opts);
        EXPECT_TRUE(r.passed) << metal.ToString() << "\n" << r.message;
    }
}

TEST(LayeredBxDF, PdfIsPositiveWhereverFIs) {
    // MIS needs a nonzero density wherever there is energy; the uniform share of PDF()
    // guarantees it. Its inner term is pbrt-v4's estimate, a density per solid angle
    // inside the coat, which refraction compresses by about eta^2; weighted by how often
    // Sample_f() enters the layers, the whole integrates to one for an index-matched coat
    // and to 0.96 - 1.56 for eta = 1.5 (pbrt-v4's, which also counts the coat's reflection
    // as if always chosen: 1.6 - 2.5). MIS stays unbiased all the same, since both of its
    // weights use this one PDF().
    auto integrate = [](const auto &bxdf, Vector3f wo, bool opaque) {
        double integral = 0;
        ForEachSphereQuadratureNode(32, 64, [&](Vector3f wi, double weight) {
            Float pdf = bxdf.PDF(wo, wi, TransportMode::Radiance);
            if (bxdf.f(wo, wi, TransportMode::Radiance)) {
                EXPECT_GT(pdf, 0);
            }
            if (opaque && wi.z < 0) {
                EXPECT_FLOAT_EQ(pdf, 0.1f / (4 * Pi));  // only the uniform share
            }
            integral += weight * pdf;
        });
        return integral;
    };
    for (Vector3f wo : Outgoing()) {
        EXPECT_NEAR(integrate(CoatedDiffuse(0, 0.5f, 0.01f, 0, 0, 10, 1, 1), wo, true), 1, 1e-3);
        double coated = integrate(CoatedConductor(0.3f, 0.2f, 0.05f, 0.3f), wo, true);
        EXPECT_GT(coated, 0.5);
        EXPECT_LT(coated, 2);
    }
}

TEST(LayeredBxDF, ReflectionIsReciprocalInExpectation) {
    // Each call is an estimate; with many walks per call the two directions agree.
    CoatedDiffuseBxDF bxdf = CoatedDiffuse(0.3f, 0.6f, 0.1f, 0.4f, 0.3f, 10, 4096);
    CoatedConductorBxDF metal(Coat(0.3f),
                              ConductorBxDF(TrowbridgeReitzDistribution(0.3f, 0.3f), kMetalEta, kMetalK),
                              0.05f, SampledSpectrum(0.5f), 0, 10, 4096);
    const std::pair<Vector3f, Vector3f> pairs[] = {
        {Normalize(Vector3f(0.5f, 0.2f, 0.8f)), Normalize(Vector3f(-0.3f, 0.4f, 0.6f))},
        {Normalize(Vector3f(0.1f, -0.7f, 0.4f)), Normalize(Vector3f(0.2f, 0.1f, 0.9f))}};
    for (auto [wo, wi] : pairs) {
        for (int c = 0; c < NSpectrumSamples; c += 2) {
            Float a = bxdf.f(wo, wi, TransportMode::Radiance)[c], b = bxdf.f(wi, wo, TransportMode::Radiance)[c];
            EXPECT_NEAR(a, b, 0.04 * std::max(a, b));
            a = metal.f(wo, wi, TransportMode::Radiance)[c], b = metal.f(wi, wo, TransportMode::Radiance)[c];
            EXPECT_NEAR(a, b, 0.04 * std::max(a, b));
        }
    }
}

TEST(LayeredBxDF, TwoSidedAndSampleFlags) {
    CoatedDiffuseBxDF bxdf = CoatedDiffuse(0.3f, 0.6f, 0.1f, 0.4f, 0.3f);
    Vector3f wo = Outgoing()[1], wi = Normalize(Vector3f(-0.3f, 0.4f, 0.6f));
    // Seen from below, the layer is mirrored.
    EXPECT_EQ(bxdf.f(-wo, -wi, TransportMode::Radiance), bxdf.f(wo, wi, TransportMode::Radiance));
    EXPECT_EQ(bxdf.PDF(-wo, -wi, TransportMode::Radiance), bxdf.PDF(wo, wi, TransportMode::Radiance));
    auto up = bxdf.Sample_f(wo, 0.6f, Point2f(0.3f, 0.8f), TransportMode::Radiance);
    auto down = bxdf.Sample_f(-wo, 0.6f, Point2f(0.3f, 0.8f), TransportMode::Radiance);
    ASSERT_TRUE(up && down);
    EXPECT_EQ(down->wi, -up->wi);
    // An opaque base transmits nothing: no transmission samples, zero density across.
    RNG rng(8);
    int reflected = 0;
    for (int i = 0; i < 1000; ++i) {
        Float uc = rng.Uniform<Float>(), u0 = rng.Uniform<Float>();
        Point2f u(u0, rng.Uniform<Float>());
        EXPECT_FALSE(bxdf.Sample_f(wo, uc, u, TransportMode::Radiance, BxDFReflTransFlags::Transmission));
        auto bs = bxdf.Sample_f(wo, uc, u, TransportMode::Radiance, BxDFReflTransFlags::Reflection);
        if (bs) {
            ++reflected;
            EXPECT_TRUE(bs->IsReflection());
            EXPECT_TRUE(bs->pdfIsProportional);
        }
    }
    EXPECT_GT(reflected, 500);
    EXPECT_EQ(bxdf.PDF(wo, wi, TransportMode::Radiance, BxDFReflTransFlags::Transmission), 0);
    EXPECT_EQ(bxdf.PDF(wo, -wi, TransportMode::Radiance, BxDFReflTransFlags::Reflection), 0);
    EXPECT_FALSE(bxdf.Sample_f(wo, 0.5f, Point2f(0.5f, 0.5f), TransportMode::Radiance, BxDFReflTransFlags::Unset));
}

TEST(LayeredBxDF, SampledWeightsStayFiniteOnDeepGlossyWalks) {
    // A glossy coat over a polished metal: each event's density is in the hundreds, and
    // walks of tens of events took Sample_f's f and pdf products past a float's range
    // (inf / inf weights, 5 in 2^17 samples here before they were rescaled).
    CoatedConductorBxDF bxdf(Coat(0.05f),
                             ConductorBxDF(TrowbridgeReitzDistribution(0.1f, 0.1f),
                                           SampledSpectrum(0.2f), SampledSpectrum(3.9f)),
                             0.01f, SampledSpectrum(0.f), 0, 100, 1);
    RNG rng(9);
    int nonFinite = 0;
    for (int i = 0; i < (1 << 17); ++i) {
        Float uc = rng.Uniform<Float>(), u0 = rng.Uniform<Float>();
        pstd::optional<BSDFSample> bs = bxdf.Sample_f(Vector3f(0, 0, 1), uc,
                                                      Point2f(u0, rng.Uniform<Float>()),
                                                      TransportMode::Importance);
        if (bs)
            nonFinite += !std::isfinite(bs->f[0] / bs->pdf);
    }
    EXPECT_EQ(nonFinite, 0);
}
