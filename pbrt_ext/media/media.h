// Participating media (pbrt-v4's src/pbrt/media.h and base/medium.h; the book's chapter 11).
//
// A medium answers two questions. SamplePoint(p): its absorption and scattering coefficients,
// phase function and emission at p. SampleRay(ray, tMax): a MajorantIterator that walks the
// ray in segments, each with a majorant sigma_maj >= sigma_t over it (one segment for a
// homogeneous medium; the voxels of a coarse majorant grid, by 3D DDA, for grid media).
// SampleT_maj() turns the two into delta tracking: it samples collision distances against the
// majorant and lets the integrator decide at each one whether it is absorption, real or null
// scattering. Sampled spectra use pbrt-v4's convention: the first wavelength is the hero that
// distances are sampled with; the others ride along with the ratios of their probabilities.
//
// Media are referred to by index into Scene::media; -1 is vacuum (pbrt-v4's null Medium).
#pragma once

#include "pbrt_ext/base/medium.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampledgrid.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/transform.h"

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace pbrt {

struct PhaseFunctionSample {
    Float p;
    Vector3f wi;
    Float pdf;
};

// Henyey and Greenstein's phase function, sampled exactly (p == pdf).
class HGPhaseFunction {
  public:
    HGPhaseFunction() = default;
    explicit HGPhaseFunction(Float g) : g(g) {}

    Float p(Vector3f wo, Vector3f wi) const { return HenyeyGreenstein(Dot(wo, wi), g); }
    std::optional<PhaseFunctionSample> Sample_p(Vector3f wo, Point2f u) const {
        Float pdf;
        Vector3f wi = SampleHenyeyGreenstein(wo, g, u, &pdf);
        return PhaseFunctionSample{pdf, wi, pdf};
    }
    Float PDF(Vector3f wo, Vector3f wi) const { return p(wo, wi); }

  private:
    Float g = 0;
};

// The medium at a point: coefficients per unit length, phase function, emitted radiance.
struct MediumProperties {
    SampledSpectrum sigma_a, sigma_s;
    HGPhaseFunction phase;
    SampledSpectrum Le;
};

// A scattering event inside a medium (pbrt-v4's MediumInteraction).
struct MediumInteraction {
    Point3f p;
    Vector3f wo;  // toward where the path came from, unit
    int medium;
    HGPhaseFunction phase;
    Float time;

    Ray SpawnRay(Vector3f w) const { return Ray(p, w, medium, time); }
    Ray SpawnRayTo(Point3f p2) const { return Ray(p, p2 - p, medium, time); }
};

// What a caller needs of SamplePoint: everything, or all but the emission (shadow rays' ratio
// tracking and bdpt's walks, which pbrt-v4 does not let media emit into), whose grid lookups
// and blackbody spectra a grid medium then skips.
enum class MediumQuery { Full, NoEmission };

// Ratio tracking's factors at a tentative collision drawn with the hero wavelength's majorant
// (T_maj sigma_maj is its density): the null-collision fraction T_maj sigma_n / p that the
// transmittance estimate takes on, and T_maj sigma_maj / p, the other wavelengths' density
// relative to the hero's, for spectral MIS.
struct RatioTrackingStep {
    SampledSpectrum nullRatio, majorantRatio;
};
inline RatioTrackingStep RatioTracking(const MediumProperties &mp, SampledSpectrum sigma_maj,
                                       SampledSpectrum T_maj) {
    SampledSpectrum sigma_n = ClampZero(sigma_maj - mp.sigma_a - mp.sigma_s);
    Float pdf = T_maj[0] * sigma_maj[0];
    return {T_maj * sigma_n / pdf, T_maj * sigma_maj / pdf};
}

// A stretch [tMin, tMax] of a ray (unit direction) over which sigma_t <= sigma_maj.
struct RayMajorantSegment {
    Float tMin, tMax;
    SampledSpectrum sigma_maj;
};

class HomogeneousMajorantIterator {
  public:
    HomogeneousMajorantIterator() = default;
    HomogeneousMajorantIterator(Float tMin, Float tMax, SampledSpectrum sigma_maj)
        : seg{tMin, tMax, sigma_maj}, called(false) {}
    std::optional<RayMajorantSegment> Next() {
        if (called)
            return {};
        called = true;
        return seg;
    }

  private:
    RayMajorantSegment seg{};
    bool called = true;
};

// Maximum density per voxel of a coarse grid over the medium's bounds.
struct MajorantGrid {
    MajorantGrid() = default;
    MajorantGrid(Bounds3f bounds, Point3i res)
        : bounds(bounds), voxels(size_t(res.x) * res.y * res.z, 0), res(res) {}

    Float Lookup(int x, int y, int z) const { return voxels[x + res.x * (y + size_t(res.y) * z)]; }
    void Set(int x, int y, int z, Float v) { voxels[x + res.x * (y + size_t(res.y) * z)] = v; }
    // The voxel's extent in [0, 1]^3 (the grid's own coordinates).
    Bounds3f VoxelBounds(int x, int y, int z) const {
        return Bounds3f(Point3f(Float(x) / res.x, Float(y) / res.y, Float(z) / res.z),
                        Point3f(Float(x + 1) / res.x, Float(y + 1) / res.y, Float(z + 1) / res.z));
    }

    Bounds3f bounds;  // in the medium's space
    std::vector<Float> voxels;
    Point3i res;
};

// The ray carried into the medium's space and its overlap [*tMin, *tMax] with the medium's
// bounds (there) within [0, rayTMax]; false if it misses them.
bool OverlapInMediumSpace(const Transform &renderFromMedium, const Bounds3f &bounds, Ray *ray,
                          Float rayTMax, Float *tMin, Float *tMax);

// Walks a ray through a MajorantGrid voxel by voxel (Amanatides and Woo's 3D DDA), giving one
// segment per voxel with sigma_maj = sigma_t times the voxel's maximum density.
class DDAMajorantIterator {
  public:
    DDAMajorantIterator() = default;
    // ray in the medium's space; [tMin, tMax] its overlap with the grid's bounds.
    DDAMajorantIterator(Ray ray, Float tMin, Float tMax, const MajorantGrid *grid,
                        SampledSpectrum sigma_t);
    std::optional<RayMajorantSegment> Next();

  private:
    SampledSpectrum sigma_t;
    Float tMin = Infinity, tMax = -Infinity;
    const MajorantGrid *grid = nullptr;
    Float nextCrossingT[3], deltaT[3];
    int step[3], voxelLimit[3], voxel[3];
};

// The same coefficients everywhere.
class HomogeneousMedium {
  public:
    using MajorantIterator = HomogeneousMajorantIterator;
    // SamplePoint does not depend on the point: SampleT_maj evaluates it once per ray.
    static constexpr bool kUniform = true;

    // sigma_a and sigma_s are multiplied by sigmaScale, Le by LeScale.
    HomogeneousMedium(Spectrum sigma_a, Spectrum sigma_s, Float sigmaScale, Spectrum Le,
                      Float LeScale, Float g);

    bool IsEmissive() const { return emissive; }
    MediumProperties SamplePoint(Point3f, const SampledWavelengths &lambda,
                                 MediumQuery = MediumQuery::Full) const {
        return MediumProperties{sigmaScale * sigma_a.Sample(lambda),
                                sigmaScale * sigma_s.Sample(lambda), phase,
                                emissive ? LeScale * Le.Sample(lambda) : SampledSpectrum(0.f)};
    }
    HomogeneousMajorantIterator SampleRay(const Ray &, Float tMax,
                                          const SampledWavelengths &lambda) const {
        return HomogeneousMajorantIterator(0, tMax, SigmaT(lambda));
    }
    // Beer-Lambert over a distance (infinite where sigma_t is 0 gives 1).
    SampledSpectrum Transmittance(Float distance, const SampledWavelengths &lambda) const {
        return Exp(-SigmaT(lambda) * std::min(distance, std::numeric_limits<Float>::max()));
    }

  private:
    SampledSpectrum SigmaT(const SampledWavelengths &lambda) const {
        return sigmaScale * (sigma_a.Sample(lambda) + sigma_s.Sample(lambda));
    }

    Spectrum sigma_a, sigma_s, Le;
    Float sigmaScale, LeScale;
    HGPhaseFunction phase;
    bool emissive;
};

// Emission of a density grid medium: a spectrum scaled by a grid (pbrt-v4's "Le" and
// "Lescale"), or blackbody radiation of a temperature grid.
struct GridEmission {
    Spectrum Le = Spectrum(0.f);       // already divided by its photometric integral
    SampledGrid<Float> LeScale;        // per-point scale of Le
    std::optional<SampledGrid<Float>> temperature;
    Float temperatureScale = 1, temperatureOffset = 0;
};

// pbrt-v4's "uniformgrid": constant sigma_a, sigma_s scaled by a trilinearly interpolated
// density over the box [p0, p1] in the medium's space.
class GridMedium {
  public:
    using MajorantIterator = DDAMajorantIterator;

    GridMedium(const Bounds3f &bounds, const Transform &renderFromMedium, Spectrum sigma_a,
               Spectrum sigma_s, Float sigmaScale, Float g, SampledGrid<Float> density,
               GridEmission emission);

    bool IsEmissive() const { return emissive; }
    MediumProperties SamplePoint(Point3f p, const SampledWavelengths &lambda,
                                 MediumQuery query = MediumQuery::Full) const;
    DDAMajorantIterator SampleRay(Ray ray, Float tMax, const SampledWavelengths &lambda) const;
    const MajorantGrid &Majorants() const { return majorantGrid; }

  private:
    // The emitted radiance at pGrid in the grid's [0, 1]^3 coordinates.
    SampledSpectrum Emission(Point3f pGrid, const SampledWavelengths &lambda) const;

    Bounds3f bounds;
    Transform renderFromMedium;
    Spectrum sigma_a, sigma_s;
    Float sigmaScale;
    HGPhaseFunction phase;
    SampledGrid<Float> density;
    GridEmission emission;
    bool emissive;
    MajorantGrid majorantGrid;
};

// pbrt-v4's "rgbgrid": sigma_a, sigma_s (and emission) given per grid sample as RGB.
class RGBGridMedium {
  public:
    using MajorantIterator = DDAMajorantIterator;

    // A missing sigma grid is 1 everywhere (pbrt-v4). Le requires sigma_a (emission is
    // sigma_a Le).
    RGBGridMedium(const Bounds3f &bounds, const Transform &renderFromMedium, Float g,
                  std::optional<SampledGrid<RGBUnboundedSpectrum>> sigma_a,
                  std::optional<SampledGrid<RGBUnboundedSpectrum>> sigma_s, Float sigmaScale,
                  std::optional<SampledGrid<RGBIlluminantSpectrum>> Le, Float LeScale);

    bool IsEmissive() const { return Le && LeScale > 0; }
    MediumProperties SamplePoint(Point3f p, const SampledWavelengths &lambda,
                                 MediumQuery query = MediumQuery::Full) const;
    DDAMajorantIterator SampleRay(Ray ray, Float tMax, const SampledWavelengths &lambda) const;
    const MajorantGrid &Majorants() const { return majorantGrid; }

  private:
    Bounds3f bounds;
    Transform renderFromMedium;
    HGPhaseFunction phase;
    std::optional<SampledGrid<RGBUnboundedSpectrum>> sigma_a, sigma_s;
    Float sigmaScale;
    std::optional<SampledGrid<RGBIlluminantSpectrum>> Le;
    Float LeScale;
    MajorantGrid majorantGrid;
};

// pbrt-v4's "cloud": a procedural cloud in a box, sums of Perlin noise thinning with altitude
// (y in the medium's space), one majorant for the whole box.
class CloudMedium {
  public:
    using MajorantIterator = HomogeneousMajorantIterator;

    CloudMedium(const Bounds3f &bounds, const Transform &renderFromMedium, Spectrum sigma_a,
                Spectrum sigma_s, Float g, Float density, Float wispiness, Float frequency);

    bool IsEmissive() const { return false; }
    MediumProperties SamplePoint(Point3f p, const SampledWavelengths &lambda,
                                 MediumQuery = MediumQuery::Full) const {
        Float d = Density(renderFromMedium.ApplyInverse(p));
        return MediumProperties{d * sigma_a.Sample(lambda), d * sigma_s.Sample(lambda), phase,
                                SampledSpectrum(0.f)};
    }
    HomogeneousMajorantIterator SampleRay(Ray ray, Float tMax,
                                          const SampledWavelengths &lambda) const;
    // The density in [0, 1] at p in the medium's space.
    Float Density(Point3f p) const;

  private:
    Bounds3f bounds;
    Transform renderFromMedium;
    Spectrum sigma_a, sigma_s;
    HGPhaseFunction phase;
    Float density, wispiness, frequency;
};

// pbrt-v4's "nanovdb": a density grid (and optionally a temperature grid, which emits as a
// blackbody) read from a NanoVDB file with the library's own reader, trilinearly interpolated,
// with a 64^3 majorant grid over its bounds. The grids live behind a pointer, so that the
// NanoVDB headers stay in nanovdbmedium.cpp.
class NanoVDBMedium {
  public:
    using MajorantIterator = DDAMajorantIterator;

    struct Grids;  // the file's density and temperature grids
    // Reads and validates the grids; throws std::runtime_error naming the file and the fault.
    NanoVDBMedium(const std::string &filename, const std::string &densityName,
                  const std::string &temperatureName, const Transform &renderFromMedium,
                  Spectrum sigma_a, Spectrum sigma_s, Float sigmaScale, Float g, Float LeScale,
                  Float temperatureOffset, Float temperatureScale);

    // The bytes the file's grids take once read, from its metadata, so that a caller can refuse
    // a file that would not fit in memory before reading it; throws std::runtime_error.
    static uint64_t GridBytes(const std::string &filename);

    bool IsEmissive() const;
    MediumProperties SamplePoint(Point3f p, const SampledWavelengths &lambda,
                                 MediumQuery query = MediumQuery::Full) const;
    DDAMajorantIterator SampleRay(Ray ray, Float tMax, const SampledWavelengths &lambda) const;
    const MajorantGrid &Majorants() const { return *majorantGrid; }
    Bounds3f Bounds() const { return bounds; }

  private:
    std::shared_ptr<const Grids> grids;
    Bounds3f bounds;
    Transform renderFromMedium;
    Spectrum sigma_a, sigma_s;
    Float sigmaScale;
    HGPhaseFunction phase;
    Float LeScale, temperatureOffset, temperatureScale;
    std::shared_ptr<const MajorantGrid> majorantGrid;
};

// A medium of the scene: the closed set of media types, dispatched once per ray segment.
class Medium {
  public:
    using Variant =
        std::variant<HomogeneousMedium, GridMedium, RGBGridMedium, CloudMedium, NanoVDBMedium>;
    template <typename T>
    Medium(T medium) : medium(std::move(medium)) {}

    bool IsEmissive() const {
        return std::visit([](const auto &m) { return m.IsEmissive(); }, medium);
    }
    MediumProperties SamplePoint(Point3f p, const SampledWavelengths &lambda,
                                 MediumQuery query = MediumQuery::Full) const {
        return std::visit([&](const auto &m) { return m.SamplePoint(p, lambda, query); }, medium);
    }
    template <typename T>
    const T *Get() const { return std::get_if<T>(&medium); }

    // The transmittance along ray up to tMax (in units of ray.d) where it has a closed form:
    // in a homogeneous medium the majorant is sigma_t, so ratio tracking's estimate is 0 at
    // its first collision and T_maj / T_maj[0] with probability T_maj[0] otherwise; shadow
    // rays take that expectation instead of drawing it. nullopt for the other media.
    std::optional<SampledSpectrum> ClosedFormTransmittance(const Ray &ray, Float tMax,
                                                           const SampledWavelengths &lambda) const {
        const HomogeneousMedium *homogeneous = Get<HomogeneousMedium>();
        if (!homogeneous)
            return std::nullopt;
        return homogeneous->Transmittance(tMax * Length(ray.d), lambda);
    }

    // Delta tracking along ray up to tMax (in units of ray.d): draws collision distances
    // against the majorant, starting from u and continuing with rng, and calls
    // callback(p, MediumProperties, sigma_maj, T_maj) at each, where T_maj is the majorant
    // transmittance since the previous one. The callback returns whether to go on. Returns
    // the majorant transmittance from the last collision to tMax, or 1 if the callback
    // stopped. query: what the callback reads of the MediumProperties.
    template <typename F>
    SampledSpectrum SampleT_maj(Ray ray, Float tMax, Float u, RNG &rng,
                                const SampledWavelengths &lambda, F callback,
                                MediumQuery query = MediumQuery::Full) const {
        return std::visit(
            [&](const auto &m) {
                return SampleT_majIn(m, ray, tMax, u, rng, lambda, callback, query);
            },
            medium);
    }

  private:
    template <typename M, typename F>
    static SampledSpectrum SampleT_majIn(const M &medium, Ray ray, Float tMax, Float u, RNG &rng,
                                         const SampledWavelengths &lambda, F &callback,
                                         MediumQuery query);

    Variant medium;
};

template <typename M, typename F>
SampledSpectrum Medium::SampleT_majIn(const M &medium, Ray ray, Float tMax, Float u, RNG &rng,
                                      const SampledWavelengths &lambda, F &callback,
                                      MediumQuery query) {
    // Distances along a unit direction, so that sigma is per unit length.
    Float length = Length(ray.d);
    tMax *= length;
    ray.d = ray.d / length;
    typename M::MajorantIterator iter = medium.SampleRay(ray, tMax, lambda);
    // A medium that is the same everywhere is evaluated once, not at every collision.
    constexpr bool uniform = requires { M::kUniform; };
    std::optional<MediumProperties> uniformProperties;
    if constexpr (uniform)
        uniformProperties = medium.SamplePoint(ray.o, lambda, query);
    // An infinite segment (a ray escaping a medium with no boundary) has finite optical depth
    // only where sigma_maj is 0; the largest float keeps 0 * dt at 0.
    auto finite = [](Float dt) { return std::isinf(dt) ? std::numeric_limits<Float>::max() : dt; };
    // The majorant's optical depth since the last collision, exponentiated only where a
    // transmittance is needed (one exp per collision instead of one per segment).
    SampledSpectrum tau(0.f);
    while (std::optional<RayMajorantSegment> seg = iter.Next()) {
        if (seg->sigma_maj[0] == 0) {
            tau += finite(seg->tMax - seg->tMin) * seg->sigma_maj;
            continue;
        }
        for (Float tMin = seg->tMin;;) {
            Float t = tMin + SampleExponential(u, seg->sigma_maj[0]);
            u = rng.Uniform<Float>();
            if (t >= seg->tMax) {
                tau += finite(seg->tMax - tMin) * seg->sigma_maj;
                break;
            }
            SampledSpectrum T_maj = Exp(-(tau + (t - tMin) * seg->sigma_maj));
            Point3f p = ray(t);
            if (!callback(p, uniform ? *uniformProperties : medium.SamplePoint(p, lambda, query),
                          seg->sigma_maj, T_maj))
                return SampledSpectrum(1.f);
            tau = SampledSpectrum(0.f);
            tMin = t;
        }
    }
    return Exp(-tau);
}

}  // namespace pbrt
