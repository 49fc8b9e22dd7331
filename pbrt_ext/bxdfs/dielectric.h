// pbrt_ext: the dielectric BSDF (glass, water), pbrt-v4's DielectricBxDF (Physically Based
// Rendering, 4th edition, Section 9.5 "Dielectric BSDF" for the smooth interface and
// Section 9.7 "Rough Dielectric BSDF" for the rough one, after Walter et al.,
// "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007).
//
// eta is the relative index of refraction, inside (below the surface, z < 0) over outside.
// Smooth (eta == 1 or an effectively smooth distribution): a Fresnel-weighted choice between
// the mirror direction and the refracted one, two Dirac deltas that f() and PDF() cannot
// represent; they return zero and only Sample_f() produces the two directions, each with its
// discrete probability as pdf. Rough: reflection and refraction through Trowbridge-Reitz
// microfacets, sampled through the normals visible from wo and split between the two in
// proportion to the Fresnel reflectance of the sampled normal.
//
// Transmission is not symmetric: radiance crossing into a medium of relative index etap is
// compressed into a cone 1/etap^2 the solid angle, so in TransportMode::Radiance the
// transmitted part of f is divided by etap^2 (importance is not); the BSDFSample's eta is
// that etap, for the integrator's Russian roulette. Consequently f(wo, wi) / eta_o^2, with
// eta_o the index on wo's side, is symmetric, and f in one mode is the other mode's
// f with the arguments swapped.
//
// Differs from pbrt-v4:
//  - Sample_f() returns no sample for wo exactly in the tangent plane, where pbrt-v4's
//    smooth branch divides by a zero cosine (as DiffuseBxDF and ConductorBxDF here);
//  - the rough branch of Sample_f() returns f() and PDF() evaluated at the sampled wi (the
//    half vector recomputed from wo and wi differs from the sampled one only by rounding,
//    which narrow lobes would otherwise turn into disagreements in the fourth digit);
//  - with eta == 1, Flags() reports Specular whatever the roughness: an index-matched
//    interface only passes light straight through, and a caller (the layered BxDF's random
//    walk) that believed it glossy would ask f() for a lobe that is not there.
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace pbrt {

class DielectricBxDF {
  public:
    DielectricBxDF() = default;
    PBRT_CPU_GPU DielectricBxDF(Float eta0, TrowbridgeReitzDistribution mfDistrib0)
        : eta(eta0), mfDistrib(mfDistrib0) {}

    // Matched indices reflect nothing.
    PBRT_CPU_GPU BxDFFlags Flags() const {
        BxDFFlags flags = (eta == 1) ? BxDFFlags::Transmission
                                     : (BxDFFlags::Reflection | BxDFFlags::Transmission);
        return flags | (IsSmooth() ? BxDFFlags::Specular : BxDFFlags::Glossy);
    }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode mode) const;

    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float uc, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const;

    PBRT_CPU_GPU Float PDF(Vector3f wo, Vector3f wi, TransportMode mode,
                           BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const;

    PBRT_CPU_GPU SampledSpectrum rho(Vector3f wo, pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, wo, uc, u2);
    }

    PBRT_CPU_GPU SampledSpectrum rho(pstd::span<const Point2f> u1,
                                     pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, u1, uc, u2);
    }

    // The relative index of refraction, inside over outside.
    PBRT_CPU_GPU Float Eta() const { return eta; }

    // Widens a near-specular interface into a glossy one, so that light paths through
    // it can be connected (an index-matched one stays a pass-through).
    PBRT_CPU_GPU void Regularize() { mfDistrib.Regularize(); }

    PBRT_CPU_GPU static constexpr const char *Name() { return "DielectricBxDF"; }

    // Host-only.
    std::string ToString() const {
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%g", eta);
        return std::string("[ DielectricBxDF eta: ") + buf +
               " mfDistrib: " + mfDistrib.ToString() + " ]";
    }

  private:
    // Where the rough model's microfacet normal is defined: the generalized half vector.
    struct HalfVector {
        Vector3f wm;  // on the normal's side (wm.z > 0)
        Float etap;   // relative index crossed from wo's side to wi's (1 for reflection)
        bool reflect;
    };

    PBRT_CPU_GPU bool IsSmooth() const { return eta == 1 || mfDistrib.EffectivelySmooth(); }

    // Probability of choosing reflection, given the Fresnel reflectance R and the lobes the
    // caller allows; negative when neither may be sampled.
    PBRT_CPU_GPU static Float ReflectionProbability(Float R, BxDFReflTransFlags sampleFlags) {
        Float pr = bool(sampleFlags & BxDFReflTransFlags::Reflection) ? R : 0;
        Float pt = bool(sampleFlags & BxDFReflTransFlags::Transmission) ? 1 - R : 0;
        if (pr == 0 && pt == 0)
            return -1;
        return pr / (pr + pt);
    }

    PBRT_CPU_GPU pstd::optional<HalfVector> FindHalfVector(Vector3f wo, Vector3f wi) const;

    // What f() and PDF() both need at a pair of directions, computed once when Sample_f()
    // needs both: the half vector, its Fresnel reflectance, its microfacet density and the
    // masking term Lambda(wo).
    struct Microfacet {
        HalfVector h;
        Float F, D, lambda_o;
    };
    PBRT_CPU_GPU pstd::optional<Microfacet> FindMicrofacet(Vector3f wo, Vector3f wi) const;
    PBRT_CPU_GPU Float FValue(Vector3f wo, Vector3f wi, TransportMode mode,
                              const Microfacet &m) const;
    PBRT_CPU_GPU Float PDFValue(Vector3f wo, Vector3f wi, BxDFReflTransFlags sampleFlags,
                                const Microfacet &m) const;

    PBRT_CPU_GPU pstd::optional<BSDFSample> SampleSmooth(Vector3f wo, Float uc,
                                                         TransportMode mode,
                                                         BxDFReflTransFlags sampleFlags) const;

    Float eta = 1;
    TrowbridgeReitzDistribution mfDistrib;
};

