#include "pbrt_ext/integrators/guidedpath.h"

#include "pbrt_ext/scene.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/sampling.h"

namespace pbrt {

GuidedPathIntegrator::GuidedPathIntegrator(const Scene &scene, const IntegratorOptions &options,
                                           SDTree &tree, bool record)
    : scene(scene), options(options), guide(tree, record) {}

DirectLight GuidedPathIntegrator::SampleLd(const SurfaceInteraction &si, const BSDF &bsdf, const VertexGuide &vertex,
                                           const SampledWavelengths &lambda, Sampler &sampler, RayCounts &rays,
                                           bool pathWeighted) const {
    LightSampleContext ctx(si);
    Float uLight = sampler.Get1D();
    Point2f u = sampler.Get2D();
    pstd::optional<SampledLight> sampled = scene.lightSampler.Sample(ctx, uLight);
    if (!sampled)
        return {};
    const Light &light = scene.lights[sampled->lightIndex];
    pstd::optional<LightLiSample> ls = light.SampleLi(ctx, u, lambda, true);
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
    bool delta = light.Type() == LightType::DeltaPosition || light.Type() == LightType::DeltaDirection;
    Float pdfBSDF = delta ? 0 : bsdf.PDF(wo, wi);
    Float weight = delta ? 1 : PowerHeuristic(1, pdfLight, 1, vertex.PDF(pdfBSDF, wi));
    // A delta light's direction has no density for the tree to learn from.
    if (guide.Recording() && !delta)
        guide.RecordAt(si.p, wi, Luminance(ls->L * weight, lambda) / pdfLight);
    DirectLight d{weight * ls->L * f / pdfLight, SampledSpectrum(0.f)};
    if (pathWeighted)
        d.LdPath = (delta ? 1 : PowerHeuristic(1, pdfLight, 1, pdfBSDF)) * ls->L * f / pdfLight;
    return d;
}

bool GuidedPathIntegrator::Survives(SampledSpectrum &beta, Float etaScale, int depth, const DTree &learned,
                                    const VertexGuide &vertex, const PathGuide::Scatter &scatter,
                                    Float pixelEstimate, Sampler &sampler, UnguidedMoment *unguided) const {
    if (depth <= 1)
        return true;
    Float throughput = (beta * etaScale).MaxComponentValue(), survival = 1;
    if (throughput < 1) {
        // DTree::Radiance of the direction, from the density already known where guided.
        Float pdfLearned = vertex.directions ? scatter.pdfGuide : GuidePDF(learned, scatter.wi);
        Float radiance = PathGuide::LearnedRadiance(learned, pdfLearned);
        survival = PathGuide::SurvivalProbability(throughput, radiance, pixelEstimate);
        if (sampler.Get1D() >= survival)
            return false;
        beta /= survival;
    }
    if (unguided)
        unguided->Survived(std::min<Float>(1, unguided->PathThroughput(throughput)), survival);
    return true;
}

SampledSpectrum GuidedPathIntegrator::Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                                         RayCounts &rays, UnguidedMoment *unguided) const {
    SampledSpectrum L(0.f), beta(1.f);
    // As in PathIntegrator::Li: whether next-event estimation covered the vertex the ray leaves.
    bool lightSampled = false, anyNonSpecularBounces = false;
    // pdfScatter: the mixture's density of the last direction; pdfScatterBSDF: the BSDF's.
    Float etaScale = 1, pdfScatter = 1, pdfScatterBSDF = 1, pixelEstimate = 0;
    LightSampleContext prevCtx;
    const bool record = guide.Recording();
    thread_local PathGuide::PathRecord vertices;
    vertices.clear();
    auto add = [&](const SampledSpectrum &contribution) {
        L += contribution;
        if (record)
            PathGuide::Arrived(vertices, contribution);
    };
    // An emitter's radiance, found by the ray: weighted against next-event estimation by the
    // mixture's density, and for the unguided moment by the BSDF's.
    auto emitted = [&](const SampledSpectrum &Le, const Light &light, int index, Vector3f w) {
        if (!lightSampled) {
            add(beta * Le);
            if (unguided)
                unguided->Add(beta * Le);
            return;
        }
        Float pdfLight = scene.lightSampler.PMF(prevCtx, index) * light.PDF_Li(prevCtx, w, true);
        add(beta * Le * PowerHeuristic(1, pdfScatter, 1, pdfLight));
        if (unguided)
            unguided->Add(beta * Le * PowerHeuristic(1, pdfScatterBSDF, 1, pdfLight));
    };
    for (int depth = 0;; ++depth) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(ray);
        if (!hit) {
            for (int index : scene.infiniteLights) {
                const Light &light = scene.lights[index];
                if (SampledSpectrum Le = light.Le(ray, lambda))
                    emitted(Le, light, index, ray.d);
            }
            break;
        }
        SurfaceInteraction &si = hit->intr;
        if (si.areaLightIndex >= 0) {
            const Light &light = scene.lights[si.areaLightIndex];
            if (SampledSpectrum Le = light.L(si.p, si.n, si.uv, -ray.d, lambda))
                emitted(Le, light, si.areaLightIndex, ray.d);
        }
        scene.ComputeDifferentials(si, ray);
        std::optional<BSDF> maybeBSDF = scene.GetBSDF(si, lambda);
        if (!maybeBSDF) {
            // An interface between media, ignored as the path tracer ignores it.
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
        const SDTree::Guide leaf = guide.LeafAt(si.p);
        const DTree &learned = leaf.directions;
        const VertexGuide vertex = PathGuide::AtSurface(si, bsdf, leaf);
        lightSampled = IsNonSpecular(bsdf.Flags()) && !scene.lights.empty();
        if (lightSampled) {
            const DirectLight d = SampleLd(si, bsdf, vertex, lambda, sampler, rays, unguided != nullptr);
            add(beta * d.Ld);
            if (unguided)
                unguided->Add(beta * d.LdPath);
        }
        pstd::optional<PathGuide::Scatter> scatter = PathGuide::SampleBSDF(bsdf, vertex, -ray.d, sampler);
        if (!scatter)
            break;
        const SampledSpectrum gain = scatter->weight * AbsDot(scatter->wi, Vector3f(si.shading.n));
        beta *= gain;
        pdfScatter = scatter->pdf;
        pdfScatterBSDF = scatter->pdfOwn;
        if (unguided)
            unguided->Scattered(scatter->pdfOwn, scatter->pdf);
        bool specular = scatter->sample.IsSpecular();
        anyNonSpecularBounces |= !specular;
        if (scatter->sample.IsTransmission())
            etaScale *= Sqr(scatter->sample.eta);
        if (record && !specular)
            vertices.push_back(PathGuide::Vertex{si.p, scatter->wi, pdfScatter, beta, SampledSpectrum(0.f),
                                                 vertex.leaf, scatter->pdfOwn, scatter->pdfGuide, gain});
        prevCtx = LightSampleContext(si);
        ray = si.SpawnRay(ray, scatter->wi, scatter->sample.flags, scatter->sample.eta);
        if (depth == 0)
            pixelEstimate = 2 * learned.MeanRadiance();  // over the hemisphere: twice the sphere's mean
        if (!Survives(beta, etaScale, depth, learned, vertex, *scatter, pixelEstimate, sampler, unguided))
            break;
    }
    if (record)
        guide.Commit(vertices, lambda);
    return L;
}

}  // namespace pbrt
