// Light tracing (pbrt-v4's LightPathIntegrator): paths traced from the lights alone, each vertex
// connected to a point on the lens and splatted to the film wherever it lands. It finds what
// camera paths cannot (caustics from small lights seen on diffuse surfaces) and misses what
// only they find (specular surfaces seen by the camera). Media are ignored, as in pbrt-v4.
#pragma once

#include "pbrt_ext/cameras/cameraimportance.h"
#include "pbrt_ext/film/film.h"
#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/samplers/samplers.h"

namespace pbrt {

class Scene;

class LightPathIntegrator {
  public:
    // Throws std::invalid_argument for a camera without importance (not perspective).
    LightPathIntegrator(Scene &scene, IntegratorOptions options);

    // Traces one light path at the wavelengths lambda and splats what it sends to the camera;
    // returns nothing for the camera sample itself (ray and pFilm are unused).
    SampledSpectrum Li(RayDifferential ray, Point2f pFilm, SampledWavelengths &lambda,
                       Sampler &sampler, RayCounts &rays) const;

  private:
    // Splats beta times what the vertex at si (BSDF bsdf) sends toward a sampled lens point.
    void ConnectToCamera(const SurfaceInteraction &si, const BSDF &bsdf, SampledSpectrum beta,
                         const SampledWavelengths &lambda, Sampler &sampler, RayCounts &rays) const;

    // Whether ray (d to its end, at t = 1) reaches its end.
    bool Unoccluded(const Ray &ray, RayCounts &rays) const;

    const Scene &scene;
    RGBFilm &film;
    IntegratorOptions options;
    CameraImportance camera;
    PowerLightSampler lightSampler;
    Float cropScale;  // the full film's area over the crop window's, as in bdpt.h
};

}  // namespace pbrt
