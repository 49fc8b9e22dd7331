// Transmittance between two points of a scene (pbrt-v4's Integrator::Tr), for the connections of
// paths traced from both ends (bdpt, lightpath): zero where a surface blocks the segment; through
// media and the interfaces between them, a ratio-tracking estimate, with the hero wavelength's
// collisions weighted for all wavelengths by their average probability (spectral MIS).
#pragma once

#include "pbrt_ext/integrators.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/spectrum.h"

namespace pbrt {

class Scene;

// ray: from the first point, with d = target - ray.o (t = 1 reaches target), in the medium it
// starts in. Without media in the scene, any surface in between blocks it (as the path tracer's
// shadow rays).
SampledSpectrum Transmittance(const Scene &scene, Ray ray, Point3f target,
                              const SampledWavelengths &lambda, RayCounts &rays);

}  // namespace pbrt
