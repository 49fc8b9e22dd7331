// Generated from pbrt_ext/bxdfs/fabricdiffuse.h by scripts/port-pbrt-v4 --regenerate: edit that file, not this one.
// FabricDiffuseBxDF: the fabric lobe over an optional Lambertian base, combined so that the directional
// albedo never exceeds 1.
//
// The DreamWorks fabric model (Deshmukh, Xie, Tabellion, SIGGRAPH 2017 Talks) pairs its specular cone
// with a diffuse base. Adding the two unweighted lets a white fabric over a white base reflect more than
// it receives. We weight the base by what the lobe leaves over:
//     f = f_fabric + kd · diffuse / π,   kd = clamp(1 - P · max_c color_c, 0, 1),
// with P = fabric.PeakAlbedo(), an upper bound of the fabric's directional albedo per unit color over
// every direction. Per channel c and for every wo:
//     a_c(wo) = a_fabric,c(wo) + kd · diffuse_c ≤ P · color_c + kd ≤ P · max color + kd ≤ 1
// (the diffuse reflectance is clamped to [0, 1]; a fabric color above 1/P already exceeds 1 on its own,
// and then kd = 0). kd does not depend on the directions, so f stays reciprocal.
//
// Sampling is a one-sample MIS mixture: the fabric lobe with probability pf = wf / (wf + wd), where
// wf = P · Average(color) and wd = kd · Average(diffuse) estimate each lobe's share of the albedo, and
// cosine sampling otherwise; uc picks the lobe and is remapped for the fabric sampler. The density is
// pf · pdf_fabric + (1 - pf) · cos θ / π. Sample_f reports f() and PDF() at the direction it made.
// With a black color it is DiffuseBxDF(diffuse); with a black diffuse it is the FabricBxDF, exactly.
//
// Conventions (pbrt-v4): local shading frame (z = normal), f excludes the cosine, pdfs per unit solid
// angle. Reflection only and two-sided, like both lobes.
#pragma once

#include <pbrt/bxdfs/fabric_compat.h>
#include <pbrt/bxdfs.h>
#include <pbrt/bxdfs/fabric.h>
#include <pbrt/pbrt.h>
#include <pbrt/util/math.h>
#include <pbrt/util/pstd.h>
#include <pbrt/util/spectrum.h>
#include <pbrt/util/vecmath.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace pbrt {

class FabricDiffuseBxDF {
  public:
    FabricDiffuseBxDF() = default;
    // diffuse is the base's reflectance before the weight kd; NaN counts as 0.
    PBRT_CPU_GPU FabricDiffuseBxDF(FabricBxDF fabric, SampledSpectrum diffuse)
        : fabric(fabric), reflectance(Clamp(ClampZero(diffuse), Float(0), Float(1))) {
        Combine();
    }

    PBRT_CPU_GPU BxDFFlags Flags() const { return fabric.Flags() | base.Flags(); }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode mode) const {
        return fabric.f(wo, wi, mode) + base.f(wo, wi, mode);
    }

    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float uc, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const;

    PBRT_CPU_GPU Float PDF(Vector3f wo, Vector3f wi, TransportMode mode,
                           BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection))
            return 0;
        return MixPDF(fabric.PDF(wo, wi, mode, sampleFlags), base.PDF(wo, wi, mode, sampleFlags));
    }

    PBRT_CPU_GPU SampledSpectrum rho(Vector3f wo, pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, wo, uc, u2);
    }
    PBRT_CPU_GPU SampledSpectrum rho(pstd::span<const Point2f> u1, pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, u1, uc, u2);
    }

    // Widens the fabric lobe (the base needs nothing). A wider lobe has another peak albedo, so the
    // weights are recomputed and the energy bound still holds.
    PBRT_CPU_GPU void Regularize() {
        fabric.Regularize();
        Combine();
    }

    PBRT_CPU_GPU static constexpr const char *Name() { return "FabricDiffuseBxDF"; }
    std::string ToString() const;

    PBRT_CPU_GPU const FabricBxDF &Fabric() const { return fabric; }
    PBRT_CPU_GPU Float DiffuseWeight() const { return kd; }
    PBRT_CPU_GPU Float FabricProbability() const { return pFabric; }

  private:
    PBRT_CPU_GPU void Combine() {
        Float peak = fabric.PeakAlbedo();
        SampledSpectrum color = fabric.Color();
        kd = Clamp(1 - peak * color.MaxComponentValue(), 0, 1);
        base = DiffuseBxDF(kd * reflectance);
        Float wf = peak * color.Average(), wd = kd * reflectance.Average();
        pFabric = wd == 0 ? Float(1) : (wf == 0 ? Float(0) : wf / (wf + wd));
    }

    PBRT_CPU_GPU Float MixPDF(Float fabricPdf, Float basePdf) const {
        return pFabric * fabricPdf + (1 - pFabric) * basePdf;
    }

    FabricBxDF fabric;
    SampledSpectrum reflectance;  // of the base, in [0, 1], before kd
    DiffuseBxDF base;             // kd · reflectance / π
    Float kd = 0, pFabric = 1;
};

PBRT_CPU_GPU inline pstd::optional<BSDFSample> FabricDiffuseBxDF::Sample_f(
    Vector3f wo, Float uc, Point2f u, TransportMode mode, BxDFReflTransFlags sampleFlags) const {
    if (!(sampleFlags & BxDFReflTransFlags::Reflection) || wo.z == 0)
        return {};
    // The result is f() and PDF() at wi. The fabric branch reuses the lobe's own values, which are its
    // f() and PDF() exactly, and so evaluates the costly lobe once.
    if (uc < pFabric) {
        pstd::optional<BSDFSample> bs =
            fabric.Sample_f(wo, std::min(uc / pFabric, OneMinusEpsilon), u, mode, sampleFlags);
        if (!bs)
            return {};
        Float pdf = MixPDF(bs->pdf, base.PDF(wo, bs->wi, mode, sampleFlags));
        if (!(pdf > 0))
            return {};
        return BSDFSample(bs->f + base.f(wo, bs->wi, mode), bs->wi, pdf, bs->flags);
    }
    pstd::optional<BSDFSample> bs = base.Sample_f(wo, uc, u, mode, sampleFlags);
    if (!bs)
        return {};
    Float pdf = PDF(wo, bs->wi, mode, sampleFlags);
    if (!(pdf > 0))
        return {};  // wi on the horizon, where f() is 0 too
    return BSDFSample(f(wo, bs->wi, mode), bs->wi, pdf, bs->flags);
}

inline std::string FabricDiffuseBxDF::ToString() const {
    char buf[128];
    std::snprintf(buf, sizeof(buf), " kd: %g pFabric: %g ]", kd, pFabric);
    return "[ FabricDiffuseBxDF fabric: " + fabric.ToString() +
           " diffuse: " + reflectance.ToString() + buf;
}

}  // namespace pbrt
