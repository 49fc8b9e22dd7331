// Path tracing guided by the radiance field an SD-tree learns (integrators/sdtree.h; Müller,
// Gross and Novák 2017): pbrt-v4's path tracer, but at each vertex whose BSDF has neither a
// specular nor a near-specular lobe, the next direction comes from the BSDF with the probability
// the vertex's spatial leaf has learned (bsdffraction.h) and from the leaf's distribution
// otherwise. The two are combined
// by one-sample MIS with the balance heuristic, so that a layered BSDF, whose density is only
// estimated, stays unbiased; for the others the weight is f cos / (the mixture's density).
// That mixture density is also what next-event estimation's and the emitters' MIS weights use.
//
// While training, each path records at its vertices the radiance that arrived there, over the
// density its direction was sampled with (Müller's irradiance records): along the scattered
// direction, everything the rest of the path found; along the light's, next-event estimation's
// radiance with its MIS weight; and at each guided vertex, what its BSDF fraction learns from.
// Recording is the only thing that training changes: a render with a frozen tree is an ordinary
// unbiased estimator.
#pragma once

#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/integrators/sdtree.h"
#include "pbrt_ext/options.h"

#include <vector>

namespace pbrt {

class Scene;

class GuidedPathIntegrator {
  public:
    // Samples from tree, and records into it where record.
    GuidedPathIntegrator(const Scene &scene, const IntegratorOptions &options, SDTree &tree, bool record);

    SampledSpectrum Li(RayDifferential ray, SampledWavelengths &lambda, Sampler &sampler,
                       RayCounts &rays) const;

  private:
    friend struct GuidedPathTestAccess;  // tests/integrators/guidedpath_test.cpp: the mixture

    // How a vertex samples: from the BSDF with probability bsdfFraction and from directions
    // otherwise, the distribution of spatial leaf `leaf`; with no directions, from the BSDF.
    struct Guide {
        const DTree *directions = nullptr;
        Float bsdfFraction = 1;
        int leaf = -1;
    };
    // A vertex of the path, for recording: where it is, the direction it scattered into and
    // that direction's density, the throughput of the ray leaving it, and the radiance (times
    // the path's throughput) that arrived along that ray. Where guided, its leaf, the BSDF's and
    // the guide's densities of the direction, and f |cos| / density, for the BSDF fraction.
    struct Vertex {
        Point3f p;
        Vector3f wi;
        Float pdf;
        SampledSpectrum beta, radiance;
        int leaf;
        Float pdfBSDF, pdfGuide;
        SampledSpectrum gain;
    };
    // The direction the path continues in, its f |cos| / (density) weight, and the density to
    // weigh emitters and records by (the mixture's where guided), with the BSDF's and the
    // guide's densities of the direction (the guide's 0 without one).
    struct Scatter {
        Vector3f wi;
        SampledSpectrum weight;
        Float pdf, pdfBSDF, pdfGuide;
        BSDFSample sample;  // flags, eta
    };

    // How to sample at a vertex with the leaf's guide: without directions for a specular or
    // near-specular BSDF, or where the tree has learned nothing yet.
    Guide GuideAt(const SurfaceInteraction &si, const BSDF &bsdf, const SDTree::Guide &leaf) const;
    // The mixture's density of wi (the BSDF's alone without a guide).
    Float ScatterPDF(const BSDF &bsdf, const Guide &guide, Vector3f wo, Vector3f wi) const;
    pstd::optional<Scatter> SampleScatter(const BSDF &bsdf, const Guide &guide, Vector3f wo,
                                          Sampler &sampler) const;
    // Next-event estimation at si, weighted against ScatterPDF; where training, its record.
    SampledSpectrum SampleLd(const SurfaceInteraction &si, const BSDF &bsdf, const Guide &guide,
                             const SampledWavelengths &lambda, Sampler &sampler, RayCounts &rays) const;
    // Russian roulette guided by the tree (Vorba and Křivánek 2016, "Adjoint-Driven Russian
    // Roulette and Splitting in Light Transport Simulation", without splitting): the probability
    // that a path continues, from its throughput, the radiance learned along its next direction,
    // and the radiance expected at the path's first vertex. pbrt-v4's throughput roulette kills
    // the paths that are about to reach light through an opening as often as the others; their
    // survivors, weighted up, were most of the noise where guiding helps most. Without a learned
    // estimate it is pbrt-v4's.
    static Float SurvivalProbability(Float throughput, Float learnedRadiance, Float pixelEstimate);
    // Adds a contribution to the radiance of every vertex before it.
    static void Arrived(std::vector<Vertex> &vertices, const SampledSpectrum &contribution);
    void Commit(const std::vector<Vertex> &vertices, const SampledWavelengths &lambda) const;
    void RecordAt(Point3f p, Vector3f w, double value) const;

    const Scene &scene;
    IntegratorOptions options;
    SDTree &tree;
    bool record;
};

}  // namespace pbrt
