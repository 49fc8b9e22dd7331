// Numerical stress: FabricBxDF never returns NaN, Inf or a negative value from f, PDF or Sample_f, and
// never a sample below the surface with a positive pdf, for random and adversarial inputs: grazing
// directions, directions equal to ±thread, unnormalized, tiny and denormal vectors, exponents up to 1e4,
// roughness outside [0, 1], zero color, threads along the normal.
#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/util/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace pbrt;

namespace {

constexpr int kBxDFs = 20000;          // random BxDF configurations
constexpr int kCallsPerBxDF = 200;     // direction pairs per configuration, each f + PDF + Sample_f
constexpr FabricSampling kSamplers[] = {FabricSampling::Uniform, FabricSampling::Cosine,
                                        FabricSampling::Paper, FabricSampling::TruncatedSinPhi,
                                        FabricSampling::Best};

class AdversarialInputs {
  public:
    explicit AdversarialInputs(uint64_t seed) : rng(seed) {}

    Float U() { return rng.Uniform<Float>(); }

    // A unit direction, often grazing or close to the poles of a fiber.
    Vector3f Direction(Vector3f thread) {
        Vector3f w = SampleUniformSphere(Point2f(U(), U()));
        switch (rng.Uniform<uint32_t>() % 8) {
        case 0:  // grazing: tiny (or zero, or denormal) z
            w.z = Float(std::ldexp(U() - 0.5f, -int(rng.Uniform<uint32_t>() % 140)));
            break;
        case 1:  // exactly ± the thread
            w = U() < 0.5f ? thread : -thread;
            break;
        case 2:  // within a few ulps of the thread
            w = Normalize(thread + Vector3f(U() - 0.5f, U() - 0.5f, U() - 0.5f) * 1e-6f);
            break;
        default:
            break;
        }
        return Scale(w);
    }

    // Unnormalized, denormal or huge lengths: the BxDF must stay finite (its value need not be right).
    Vector3f Scale(Vector3f w) {
        switch (rng.Uniform<uint32_t>() % 10) {
        case 0:
            return w * Float(1e-41);  // denormal components
        case 1:
            return w * Float(3e4);
        case 2:
            return w * (0.5f + U());
        default:
            return w;
        }
    }

    FabricBxDF BxDF() {
        Vector3f thread = ThreadFor(rng.Uniform<uint32_t>() % 6);
        // Zero, ordinary and (invalid, clamped to zero) negative colors.
        SampledSpectrum color(U() < 0.1f ? 0.f : U() < 0.1f ? -U() : U());
        FabricSampling sampling = kSamplers[rng.Uniform<uint32_t>() % 5];
        FabricNormalization norm =
            U() < 0.5f ? FabricNormalization::Paper : FabricNormalization::UnitPeak;
        FabricBxDF bxdf = U() < 0.5f
                              ? FabricBxDF(color, -2 + 5 * U(), thread, sampling, norm)
                              : FabricBxDF(color, FabricExponent{Exponent()}, thread, sampling, norm);
        if (U() < 0.2f)
            bxdf.Regularize();
        return bxdf;
    }

  private:
    Vector3f ThreadFor(uint32_t kind) {
        switch (kind) {
        case 0:
            return Vector3f(0, 0, U() < 0.5f ? 1 : -1);  // along the normal
        case 1:
            return Vector3f(1, 0, 1e-30f);  // tangent up to a denormal-scale elevation
        case 2:
            return Vector3f(0, 0, 0);  // degenerate: the BxDF picks a default
        default:
            return SampleUniformSphere(Point2f(U(), U())) * (0.1f + 10 * U());
        }
    }

    Float Exponent() {
        switch (rng.Uniform<uint32_t>() % 4) {
        case 0:
            return 1e4f * U();
        case 1:
            return 1e4f;
        case 2:
            return std::numeric_limits<Float>::denorm_min();
        default:
            return 40 * U();
        }
    }

    RNG rng;
};

bool Valid(Float v) { return std::isfinite(v) && v >= 0; }
bool Valid(const SampledSpectrum &s) { return Valid(s[0]) && Valid(s[1]) && Valid(s[2]); }

}  // namespace

TEST(FabricStress, NoNaNInfOrNegativeOutputForAdversarialInputs) {
    AdversarialInputs in(20171115);
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
