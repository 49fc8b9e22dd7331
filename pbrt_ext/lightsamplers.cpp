#include "pbrt_ext/lightsamplers.h"

#include <algorithm>
#include <vector>

namespace pbrt {

pstd::optional<SampledLight> UniformLightSampler::Sample(Float u) const {
    if (lightCount == 0)
        return {};
    int lightIndex = std::min(int(u * lightCount), lightCount - 1);
    return SampledLight{lightIndex, Float(1) / lightCount};
}

Float UniformLightSampler::PMF(int lightIndex) const {
    if (lightIndex < 0 || lightIndex >= lightCount)
        return 0;
    return Float(1) / lightCount;
}

std::string UniformLightSampler::ToString() const {
    return "[ UniformLightSampler lightCount: " + std::to_string(lightCount) + " ]";
}

namespace {

std::vector<Float> LightPowers(pstd::span<const Light> lights) {
    // pbrt-v4's: the power at four visible wavelengths, weighted as the film weights them.
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    std::vector<Float> power(lights.size());
    for (size_t i = 0; i < lights.size(); ++i)
        power[i] = std::max<Float>(SafeDiv(lights[i].Phi(lambda), lambda.PDF()).Average(), 0);
    if (std::all_of(power.begin(), power.end(), [](Float p) { return p == 0; }))
        std::fill(power.begin(), power.end(), Float(1));
    return power;
}

}  // namespace

PowerLightSampler::PowerLightSampler(pstd::span<const Light> lights) {
    if (!lights.empty())
        distribution = PiecewiseConstant1D(LightPowers(lights));
}

// A piece's density over [0, 1] is n times its probability.
pstd::optional<SampledLight> PowerLightSampler::Sample(Float u) const {
    if (distribution.size() == 0)
        return {};
    Float pdf;
    int lightIndex;
    distribution.Sample(u, &pdf, &lightIndex);
    return SampledLight{lightIndex, pdf / distribution.size()};
}

Float PowerLightSampler::PMF(int lightIndex) const {
    if (lightIndex < 0 || size_t(lightIndex) >= distribution.size())
        return 0;
    return distribution.func[lightIndex] / (distribution.Integral() * distribution.size());
}

std::string PowerLightSampler::ToString() const {
    return "[ PowerLightSampler lightCount: " + std::to_string(distribution.size()) + " ]";
}

}  // namespace pbrt
