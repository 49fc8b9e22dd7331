// pbrt_ext: sample warps, their densities and their inverses (pbrt-v4's util/sampling.h, reduced).
// Every warp maps [0,1)^k onto its domain and has an Invert...Sample that maps a point of the
// domain back to the u that produces it, so that round trips can be tested.
#pragma once

#include <pbrt_ext/pbrt.h>
#include <pbrt_ext/util/math.h>
#include <pbrt_ext/util/vecmath.h>

#include <algorithm>
#include <cmath>

namespace pbrt {

// Azimuth of (x, y) in [0, 2pi), as u[1] of the warps below measures it.
namespace detail {
PBRT_CPU_GPU inline Float Azimuth(Float x, Float y) {
    Float phi = std::atan2(y, x);
    return (phi < 0) ? phi + 2 * Pi : phi;
}
}  // namespace detail

// Uniform over the hemisphere z >= 0: z is uniform in [0, 1] (Archimedes), phi uniform.
PBRT_CPU_GPU inline Vector3f SampleUniformHemisphere(Point2f u) {
    Float z = u[0];
    Float r = SafeSqrt(1 - Sqr(z));
    Float phi = 2 * Pi * u[1];
    return Vector3f(r * std::cos(phi), r * std::sin(phi), z);
}
PBRT_CPU_GPU inline Float UniformHemispherePDF() {
    return Inv2Pi;
}
PBRT_CPU_GPU inline Point2f InvertUniformHemisphereSample(Vector3f w) {
    return Point2f(w.z, detail::Azimuth(w.x, w.y) * Inv2Pi);
}

// Uniform over the sphere: z uniform in [-1, 1].
PBRT_CPU_GPU inline Vector3f SampleUniformSphere(Point2f u) {
    Float z = 1 - 2 * u[0];
    Float r = SafeSqrt(1 - Sqr(z));
    Float phi = 2 * Pi * u[1];
    return Vector3f(r * std::cos(phi), r * std::sin(phi), z);
}
PBRT_CPU_GPU inline Float UniformSpherePDF() {
    return Inv4Pi;
}
PBRT_CPU_GPU inline Point2f InvertUniformSphereSample(Vector3f w) {
    return Point2f((1 - w.z) / 2, detail::Azimuth(w.x, w.y) * Inv2Pi);
}

// Shirley-Chiu concentric map: squares around the centre of [-1,1]^2 go to circles, so
// strata keep their shape better than with the polar map. Uniform density 1/pi on the disk.
PBRT_CPU_GPU inline Point2f SampleUniformDiskConcentric(Point2f u) {
    Point2f uOffset = 2 * u - Vector2f(1, 1);
    if (uOffset.x == 0 && uOffset.y == 0) return Point2f(0, 0);
    Float r, theta;
    if (std::abs(uOffset.x) > std::abs(uOffset.y)) {
        r = uOffset.x;
        theta = PiOver4 * (uOffset.y / uOffset.x);
    } else {
        r = uOffset.y;
        theta = PiOver2 - PiOver4 * (uOffset.x / uOffset.y);
    }
    return Point2f(r * std::cos(theta), r * std::sin(theta));
}
// The forward map sends the wedge |x| > |y| of the square to the disk wedge |x| > |y| (and the
// other wedge likewise); within a wedge, the signed radius and tan of the angle off its axis
// give the square coordinates back.
PBRT_CPU_GPU inline Point2f InvertUniformDiskConcentricSample(Point2f p) {
    if (p.x == 0 && p.y == 0) return Point2f(0.5f, 0.5f);
    Float r = std::sqrt(Sqr(p.x) + Sqr(p.y));
    Point2f uOffset;
    if (std::abs(p.x) > std::abs(p.y)) {
        uOffset.x = std::copysign(r, p.x);
        uOffset.y = uOffset.x * std::atan(p.y / p.x) / PiOver4;
    } else {
        uOffset.y = std::copysign(r, p.y);
        uOffset.x = uOffset.y * std::atan(p.x / p.y) / PiOver4;
    }
    return Point2f((uOffset.x + 1) / 2, (uOffset.y + 1) / 2);
}

// Polar map: r = sqrt(u0) makes the area density uniform.
PBRT_CPU_GPU inline Point2f SampleUniformDiskPolar(Point2f u) {
    Float r = std::sqrt(u[0]);
    Float theta = 2 * Pi * u[1];
    return Point2f(r * std::cos(theta), r * std::sin(theta));
}
PBRT_CPU_GPU inline Point2f InvertUniformDiskPolarSample(Point2f p) {
    return Point2f(Sqr(p.x) + Sqr(p.y), detail::Azimuth(p.x, p.y) * Inv2Pi);
}

// Malley's method: a uniform disk point lifted onto the hemisphere has density cos(theta)/pi.
PBRT_CPU_GPU inline Vector3f SampleCosineHemisphere(Point2f u) {
    Point2f d = SampleUniformDiskConcentric(u);
    Float z = SafeSqrt(1 - Sqr(d.x) - Sqr(d.y));
    return Vector3f(d.x, d.y, z);
}
PBRT_CPU_GPU inline Float CosineHemispherePDF(Float cosTheta) {
    return cosTheta * InvPi;
}
PBRT_CPU_GPU inline Point2f InvertCosineHemisphereSample(Vector3f w) {
    return InvertUniformDiskConcentricSample(Point2f(w.x, w.y));
}

// Density on [0, 1] proportional to the line from a (at 0) to b (at 1); a, b >= 0, not both 0.
// The CDF is x (a (2 - x) + b x) / (a + b); its quadratic is solved in the form without
// cancellation when a is close to b.
PBRT_CPU_GPU inline Float SampleLinear(Float u, Float a, Float b) {
    if (u == 0 && a == 0) return 0;
    Float x = u * (a + b) / (a + std::sqrt(Lerp(u, Sqr(a), Sqr(b))));
    return std::min(x, OneMinusEpsilon);
}
PBRT_CPU_GPU inline Float LinearPDF(Float x, Float a, Float b) {
    if (x < 0 || x > 1) return 0;
    return 2 * Lerp(x, a, b) / (a + b);
}
PBRT_CPU_GPU inline Float InvertLinearSample(Float x, Float a, Float b) {
    return x * (a * (2 - x) + b * x) / (a + b);
}

// Multiple importance sampling weights for strategy f (nf samples) against g (ng samples).
// Where both densities vanish the sample cannot occur; weight 0 keeps the estimate finite.
PBRT_CPU_GPU inline Float BalanceHeuristic(int nf, Float fPdf, int ng, Float gPdf) {
    Float f = nf * fPdf, g = ng * gPdf;
    if (IsInf(f)) return 1;
    return (f > 0) ? f / (f + g) : 0;
}
PBRT_CPU_GPU inline Float PowerHeuristic(int nf, Float fPdf, int ng, Float gPdf) {
    Float f = nf * fPdf, g = ng * gPdf;
    if (IsInf(Sqr(f))) return 1;
    return (f > 0) ? Sqr(f) / (Sqr(f) + Sqr(g)) : 0;
}

}  // namespace pbrt
