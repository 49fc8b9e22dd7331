// For the CUDA compile checks: every member of a BxDF's interface called from device code.
#pragma once

#include "pbrt_ext/base/bxdf.h"

namespace pbrt {

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

}  // namespace pbrt
