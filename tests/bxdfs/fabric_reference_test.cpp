// FabricBxDF against the independent reference values of tests/data/fabric_reference.json (computed in
// 60-digit arithmetic and by quadrature with the Python scripts of the fabric derivations): the
// normalization, the exact sampler densities, and the lobe's symmetry.
#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/util/rng.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>

using namespace pbrt;

namespace {

// Float evaluation of quantities known to double precision: relative agreement required.
constexpr double kNormalizationTolerance = 1e-5;
constexpr double kPdfTolerance = 1e-5;

const nlohmann::json &Reference() {
    static const nlohmann::json ref = [] {
        std::ifstream in(std::string(PBRT_EXT_TEST_DATA_DIR) + "/fabric_reference.json");
        return nlohmann::json::parse(in);
    }();
    return ref;
}

Vector3f ToVector(const nlohmann::json &v) {
    return Vector3f(v[0].get<Float>(), v[1].get<Float>(), v[2].get<Float>());
}

double RelativeError(double value, double reference) {
    return std::abs(value - reference) / std::abs(reference);
}

}  // namespace

TEST(FabricNormalization, InverseIoMatchesReferenceForIntegerExponents) {
    for (auto &[key, value] : Reference()["inv_Io"].items()) {
        Float n = std::stof(key);
        EXPECT_LT(RelativeError(FabricBxDF::InverseIo(n), value.get<double>()),
                  kNormalizationTolerance)
            << "n = " << n;
    }
}

TEST(FabricNormalization, InverseIoMatchesReferenceForRealExponents) {
    for (auto &[key, value] : Reference()["Io_noninteger"].items()) {
        Float n = std::stof(key);
        EXPECT_LT(RelativeError(1 / FabricBxDF::InverseIo(n), value.get<double>()),
                  kNormalizationTolerance)
            << "n = " << n;
    }
}

TEST(FabricNormalization, InverseIoFollowsItsAsymptoticSeriesForHugeExponents) {
    // 1/J = X + 3/X - 9/X² + 45/X³ (REPORT §8), X = n + 1, J = I_o / 4π: four terms reach 1e-11 here.
    for (Float n : {1000.f, 1e4f, 1e5f}) {
        double X = double(n) + 1, invJ = X + 3 / X - 9 / (X * X) + 45 / (X * X * X);
        EXPECT_LT(RelativeError(FabricBxDF::InverseIo(n), invJ / (4 * M_PI)),
                  kNormalizationTolerance)
            << "n = " << n;
    }
}

TEST(FabricNormalization, InverseIcIsTheAlbedoAtNormalIncidenceOfTheUnnormalizedLobe) {
    // At n = 0 the lobe is constant: I_c = π (a Lambertian albedo of 1 needs 1/π).
    EXPECT_LT(RelativeError(FabricBxDF::InverseIc(0), 1 / M_PI), kNormalizationTolerance);
    // I_c / I_o is the peak albedo with the paper's normalization: 0.5332 (n=1) ... 0.6342 (n=30).
    for (auto [n, peak] : {std::pair{1.f, 0.533240563288398}, std::pair{30.f, 0.6342383669131979}}) {
        double ratio = FabricBxDF::InverseIo(n) / FabricBxDF::InverseIc(n);
        EXPECT_NEAR(ratio, peak, 1e-5) << "n = " << n;
    }
}

TEST(FabricExponent, RoughnessMapsAsThePaper) {
    EXPECT_EQ(FabricBxDF::RoughnessToExponent(0), 30);
    EXPECT_EQ(FabricBxDF::RoughnessToExponent(1), 1);
    EXPECT_EQ(FabricBxDF::RoughnessToExponent(0.5f), 9);  // ceil(1 + 29/4)
    EXPECT_FLOAT_EQ(FabricBxDF::RoughnessToExponent(0.5f, true), 8.25f);
    // Out of range and NaN roughness clamp into [0, 1].
    EXPECT_EQ(FabricBxDF::RoughnessToExponent(-3), 30);
    EXPECT_EQ(FabricBxDF::RoughnessToExponent(7), 1);
    EXPECT_EQ(FabricBxDF::RoughnessToExponent(std::nanf("")), 30);
}

TEST(FabricThread, ArtistAnglesGiveTheDocumentedDirection) {
    Vector3f t = FabricBxDF::ThreadDirection(90, 30);
    EXPECT_NEAR(t.x, 0, 1e-6);
    EXPECT_NEAR(t.y, std::cos(M_PI / 6), 1e-6);
    EXPECT_NEAR(t.z, 0.5, 1e-6);
    EXPECT_NEAR(Length(FabricBxDF::ThreadDirection(17, -40)), 1, 1e-6);
}

// The reference densities are for a tangent thread along +x, with the keys of the samplers that
// FABRIC_MATH names: the paper's (uniform azimuth, independent sign) and S4 (truncated, sin φ).
TEST(FabricPdf, SamplerDensitiesMatchReference) {
    const std::pair<FabricSampling, const char *> samplers[] = {
        {FabricSampling::Paper, "pdf_uniform_azimuth_independent_sign"},
        {FabricSampling::TruncatedSinPhi, "pdf_truncated_sin_azimuth"}};
    for (auto [sampling, key] : samplers)
        for (const auto &c : Reference()["pdf_values"]) {
            FabricBxDF bxdf(SampledSpectrum(1), FabricExponent{c["n"].get<Float>()},
                            Vector3f(1, 0, 0), sampling);
            Float pdf = bxdf.PDF(ToVector(c["wo"]), ToVector(c["wi"]), TransportMode::Radiance);
            EXPECT_LT(RelativeError(pdf, c[key].get<double>()), kPdfTolerance) << key << c.dump();
        }
}

TEST(FabricLobe, IsReciprocalForRandomDirectionsAndThreads) {
    RNG rng(7);
    int checked = 0;
    for (int i = 0; i < 200000; ++i) {
        auto dir = [&] {
            return SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        };
        Vector3f wo = dir(), wi = dir(), thread = dir();
        FabricBxDF bxdf(SampledSpectrum(1), FabricExponent{1 + 40 * rng.Uniform<Float>()}, thread);
        Float a = bxdf.f(wo, wi, TransportMode::Radiance)[0];
        Float b = bxdf.f(wi, wo, TransportMode::Importance)[0];
        // The evaluation is symmetric in its arguments: equal to the last bit, not merely close.
        ASSERT_EQ(a, b)
            << "wo " << wo.x << " " << wo.y << " " << wo.z << " wi " << wi.x << " " << wi.y << " "
            << wi.z;
        checked += a > 0;
    }
    EXPECT_GT(checked, 50000);  // the test saw the lobe, not only zeros
}
