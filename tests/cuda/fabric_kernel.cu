// Compile check: fabric.h and fabricdiffuse.h are GPU-clean. Every member a renderer calls, inside a
// __global__ kernel.
// Built by nvcc when it is installed (tests/CMakeLists.txt); nothing here runs.
#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/bxdfs/fabricdiffuse.h"

namespace pbrt {

__global__ void FabricKernel(const Vector3f *wo, const Point2f *u, Float *out, int count) {
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count)
        return;
    Vector3f thread = FabricBxDF::ThreadDirection(30, 10);
    FabricBxDF bxdf(SampledSpectrum(0.5f, 0.6f, 0.7f, 0.8f), Float(0.3f), thread, FabricSampling::Best,
                    FabricNormalization::UnitPeak);
    FabricBxDF continuous(SampledSpectrum(1), FabricExponent{7.5f}, thread, FabricSampling::Paper);
    continuous.Regularize();
    Float sum = continuous.PDF(wo[i], Vector3f(0, 0, 1), TransportMode::Importance);
    pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo[i], u[i][0], u[i], TransportMode::Radiance);
    if (bs)
        sum += bs->pdf + bs->f.Average() + bxdf.f(wo[i], bs->wi, TransportMode::Radiance)[0] +
               bxdf.PDF(wo[i], bs->wi, TransportMode::Radiance);
    Float uc[1] = {u[i][1]};
    Point2f u2[1] = {u[i]};
    sum += bxdf.rho(wo[i], uc, u2).MaxComponentValue() + Float(IsReflective(bxdf.Flags()));
    FabricDiffuseBxDF mixed(bxdf, SampledSpectrum(0.8f));
    mixed.Regularize();
    pstd::optional<BSDFSample> ms = mixed.Sample_f(wo[i], u[i][1], u[i], TransportMode::Radiance);
    if (ms)
        sum += ms->pdf + mixed.f(wo[i], ms->wi, TransportMode::Radiance)[1] +
               mixed.PDF(wo[i], ms->wi, TransportMode::Radiance);
    sum += mixed.rho(wo[i], uc, u2)[2] + Float(IsGlossy(mixed.Flags())) + bxdf.PeakAlbedo() +
           FabricDiffuseBxDF::Name()[0];
    out[i] = sum;
}

}  // namespace pbrt
