#include "pbrt_ext/integrators/path.h"

#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/sampling.h"

#include <stdexcept>

namespace pbrt {

PathIntegrator::PathIntegrator(const Scene &scene, IntegratorOptions options)
    : scene(scene), options(options) {
    if (options.strategy != PathStrategy::MIS && scene.lightSampler.NeedsIncompletePDFs())
        throw std::invalid_argument("the " + ToString(options.strategy) +
                                    " strategy needs a scene built for it: its light sampler "
                                    "leaves the uniform sky to MIS's BSDF sampling");
}

Float PathIntegrator::BSDFHitWeight(bool lightSamplingApplied, BSDFDensity &pdfBSDF,
                                    Float pdfLight) const {
    if (!lightSamplingApplied)
        return 1;  // seen directly or through a specular bounce: no other estimator covers it
    switch (options.strategy) {
    case PathStrategy::MIS:
        return PowerHeuristic(1, pdfBSDF.Get(), 1, pdfLight);
    case PathStrategy::BSDF:
        return 1;
    case PathStrategy::Light:
        return 0;
    }
    return 0;
}

SampledSpectrum PathIntegrator::Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                                   RayCounts &rays) const {
    SampledSpectrum L(0.f), beta(1.f);
    // Whether next-event estimation covered the vertex the ray leaves from; false at the camera and
    // after specular bounces, where only the path itself can find the emitters.
    bool lightSampled = false, anyNonSpecularBounces = false;
    Float etaScale = 1;
    BSDFDensity pdfBSDF;
    LightSampleContext prevCtx;
    for (int depth = 0;; ++depth) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray);
        if (!hit) {
            // Only infinite lights are seen by escaping rays; with none, nothing is looked up.
            for (int index : scene.infiniteLights) {
                const Light &light = scene.lights[index];
                SampledSpectrum Le = light.Le(ray, lambda);
                if (!Le)
                    continue;
                Float pdfLight = lightSampled ? scene.lightSampler.PMF(prevCtx, index) *
                                                    light.PDF_Li(prevCtx, ray.d, AllowIncompletePDF())
                                              : 0;
                L += beta * Le * BSDFHitWeight(lightSampled, pdfBSDF, pdfLight);
            }
            break;
        }
        SurfaceInteraction &si = hit->intr;
        if (si.areaLightIndex >= 0) {
            const Light &light = scene.lights[si.areaLightIndex];
            SampledSpectrum Le = light.L(si.p, si.n, si.uv, -ray.d, lambda);
            if (Le) {
                Float pdfLight = lightSampled ? scene.lightSampler.PMF(prevCtx, si.areaLightIndex) *
                                                    light.PDF_Li(prevCtx, ray.d, AllowIncompletePDF())
                                              : 0;
                L += beta * Le * BSDFHitWeight(lightSampled, pdfBSDF, pdfLight);
            }
        }
        scene.ComputeDifferentials(si, ray);
        std::optional<BSDF> maybeBSDF = scene.GetBSDF(si, lambda);
        if (!maybeBSDF) {
            // An interface between media, which this integrator ignores (as pbrt-v4's path
            // does): continue straight through. Shadow rays stop at it, so only this path can
            // reach what lies behind: the next emitter counts in full, as after a specular
            // bounce.
            ray = si.SpawnRay(ray.d);
            lightSampled = false;
            --depth;
            continue;
        }
        if (depth == options.maxDepth)
            break;
        BSDF &bsdf = *maybeBSDF;
        if (options.regularize && anyNonSpecularBounces)
            bsdf.Regularize();

        BxDFFlags flags = bsdf.Flags();
        lightSampled = IsNonSpecular(flags) && options.strategy != PathStrategy::BSDF &&
                       !scene.lights.empty();
        if (lightSampled)
            L += beta * SampleLd(si, bsdf, lambda, sampler, rays);

        Vector3f wo = -ray.d;
        Float u = sampler.Get1D();
        pstd::optional<BSDFSample> bs = bsdf.Sample_f(wo, u, sampler.Get2D());
        if (!bs)
            break;
        beta *= bs->f * AbsDot(bs->wi, Vector3f(si.shading.n)) / bs->pdf;
        if (bs->pdfIsProportional)
            pdfBSDF.Defer(bsdf, wo, bs->wi);
        else
            pdfBSDF.Set(bs->pdf);
        anyNonSpecularBounces |= !bs->IsSpecular();
        if (bs->IsTransmission())
            etaScale *= Sqr(bs->eta);
        prevCtx = LightSampleContext(si);
        ray = si.SpawnRay(ray, bs->wi, bs->flags, bs->eta);

        // Russian roulette on the throughput without the radiance scaling of refraction.
        SampledSpectrum rrBeta = beta * etaScale;
        if (rrBeta.MaxComponentValue() < 1 && depth > 1) {
            Float q = std::max<Float>(0, 1 - rrBeta.MaxComponentValue());
            if (sampler.Get1D() < q)
                break;
            beta /= 1 - q;
        }
    }
    return L;
}

SampledSpectrum PathIntegrator::SampleLd(const SurfaceInteraction &si, const BSDF &bsdf,
                                         const SampledWavelengths &lambda, Sampler &sampler,
                                         RayCounts &rays) const {
    LightSampleContext ctx(si);
    Float uLight = sampler.Get1D();
    Point2f u = sampler.Get2D();
    pstd::optional<SampledLight> sampled = scene.lightSampler.Sample(ctx, uLight);
    if (!sampled)
        return {};
    const Light &light = scene.lights[sampled->lightIndex];
    pstd::optional<LightLiSample> ls = light.SampleLi(ctx, u, lambda, AllowIncompletePDF());
    if (!ls || !ls->L || !(ls->pdf > 0))
        return {};
    Vector3f wo = si.wo, wi = ls->wi;
    SampledSpectrum f = bsdf.f(wo, wi) * AbsDot(wi, Vector3f(si.shading.n));
    if (!f)
        return {};
    ++rays.shadow;
    if (scene.IntersectP(si.SpawnRayTo(ls->pLight), 1 - ShadowEpsilon()))
        return {};
    Float pdfLight = sampled->p * ls->pdf;
    bool delta = light.Type() == LightType::DeltaPosition ||
                 light.Type() == LightType::DeltaDirection;
    Float weight = delta || options.strategy == PathStrategy::Light
                       ? 1
                       : PowerHeuristic(1, pdfLight, 1, bsdf.PDF(wo, wi));
    return weight * ls->L * f / pdfLight;
}

}  // namespace pbrt
