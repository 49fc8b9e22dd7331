// pbrt-v4's AOIntegrator ("ambientocclusion"): the fraction of the hemisphere above the first
// surface a camera ray reaches that is open to within maxdistance, cosine-weighted, as the
// radiance of a white sky of luminance 1 (the film colour space's illuminant, scaled to
// luminance 1) that only unoccluded directions see. Directions are drawn cosine-distributed
// ("cossample", the default) or uniformly over the hemisphere about the geometric normal turned
// toward the camera. Surfaces without a material (interfaces) are passed through.
#pragma once

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/options.h"
#include "pbrt_ext/spectra/spectrum.h"

namespace pbrt {

class Scene;

class AOIntegrator {
  public:
    AOIntegrator(const Scene &scene, const IntegratorOptions &options);

    SampledSpectrum Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                       RayCounts &rays) const;

  private:
    const Scene &scene;
    bool cosSample;
    Float maxDistance;
    Spectrum illuminant;    // the film colour space's
    Float illuminantScale;  // 1 / its luminance
};

}  // namespace pbrt
