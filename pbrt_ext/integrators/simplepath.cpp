#include "pbrt_ext/integrators/simplepath.h"

#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/sampling.h"

namespace pbrt {

SimplePathIntegrator::SimplePathIntegrator(const Scene &scene, const IntegratorOptions &options)
    : scene(scene),
      maxDepth(options.maxDepth),
      sampleLights(options.simplePath.sampleLights),
      sampleBSDF(options.simplePath.sampleBSDF),
      lightSampler(scene.lights) {}

SampledSpectrum SimplePathIntegrator::Li(RayDifferential ray, SampledWavelengths &lambda,
                                         Sampler &sampler, RayCounts &rays) const {
    SampledSpectrum L(0.f), beta(1.f);
    // Whether emission the path reaches counts: always without light sampling, else only where
    // light sampling could not have found it (seen directly or through a specular bounce).
    bool specularBounce = true;
    for (int depth = 0; beta; ) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray);
        if (!hit) {
            if (!sampleLights || specularBounce)
                for (int index : scene.infiniteLights)
                    L += beta * scene.lights[index].Le(ray, lambda);
            break;
        }
        SurfaceInteraction &si = hit->intr;
        if ((!sampleLights || specularBounce) && si.areaLightIndex >= 0)
            L += beta * scene.lights[si.areaLightIndex].L(si.p, si.n, si.uv, -ray.d, lambda);
        // As pbrt-v4, a media interface counts toward the depth here (it does not in path).
        if (depth++ == maxDepth)
            break;
        scene.ComputeDifferentials(si, ray);
        std::optional<BSDF> bsdf = scene.GetBSDF(si, lambda);
        if (!bsdf) {
            specularBounce = true;
            ray = si.SpawnRay(ray.d);
            continue;
        }
        Vector3f wo = -ray.d;
        if (sampleLights)
            L += beta * SampleLd(si, *bsdf, lambda, sampler, rays);
        pstd::optional<BSDFSample> bs = SampleDirection(si, *bsdf, wo, sampler);
        if (!bs)
            break;
        beta *= bs->f * AbsDot(bs->wi, Vector3f(si.shading.n)) / bs->pdf;
        specularBounce = bs->IsSpecular();
        ray = si.SpawnRay(bs->wi);
    }
    return L;
}

SampledSpectrum SimplePathIntegrator::SampleLd(const SurfaceInteraction &si, const BSDF &bsdf,
                                               const SampledWavelengths &lambda, Sampler &sampler,
                                               RayCounts &rays) const {
    pstd::optional<SampledLight> sampled = lightSampler.Sample(sampler.Get1D());
    Point2f u = sampler.Get2D();
    if (!sampled)
        return {};
    pstd::optional<LightLiSample> ls =
        scene.lights[sampled->lightIndex].SampleLi(LightSampleContext(si), u, lambda, false);
    if (!ls || !ls->L || !(ls->pdf > 0))
        return {};
    SampledSpectrum f = bsdf.f(si.wo, ls->wi) * AbsDot(ls->wi, Vector3f(si.shading.n));
    if (!f)
        return {};
    ++rays.shadow;
    if (scene.IntersectP(si.SpawnRayTo(ls->pLight), 1 - ShadowEpsilon()))
        return {};
    return f * ls->L / (sampled->p * ls->pdf);
}

pstd::optional<BSDFSample> SimplePathIntegrator::SampleDirection(const SurfaceInteraction &si,
                                                                 const BSDF &bsdf, Vector3f wo,
                                                                 Sampler &sampler) const {
    if (!sampleBSDF)
        return SampleUniform(si, bsdf, wo, sampler.Get2D());
    Float u = sampler.Get1D();
    return bsdf.Sample_f(wo, u, sampler.Get2D());
}

pstd::optional<BSDFSample> SimplePathIntegrator::SampleUniform(const SurfaceInteraction &si,
                                                               const BSDF &bsdf, Vector3f wo,
                                                               Point2f u) const {
    BxDFFlags flags = bsdf.Flags();
    Vector3f wi;
    Float pdf;
    if (IsReflective(flags) && IsTransmissive(flags)) {
        wi = SampleUniformSphere(u);
        pdf = UniformSpherePDF();
    } else {
        // The hemisphere on the side the BSDF scatters to: wo's for reflection, the other for
        // transmission.
        wi = SampleUniformHemisphere(u);
        pdf = UniformHemispherePDF();
        Vector3f n(si.n);
        bool sameSide = Dot(wo, n) * Dot(wi, n) > 0;
        if ((IsReflective(flags) && !sameSide) || (IsTransmissive(flags) && sameSide))
            wi = -wi;
    }
    SampledSpectrum f = bsdf.f(wo, wi);
    if (!f)
        return {};
    return BSDFSample(f, wi, pdf, IsReflective(flags) && !IsTransmissive(flags)
                                      ? BxDFFlags::DiffuseReflection
                                      : BxDFFlags::DiffuseTransmission);
}

}  // namespace pbrt
