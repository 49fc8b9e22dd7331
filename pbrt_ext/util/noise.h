// Perlin noise as pbrt-v4 computes it (util/noise.h): gradient noise on the integer lattice
// with Perlin's quintic fade, the lattice hashed through Perlin's permutation table, and
// pbrt-v4's choice of the 16 gradients. Its value at a point matches pbrt-v4's, so that the
// cloud medium and the procedural textures make pbrt-v4's patterns.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/vecmath.h"

namespace pbrt {

// Noise in [-1, 1], 0 at every lattice point; periodic with period 256.
Float Noise(Float x, Float y, Float z);
inline Float Noise(Point3f p) { return Noise(p.x, p.y, p.z); }

// The gradient of Noise by forward differences of 0.01 (pbrt-v4's DNoise).
Vector3f DNoise(Point3f p);

// Fractional Brownian motion: octaves of Noise at frequencies 1.99^i and weights omega^i, as
// many as the footprint (dpdx, dpdy) resolves, at most maxOctaves (pbrt-v4's FBm).
Float FBm(Point3f p, Vector3f dpdx, Vector3f dpdy, Float omega, int maxOctaves);
// The same sum of |Noise| (pbrt-v4's Turbulence), unresolved octaves at their mean 0.2.
Float Turbulence(Point3f p, Vector3f dpdx, Vector3f dpdy, Float omega, int maxOctaves);

}  // namespace pbrt
