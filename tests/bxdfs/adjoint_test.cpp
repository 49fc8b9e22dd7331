// The adjoint of every BxDF, which paths traced from the lights use (bdpt, lightpath): in
// importance mode f(wo, wi) is radiance mode's f(wi, wo) (pbrt-v4's convention; for
// refraction the radiance mode carries the 1 / eta^2 scaling, tested in
// bxdfs_transmission_test.cpp). For the deterministic BxDFs the two agree to float rounding on
// random direction pairs; the layered ones estimate f by random walks seeded by the directions,
// so their two modes are independent estimates that agree on average over the pairs.
#include "pbrt_ext/bxdfs/bxdfs.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

const SampledSpectrum kEta(1.22f, 0.95f, 0.27f, 0.21f), kK(2.4f, 2.6f, 3.6f, 4.2f);

DielectricBxDF Glass(Float alpha) { return DielectricBxDF(1.5f, TrowbridgeReitzDistribution(alpha, alpha)); }
ConductorBxDF Metal(Float alpha) { return ConductorBxDF(TrowbridgeReitzDistribution(alpha, alpha), kEta, kK); }
FabricBxDF Fabric() {
    return FabricBxDF(SampledSpectrum(0.8f), 0.4f, Normalize(Vector3f(1, 0.3f, 0.2f)));
}

std::vector<std::pair<std::string, BxDF>> DeterministicBxDFs() {
    return {{"diffuse", DiffuseBxDF(SampledSpectrum(0.3f, 0.5f, 0.7f, 0.9f))},
            {"conductor", Metal(0.3f)},
            {"anisotropic conductor", ConductorBxDF(TrowbridgeReitzDistribution(0.1f, 0.5f), kEta, kK)},
            {"rough dielectric", Glass(0.3f)},
            {"rough dielectric from inside", DielectricBxDF(1 / 1.33f, TrowbridgeReitzDistribution(0.2f, 0.2f))},
            {"diffuse transmission", DiffuseTransmissionBxDF(SampledSpectrum(0.4f), SampledSpectrum(0.5f))},
            {"fabric", Fabric()},
            {"fabric with a diffuse base", FabricDiffuseBxDF(Fabric(), SampledSpectrum(0.3f))}};
}

// Directions over the whole sphere: reflection and transmission alike.
Vector3f RandomDirection(RNG &rng) {
    return SampleUniformSphere(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
}

TEST(Adjoint, ImportanceIsRadianceWithDirectionsSwapped) {
    for (const auto &[name, bxdf] : DeterministicBxDFs()) {
        RNG rng(23);
        int nonzero = 0;
        for (int i = 0; i < 20000; ++i) {
            Vector3f wo = RandomDirection(rng), wi = RandomDirection(rng);
            SampledSpectrum importance = bxdf.f(wo, wi, TransportMode::Importance);
            SampledSpectrum radiance = bxdf.f(wi, wo, TransportMode::Radiance);
            for (int c = 0; c < NSpectrumSamples; ++c)
                ASSERT_NEAR(importance[c], radiance[c], 1e-4f * std::max<Float>(1, radiance[c]))
                    << name << ": wo " << wo.x << " " << wo.y << " " << wo.z << ", wi " << wi.x
                    << " " << wi.y << " " << wi.z;
            nonzero += bool(radiance);
        }
        EXPECT_GT(nonzero, 1000) << name << ": the test saw the lobes";
    }
}

TEST(Adjoint, HairIgnoresTheModeAsInPbrtV4) {
    // The hair model is not reciprocal (its longitudinal lobes are centred on the outgoing
    // direction's reflection), and pbrt-v4's HairBxDF evaluates and samples the same way in
    // both modes; so does ours, so that bdpt's hair is pbrt-v4's.
    HairBxDF hair(0.3f, 1.55f, SampledSpectrum(0.4f), 0.3f, 0.3f, 2);
    RNG rng(31);
    int asymmetric = 0;
    for (int i = 0; i < 2000; ++i) {
        Vector3f wo = RandomDirection(rng), wi = RandomDirection(rng);
        SampledSpectrum radiance = hair.f(wo, wi, TransportMode::Radiance);
        ASSERT_EQ(hair.f(wo, wi, TransportMode::Importance), radiance);
        asymmetric += std::abs(radiance[0] - hair.f(wi, wo, TransportMode::Radiance)[0]) >
                      1e-3f * std::max<Float>(1, radiance[0]);
    }
    EXPECT_GT(asymmetric, 100);
}

TEST(Adjoint, LayeredImportanceAgreesWithRadianceOnAverage) {
    // Sums of f |cos wi| over 4000 pairs, each f an estimate from 8 random walks: within 2 %
    // (the sums' standard error is about 0.5 %).
    std::vector<std::pair<std::string, BxDF>> layered = {
        {"coated diffuse", CoatedDiffuseBxDF(Glass(0.2f), DiffuseBxDF(SampledSpectrum(0.6f)), 0.01f,
                                             SampledSpectrum(0.f), 0, 10, 8)},
        {"coated conductor", CoatedConductorBxDF(Glass(0.2f), Metal(0.3f), 0.01f, SampledSpectrum(0.f),
                                                 0, 10, 8)}};
    for (const auto &[name, bxdf] : layered) {
        RNG rng(29);
        double importance = 0, radiance = 0;
        for (int i = 0; i < 4000; ++i) {
            Vector3f wo = RandomDirection(rng), wi = RandomDirection(rng);
            wi.z = std::copysign(wi.z, wo.z);  // reflection: the coats transmit nothing
            importance += bxdf.f(wo, wi, TransportMode::Importance).Average() * std::abs(wi.z);
            radiance += bxdf.f(wi, wo, TransportMode::Radiance).Average() * std::abs(wi.z);
        }
        EXPECT_GT(radiance, 0) << name;
        EXPECT_NEAR(importance, radiance, 0.02 * radiance) << name;
    }
}

}  // namespace
