// Sampling a tabulated function over a window of [0, 1]^2 (pbrt-v4's SummedAreaTable and
// WindowedPiecewiseConstant2D): the portal light samples the part of its image that a point sees
// through the portal, a rectangle that changes with the point.
//
// The function is piecewise constant on an nx x ny grid over [0, 1]^2, row-major (x fastest).
// Its integral over the corner rectangle [0, x] x [0, y] is bilinear in x and y within a cell, so
// interpolating the summed-area table bilinearly integrates over any rectangle exactly.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace pbrt {

class SummedAreaTable {
  public:
    SummedAreaTable(const std::vector<Float> &values, int nx, int ny) : nx(nx), ny(ny), sum(values.size()) {
        if (nx <= 0 || ny <= 0 || values.size() != size_t(nx) * size_t(ny))
            throw std::invalid_argument("SummedAreaTable: values do not fill an nx x ny grid");
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x)
                Sum(x, y) = double(values[size_t(y) * size_t(nx) + size_t(x)]) + (x > 0 ? Sum(x - 1, y) : 0) +
                            (y > 0 ? Sum(x, y - 1) : 0) - (x > 0 && y > 0 ? Sum(x - 1, y - 1) : 0);
    }

    // The integral over extent (inside [0, 1]^2), in the unit square's measure; never negative.
    Float Integral(Bounds2f extent) const {
        double s = (Lookup(extent.pMax.x, extent.pMax.y) - Lookup(extent.pMin.x, extent.pMax.y)) +
                   (Lookup(extent.pMin.x, extent.pMin.y) - Lookup(extent.pMax.x, extent.pMin.y));
        return Float(std::max(s / (double(nx) * ny), 0.0));
    }

  private:
    double &Sum(int x, int y) { return sum[size_t(y) * size_t(nx) + size_t(x)]; }
    // The sum over the cells below and left of the grid corner (x, y).
    double Corner(int x, int y) const {
        if (x <= 0 || y <= 0) return 0;
        x = std::min(x, nx);
        y = std::min(y, ny);
        return sum[size_t(y - 1) * size_t(nx) + size_t(x - 1)];
    }
    double Lookup(Float x, Float y) const {
        double fx = double(x) * nx, fy = double(y) * ny;
        int x0 = int(fx), y0 = int(fy);
        double dx = fx - x0, dy = fy - y0;
        return (1 - dx) * (1 - dy) * Corner(x0, y0) + dx * (1 - dy) * Corner(x0 + 1, y0) +
               (1 - dx) * dy * Corner(x0, y0 + 1) + dx * dy * Corner(x0 + 1, y0 + 1);
    }

    int nx, ny;
    std::vector<double> sum;
};

class WindowedPiecewiseConstant2D {
  public:
    WindowedPiecewiseConstant2D(std::vector<Float> f, int nx, int ny)
        : sat(f, nx, ny), func(std::move(f)), nx(nx), ny(ny) {}

    // A point of window b with density func / (its integral over b), per unit area of [0, 1]^2;
    // none where the function is zero over b.
    pstd::optional<Point2f> Sample(Point2f u, Bounds2f b, Float *pdf) const {
        Float bInt = sat.Integral(b);
        if (bInt == 0) return {};
        // x from the marginal over the window, then y from the window's column at x.
        auto Px = [&](Float x) {
            Bounds2f bx = b;
            bx.pMax.x = x;
            return sat.Integral(bx) / bInt;
        };
        Point2f p;
        p.x = SampleBisection(Px, u[0], b.pMin.x, b.pMax.x, nx);
        Bounds2f bCond(Point2f(std::floor(p.x * nx) / nx, b.pMin.y), Point2f(std::ceil(p.x * nx) / nx, b.pMax.y));
        if (bCond.pMin.x == bCond.pMax.x) bCond.pMax.x += Float(1) / nx;
        Float condInt = sat.Integral(bCond);
        if (condInt == 0) return {};
        auto Py = [&](Float y) {
            Bounds2f by = bCond;
            by.pMax.y = y;
            return sat.Integral(by) / condInt;
        };
        p.y = SampleBisection(Py, u[1], b.pMin.y, b.pMax.y, ny);
        *pdf = Eval(p) / bInt;
        return p;
    }

    // Zero outside the window (pbrt-v4's does not check, so its density there is not zero).
    Float PDF(Point2f p, Bounds2f b) const {
        if (!Inside(p, b)) return 0;
        Float bInt = sat.Integral(b);
        return bInt == 0 ? 0 : Eval(p) / bInt;
    }

  private:
    // The x in [min, max] where the CDF P reaches u: bisection down to one cell of n, then the
    // CDF's linear inverse within it.
    template <typename CDF>
    static Float SampleBisection(CDF P, Float u, Float min, Float max, int n) {
        while (std::ceil(n * max) - std::floor(n * min) > 1) {
            Float mid = (min + max) / 2;
            if (P(mid) > u)
                max = mid;
            else
                min = mid;
        }
        Float pMin = P(min), pMax = P(max);
        Float t = pMax > pMin ? (u - pMin) / (pMax - pMin) : 0;
        return Clamp(Lerp(t, min, max), min, max);
    }

    Float Eval(Point2f p) const {
        int x = std::min(int(p[0] * nx), nx - 1), y = std::min(int(p[1] * ny), ny - 1);
        return func[size_t(y) * size_t(nx) + size_t(x)];
    }

    SummedAreaTable sat;
    std::vector<Float> func;
    int nx, ny;
};

}  // namespace pbrt
