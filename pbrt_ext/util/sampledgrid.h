// Values on a regular 3D grid over [0, 1]^3, looked up with trilinear interpolation (pbrt-v4's
// SampledGrid in util/containers.h): sample (x, y, z) sits at the centre of its cell,
// ((x + 1/2) / nx, ...), and lookups between the outer samples and the box's faces fade
// towards zero, as pbrt-v4's do, so that a grid medium has no hard edge.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>
#include <vector>

namespace pbrt {

template <typename T>
class SampledGrid {
  public:
    SampledGrid() = default;
    // values in x-fastest order: values[(z * ny + y) * nx + x]; nx * ny * nz of them.
    SampledGrid(std::vector<T> values, int nx, int ny, int nz)
        : values(std::move(values)), nx(nx), ny(ny), nz(nz) {
        assert(size_t(nx) * ny * nz == this->values.size());
    }

    int XSize() const { return nx; }
    int YSize() const { return ny; }
    int ZSize() const { return nz; }
    size_t BytesAllocated() const { return values.size() * sizeof(T); }

    // The converted sample at integer coordinates, or zero outside the grid.
    template <typename F>
    auto Lookup(Point3i p, F convert) const {
        using Result = decltype(convert(values[0]));
        if (p.x < 0 || p.x >= nx || p.y < 0 || p.y >= ny || p.z < 0 || p.z >= nz)
            return Result(0);
        return convert(values[(size_t(p.z) * ny + p.y) * nx + p.x]);
    }

    // Trilinear interpolation at p in [0, 1]^3, each sample passed through convert first.
    template <typename F>
    auto Lookup(Point3f p, F convert) const {
        Point3f ps(p.x * nx - .5f, p.y * ny - .5f, p.z * nz - .5f);
        Point3i pi(int(std::floor(ps.x)), int(std::floor(ps.y)), int(std::floor(ps.z)));
        Float dx = ps.x - pi.x, dy = ps.y - pi.y, dz = ps.z - pi.z;
        auto at = [&](int x, int y, int z) {
            return Lookup(Point3i(pi.x + x, pi.y + y, pi.z + z), convert);
        };
        // Lerp for any T with scalar products: Float, or a SampledSpectrum after convert.
        auto lerp = [](Float t, auto a, auto b) { return (1 - t) * a + t * b; };
        auto d00 = lerp(dx, at(0, 0, 0), at(1, 0, 0));
        auto d10 = lerp(dx, at(0, 1, 0), at(1, 1, 0));
        auto d01 = lerp(dx, at(0, 0, 1), at(1, 0, 1));
        auto d11 = lerp(dx, at(0, 1, 1), at(1, 1, 1));
        return lerp(dz, lerp(dy, d00, d10), lerp(dy, d01, d11));
    }
    T Lookup(Point3f p) const { return Lookup(p, Identity); }

    // The largest converted sample that a lookup anywhere in bounds (a box in [0, 1]^3) can
    // interpolate: an upper bound on Lookup over the box, for a majorant.
    template <typename F>
    Float MaxValue(const Bounds3f &bounds, F convert) const {
        auto first = [](Float v, int n) { return std::max(int(std::floor(v * n - .5f)), 0); };
        auto last = [](Float v, int n) { return std::min(int(std::floor(v * n - .5f)) + 1, n - 1); };
        Float m = 0;
        for (int z = first(bounds.pMin.z, nz); z <= last(bounds.pMax.z, nz); ++z)
            for (int y = first(bounds.pMin.y, ny); y <= last(bounds.pMax.y, ny); ++y)
                for (int x = first(bounds.pMin.x, nx); x <= last(bounds.pMax.x, nx); ++x)
                    m = std::max<Float>(m, convert(values[(size_t(z) * ny + y) * nx + x]));
        return m;
    }

  private:
    static T Identity(T v) { return v; }

    std::vector<T> values;
    int nx = 0, ny = 0, nz = 0;
};

}  // namespace pbrt
