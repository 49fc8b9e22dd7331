// pbrt-v4's SimpleVolPathIntegrator: the reference estimator for participating media alone.
// Delta tracking with the hero wavelength's probabilities (the others are terminated first):
// each tentative collision is absorption (adding the medium's emission there), real scattering
// (sampling the phase function) or null scattering, with probabilities sigma_a, sigma_s and the
// rest of the majorant. No light sampling: emission counts where a path reaches it. Surfaces
// may only bound media or emit; one that scatters light is an error, as in pbrt-v4 (here when
// the integrator is made, before anything renders).
#pragma once

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/options.h"

namespace pbrt {

class Scene;

class SimpleVolPathIntegrator {
  public:
    // Throws std::invalid_argument if a surface of the scene has a material.
    SimpleVolPathIntegrator(const Scene &scene, const IntegratorOptions &options);

    SampledSpectrum Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                       RayCounts &rays) const;

  private:
    const Scene &scene;
    int maxDepth;
};

}  // namespace pbrt
