// The volumetric path tracer (pbrt-v4's VolPathIntegrator; the book's section 14.2).
//
// Media are sampled by delta tracking against each medium's majorant: at every tentative
// collision the path absorbs, scatters or passes on (null scattering) in proportion to
// sigma_a, sigma_s and sigma_maj - sigma_t at the hero wavelength. Shadow rays cross media and
// interfaces by ratio tracking. Every estimate carries rescaled path probabilities r_u
// (unidirectional) and r_l (light sampling) per wavelength, so that the final division by
// their average is spectral MIS over the wavelengths (chromatic media stay free of colour
// noise) and, at emitters, the balance heuristic between BSDF or phase sampling and light
// sampling, as pbrt-v4 combines them. Under a subsurface material's boundary, light leaves
// through the BSSRDF's exit points, as pbrt-v4's volpath (and only it) renders them.
//
// With a guide it is guidedvolpath: surface and medium vertices sample their direction from the
// mixture of BSDF or phase function and the learned distribution (pathguide.h), whose density the
// rescaled probabilities carry, Russian roulette follows the radiance learned along the path
// (PathGuide::SurvivalProbability), and paths record what arrived while training (a subsurface
// exit is not guided, and only its next-event estimation records). Without one, it is pbrt-v4's
// volpath, sample for sample. Given an UnguidedMoment, a guided Li also estimates the second
// moment of volpath's estimate (unguidedmoment.h), for guiding's trial: each contribution is also
// weighted by the light-sampling probability volpath would carry (r_l over the BSDF's or phase
// function's density, not the mixture's), and the importance ratio follows the scatters and
// roulettes; medium sampling, spectral MIS and subsurface exits are the same in both.
#pragma once

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/integrators/pathguide.h"
#include "pbrt_ext/integrators/unguidedmoment.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/materials/bsdf.h"
#include "pbrt_ext/materials/bssrdf.h"
#include "pbrt_ext/media/media.h"
#include "pbrt_ext/samplers/samplers.h"

namespace pbrt {

class Scene;

class VolPathIntegrator {
  public:
    // options.strategy must be MIS (volpath combines its estimators only that way).
    VolPathIntegrator(const Scene &scene, IntegratorOptions options, std::optional<PathGuide> guide = {})
        : scene(scene), options(options), guide(guide) {}

    // unguided: only with a guide.
    SampledSpectrum Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                       RayCounts &rays, UnguidedMoment *unguided = nullptr) const;
    bool Guided() const { return guide.has_value(); }

  private:
    // What a path carries from vertex to vertex.
    struct PathState {
        RayDifferential ray;
        SampledSpectrum L{0.f}, beta{1.f}, r_u{1.f}, r_l{1.f};
        int depth = 0;
        bool specularBounce = false, anyNonSpecularBounces = false;
        Float etaScale = 1;
        LightSampleContext prevCtx;
        PathGuide::PathRecord *record = nullptr;  // where the guide records
        // With a guide: the radiance its tree expects at the path's first vertex (negative until
        // then), for its Russian roulette.
        Float pixelEstimate = -1;
        // With the trial's moment: what it sums, and the light-sampling probability r_l as volpath
        // carries it.
        UnguidedMoment *unguided = nullptr;
        SampledSpectrum r_lPath{1.f};
        // Adds to the estimate, and to what arrived at the recorded vertices; asPath: the same
        // contribution weighted as volpath weighs it, for the moment.
        void Add(const SampledSpectrum &contribution, const SampledSpectrum &asPath) {
            L += contribution;
            if (record)
                PathGuide::Arrived(*record, contribution);
            if (unguided)
                unguided->Add(asPath);
        }
        void Add(const SampledSpectrum &contribution) { Add(contribution, contribution); }
        void Add(const DirectLight &d) { Add(d.Ld, d.LdPath); }
        // After a scatter into a direction sampled with density pdf, which volpath samples with
        // pdfOwn: the light-sampling probabilities from r_u, and the moment's importance ratio.
        void Scattered(Float pdf, Float pdfOwn) {
            r_l = r_u / pdf;
            if (unguided) {
                r_lPath = r_u / pdfOwn;
                unguided->Scattered(pdfOwn, pdf);
            }
        }
        // Multiplies both light-sampling probabilities along a stretch of medium.
        void ScaleLightProbability(const SampledSpectrum &factor) {
            r_l *= factor;
            if (unguided)
                r_lPath *= factor;
        }
    };
    enum class MediumOutcome { PassedThrough, Scattered, Terminated };

