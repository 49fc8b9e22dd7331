// Stochastic progressive photon mapping (pbrt-v4's SPPMIntegrator; Hachisuka and Jensen 2009).
//
// Each iteration traces one camera path per pixel to its first diffuse surface (its visible
// point), adding the light it finds on the way by path tracing with next-event estimation;
// then shoots photons from the lights (chosen by power) and adds, at every visible point within
// the pixel's search radius of a photon's hit, the photon's flux times the visible point's
// BSDF. After each iteration every pixel's radius shrinks by the fraction of new photons it
// keeps (alpha = 2/3), so that the estimate is consistent: its bias vanishes as iterations
// grow. Iterations follow the sampler's samples per pixel; media are ignored, as in pbrt-v4.
#pragma once

#include "pbrt_ext/render.h"

namespace pbrt {

class Scene;

// Renders the scene by SPPM into its film (one value per pixel, in the sensor's RGB). Render
// calls it, under the thread limit of options.
RenderStatistics RenderSPPM(Scene &scene, const RenderOptions &options);

}  // namespace pbrt
