// FabricDiffuseBxDF: the fabric lobe over a Lambertian base weighted by what the lobe leaves over.
// The mixture sampler follows PDF() (chi-square); Sample_f is f() and PDF(); f is reciprocal, finite
// and non-negative; the directional albedo never exceeds 1 (quadrature, white over white); a black
// color or a black base leaves exactly the other BxDF.
#include "tests/support/bxdf_properties.h"
#include "tests/support/chi2.h"

#include "pbrt_ext/bxdfs/albedo.h"
#include "pbrt_ext/bxdfs/diffuse.h"
#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/bxdfs/fabric_albedo.h"
#include "pbrt_ext/bxdfs/fabricdiffuse.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/spherequadrature.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

// Energy bound, with room only for the quadrature's own error: at nPhi = 256 it overestimates the
// exact unit peak of a tangent thread by 4e-5.
constexpr double kQuadratureError = 1e-4;
// For white over white the base fills what the lobe leaves: the bound is tight up to the unit-peak
// table's margin (≤ 0.4 %, docs/fabric/unit_peak.md) at the fabric's peak direction.
constexpr double kTightnessMinimum = 0.99;

struct Case {
    Float n, elevation;  // exponent; thread elevation in degrees (thread angle 30° about N)
    FabricNormalization normalization;
    SampledSpectrum color, diffuse;
    Float woPolar, woAzimuth;  // degrees
};

const SampledSpectrum kBright(0.9f, 0.8f, 0.7f, 0.6f), kDark(0.08f, 0.05f, 0.02f, 0.03f);

// n 1/5/30, elevations 0/45, both normalizations, dark and bright colors and bases; wo from the
// normal to grazing and below the surface.
const Case kCases[] = {
    {1, 0, FabricNormalization::Paper, kBright, SampledSpectrum(0.8f, 0.6f, 0.9f, 0.7f), 40, 70},
    {5, 0, FabricNormalization::UnitPeak, kDark, SampledSpectrum(0.9f), 60, 10},
    {30, 0, FabricNormalization::Paper, SampledSpectrum(1), SampledSpectrum(1), 20, 200},
    {30, 45, FabricNormalization::UnitPeak, SampledSpectrum(0.2f, 0.15f, 0.1f, 0.05f), kBright, 70, 120},
    {5, 45, FabricNormalization::Paper, kDark, kDark, 30, 300},
    {1, 45, FabricNormalization::UnitPeak, SampledSpectrum(0.6f), SampledSpectrum(0.5f), 130, 45},
    {30, 0, FabricNormalization::UnitPeak, SampledSpectrum(0.5f), SampledSpectrum(0.9f), 85, 30},
    {5, 0, FabricNormalization::Paper, SampledSpectrum(0.7f), SampledSpectrum(0.4f), 0, 0},
};
constexpr int kNumCases = sizeof(kCases) / sizeof(kCases[0]);

Vector3f FromPolarAzimuth(Float polarDegrees, Float azimuthDegrees) {
    Float theta = Radians(polarDegrees), phi = Radians(azimuthDegrees);
    return SphericalDirection(std::sin(theta), std::cos(theta), phi);
}

FabricBxDF MakeFabric(Float n, Float elevation, FabricNormalization norm, SampledSpectrum color,
                      Float threadAngle = 30) {
    return FabricBxDF(color, FabricExponent{n}, FabricBxDF::ThreadDirection(threadAngle, elevation),
                      FabricSampling::Best, norm);
}

FabricDiffuseBxDF Make(const Case &c) {
    return FabricDiffuseBxDF(MakeFabric(c.n, c.elevation, c.normalization, c.color), c.diffuse);
}

Vector3f Outgoing(const Case &c) { return FromPolarAzimuth(c.woPolar, c.woAzimuth); }

const char *NormalizationName(FabricNormalization norm) {
    return norm == FabricNormalization::Paper ? "Paper" : "UnitPeak";
}

std::string NormalizationParamName(const testing::TestParamInfo<FabricNormalization> &info) {
    return NormalizationName(info.param);
}

