// Surface interactions: what the integrator knows about a ray's hit (pbrt-v4's src/pbrt/interaction.h,
// reduced: no ray differentials).
#pragma once

#include "pbrt_ext/base/medium.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/vecmath.h"

namespace pbrt {

// The geometry of a hit. n is the geometric normal, flipped by ReverseOrientation and transform
// handedness exactly as pbrt-v4 does; shading.n lies on the same side as n.
struct SurfaceInteraction {
    Point3f p;
    Normal3f n;
    Point2f uv;
    Vector3f wo;  // toward the ray origin, unit
    Vector3f dpdu, dpdv;
    struct {
        Normal3f n;
        Vector3f dpdu, dpdv;
        // How the shading normal turns across the surface (pbrt-v4's dndu, dndv), for bump
        // mapping: from the vertex normals of a mesh, dpdu / r on a sphere, zero where flat.
        Normal3f dndu, dndv;
    } shading;
    Float time = 0;           // the time of the ray that found it; rays leaving keep it
    Float errorBound = 0;     // how far p may be from the surface: a curve's width, else 0
    int materialIndex = -1;   // into Scene::materials; -1: no material (an interface)
    int areaLightIndex = -1;  // into Scene::lights; -1: not emissive
    // The media on either side: the shape's where it separates two media, else the ray's on
    // both sides (pbrt-v4's SetIntersectionProperties).
    MediumInterface mediumInterface;

    // The medium a ray leaving in direction w travels through.
    PBRT_CPU_GPU int GetMedium(Vector3f w) const {
        return Dot(w, Vector3f(n)) > 0 ? mediumInterface.outside : mediumInterface.inside;
    }
    // A ray leaving the surface in direction w, its origin offset to w's side.
    PBRT_CPU_GPU Ray SpawnRay(Vector3f w) const {
        return Ray(OffsetRayOrigin(p, n, w, errorBound), w, GetMedium(w), time);
    }
    // A ray toward the point p2 with d = p2 - o, so that t = 1 reaches it.
    PBRT_CPU_GPU Ray SpawnRayTo(Point3f p2) const {
        Point3f o = OffsetRayOrigin(p, n, p2 - p, errorBound);
        return Ray(o, p2 - o, GetMedium(p2 - p), time);
    }
};

// What a light needs to know about the point it illuminates (pbrt-v4's LightSampleContext).
struct LightSampleContext {
    LightSampleContext() = default;
    PBRT_CPU_GPU explicit LightSampleContext(const SurfaceInteraction &si)
        : p(si.p), n(si.n), ns(si.shading.n) {}
    PBRT_CPU_GPU LightSampleContext(Point3f p, Normal3f n, Normal3f ns) : p(p), n(n), ns(ns) {}

    Point3f p;
    Normal3f n, ns;  // zero for a point in free space
};

}  // namespace pbrt
