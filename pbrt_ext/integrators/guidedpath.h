// Path tracing guided by the radiance field an SD-tree learns (integrators/sdtree.h; Müller,
// Gross and Novák 2017): pbrt-v4's path tracer, but at each vertex whose BSDF has neither a
// specular nor a near-specular lobe, the next direction comes from the mixture of the BSDF and
// the leaf's learned distribution that pathguide.h describes, whose density is also what next-
// event estimation's and the emitters' MIS weights use; and Russian roulette follows the
// radiance learned along the path's direction (PathGuide::SurvivalProbability).
//
// While training, each path records at its vertices the radiance that arrived there, over the
// density its direction was sampled with (Müller's irradiance records): along the scattered
// direction, everything the rest of the path found; along the light's, next-event estimation's
// radiance with its MIS weight; and at each guided vertex, what its BSDF fraction learns from.
// Recording is the only thing that training changes: a render with a frozen tree is an ordinary
// unbiased estimator. Given an UnguidedMoment, Li also estimates the second moment of the path
// tracer's estimate from the path it takes (unguidedmoment.h), for guiding's trial.
#pragma once

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/integrators/pathguide.h"
#include "pbrt_ext/integrators/unguidedmoment.h"
#include "pbrt_ext/options.h"

namespace pbrt {

class Scene;

class GuidedPathIntegrator {
  public:
    // Samples from tree, and records into it where record.
    GuidedPathIntegrator(const Scene &scene, const IntegratorOptions &options, SDTree &tree, bool record);

    SampledSpectrum Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler, RayCounts &rays,
                       UnguidedMoment *unguided = nullptr) const;

  private:
    using VertexGuide = PathGuide::VertexGuide;

    // Next-event estimation at si, LdPath where pathWeighted; where training, its record.
    DirectLight SampleLd(const SurfaceInteraction &si, const BSDF &bsdf, const VertexGuide &guide,
                        const SampledWavelengths &lambda, Sampler &sampler, RayCounts &rays,
                        bool pathWeighted) const;
    // Russian roulette by what the path is expected to bring (PathGuide::SurvivalProbability), from
    // the third vertex on and only while the throughput is under 1, as in the path tracer: whether
    // the path survives, its throughput beta then divided by the probability that it did. learned:
    // the leaf's distribution at the vertex, scatter: the direction it sampled; unguided: told of
    // the roulette the path tracer would have rolled.
    bool Survives(SampledSpectrum &beta, Float etaScale, int depth, const DTree &learned,
                  const VertexGuide &vertex, const PathGuide::Scatter &scatter, Float pixelEstimate,
                  Sampler &sampler, UnguidedMoment *unguided) const;

    const Scene &scene;
    IntegratorOptions options;
    PathGuide guide;
};

}  // namespace pbrt