    // The path from its camera ray until it ends.
    void Trace(PathState &path, SampledWavelengths &lambda, Sampler &sampler, RayCounts &rays) const;
    // With a guide, its spatial leaf at p; where it is the path's first vertex, the radiance
    // expected there (over the sphere in a medium, twice that at a surface, whose hemisphere
    // gets it all) becomes the path's pixel estimate.
    std::optional<SDTree::Guide> LeafAt(PathState &path, Point3f p, Float expectedOverMean) const;
    // The direction out of a surface vertex (the mixture's with a guide, else the BSDF's alone):
    // updates the path's throughput, its light-sampling probability and its ray; false where the
    // path ends.
    bool ScatterAtSurface(PathState &path, const SurfaceInteraction &si, const BSDF &bsdf,
                          const PathGuide::VertexGuide &vertex, Sampler &sampler, BSDFSample *sample) const;
    // The same in a medium, at mi, with the phase function.
    bool ScatterInMedium(PathState &path, const MediumInteraction &mi, const PathGuide::VertexGuide &vertex,
                         Sampler &sampler) const;
    // While training: the vertex at p the path left by scatter, with its scattering weight gain.
    void AddRecordedVertex(PathState &path, Point3f p, const PathGuide::VertexGuide &vertex,
                           const PathGuide::Scatter &scatter, const SampledSpectrum &gain) const;

    // Delta tracking along the ray's medium up to tMax: medium emission, absorption, real
    // scattering (with next-event estimation and a new direction) or null scattering.
    MediumOutcome SampleMedium(PathState &path, Float tMax, SampledWavelengths &lambda,
                               Sampler &sampler, RayCounts &rays) const;
    // Russian roulette on the throughput over its probability, without refraction's radiance
    // scaling (from the second surface vertex on, while under 1); with a guide (leaf), also by
    // the radiance learned along the new direction. Whether the path survives; its moment is
    // told of the roulette volpath would have rolled.
    bool Survives(PathState &path, const std::optional<SDTree::Guide> &leaf, Sampler &sampler) const;
    // What a vertex's scattering gives a light's direction, for next-event estimation: f (times
    // the cosine at a surface), the mixture's density and the vertex's own.
    struct ScatterToward {
        SampledSpectrum f;
        Float pdf, pdfOwn;
    };
    // Next-event estimation at a surface vertex with its BSDF.
    DirectLight SampleLdAtSurface(const SurfaceInteraction &si, const BSDF &bsdf,
                                      const PathGuide::VertexGuide &vertex,
                                      const SampledWavelengths &lambda, Sampler &sampler,
                                      const PathState &path, RayCounts &rays) const;
    // Subsurface scattering after the path refracted into a subsurface material at si (pbrt-v4's
    // volpath): a probe segment for the exit point, one of the material's surfaces along it
    // chosen uniformly, the BSSRDF's weight over its sampling density (with spectral MIS over the
    // wavelengths' densities), next-event estimation at the exit and a new direction from the
    // exit's BSDF. False when the path ends there.
    bool ScatterSubsurface(PathState &path, const SurfaceInteraction &si, const TabulatedBSSRDF &bssrdf,
                           SampledWavelengths &lambda, Sampler &sampler, RayCounts &rays) const;
    // Emission Le reached by the path, from light lightIndex, weighted against light sampling.
    void AddEmitted(PathState &path, SampledSpectrum Le, int lightIndex) const;
    // Next-event estimation at a surface or medium vertex: one light sample, attenuated by
    // the media and interfaces on the way (ratio tracking), weighted by MIS against the density
    // scatter(wi) (a ScatterToward) reports, and where pathWeighted against its own density too
    // (LdPath). r_p is the path's rescaled probability r_u at the vertex. While training, the
    // light's radiance, with its MIS weight over its density, is recorded at the vertex.
    template <typename Scatter, typename SpawnTo>
    DirectLight SampleLd(const LightSampleContext &ctx, Scatter scatter, SpawnTo spawnTo,
                         const SampledWavelengths &lambda, Sampler &sampler, SampledSpectrum beta,
                         SampledSpectrum r_p, bool pathWeighted, RayCounts &rays) const;
    // Transmittance along ray to pLight through media and interfaces (0 if a surface blocks
    // it), updating the light-path probabilities r_l and r_u by ratio tracking (by its
    // expectation in homogeneous media).
    SampledSpectrum Transmittance(Ray ray, Point3f pLight, const SampledWavelengths &lambda,
                                  SampledSpectrum *r_l, SampledSpectrum *r_u,
                                  RayCounts &rays) const;
    // The average of the rescaled probabilities over the wavelengths (spectral MIS), or with
    // spectral MIS off (for the test that measures its worth) the hero wavelength's alone.
    Float MISDenominator(const SampledSpectrum &r) const {
        return options.spectralMIS ? r.Average() : r[0];
    }

    const Scene &scene;
    IntegratorOptions options;
    std::optional<PathGuide> guide;
};

}  // namespace pbrt