std::string CaseName(const testing::TestParamInfo<Case> &info) {
    const Case &c = info.param;
    char name[96];
    std::snprintf(name, sizeof(name), "%d_n%g_elevation%g_%s_wo%g", int(info.index), c.n,
                  c.elevation, NormalizationName(c.normalization), c.woPolar);
    return name;
}

// a(wo) of channel 0 by quadrature: the fabric lobe by its own rule (sharp in the fiber latitude),
// the rest of f, a constant on each hemisphere, by a plain rule in the normal frame.
double Albedo(const FabricDiffuseBxDF &bxdf, Vector3f wo, int nPhi = 256) {
    const FabricBxDF &fabric = bxdf.Fabric();
    double rest = IntegrateSphere(
        [&](Vector3f wi) {
            return double(bxdf.f(wo, wi, TransportMode::Radiance)[0] -
                          fabric.f(wo, wi, TransportMode::Radiance)[0]) *
                   std::abs(wi.z);
        },
        Frame::FromZ(Vector3f(0, 0, 1)), {0.0}, 8, 16);
    return FabricDirectionalAlbedo(fabric, wo, nPhi) + rest;
}

// The albedo depends on wo only through its fiber latitude: the plane of the thread (azimuth 0 and
// 180°, thread angle 0) passes through every latitude. 1° steps, then toward grazing, where the peak
// lies for threads above ≈ 46°.
double MaxAlbedoOverThreadPlane(const FabricDiffuseBxDF &bxdf) {
    std::vector<Float> polars;
    for (Float p = 0; p < 90; p += 1)
        polars.push_back(p);
    for (Float p : {89.5f, 89.9f, 89.99f, 89.999f})
        polars.push_back(p);
    double peak = 0;
    for (Float polar : polars)
        for (Float azimuth : {0.f, 180.f})
            peak = std::max(peak, Albedo(bxdf, FromPolarAzimuth(polar, azimuth)));
    return peak;
}

FabricDiffuseBxDF WhiteOverWhite(Float n, Float elevation, FabricNormalization norm) {
    return FabricDiffuseBxDF(MakeFabric(n, elevation, norm, SampledSpectrum(1), 0),
                             SampledSpectrum(1));
}

// Random directions for the comparisons: on both sides of the surface.
Vector3f RandomDirection(RNG &rng) {
    Float u0 = rng.Uniform<Float>();
    return SampleUniformSphere(Point2f(u0, rng.Uniform<Float>()));
}

// a and b are the same BxDF: f, PDF and Sample_f bit for bit, for wo on every test direction.
template <typename A, typename B>
void ExpectIdentical(const A &a, const B &b) {
    EXPECT_EQ(a.Flags(), b.Flags());
    RNG rng(7);
    for (Vector3f wo : PropertyTestDirections())
        for (int i = 0; i < 256; ++i) {
            Vector3f wi = RandomDirection(rng);
            Float uc = rng.Uniform<Float>(), u0 = rng.Uniform<Float>();
            Point2f u(u0, rng.Uniform<Float>());
            EXPECT_EQ(a.f(wo, wi, TransportMode::Radiance), b.f(wo, wi, TransportMode::Radiance));
            EXPECT_EQ(a.PDF(wo, wi, TransportMode::Radiance), b.PDF(wo, wi, TransportMode::Radiance));
            pstd::optional<BSDFSample> sa = a.Sample_f(wo, uc, u, TransportMode::Radiance);
            pstd::optional<BSDFSample> sb = b.Sample_f(wo, uc, u, TransportMode::Radiance);
            ASSERT_EQ(sa.has_value(), sb.has_value());
            if (!sa)
                continue;
            EXPECT_EQ(sa->wi, sb->wi);
            EXPECT_EQ(sa->f, sb->f);
            EXPECT_EQ(sa->pdf, sb->pdf);
            EXPECT_EQ(sa->flags, sb->flags);
        }
}

}  // namespace

class FabricDiffuse_ : public testing::TestWithParam<Case> {};

