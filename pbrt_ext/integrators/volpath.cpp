#include "pbrt_ext/integrators/volpath.h"

#include "pbrt_ext/integrators/transmittance.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"

namespace pbrt {

SampledSpectrum VolPathIntegrator::Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                                      RayCounts &rays, UnguidedMoment *unguided) const {
    PathState path;
    path.ray = ray;
    path.unguided = unguided;
    if (guide && guide->Recording()) {
        thread_local PathGuide::PathRecord vertices;  // one per thread, its storage reused
        vertices.clear();
        path.record = &vertices;
    }
    Trace(path, lambda, sampler, rays);
    if (path.record)
        guide->Commit(*path.record, lambda);
    return path.L;
}

void VolPathIntegrator::Trace(PathState &path, SampledWavelengths &lambda, Sampler &sampler,
                              RayCounts &rays) const {
    while (true) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(path.ray);
        if (path.ray.medium >= 0) {
            MediumOutcome outcome =
                SampleMedium(path, hit ? hit->tHit : Infinity, lambda, sampler, rays);
            if (outcome == MediumOutcome::Terminated)
                return;
            if (outcome == MediumOutcome::Scattered)
                continue;
        }
        if (!hit) {
            for (int index : scene.infiniteLights)
                AddEmitted(path, scene.lights[index].Le(path.ray, lambda), index);
            return;
        }
        SurfaceInteraction &si = hit->intr;
        if (si.areaLightIndex >= 0)
            AddEmitted(path,
                       scene.lights[si.areaLightIndex].L(si.p, si.n, si.uv, -path.ray.d, lambda),
                       si.areaLightIndex);

        scene.ComputeDifferentials(si, path.ray);
        std::optional<BSDF> maybeBSDF = scene.GetBSDF(si, lambda);
        if (!maybeBSDF) {
            // A boundary between media with no surface: continue into the next medium.
            path.ray = si.SpawnRay(path.ray.d);
            continue;
        }
        if (path.depth++ >= options.maxDepth)
            return;
        BSDF &bsdf = *maybeBSDF;
        if (options.regularize && path.anyNonSpecularBounces)
            bsdf.Regularize();

        const std::optional<SDTree::Guide> leaf = LeafAt(path, si.p, 2);
        const PathGuide::VertexGuide vertex = leaf ? PathGuide::AtSurface(si, bsdf, *leaf) : PathGuide::VertexGuide{};
        if (IsNonSpecular(bsdf.Flags()) && !scene.lights.empty())
            path.Add(SampleLdAtSurface(si, bsdf, vertex, lambda, sampler, path, rays));
        path.prevCtx = LightSampleContext(si);

        BSDFSample bs;
        if (!ScatterAtSurface(path, si, bsdf, vertex, sampler, &bs))
            return;
        if (bs.IsTransmission())
            if (std::optional<TabulatedBSSRDF> bssrdf = scene.GetBSSRDF(si, lambda))
                if (!ScatterSubsurface(path, si, *bssrdf, lambda, sampler, rays))
                    return;

        if (!path.beta || !Survives(path, leaf, sampler))
            return;
    }
}

bool VolPathIntegrator::Survives(PathState &path, const std::optional<SDTree::Guide> &leaf, Sampler &sampler) const {
    Float throughput = (path.beta * path.etaScale / MISDenominator(path.r_u)).MaxComponentValue();
    Float uRR = sampler.Get1D(), survival = 1;
    if (throughput < 1 && path.depth > 1) {
        if (leaf) {
            const DTree &learned = leaf->directions;
            Float radiance = PathGuide::LearnedRadiance(learned, GuidePDF(learned, path.ray.d));
            survival = PathGuide::SurvivalProbability(throughput, radiance, path.pixelEstimate);
            if (uRR >= survival)
                return false;
            path.beta /= survival;
        } else {
            Float q = std::max<Float>(0, 1 - throughput);
            if (uRR < q)
                return false;
            path.beta /= 1 - q;
        }
    }
    if (path.unguided && path.depth > 1)
        path.unguided->Survived(std::min<Float>(1, path.unguided->PathThroughput(throughput)), survival);
    return true;
}

std::optional<SDTree::Guide> VolPathIntegrator::LeafAt(PathState &path, Point3f p, Float expectedOverMean) const {
    if (!guide)
        return {};
    SDTree::Guide leaf = guide->LeafAt(p);
    if (path.pixelEstimate < 0)
        path.pixelEstimate = expectedOverMean * leaf.directions.MeanRadiance();
    return leaf;
}

