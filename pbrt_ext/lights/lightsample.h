// What every light shares: its type, and what sampling it returns (pbrt-v4's LightType,
// LightLiSample and LightLeSample).
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
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
    Point2f uvLight{};  // the surface's parameters there
};

// A ray leaving a light (pbrt-v4's LightLeSample), for paths traced from the lights: the
// radiance L it carries, the density pdfPos of its origin (per unit area; 1 for a point light)
// and pdfDir of its direction (per unit solid angle; 1 for a distant light). A ray from an area
// light starts on its surface, whose normal n is then nonzero.
struct LightLeSample {
    SampledSpectrum L;
    Ray ray;
    Normal3f n;
    Point2f uv;
    Float pdfPos = 0, pdfDir = 0;

    bool OnSurface() const { return n != Normal3f(0, 0, 0); }
    // The cosine that turns emitted radiance into power along w: 1 off surfaces.
    Float AbsCosTheta(Vector3f w) const { return OnSurface() ? AbsDot(w, n) : 1; }
};

// The densities with which SampleLe would have drawn a ray (pbrt-v4's PDF_Le).
struct LightLePDF {
    Float pos = 0, dir = 0;
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