// Chi-square: 1e6 samples, 32 x 64 equal-solid-angle cells (tests/support/chi2.h), α = 0.01 over the suite
// (Šidák), fixed seed.
TEST_P(FabricDiffuse_, DirectionsFollowTheReportedDensity) {
    Chi2Options opts;
    opts.numTests = kNumCases;
    opts.seed = 20170731;
    Chi2Result r = Chi2TestBxDF(Make(GetParam()), Outgoing(GetParam()), opts);
    EXPECT_TRUE(r.passed) << r.message;
    EXPECT_LE(r.integralPdf, 1 + 1e-3) << r.message;
}

// Sample_f reports f() and PDF() at its direction exactly (zero tolerance), and nothing is NaN,
// infinite or negative.
TEST_P(FabricDiffuse_, SampleIsEvaluationAndFinite) {
    BxDFCheckOptions exact;
    exact.relTolerance = 0;
    exact.absTolerance = 0;
    FabricDiffuseBxDF bxdf = Make(GetParam());
    for (Vector3f wo : PropertyTestDirections()) {
        PropertyResult match = CheckSampleMatchesEval(bxdf, wo, exact);
        EXPECT_TRUE(match.passed) << bxdf.ToString() << "\n" << match.message;
        PropertyResult finite = CheckFiniteNonNegative(bxdf, wo);
        EXPECT_TRUE(finite.passed) << bxdf.ToString() << "\n" << finite.message;
    }
}

// kd is a constant, so f is as reciprocal as the fabric lobe: to the last bit.
TEST_P(FabricDiffuse_, IsReciprocal) {
    BxDFCheckOptions exact;
    exact.relTolerance = 0;
    exact.absTolerance = 0;
    PropertyResult r = CheckReflectionReciprocity(Make(GetParam()), exact);
    EXPECT_TRUE(r.passed) << r.message;
}

INSTANTIATE_TEST_SUITE_P(Fabric, FabricDiffuse_, testing::ValuesIn(kCases), CaseName);

// The furnace: white fabric over a white base, both normalizations, thread elevations up to 80°:
// the directional albedo by quadrature never exceeds 1, and reaches it at the fabric's peak.
class FabricDiffuseFurnace_ : public testing::TestWithParam<FabricNormalization> {};

TEST_P(FabricDiffuseFurnace_, AlbedoNeverAboveOne) {
    double overall = 0;
    for (Float elevation : {0.f, 30.f, 45.f, 60.f, 80.f})
        for (Float n : {1.f, 5.f, 30.f}) {
            FabricDiffuseBxDF bxdf = WhiteOverWhite(n, elevation, GetParam());
            double peak = MaxAlbedoOverThreadPlane(bxdf);
            EXPECT_LE(peak, 1 + kQuadratureError) << bxdf.ToString();
            EXPECT_GE(peak, kTightnessMinimum) << bxdf.ToString();
            overall = std::max(overall, peak);
            std::printf("n %4g elevation %2g kd %.5f: max albedo %.6f\n", n, elevation,
                        bxdf.DiffuseWeight(), peak);
        }
    RecordProperty("max_albedo", std::to_string(overall));
}

INSTANTIATE_TEST_SUITE_P(Fabric, FabricDiffuseFurnace_,
                         testing::Values(FabricNormalization::Paper,
                                         FabricNormalization::UnitPeak),
                         NormalizationParamName);

// A colored fabric bounds only the channel of its largest component: that channel reaches 1, and
// kd = 1 - P max color keeps it there.
TEST(FabricDiffuseFurnace, ColoredFabricKeepsItsLargestChannelBelowOne) {
    FabricDiffuseBxDF bxdf(
        MakeFabric(5, 30, FabricNormalization::Paper, SampledSpectrum(0.9f, 0.5f, 0.2f, 0.6f), 0),
        SampledSpectrum(1));
    double peak = MaxAlbedoOverThreadPlane(bxdf);
    EXPECT_LE(peak, 1 + kQuadratureError) << bxdf.ToString();
    EXPECT_GE(peak, kTightnessMinimum) << bxdf.ToString();
}

