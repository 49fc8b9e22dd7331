// pbrt_ext: the conductor (metal) BRDF, pbrt-v4's ConductorBxDF (Physically Based
// Rendering, 4th edition, Section 9.4 "Conductor BRDF" for the smooth case and Section
// 9.6.5 "The Torrance-Sparrow Model" for the rough one).
//
// Smooth (TrowbridgeReitzDistribution::EffectivelySmooth()): a perfect mirror, a Dirac
// delta that f() and PDF() cannot represent, so both return zero and only Sample_f()
// produces the mirror direction (flag SpecularReflection, pdf 1 in the discrete sense).
// Rough: the Torrance-Sparrow microfacet BRDF D(wm) F G / (4 cos_o cos_i) with
// Trowbridge-Reitz normals, sampled through the normals visible from wo.
// Fresnel reflectance is FrComplex with the per-channel complex index eta + i k.
// Two-sided: all cosines enter through their absolute values. Reflection is reciprocal,
// so TransportMode plays no part; with a single lobe, no uc is needed.
// Differs from pbrt-v4: Sample_f() returns no sample for wo exactly in the tangent plane,
// where pbrt-v4's mirror branch divides by a zero cosine.
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <string>

namespace pbrt {

class ConductorBxDF {
  public:
    ConductorBxDF() = default;
    PBRT_CPU_GPU ConductorBxDF(const TrowbridgeReitzDistribution &mfDistrib0,
                               SampledSpectrum eta0, SampledSpectrum k0)
        : mfDistrib(mfDistrib0), eta(eta0), k(k0) {}

    PBRT_CPU_GPU BxDFFlags Flags() const {
        return mfDistrib.EffectivelySmooth() ? BxDFFlags::SpecularReflection
                                             : BxDFFlags::GlossyReflection;
    }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode /*mode*/) const {
        // SameHemisphere() also rules out grazing directions, so the cosines below are
        // nonzero and wo + wi cannot vanish.
        if (!SameHemisphere(wo, wi) || mfDistrib.EffectivelySmooth())
            return SampledSpectrum(0.f);
        return FValue(wo, wi, FindMicrofacet(wo, wi));
    }

    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float /*uc*/, Point2f u, TransportMode /*mode*/,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        // A direction in the tangent plane has no hemisphere to reflect into (and the
        // mirror's f would divide by its zero cosine).
        if (!(sampleFlags & BxDFReflTransFlags::Reflection) || wo.z == 0)
            return {};
        if (mfDistrib.EffectivelySmooth()) {
            // Dividing by the cosine cancels the one the integrator multiplies in, so the
            // sample carries exactly the Fresnel reflectance.
            Vector3f wi(-wo.x, -wo.y, wo.z);
            SampledSpectrum f = FrComplex(AbsCosTheta(wi), eta, k) / AbsCosTheta(wi);
            return BSDFSample(f, wi, 1, BxDFFlags::SpecularReflection);
        }
        Vector3f wm = mfDistrib.Sample_wm(wo, u);
        Vector3f wi = Reflect(wo, wm);
        // A normal visible from wo can still reflect it below the surface; those samples
        // are lost, which is the single-scattering model's energy loss.
        if (!SameHemisphere(wo, wi))
            return {};
        // Evaluated at the half vector of (wo, wi), not at the sampled wm: the two differ
        // by rounding, and narrow lobes are steep enough that Sample_f() would otherwise
        // disagree with f() and PDF() in the fourth digit.
        Microfacet m = FindMicrofacet(wo, wi);
        return BSDFSample(FValue(wo, wi, m), wi, PDFValue(wo, m), BxDFFlags::GlossyReflection);
    }

    PBRT_CPU_GPU Float PDF(Vector3f wo, Vector3f wi, TransportMode /*mode*/,
                           BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection) || !SameHemisphere(wo, wi) ||
            mfDistrib.EffectivelySmooth())
            return 0;
        return PDFValue(wo, FindMicrofacet(wo, wi));
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

    PBRT_CPU_GPU void Regularize() { mfDistrib.Regularize(); }

    PBRT_CPU_GPU static constexpr const char *Name() { return "ConductorBxDF"; }

    // Host-only.
    std::string ToString() const {
        return "[ ConductorBxDF mfDistrib: " + mfDistrib.ToString() +
               " eta: " + eta.ToString() + " k: " + k.ToString() + " ]";
    }

  private:
    // What f() and PDF() share at a pair of directions in one hemisphere, computed once when
    // Sample_f() needs both: the half vector on the normal's side (where Sample_wm() returns
    // it; D and |wo . wm| do not depend on the side), its density and Lambda(wo).
    struct Microfacet {
        Vector3f wm;
        Float D, lambda_o;
    };
    PBRT_CPU_GPU Microfacet FindMicrofacet(Vector3f wo, Vector3f wi) const {
        Vector3f wm = FaceForward(Normalize(wo + wi), Vector3f(0, 0, 1));
        return {wm, mfDistrib.D(wm), mfDistrib.Lambda(wo)};
    }
    PBRT_CPU_GPU SampledSpectrum FValue(Vector3f wo, Vector3f wi, const Microfacet &m) const {
        SampledSpectrum F = FrComplex(AbsDot(wo, m.wm), eta, k);
        return m.D * F * mfDistrib.G(m.lambda_o, wi) / (4 * AbsCosTheta(wi) * AbsCosTheta(wo));
    }
    // Jacobian of the half-vector reflection: d wm / d wi = 1 / (4 |wo . wm|).
    PBRT_CPU_GPU Float PDFValue(Vector3f wo, const Microfacet &m) const {
        return mfDistrib.PDF(wo, m.lambda_o, m.wm, m.D) / (4 * AbsDot(wo, m.wm));
    }

    TrowbridgeReitzDistribution mfDistrib;
    SampledSpectrum eta, k;
};

}  // namespace pbrt
