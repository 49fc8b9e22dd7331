// Compile check: diffuse.h, conductor.h and scattering.h are GPU-clean (built by nvcc when installed).
#include "pbrt_ext/bxdfs/conductor.h"
#include "pbrt_ext/bxdfs/diffuse.h"

using namespace pbrt;

template <typename BxDF>
__device__ Float Exercise(BxDF bxdf, Vector3f wo, Point2f u, Float uc) {
    Float sum = 0;
    pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, uc, u, TransportMode::Radiance);
    if (bs) sum += bs->f[0] + bs->pdf + bxdf.PDF(wo, bs->wi, TransportMode::Radiance);
    sum += bxdf.f(wo, Vector3f(0, 0, 1), TransportMode::Importance)[1];
    Float ucs[2] = {0.25f, 0.75f};
    Point2f us[2] = {Point2f(0.1f, 0.2f), Point2f(0.7f, 0.4f)};
    sum += bxdf.rho(wo, pstd::span<const Float>(ucs), pstd::span<const Point2f>(us))[2];
    sum += bxdf.rho(pstd::span<const Point2f>(us), pstd::span<const Float>(ucs), pstd::span<const Point2f>(us))[0];
    bxdf.Regularize();
    sum += IsSpecular(bxdf.Flags()) ? 1 : 0;
    sum += BxDF::Name()[0];
    return sum;
}

__global__ void BxDFKernel(Float *out) {
    Vector3f wo = Normalize(Vector3f(0.3f, 0.1f, 0.9f));
    Point2f u(0.3f, 0.6f);
    TrowbridgeReitzDistribution distrib(0.2f, 0.4f);
    out[0] = Exercise(DiffuseBxDF(SampledSpectrum(0.5f)), wo, u, 0.5f);
    out[1] = Exercise(ConductorBxDF(distrib, SampledSpectrum(0.2f, 0.9f, 1.1f),
                                    SampledSpectrum(3.f, 2.5f, 2.f)), wo, u, 0.5f);
    out[2] = Exercise(ConductorBxDF(TrowbridgeReitzDistribution(0, 0), SampledSpectrum(0.2f),
                                    SampledSpectrum(3.f)), wo, u, 0.5f);
    Vector3f wt;
    Float etap;
    out[3] = Refract(wo, Normal3f(0, 0, 1), 1.5f, &etap, &wt) ? FrDielectric(wo.z, 1.5f) : 0;
    out[4] = distrib.Sample_wm(-wo, u).z + distrib.D(wo, Vector3f(0,0,1)) +
             TrowbridgeReitzDistribution::RoughnessToAlpha(0.3f) + Reflect(wo, Vector3f(0,0,1)).x;
}
