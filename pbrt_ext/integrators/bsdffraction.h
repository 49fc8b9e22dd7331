// The fraction of directions a spatial leaf of the SD-tree samples from the BSDF rather than from
// its learned distribution, chosen from what an iteration's guided samples found there.
//
// Müller's "Practical Path Guiding in Production" (SIGGRAPH 2019 course) learns it by stochastic
// gradient descent on the KL divergence between the integrand f cos Li (normalized) and the
// mixture alpha p_bsdf + (1 - alpha) p_guide. That divergence is, up to a constant, the cross
// entropy -E_target[log p_mix], which each guided sample estimates without bias by
// (F / p_sampled) * -log p_mix(w) (importance weights of the target). It is convex in alpha, so
// the minimum over a grid of candidates is found by summing every candidate's estimate at once:
// no learning rate, and the result depends on what was recorded, not on the order threads add it.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/atomicsum.h"

#include <array>
#include <atomic>
#include <cstdint>

namespace pbrt {

class BSDFFractionLearner {
  public:
    // 0.1, 0.2, ..., 0.9: never 0, so that where the guide has no density the BSDF still
    // samples (the estimator stays unbiased); never 1, which would learn nothing more.
    static constexpr int kCandidates = 9;
    static Float Candidate(int i) { return Float(i + 1) / (kCandidates + 1); }
    // A leaf with fewer guided samples than this keeps its fraction.
    static constexpr uint64_t kMinimumSamples = 64;

    // A guided sample: the BSDF's and the guide's densities (per steradian) of its direction,
    // and the luminance of f cos Li over the density it was sampled with. Thread-safe.
    void Record(Float pdfBSDF, Float pdfGuide, double integrandOverPDF);
    // The candidate of least estimated cross entropy, or current where too little was recorded.
    Float Best(Float current) const;
    void Reset();

  private:
    std::array<AtomicSum, kCandidates> crossEntropy;
    AtomicSum weight;
    std::atomic<uint64_t> samples{0};
};

}  // namespace pbrt
