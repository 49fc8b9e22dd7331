// The second moment of the path tracer's estimate of a camera sample (path.h), estimated from one
// guided path (guidedpath.h) by importance weights, for guiding's trial (guiding.h).
//
// Where path tracing struggles, its variance comes from rare bright paths, which a trial's few
// unguided samples per pixel seldom find, so that their variance underestimates the path
// tracer's. A guided path finds such paths more often, and counts each by how much likelier the
// path tracer was to take it.
//
// The path tracer's estimate sums contributions c_k, each a function of the path's first k
// vertices; let r_k be the density of those vertices under the path tracer over the guided one (at
// each guided vertex the BSDF's density over the mixture's, at each roulette the path tracer's
// survival probability over the guided one's). Then
//     E_path[(sum_k c_k)^2] = E_guided[sum_k r_k c_k (c_k + 2 sum_{j<k} c_j)].
// The guided path carries b_k = r_k c_k: the contribution with the guided throughput (which is the
// path tracer's times r_k) and the path tracer's MIS weights. The estimate is unbiased wherever
// the guided path samples every direction the BSDF does (its BSDF fraction is never 0), with two
// approximations: the stochastic densities of layered BSDFs are taken as exact, and a direction
// the guide sampled through a rough dielectric leaves the path's eta scale as it was
// (PathGuide::SampleBSDF), so that the path tracer's roulette after it is emulated from a
// throughput without the refraction's radiance scaling.
//
// The contributions are spectral, and what a unit of radiance at each wavelength adds to the
// sample's value is known only once the path is done (a dispersive surface can terminate the
// secondary wavelengths), so the moment is kept per pair of wavelengths and weighed at the end.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/spectrum.h"

#include <array>

namespace pbrt {

class UnguidedMoment {
  public:
    // b_k: a contribution with the guided path's throughput and the path tracer's MIS weight.
    void Add(const SampledSpectrum &contribution) {
        if (!(ratio > 0))
            return;  // a path the path tracer cannot take
        for (int i = 0; i < NSpectrumSamples; ++i) {
            const double b = contribution[i];
            for (int j = 0; j < NSpectrumSamples; ++j)
                secondMoment[i][j] += b * (contribution[j] / ratio + 2 * sum[j]);
        }
        for (int j = 0; j < NSpectrumSamples; ++j) {
            sum[j] += contribution[j] / ratio;
            weightedSum[j] += contribution[j];
        }
    }
    // The path scattered into a direction the path tracer samples with density pdfPath and the
    // guided path sampled with pdfGuided.
    void Scattered(Float pdfPath, Float pdfGuided) { ratio *= double(pdfPath) / pdfGuided; }
    // The path survived a roulette that the path tracer survives with probability path and the
    // guided path survived with probability guided.
    void Survived(Float path, Float guided) { ratio *= double(path) / guided; }
    // The path tracer's throughput, from the guided path's.
    Float PathThroughput(Float guidedThroughput) const { return Float(guidedThroughput / ratio); }

    // The estimate of the second moment of the sample's value, where toValue is what a unit of
    // radiance at each wavelength adds to it (the value being linear in the radiance).
    double SecondMoment(const SampledSpectrum &toValue) const {
        double total = 0;
        for (int i = 0; i < NSpectrumSamples; ++i)
            for (int j = 0; j < NSpectrumSamples; ++j) total += double(toValue[i]) * toValue[j] * secondMoment[i][j];
        return total;
    }

    // The path tracer's estimate weighted by its importance ratio, sum_k b_k: like the guided
    // path's own, an unbiased estimate of the sample's mean value (what tests check the weights
    // and ratios by, pairing the two).
    double WeightedEstimate(const SampledSpectrum &toValue) const {
        double total = 0;
        for (int i = 0; i < NSpectrumSamples; ++i) total += double(toValue[i]) * weightedSum[i];
        return total;
    }

  private:
    double ratio = 1;
    // Per wavelength, the sum of the path tracer's contributions so far, and of the b_k; per pair
    // of wavelengths, the estimate so far (what SecondMoment weighs).
    std::array<double, NSpectrumSamples> sum{}, weightedSum{};
    std::array<std::array<double, NSpectrumSamples>, NSpectrumSamples> secondMoment{};
};

// Next-event estimation's radiance at a guided vertex, weighted against the mixture's density
// (Ld) and, where asked for, against the BSDF's or phase function's, as the path tracer weighs it
// (LdPath, for UnguidedMoment::Add).
struct DirectLight {
    SampledSpectrum Ld, LdPath;
};

}  // namespace pbrt
