// pbrt_ext: Clarberg's equal-area octahedral map between the unit square and the sphere
// (pbrt-v4's EqualAreaSquareToSphere and friends in util/math.h; P. Clarberg, "Fast
// equal-area mapping of the (hemi)sphere using SIMD", JGT 2008). Equal area means that a
// region of the square of area A maps to solid angle 4 pi A, so a density over the square
// becomes a density over directions by dividing by 4 pi; that is why environment maps are
// stored in this parameterization. The upper hemisphere is the inner diamond |u|+|v| <= 1
// of [-1,1]^2, the lower one the four corner triangles, folded over the diamond's edges.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"

#include <cmath>
#include <utility>

namespace pbrt {

PBRT_CPU_GPU inline Vector3f EqualAreaSquareToSphere(Point2f p) {
    Float u = 2 * p.x - 1, v = 2 * p.y - 1;
    Float up = std::abs(u), vp = std::abs(v);
    // Distance from the diamond's edge, positive inside (upper hemisphere); r is the
    // radial coordinate that grows from the pole (r = 0) to the equator (r = 1).
    Float signedDistance = 1 - (up + vp);
    Float r = 1 - std::abs(signedDistance);
    // Position along the diamond's edge in the first quadrant, as an angle in [0, pi/2].
    Float phi = (r == 0 ? 1 : (vp - up) / r + 1) * PiOver4;
    Float z = std::copysign(1 - Sqr(r), signedDistance);
    Float cosPhi = std::copysign(std::cos(phi), u);
    Float sinPhi = std::copysign(std::sin(phi), v);
    Float s = r * SafeSqrt(2 - Sqr(r));  // = sin(theta), since 1 - z^2 = r^2 (2 - r^2)
    return Vector3f(cosPhi * s, sinPhi * s, z);
}

// The inverse for unit d: fold d into the first octant, invert there, unfold.
PBRT_CPU_GPU inline Point2f EqualAreaSphereToSquare(Vector3f d) {
    Float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
    Float r = SafeSqrt(1 - z);
    Float a = std::max(x, y), b = std::min(x, y);
    b = a == 0 ? 0 : b / a;
    // phi / (pi/2) measured from the nearer of the x and y axes.
    Float phi = std::atan(b) * (2 / Pi);
    if (x < y)
        phi = 1 - phi;
    Float v = phi * r, u = r - v;
    if (d.z < 0) {
        // Lower hemisphere: reflect across the diamond's edge u + v = 1.
        std::swap(u, v);
        u = 1 - u;
        v = 1 - v;
    }
    u = std::copysign(u, d.x);
    v = std::copysign(v, d.y);
    return Point2f((u + 1) / 2, (v + 1) / 2);
}

// Maps a pixel index just outside an equal-area square image back inside it. Across each
// edge of the square the sphere continues mirrored (the fold of the lower hemisphere), so
// stepping off one edge lands on the same edge with the other coordinate reflected.
PBRT_CPU_GPU inline Point2i WrapEqualAreaSquare(Point2i uv, Point2i resolution) {
    if (uv[0] < 0) {
        uv[0] = -uv[0];
        uv[1] = resolution[1] - 1 - uv[1];
    } else if (uv[0] >= resolution[0]) {
        uv[0] = 2 * resolution[0] - 1 - uv[0];
        uv[1] = resolution[1] - 1 - uv[1];
    }
    if (uv[1] < 0) {
        uv[0] = resolution[0] - 1 - uv[0];
        uv[1] = -uv[1];
    } else if (uv[1] >= resolution[1]) {
        uv[0] = resolution[0] - 1 - uv[0];
        uv[1] = 2 * resolution[1] - 1 - uv[1];
    }
    return uv;
}

// The same for a point of the square's continuous parameterization, [0, 1]^2.
PBRT_CPU_GPU inline Point2f WrapEqualAreaSquare(Point2f uv) {
    if (uv[0] < 0) {
        uv[0] = -uv[0];
        uv[1] = 1 - uv[1];
    } else if (uv[0] > 1) {
        uv[0] = 2 - uv[0];
        uv[1] = 1 - uv[1];
    }
    if (uv[1] < 0) {
        uv[0] = 1 - uv[0];
        uv[1] = -uv[1];
    } else if (uv[1] > 1) {
        uv[0] = 1 - uv[0];
        uv[1] = 2 - uv[1];
    }
    return uv;
}

}  // namespace pbrt
