// The closed set of BxDFs, listed in one place, and their dispatch (pbrt-v4's end of bxdfs.h). Each
// interface method dispatches in one line; no virtual functions.
#pragma once

#include "pbrt_ext/bxdfs/conductor.h"
#include "pbrt_ext/bxdfs/dielectric.h"
#include "pbrt_ext/bxdfs/diffuse.h"
#include "pbrt_ext/bxdfs/diffusetransmission.h"
#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/bxdfs/fabricdiffuse.h"
#include "pbrt_ext/bxdfs/hair.h"
#include "pbrt_ext/bxdfs/layered.h"
#include "pbrt_ext/bxdfs/measured.h"
#include "pbrt_ext/bxdfs/normalizedfresnel.h"
#include "pbrt_ext/bxdfs/thindielectric.h"

#include <string>
#include <variant>

namespace pbrt {

class BxDF {
  public:
    using Variant =
        std::variant<DiffuseBxDF, ConductorBxDF, DielectricBxDF, ThinDielectricBxDF,
                     DiffuseTransmissionBxDF, CoatedDiffuseBxDF, CoatedConductorBxDF, FabricBxDF,
                     FabricDiffuseBxDF, HairBxDF, MeasuredBxDF, NormalizedFresnelBxDF>;

    template <typename T>
    BxDF(T bxdf) : bxdf(std::move(bxdf)) {}

    BxDFFlags Flags() const {
        return std::visit([](const auto &b) { return b.Flags(); }, bxdf);
    }
    SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode mode) const {
        return std::visit([&](const auto &b) { return b.f(wo, wi, mode); }, bxdf);
    }
    pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float uc, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        return std::visit([&](const auto &b) { return b.Sample_f(wo, uc, u, mode, sampleFlags); },
                          bxdf);
    }
    Float PDF(Vector3f wo, Vector3f wi, TransportMode mode,
              BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        return std::visit([&](const auto &b) { return b.PDF(wo, wi, mode, sampleFlags); }, bxdf);
    }
    void Regularize() {
        std::visit([](auto &b) { b.Regularize(); }, bxdf);
    }
    SampledSpectrum rho(Vector3f wo, pstd::span<const Float> uc, pstd::span<const Point2f> u2) const {
        return std::visit([&](const auto &b) { return b.rho(wo, uc, u2); }, bxdf);
    }
    std::string ToString() const {
        return std::visit([](const auto &b) { return b.ToString(); }, bxdf);
    }

  private:
    Variant bxdf;
};

}  // namespace pbrt
