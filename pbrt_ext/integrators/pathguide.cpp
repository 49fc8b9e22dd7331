#include "pbrt_ext/integrators/pathguide.h"

#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/scattering.h"

#include <algorithm>

namespace pbrt {

namespace {

// A lobe whose density toward the mirror direction exceeds this (per steradian: a Trowbridge-
// Reitz lobe of alpha about 0.06) is near-specular: guided samples would nearly all miss it.
constexpr Float kNearSpecularDensity = 100;

// Russian roulette: a path whose throughput times the radiance learned along its direction is
// under this fraction of the pixel's estimate survives in proportion to it, but at least with
// this fraction of its throughput (so that a direction the tree has seen no light from is still
// explored, and the estimator stays unbiased). Chosen on scenes/guiding-slit.pbrt: 0.3 and 1 left
// 1.6x and 3.5x the error of 0.1 at about the same time; 0.03 took 7 % longer for 14 % less error.
constexpr Float kSurvivalWindow = 0.1f, kSurvivalFloor = 0.1f;

// A direction from the guide, with its density per steradian.
Vector3f SampleGuide(const DTree &directions, Point2f u, Float *pdf) {
    Vector3f wi = DirectionFromCanonical(directions.Sample(u, pdf));
    *pdf *= Inv4Pi;
    return wi;
}

}  // namespace

Float PathGuide::VertexGuide::PDF(Float pdfOwn, Vector3f wi) const {
    if (!directions)
        return pdfOwn;
    return Mixture(pdfOwn, GuidePDF(*directions, wi));
}

PathGuide::VertexGuide PathGuide::AtSurface(const SurfaceInteraction &si, const BSDF &bsdf,
                                            const SDTree::Guide &leaf) {
    BxDFFlags flags = bsdf.Flags();
    if (!IsNonSpecular(flags) || IsSpecular(flags))
        return {};
    if (!IsDiffuse(flags)) {
        Vector3f n = Vector3f(FaceForward(si.shading.n, si.wo));
        if (bsdf.PDF(si.wo, Reflect(si.wo, n)) > kNearSpecularDensity)
            return {};
    }
    return InMedium(leaf);
}

PathGuide::VertexGuide PathGuide::InMedium(const SDTree::Guide &leaf) {
    if (leaf.bsdfFraction >= 1 || !(leaf.directions.Energy() > 0))
        return {};
    return VertexGuide{&leaf.directions, leaf.bsdfFraction, leaf.leaf};
}

pstd::optional<PathGuide::Scatter> PathGuide::SampleBSDF(const BSDF &bsdf, const VertexGuide &guide,
                                                         Vector3f wo, Sampler &sampler) {
    Float uChoice = sampler.Get1D(), uc = sampler.Get1D();
    Point2f u = sampler.Get2D();
    if (!guide.directions || uChoice < guide.ownFraction) {
        pstd::optional<BSDFSample> bs = bsdf.Sample_f(wo, uc, u);
        if (!bs)
            return {};
        SampledSpectrum weight = bs->f / bs->pdf;  // exact even where the pdf is only proportional
        Float pdfBSDF = bs->pdfIsProportional ? bsdf.PDF(wo, bs->wi) : bs->pdf;
        if (!guide.directions)
            return Scatter{bs->wi, weight, pdfBSDF, pdfBSDF, 0, *bs};
        // One-sample MIS, balance heuristic: this strategy's share of the mixture at wi.
        Float pdfGuide = GuidePDF(*guide.directions, bs->wi);
        Float mixture = guide.Mixture(pdfBSDF, pdfGuide);
        if (!(mixture > 0))
            return {};
        return Scatter{bs->wi, weight * (pdfBSDF / mixture), mixture, pdfBSDF, pdfGuide, *bs};
    }
    Float pdfGuide;
    Vector3f wi = SampleGuide(*guide.directions, u, &pdfGuide);
    SampledSpectrum f = bsdf.f(wo, wi);
    Float pdfBSDF = bsdf.PDF(wo, wi), mixture = guide.Mixture(pdfBSDF, pdfGuide);
    if (!f || !(mixture > 0))
        return {};
    Vector3f n = Vector3f(bsdf.LocalToRender(Vector3f(0, 0, 1)));
    BxDFFlags flags = Dot(wi, n) * Dot(wo, n) > 0 ? BxDFFlags::GlossyReflection : BxDFFlags::GlossyTransmission;
    return Scatter{wi, f / mixture, mixture, pdfBSDF, pdfGuide, BSDFSample(f, wi, mixture, flags)};
}

pstd::optional<PathGuide::Scatter> PathGuide::SamplePhase(const HGPhaseFunction &phase, const VertexGuide &guide,
                                                          Vector3f wo, Sampler &sampler) {
    Float uChoice = sampler.Get1D();
    Point2f u = sampler.Get2D();
    Vector3f wi;
    Float pdfGuide = 0;
    if (!guide.directions || uChoice < guide.ownFraction) {
        std::optional<PhaseFunctionSample> ps = phase.Sample_p(wo, u);
        if (!ps || !(ps->pdf > 0))
            return {};
        wi = ps->wi;
        if (guide.directions)
            pdfGuide = GuidePDF(*guide.directions, wi);
    } else {
        wi = SampleGuide(*guide.directions, u, &pdfGuide);
    }
    const Float p = phase.p(wo, wi), pdfPhase = p;  // Henyey-Greenstein samples its own density
    const Float mixture = guide.directions ? guide.Mixture(pdfPhase, pdfGuide) : pdfPhase;
    if (!(mixture > 0))
        return {};
    return Scatter{wi, SampledSpectrum(p / mixture), mixture, pdfPhase, pdfGuide,
                   BSDFSample(SampledSpectrum(p), wi, mixture, BxDFFlags::GlossyReflection)};
}

Float PathGuide::SurvivalProbability(Float throughput, Float learnedRadiance, Float pixelEstimate) {
    if (!(pixelEstimate > 0) || !(learnedRadiance > 0))
        return throughput;
    return std::clamp(throughput * learnedRadiance / (kSurvivalWindow * pixelEstimate),
                      std::min(kSurvivalFloor * throughput, Float(1)), Float(1));
}

void PathGuide::RecordAt(Point3f p, Vector3f w, double valueOverPDF) const {
    // The filter's jitter, from what is recorded (deterministic, and independent of the sampler's
    // dimensions).
    RNG rng(Hash(p, w, valueOverPDF));
    tree->Record(p, w, valueOverPDF, rng);
}

void PathGuide::Commit(const PathRecord &path, const SampledWavelengths &lambda) const {
    for (const Vertex &v : path) {
        SampledSpectrum incident = SafeDiv(v.radiance, v.beta);
        RecordAt(v.p, v.wi, Luminance(incident, lambda) / v.pdf);
        if (v.leaf >= 0)
            tree->RecordFraction(v.leaf, v.pdfOwn, v.pdfGuide, Luminance(incident * v.gain, lambda));
    }
}

}  // namespace pbrt
