// pbrt_ext: sample warps, their densities and their inverses (pbrt-v4's util/sampling.h, reduced).
// Every warp maps [0,1)^k onto its domain and has an Invert...Sample that maps a point of the
// domain back to the u that produces it, so that round trips can be tested.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"

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

// The normal distribution of mean mu and deviation sigma, by inverting its CDF
// (mu + sigma sqrt(2) erf^-1(2u - 1)); u in (0, 1).
PBRT_CPU_GPU inline Float SampleNormal(Float u, Float mu = 0, Float sigma = 1) {
    return mu + Sqrt2 * sigma * ErfInv(2 * u - 1);
}
PBRT_CPU_GPU inline Float NormalPDF(Float x, Float mu = 0, Float sigma = 1) {
    return std::exp(-Sqr(x - mu) / (2 * Sqr(sigma))) / (sigma * std::sqrt(2 * Pi));
}
PBRT_CPU_GPU inline Float InvertNormalSample(Float x, Float mu = 0, Float sigma = 1) {
    return 0.5f * (1 + std::erf((x - mu) / (sigma * Sqrt2)));
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

// ---------------------------------------------------------------------------------------
// Cone and triangle warps, and tabulated distributions (added for lights, shapes, filters).
// These parts need <array> and <vector>; the includes sit here so the original header's
// prologue stays untouched.

#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/pstd.h"

#include <array>
#include <vector>

namespace pbrt {

// Uniform over the cone of directions within theta_max of +z: cos theta is uniform in
// [cosThetaMax, 1], which makes solid angle uniform for the same reason as on the sphere.
PBRT_CPU_GPU inline Vector3f SampleUniformCone(Point2f u, Float cosThetaMax) {
    Float cosTheta = (1 - u[0]) + u[0] * cosThetaMax;
    Float sinTheta = SafeSqrt(1 - Sqr(cosTheta));
    Float phi = u[1] * 2 * Pi;
    return SphericalDirection(sinTheta, cosTheta, phi);
}
PBRT_CPU_GPU inline Float UniformConePDF(Float cosThetaMax) {
    return 1 / (2 * Pi * (1 - cosThetaMax));
}
PBRT_CPU_GPU inline Point2f InvertUniformConeSample(Vector3f w, Float cosThetaMax) {
    return Point2f((1 - w.z) / (1 - cosThetaMax), detail::Azimuth(w.x, w.y) * Inv2Pi);
}

// Density on [0,1]^2 proportional to the bilinear interpolation of corner weights w (00, 10,
// 01, 11): v from its marginal, then u given v (pbrt-v4's SampleBilinear/BilinearPDF). Used to
// follow an area element (bilinear patches) or the cosine factor across an emitter's solid
// angle (spherical triangles and rectangles).
PBRT_CPU_GPU inline Point2f SampleBilinear(Point2f u, const std::array<Float, 4> &w) {
    Float y = SampleLinear(u[1], w[0] + w[1], w[2] + w[3]);
    Float x = SampleLinear(u[0], Lerp(y, w[0], w[2]), Lerp(y, w[1], w[3]));
    return Point2f(x, y);
}
PBRT_CPU_GPU inline Float BilinearPDF(Point2f p, const std::array<Float, 4> &w) {
    if (p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1)
        return 0;
    Float sum = w[0] + w[1] + w[2] + w[3];
    if (sum == 0)
        return 1;
    Float bilerp = (1 - p.x) * (1 - p.y) * w[0] + p.x * (1 - p.y) * w[1] + (1 - p.x) * p.y * w[2] +
                   p.x * p.y * w[3];
    return 4 * bilerp / sum;
}

// Barycentrics uniform over a triangle. The map folds the unit square onto the triangle
// along its diagonal without the square root of the classic warp, so neighbouring u stay
// neighbours (pbrt-v4, after Heitz's "A low-distortion map between triangle and square").
PBRT_CPU_GPU inline std::array<Float, 3> SampleUniformTriangle(Point2f u) {
    Float b0, b1;
    if (u[0] < u[1]) {
        b0 = u[0] / 2;
        b1 = u[1] - b0;
    } else {
        b1 = u[1] / 2;
        b0 = u[0] - b1;
    }
    return {b0, b1, 1 - b0 - b1};
}
// The two halves of the square meet where b0 = b1; each branch above is linear, so it
// inverts directly.
PBRT_CPU_GPU inline Point2f InvertUniformTriangleSample(const std::array<Float, 3> &b) {
    if (b[0] > b[1])
        return Point2f(b[0] + b[1], 2 * b[1]);
    return Point2f(2 * b[0], b[1] + b[0]);
}

// A piecewise-constant density on [min, max] proportional to |f| over n equal pieces
// (pbrt-v4's PiecewiseConstant1D). Sampling inverts the tabulated CDF, so it is exact and
// has an exact inverse. A function that is zero everywhere samples uniformly with pdf 0.
// f must not be empty.
// The tables live on the heap, so this and PiecewiseConstant2D are host types (pbrt-v4
// places them in device memory through its Allocator; this project has no GPU back end).
class PiecewiseConstant1D {
  public:
    PiecewiseConstant1D() = default;
    explicit PiecewiseConstant1D(pstd::span<const Float> f) : PiecewiseConstant1D(f, 0, 1) {}
    PiecewiseConstant1D(pstd::span<const Float> f, Float min, Float max)
        : func(f.begin(), f.end()), cdf(f.size() + 1), min(min), max(max) {
        // Negative values (a signed filter) are sampled by magnitude; callers weight by sign.
        for (Float &v : func)
            v = std::abs(v);
        size_t n = func.size();
        cdf[0] = 0;
        for (size_t i = 1; i <= n; ++i)
            cdf[i] = cdf[i - 1] + func[i - 1] * (max - min) / n;
        funcInt = cdf[n];
        for (size_t i = 1; i <= n; ++i)
            cdf[i] = funcInt > 0 ? cdf[i] / funcInt : Float(i) / Float(n);
        guide.resize(n + 1);
        for (size_t k = 0; k <= n; ++k)
            guide[k] = FindPiece(Float(k) / Float(n), 0, int(n) - 1);
    }

    Float Integral() const { return funcInt; }
    size_t size() const { return func.size(); }

    // x in [min, max]; *pdf is the density per unit x, *offset the piece x lies in.
    Float Sample(Float u, Float *pdf = nullptr, int *offset = nullptr) const {
        int o = FindPiece(u);
        if (offset)
            *offset = o;
        Float du = u - cdf[o];
        if (cdf[o + 1] - cdf[o] > 0)
            du /= cdf[o + 1] - cdf[o];
        if (pdf)
            *pdf = funcInt > 0 ? func[o] / funcInt : 0;
        return Lerp((o + du) / size(), min, max);
    }

    // The u that Sample maps to x; empty outside [min, max].
    pstd::optional<Float> Invert(Float x) const {
        if (!(x >= min && x <= max))
            return {};
        Float c = (x - min) / (max - min) * func.size();
        int offset = Clamp(int(c), 0, int(func.size()) - 1);
        return Lerp(c - offset, cdf[offset], cdf[offset + 1]);
    }

    std::vector<Float> func, cdf;  // |f|, and the CDF normalized to end at 1
    Float min = 0, max = 1;
    Float funcInt = 0;  // integral of |f| over [min, max]

  private:
    // The piece u falls in: the last i with cdf[i] <= u (0 for u below them all), as
    // FindInterval's bisection finds it over the pieces [first, last].
    int FindPiece(Float u, int first, int last) const {
        return first + detail::FindInterval(last - first + 2, [&](int i) { return cdf[first + i] <= u; });
    }
    // The same over all pieces, in a step or two: the piece lies between the guide's pieces at
    // the multiples of 1 / n around u (the CDF is monotone), a range that holds one or two
    // pieces for a smooth density, and the bisection runs over that range only. The camera
    // samples its filter this way twice per ray. The steps after it only act where u n rounded
    // across a multiple.
    int FindPiece(Float u) const {
        int n = int(size());
        if (!(u >= 0 && u < 1))
            return FindPiece(u, 0, n - 1);
        int k = std::min(int(u * n), n - 1);
        return detail::FindIntervalFrom(FindPiece(u, guide[k], guide[k + 1]), int(cdf.size()),
                                        [&](int i) { return cdf[i] <= u; });
    }

    std::vector<int> guide;  // guide[k]: FindPiece(k / n); n + 1 entries
};

// A piecewise-constant density over a rectangle, proportional to |f| on an nu x nv grid
// (f row-major: f[v * nu + u]); pbrt-v4's PiecewiseConstant2D. The second coordinate is
// drawn from the marginal over rows and the first from that row's conditional, so Sample
// is a bijection with Invert as its inverse and its density is exactly PDF.
class PiecewiseConstant2D {
  public:
    PiecewiseConstant2D() = default;
    PiecewiseConstant2D(pstd::span<const Float> f, int nu, int nv,
                        Bounds2f domain = Bounds2f(Point2f(0, 0), Point2f(1, 1)))
        : domain(domain) {
        pConditionalV.reserve(nv);
        for (int v = 0; v < nv; ++v)
            pConditionalV.emplace_back(f.subspan(size_t(v) * nu, nu), domain.pMin[0],
                                       domain.pMax[0]);
        std::vector<Float> marginalFunc(nv);
        for (int v = 0; v < nv; ++v)
            marginalFunc[v] = pConditionalV[v].Integral();
        pMarginal = PiecewiseConstant1D(marginalFunc, domain.pMin[1], domain.pMax[1]);
    }

    Float Integral() const { return pMarginal.Integral(); }
    int ResolutionU() const { return int(pConditionalV[0].size()); }
    int ResolutionV() const { return int(pMarginal.size()); }
    Bounds2f Domain() const { return domain; }

    // *pdf is the density per unit area of the domain; *offset the grid cell.
    Point2f Sample(Point2f u, Float *pdf = nullptr, Point2i *offset = nullptr) const {
        Float pdfs[2];
        int uv[2];
        Float d1 = pMarginal.Sample(u[1], &pdfs[1], &uv[1]);
        Float d0 = pConditionalV[uv[1]].Sample(u[0], &pdfs[0], &uv[0]);
        if (pdf)
            *pdf = pdfs[0] * pdfs[1];
        if (offset)
            *offset = Point2i(uv[0], uv[1]);
        return Point2f(d0, d1);
    }

    // Density at p, which is clamped into the domain.
    Float PDF(Point2f p) const {
        Vector2f o = domain.Offset(p);
        int iu = Clamp(int(o[0] * ResolutionU()), 0, ResolutionU() - 1);
        int iv = Clamp(int(o[1] * ResolutionV()), 0, ResolutionV() - 1);
        return Integral() > 0 ? pConditionalV[iv].func[iu] / Integral() : 0;
    }

    // The u that Sample maps to p; empty outside the domain.
    pstd::optional<Point2f> Invert(Point2f p) const {
        pstd::optional<Float> mInv = pMarginal.Invert(p[1]);
        if (!mInv)
            return {};
        Float o1 = domain.Offset(p)[1];
        int row = Clamp(int(o1 * ResolutionV()), 0, ResolutionV() - 1);
        pstd::optional<Float> cInv = pConditionalV[row].Invert(p[0]);
        if (!cInv)
            return {};
        return Point2f(*cInv, *mInv);
    }

  private:
    Bounds2f domain;
    std::vector<PiecewiseConstant1D> pConditionalV;
    PiecewiseConstant1D pMarginal;
};

}  // namespace pbrt
