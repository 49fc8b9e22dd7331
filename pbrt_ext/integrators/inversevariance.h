// Combines the renders that make one image, each an unbiased estimate of it (a guided render's
// training iterations, the trial's halves and the final render: guiding.h), weighting each by the
// inverse of its variance, as Müller (SIGGRAPH 2019 course, "Practical Path Guiding in
// Production") combines training iterations, instead of by sample count: an iteration guided by a
// young tree is noisier per sample than the last (on scenes/guiding-slit.pbrt, 3.6 against 0.96).
// A render's samples each weigh the inverse of its variance of one sample, relative to the
// pixel's value (SampleMoments::RelativeVarianceByBlockParity), so that a pixel's value is the
// inverse-variance weighted mean of the renders' estimates of it.
// - A render's variance counts as at least every later render's. Where path tracing struggles,
//   the variance comes from rare bright paths, which a render of a few samples per pixel seldom
//   sees: it underestimates its variance (in the fog-filled slit room, renders of 4 samples per
//   pixel measured 5 to 6; the final render of 241, by the same estimator, 29). A later render is
//   larger, and guided by a tree trained longer. Without this floor the combination raised the
//   error there by a fifth, and on scenes/guiding-fabric.pbrt by 5 %.
// - The weights are estimated from the samples they weigh, which biases the image where a bright
//   sample raises its render's variance and so lowers its own weight. So that a pixel's own
//   samples do not set its weights, the pixels of each parity of a checkerboard of 8 × 8-pixel
//   blocks are weighted by the variance measured in the other parity's blocks (a pixel's own
//   where the other has none). The image is consistent: the weights' noise vanishes as renders
//   grow.
// - A render whose pixels took fewer than two samples on average has no variance to be weighed
//   by: it joins the next.
// The film keeps its weight sums (the g-buffer's divisor), its spectral bands and splats, all by
// sample count; until Finish its pixels hold every sample by count, so that partial images and
// --mse-reference-out's curve show that. Memory: 16 bytes a pixel for each run of renders whose
// variances fall (renders whose floor joins them share one).
#pragma once

#include "pbrt_ext/film/film.h"
#include "pbrt_ext/integrators/samplemoments.h"

#include <array>
#include <vector>

namespace pbrt {

class InverseVarianceCombination {
  public:
    explicit InverseVarianceCombination(RGBFilm &film) : film(film), pending(film.PixelBounds()) {}

    // Ends a render: the samples the film gathered since the last render ended, whose moments are
    // moments.
    void EndRender(const SampleMoments &moments);
    // Puts the combination into the film; a render still pending (too few samples) joins the
    // last one weighed, or where none was, the film stays by sample count.
    void Finish();

    // Each weighed render's samples per pixel and relative variance of one sample (both parities'
    // pixels together, before the floor), for --stats.
    struct Weighed {
        double samplesPerPixel = 0, relativeVariance = 0;
    };
    const std::vector<Weighed> &Renders() const { return weighed; }

  private:
    // Renders weighed alike: their samples' sums per pixel, and the variance (per parity) that
    // weighs them.
    struct Group {
        struct Sums {
            float rgb[3] = {0, 0, 0};
            float weight = 0;
        };
        std::vector<Sums> pixels;
        std::array<double, 2> variance;

        // Adds other's samples, of the same pixels, to these.
        void AddSums(const Group &other);
    };

    // The film's samples since the last render ended.
    Group Pending() const;
    int Parity(Point2i p) const;

    RGBFilm &film;
    SampleMoments pending;
    // By render order, each group's variances above the next's in both parities: a render whose
    // variance in either parity reaches an earlier group's joins it (each parity's the larger).
    std::vector<Group> groups;
    std::vector<Weighed> weighed;
};

}  // namespace pbrt
