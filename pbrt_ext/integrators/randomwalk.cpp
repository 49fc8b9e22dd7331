#include "pbrt_ext/integrators/randomwalk.h"

#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/sampling.h"

namespace pbrt {

// pbrt-v4 writes it as a recursion; the same sum as a loop: each vertex's emission times the
// product of the weights of the directions before it.
SampledSpectrum RandomWalkIntegrator::Li(RayDifferential ray, SampledWavelengths &lambda,
                                         Sampler &sampler, RayCounts &rays) const {
    SampledSpectrum L(0.f), beta(1.f);
    for (int depth = 0;; ++depth) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray);
        if (!hit) {
            for (int index : scene.infiniteLights)
                L += beta * scene.lights[index].Le(ray, lambda);
            break;
        }
        SurfaceInteraction &si = hit->intr;
        Vector3f wo = -ray.d;
        if (si.areaLightIndex >= 0)
            L += beta * scene.lights[si.areaLightIndex].L(si.p, si.n, si.uv, wo, lambda);
        if (depth == maxDepth)
            break;
        scene.ComputeDifferentials(si, ray);
        // An interface ends the walk, as in pbrt-v4 (its emission has been counted).
        std::optional<BSDF> bsdf = scene.GetBSDF(si, lambda);
        if (!bsdf)
            break;
        Vector3f wi = SampleUniformSphere(sampler.Get2D());
        SampledSpectrum fcos = bsdf->f(wo, wi) * AbsDot(wi, Vector3f(si.shading.n));
        if (!fcos)
            break;
        beta *= fcos / UniformSpherePDF();
        ray = si.SpawnRay(wi);
    }
    return L;
}

}  // namespace pbrt
