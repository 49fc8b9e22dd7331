// pbrt_ext: Lambertian reflection plus Lambertian transmission (paper, leaves, lamp
// shades), pbrt-v4's DiffuseTransmissionBxDF (Physically Based Rendering, 4th edition,
// Section 9.2 and the "diffusetransmission" material).
//
// f = R / Pi for wi on wo's side and T / Pi for wi on the other side. Sampling picks the
// side in proportion to the largest channel of R and of T, then samples the cosine there,
// so the sample weight is R (or T) divided by that side's probability. Symmetric in wo and
// wi and free of any index change, so TransportMode plays no part.
// Differs from pbrt-v4: a wo or wi exactly in the tangent plane is on neither side, so f()
// and PDF() are zero there and Sample_f() returns no sample, instead of pbrt-v4's
// transmission value for a sample it labels as reflection.
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

class DiffuseTransmissionBxDF {
  public:
    DiffuseTransmissionBxDF() = default;
    PBRT_CPU_GPU DiffuseTransmissionBxDF(SampledSpectrum R0, SampledSpectrum T0)
        : R(R0), T(T0) {}

    // A black side scatters nothing, so it reports no lobe.
    PBRT_CPU_GPU BxDFFlags Flags() const {
        return (R ? BxDFFlags::DiffuseReflection : BxDFFlags::Unset) |
               (T ? BxDFFlags::DiffuseTransmission : BxDFFlags::Unset);
    }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode /*mode*/) const {
        if (wo.z == 0 || wi.z == 0)
            return SampledSpectrum(0.f);
        return SameHemisphere(wo, wi) ? R * InvPi : T * InvPi;
    }

    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float uc, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        Float prReflect = ReflectionProbability(sampleFlags);
        if (prReflect < 0 || wo.z == 0)
            return {};
        bool reflect = uc < prReflect;
        Vector3f wi = SampleCosineHemisphere(u);
        // The cosine lobe goes on wo's side for reflection, on the other for transmission.
        if ((wo.z < 0) == reflect)
            wi.z *= -1;
        if (wi.z == 0)
            return {};
        Float pdf = CosineHemispherePDF(AbsCosTheta(wi)) * (reflect ? prReflect : 1 - prReflect);
        return BSDFSample(f(wo, wi, mode), wi, pdf,
                          reflect ? BxDFFlags::DiffuseReflection : BxDFFlags::DiffuseTransmission);
    }

    PBRT_CPU_GPU Float PDF(Vector3f wo, Vector3f wi, TransportMode /*mode*/,
                           BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        Float prReflect = ReflectionProbability(sampleFlags);
        if (prReflect < 0 || wo.z == 0 || wi.z == 0)
            return 0;
        Float pSide = SameHemisphere(wo, wi) ? prReflect : 1 - prReflect;
        return pSide * CosineHemispherePDF(AbsCosTheta(wi));
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

    // Nothing to do: both lobes already span a whole hemisphere.
    PBRT_CPU_GPU void Regularize() {}

    PBRT_CPU_GPU static constexpr const char *Name() { return "DiffuseTransmissionBxDF"; }

    // Host-only.
    std::string ToString() const {
        return "[ DiffuseTransmissionBxDF R: " + R.ToString() + " T: " + T.ToString() + " ]";
    }

  private:
    // Probability of sampling wo's side, from the sides' largest channels and the lobes the
    // caller allows; negative when neither may be sampled.
    PBRT_CPU_GPU Float ReflectionProbability(BxDFReflTransFlags sampleFlags) const {
        Float pr = bool(sampleFlags & BxDFReflTransFlags::Reflection) ? R.MaxComponentValue() : 0;
        Float pt =
            bool(sampleFlags & BxDFReflTransFlags::Transmission) ? T.MaxComponentValue() : 0;
        if (pr == 0 && pt == 0)
            return -1;
        return pr / (pr + pt);
    }

    SampledSpectrum R, T;
};

}  // namespace pbrt
