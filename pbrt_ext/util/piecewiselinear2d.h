// pbrt_ext: a piecewise-bilinear density on [0, 1]^2, optionally conditioned on parameters
// (pbrt-v4's PiecewiseLinear2D, itself Mitsuba's Marginal2D, from Dupuy and Jakob, "An Adaptive
// Parameterization for Efficient Material Acquisition and Rendering", SIGGRAPH Asia 2018), which
// the measured BRDF samples and evaluates.
//
// The density is given at the nodes of an xSize x ySize grid over [0, 1]^2 and is bilinear in each
// cell. Sample() inverts its marginal in y (a density linear in each row strip) and then its
// conditional in x at that y (linear in each cell), both by solving a quadratic: the map from
// [0, 1]^2 is continuous and exact for the bilinear density. Invert() is its inverse.
//
// Parameters: with Dimension > 0 there is one such grid (a slice) per combination of parameter
// values; data holds the slices with the first parameter outermost. A lookup between parameter
// values interpolates the slices (the density, its row sums and its cumulative sums) linearly in
// each parameter, which is exactly the mixture of the neighbouring slices' distributions, so that
// Sample() and Evaluate() agree for any parameter. Outside a parameter's range the nearest value's
// slice is used.
//
// Differs from pbrt-v4: the stored values are densities (they integrate to 1 over [0, 1]^2, or are
// the raw values when not normalized) rather than values in units of a grid cell, and a slice that
// is zero everywhere becomes uniform instead of dividing by zero (a measured table may hold one at
// an angle it has no light for; the BRDF is zero there, so how such samples are spread does not
// matter).
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace pbrt {

struct PLSample {
    Point2f p;
    Float pdf;
};

template <int Dimension>
class PiecewiseLinear2D {
  public:
    using Params = std::array<Float, Dimension>;

    PiecewiseLinear2D() = default;
    // data: one xSize x ySize grid (row-major, y outer) per combination of paramValues (first
    // parameter outermost); paramValues[d] increasing. normalize: scale each slice to a density
    // (and build what sampling needs); otherwise Evaluate() interpolates the raw values. Throws
    // std::invalid_argument for sizes below 2 x 2, an empty or decreasing parameter, or negative
    // or non-finite data where a density is asked for.
    PiecewiseLinear2D(const float *data, int xSize, int ySize,
                      std::array<std::vector<float>, Dimension> paramValues, bool normalize)
        : xSize(xSize), ySize(ySize), paramValues(std::move(paramValues)) {
        if (xSize < 2 || ySize < 2)
            throw std::invalid_argument("a piecewise-linear table needs at least 2 x 2 values");
        size_t slices = 1;
        for (int d = Dimension - 1; d >= 0; --d) {
            const std::vector<float> &v = this->paramValues[size_t(d)];
            if (v.empty()) throw std::invalid_argument("a parameter has no values");
            for (size_t i = 1; i < v.size(); ++i)
                if (!(v[i] > v[i - 1]))
                    throw std::invalid_argument("a parameter's values do not increase");
            paramStride[size_t(d)] = v.size() > 1 ? uint32_t(slices) : 0;
            slices *= v.size();
        }
        const size_t n = size_t(xSize) * size_t(ySize);
        values.assign(data, data + slices * n);
        if (!normalize) return;
        marginalCDF.resize(slices * size_t(ySize));
        conditionalCDF.resize(slices * n);
        for (size_t s = 0; s < slices; ++s) BuildSlice(s);
    }

    // A point drawn from the density (for the parameters) by the uniform u, and its density.
    PLSample Sample(Point2f u, const Params &param) const {
        const Weights w = ParamWeights(param);
        u[0] = Clamp(u[0], 1 - OneMinusEpsilon, OneMinusEpsilon);
        u[1] = Clamp(u[1], 1 - OneMinusEpsilon, OneMinusEpsilon);
        const size_t n = size_t(xSize) * size_t(ySize);
        const Float dx = Float(1) / Float(xSize - 1), dy = Float(1) / Float(ySize - 1);

        // The row strip, then the fraction t across it, where the row sums are linear.
        const size_t marginal = w.slice * size_t(ySize);
        int row = detail::FindInterval(ySize, [&](int i) {
            return Lookup(marginalCDF, marginal + size_t(i), size_t(ySize), w) <= u[1];
        });
        Float uy = (u[1] - Lookup(marginalCDF, marginal + size_t(row), size_t(ySize), w)) / dy;
        const size_t rowStart = w.slice * n + size_t(row) * size_t(xSize);
        Float r0 = Lookup(conditionalCDF, rowStart + size_t(xSize) - 1, n, w);
        Float r1 = Lookup(conditionalCDF, rowStart + 2 * size_t(xSize) - 1, n, w);
        Float t = SolveLinearDensity(r0, r1, uy);

        // The column at that t, then the fraction s across its cell.
        Float ux = u[0] * Lerp(t, r0, r1);
        auto conditional = [&](int i) {
            return Lerp(t, Lookup(conditionalCDF, rowStart + size_t(i), n, w),
                        Lookup(conditionalCDF, rowStart + size_t(xSize) + size_t(i), n, w));
        };
        int col = detail::FindInterval(xSize, [&](int i) { return conditional(i) <= ux; });
        ux = (ux - conditional(col)) / dx;
        const size_t cell = rowStart + size_t(col);
        Float c0 = Lerp(t, Lookup(values, cell, n, w), Lookup(values, cell + size_t(xSize), n, w));
        Float c1 =
            Lerp(t, Lookup(values, cell + 1, n, w), Lookup(values, cell + size_t(xSize) + 1, n, w));
        Float s = SolveLinearDensity(c0, c1, ux);
        return {Point2f((Float(col) + s) * dx, (Float(row) + t) * dy), Lerp(s, c0, c1)};
    }

    // The u that Sample() maps to p, and the density at p.
    PLSample Invert(Point2f p, const Params &param) const {
        const Weights w = ParamWeights(param);
        const Cell c = CellOf(p, w);
        const size_t n = size_t(xSize) * size_t(ySize);
        const Float dx = Float(1) / Float(xSize - 1), dy = Float(1) / Float(ySize - 1);
        Float c0 = Lerp(c.t, c.v00, c.v01), c1 = Lerp(c.t, c.v10, c.v11);
        Float pdf = Lerp(c.s, c0, c1);

        const size_t rowStart = w.slice * n + size_t(c.y) * size_t(xSize);
        Float r0 = Lookup(conditionalCDF, rowStart + size_t(xSize) - 1, n, w);
        Float r1 = Lookup(conditionalCDF, rowStart + 2 * size_t(xSize) - 1, n, w);
        Float before = Lerp(c.t, Lookup(conditionalCDF, rowStart + size_t(c.x), n, w),
                            Lookup(conditionalCDF, rowStart + size_t(xSize) + size_t(c.x), n, w));
        Float ux = (before + dx * c.s * (c0 + c.s / 2 * (c1 - c0))) / Lerp(c.t, r0, r1);
        Float uy = Lookup(marginalCDF, w.slice * size_t(ySize) + size_t(c.y), size_t(ySize), w) +
                   dy * c.t * (r0 + c.t / 2 * (r1 - r0));
        return {Point2f(ux, uy), pdf};
    }

    // The density (or the raw values' bilinear interpolation) at p.
    Float Evaluate(Point2f p, const Params &param) const {
        const Weights w = ParamWeights(param);
        const Cell c = CellOf(p, w);
        return Lerp(c.t, Lerp(c.s, c.v00, c.v10), Lerp(c.s, c.v01, c.v11));
    }

    size_t BytesUsed() const {
        size_t bytes = sizeof(float) * (values.size() + marginalCDF.size() + conditionalCDF.size());
        for (const std::vector<float> &v : paramValues) bytes += sizeof(float) * v.size();
        return bytes;
    }

  private:
    // The slice below the parameters and the weights of the lower and upper value per parameter.
    struct Weights {
        size_t slice = 0;
        std::array<Float, 2 * Dimension + 1> w{};  // +1: no zero-length array for Dimension 0
    };
    // A grid cell and the point's fractions s (in x) and t (in y) across it, with its corners.
    struct Cell {
        int x, y;
        Float s, t, v00, v10, v01, v11;
    };

    Weights ParamWeights(const Params &param) const {
        Weights w;
        for (int d = 0; d < Dimension; ++d) {
            const std::vector<float> &v = paramValues[size_t(d)];
            if (v.size() == 1) {
                w.w[size_t(2 * d)] = 1;
                continue;
            }
            int i = detail::FindInterval(int(v.size()),
                                         [&](int k) { return v[size_t(k)] <= param[size_t(d)]; });
            Float f =
                Clamp((param[size_t(d)] - v[size_t(i)]) / (v[size_t(i) + 1] - v[size_t(i)]), 0, 1);
            if (!(f == f)) f = 0;  // a NaN parameter takes the first value
            w.w[size_t(2 * d)] = 1 - f;
            w.w[size_t(2 * d) + 1] = f;
            w.slice += paramStride[size_t(d)] * size_t(i);
        }
        return w;
    }

    // table[index] interpolated across the parameters: the 2^Dimension neighbouring slices
    // (sliceSize apart per unit of stride), weighted.
    Float Lookup(const std::vector<float> &table, size_t index, size_t sliceSize,
                 const Weights &w) const {
        Float sum = 0;
        for (int corner = 0; corner < (1 << Dimension); ++corner) {
            Float weight = 1;
            size_t i = index;
            for (int d = 0; d < Dimension; ++d) {
                bool upper = (corner >> d) & 1;
                weight *= w.w[size_t(2 * d) + upper];
                if (upper) i += paramStride[size_t(d)] * sliceSize;
            }
            if (weight != 0) sum += weight * table[i];
        }
        return sum;
    }

    Cell CellOf(Point2f p, const Weights &w) const {
        Float px = Clamp(p[0], 0, 1) * Float(xSize - 1), py = Clamp(p[1], 0, 1) * Float(ySize - 1);
        if (!(px == px)) px = 0;
        if (!(py == py)) py = 0;
        Cell c;
        c.x = std::min(int(px), xSize - 2);
        c.y = std::min(int(py), ySize - 2);
        c.s = px - Float(c.x);
        c.t = py - Float(c.y);
        const size_t n = size_t(xSize) * size_t(ySize);
        const size_t i = w.slice * n + size_t(c.y) * size_t(xSize) + size_t(c.x);
        c.v00 = Lookup(values, i, n, w);
        c.v10 = Lookup(values, i + 1, n, w);
        c.v01 = Lookup(values, i + size_t(xSize), n, w);
        c.v11 = Lookup(values, i + size_t(xSize) + 1, n, w);
        return c;
    }

    // The fraction x in [0, 1] where the integral of the density a (1 - x) + b x from 0 to x is
    // `area`: a root of (b - a) / 2 x^2 + a x - area, taken in the form that does not cancel.
    static Float SolveLinearDensity(Float a, Float b, Float area) {
        Float x = std::abs(a - b) < 1e-4f * (a + b)
                      ? 2 * area / (a + b)
                      : (a - std::sqrt(std::max<Float>(0, a * a - 2 * area * (a - b)))) / (a - b);
        return x == x ? Clamp(x, 0, 1) : 0;
    }

    // Scales slice s to a density and fills its cumulative sums (trapezoids, in double).
    void BuildSlice(size_t s) {
        const size_t n = size_t(xSize) * size_t(ySize);
        float *v = &values[s * n];
        for (size_t i = 0; i < n; ++i)
            if (!(v[i] >= 0) || std::isinf(v[i]))
                throw std::invalid_argument("a density table holds a negative or non-finite value");
        const double dx = 1.0 / (xSize - 1), dy = 1.0 / (ySize - 1);
        auto rowIntegral = [&](int y) {
            double sum = 0;
            for (int x = 0; x + 1 < xSize; ++x)
                sum += (double(v[size_t(y * xSize + x)]) + v[size_t(y * xSize + x + 1)]) / 2 * dx;
            return sum;
        };
        double total = 0;
        for (int y = 0; y + 1 < ySize; ++y) total += (rowIntegral(y) + rowIntegral(y + 1)) / 2 * dy;
        if (total > 0 && std::isfinite(total)) {
            for (size_t i = 0; i < n; ++i) v[i] = float(v[i] / total);
        } else {
            std::fill(v, v + n, 1.f);  // zero everywhere: uniform (see the file's comment)
        }
        float *conditional = &conditionalCDF[s * n];
        float *marginal = &marginalCDF[s * size_t(ySize)];
        double below = 0;
        for (int y = 0; y < ySize; ++y) {
            double sum = 0;
            conditional[size_t(y * xSize)] = 0;
            for (int x = 0; x + 1 < xSize; ++x) {
                sum += (double(v[size_t(y * xSize + x)]) + v[size_t(y * xSize + x + 1)]) / 2 * dx;
                conditional[size_t(y * xSize + x + 1)] = float(sum);
            }
            if (y > 0)
                below += (double(conditional[size_t(y * xSize - 1)]) +
                          conditional[size_t((y + 1) * xSize - 1)]) /
                         2 * dy;
            marginal[y] = float(below);
        }
    }

    int xSize = 0, ySize = 0;
    std::array<std::vector<float>, Dimension> paramValues;
    std::array<size_t, Dimension + 1>
        paramStride{};  // slices per step of each parameter (0: one value)
    std::vector<float> values, marginalCDF, conditionalCDF;
};

}  // namespace pbrt