// wi * etap + wo is normal to the microfacet that reflects (etap = 1) or refracts wo into
// wi; microfacets seen from behind by either direction scatter nothing between them.
PBRT_CPU_GPU inline pstd::optional<DielectricBxDF::HalfVector> DielectricBxDF::FindHalfVector(
    Vector3f wo, Vector3f wi) const {
    Float cosTheta_o = CosTheta(wo), cosTheta_i = CosTheta(wi);
    if (cosTheta_o == 0 || cosTheta_i == 0)
        return {};
    bool reflect = cosTheta_i * cosTheta_o > 0;
    Float etap = reflect ? 1 : (cosTheta_o > 0 ? eta : 1 / eta);
    Vector3f wm = wi * etap + wo;
    if (LengthSquared(wm) == 0)
        return {};
    wm = FaceForward(Normalize(wm), Vector3f(0, 0, 1));
    if (Dot(wm, wi) * cosTheta_i < 0 || Dot(wm, wo) * cosTheta_o < 0)
        return {};
    return HalfVector{wm, etap, reflect};
}

PBRT_CPU_GPU inline pstd::optional<DielectricBxDF::Microfacet> DielectricBxDF::FindMicrofacet(
    Vector3f wo, Vector3f wi) const {
    pstd::optional<HalfVector> h = FindHalfVector(wo, wi);
    if (!h)
        return {};
    return Microfacet{*h, FrDielectric(Dot(wo, h->wm), eta), mfDistrib.D(h->wm),
                      mfDistrib.Lambda(wo)};
}

PBRT_CPU_GPU inline Float DielectricBxDF::FValue(Vector3f wo, Vector3f wi, TransportMode mode,
                                                 const Microfacet &m) const {
    Float DG = m.D * mfDistrib.G(m.lambda_o, wi);
    if (m.h.reflect)
        return DG * m.F / std::abs(4 * CosTheta(wi) * CosTheta(wo));
    Float denom =
        Sqr(Dot(wi, m.h.wm) + Dot(wo, m.h.wm) / m.h.etap) * CosTheta(wi) * CosTheta(wo);
    Float ft = DG * (1 - m.F) * std::abs(Dot(wi, m.h.wm) * Dot(wo, m.h.wm) / denom);
    // Radiance is compressed into the smaller solid angle of the denser side.
    if (mode == TransportMode::Radiance)
        ft /= Sqr(m.h.etap);
    return ft;
}

PBRT_CPU_GPU inline Float DielectricBxDF::PDFValue(Vector3f wo, Vector3f wi,
                                                   BxDFReflTransFlags sampleFlags,
                                                   const Microfacet &m) const {
    Float prReflect = ReflectionProbability(m.F, sampleFlags);
    if (prReflect < 0)
        return 0;
    Float pdf_wm = mfDistrib.PDF(wo, m.lambda_o, m.h.wm, m.D);
    if (m.h.reflect)
        // Jacobian of the reflection about wm: d wm / d wi = 1 / (4 |wo . wm|).
        return pdf_wm / (4 * AbsDot(wo, m.h.wm)) * prReflect;
    // Jacobian of refraction through wm (Walter et al., Eq. 17).
    Float dwm_dwi = AbsDot(wi, m.h.wm) / Sqr(Dot(wi, m.h.wm) + Dot(wo, m.h.wm) / m.h.etap);
    return pdf_wm * dwm_dwi * (1 - prReflect);
}

