// What guided path tracing adds to a path tracer, shared by guidedpath (guidedpath.h) and
// guidedvolpath (volpath.h with a guide): at each vertex, sampling the next direction from the
// BSDF or phase function with the probability its spatial leaf of the SD-tree has learned
// (bsdffraction.h), and from the leaf's distribution otherwise, by one-sample MIS with the
// balance heuristic (Müller, Gross and Novák 2017); and, while training, recording the radiance
// that arrived at each vertex along its direction, over the density it was sampled with.
//
// The mixture's density is what every MIS weight at the vertex uses (next-event estimation's,
// the emitters'). For a BSDF whose density is only estimated (layered), the BSDF's sample keeps
// f / pdf times its balance weight, so that the estimator stays unbiased; for the others the
// weight is f cos / (the mixture's density) whichever strategy sampled.
#pragma once

#include "pbrt_ext/integrators/sdtree.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/materials/bsdf.h"
#include "pbrt_ext/media/media.h"
#include "pbrt_ext/samplers/samplers.h"

#include <vector>

namespace pbrt {

class PathGuide {
  public:
    // Samples from tree, and records into it where record.
    PathGuide(SDTree &tree, bool record) : tree(&tree), record(record) {}

    // How one vertex samples: from its own distribution (BSDF or phase function) with
    // probability ownFraction and from directions otherwise, the distribution of spatial leaf
    // `leaf`; with no directions, from its own alone.
    struct VertexGuide {
        const DTree *directions = nullptr;
        Float ownFraction = 1;
        int leaf = -1;
        // The mixture's density of wi, given the vertex's own density of it.
        Float PDF(Float pdfOwn, Vector3f wi) const;
        // The mixture's density of a direction from its two densities (with directions).
        Float Mixture(Float pdfOwn, Float pdfGuide) const {
            return ownFraction * pdfOwn + (1 - ownFraction) * pdfGuide;
        }
    };
    // The direction sampled, its weight (f or the phase function over the mixture's density; a
    // BSDF's cosine is the caller's), the mixture's density (to weigh emitters and records by)
    // with the vertex's own and the guide's (0 without one), and the BSDF sample's flags and eta.
    struct Scatter {
        Vector3f wi;
        SampledSpectrum weight;
        Float pdf, pdfOwn, pdfGuide;
        BSDFSample sample;
    };

    // The leaf holding p, and how a vertex there samples: without the leaf's directions for a
    // specular or near-specular BSDF, or where the tree has learned nothing yet.
    SDTree::Guide LeafAt(Point3f p) const { return tree->SamplingGuide(p); }
    static VertexGuide AtSurface(const SurfaceInteraction &si, const BSDF &bsdf, const SDTree::Guide &leaf);
    static VertexGuide InMedium(const SDTree::Guide &leaf);

    // The next direction from the mixture at a surface (u: 1D choice, 1D and 2D for the BSDF)
    // or in a medium (the phase function, exact: p == pdf).
    static pstd::optional<Scatter> SampleBSDF(const BSDF &bsdf, const VertexGuide &guide, Vector3f wo,
                                              Sampler &sampler);
    static pstd::optional<Scatter> SamplePhase(const HGPhaseFunction &phase, const VertexGuide &guide,
                                               Vector3f wo, Sampler &sampler);

    // A vertex of the path, for recording: where it is, the direction it scattered into and the
    // mixture's density of it, the throughput of the ray leaving it, and the radiance (times the
    // path's throughput) that arrived along that ray. Where guided, its leaf, its own and the
    // guide's densities of the direction, and its scattering weight, for the leaf's fraction.
    struct Vertex {
        Point3f p;
        Vector3f wi;
        Float pdf;
        SampledSpectrum beta, radiance;
        int leaf;
        Float pdfOwn, pdfGuide;
        SampledSpectrum gain;
    };
    // The vertices of one path, for one thread: a contribution to the path's estimate arrived at
    // every vertex before it.
    using PathRecord = std::vector<Vertex>;
    static void Arrived(PathRecord &path, const SampledSpectrum &contribution) {
        for (Vertex &v : path) v.radiance += contribution;
    }

    // Russian roulette guided by the tree (Vorba and Křivánek 2016, "Adjoint-Driven Russian
    // Roulette and Splitting in Light Transport Simulation", without splitting): the probability
    // that a path continues, from its throughput, the radiance learned along its next direction
    // (LearnedRadiance), and the radiance expected at the path's first vertex. pbrt-v4's
    // throughput roulette kills the paths that are about to reach light through an opening as
    // often as the others; their survivors, weighted up, were most of the noise where guiding
    // helps most. Without a learned estimate it is pbrt-v4's (the throughput, which callers roll
    // only below 1).
    static Float SurvivalProbability(Float throughput, Float learnedRadiance, Float pixelEstimate);
    // DTree::Radiance of w, from the learned distribution's density of it (per steradian).
    static Float LearnedRadiance(const DTree &learned, Float pdfLearned) {
        return 4 * Pi * pdfLearned * learned.MeanRadiance();
    }

    bool Recording() const { return record; }
    // Records at p the luminance of radiance that arrived along w over its density (next-event
    // estimation's), and at the end of a path, what arrived at each of its vertices.
    void RecordAt(Point3f p, Vector3f w, double valueOverPDF) const;
    void Commit(const PathRecord &path, const SampledWavelengths &lambda) const;

  private:
    SDTree *tree;
    bool record;
};

// The guide's density per steradian of w (the tree's is per unit area of the canonical square).
inline Float GuidePDF(const DTree &guide, Vector3f w) { return guide.PDF(CanonicalFromDirection(w)) * Inv4Pi; }

}  // namespace pbrt
