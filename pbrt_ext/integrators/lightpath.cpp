#include "pbrt_ext/integrators/lightpath.h"

#include "pbrt_ext/scene.h"

namespace pbrt {

LightPathIntegrator::LightPathIntegrator(Scene &scene, IntegratorOptions options)
    : scene(scene), film(scene.film), options(options), camera(scene.camera, scene.film),
      lightSampler(scene.lights) {
    Point2i res = film.FullResolution();
    cropScale = Float(res.x) * Float(res.y) / Float(film.PixelBounds().Area());
    film.EnableSplats();
}

bool LightPathIntegrator::Unoccluded(const Ray &ray, RayCounts &rays) const {
    ++rays.shadow;
    return !scene.IntersectP(ray, 1 - ShadowEpsilon());
}

SampledSpectrum LightPathIntegrator::Li(RayDifferential ray, Point2f, SampledWavelengths &lambda,
                                        Sampler &sampler, RayCounts &rays) const {
    pstd::optional<SampledLight> sampled = lightSampler.Sample(sampler.Get1D());
    if (!sampled)
        return SampledSpectrum(0.f);
    const Light &light = scene.lights[sampled->lightIndex];
    Point2f ul0 = sampler.Get2D(), ul1 = sampler.Get2D();
    pstd::optional<LightLeSample> les = light.SampleLe(ul0, ul1, lambda, ray.time);
    if (!les || les->pdfPos == 0 || les->pdfDir == 0 || !les->L)
        return SampledSpectrum(0.f);
    Float p_l = sampled->p * les->pdfPos;

    // The emitting point itself, seen through the lens: its radiance toward the lens times the
    // importance there, over the densities of the light point and of the lens point.
    Point2f uLens = sampler.Get2D();
    if (les->OnSurface()) {
        Point3f pLight = les->ray.o;
        if (pstd::optional<CameraWiSample> cs = camera.SampleWi(pLight, ray.time, uLens)) {
            SampledSpectrum Le = light.L(pLight, les->n, les->uv, cs->wi, lambda);
            if (Le && Unoccluded(Ray(pLight, cs->pLens - pLight, -1, ray.time), rays))
                film.AddSplat(cs->pRaster, cropScale * Le * AbsDot(cs->wi, les->n) * cs->Wi / (p_l * cs->pdf),
                              lambda);
        }
    }

    SampledSpectrum beta = les->L * les->AbsCosTheta(les->ray.d) / (p_l * les->pdfDir);
    RayDifferential path(les->ray);
    for (int depth = 0; depth < options.maxDepth && beta;) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(path);
        if (!hit)
            break;
        SurfaceInteraction &si = hit->intr;
        scene.ComputeDifferentials(si, path);
        std::optional<BSDF> bsdf = scene.GetBSDF(si, lambda);
        if (!bsdf) {
            path = RayDifferential(si.SpawnRay(path.d));  // an interface: media are ignored
            continue;
        }
        if (IsNonSpecular(bsdf->Flags()))
            ConnectToCamera(si, *bsdf, beta, lambda, sampler, rays);
        ++depth;
        Float u = sampler.Get1D();
        pstd::optional<BSDFSample> bs = bsdf->Sample_f(si.wo, u, sampler.Get2D(), TransportMode::Importance);
        if (!bs)
            break;
        beta *= bs->f * AbsDot(bs->wi, Vector3f(si.shading.n)) / bs->pdf;
        path = si.SpawnRay(path, bs->wi, bs->flags, bs->eta);
    }
    return SampledSpectrum(0.f);
}

void LightPathIntegrator::ConnectToCamera(const SurfaceInteraction &si, const BSDF &bsdf,
                                          SampledSpectrum beta, const SampledWavelengths &lambda,
                                          Sampler &sampler, RayCounts &rays) const {
    pstd::optional<CameraWiSample> cs = camera.SampleWi(si.p, si.time, sampler.Get2D());
    if (!cs)
        return;
    film.PrefetchSplat(cs->pRaster);
    SampledSpectrum L = beta * bsdf.f(si.wo, cs->wi, TransportMode::Importance) *
                        AbsDot(cs->wi, Vector3f(si.shading.n)) * cs->Wi / cs->pdf;
    if (L && Unoccluded(si.SpawnRayTo(cs->pLens), rays))
        film.AddSplat(cs->pRaster, cropScale * L, lambda);
}

}  // namespace pbrt