bool VolPathIntegrator::ScatterAtSurface(PathState &path, const SurfaceInteraction &si, const BSDF &bsdf,
                                         const PathGuide::VertexGuide &vertex, Sampler &sampler,
                                         BSDFSample *sample) const {
    const Vector3f wo = si.wo, ns(si.shading.n);
    if (!guide) {
        Float u = sampler.Get1D();
        pstd::optional<BSDFSample> bs = bsdf.Sample_f(wo, u, sampler.Get2D());
        if (!bs)
            return false;
        path.beta *= bs->f * AbsDot(bs->wi, ns) / bs->pdf;
        path.r_l = path.r_u / (bs->pdfIsProportional ? bsdf.PDF(wo, bs->wi) : bs->pdf);
        *sample = *bs;
    } else {
        pstd::optional<PathGuide::Scatter> scatter = PathGuide::SampleBSDF(bsdf, vertex, wo, sampler);
        if (!scatter)
            return false;
        const SampledSpectrum gain = scatter->weight * AbsDot(scatter->wi, ns);
        path.beta *= gain;
        path.Scattered(scatter->pdf, scatter->pdfOwn);
        *sample = scatter->sample;
        if (path.record && !sample->IsSpecular())
            AddRecordedVertex(path, si.p, vertex, *scatter, gain);
    }
    path.specularBounce = sample->IsSpecular();
    path.anyNonSpecularBounces |= !sample->IsSpecular();
    if (sample->IsTransmission())
        path.etaScale *= Sqr(sample->eta);
    path.ray = si.SpawnRay(path.ray, sample->wi, sample->flags, sample->eta);
    return true;
}

bool VolPathIntegrator::ScatterInMedium(PathState &path, const MediumInteraction &mi,
                                        const PathGuide::VertexGuide &vertex, Sampler &sampler) const {
    Vector3f wi;
    if (!guide) {
        std::optional<PhaseFunctionSample> ps = mi.phase.Sample_p(mi.wo, sampler.Get2D());
        if (!ps || ps->pdf == 0)
            return false;
        path.beta *= ps->p / ps->pdf;
        path.r_l = path.r_u / ps->pdf;
        wi = ps->wi;
    } else {
        pstd::optional<PathGuide::Scatter> scatter = PathGuide::SamplePhase(mi.phase, vertex, mi.wo, sampler);
        if (!scatter)
            return false;
        path.beta *= scatter->weight;
        path.Scattered(scatter->pdf, scatter->pdfOwn);
        wi = scatter->wi;
        if (path.record)
            AddRecordedVertex(path, mi.p, vertex, *scatter, scatter->weight);
    }
    path.prevCtx = LightSampleContext(mi.p, Normal3f(), Normal3f());
    path.ray = mi.SpawnRay(wi);
    path.specularBounce = false;
    path.anyNonSpecularBounces = true;
    return true;
}

void VolPathIntegrator::AddRecordedVertex(PathState &path, Point3f p, const PathGuide::VertexGuide &vertex,
                                          const PathGuide::Scatter &scatter, const SampledSpectrum &gain) const {
    // The path's throughput past the vertex: what later contributions are divided by, so that
    // they become the radiance that arrived along wi.
    SampledSpectrum throughput = path.beta / MISDenominator(path.r_u);
    path.record->push_back(PathGuide::Vertex{p, scatter.wi, scatter.pdf, throughput, SampledSpectrum(0.f),
                                             vertex.leaf, scatter.pdfOwn, scatter.pdfGuide, gain});
}

DirectLight VolPathIntegrator::SampleLdAtSurface(const SurfaceInteraction &si, const BSDF &bsdf,
                                                 const PathGuide::VertexGuide &vertex,
                                                 const SampledWavelengths &lambda, Sampler &sampler,
                                                 const PathState &path, RayCounts &rays) const {
    Vector3f ns(si.shading.n);
    auto scatter = [&](Vector3f wi) {
        Float pdfBSDF = bsdf.PDF(si.wo, wi);
        return ScatterToward{bsdf.f(si.wo, wi) * AbsDot(wi, ns), vertex.PDF(pdfBSDF, wi), pdfBSDF};
    };
    auto spawnTo = [&](Point3f pLight) { return si.SpawnRayTo(pLight); };
    return SampleLd(LightSampleContext(si), scatter, spawnTo, lambda, sampler, path.beta, path.r_u,
                    path.unguided != nullptr, rays);
}

