// Bidirectional path tracing (pbrt-v4's BDPTIntegrator; Veach's thesis, chapter 10; the book's
// section 13.4 of its third edition).
//
// Each camera sample traces a subpath from the camera and one from a light chosen by power, then
// connects every prefix of one to every prefix of the other: strategy (s, t) joins the first s
// light vertices to the first t camera vertices. s = 0 is the camera subpath reaching an emitter
// by itself, s = 1 samples a light point for it (next-event estimation), t = 1 samples a lens
// point for the light subpath (light tracing, splatted to the film wherever it lands). The
// strategies that make the same path are weighted by the balance heuristic, computed as pbrt-v4
// does from the densities of each vertex in both directions. Media are sampled by delta tracking
// along both subpaths; their vertices connect like surfaces.
#pragma once

#include "pbrt_ext/cameras/cameraimportance.h"
#include "pbrt_ext/film/film.h"
#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/samplers/samplers.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pbrt {

class Scene;
struct BDPTVertex;  // bdpt.cpp

class BDPTIntegrator {
  public:
    // Throws std::invalid_argument for a camera without importance (not perspective).
    // cameraSampleArea: the film area, in pixels, that camera samples spread over (the pixel
    // bounds' by default; mlt's sample bounds). Light paths splat over the whole film, so the
    // t = 1 strategy's contributions scale by the full film's area over it.
    BDPTIntegrator(Scene &scene, IntegratorOptions options,
                   std::optional<Float> cameraSampleArea = std::nullopt);

    // The camera subpath starts with ray from the film position pFilm; t = 1 strategies go to
    // the film as splats, the rest is returned.
    SampledSpectrum Li(RayDifferential ray, Point2f pFilm, SampledWavelengths &lambda,
                       Sampler &sampler, RayCounts &rays) const;

    // With visualizestrategies or visualizeweights, writes each strategy's image beside the
    // film's file (bdpt_dDD_sSS_tTT.exr, as pbrt-v4), scaled for the light paths per pixel.
    void WriteStrategyImages(Float splatScale) const;

    // One strategy at a time, as Metropolis light transport makes paths (integrators/mlt.h):
    // subpaths of at most maxVertices vertices (fewer where they end), and the connection of
    // the first s light to the first t camera vertices, with its MIS weight applied and
    // returned in *misWeight, and where a t = 1 connection lands on the film in *pRaster.
    int GenerateCameraSubpath(const RayDifferential &ray, SampledWavelengths &lambda, Sampler &sampler,
                              RayCounts &rays, BDPTVertex *path, int maxVertices) const;
    int GenerateLightSubpath(SampledWavelengths &lambda, Sampler &sampler, Float time,
                             RayCounts &rays, BDPTVertex *path, int maxVertices) const;
    SampledSpectrum ConnectBDPT(SampledWavelengths &lambda, BDPTVertex *lightVertices,
                                BDPTVertex *cameraVertices, int s, int t, Sampler &sampler,
                                RayCounts &rays, pstd::optional<Point2f> *pRaster,
                                Float *misWeight) const;

  private:
    // The MIS weight of strategy (s, t) for the path made of the first s light and t camera
    // vertices, where for s = 1 (t = 1) the light (camera) endpoint is the one the connection
    // sampled, *sampled.
    Float MISWeight(BDPTVertex *lightVertices, BDPTVertex *cameraVertices, BDPTVertex *sampled,
                    int s, int t) const;
    friend struct BDPTVertex;  // its densities need the camera, lights and scene
    friend struct BDPTTestAccess;  // tests/integrators/bdptmis_test.cpp checks the weights path by path

    int RandomWalk(SampledWavelengths &lambda, RayDifferential ray, Sampler &sampler,
                   SampledSpectrum beta, Float pdf, int maxDepth, TransportMode mode,
                   RayCounts &rays, BDPTVertex *path) const;
    struct Walk;  // bdpt.cpp: RandomWalk's state
    enum class MediumStep { PassedThrough, Scattered, Ended };
    // Delta tracking along the walk's ray up to tMax: a real collision makes a medium vertex.
    MediumStep TrackThroughMedium(Walk &walk, Float tMax, const SampledWavelengths &lambda,
                                  Sampler &sampler) const;
    // Makes the surface vertex at si and samples the walk's next direction from it; false
    // where the walk ends there.
    bool ScatterAtSurface(Walk &walk, const SurfaceInteraction &si, BSDF bsdf,
                          Sampler &sampler) const;
    SampledSpectrum ConnectToCamera(SampledWavelengths &lambda, BDPTVertex *lightVertices,
                                    BDPTVertex *cameraVertices, int s, Sampler &sampler, RayCounts &rays,
                                    pstd::optional<Point2f> *pRaster, Float *misWeight) const;
    SampledSpectrum ConnectToLight(SampledWavelengths &lambda, BDPTVertex *lightVertices,
                                   BDPTVertex *cameraVertices, int t, Sampler &sampler, RayCounts &rays,
                                   Float *misWeight) const;
    // L times its MIS weight, which goes to *misWeight (0 for no contribution).
    SampledSpectrum WeightedByMIS(SampledSpectrum L, BDPTVertex *lightVertices,
                                  BDPTVertex *cameraVertices, BDPTVertex *sampled, int s, int t,
                                  Float *misWeight) const;
    // The density with which the light subpath starts at an infinite light toward -w.
    Float InfiniteLightDensity(Vector3f w) const;
    RGBFilm *StrategyFilm(int s, int t) const;

    const Scene &scene;
    RGBFilm &film;
    IntegratorOptions options;
    CameraImportance camera;
    PowerLightSampler lightSampler;
    Float sceneRadius;
    // Contributions of t = 1 strategies scale by the full film's area over the crop window's
    // (pbrt-v4's issue 347), since light paths are spread over the whole film.
    Float cropScale;
    // One film per (s, t) for visualizestrategies / visualizeweights, else empty.
    mutable std::vector<std::unique_ptr<RGBFilm>> strategyFilms;
};

}  // namespace pbrt
