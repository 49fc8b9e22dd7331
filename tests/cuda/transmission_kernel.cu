// Compile check: dielectric, thin dielectric, diffuse transmission and the layered BxDFs are
// GPU-clean (built by nvcc when installed).
#include "pbrt_ext/bxdfs/dielectric.h"
#include "pbrt_ext/bxdfs/diffusetransmission.h"
#include "pbrt_ext/bxdfs/layered.h"
#include "pbrt_ext/bxdfs/thindielectric.h"
#include "exercise_bxdf.cuh"

using namespace pbrt;

__global__ void Kernel(Float *out) {
    Vector3f wo = Normalize(Vector3f(0.3f, 0.1f, 0.9f));
    Point2f u(0.3f, 0.6f);
    TrowbridgeReitzDistribution rough(0.2f, 0.4f), smooth(0, 0);
    DielectricBxDF coat(1.5f, smooth);
    out[0] = Exercise(DielectricBxDF(1.5f, rough), wo, u, 0.5f);
    out[1] = Exercise(DielectricBxDF(1.33f, smooth), wo, u, 0.5f);
    out[2] = Exercise(ThinDielectricBxDF(1.5f), wo, u, 0.5f);
    out[3] = Exercise(DiffuseTransmissionBxDF(SampledSpectrum(0.3f), SampledSpectrum(0.5f)), wo, u, 0.5f);
    out[4] = Exercise(CoatedDiffuseBxDF(coat, DiffuseBxDF(SampledSpectrum(0.5f)), 0.01f,
                                        SampledSpectrum(0.2f), 0.3f, 10, 1), wo, u, 0.5f);
    out[5] = Exercise(CoatedConductorBxDF(coat, ConductorBxDF(rough, SampledSpectrum(0.2f), SampledSpectrum(3.f)),
                                          0.01f, SampledSpectrum(0.f), 0, 10, 1), -wo, u, 0.5f);
    Float pdf;
    out[6] = SampleHenyeyGreenstein(wo, 0.4f, u, &pdf).z + pdf + SampleExponential(0.3f, 2.f) +
             ExponentialPDF(0.1f, 2.f) + InvertExponentialSample(0.2f, 2.f) + Float(Hash(wo, 1.f) & 1) + Float(MixBits(3) & 1);
}