bool VolPathIntegrator::ScatterSubsurface(PathState &path, const SurfaceInteraction &si,
                                          const TabulatedBSSRDF &bssrdf, SampledWavelengths &lambda,
                                          Sampler &sampler, RayCounts &rays) const {
    Float uAxis = sampler.Get1D();
    Point2f uDisk = sampler.Get2D();
    std::optional<BSSRDFProbeSegment> probe = bssrdf.SampleSp(uAxis, uDisk);
    if (!probe)
        return false;
    // Every surface of the material along the probe is a candidate exit; one is kept with equal
    // probability by reservoir sampling, its RNG seeded by the sampler as pbrt-v4 seeds it. The
    // walk stops after kMaxProbeHits surfaces, which no closed object comes near.
    constexpr int kMaxProbeHits = 1024;
    RNG rng(Hash(sampler.Get1D()));
    std::optional<SurfaceInteraction> exit;
    int candidates = 0;
    SurfaceInteraction base;
    base.p = probe->p0;
    base.time = path.ray.time;
    for (int i = 0; i < kMaxProbeHits; ++i) {
        Ray r = base.SpawnRayTo(probe->p1);
        if (r.d == Vector3f(0, 0, 0))
            break;
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(r, 1);
        if (!hit)
            break;
        base = hit->intr;
        if (hit->intr.materialIndex == si.materialIndex && rng.Uniform<Float>() * Float(++candidates) < 1)
            exit = hit->intr;
    }
    if (!exit)
        return false;
    SampledSpectrum Sp = bssrdf.Sp(exit->p), pdf = bssrdf.PDF_Sp(exit->p, exit->n);
    if (!Sp || !pdf || !(pdf[0] > 0))
        return false;
    path.beta *= Sp * Float(candidates) / pdf[0];
    path.r_u *= pdf / pdf[0];

    // The exit point's BSDF, seen from its shading normal.
    SurfaceInteraction &pi = *exit;
    pi.wo = Vector3f(pi.shading.n);
    BSDF Sw(pi.shading.n, pi.shading.dpdu, NormalizedFresnelBxDF(bssrdf.Eta()));
    path.anyNonSpecularBounces = true;
    path.prevCtx = LightSampleContext(pi);
    if (!scene.lights.empty())
        path.Add(SampleLdAtSurface(pi, Sw, PathGuide::VertexGuide{}, lambda, sampler, path, rays));
    Float u = sampler.Get1D();
    pstd::optional<BSDFSample> bs = Sw.Sample_f(pi.wo, u, sampler.Get2D());
    if (!bs)
        return false;
    path.beta *= bs->f * AbsDot(bs->wi, Vector3f(pi.shading.n)) / bs->pdf;
    path.Scattered(bs->pdf, bs->pdf);  // the exit is not guided
    path.specularBounce = false;
    path.ray = pi.SpawnRay(path.ray, bs->wi, bs->flags, bs->eta);
    return true;
}

