// How a guided render (guiding.h) spends its sample budget on training: iterations of 1, 2, 4, ...
// samples per pixel, each while it fits in half of the budget with those before it (Müller et al.
// 2017, section 5); and what a guided ray costs on average over the rest of the render, training
// and rendering, which the trial charges a guided sample.
#pragma once

namespace pbrt {

// What a guided ray costs against an unguided one, rendering (the tree's lookups and the
// mixture's densities) and training (recording too, and the BSDF fraction's candidates); rays are
// counted instead of timed so that the decision, and with it the image, is the same on every run.
// Seconds per ray over path's (volpath's), 2 threads: rendering with a loaded tree 1.26 on
// scenes/cornell-box.pbrt (128×128, 64 spp), 1.24 on scenes/guiding-slit.pbrt (160×120, 256 spp),
// 1.30 and 1.31 for guidedvolpath on scenes/media-cornell-fog.pbrt and scenes/guiding-slit-fog.pbrt
// (160×120, 64 spp); training 2.26 and 1.69 on the first two (31 of 64 spp).
constexpr double kGuidedRayCost = 1.25, kTrainingRayCost = 2;

// The samples per pixel of training iteration k.
constexpr int IterationSamples(int k) { return 1 << k; }

// Whether iteration k fits in a budget of count samples per pixel after done of training.
constexpr bool IterationFits(int done, int count, int k) { return 2 * (done + IterationSamples(k)) <= count; }

// The samples per pixel that training would still take after done, iteration k first, within a
// budget of count.
constexpr int TrainingToCome(int done, int count, int k) {
    int samples = 0;
    for (; IterationFits(done + samples, count, k); ++k)
        samples += IterationSamples(k);
    return samples;
}

// What a guided ray of the rest of a budget of count costs on average after done samples per
// pixel, iteration k the next: training's cost while it trains, rendering's after.
constexpr double GuidedRayCost(int done, int count, int k) {
    const int training = TrainingToCome(done, count, k), rest = count - done;
    return rest > 0 ? (training * kTrainingRayCost + (rest - training) * kGuidedRayCost) / rest : kGuidedRayCost;
}

}  // namespace pbrt
