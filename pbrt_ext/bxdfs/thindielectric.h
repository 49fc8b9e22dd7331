// pbrt_ext: a thin dielectric slab (a window pane, a soap bubble), pbrt-v4's
// ThinDielectricBxDF (Physically Based Rendering, 4th edition, Section 9.5.3 "Thin
// Dielectric BSDF").
//
// Two parallel smooth interfaces of relative index eta, so close together that the light
// leaves where it entered: reflection in the mirror direction, transmission straight
// through (wi = -wo, no change of medium, so sample eta 1 and no radiance scaling). The
// slab's reflectance sums the inter-reflections between the two interfaces, the geometric
// series R + T^2 R / (1 - R^2), and T = 1 - R. Both lobes are Dirac deltas: f() and PDF()
// are zero and only Sample_f() produces them, each with its discrete probability as pdf.
// Reciprocal; TransportMode plays no part.
// Differs from pbrt-v4: Sample_f() returns no sample for wo exactly in the tangent plane,
// where pbrt-v4 divides by a zero cosine; sampleFlags defaults to All, as everywhere here.
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <cstdio>
#include <string>

namespace pbrt {

class ThinDielectricBxDF {
  public:
    ThinDielectricBxDF() = default;
    PBRT_CPU_GPU ThinDielectricBxDF(Float eta0) : eta(eta0) {}

    PBRT_CPU_GPU BxDFFlags Flags() const {
        return BxDFFlags::Reflection | BxDFFlags::Transmission | BxDFFlags::Specular;
    }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f /*wo*/, Vector3f /*wi*/,
                                   TransportMode /*mode*/) const {
        return SampledSpectrum(0.f);
    }

    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float uc, Point2f /*u*/, TransportMode /*mode*/,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (wo.z == 0)
            return {};
        Float R = FrDielectric(AbsCosTheta(wo), eta), T = 1 - R;
        // Light bounces between the interfaces; each round trip returns R^2 of it. At
        // R == 1 (grazing) the series is 0 / 0 and everything is reflected anyway.
        if (R < 1) {
            R += Sqr(T) * R / (1 - Sqr(R));
            T = 1 - R;
        }
        Float pr = bool(sampleFlags & BxDFReflTransFlags::Reflection) ? R : 0;
        Float pt = bool(sampleFlags & BxDFReflTransFlags::Transmission) ? T : 0;
        if (pr == 0 && pt == 0)
            return {};
        // f carries 1 / |cos| so that the sample weight is R / pr (or T / pt).
        if (uc < pr / (pr + pt)) {
            Vector3f wi(-wo.x, -wo.y, wo.z);
            return BSDFSample(SampledSpectrum(R / AbsCosTheta(wi)), wi, pr / (pr + pt),
                              BxDFFlags::SpecularReflection);
        }
        Vector3f wi = -wo;
        return BSDFSample(SampledSpectrum(T / AbsCosTheta(wi)), wi, pt / (pr + pt),
                          BxDFFlags::SpecularTransmission);
    }

    PBRT_CPU_GPU Float PDF(Vector3f /*wo*/, Vector3f /*wi*/, TransportMode /*mode*/,
                           BxDFReflTransFlags /*sampleFlags*/ = BxDFReflTransFlags::All) const {
        return 0;
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

    // Nothing to widen: the slab has no roughness, and giving it one would move the
    // transmitted light sideways, which a thin slab by definition does not do (pbrt-v4
    // leaves this empty too).
    PBRT_CPU_GPU void Regularize() {}

    PBRT_CPU_GPU static constexpr const char *Name() { return "ThinDielectricBxDF"; }

    // Host-only.
    std::string ToString() const {
        char buf[64];
        std::snprintf(buf, sizeof(buf), "[ ThinDielectricBxDF eta: %g ]", eta);
        return buf;
    }

  private:
    Float eta = 1;
};

}  // namespace pbrt
