// What every light shares: its type, and what sampling it returns (pbrt-v4's LightType and
// LightLiSample).
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/spectrum.h"
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

}  // namespace pbrt
