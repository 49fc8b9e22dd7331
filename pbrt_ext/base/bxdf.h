// pbrt_ext: the BxDF interface vocabulary (pbrt-v4's base/bxdf.h and the shared parts of bxdfs.h).
//
// Conventions every BxDF follows, as in pbrt-v4:
//  - directions are in the local shading frame: z is the shading normal, x is dpdu;
//  - wo is given and points away from the surface, as does wi; both are unit vectors;
//  - f(wo, wi, mode) excludes the cosine factor |cos theta_i|;
//  - pdf is per unit solid angle of wi;
//  - Sample_f returns an empty optional when it produces no sample (never a zero-pdf sample
//    that the caller would have to filter);
//  - sampleFlags restricts Sample_f and PDF to reflection and/or transmission, identically.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <cstdio>
#include <string>
#include <type_traits>

namespace pbrt {

// What a BxDF can do: which hemispheres it scatters into and how sharply.
enum class BxDFFlags {
    Unset = 0,
    Reflection = 1 << 0,
    Transmission = 1 << 1,
    Diffuse = 1 << 2,
    Glossy = 1 << 3,
    Specular = 1 << 4,
    DiffuseReflection = Diffuse | Reflection,
    DiffuseTransmission = Diffuse | Transmission,
    GlossyReflection = Glossy | Reflection,
    GlossyTransmission = Glossy | Transmission,
    SpecularReflection = Specular | Reflection,
    SpecularTransmission = Specular | Transmission,
    All = Diffuse | Glossy | Specular | Reflection | Transmission
};

// Which hemispheres a caller lets Sample_f and PDF consider.
enum class BxDFReflTransFlags {
    Unset = 0,
    Reflection = 1 << 0,
    Transmission = 1 << 1,
    All = Reflection | Transmission
};

// Radiance: paths traced from the camera; Importance: from the lights. Only BxDFs that are not
// symmetric (refraction scales radiance by 1/eta^2) care which.
enum class TransportMode { Radiance, Importance };

// Bit operations for the two flag enums only (not TransportMode, whose values are not bits).
template <typename E>
concept FlagEnum = std::is_same_v<E, BxDFFlags> || std::is_same_v<E, BxDFReflTransFlags>;

template <FlagEnum E>
PBRT_CPU_GPU constexpr E operator|(E a, E b) {
    return E(int(a) | int(b));
}
template <FlagEnum E>
PBRT_CPU_GPU constexpr E operator&(E a, E b) {
    return E(int(a) & int(b));
}
template <FlagEnum E>
PBRT_CPU_GPU constexpr E &operator|=(E &a, E b) {
    return a = a | b;
}
template <FlagEnum E>
PBRT_CPU_GPU constexpr E operator~(E a) {
    return E(~int(a) & int(E::All));
}
// True when no flag is set, so that `if (!(sampleFlags & BxDFReflTransFlags::Reflection))` reads
// as in pbrt-v4.
template <FlagEnum E>
PBRT_CPU_GPU constexpr bool operator!(E a) {
    return a == E::Unset;
}

PBRT_CPU_GPU constexpr bool IsReflective(BxDFFlags f) {
    return bool(f & BxDFFlags::Reflection);
}
PBRT_CPU_GPU constexpr bool IsTransmissive(BxDFFlags f) {
    return bool(f & BxDFFlags::Transmission);
}
PBRT_CPU_GPU constexpr bool IsDiffuse(BxDFFlags f) {
    return bool(f & BxDFFlags::Diffuse);
}
PBRT_CPU_GPU constexpr bool IsGlossy(BxDFFlags f) {
    return bool(f & BxDFFlags::Glossy);
}
PBRT_CPU_GPU constexpr bool IsSpecular(BxDFFlags f) {
    return bool(f & BxDFFlags::Specular);
}
PBRT_CPU_GPU constexpr bool IsNonSpecular(BxDFFlags f) {
    return bool(f & (BxDFFlags::Diffuse | BxDFFlags::Glossy));
}

// Host-only: "Reflection | Glossy"-style names, as pbrt-v4 prints them.
inline std::string ToString(BxDFFlags flags) {
    if (flags == BxDFFlags::Unset) return "Unset";
    std::string s;
    auto add = [&](BxDFFlags bit, const char *name) {
        if (bool(flags & bit)) s += (s.empty() ? "" : " | ") + std::string(name);
    };
    add(BxDFFlags::Reflection, "Reflection");
    add(BxDFFlags::Transmission, "Transmission");
    add(BxDFFlags::Diffuse, "Diffuse");
    add(BxDFFlags::Glossy, "Glossy");
    add(BxDFFlags::Specular, "Specular");
    return s;
}
inline std::string ToString(TransportMode mode) {
    return mode == TransportMode::Radiance ? "Radiance" : "Importance";
}

// One sampled direction: f and pdf at wi, what kind of scattering produced it, and the relative
// index of refraction crossed (1 unless transmitted). pdfIsProportional marks a pdf known only
// up to a constant (stochastic layered BxDFs), so that callers do not use it for MIS.
struct BSDFSample {
    BSDFSample() = default;
    PBRT_CPU_GPU BSDFSample(SampledSpectrum f0, Vector3f wi0, Float pdf0, BxDFFlags flags0,
                            Float eta0 = 1, bool pdfIsProportional0 = false)
        : f(f0), wi(wi0), pdf(pdf0), flags(flags0), eta(eta0), pdfIsProportional(pdfIsProportional0) {}

