#include "pbrt_ext/integrators/inversevariance.h"

#include <algorithm>

namespace pbrt {

namespace {

// A render whose samples do not vary (a white furnace) would weigh infinitely: its relative
// variance counts as at least this, so that renders that all do not vary count by sample count.
constexpr double kLeastVariance = 1e-12;

}  // namespace

InverseVarianceCombination::InverseVarianceCombination(RGBFilm &film)
    : film(film),
      pending(film.PixelBounds()),
      atLastEnd(size_t(film.PixelBounds().Area())),
      weighted(atLastEnd.size()) {}

int InverseVarianceCombination::Parity(Point2i p) const {
    const Vector2i o = p - film.PixelBounds().pMin;
    return (o.x / SampleMoments::kBlock + o.y / SampleMoments::kBlock) % 2;
}

void InverseVarianceCombination::EndRender(const SampleMoments &moments) {
    pending.Add(moments);
    if (pending.MeanCount() < 2)
        return;
    const std::array<std::optional<double>, 2> variance = pending.RelativeVarianceByBlockParity();
    std::array<double, 2> scale;
    for (int parity = 0; parity < 2; ++parity) {
        // The other parity's variance weighs this parity's pixels; a mean count of two or more
        // leaves at least one parity with a variance.
        const double v = variance[1 - parity].value_or(variance[parity].value_or(1));
        scale[parity] = 1 / std::max(v, kLeastVariance);
    }
    Fold(scale);
    lastScale = scale;
    const double both = variance[0] && variance[1] ? (*variance[0] + *variance[1]) / 2
                                                   : variance[0].value_or(variance[1].value_or(0));
    weighed.push_back({pending.MeanCount(), both});
    pending = SampleMoments(film.PixelBounds());
}

void InverseVarianceCombination::Fold(const std::array<double, 2> &scale) {
    size_t i = 0;
    for (Point2i p : film.PixelBounds()) {
        const RGBFilm::PixelSums now = film.GetPixelSums(p);
        const double s = scale[Parity(p)];
        for (int c = 0; c < 3; ++c) weighted[i].rgb[c] += s * (now.rgb[c] - atLastEnd[i].rgb[c]);
        weighted[i].weight += s * (now.weight - atLastEnd[i].weight);
        for (int c = 0; c < 3; ++c) atLastEnd[i].rgb[c] = now.rgb[c];
        atLastEnd[i].weight = now.weight;
        ++i;
    }
}

void InverseVarianceCombination::Finish() {
    Fold(lastScale);
    size_t i = 0;
    for (Point2i p : film.PixelBounds()) {
        // The weighted mean, times the film's weight sum, which stays the pixel's divisor.
        RGBFilm::PixelSums sums = film.GetPixelSums(p);
        const Sums &w = weighted[i++];
        for (int c = 0; c < 3; ++c) sums.rgb[c] = w.weight != 0 ? w.rgb[c] / w.weight * sums.weight : 0;
        film.SetPixelSums(p, sums);
    }
}

}  // namespace pbrt
