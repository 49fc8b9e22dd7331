#include "pbrt_ext/integrators/ambientocclusion.h"

#include "pbrt_ext/scene.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/sampling.h"

namespace pbrt {

AOIntegrator::AOIntegrator(const Scene &scene, const IntegratorOptions &options)
    : scene(scene),
      cosSample(options.ambientOcclusion.cosSample),
      maxDistance(options.ambientOcclusion.maxDistance),
      illuminant(Spectrum::DenselySampled(scene.film.ColorSpace().illuminant)),
      illuminantScale(1 / SpectrumToPhotometric(illuminant)) {}

SampledSpectrum AOIntegrator::Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                                 RayCounts &rays) const {
    pstd::optional<ShapeIntersection> hit;
    for (;;) {
        ++rays.closest;
        if (!(hit = scene.Intersect(ray)))
            return SampledSpectrum(0.f);
        // A surface with a material; its BSDF is not needed.
        if (scene.ResolveMaterial(hit->intr) >= 0)
            break;
        ray = hit->intr.SpawnRay(ray.d);  // an interface: look past it
    }
    const SurfaceInteraction &si = hit->intr;
    // The geometric normal's frame, not the shading one, as pbrt-v4.
    Normal3f n = FaceForward(si.n, -ray.d);
    Point2f u = sampler.Get2D();
    Vector3f wi = cosSample ? SampleCosineHemisphere(u) : SampleUniformHemisphere(u);
    Float pdf = cosSample ? CosineHemispherePDF(std::abs(wi.z)) : UniformHemispherePDF();
    if (pdf == 0)
        return SampledSpectrum(0.f);
    wi = Frame::FromZ(n).FromLocal(wi);
    ++rays.shadow;
    if (scene.IntersectP(si.SpawnRay(wi), maxDistance))
        return SampledSpectrum(0.f);
    // Divided by pi, so that a fully open hemisphere gives the illuminant itself.
    return illuminantScale * illuminant.Sample(lambda) * Dot(wi, Vector3f(n)) / (Pi * pdf);
}

}  // namespace pbrt
