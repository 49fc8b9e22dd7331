#include "pbrt_ext/integrators/inversevariance.h"

#include <algorithm>

namespace pbrt {

namespace {

// A render whose samples do not vary (a white furnace) would weigh infinitely: its relative
// variance counts as at least this, so that renders that all do not vary count by sample count.
constexpr double kLeastVariance = 1e-12;

}  // namespace

void InverseVarianceCombination::Group::AddSums(const Group &other) {
    for (size_t i = 0; i < pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) pixels[i].rgb[c] += other.pixels[i].rgb[c];
        pixels[i].weight += other.pixels[i].weight;
    }
}

int InverseVarianceCombination::Parity(Point2i p) const {
    const Vector2i o = p - film.PixelBounds().pMin;
    return SampleMoments::BlockParity(o.x, o.y);
}

InverseVarianceCombination::Group InverseVarianceCombination::Pending() const {
    Group group;
    group.pixels.resize(size_t(film.PixelBounds().Area()));
    size_t i = 0;
    for (Point2i p : film.PixelBounds()) {
        RGBFilm::PixelSums sums = film.GetPixelSums(p);
        for (const Group &earlier : groups) {
            for (int c = 0; c < 3; ++c) sums.rgb[c] -= earlier.pixels[i].rgb[c];
            sums.weight -= earlier.pixels[i].weight;
        }
        for (int c = 0; c < 3; ++c) group.pixels[i].rgb[c] = float(sums.rgb[c]);
        group.pixels[i].weight = float(sums.weight);
        ++i;
    }
    return group;
}

void InverseVarianceCombination::EndRender(const SampleMoments &moments) {
    pending.Add(moments);
    if (pending.MeanCount() < 2)
        return;
    const std::array<std::optional<double>, 2> measured = pending.RelativeVarianceByBlockParity();
    Group group = Pending();
    for (int parity = 0; parity < 2; ++parity)
        // The other parity's variance weighs this parity's pixels; a mean count of two or more
        // leaves at least one parity with a variance.
        group.variance[parity] = std::max(measured[1 - parity].value_or(measured[parity].value_or(0)), kLeastVariance);
    // Earlier renders whose variance this one's floors join it.
    while (!groups.empty() && (groups.back().variance[0] <= group.variance[0] ||
                               groups.back().variance[1] <= group.variance[1])) {
        const Group &earlier = groups.back();
        group.AddSums(earlier);
        for (int parity = 0; parity < 2; ++parity)
            group.variance[parity] = std::max(group.variance[parity], earlier.variance[parity]);
        groups.pop_back();
    }
    groups.push_back(std::move(group));
    const double both = measured[0] && measured[1] ? (*measured[0] + *measured[1]) / 2
                                                   : measured[0].value_or(measured[1].value_or(0));
    weighed.push_back({pending.MeanCount(), both});
    pending = SampleMoments(film.PixelBounds());
}

void InverseVarianceCombination::Finish() {
    if (groups.empty())
        return;
    // A pending render (too few samples to weigh) joins the last group.
    groups.back().AddSums(Pending());
    size_t i = 0;
    for (Point2i p : film.PixelBounds()) {
        // The weighted mean, times the film's weight sum, which stays the pixel's divisor.
        double rgb[3] = {0, 0, 0}, weight = 0;
        const int parity = Parity(p);
        for (const Group &group : groups) {
            const double scale = 1 / group.variance[parity];
            for (int c = 0; c < 3; ++c) rgb[c] += scale * group.pixels[i].rgb[c];
            weight += scale * group.pixels[i].weight;
        }
        RGBFilm::PixelSums sums = film.GetPixelSums(p);
        for (int c = 0; c < 3; ++c) sums.rgb[c] = weight != 0 ? rgb[c] / weight * sums.weight : 0;
        film.SetPixelSums(p, sums);
        ++i;
    }
}

}  // namespace pbrt
