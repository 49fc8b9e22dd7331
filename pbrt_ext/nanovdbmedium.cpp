// NanoVDBMedium (media.h): grids read by NanoVDB's own reader (Debian's libnanovdb-dev,
// header-only; zlib-compressed files too) and checked by its validator before any voxel is
// touched, since a grid's tree is addressed by offsets stored in the file.
#include "pbrt_ext/media.h"

#include <iostream>  // GridValidator.h uses std::cerr without including it

#define NANOVDB_USE_ZIP 1
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <stdexcept>

namespace pbrt {

struct NanoVDBMedium::Grids {
    nanovdb::GridHandle<nanovdb::HostBuffer> densityHandle, temperatureHandle;
    const nanovdb::FloatGrid *density = nullptr, *temperature = nullptr;
};

namespace {

using TrilinearSampler = nanovdb::SampleFromVoxels<nanovdb::FloatGrid::TreeType, 1, false>;

// Throws unless every voxel of grid satisfies isValid: a density must be finite and >= 0, a
// temperature finite, whatever bytes a file holds (NanoVDB's validator checks the structure
// and, where the writer stored one, the checksum; not the values).
template <typename Check>
void CheckValues(const nanovdb::FloatGrid &grid, const std::string &what, Check isValid) {
    const nanovdb::CoordBBox box = grid.indexBBox();
    auto accessor = grid.getAccessor();
    for (int k = box.min()[2]; k <= box.max()[2]; ++k)
        for (int j = box.min()[1]; j <= box.max()[1]; ++j)
            for (int i = box.min()[0]; i <= box.max()[0]; ++i)
                if (!isValid(accessor.getValue(nanovdb::Coord(i, j, k))))
                    throw std::runtime_error(what + " has an invalid value at voxel (" +
                                             std::to_string(i) + ", " + std::to_string(j) + ", " +
                                             std::to_string(k) + ")");
}

// The float grid gridName of the file, validated (densities >= 0: it is the density grid if
// its name is densityName); null if the file has no grid of that name and it is optional.
const nanovdb::FloatGrid *ReadGrid(const std::string &filename, const std::string &gridName,
                                   const std::string &densityName, bool required,
                                   nanovdb::GridHandle<nanovdb::HostBuffer> *handle) {
    std::string what = filename + ": grid \"" + gridName + "\"";
    try {
        *handle = nanovdb::io::readGrid<nanovdb::HostBuffer>(filename, gridName);
    } catch (const std::exception &e) {
        throw std::runtime_error(filename + ": " + e.what());
    }
    if (!*handle) {
        if (required)
            throw std::runtime_error(what + " not found");
        return nullptr;
    }
    const nanovdb::FloatGrid *grid = handle->grid<float>();
    if (!grid)
        throw std::runtime_error(what + " does not hold floats");
    if (!nanovdb::isValid(*grid, true, false))
        throw std::runtime_error(what + " is corrupt (NanoVDB's validator rejects it)");
    if (!grid->isFogVolume() && !grid->isUnknown())
        throw std::runtime_error(what + " is not a fog volume");
    CheckValues(*grid, what, [&](float v) {
        return std::isfinite(v) && (v >= 0 || gridName != densityName);
    });
    return grid;
}

Bounds3f WorldBounds(const nanovdb::FloatGrid &grid) {
    const auto &b = grid.worldBBox();
    return Bounds3f(Point3f(b.min()[0], b.min()[1], b.min()[2]),
                    Point3f(b.max()[0], b.max()[1], b.max()[2]));
}

// pbrt-v4's majorants: for each voxel of a 64^3 grid over the bounds, the largest density
// sample within it, one index-space voxel wider for the trilinear filter's reach.
std::shared_ptr<const MajorantGrid> DensityMajorants(const nanovdb::FloatGrid &density,
                                                     const Bounds3f &bounds) {
    auto grid = std::make_shared<MajorantGrid>(bounds, Point3i(64, 64, 64));
    const nanovdb::CoordBBox indexBox = density.indexBBox();
    int n = grid->res.x * grid->res.y * grid->res.z;
    tbb::parallel_for(0, n, [&](int index) {
        int x = index % grid->res.x, y = (index / grid->res.x) % grid->res.y,
            z = index / (grid->res.x * grid->res.y);
        Bounds3f voxel = grid->VoxelBounds(x, y, z);
        Point3f w0 = bounds.Lerp(voxel.pMin), w1 = bounds.Lerp(voxel.pMax);
        auto i0 = density.worldToIndexF(nanovdb::Vec3f(w0.x, w0.y, w0.z));
        auto i1 = density.worldToIndexF(nanovdb::Vec3f(w1.x, w1.y, w1.z));
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(int(std::min(i0[a], i1[a]) - 1), indexBox.min()[a]);
            hi[a] = std::min(int(std::max(i0[a], i1[a]) + 1), indexBox.max()[a]);
        }
        auto accessor = density.getAccessor();
        float maxValue = 0;
        for (int k = lo[2]; k <= hi[2]; ++k)
            for (int j = lo[1]; j <= hi[1]; ++j)
                for (int i = lo[0]; i <= hi[0]; ++i)
                    maxValue = std::max(maxValue, accessor.getValue(nanovdb::Coord(i, j, k)));
        grid->Set(x, y, z, maxValue);
    });
    return grid;
}

}  // namespace

