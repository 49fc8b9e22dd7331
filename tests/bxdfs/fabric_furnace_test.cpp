// White furnace: the directional albedo a(wo) = ∫ f(wo, wi) cos θi dωi of FabricBxDF, by quadrature,
// against the reference albedos; never above 1 for either normalization; exactly 1 at the peak for the
// unit-peak one; Regularize keeps it so; rho() estimates it.
#include "tests/support/bxdf_properties.h"

#include "pbrt_ext/bxdfs/albedo.h"
#include "pbrt_ext/bxdfs/fabric_albedo.h"
#include "pbrt_ext/util/rng.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

// The reference albedos are accurate to ~1e-9; our quadrature of the float BxDF to ~1e-4.
constexpr double kAlbedoTolerance = 1e-3;
// Energy bound, with room only for the quadrature's own error.
constexpr double kQuadratureError = 2e-4;
// The unit-peak normalization reaches 1 at its peak to within this (docs/fabric/unit_peak.md).
constexpr double kUnitPeakMinimum = 0.99;
// rho() by 2^16 importance samples against quadrature: > 10 standard errors for every case here.
constexpr double kRhoRelativeTolerance = 5e-3;

double Albedo(const FabricBxDF &bxdf, Vector3f wo, int nPhi = 768) {
    return FabricDirectionalAlbedo(bxdf, wo, nPhi);
}

Vector3f FromPolarAzimuth(Float polarDegrees, Float azimuthDegrees) {
    Float theta = Radians(polarDegrees), phi = Radians(azimuthDegrees);
    return SphericalDirection(std::sin(theta), std::cos(theta), phi);
}

// Directions above the surface: a (polar, azimuth) grid, plus a 1° scan of the plane of the thread
// (azimuth 0 and 180°) up to 89.9°. The albedo depends on wo only through its fiber latitude
// (docs/fabric/unit_peak.md), and that scan passes through every latitude: it finds the peak, which
// for elevated threads lies at polar β - θ* away from the thread, or at grazing.
std::vector<Vector3f> DirectionGrid() {
    std::vector<Vector3f> dirs{Vector3f(0, 0, 1)};
    for (Float polar : {15.f, 30.f, 45.f, 60.f, 75.f, 88.f})
        for (Float az = 0; az < 360; az += 30)
            dirs.push_back(FromPolarAzimuth(polar, az));
    for (Float polar = 1; polar < 90; polar += 1)
        for (Float az : {0.f, 180.f})
            dirs.push_back(FromPolarAzimuth(polar, az));
    // Above β ≈ 46° the peak is the grazing limit, approached steeply (1 % per 0.1° at β = 90°).
    for (Float polar : {89.9f, 89.99f, 89.999f})
        for (Float az : {0.f, 180.f})
            dirs.push_back(FromPolarAzimuth(polar, az));
    return dirs;
}

struct FurnaceCase {
    Float n, elevation;
};
const FurnaceCase kCases[] = {{0, 0},   {0.5f, 0}, {1, 0},   {2.5f, 0},  {5, 0},   {30, 0},
                              {100, 0}, {1, 30},   {5, 30},  {30, 30},   {1, 60},  {5, 60},
                              {30, 60}, {2.5f, 45}, {10, 75}, {10, 90}};

FabricBxDF Make(FurnaceCase c, FabricNormalization norm) {
    return FabricBxDF(SampledSpectrum(1), FabricExponent{c.n},
                      FabricBxDF::ThreadDirection(0, c.elevation), FabricSampling::Best, norm);
}

double MaxAlbedo(const FabricBxDF &bxdf) {
    double peak = 0;
    for (Vector3f wo : DirectionGrid())
        peak = std::max(peak, Albedo(bxdf, wo, 128));
    return peak;
}

}  // namespace

// Reference albedos for tangent and elevated threads: the shared reference values (n = 1, 5, 10, 30)
// and docs/fabric/elevated_albedo.py (n = 1, 2.5, 5, 30 at β = 30°, 60°), both accurate to ~1e-9.
class FabricFurnaceReference : public testing::TestWithParam<const char *> {};

TEST_P(FabricFurnaceReference, AlbedoMatchesReference) {
    std::ifstream in(std::string(PBRT_EXT_TEST_DATA_DIR) + "/" + GetParam());
    nlohmann::json ref = nlohmann::json::parse(in);
    const nlohmann::json &cases = ref.is_array() ? ref : ref["directional_albedo"];
    ASSERT_GE(cases.size(), 38u);
    for (const auto &c : cases) {
        // The reference thread is T = (cos β, 0, sin β).
        FabricBxDF bxdf(SampledSpectrum(1), FabricExponent{c["n"].get<Float>()},
                        FabricBxDF::ThreadDirection(0, c["beta_deg"].get<Float>()));
        Vector3f w(c["w"][0].get<Float>(), c["w"][1].get<Float>(), c["w"][2].get<Float>());
        EXPECT_NEAR(Albedo(bxdf, w), c["albedo_paper_over_Io"].get<double>(), kAlbedoTolerance)
            << c.dump();
    }
}