PBRT_CPU_GPU inline SampledSpectrum DielectricBxDF::f(Vector3f wo, Vector3f wi,
                                                      TransportMode mode) const {
    if (IsSmooth())
        return SampledSpectrum(0.f);
    pstd::optional<Microfacet> m = FindMicrofacet(wo, wi);
    return SampledSpectrum(m ? FValue(wo, wi, mode, *m) : 0);
}

PBRT_CPU_GPU inline Float DielectricBxDF::PDF(Vector3f wo, Vector3f wi, TransportMode /*mode*/,
                                              BxDFReflTransFlags sampleFlags) const {
    if (IsSmooth())
        return 0;
    pstd::optional<Microfacet> m = FindMicrofacet(wo, wi);
    return m ? PDFValue(wo, wi, sampleFlags, *m) : 0;
}

PBRT_CPU_GPU inline pstd::optional<BSDFSample> DielectricBxDF::SampleSmooth(
    Vector3f wo, Float uc, TransportMode mode, BxDFReflTransFlags sampleFlags) const {
    Float R = FrDielectric(CosTheta(wo), eta), T = 1 - R;
    Float prReflect = ReflectionProbability(R, sampleFlags);
    if (prReflect < 0)
        return {};
    // Dividing by the cosine cancels the one the integrator multiplies in, so the sample
    // weight f |cos| / pdf is R / prReflect (or T / (1 - prReflect)).
    if (uc < prReflect) {
        Vector3f wi(-wo.x, -wo.y, wo.z);
        return BSDFSample(SampledSpectrum(R / AbsCosTheta(wi)), wi, prReflect,
                          BxDFFlags::SpecularReflection);
    }
    Vector3f wi;
    Float etap;
    if (!Refract(wo, Normal3f(0, 0, 1), eta, &etap, &wi) || wi.z == 0)
        return {};
    SampledSpectrum ft(T / AbsCosTheta(wi));
    // Radiance is compressed into the smaller solid angle of the denser side.
    if (mode == TransportMode::Radiance)
        ft /= Sqr(etap);
    return BSDFSample(ft, wi, 1 - prReflect, BxDFFlags::SpecularTransmission, etap);
}

PBRT_CPU_GPU inline pstd::optional<BSDFSample> DielectricBxDF::Sample_f(
    Vector3f wo, Float uc, Point2f u, TransportMode mode,
    BxDFReflTransFlags sampleFlags) const {
    // A direction in the tangent plane has no side to reflect to or refract from.
    if (wo.z == 0)
        return {};
    if (IsSmooth())
        return SampleSmooth(wo, uc, mode, sampleFlags);

    Vector3f wm = mfDistrib.Sample_wm(wo, u);
    // Restricted to one side, the choice needs no Fresnel term: total internal reflection
    // makes Refract() fail, and PDFValue() below weighs the side actually taken.
    Float prReflect;
    if (sampleFlags == BxDFReflTransFlags::Reflection)
        prReflect = 1;
    else if (sampleFlags == BxDFReflTransFlags::Transmission)
        prReflect = 0;
    else
        prReflect = ReflectionProbability(FrDielectric(Dot(wo, wm), eta), sampleFlags);
    if (prReflect < 0)
        return {};
    Vector3f wi;
    Float etap = 1;
    BxDFFlags flags;
    if (uc < prReflect) {
        wi = Reflect(wo, wm);
        flags = BxDFFlags::GlossyReflection;
        // A visible normal can still reflect wo to the other side: that energy is lost, as
        // in every single-scattering microfacet model.
        if (!SameHemisphere(wo, wi))
            return {};
    } else {
        flags = BxDFFlags::GlossyTransmission;
        if (!Refract(wo, Normal3f(wm), eta, &etap, &wi) || SameHemisphere(wo, wi) || wi.z == 0)
            return {};
    }
    pstd::optional<Microfacet> m = FindMicrofacet(wo, wi);
    Float pdf = m ? PDFValue(wo, wi, sampleFlags, *m) : 0;
    if (pdf == 0)
        return {};
    return BSDFSample(SampledSpectrum(FValue(wo, wi, mode, *m)), wi, pdf, flags, etap);
}

}  // namespace pbrt
