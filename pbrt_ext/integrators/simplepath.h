// pbrt-v4's SimplePathIntegrator: the reference path tracer without MIS. At each vertex it either
// samples a light chosen uniformly (next-event estimation, "samplelights") and then ignores the
// emitters that the path itself reaches, or it leaves all emission to the path; it continues by
// sampling the BSDF ("samplebsdf") or a uniform direction on the sphere or hemisphere. Every
// combination estimates the same image; no Russian roulette, no regularization. Convergence
// studies compare the MIS estimators against it.
#pragma once

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/options.h"

namespace pbrt {

class Scene;

class SimplePathIntegrator {
  public:
    SimplePathIntegrator(const Scene &scene, const IntegratorOptions &options);

    SampledSpectrum Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                       RayCounts &rays) const;

  private:
    // One light chosen uniformly, a point sampled on it, weight 1.
    SampledSpectrum SampleLd(const SurfaceInteraction &si, const BSDF &bsdf,
                             const SampledWavelengths &lambda, Sampler &sampler,
                             RayCounts &rays) const;
    // The next direction: the BSDF's sample, or SampleUniform's.
    pstd::optional<BSDFSample> SampleDirection(const SurfaceInteraction &si, const BSDF &bsdf,
                                               Vector3f wo, Sampler &sampler) const;
    // A direction uniformly on the sphere, or on the hemisphere of the side the BSDF scatters
    // to, with f cos / pdf; none where the BSDF is zero.
    pstd::optional<BSDFSample> SampleUniform(const SurfaceInteraction &si, const BSDF &bsdf,
                                             Vector3f wo, Point2f u) const;

    const Scene &scene;
    int maxDepth;
    bool sampleLights, sampleBSDF;
    UniformLightSampler lightSampler;
};

}  // namespace pbrt
