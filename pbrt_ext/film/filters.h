// Pixel reconstruction filters (pbrt-v4's filters.h, reduced to box, gaussian, mitchell and
// triangle), with pbrt-v4's filter importance sampling: the film never splats a sample over
// several pixels; instead each camera sample is offset from its pixel center by a point drawn
// from the filter, and carries the weight f(p) / pdf(p).
//
// Box and triangle are sampled exactly (weight 1). Gaussian and Mitchell are sampled from a
// tabulated PiecewiseConstant2D of |f| over the filter's support (FilterSampler); the weight is
// then the table's value over its density, constant in magnitude and negative in Mitchell's
// negative lobes. Positions p are offsets from the pixel center, in pixels.
//
// Host types: the tabulated samplers own heap tables (as pbrt-v4's do through its allocator).
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/vecmath.h"

#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace pbrt {

struct FilterSample {
    Point2f p;
    Float weight;
};

// The normal density, and its integral over [x0, x1].
PBRT_CPU_GPU inline Float Gaussian(Float x, Float mu = 0, Float sigma = 1) {
    return 1 / std::sqrt(2 * Pi * sigma * sigma) * std::exp(-Sqr(x - mu) / (2 * sigma * sigma));
}
PBRT_CPU_GPU inline Float GaussianIntegral(Float x0, Float x1, Float mu = 0, Float sigma = 1) {
    Float sigmaRoot2 = sigma * Sqrt2;
    return 0.5f * (std::erf((mu - x0) / sigmaRoot2) - std::erf((mu - x1) / sigmaRoot2));
}

// A tabulated sampler for filters without an analytic inverse: 32 cells per pixel of radius
// along each axis (pbrt-v4's resolution), each holding the filter at its center.
class FilterSampler {
  public:
    template <typename F>
    explicit FilterSampler(const F &filter);

    FilterSample Sample(Point2f u) const {
        Float pdf;
        Point2i pi;
        Point2f p = distrib.Sample(u, &pdf, &pi);
        return FilterSample{p, f[size_t(pi.y) * nx + pi.x] / pdf};
    }

  private:
    int nx, ny;
    std::vector<Float> f;
    PiecewiseConstant2D distrib;
};

class BoxFilter {
  public:
    explicit BoxFilter(Vector2f radius = Vector2f(0.5f, 0.5f)) : radius(radius) {}

    static constexpr const char *Name() { return "box"; }
    Vector2f Radius() const { return radius; }
    Float Evaluate(Point2f p) const { return Evaluate1D(0, p.x) * Evaluate1D(1, p.y); }
    Float Evaluate1D(int axis, Float v) const { return std::abs(v) <= radius[axis] ? 1 : 0; }
    Float Integral() const { return 4 * radius.x * radius.y; }
    FilterSample Sample(Point2f u) const {
        return {Point2f(Lerp(u[0], -radius.x, radius.x), Lerp(u[1], -radius.y, radius.y)), 1};
    }
    std::string ToString() const;

  private:
    Vector2f radius;
};

// A Gaussian with its value at the radius subtracted, so it falls to zero there.
class GaussianFilter {
  public:
    explicit GaussianFilter(Vector2f radius = Vector2f(1.5f, 1.5f), Float sigma = 0.5f)
        : radius(radius), sigma(sigma), expX(Gaussian(radius.x, 0, sigma)),
          expY(Gaussian(radius.y, 0, sigma)), sampler(*this) {}

    static constexpr const char *Name() { return "gaussian"; }
    Vector2f Radius() const { return radius; }
    Float Evaluate(Point2f p) const { return Evaluate1D(0, p.x) * Evaluate1D(1, p.y); }
    Float Evaluate1D(int axis, Float v) const {
        return std::max<Float>(0, Gaussian(v, 0, sigma) - (axis == 0 ? expX : expY));
    }
    Float Integral() const {
        return (GaussianIntegral(-radius.x, radius.x, 0, sigma) - 2 * radius.x * expX) *
               (GaussianIntegral(-radius.y, radius.y, 0, sigma) - 2 * radius.y * expY);
    }
    FilterSample Sample(Point2f u) const { return sampler.Sample(u); }
    std::string ToString() const;

  private:
    Vector2f radius;
    Float sigma, expX, expY;
    FilterSampler sampler;
};