NanoVDBMedium::NanoVDBMedium(const std::string &filename, const std::string &densityName,
                             const std::string &temperatureName,
                             const Transform &renderFromMedium, Spectrum sigma_a,
                             Spectrum sigma_s, Float sigmaScale, Float g, Float LeScale,
                             Float temperatureOffset, Float temperatureScale)
    : renderFromMedium(renderFromMedium), sigma_a(TabulatedForLookup(sigma_a)),
      sigma_s(TabulatedForLookup(sigma_s)), sigmaScale(sigmaScale), phase(g), LeScale(LeScale),
      temperatureOffset(temperatureOffset), temperatureScale(temperatureScale) {
    auto loaded = std::make_shared<Grids>();
    loaded->density = ReadGrid(filename, densityName, densityName, true, &loaded->densityHandle);
    loaded->temperature =
        ReadGrid(filename, temperatureName, densityName, false, &loaded->temperatureHandle);
    bounds = WorldBounds(*loaded->density);
    if (loaded->temperature)
        bounds = Union(bounds, WorldBounds(*loaded->temperature));
    majorantGrid = DensityMajorants(*loaded->density, bounds);
    grids = std::move(loaded);
}

uint64_t NanoVDBMedium::GridBytes(const std::string &filename) {
    try {
        uint64_t bytes = 0;
        for (const nanovdb::io::GridMetaData &grid : nanovdb::io::readGridMetaData(filename))
            bytes = grid.gridSize > UINT64_MAX - bytes ? UINT64_MAX : bytes + grid.gridSize;
        return bytes;
    } catch (const std::exception &e) {
        throw std::runtime_error(filename + ": " + e.what());
    }
}

bool NanoVDBMedium::IsEmissive() const { return grids->temperature && LeScale > 0; }

MediumProperties NanoVDBMedium::SamplePoint(Point3f p, const SampledWavelengths &lambda) const {
    p = renderFromMedium.ApplyInverse(p);
    nanovdb::Vec3f pw(p.x, p.y, p.z);
    Float d = TrilinearSampler(grids->density->tree())(grids->density->worldToIndexF(pw));
    SampledSpectrum Le(0.f);
    if (grids->temperature && LeScale > 0) {
        Float T = TrilinearSampler(grids->temperature->tree())(
            grids->temperature->worldToIndexF(pw));
        T = (T - temperatureOffset) * temperatureScale;
        // pbrt-v4 emits nothing at or below 100 K.
        if (T > 100)
            Le = LeScale * BlackbodySpectrum(T).Sample(lambda);
    }
    return MediumProperties{(sigmaScale * d) * sigma_a.Sample(lambda),
                            (sigmaScale * d) * sigma_s.Sample(lambda), phase, Le};
}

DDAMajorantIterator NanoVDBMedium::SampleRay(Ray ray, Float rayTMax,
                                             const SampledWavelengths &lambda) const {
    ray = renderFromMedium.ApplyInverse(ray);
    Float tMin, tMax;
    if (!bounds.IntersectP(ray.o, ray.d, rayTMax, &tMin, &tMax))
        return {};
    SampledSpectrum sigma_t = sigmaScale * (sigma_a.Sample(lambda) + sigma_s.Sample(lambda));
    return DDAMajorantIterator(ray, tMin, tMax, majorantGrid.get(), sigma_t);
}

}  // namespace pbrt
