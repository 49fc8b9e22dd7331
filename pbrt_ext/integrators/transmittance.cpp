#include "pbrt_ext/integrators/transmittance.h"

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
    bool reached = WalkToTarget(scene, ray, target, rays, [&](const Ray &r, Float tMax) {
        const Medium &medium = scene.media[r.medium];
        // Exact where it can be: no distance is drawn, so no wavelength's density to weigh.
        if (std::optional<SampledSpectrum> T = medium.ClosedFormTransmittance(r, tMax, lambda)) {
            T_ray *= *T;
            return bool(T_ray);
        }
        SampledSpectrum T_majEnd = medium.SampleT_maj(
            r, tMax, rng.Uniform<Float>(), rng, lambda,
            [&](Point3f, const MediumProperties &mp, SampledSpectrum sigma_maj, SampledSpectrum T_maj) {
                RatioTrackingStep step = RatioTracking(mp, sigma_maj, T_maj);
                T_ray *= step.nullRatio;
                inv_w *= step.majorantRatio;
                return bool(T_ray) && bool(inv_w);
            },
            MediumQuery::NoEmission);
        SampledSpectrum tailRelativeToHero = T_majEnd / T_majEnd[0];
        T_ray *= tailRelativeToHero;
        inv_w *= tailRelativeToHero;
        return bool(T_ray) && bool(inv_w);
    });
    return reached ? T_ray / inv_w.Average() : SampledSpectrum(0.f);
}

}  // namespace pbrt
