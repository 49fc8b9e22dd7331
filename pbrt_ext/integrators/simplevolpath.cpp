#include "pbrt_ext/integrators/simplevolpath.h"

#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"

#include <stdexcept>

namespace pbrt {

SimpleVolPathIntegrator::SimpleVolPathIntegrator(const Scene &scene, const IntegratorOptions &options)
    : scene(scene), maxDepth(options.maxDepth) {
    if (!scene.materials.empty())
        throw std::invalid_argument(
            "simplevolpath renders participating media alone (pbrt-v4's SimpleVolPathIntegrator): "
            "its surfaces may only bound media or emit (Material \"interface\"), but this scene "
            "has " + std::to_string(scene.materials.size()) +
            " material(s); render it with volpath");
}

SampledSpectrum SimpleVolPathIntegrator::Li(RayDifferential ray, SampledWavelengths &lambda,
                                            Sampler &sampler, RayCounts &rays) const {
    SampledSpectrum L(0.f);
    Float beta = 1;  // the hero wavelength's throughput: only scalar ratios change it
    int depth = 0;
    lambda.TerminateSecondary();
    for (;;) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray);
        bool scattered = false, terminated = false;
        if (ray.medium >= 0) {
            uint64_t hash0 = Hash(sampler.Get1D()), hash1 = Hash(sampler.Get1D());
            RNG rng(hash0, hash1);
            Float u = sampler.Get1D(), uMode = sampler.Get1D();
            scene.media[ray.medium].SampleT_maj(
                ray, hit ? hit->tHit : Infinity, u, rng, lambda,
                [&](Point3f p, const MediumProperties &mp, SampledSpectrum sigma_maj,
                    SampledSpectrum) {
                    Float pAbsorb = mp.sigma_a[0] / sigma_maj[0];
                    Float pScatter = mp.sigma_s[0] / sigma_maj[0];
                    Float pNull = std::max<Float>(0, 1 - pAbsorb - pScatter);
                    Float um = uMode * (pAbsorb + pScatter + pNull);
                    int mode = um < pAbsorb ? 0 : um < pAbsorb + pScatter ? 1 : 2;
                    if (mode == 0) {  // absorption: the emission there ends the path
                        L += beta * mp.Le;
                        terminated = true;
                        return false;
                    }
                    if (mode == 1) {  // real scattering: the phase function's direction
                        if (depth++ >= maxDepth) {
                            terminated = true;
                            return false;
                        }
                        Vector3f wo = -ray.d / Length(ray.d);
                        std::optional<PhaseFunctionSample> ps =
                            mp.phase.Sample_p(wo, Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
                        if (!ps) {
                            terminated = true;
                            return false;
                        }
                        beta *= ps->p / ps->pdf;
                        ray.o = p;
                        ray.d = ps->wi;
                        scattered = true;
                        return false;
                    }
                    uMode = rng.Uniform<Float>();  // null scattering: on along the ray
                    return true;
                });
        }
        if (terminated)
            return L;
        if (scattered)
            continue;
        if (!hit) {
            for (int index : scene.infiniteLights)
                L += beta * scene.lights[index].Le(ray, lambda);
            return L;
        }
        SurfaceInteraction &si = hit->intr;
        if (si.areaLightIndex >= 0)
            L += beta * scene.lights[si.areaLightIndex].L(si.p, si.n, si.uv, -ray.d, lambda);
        ray = si.SpawnRay(ray.d);  // every surface is an interface (checked when made)
    }
}

}  // namespace pbrt