TEST(FabricDiffuse, BlackColorIsTheDiffuseBxDF) {
    SampledSpectrum diffuse(0.3f, 0.6f, 0.9f, 0.45f);
    for (auto norm : {FabricNormalization::Paper, FabricNormalization::UnitPeak})
        for (Float n : {1.f, 30.f})
            ExpectIdentical(FabricDiffuseBxDF(MakeFabric(n, 45, norm, SampledSpectrum(0)), diffuse),
                            DiffuseBxDF(diffuse));
}

TEST(FabricDiffuse, BlackBaseIsTheFabricBxDF) {
    for (auto norm : {FabricNormalization::Paper, FabricNormalization::UnitPeak})
        for (Float n : {1.f, 5.f, 30.f})
            for (Float elevation : {0.f, 45.f}) {
                FabricBxDF fabric = MakeFabric(n, elevation, norm, kBright);
                ExpectIdentical(FabricDiffuseBxDF(fabric, SampledSpectrum(0)), fabric);
            }
}

// The weights: kd from the lobe's peak albedo, the lobe chosen in proportion to the albedo shares.
TEST(FabricDiffuse, WeightsFollowThePeakAlbedo) {
    FabricBxDF fabric = MakeFabric(5, 0, FabricNormalization::Paper, SampledSpectrum(0.5f, 0.4f, 0.3f, 0.4f));
    // Tangent thread: the paper normalization's peak is I_c / I_o exactly (docs/fabric.md).
    Float peak = FabricBxDF::InverseIo(5) / FabricBxDF::InverseIc(5);
    EXPECT_NEAR(fabric.PeakAlbedo(), peak, 1e-6f);
    FabricDiffuseBxDF bxdf(fabric, SampledSpectrum(0.6f));
    // The color's maximum is 0.5 and its average 0.4.
    Float kd = 1 - peak * 0.5f, wf = peak * 0.4f, wd = kd * 0.6f;
    EXPECT_NEAR(bxdf.DiffuseWeight(), kd, 1e-6f);
    EXPECT_NEAR(bxdf.FabricProbability(), wf / (wf + wd), 1e-6f);
    // Unit peak: white fabric leaves nothing for the base.
    FabricDiffuseBxDF white(MakeFabric(5, 45, FabricNormalization::UnitPeak, SampledSpectrum(1)),
                            SampledSpectrum(1));
    EXPECT_EQ(white.DiffuseWeight(), 0);
    EXPECT_EQ(white.FabricProbability(), 1);
}

// Regularize widens the fabric lobe as FabricBxDF::Regularize does and recomputes kd, so the
// furnace bound still holds.
TEST(FabricDiffuse, RegularizeWidensTheLobeAndKeepsTheBound) {
    for (Float elevation : {0.f, 45.f}) {
        FabricDiffuseBxDF bxdf = WhiteOverWhite(30, elevation, FabricNormalization::Paper);
        FabricBxDF expected = bxdf.Fabric();
        expected.Regularize();
        bxdf.Regularize();
        EXPECT_EQ(bxdf.Fabric().Exponent(), expected.Exponent());
        EXPECT_EQ(bxdf.DiffuseWeight(), 1 - expected.PeakAlbedo());
        EXPECT_LE(MaxAlbedoOverThreadPlane(bxdf), 1 + kQuadratureError) << bxdf.ToString();
    }
}

// rho() by 2^16 mixture samples against quadrature, 1 % (> 10 standard errors here).
TEST(FabricDiffuse, RhoAgreesWithQuadrature) {
    RhoSamples in = MakeRhoSamples(1 << 16, 3);
    for (const Case &c : {kCases[0], kCases[3]}) {
        FabricDiffuseBxDF bxdf = Make(c);
        for (Vector3f wo : {Vector3f(0, 0, 1), FromPolarAzimuth(50, 200)}) {
            double expected = Albedo(bxdf, wo, 768);
            EXPECT_NEAR(bxdf.rho(wo, in.uc, in.u2)[0], expected, 0.01 * expected)
                << bxdf.ToString();
        }
    }
}
