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
// the guided path samples every direction the BSDF does (its BSDF fraction is never 0), up to the
// stochastic densities of layered BSDFs, which it takes as exact.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/spectrum.h"

namespace pbrt {

class UnguidedMoment {
  public:
    // toValue: per wavelength, what a unit of radiance adds to the sample's value (the value
    // SampleMoments takes: linear in the radiance).
    explicit UnguidedMoment(const SampledSpectrum &toValue) : toValue(toValue) {}

    // b_k: a contribution with the guided path's throughput and the path tracer's MIS weight.
    void Add(const SampledSpectrum &contribution) {
        if (!(ratio > 0))
            return;  // a path the path tracer cannot take
        double b = 0;
        for (int i = 0; i < NSpectrumSamples; ++i) b += double(toValue[i]) * contribution[i];
        const double c = b / ratio;
        secondMoment += b * (c + 2 * sum);
        sum += c;
    }
    // The path scattered into a direction the path tracer samples with density pdfPath and the
    // guided path sampled with pdfGuided.
    void Scattered(Float pdfPath, Float pdfGuided) { ratio *= double(pdfPath) / pdfGuided; }
    // The path survived a roulette that the path tracer survives with probability path and the
    // guided path survived with probability guided.
    void Survived(Float path, Float guided) { ratio *= double(path) / guided; }
    // The path tracer's throughput, from the guided path's.
    Float PathThroughput(Float guidedThroughput) const { return Float(guidedThroughput / ratio); }

    double SecondMoment() const { return secondMoment; }

  private:
    SampledSpectrum toValue;
    double ratio = 1, sum = 0, secondMoment = 0;
};

}  // namespace pbrt
