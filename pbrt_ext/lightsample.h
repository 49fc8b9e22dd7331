// What every light shares: its type, and what sampling it returns (pbrt-v4's LightType and
// LightLiSample).
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/transform.h"
#include "pbrt_ext/util/vecmath.h"

namespace pbrt {

enum class LightType { DeltaPosition, DeltaDirection, Area, Infinite };

inline bool IsDeltaLight(LightType type) {
    return type == LightType::DeltaPosition || type == LightType::DeltaDirection;
}

struct LightLiSample {
    SampledSpectrum L;
    Vector3f wi;  // unit, from the receiving point toward the light
    Float pdf;    // per unit solid angle; 1 for delta lights
    Point3f pLight;
    Normal3f nLight;  // zero where the light has no surface
};

// What arrives at ctx from a point light at the light-space origin whose intensity toward the
// light-space unit direction w is I(w): I / r^2 along wi (spot, goniometric, projection).
template <typename Intensity>
pstd::optional<LightLiSample> PointLightSample(const Transform &worldFromLight, LightSampleContext ctx,
                                               Intensity I) {
    Point3f p = worldFromLight(Point3f(0, 0, 0));
    Float r2 = DistanceSquared(p, ctx.p);
    if (r2 == 0) return {};
    Vector3f wi = Normalize(p - ctx.p);
    SampledSpectrum Li = I(Normalize(worldFromLight.ApplyInverse(-wi))) / r2;
    if (!Li) return {};
    return LightLiSample{Li, wi, 1, p, Normal3f(0, 0, 0)};
}

}  // namespace pbrt
