// Transmittance between two points of a scene (pbrt-v4's Integrator::Tr), for the connections of
// paths traced from both ends (bdpt, lightpath): zero where a surface blocks the segment; through
// media and the interfaces between them, Beer-Lambert in homogeneous media and a ratio-tracking
// estimate in the others, with the hero wavelength's collisions weighted for all wavelengths by
// their average probability (spectral MIS).
#pragma once

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/spectrum.h"

namespace pbrt {

// ray: from the first point, with d = target - ray.o (t = 1 reaches target), in the medium it
// starts in. Without media in the scene, any surface in between blocks it (as the path tracer's
// shadow rays).
SampledSpectrum Transmittance(const Scene &scene, Ray ray, Point3f target,
                              const SampledWavelengths &lambda, RayCounts &rays);

// Walks a shadow ray (d = target - ray.o) to target through the interfaces between media,
// calling inMedium(ray, tMax) for each stretch of it inside a medium; that returns false to
// give up. False where a surface with a material blocks the ray or inMedium gave up.
template <typename InMedium>
bool WalkToTarget(const Scene &scene, Ray ray, Point3f target, RayCounts &rays, InMedium inMedium) {
    while (true) {
        ++rays.shadow;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray, 1 - ShadowEpsilon());
        if (hit && hit->intr.materialIndex >= 0)
            return false;
        if (ray.medium >= 0 && !inMedium(ray, hit ? hit->tHit : 1 - ShadowEpsilon()))
            return false;
        if (!hit)
            return true;
        ray = hit->intr.SpawnRayTo(target);
    }
}

}  // namespace pbrt
