// Numerical stress: FabricBxDF never returns NaN, Inf or a negative value from f, PDF or Sample_f, and
// never a sample below the surface with a positive pdf, for random and adversarial inputs: grazing
// directions, directions equal to ±thread, unnormalized, tiny and denormal vectors, exponents up to 1e4,
// roughness outside [0, 1], zero color, threads along the normal.
#include "tests/support/fabric_adversarial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace pbrt;

namespace {

constexpr int kBxDFs = 20000;          // random BxDF configurations
constexpr int kCallsPerBxDF = 200;     // direction pairs per configuration, each f + PDF + Sample_f

bool Valid(Float v) { return std::isfinite(v) && v >= 0; }
bool Valid(const SampledSpectrum &s) { return Valid(s[0]) && Valid(s[1]) && Valid(s[2]); }

}  // namespace

TEST(FabricStress, NoNaNInfOrNegativeOutputForAdversarialInputs) {
    FabricAdversarialInputs in(20171115);
    long calls = 0, samplesReturned = 0;
    for (int b = 0; b < kBxDFs; ++b) {
        FabricBxDF bxdf = in.BxDF();
        Vector3f thread = bxdf.Thread();
        for (int i = 0; i < kCallsPerBxDF; ++i) {
            Vector3f wo = in.Direction(thread), wi = in.Direction(thread);
            SampledSpectrum f = bxdf.f(wo, wi, TransportMode::Radiance);
            Float pdf = bxdf.PDF(wo, wi, TransportMode::Radiance);
            ASSERT_TRUE(Valid(f) && Valid(pdf)) << bxdf.ToString() << " f " << f[0] << " pdf " << pdf;
            pstd::optional<BSDFSample> bs =
                bxdf.Sample_f(wo, in.U(), Point2f(in.U(), in.U()), TransportMode::Radiance);
            calls += 3;
            if (!bs)
                continue;
            ++samplesReturned;
            ASSERT_TRUE(Valid(bs->f) && Valid(bs->pdf) && bs->pdf > 0) << bxdf.ToString();
            ASSERT_TRUE(std::isfinite(bs->wi.x) && std::isfinite(bs->wi.y) &&
                        std::isfinite(bs->wi.z));
            // Reflection only: the sample lies strictly on wo's side of the surface, and PDF()
            // agrees that it can be produced.
            ASSERT_TRUE((wo.z > 0 && bs->wi.z > 0) || (wo.z < 0 && bs->wi.z < 0)) << bxdf.ToString();
            ASSERT_GT(bxdf.PDF(wo, bs->wi, TransportMode::Radiance), 0) << bxdf.ToString();
        }
    }
    EXPECT_GE(calls, 10'000'000);
    EXPECT_GT(samplesReturned, calls / 6);  // most configurations do produce samples
}

TEST(FabricStress, GrazingAndPoleDirectionsGiveFiniteDensities) {
    // The sampler's density diverges (integrably) at wi = ±T; PDF must stay finite arbitrarily close.
    FabricBxDF bxdf(SampledSpectrum(1), FabricExponent{30}, FabricBxDF::ThreadDirection(0, 60));
    Vector3f t = bxdf.Thread(), wo = Normalize(Vector3f(0.3f, -0.2f, 1));
    for (int k = 1; k < 40; ++k) {
        Float eps = std::ldexp(1.f, -k);
        Vector3f wi = Normalize(t + Vector3f(0, eps, 0));
        Float pdf = bxdf.PDF(wo, wi, TransportMode::Radiance);
        EXPECT_TRUE(Valid(pdf)) << "eps " << eps;
    }
}
