// Rays, ray differentials and safe spawning from surfaces (pbrt-v4's src/pbrt/ray.h).
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"

namespace pbrt {

struct Ray {
    Ray() = default;
    PBRT_CPU_GPU Ray(Point3f o, Vector3f d, int medium = -1, Float time = 0)
        : o(o), d(d), medium(medium), time(time) {}
    PBRT_CPU_GPU Point3f operator()(Float t) const { return o + d * t; }

    Point3f o;
    Vector3f d;
    int medium = -1;  // the medium the origin lies in: an index into Scene::media, -1 vacuum
    Float time = 0;   // within the camera's shutter interval: where moving shapes are
};

// A camera ray with its neighbours one pixel over in x and in y (pbrt-v4's RayDifferential),
// for the footprint of a hit on the film. A ray spawned from a surface has none
// (hasDifferentials false): its hits use the camera's approximation.
struct RayDifferential : Ray {
    RayDifferential() = default;
    PBRT_CPU_GPU RayDifferential(const Ray &ray) : Ray(ray) {}  // without differentials
    PBRT_CPU_GPU RayDifferential &operator=(const Ray &ray) {
        Ray::operator=(ray);
        hasDifferentials = false;
        return *this;
    }
    // The neighbours s pixels away instead of one (pbrt-v4: 1 / sqrt(spp), at least 1/8).
    PBRT_CPU_GPU void ScaleDifferentials(Float s) {
        rxOrigin = o + (rxOrigin - o) * s;
        ryOrigin = o + (ryOrigin - o) * s;
        rxDirection = d + (rxDirection - d) * s;
        ryDirection = d + (ryDirection - d) * s;
    }

    bool hasDifferentials = false;
    Point3f rxOrigin, ryOrigin;
    Vector3f rxDirection, ryDirection;
};

// Moves a ray origin off the surface at p along the geometric normal n, to the side w leaves
// toward, so that the spawned ray does not re-hit its own surface. pbrt-v4 bounds the
// intersection's rounding error exactly; we use a bound proportional to the magnitude of p,
// which covers Embree's watertight triangle and our quadric intersection routines. errorBound:
// a larger distance p may lie from the surface (a curve's width, as pbrt-v4 bounds it).
PBRT_CPU_GPU inline Point3f OffsetRayOrigin(Point3f p, Normal3f n, Vector3f w,
                                            Float errorBound = 0) {
    Float scale = 1 + std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z));
    Vector3f offset = Vector3f(n) * std::max(Float(1e-4) * scale, errorBound);
    if (Dot(w, Vector3f(n)) < 0)
        offset = -offset;
    return p + offset;
}

// The parametric distance to use as tMax for a shadow ray from an offset origin toward pLight:
// a little short of 1, so that the light's own surface does not occlude it.
PBRT_CPU_GPU inline constexpr Float ShadowEpsilon() { return Float(1e-4); }

}  // namespace pbrt
