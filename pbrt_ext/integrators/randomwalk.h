// pbrt-v4's RandomWalkIntegrator: the plainest unbiased estimator of the rendering equation. Each
// vertex adds the emission it sees and continues in a direction uniform over the whole sphere,
// weighted by f |cos| / (1 / 4 pi); no light sampling, no Russian roulette, up to maxdepth
// bounces. It shares no sampling code with the other integrators, which makes it the reference
// they are checked against where its variance allows.
#pragma once

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/options.h"

namespace pbrt {

class Scene;

class RandomWalkIntegrator {
  public:
    RandomWalkIntegrator(const Scene &scene, const IntegratorOptions &options)
        : scene(scene), maxDepth(options.maxDepth) {}

    SampledSpectrum Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                       RayCounts &rays) const;

  private:
    const Scene &scene;
    int maxDepth;
};

}  // namespace pbrt
