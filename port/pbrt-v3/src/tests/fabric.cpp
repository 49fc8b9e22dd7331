// pbrt_ext's fabric BxDF through pbrt-v3's BxDF interface (materials/fabricreflection.h), in
// pbrt-v3's own tests: the chi-square test of bsdfs.cpp on every sampler, reciprocity, and the
// white furnace at the lobe's peak. Thresholds are stated at each test; random numbers come from
// pbrt-v3's RNG with its default seed.
#include "tests/gtest/gtest.h"

#include "pbrt.h"
#include "materials/fabricreflection.h"
#include "memory.h"
#include "reflection.h"
#include "rng.h"
#include "sampling.h"

#include <cmath>

using namespace pbrt;

// bsdfs.cpp's chi-square harness (significance 0.01, 80 x 160 bins, 10^6 samples, five outgoing
// directions from the cosine-weighted hemisphere).
void TestBSDF(void (*createBSDF)(BSDF *, MemoryArena &), const char *description);

namespace {

pbrt_ext::FabricDiffuseBxDF MakeFabric(Float roughness, Float threadAngle, Float elevation,
                                       pbrt_ext::FabricSampling sampling,
                                       Float diffuse = 0) {
    pbrt_ext::FabricBxDF fabric(pbrt_ext::SampledSpectrum(1.f), roughness,
                                pbrt_ext::FabricBxDF::ThreadDirection(threadAngle, elevation),
                                sampling);
    return pbrt_ext::FabricDiffuseBxDF(fabric, pbrt_ext::SampledSpectrum(diffuse));
}

template <pbrt_ext::FabricSampling sampling, int roughnessPercent, int elevation, int diffuse>
void CreateFabric(BSDF *bsdf, MemoryArena &arena) {
    bsdf->Add(ARENA_ALLOC(arena, FabricReflection)(
        MakeFabric(roughnessPercent / Float(100), 30, elevation, sampling, diffuse / Float(10))));
}

using S = pbrt_ext::FabricSampling;

}  // namespace

// Roughness 0.5 is exponent 9 (the paper's mapping); 0.1 is 25.
TEST(FabricBSDFSampling, Uniform) { TestBSDF(CreateFabric<S::Uniform, 50, 0, 0>, "FabricUniform"); }
TEST(FabricBSDFSampling, Cosine) { TestBSDF(CreateFabric<S::Cosine, 50, 0, 0>, "FabricCosine"); }
TEST(FabricBSDFSampling, Paper) { TestBSDF(CreateFabric<S::Paper, 50, 0, 0>, "FabricPaper"); }
TEST(FabricBSDFSampling, TruncatedSinPhi) {
    TestBSDF(CreateFabric<S::TruncatedSinPhi, 10, 0, 0>, "FabricTruncatedSinPhi");
}
TEST(FabricBSDFSampling, Best) { TestBSDF(CreateFabric<S::Best, 50, 0, 0>, "FabricBest"); }
TEST(FabricBSDFSampling, BestElevatedWithDiffuseBase) {
    TestBSDF(CreateFabric<S::Best, 30, 40, 8>, "FabricBestElevatedDiffuse");
}

// f(wo, wi) = f(wi, wo) to the last bit through the adapter.
TEST(FabricReflection, Reciprocity) {
    RNG rng;
    for (int config = 0; config < 20; ++config) {
        FabricReflection bxdf(MakeFabric(rng.UniformFloat(), 360 * rng.UniformFloat(),
                                         180 * rng.UniformFloat() - 90, S::Best,
                                         rng.UniformFloat()));
        for (int i = 0; i < 1000; ++i) {
            Vector3f wo = UniformSampleSphere({rng.UniformFloat(), rng.UniformFloat()});
            Vector3f wi = UniformSampleSphere({rng.UniformFloat(), rng.UniformFloat()});
            Spectrum a = bxdf.f(wo, wi), b = bxdf.f(wi, wo);
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(a[c], b[c]) << bxdf.ToString();
        }
    }
}

// White furnace at the peak: a white unit-peak fabric with a tangent thread reflects all the
// light at normal incidence. 2^16 samples through pbrt-v3's Sample_f (and so through the hashed
// third dimension); the mean within 4 standard errors of 1, and every sample's pdf equals Pdf().
TEST(FabricReflection, WhiteFurnaceAtPeak) {
    pbrt_ext::FabricBxDF fabric(pbrt_ext::SampledSpectrum(1.f), 0.4f,
                                pbrt_ext::FabricBxDF::ThreadDirection(30, 0), S::Best,
                                pbrt_ext::FabricNormalization::UnitPeak);
    FabricReflection bxdf(pbrt_ext::FabricDiffuseBxDF(fabric, pbrt_ext::SampledSpectrum(0.f)));
    RNG rng;
    Vector3f wo(0, 0, 1);
    const int n = 1 << 16;
    double sum = 0, sumSquares = 0;
    for (int i = 0; i < n; ++i) {
        Vector3f wi;
        Float pdf = 0;
        Spectrum f = bxdf.Sample_f(wo, &wi, {rng.UniformFloat(), rng.UniformFloat()}, &pdf);
        if (pdf == 0)
            continue;
        ASSERT_NEAR(pdf, bxdf.Pdf(wo, wi), 1e-5 * pdf);
        double v = f[0] * AbsCosTheta(wi) / pdf;
        sum += v;
        sumSquares += v * v;
    }
    double mean = sum / n, error = std::sqrt((sumSquares / n - mean * mean) / n);
    EXPECT_NEAR(mean, 1, 4 * error);
}
