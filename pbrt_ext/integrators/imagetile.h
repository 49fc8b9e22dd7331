// Rendering by camera samples (pbrt-v4's ImageTileIntegrator::Render): tiles over all cores (TBB)
// in waves of samples, a progress bar, the time limit and cancellation of RenderOptions, and the
// statistics. Every integrator that estimates each camera sample by itself renders this way;
// sppm, mlt and function have their own loops, and the guided ones call this once per iteration.
#pragma once

#include "pbrt_ext/integrators/ambientocclusion.h"
#include "pbrt_ext/integrators/bdpt.h"
#include "pbrt_ext/integrators/guidedpath.h"
#include "pbrt_ext/integrators/lightpath.h"
#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/integrators/randomwalk.h"
#include "pbrt_ext/integrators/simplepath.h"
#include "pbrt_ext/integrators/simplevolpath.h"
#include "pbrt_ext/integrators/volpath.h"
#include "pbrt_ext/render.h"

#include <variant>

namespace pbrt {

class Scene;

using TileIntegrator = std::variant<PathIntegrator, VolPathIntegrator, BDPTIntegrator, LightPathIntegrator,
                                    SimplePathIntegrator, SimpleVolPathIntegrator, RandomWalkIntegrator,
                                    AOIntegrator, GuidedPathIntegrator>;

class SampleMoments;

// Renders sample indices [samples.first, samples.last) of every pixel into the scene's film, in
// waves (render.h's Render says how), with a progress bar titled title; where moments is given,
// also adds each sample's value to it (the mean of its output RGB, times its filter weight), and
// where they estimate the path tracer's moments (for guidedpath's trial only), each sample's
// estimate. Throws std::invalid_argument for such moments with another integrator.
RenderStatistics RenderTiles(Scene &scene, const TileIntegrator &integrator, SampleRange samples,
                             const RenderOptions &options, const char *title,
                             SampleMoments *moments = nullptr);

}  // namespace pbrt
