// Compile check: diffuse.h, conductor.h, scattering.h and util/spectrum.h (SampledSpectrum,
// SampledWavelengths) are GPU-clean (built by nvcc when installed).
#include "pbrt_ext/bxdfs/conductor.h"
#include "pbrt_ext/bxdfs/diffuse.h"
#include "exercise_bxdf.cuh"

using namespace pbrt;

__global__ void BxDFKernel(Float *out) {
    Vector3f wo = Normalize(Vector3f(0.3f, 0.1f, 0.9f));
    Point2f u(0.3f, 0.6f);
    TrowbridgeReitzDistribution distrib(0.2f, 0.4f);
    out[0] = Exercise(DiffuseBxDF(SampledSpectrum(0.5f)), wo, u, 0.5f);
    out[1] = Exercise(ConductorBxDF(distrib, SampledSpectrum(0.2f, 0.9f, 1.1f, 1.2f),
                                    SampledSpectrum(3.f, 2.5f, 2.f, 1.8f)), wo, u, 0.5f);
    out[2] = Exercise(ConductorBxDF(TrowbridgeReitzDistribution(0, 0), SampledSpectrum(0.2f),
                                    SampledSpectrum(3.f)), wo, u, 0.5f);
    Vector3f wt;
    Float etap;
    out[3] = Refract(wo, Normal3f(0, 0, 1), 1.5f, &etap, &wt) ? FrDielectric(wo.z, 1.5f) : 0;
    out[4] = distrib.Sample_wm(-wo, u).z + distrib.D(wo, Vector3f(0,0,1)) +
             TrowbridgeReitzDistribution::RoughnessToAlpha(0.3f) + Reflect(wo, Vector3f(0,0,1)).x;
    // The wavelengths a path carries (util/spectrum.h), as a GPU integrator samples and uses them.
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(u[0]);
    SampledWavelengths uniform = SampledWavelengths::SampleUniform(u[1]);
    lambda.TerminateSecondary();
    out[5] = lambda[3] + SafeDiv(SampledSpectrum(1.f), lambda.PDF())[0] + uniform.PDF().Average() +
             Float(lambda.SecondaryTerminated() && !(lambda == uniform)) +
             VisibleWavelengthsPDF(550.f) + SampleVisibleWavelengths(0.5f);
}
