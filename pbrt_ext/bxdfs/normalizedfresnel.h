// pbrt_ext: the directional part Sw of a separable BSSRDF at its exit point, pbrt-v4's
// NormalizedFresnelBxDF (materials/bssrdf.h): the Fresnel transmittance out of a dielectric of relative
// index eta, normalized to reflect everything that reaches it,
//   f(wo, wi) = (1 - Fr(cos theta_i, eta)) / (c pi),  c = 1 - 2 FresnelMoment1(1 / eta),
// times eta^2 for radiance, as pbrt-v4 scales it (radiance leaving a medium of index eta).
// Cosine-sampled; reflection only.
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <string>

namespace pbrt {

class NormalizedFresnelBxDF {
  public:
    NormalizedFresnelBxDF() = default;
    explicit NormalizedFresnelBxDF(Float eta) : eta(eta), c(1 - 2 * FresnelMoment1(1 / eta)) {}

    BxDFFlags Flags() const { return BxDFFlags::DiffuseReflection; }

    SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode mode) const {
        if (!SameHemisphere(wo, wi)) return SampledSpectrum(0.f);
        Float value = (1 - FrDielectric(CosTheta(wi), eta)) / (c * Pi);
        return SampledSpectrum(mode == TransportMode::Radiance ? value * Sqr(eta) : value);
    }

    pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float /*uc*/, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection) || wo.z == 0) return {};
        Vector3f wi = SampleCosineHemisphere(u);
        if (wo.z < 0) wi.z *= -1;
        return BSDFSample(f(wo, wi, mode), wi, CosineHemispherePDF(AbsCosTheta(wi)),
                          BxDFFlags::DiffuseReflection);
    }

    Float PDF(Vector3f wo, Vector3f wi, TransportMode /*mode*/,
              BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection) || !SameHemisphere(wo, wi)) return 0;
        return CosineHemispherePDF(AbsCosTheta(wi));
    }

    void Regularize() {}
    SampledSpectrum rho(Vector3f wo, pstd::span<const Float> uc,
                        pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, wo, uc, u2);
    }
    SampledSpectrum rho(pstd::span<const Point2f> u1, pstd::span<const Float> uc,
                        pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, u1, uc, u2);
    }
    static constexpr const char *Name() { return "NormalizedFresnelBxDF"; }
    std::string ToString() const {
        return "[ NormalizedFresnelBxDF eta: " + std::to_string(eta) + " ]";
    }

  private:
    Float eta = 1, c = 1;
};

}  // namespace pbrt
