// Bounds on what a light can send toward a region (pbrt-v4's LightBounds): where it is, how much
// it emits, and the directions it emits in. The BVH light sampler (lightsamplers.h) keeps one per
// node and estimates from it how much each subtree can contribute at a shading point.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/directioncone.h"
#include "pbrt_ext/util/vecmath.h"

#include <string>

namespace pbrt {

struct LightBounds {
    Bounds3f bounds;
    Vector3f w;               // the axis of the emitters' normals (unit)
    Float phi = 0;            // an upper bound of the emitted power
    Float cosTheta_o = 1;     // the normals lie within acos(cosTheta_o) of w
    Float cosTheta_e = 0;     // each surface emits within acos(cosTheta_e) of its normal
    bool twoSided = false;    // emits along -normal too

    LightBounds() = default;
    LightBounds(const Bounds3f &bounds, Vector3f w, Float phi, Float cosTheta_o, Float cosTheta_e,
                bool twoSided)
        : bounds(bounds), w(Normalize(w)), phi(phi), cosTheta_o(cosTheta_o),
          cosTheta_e(cosTheta_e), twoSided(twoSided) {}

    Point3f Centroid() const { return (bounds.pMin + bounds.pMax) / 2; }

    // The terms of Importance that depend on the bounds alone. The BVH light sampler keeps them
    // in its nodes, since it asks two nodes' importance per level at every shading point, and
    // these are three of its square roots.
    struct Constants {
        explicit Constants(const LightBounds &lb);
        Point3f centroid;
        Float halfDiagonal;     // the clamp of the squared distance
        Point3f sphereCenter;   // the bounding sphere of BoundSubtendedDirections
        Float sphereRadius;
        Float sinTheta_o;
    };

    // An estimate, conservative in direction, of what the lights could contribute at p (surface
    // normal n; zero n for a point in a medium): phi over the clamped squared distance, times the
    // cosine of the smallest angle between the emission cone and the directions to p, times the
    // smallest incident cosine at p. Zero only where no light of the bounds can reach p's side.
    Float Importance(Point3f p, Normal3f n) const { return Importance(p, n, Constants(*this)); }
    // The same, to the last bit, with the constants of these bounds worked out before.
    Float Importance(Point3f p, Normal3f n, const Constants &k) const;

    std::string ToString() const;
};

// What a light without bounds (distant, infinite) gives a surface, in the units of
// LightBounds::Importance, so that the BVH light sampler can weigh it against its tree: pi
// times irradiance, which is what Importance gives for a small area light (phi = pi L area). A
// distant light's irradiance is its radiance times the cosine to its direction; an infinite
// light's, averaged over the orientations of the surface, is pi times its mean radiance.
struct UnboundedLightImportance {
    Float irradiance = 0;  // a distant light's at normal incidence; an infinite light's average
    Vector3f w;            // unit, toward a distant light; zero for an infinite light

    // At a surface of normal n (zero n for a point in a medium); either side, as Importance.
    Float Importance(Normal3f n) const {
        if (w == Vector3f(0, 0, 0) || n == Normal3f(0, 0, 0))
            return Pi * irradiance;
        return Pi * irradiance * AbsDot(w, Vector3f(n));
    }
};

// Bounds of both; bounds without power leave the other unchanged.
LightBounds Union(const LightBounds &a, const LightBounds &b);

}  // namespace pbrt
