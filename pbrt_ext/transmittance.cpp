#include "pbrt_ext/transmittance.h"

#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/rng.h"

namespace pbrt {

SampledSpectrum Transmittance(const Scene &scene, Ray ray, Point3f target,
                              const SampledWavelengths &lambda, RayCounts &rays) {
    if (scene.media.empty()) {
        ++rays.shadow;
        return SampledSpectrum(scene.IntersectP(ray, 1 - ShadowEpsilon()) ? 0.f : 1.f);
    }
    // T_ray: the ratio-tracking estimate; inv_w: its probability at each wavelength relative to
    // the hero wavelength's, whose average the estimate is divided by.
    SampledSpectrum T_ray(1.f), inv_w(1.f);
    RNG rng(Hash(ray.o), Hash(target));
    while (true) {
        ++rays.shadow;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray, 1 - ShadowEpsilon());
        if (hit && hit->intr.materialIndex >= 0)
            return SampledSpectrum(0.f);
        if (ray.medium >= 0) {
            Float tMax = hit ? hit->tHit : 1 - ShadowEpsilon();
            SampledSpectrum T_majEnd = scene.media[ray.medium].SampleT_maj(
                ray, tMax, rng.Uniform<Float>(), rng, lambda,
                [&](Point3f, const MediumProperties &mp, SampledSpectrum sigma_maj,
                    SampledSpectrum T_maj) {
                    SampledSpectrum sigma_n = ClampZero(sigma_maj - mp.sigma_a - mp.sigma_s);
                    Float pdf = T_maj[0] * sigma_maj[0];
                    T_ray *= T_maj * sigma_n / pdf;
                    inv_w *= T_maj * sigma_maj / pdf;
                    return bool(T_ray) && bool(inv_w);
                });
            T_ray *= T_majEnd / T_majEnd[0];
            inv_w *= T_majEnd / T_majEnd[0];
        }
        if (!T_ray || !inv_w)
            return SampledSpectrum(0.f);
        if (!hit)
            return T_ray / inv_w.Average();
        ray = hit->intr.SpawnRayTo(target);
    }
}

}  // namespace pbrt