INSTANTIATE_TEST_SUITE_P(Fabric, FabricFurnaceReference,
                         testing::Values("fabric_reference.json",
                                         "fabric_elevated_albedo.json"));

TEST(FabricFurnace, NeverAboveOneForEitherNormalization) {
    for (FurnaceCase c : kCases)
        for (auto norm : {FabricNormalization::Paper, FabricNormalization::UnitPeak})
            EXPECT_LE(MaxAlbedo(Make(c, norm)), 1 + kQuadratureError)
                << "n " << c.n << " elevation " << c.elevation << " " << Make(c, norm).ToString();
}

TEST(FabricFurnace, UnitPeakReachesOneAtItsPeak) {
    for (FurnaceCase c : kCases) {
        FabricBxDF bxdf = Make(c, FabricNormalization::UnitPeak);
        EXPECT_GE(MaxAlbedo(bxdf), kUnitPeakMinimum) << bxdf.ToString();
    }
}

TEST(FabricFurnace, TangentThreadPeaksAtOneExactlyPerpendicularToTheThread) {
    // For a tangent thread the albedo peaks at θ = 0 (wi ⊥ T), where unit peak is exact by construction.
    for (Float n : {0.f, 1.f, 3.3f, 30.f, 1000.f}) {
        FabricBxDF bxdf(SampledSpectrum(1), FabricExponent{n}, Vector3f(1, 0, 0),
                        FabricSampling::Best, FabricNormalization::UnitPeak);
        EXPECT_NEAR(Albedo(bxdf, Vector3f(0, 0, 1)), 1, kQuadratureError)
            << "n " << n;
    }
}

TEST(FabricRegularize, WidensTheLobeAndKeepsTheFurnaceBounds) {
    for (FurnaceCase c : kCases) {
        for (auto norm : {FabricNormalization::Paper, FabricNormalization::UnitPeak}) {
            FabricBxDF sharp = Make(c, norm), regularized = sharp;
            regularized.Regularize();
            // pbrt-v4's alpha rule on alpha = 1/(n+1): narrow lobes get at most n = 9 and at
            // least halve their width; lobes with n <= 7/3 are left alone.
            if (c.n > Float(7) / 3) {
                EXPECT_LT(regularized.Exponent(), sharp.Exponent());
                EXPECT_LE(regularized.Exponent(), 9 + 1e-4f);
                EXPECT_NEAR(regularized.Exponent(),
                            std::max(Float(7) / 3, std::min(Float(9), (c.n + 1) / 2 - 1)), 1e-3f);
            } else {
                EXPECT_EQ(regularized.Exponent(), sharp.Exponent());
            }
            double peak = MaxAlbedo(regularized);
            EXPECT_LE(peak, 1 + kQuadratureError) << regularized.ToString();
            if (norm == FabricNormalization::UnitPeak) {
                EXPECT_GE(peak, kUnitPeakMinimum) << regularized.ToString();
            }
        }
    }
}

TEST(FabricRho, DirectionalRhoAgreesWithQuadrature) {
    RhoSamples in = MakeRhoSamples(1 << 16, 1);
    for (FurnaceCase c : {FurnaceCase{1, 0}, FurnaceCase{5, 0}, FurnaceCase{30, 30}}) {
        FabricBxDF bxdf = Make(c, FabricNormalization::Paper);
        // Not wo = T (polar 60°, azimuth 0 at β = 30°), where the albedo is ~4e-7.
        for (Vector3f wo : {Vector3f(0, 0, 1), FromPolarAzimuth(50, 200), FromPolarAzimuth(45, 120)}) {
            double expected = Albedo(bxdf, wo);
            double estimate = bxdf.rho(wo, in.uc, in.u2)[0];
            EXPECT_NEAR(estimate, expected, kRhoRelativeTolerance * expected)
                << bxdf.ToString() << " wo polar " << SphericalTheta(wo);
        }
    }
}

TEST(FabricRho, HemisphericalRhoIsTheCosineWeightedMeanAlbedo) {
    // ρ_hh = (1/π) ∫ a(wo) cos θo dωo; its quadrature against rho(u1, uc, u2).
    RhoSamples in = MakeRhoSamples(1 << 16, 2);
    FabricBxDF bxdf(SampledSpectrum(1), FabricExponent{5}, Vector3f(1, 0, 0));
    double expected = IntegrateSphere(
                          [&](Vector3f wo) {
                              return wo.z > 0 ? Albedo(bxdf, wo, 64) * wo.z : 0.0;
                          },
                          Frame::FromZ(Vector3f(0, 0, 1)), 24, 24) /
                      Pi;
    // The estimator's per-sample relative sd is 0.84 (uniform wo): a standard error of 0.33 % at
    // 2^16 samples; the threshold is 5 of them.
    EXPECT_NEAR(bxdf.rho(in.u1, in.uc, in.u2)[0], expected, 5 * 0.0033 * expected);
}
