#include "pbrt_ext/film/spectralbuckets.h"

#include "pbrt_ext/util/ciedata.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>

namespace pbrt {

SpectralBuckets::SpectralBuckets(Float lambdaMin, Float lambdaMax, int count, size_t nPixels)
    : lambdaMin(lambdaMin), lambdaMax(lambdaMax), count(count), nPixels(nPixels),
      sums(nPixels * size_t(std::max(count, 0))), weights(sums.size()), splats(sums.size()) {
    if (!(lambdaMin >= Lambda_min && lambdaMin < lambdaMax && lambdaMax <= Lambda_max))
        throw std::invalid_argument(fmt::format(
            "the wavelength range [{}, {}] nm is not an interval inside [{}, {}] nm", lambdaMin,
            lambdaMax, Lambda_min, Lambda_max));
    if (count < 1)
        throw std::invalid_argument(fmt::format("{} spectral buckets; expected 1 or more", count));
}

int SpectralBuckets::BucketOf(Float lambda) const {
    int b = int((lambda - lambdaMin) / (lambdaMax - lambdaMin) * count);
    return std::clamp(b, 0, count - 1);
}

void SpectralBuckets::AddSample(size_t pixel, SampledSpectrum L, const SampledWavelengths &lambda,
                                Float weight, Float maxComponentValue) {
    Float m = L.MaxComponentValue();
    if (m > maxComponentValue) L *= maxComponentValue / m;
    for (int i = 0; i < NSpectrumSamples; ++i) {
        size_t index = pixel * size_t(count) + size_t(BucketOf(lambda[i]));
        sums[index] += double(weight) * L[i] * CIE_Y_integral;
        weights[index] += weight;
    }
}

void SpectralBuckets::AddSplat(size_t pixel, SampledSpectrum L, const SampledWavelengths &lambda,
                               Float weight, Float maxComponentValue) {
    Float m = L.MaxComponentValue();
    if (m > maxComponentValue) L *= maxComponentValue / m;
    // Each of the NSpectrumSamples wavelengths falls in a given band with probability 1/count.
    double scale = double(weight) * CIE_Y_integral * count / NSpectrumSamples;
    for (int i = 0; i < NSpectrumSamples; ++i)
        std::atomic_ref<double>(splats[pixel * size_t(count) + size_t(BucketOf(lambda[i]))])
            .fetch_add(scale * L[i], std::memory_order_relaxed);
}

Float SpectralBuckets::Value(size_t pixel, int b, double splatScale) const {
    size_t index = pixel * size_t(count) + size_t(b);
    double v = weights[index] > 0 ? sums[index] / weights[index] : 0;
    return Float(v + splatScale * splats[index]);
}

std::string SpectralBuckets::ChannelName(int b) const {
    std::string nm = fmt::format("{:.3f}nm", BucketCenter(b));
    std::replace(nm.begin(), nm.end(), '.', ',');
    return "S0." + nm;
}

std::vector<ImageExtraChannel> SpectralBuckets::Channels(double splatScale) const {
    std::vector<ImageExtraChannel> channels(static_cast<size_t>(count));
    for (int b = 0; b < count; ++b) {
        channels[size_t(b)].name = ChannelName(b);
        channels[size_t(b)].values.resize(nPixels);
        for (size_t p = 0; p < nPixels; ++p)
            channels[size_t(b)].values[p] = Value(p, b, splatScale);
    }
    return channels;
}

}  // namespace pbrt
