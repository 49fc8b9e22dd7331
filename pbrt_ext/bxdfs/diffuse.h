// pbrt_ext: the Lambertian BRDF, pbrt-v4's DiffuseBxDF (Physically Based Rendering,
// 4th edition, Section 9.2 "Diffuse Reflection").
//
// f = R / Pi on the side of the surface that wo is on, zero on the other side; sampling
// is cosine-weighted, which makes the sample weight f cos / pdf exactly R. The BRDF is
// two-sided: for wo below the surface the sampled hemisphere is mirrored to follow it.
// Reflection is reciprocal, so TransportMode plays no part; one sample needs no uc.
// Differs from pbrt-v4: Sample_f() returns no sample for wo exactly in the tangent plane,
// where f() and PDF() are zero, instead of a sample that disagrees with them.
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <string>

namespace pbrt {

class DiffuseBxDF {
  public:
    DiffuseBxDF() = default;
    PBRT_CPU_GPU DiffuseBxDF(SampledSpectrum R0) : R(R0) {}

    // A black surface scatters nothing, so it reports no lobe at all.
    PBRT_CPU_GPU BxDFFlags Flags() const {
        return R ? BxDFFlags::DiffuseReflection : BxDFFlags::Unset;
    }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode /*mode*/) const {
        if (!SameHemisphere(wo, wi))
            return SampledSpectrum(0.f);
        return R * InvPi;
    }

    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float /*uc*/, Point2f u, TransportMode /*mode*/,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        // A wo in the tangent plane has no hemisphere to follow; f() and PDF() are zero there.
        if (!(sampleFlags & BxDFReflTransFlags::Reflection) || wo.z == 0)
            return {};
        Vector3f wi = SampleCosineHemisphere(u);
        if (wo.z < 0)
            wi.z *= -1;
        Float pdf = CosineHemispherePDF(AbsCosTheta(wi));
        return BSDFSample(R * InvPi, wi, pdf, BxDFFlags::DiffuseReflection);
    }

    PBRT_CPU_GPU Float PDF(Vector3f wo, Vector3f wi, TransportMode /*mode*/,
                           BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection) || !SameHemisphere(wo, wi))
            return 0;
        return CosineHemispherePDF(AbsCosTheta(wi));
    }

    PBRT_CPU_GPU SampledSpectrum rho(Vector3f wo, pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, wo, uc, u2);
    }

    PBRT_CPU_GPU SampledSpectrum rho(pstd::span<const Point2f> u1,
                                     pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, u1, uc, u2);
    }

    // Nothing to do: regularization widens near-specular lobes, and a Lambertian lobe
    // already spans the whole hemisphere.
    PBRT_CPU_GPU void Regularize() {}

    PBRT_CPU_GPU static constexpr const char *Name() { return "DiffuseBxDF"; }

    // Host-only.
    std::string ToString() const { return "[ DiffuseBxDF R: " + R.ToString() + " ]"; }

  private:
    SampledSpectrum R;
};

}  // namespace pbrt