VolPathIntegrator::MediumOutcome VolPathIntegrator::SampleMedium(PathState &path, Float tMax,
                                                                 SampledWavelengths &lambda,
                                                                 Sampler &sampler,
                                                                 RayCounts &rays) const {
    bool scattered = false, terminated = false;
    // The collision distances after the first come from an RNG seeded by the sampler, as in
    // pbrt-v4, so that the sampler's dimensions do not depend on the number of collisions.
    uint64_t hash0 = Hash(sampler.Get1D()), hash1 = Hash(sampler.Get1D());
    RNG rng(hash0, hash1);
    const Ray ray = path.ray;
    const Medium &medium = scene.media[ray.medium];
    SampledSpectrum T_majEnd = medium.SampleT_maj(
        ray, tMax, sampler.Get1D(), rng, lambda,
        [&](Point3f p, const MediumProperties &mp, SampledSpectrum sigma_maj,
            SampledSpectrum T_maj) {
            if (!path.beta) {
                terminated = true;
                return false;
            }
            if (path.depth < options.maxDepth && mp.Le) {
                // Emission, estimated at every tentative collision.
                Float pdf = sigma_maj[0] * T_maj[0];
                SampledSpectrum betap = path.beta * T_maj / pdf;
                SampledSpectrum r_e = path.r_u * sigma_maj * T_maj / pdf;
                if (r_e)
                    path.Add(betap * mp.sigma_a * mp.Le / MISDenominator(r_e));
            }
            Float pAbsorb = mp.sigma_a[0] / sigma_maj[0];
            Float pScatter = mp.sigma_s[0] / sigma_maj[0];
            Float pNull = std::max<Float>(0, 1 - pAbsorb - pScatter);
            // The three probabilities sum to 1 unless sigma_t exceeds the majorant by rounding.
            Float um = rng.Uniform<Float>() * (pAbsorb + pScatter + pNull);
            int mode = um < pAbsorb ? 0 : um < pAbsorb + pScatter ? 1 : 2;
            if (mode == 0) {
                terminated = true;
                return false;
            }
            if (mode == 1) {
                if (path.depth++ >= options.maxDepth) {
                    terminated = true;
                    return false;
                }
                Float pdf = T_maj[0] * mp.sigma_s[0];
                path.beta *= T_maj * mp.sigma_s / pdf;
                path.r_u *= T_maj * mp.sigma_s / pdf;
                if (!path.beta || !path.r_u)
                    return false;
                MediumInteraction mi{p, -ray.d / Length(ray.d), ray.medium, mp.phase, ray.time};
                const std::optional<SDTree::Guide> leaf = LeafAt(path, p, 1);
                const PathGuide::VertexGuide vertex = leaf ? PathGuide::InMedium(*leaf) : PathGuide::VertexGuide{};
                if (!scene.lights.empty()) {
                    auto scatter = [&](Vector3f wi) {
                        Float ph = mi.phase.p(mi.wo, wi);
                        return ScatterToward{SampledSpectrum(ph), vertex.PDF(ph, wi), ph};
                    };
                    auto spawnTo = [&](Point3f pLight) { return mi.SpawnRayTo(pLight); };
                    path.Add(SampleLd(LightSampleContext(p, Normal3f(), Normal3f()), scatter, spawnTo, lambda,
                                      sampler, path.beta, path.r_u, path.unguided != nullptr, rays));
                }
                scattered = ScatterInMedium(path, mi, vertex, sampler);
                terminated = !scattered;
                return false;
            }
            SampledSpectrum sigma_n = ClampZero(sigma_maj - mp.sigma_a - mp.sigma_s);
            Float pdf = T_maj[0] * sigma_n[0];
            path.beta = pdf == 0 ? SampledSpectrum(0.f) : path.beta * T_maj * sigma_n / pdf;
            path.r_u *= T_maj * sigma_n / pdf;
            path.ScaleLightProbability(T_maj * sigma_maj / pdf);
            return bool(path.beta) && bool(path.r_u);
        });
    if (terminated || !path.beta || !path.r_u)
        return MediumOutcome::Terminated;
    if (scattered)
        return MediumOutcome::Scattered;
    // Past the last collision: the majorant transmittance over its own probability.
    SampledSpectrum tailRelativeToHero = T_majEnd / T_majEnd[0];
    path.beta *= tailRelativeToHero;
    path.r_u *= tailRelativeToHero;
    path.ScaleLightProbability(tailRelativeToHero);
    return MediumOutcome::PassedThrough;
}

void VolPathIntegrator::AddEmitted(PathState &path, SampledSpectrum Le, int lightIndex) const {
    if (!Le)
        return;
    if (path.depth == 0 || path.specularBounce) {
        path.Add(path.beta * Le / MISDenominator(path.r_u));
        return;
    }
    const Light &light = scene.lights[lightIndex];
    Float p_l = scene.lightSampler.PMF(path.prevCtx, lightIndex) *
                light.PDF_Li(path.prevCtx, path.ray.d, true);
    const SampledSpectrum contribution = path.beta * Le / MISDenominator(path.r_u + path.r_l * p_l);
    if (!path.unguided) {
        path.Add(contribution);
        return;
    }
    path.Add(contribution, path.beta * Le / MISDenominator(path.r_u + path.r_lPath * p_l));
}

