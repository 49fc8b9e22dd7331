// Adversarial inputs for FabricBxDF, shared by the stress test and the stress benchmark: grazing
// (tiny, zero, denormal z) directions, directions equal or within ulps of ±thread, unnormalized,
// denormal and huge vectors, exponents up to 1e4 and down to the smallest denormal, roughness
// outside [0, 1], zero and negative colors, threads along the normal, tangent or of zero length,
// every sampler, both normalizations, regularized or not. Deterministic for a seed.
#pragma once

#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/util/rng.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace pbrt {

class FabricAdversarialInputs {
  public:
    explicit FabricAdversarialInputs(uint64_t seed) : rng(seed) {}

    Float U() { return rng.Uniform<Float>(); }
    uint32_t Pick(uint32_t n) { return rng.Uniform<uint32_t>() % n; }

    // A unit direction, often grazing or close to the poles of a fiber, often rescaled.
    Vector3f Direction(Vector3f thread) {
        Vector3f w = SampleUniformSphere(Point2f(U(), U()));
        switch (Pick(8)) {
        case 0:  // grazing: tiny (or zero, or denormal) z
            w.z = Float(std::ldexp(U() - 0.5f, -int(Pick(140))));
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

    FabricBxDF BxDF() {
        static constexpr FabricSampling samplers[] = {
            FabricSampling::Uniform, FabricSampling::Cosine, FabricSampling::Paper,
            FabricSampling::TruncatedSinPhi, FabricSampling::Best};
        Vector3f thread = Thread();
        // Zero, ordinary and (invalid, clamped to zero) negative colors.
        SampledSpectrum color(U() < 0.1f ? 0.f : U() < 0.1f ? -U() : U());
        FabricSampling sampling = samplers[Pick(5)];
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
    // Unnormalized, denormal or huge lengths: the BxDF must stay finite (its value need not be right).
    Vector3f Scale(Vector3f w) {
        switch (Pick(10)) {
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

    Vector3f Thread() {
        switch (Pick(6)) {
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
        switch (Pick(4)) {
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

}  // namespace pbrt
