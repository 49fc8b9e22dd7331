#include "pbrt_ext/integrators/bsdffraction.h"

#include <cmath>

namespace pbrt {

void BSDFFractionLearner::Record(Float pdfBSDF, Float pdfGuide, double integrandOverPDF) {
    if (!(integrandOverPDF >= 0) || !std::isfinite(integrandOverPDF) || !(pdfBSDF >= 0) || !(pdfGuide >= 0) ||
        !(pdfBSDF + pdfGuide > 0) || !std::isfinite(pdfBSDF + pdfGuide))
        return;
    samples.fetch_add(1, std::memory_order_relaxed);
    if (integrandOverPDF == 0)
        return;
    weight.Add(integrandOverPDF);
    for (int i = 0; i < kCandidates; ++i) {
        double alpha = Candidate(i), mixture = alpha * pdfBSDF + (1 - alpha) * pdfGuide;
        crossEntropy[size_t(i)].Add(-integrandOverPDF * std::log(mixture));
    }
}

Float BSDFFractionLearner::Best(Float current) const {
    if (samples.load(std::memory_order_relaxed) < kMinimumSamples || !(weight.Load() > 0))
        return current;
    int best = 0;
    for (int i = 1; i < kCandidates; ++i)
        if (crossEntropy[size_t(i)].Load() < crossEntropy[size_t(best)].Load())
            best = i;
    return Candidate(best);
}

void BSDFFractionLearner::Reset() {
    for (AtomicSum &s : crossEntropy) s.Store(0);
    weight.Store(0);
    samples.store(0, std::memory_order_relaxed);
}

}  // namespace pbrt