// Mitchell and Netravali's cubic (SIGGRAPH 1988) over [-2, 2], stretched to the radius; b and c
// trade blur against ringing (b = c = 1/3 is their recommendation).
class MitchellFilter {
  public:
    explicit MitchellFilter(Vector2f radius = Vector2f(2, 2), Float b = 1.f / 3, Float c = 1.f / 3)
        : radius(radius), b(b), c(c), sampler(*this) {}

    static constexpr const char *Name() { return "mitchell"; }
    Vector2f Radius() const { return radius; }
    Float Evaluate(Point2f p) const { return Evaluate1D(0, p.x) * Evaluate1D(1, p.y); }
    Float Evaluate1D(int axis, Float v) const { return Mitchell1D(2 * v / radius[axis]); }
    // The 1D cubic integrates to 1 over [-2, 2] for any b, c.
    Float Integral() const { return radius.x * radius.y / 4; }
    FilterSample Sample(Point2f u) const { return sampler.Sample(u); }
    std::string ToString() const;

  private:
    Float Mitchell1D(Float x) const {
        x = std::abs(x);
        if (x <= 1)
            return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) *
                   (1.f / 6);
        if (x <= 2)
            return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x +
                    (8 * b + 24 * c)) *
                   (1.f / 6);
        return 0;
    }

    Vector2f radius;
    Float b, c;
    FilterSampler sampler;
};

class TriangleFilter {
  public:
    explicit TriangleFilter(Vector2f radius = Vector2f(2, 2)) : radius(radius) {}

    static constexpr const char *Name() { return "triangle"; }
    Vector2f Radius() const { return radius; }
    Float Evaluate(Point2f p) const { return Evaluate1D(0, p.x) * Evaluate1D(1, p.y); }
    Float Evaluate1D(int axis, Float v) const { return std::max<Float>(0, radius[axis] - std::abs(v)); }
    Float Integral() const { return Sqr(radius.x) * Sqr(radius.y); }
    // Each axis is a tent: the sample picks a half by u, then a linear ramp within it.
    FilterSample Sample(Point2f u) const {
        return {Point2f(radius.x * SampleUnitTent(u[0]), radius.y * SampleUnitTent(u[1])), 1};
    }
    std::string ToString() const;

  private:
    static Float SampleUnitTent(Float u) {
        if (u < 0.5f) return -1 + SampleLinear(std::min(2 * u, OneMinusEpsilon), 0, 1);
        return SampleLinear(std::min(2 * (u - 0.5f), OneMinusEpsilon), 1, 0);
    }

    Vector2f radius;
};

template <typename F>
FilterSampler::FilterSampler(const F &filter)
    : nx(std::max(1, int(32 * filter.Radius().x))), ny(std::max(1, int(32 * filter.Radius().y))),
      f(size_t(nx) * ny) {
    Bounds2f domain(Point2f(-filter.Radius().x, -filter.Radius().y),
                    Point2f(filter.Radius().x, filter.Radius().y));
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x)
            f[size_t(y) * nx + x] = filter.Evaluate(domain.Lerp(Point2f((x + 0.5f) / nx, (y + 0.5f) / ny)));
    distrib = PiecewiseConstant2D(f, nx, ny, domain);
}

// The closed set of filters.
class Filter {
    using Variant = std::variant<BoxFilter, GaussianFilter, MitchellFilter, TriangleFilter>;

  public:
    template <typename F>
        requires std::is_constructible_v<Variant, F> && (!std::is_same_v<std::remove_cvref_t<F>, Filter>)
    Filter(F &&f) : filter(std::forward<F>(f)) {}
    Filter() : filter(GaussianFilter()) {}  // pbrt-v4's default

    Vector2f Radius() const {
        return std::visit([](const auto &f) { return f.Radius(); }, filter);
    }
    Float Evaluate(Point2f p) const {
        return std::visit([&](const auto &f) { return f.Evaluate(p); }, filter);
    }
    // Every filter is separable: Evaluate(p) is Evaluate1D(0, p.x) * Evaluate1D(1, p.y).
    Float Evaluate1D(int axis, Float v) const {
        return std::visit([&](const auto &f) { return f.Evaluate1D(axis, v); }, filter);
    }
    Float Integral() const {
        return std::visit([](const auto &f) { return f.Integral(); }, filter);
    }
    FilterSample Sample(Point2f u) const {
        return std::visit([&](const auto &f) { return f.Sample(u); }, filter);
    }
    const char *Name() const {
        return std::visit([](const auto &f) { return f.Name(); }, filter);
    }
    std::string ToString() const {
        return std::visit([](const auto &f) { return f.ToString(); }, filter);
    }

  private:
    Variant filter;
};

}  // namespace pbrt