template <typename Scatter, typename SpawnTo>
DirectLight VolPathIntegrator::SampleLd(const LightSampleContext &ctx, Scatter scatter, SpawnTo spawnTo,
                                        const SampledWavelengths &lambda, Sampler &sampler, SampledSpectrum beta,
                                        SampledSpectrum r_p, bool pathWeighted, RayCounts &rays) const {
    Float u = sampler.Get1D();
    pstd::optional<SampledLight> sampled = scene.lightSampler.Sample(ctx, u);
    Point2f uLight = sampler.Get2D();
    if (!sampled)
        return {};
    const Light &light = scene.lights[sampled->lightIndex];
    pstd::optional<LightLiSample> ls = light.SampleLi(ctx, uLight, lambda, true);
    if (!ls || !ls->L || !(ls->pdf > 0))
        return {};
    Float p_l = sampled->p * ls->pdf;
    const ScatterToward s = scatter(ls->wi);
    if (!s.f)
        return {};
    SampledSpectrum r_l(1.f), r_u(1.f);
    SampledSpectrum T_ray = Transmittance(spawnTo(ls->pLight), ls->pLight, lambda, &r_l, &r_u, rays);
    if (!T_ray)
        return {};
    const SampledSpectrum r_uTransmitted = r_u;
    r_l *= r_p * p_l;
    r_u *= r_p * s.pdf;
    bool delta = light.Type() == LightType::DeltaPosition ||
                 light.Type() == LightType::DeltaDirection;
    // A delta light's direction has no density for the tree to learn from. The record is the
    // radiance over the light's density, weighted by the balance heuristic.
    if (guide && guide->Recording() && !delta)
        guide->RecordAt(ctx.p, ls->wi,
                        Luminance(T_ray * ls->L, lambda) * MISDenominator(r_p) / MISDenominator(r_l + r_u));
    const SampledSpectrum unweighted = beta * s.f * T_ray * ls->L;
    DirectLight d{unweighted / MISDenominator(delta ? r_l : r_l + r_u), SampledSpectrum(0.f)};
    if (pathWeighted)
        d.LdPath = unweighted / MISDenominator(delta ? r_l : r_l + r_uTransmitted * (r_p * s.pdfOwn));
    return d;
}

SampledSpectrum VolPathIntegrator::Transmittance(Ray ray, Point3f pLight,
                                                 const SampledWavelengths &lambda,
                                                 SampledSpectrum *r_l, SampledSpectrum *r_u,
                                                 RayCounts &rays) const {
    SampledSpectrum T_ray(1.f);
    RNG rng(Hash(ray.o), Hash(ray.d));
    bool reached = WalkToTarget(scene, ray, pLight, rays, [&](const Ray &r, Float tMax) {
        const Medium &medium = scene.media[r.medium];
        // Ratio tracking's expectation where it has one: it would survive with probability
        // T[0] and then weigh by T / T[0], which the MIS densities keep, so that they stay
        // those of the unidirectional paths through the same stretch.
        if (std::optional<SampledSpectrum> T = medium.ClosedFormTransmittance(r, tMax, lambda)) {
            if (!((*T)[0] > 0))
                return false;
            T_ray *= *T;
            SampledSpectrum relativeToHero = *T / (*T)[0];
            *r_l *= relativeToHero;
            *r_u *= relativeToHero;
            return bool(T_ray);
        }
        SampledSpectrum T_majEnd = medium.SampleT_maj(
            r, tMax, rng.Uniform<Float>(), rng, lambda,
            [&](Point3f, const MediumProperties &mp, SampledSpectrum sigma_maj, SampledSpectrum T_maj) {
                // Ratio tracking: every collision multiplies by the null fraction.
                RatioTrackingStep step = RatioTracking(mp, sigma_maj, T_maj);
                T_ray *= step.nullRatio;
                *r_l *= step.majorantRatio;
                *r_u *= step.nullRatio;
                // Russian roulette once the estimate is small (pbrt-v4's 0.05 and 0.75).
                SampledSpectrum Tr = T_ray / MISDenominator(*r_l + *r_u);
                if (Tr.MaxComponentValue() < 0.05f) {
                    if (rng.Uniform<Float>() < 0.75f)
                        T_ray = SampledSpectrum(0.f);
                    else
                        T_ray /= 0.25f;
                }
                return bool(T_ray);
            },
            MediumQuery::NoEmission);
        SampledSpectrum tailRelativeToHero = T_majEnd / T_majEnd[0];
        T_ray *= tailRelativeToHero;
        *r_l *= tailRelativeToHero;
        *r_u *= tailRelativeToHero;
        return bool(T_ray);
    });
    return reached ? T_ray : SampledSpectrum(0.f);
}

}  // namespace pbrt
