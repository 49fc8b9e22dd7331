// Combines the renders that make one image, each an unbiased estimate of it (a guided render's
// training iterations, the trial's halves and the final render: guiding.h), weighting each by the
// inverse of its variance, as Müller (SIGGRAPH 2019 course, "Practical Path Guiding in
// Production") combines training iterations, instead of by sample count: an iteration guided by a
// young tree is noisier per sample than the last (on scenes/guiding-slit.pbrt, 3.6 against 0.96).
// A render's samples each weigh the inverse of its variance of one sample, relative to the
// pixel's value (SampleMoments::RelativeVarianceByBlockParity), so that a pixel's value is the
// inverse-variance weighted mean of the renders' estimates of it.
// The weights are estimated from the samples they weigh, which biases the image where a bright
// sample raises its render's variance and so lowers its own weight. So that a pixel's own samples
// do not set its weights, the pixels of each parity of a checkerboard of 8 × 8-pixel blocks are
// weighted by the variance measured in the other parity's blocks (a pixel's own where the other
// has none). The image is consistent: the weights' noise vanishes as the renders grow.
// A render whose pixels took fewer than two samples on average has no variance to be weighed by:
// it joins the next. The film keeps its weight sums (the g-buffer's divisor), its spectral bands
// and splats, all by sample count; until Finish its pixels hold every sample by count, so that
// partial images and --mse-reference-out's curve show that.
// Memory: 64 bytes a pixel (the film's sums at the last render's end, and the weighted sums).
#pragma once

#include "pbrt_ext/film/film.h"
#include "pbrt_ext/integrators/samplemoments.h"

#include <array>
#include <vector>

namespace pbrt {

class InverseVarianceCombination {
  public:
    explicit InverseVarianceCombination(RGBFilm &film);

    // Ends a render: the samples the film gathered since the last render ended, whose moments are
    // moments.
    void EndRender(const SampleMoments &moments);
    // Puts the combination into the film; a render still pending (too few samples) counts with the
    // weights of the last render weighed, or by sample count where none was.
    void Finish();

    // Each weighed render's samples per pixel and relative variance of one sample (both parities'
    // pixels together), for --stats.
    struct Weighed {
        double samplesPerPixel = 0, relativeVariance = 0;
    };
    const std::vector<Weighed> &Renders() const { return weighed; }

  private:
    // Adds the film's samples since the last render ended, each weighing scale[parity].
    void Fold(const std::array<double, 2> &scale);
    int Parity(Point2i p) const;

    struct Sums {
        double rgb[3] = {0, 0, 0};
        double weight = 0;
    };

    RGBFilm &film;
    SampleMoments pending;
    std::vector<Sums> atLastEnd, weighted;
    std::array<double, 2> lastScale{1, 1};
    std::vector<Weighed> weighed;
};

}  // namespace pbrt
