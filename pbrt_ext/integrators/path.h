// The path tracer (pbrt-v4's PathIntegrator): next-event estimation and BSDF sampling combined by the
// power heuristic, Russian roulette, maxdepth, and pbrt-v4's regularization. A strategy switch keeps
// only one of the two estimators, for convergence studies; all three converge to the same image.
#pragma once

#include "pbrt_ext/cameras/cameras.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/materials/bsdf.h"
#include "pbrt_ext/options.h"
#include "pbrt_ext/samplers/samplers.h"

#include <cstdint>
#include <optional>
#include <string>

namespace pbrt {

class Scene;

// Counts of traced rays, per thread; summed for the statistics.
struct RayCounts {
    int64_t closest = 0, shadow = 0;
};

class PathIntegrator {
  public:
    // Throws std::invalid_argument for a strategy without MIS on a scene whose light sampler
    // was built for MIS and leaves lights to BSDF sampling (LightSampler::NeedsIncompletePDFs).
    PathIntegrator(const Scene &scene, IntegratorOptions options);

    // Radiance arriving along ray (from its origin's point of view) at the wavelengths lambda,
    // whose secondary wavelengths a dispersive surface may terminate.
    // ray: a camera ray with its differentials (a plain ray converts to one without).
    SampledSpectrum Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                       RayCounts &rays) const;
    // Direct lighting at an intersection by sampling one light: its contribution weighted for MIS
    // against BSDF sampling (or with weight 1 for strategy Light). Also sppm's at its camera
    // paths' vertices.
    SampledSpectrum SampleLd(const SurfaceInteraction &si, const BSDF &bsdf,
                             const SampledWavelengths &lambda, Sampler &sampler,
                             RayCounts &rays) const;

  private:
    // The BSDF density of the direction a path was sampled in, for the MIS weight of an emitter
    // the path reaches. A proportional sample's (the layered BxDFs') is an estimate that costs
    // random walks, so it is estimated only once an emitter asks for it: most bounces reach
    // none (pbrt-v4 estimates it at every bounce).
    class BSDFDensity {
      public:
        void Set(Float pdf) {
            value = pdf;
            pending.reset();
        }
        void Defer(const BSDF &bsdf, Vector3f wo, Vector3f wi) {
            pending = bsdf;
            pendingWo = wo;
            pendingWi = wi;
        }
        Float Get() {
            if (pending)
                Set(pending->PDF(pendingWo, pendingWi));
            return value;
        }

      private:
        Float value = 1;
        std::optional<BSDF> pending;
        Vector3f pendingWo, pendingWi;
    };

    // Weight of an emitter reached by BSDF sampling with density pdfBSDF, that light sampling
    // from prevCtx would have chosen with density pdfLight.
    Float BSDFHitWeight(bool lightSamplingApplied, BSDFDensity &pdfBSDF, Float pdfLight) const;
    // pbrt-v4 lets lights leave out directions that BSDF sampling covers well (a uniform
    // environment, the dim parts of an image) when MIS combines the two; alone, light sampling
    // must cover every direction.
    bool AllowIncompletePDF() const { return options.strategy == PathStrategy::MIS; }

    const Scene &scene;
    IntegratorOptions options;
};

}  // namespace pbrt