    PBRT_CPU_GPU bool IsReflection() const { return pbrt::IsReflective(flags); }
    PBRT_CPU_GPU bool IsTransmission() const { return pbrt::IsTransmissive(flags); }
    PBRT_CPU_GPU bool IsSpecular() const { return pbrt::IsSpecular(flags); }

    // Host-only.
    std::string ToString() const {
        char buf[160];
        std::snprintf(buf, sizeof(buf), "[ BSDFSample wi: [ %g, %g, %g ] pdf: %g eta: %g pdfIsProportional: %s ",
                      wi.x, wi.y, wi.z, pdf, eta, pdfIsProportional ? "true" : "false");
        return std::string(buf) + "f: " + f.ToString() + " flags: " + pbrt::ToString(flags) + " ]";
    }

    SampledSpectrum f;
    Vector3f wi;
    Float pdf = 0;
    BxDFFlags flags = BxDFFlags::Unset;
    Float eta = 1;
    bool pdfIsProportional = false;
};

// Monte Carlo reflectance estimates shared by every BxDF's rho() members (which forward here in
// one line). Both sample with the BxDF's own Sample_f, so the estimate is exact for a BxDF whose
// sampling is perfectly proportional to f |cos|, and they use as many samples as uc holds.

// Sums sample values in double: a float running sum of 1e6 terms drifts by ~1 %.
class RhoAccumulator {
  public:
    PBRT_CPU_GPU void Add(const SampledSpectrum &v) {
        for (int c = 0; c < NSpectrumSamples; ++c)
            sum[c] += v[c];
    }
    PBRT_CPU_GPU SampledSpectrum Mean(double count) const {
        SampledSpectrum r;
        for (int c = 0; c < NSpectrumSamples; ++c)
            r[c] = Float(sum[c] / count);
        return r;
    }

  private:
    double sum[NSpectrumSamples] = {};
};

// Hemispherical-directional reflectance rho(wo) = integral of f(wo, wi) |cos theta_i| dwi.
template <typename BxDF>
PBRT_CPU_GPU SampledSpectrum EstimateRho(const BxDF &bxdf, Vector3f wo, pstd::span<const Float> uc,
                                         pstd::span<const Point2f> u2) {
    if (uc.empty()) return SampledSpectrum(0.f);
    RhoAccumulator r;
    for (std::size_t i = 0; i < uc.size(); ++i) {
        pstd::optional<BSDFSample> bs =
            bxdf.Sample_f(wo, uc[i], u2[i], TransportMode::Radiance, BxDFReflTransFlags::All);
        if (bs && bs->pdf > 0) r.Add(bs->f * AbsCosTheta(bs->wi) / bs->pdf);
    }
    return r.Mean(double(uc.size()));
}

// Hemispherical-hemispherical reflectance: rho(wo) averaged over wo with weight |cos theta_o| / pi.
// wo is drawn uniformly from the upper hemisphere with u1.
template <typename BxDF>
PBRT_CPU_GPU SampledSpectrum EstimateRho(const BxDF &bxdf, pstd::span<const Point2f> u1,
                                         pstd::span<const Float> uc, pstd::span<const Point2f> u2) {
    if (uc.empty()) return SampledSpectrum(0.f);
    RhoAccumulator r;
    for (std::size_t i = 0; i < uc.size(); ++i) {
        Vector3f wo = SampleUniformHemisphere(u1[i]);
        if (wo.z == 0) continue;
        Float pdfo = UniformHemispherePDF();
        pstd::optional<BSDFSample> bs =
            bxdf.Sample_f(wo, uc[i], u2[i], TransportMode::Radiance, BxDFReflTransFlags::All);
        if (bs && bs->pdf > 0) r.Add(bs->f * AbsCosTheta(bs->wi) * AbsCosTheta(wo) / (pdfo * bs->pdf));
    }
    return r.Mean(Pi * double(uc.size()));
}

}  // namespace pbrt
