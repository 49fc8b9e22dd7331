// Light samplers: which light next-event estimation asks (pbrt-v4's src/pbrt/lightsamplers.h,
// reduced to the uniform and power samplers). Lights are named by their index in the scene's
// light list; Sample returns the index and the discrete probability p of choosing it, and
// PMF(i) is that same probability, so an estimate divides by p and MIS weights use PMF.
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/lights.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"

#include <string>

namespace pbrt {

struct SampledLight {
    int lightIndex;
    Float p;
};

// Every light with probability 1/n.
class UniformLightSampler {
  public:
    explicit UniformLightSampler(pstd::span<const Light> lights) : lightCount(int(lights.size())) {}

    pstd::optional<SampledLight> Sample(Float u) const;
    Float PMF(int lightIndex) const;
    // pbrt-v4's context-aware overloads: this sampler ignores the receiving point.
    pstd::optional<SampledLight> Sample(const LightSampleContext &, Float u) const {
        return Sample(u);
    }
    Float PMF(const LightSampleContext &, int lightIndex) const { return PMF(lightIndex); }
    std::string ToString() const;

  private:
    int lightCount;
};

// Lights with probability proportional to their power (the average of Phi's channels), as
// pbrt-v4; if no light has power, uniformly. Infinite and distant lights must have been
// preprocessed, since their power depends on the scene's extent.
class PowerLightSampler {
  public:
    explicit PowerLightSampler(pstd::span<const Light> lights);

    pstd::optional<SampledLight> Sample(Float u) const;
    Float PMF(int lightIndex) const;
    pstd::optional<SampledLight> Sample(const LightSampleContext &, Float u) const {
        return Sample(u);
    }
    Float PMF(const LightSampleContext &, int lightIndex) const { return PMF(lightIndex); }
    std::string ToString() const;

  private:
    // Over [0, 1] with one piece per light: piece i has probability power_i / total.
    PiecewiseConstant1D distribution;
};

}  // namespace pbrt
