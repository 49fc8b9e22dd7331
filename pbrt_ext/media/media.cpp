#include "pbrt_ext/media/media.h"

#include "pbrt_ext/util/noise.h"

#include <algorithm>

namespace pbrt {

namespace {

// pbrt-v4's resolution of the majorant grids of the density grid media.
constexpr Point3i kMajorantGridResolution(16, 16, 16);

// Fills grid with maxDensity(voxel bounds in [0, 1]^3) for every voxel.
template <typename F>
void FillMajorants(MajorantGrid &grid, F maxDensity) {
    for (int z = 0; z < grid.res.z; ++z)
        for (int y = 0; y < grid.res.y; ++y)
            for (int x = 0; x < grid.res.x; ++x)
                grid.Set(x, y, z, maxDensity(grid.VoxelBounds(x, y, z)));
}

}  // namespace

bool OverlapInMediumSpace(const Transform &renderFromMedium, const Bounds3f &bounds, Ray *ray,
                          Float rayTMax, Float *tMin, Float *tMax) {
    // The transformation is linear, so t means the same distance in both spaces.
    *ray = renderFromMedium.ApplyInverse(*ray);
    return bounds.IntersectP(ray->o, ray->d, rayTMax, tMin, tMax);
}

// ---- DDAMajorantIterator ------------------------------------------------------------------

DDAMajorantIterator::DDAMajorantIterator(Ray ray, Float tMin, Float tMax,
                                         const MajorantGrid *grid, SampledSpectrum sigma_t)
    : sigma_t(sigma_t), tMin(tMin), tMax(tMax), grid(grid) {
    // In the grid's [0, 1]^3 coordinates.
    Vector3f diag = grid->bounds.Diagonal();
    Point3f o(grid->bounds.Offset(ray.o));
    Vector3f d(ray.d.x / diag.x, ray.d.y / diag.y, ray.d.z / diag.z);
    Point3f entry = o + d * tMin;
    for (int axis = 0; axis < 3; ++axis) {
        int res = grid->res[axis];
        voxel[axis] = std::clamp(int(entry[axis] * res), 0, res - 1);
        deltaT[axis] = 1 / (std::abs(d[axis]) * res);
        if (d[axis] == -0.f)
            d[axis] = 0.f;  // so that a zero component steps up, towards an infinite crossing
        if (d[axis] >= 0) {
            Float next = Float(voxel[axis] + 1) / res;
            nextCrossingT[axis] = tMin + (next - entry[axis]) / d[axis];
            step[axis] = 1;
            voxelLimit[axis] = res;
        } else {
            Float next = Float(voxel[axis]) / res;
            nextCrossingT[axis] = tMin + (next - entry[axis]) / d[axis];
            step[axis] = -1;
            voxelLimit[axis] = -1;
        }
    }
}

std::optional<RayMajorantSegment> DDAMajorantIterator::Next() {
    if (tMin >= tMax)
        return {};
    // The axis whose voxel boundary the ray crosses first.
    int stepAxis = nextCrossingT[0] < nextCrossingT[1]
                       ? (nextCrossingT[0] < nextCrossingT[2] ? 0 : 2)
                       : (nextCrossingT[1] < nextCrossingT[2] ? 1 : 2);
    Float tVoxelExit = std::min(tMax, nextCrossingT[stepAxis]);
    RayMajorantSegment seg{tMin, tVoxelExit,
                           sigma_t * grid->Lookup(voxel[0], voxel[1], voxel[2])};
    tMin = nextCrossingT[stepAxis] > tMax ? tMax : tVoxelExit;
    voxel[stepAxis] += step[stepAxis];
    if (voxel[stepAxis] == voxelLimit[stepAxis])
        tMin = tMax;
    nextCrossingT[stepAxis] += deltaT[stepAxis];
    return seg;
}

// ---- HomogeneousMedium --------------------------------------------------------------------

HomogeneousMedium::HomogeneousMedium(Spectrum sigma_a, Spectrum sigma_s, Float sigmaScale,
                                     Spectrum Le, Float LeScale, Float g)
    : sigma_a(TabulatedForLookup(sigma_a)), sigma_s(TabulatedForLookup(sigma_s)),
      Le(TabulatedForLookup(Le)), sigmaScale(sigmaScale), LeScale(LeScale), phase(g),
      emissive(Le.MaxValue() * LeScale > 0) {}

// ---- GridMedium ---------------------------------------------------------------------------

GridMedium::GridMedium(const Bounds3f &bounds, const Transform &renderFromMedium,
                       Spectrum sigma_a, Spectrum sigma_s, Float sigmaScale, Float g,
                       SampledGrid<Float> density, GridEmission emission)
    : bounds(bounds), renderFromMedium(renderFromMedium), sigma_a(TabulatedForLookup(sigma_a)),
      sigma_s(TabulatedForLookup(sigma_s)), sigmaScale(sigmaScale), phase(g),
      density(std::move(density)), emission(std::move(emission)),
      majorantGrid(bounds, kMajorantGridResolution) {
    this->emission.Le = TabulatedForLookup(this->emission.Le);
    emissive = this->emission.temperature || this->emission.Le.MaxValue() > 0;
    FillMajorants(majorantGrid, [&](const Bounds3f &voxel) {
        return this->density.MaxValue(voxel, [](Float d) { return d; });
    });
}

MediumProperties GridMedium::SamplePoint(Point3f p, const SampledWavelengths &lambda,
                                         MediumQuery query) const {
    Point3f pGrid(bounds.Offset(renderFromMedium.ApplyInverse(p)));
    Float d = density.Lookup(pGrid);
    SampledSpectrum sa = (sigmaScale * d) * sigma_a.Sample(lambda);
    SampledSpectrum ss = (sigmaScale * d) * sigma_s.Sample(lambda);
    return MediumProperties{sa, ss, phase,
                            query == MediumQuery::Full ? Emission(pGrid, lambda) : SampledSpectrum(0.f)};
}

SampledSpectrum GridMedium::Emission(Point3f pGrid, const SampledWavelengths &lambda) const {
    Float scale = emissive ? emission.LeScale.Lookup(pGrid) : 0;
    if (!(scale > 0))
        return SampledSpectrum(0.f);
    if (!emission.temperature)
        return scale * emission.Le.Sample(lambda);
    Float T = (emission.temperature->Lookup(pGrid) - emission.temperatureOffset) *
              emission.temperatureScale;
    // pbrt-v4 emits nothing at or below 100 K.
    return T > 100 ? scale * BlackbodySpectrum(T).Sample(lambda) : SampledSpectrum(0.f);
}

DDAMajorantIterator GridMedium::SampleRay(Ray ray, Float rayTMax,
                                          const SampledWavelengths &lambda) const {
    Float tMin, tMax;
    if (!OverlapInMediumSpace(renderFromMedium, bounds, &ray, rayTMax, &tMin, &tMax))
        return {};
    SampledSpectrum sigma_t = sigmaScale * (sigma_a.Sample(lambda) + sigma_s.Sample(lambda));
    return DDAMajorantIterator(ray, tMin, tMax, &majorantGrid, sigma_t);
}

// ---- RGBGridMedium ------------------------------------------------------------------------

RGBGridMedium::RGBGridMedium(const Bounds3f &bounds, const Transform &renderFromMedium, Float g,
                             std::optional<SampledGrid<RGBUnboundedSpectrum>> sigma_a,
                             std::optional<SampledGrid<RGBUnboundedSpectrum>> sigma_s,
                             Float sigmaScale,
                             std::optional<SampledGrid<RGBIlluminantSpectrum>> Le, Float LeScale)
    : bounds(bounds), renderFromMedium(renderFromMedium), phase(g), sigma_a(std::move(sigma_a)),
      sigma_s(std::move(sigma_s)), sigmaScale(sigmaScale), Le(std::move(Le)), LeScale(LeScale),
      majorantGrid(bounds, kMajorantGridResolution) {
    auto max = [](const RGBUnboundedSpectrum &s) { return s.MaxValue(); };
    FillMajorants(majorantGrid, [&](const Bounds3f &voxel) {
        Float a = this->sigma_a ? this->sigma_a->MaxValue(voxel, max) : 1;
        Float s = this->sigma_s ? this->sigma_s->MaxValue(voxel, max) : 1;
        return this->sigmaScale * (a + s);
    });
}

MediumProperties RGBGridMedium::SamplePoint(Point3f p, const SampledWavelengths &lambda,
                                            MediumQuery query) const {
    Point3f pGrid(bounds.Offset(renderFromMedium.ApplyInverse(p)));
    auto sample = [&](const auto &s) { return s.Sample(lambda); };
    SampledSpectrum sa = sigma_a ? sigma_a->Lookup(pGrid, sample) : SampledSpectrum(1.f);
    SampledSpectrum ss = sigma_s ? sigma_s->Lookup(pGrid, sample) : SampledSpectrum(1.f);
    SampledSpectrum emitted(0.f);
    if (Le && LeScale > 0 && query == MediumQuery::Full)
        emitted = LeScale * Le->Lookup(pGrid, sample);
    return MediumProperties{sigmaScale * sa, sigmaScale * ss, phase, emitted};
}

DDAMajorantIterator RGBGridMedium::SampleRay(Ray ray, Float rayTMax,
                                             const SampledWavelengths &) const {
    Float tMin, tMax;
    if (!OverlapInMediumSpace(renderFromMedium, bounds, &ray, rayTMax, &tMin, &tMax))
        return {};
    // The majorant grid holds sigma_t itself.
    return DDAMajorantIterator(ray, tMin, tMax, &majorantGrid, SampledSpectrum(1.f));
}

// ---- CloudMedium --------------------------------------------------------------------------

CloudMedium::CloudMedium(const Bounds3f &bounds, const Transform &renderFromMedium,
                         Spectrum sigma_a, Spectrum sigma_s, Float g, Float density,
                         Float wispiness, Float frequency)
    : bounds(bounds), renderFromMedium(renderFromMedium), sigma_a(TabulatedForLookup(sigma_a)),
      sigma_s(TabulatedForLookup(sigma_s)), phase(g), density(density), wispiness(wispiness),
      frequency(frequency) {}

HomogeneousMajorantIterator CloudMedium::SampleRay(Ray ray, Float rayTMax,
                                                   const SampledWavelengths &lambda) const {
    Float tMin, tMax;
    if (!OverlapInMediumSpace(renderFromMedium, bounds, &ray, rayTMax, &tMin, &tMax))
        return {};
    // The density is at most 1.
    return HomogeneousMajorantIterator(tMin, tMax, sigma_a.Sample(lambda) + sigma_s.Sample(lambda));
}

// pbrt-v4's cloud: the lookup point pushed around by two octaves of the noise's gradient
// (wisps), five octaves of noise, scaled by density and falling off with altitude, with a
// dense layer below y = 0.5.
Float CloudMedium::Density(Point3f p) const {
    Point3f pp = frequency * p;
    if (wispiness > 0) {
        Float vomega = 0.05f * wispiness, vlambda = 10.f;
        for (int i = 0; i < 2; ++i) {
            pp += vomega * DNoise(vlambda * pp);
            vomega *= 0.5f;
            vlambda *= 1.99f;
        }
    }
    Float d = 0, omega = 0.5f, lambda = 1.f;
    for (int i = 0; i < 5; ++i) {
        d += omega * Noise(lambda * pp);
        omega *= 0.5f;
        lambda *= 1.99f;
    }
    d = Clamp((1 - p.y) * 4.5f * density * d, 0, 1);
    d += 2 * std::max<Float>(0, 0.5f - p.y);
    return Clamp(d, 0, 1);
}

}  // namespace pbrt
