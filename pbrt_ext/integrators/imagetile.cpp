#include "pbrt_ext/integrators/imagetile.h"

#include "pbrt_ext/film/pixelstatistics.h"
#include "pbrt_ext/integrators/samplemoments.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/progressreporter.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

namespace pbrt {

namespace {


constexpr int kTileSize = 16;
// pbrt-v4's cap on a wave: large enough that the waits at the end of each wave cost little.
constexpr int kMaxWaveSize = 64;

std::vector<Bounds2i> Tiles(const Bounds2i &pixels) {
    std::vector<Bounds2i> tiles;
    for (int y = pixels.pMin.y; y < pixels.pMax.y; y += kTileSize)
        for (int x = pixels.pMin.x; x < pixels.pMax.x; x += kTileSize)
            tiles.push_back(Bounds2i(Point2i(x, y), Point2i(std::min(x + kTileSize, pixels.pMax.x),
                                                             std::min(y + kTileSize, pixels.pMax.y))));
    return tiles;
}

bool IsValidRadiance(const SampledSpectrum &L) {
    for (int c = 0; c < NSpectrumSamples; ++c)
        if (!std::isfinite(L[c]))
            return false;
    return true;
}

struct ThreadCounts {
    RayCounts rays;
    int64_t discarded = 0;
};

// After the first wave, kMaxWaveSize: a pixel's samples drawn one after another share the
// sampler's per-pixel work (zsobol's pixel digits, Halton's first index), which a new wave
// redoes (8 spp in waves of 1, 2, 4 and 1 took 4.7 % more instructions on the Cornell box than
// in 1 and 7). Under a time limit, twice the last wave, and no more samples than the remaining
// time is predicted to fit at the speed so far (at least one), so that a wave does not overrun
// the limit.
int NextWaveSize(int waveSize, int samplesDone, double elapsed, double timeLimit) {
    if (timeLimit <= 0)
        return kMaxWaveSize;
    double fits = (timeLimit - elapsed) / (elapsed / samplesDone);
    return int(std::clamp(fits, 1.0, double(std::min(2 * waveSize, kMaxWaveSize))));
}

// While alive, times one pixel's samples and counts their rays, for --pixelstats; with no
// statistics to fill, does nothing.
class PixelStatisticsScope {
  public:
    PixelStatisticsScope(PixelStatistics *stats, Point2i p, const RayCounts &rays)
        : stats(stats), p(p), rays(rays) {
        if (stats) {
            rays0 = Total();
            start = std::chrono::steady_clock::now();
        }
    }
    ~PixelStatisticsScope() {
        if (!stats) return;
        std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - start;
        stats->Add(p, ms.count(), Total() - rays0);
    }
    PixelStatisticsScope(const PixelStatisticsScope &) = delete;
    PixelStatisticsScope &operator=(const PixelStatisticsScope &) = delete;

  private:
    int64_t Total() const { return rays.closest + rays.shadow; }
    PixelStatistics *stats;
    Point2i p;
    const RayCounts &rays;
    int64_t rays0 = 0;
    std::chrono::steady_clock::time_point start;
};

// A sample's value as image comparisons see it: the mean of the output RGB the film stores
// (scripts/compare-pbrt-v4's relMSE averages over the channels).
Float MeanOutputRGB(const RGBFilm &film, const SampledSpectrum &L, const SampledWavelengths &lambda) {
    const RGB rgb = film.OutputRGBFromSensorRGB() * film.ClampedSensorRGB(L, lambda);
    return (rgb.r + rgb.g + rgb.b) / 3;
}

// What a unit of radiance at each sampled wavelength adds to the value MeanOutputRGB gives a
// sample of camera weight cameraWeight and filter weight filterWeight (linear in the radiance).
SampledSpectrum ValuePerRadiance(const RGBFilm &film, const SampledSpectrum &cameraWeight, Float filterWeight,
                                 const SampledWavelengths &lambda) {
    SampledSpectrum perRadiance;
    for (int i = 0; i < NSpectrumSamples; ++i) {
        SampledSpectrum unit(0.f);
        unit[i] = cameraWeight[i];
        perRadiance[i] = filterWeight * MeanOutputRGB(film, unit, lambda);
    }
    return perRadiance;
}

// The camera ray's radiance by integrator; with unguided (for the guided integrators only), also
// its estimate of the path tracer's second moment (unguidedmoment.h).
template <typename Integrator>
SampledSpectrum Radiance(const Integrator &integrator, const CameraRayDifferential &cr, const CameraSample &cs,
                         SampledWavelengths &lambda, Sampler &sampler, RayCounts &rays, UnguidedMoment *unguided) {
    if constexpr (requires { integrator.Li(cr.ray, cs.pFilm, lambda, sampler, rays); })
        return cr.weight * integrator.Li(cr.ray, cs.pFilm, lambda, sampler, rays);
    else if constexpr (requires { integrator.Li(cr.ray, lambda, sampler, rays, unguided); })
        return cr.weight * integrator.Li(cr.ray, lambda, sampler, rays, unguided);
    else
        return cr.weight * integrator.Li(cr.ray, lambda, sampler, rays);
}

// Samples [first, last) of every pixel of the tile, each pixel's in index order.
template <typename Integrator>
void RenderTile(Scene &scene, const Integrator &integrator, const Bounds2i &tile, int first,
                int last, ThreadCounts &counts, PixelStatistics *stats, SampleMoments *moments) {
    // Embree traverses fastest without denormals (its documentation's advice for every rendering
    // thread); set per tile since TBB owns the threads.
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    Sampler sampler = scene.sampler;  // per tile: samplers carry per-pixel state
    const bool estimatesPath = moments && moments->EstimatesPath();
    for (Point2i p : tile) {
        PixelStatisticsScope pixelStatistics(stats, p, counts.rays);
        for (int i = first; i < last; ++i) {
            sampler.StartPixelSample(p, i);
            // pbrt-v4's order: the wavelengths take the first dimension, then the camera sample.
            SampledWavelengths lambda = scene.SampleWavelengths(sampler.Get1D());
            CameraSample cs = GetCameraSample(sampler, p, scene.film.GetFilter(), scene.hasMotion,
                                              scene.switches.pixelJitter);
            // pbrt-v4 narrows the differentials to the samples' spacing only when they jitter.
            Float differentialScale = scene.switches.pixelJitter
                                          ? RayDifferentialScale(scene.sampler.SamplesPerPixel())
                                          : 1;
            pstd::optional<CameraRayDifferential> cr = scene.GenerateCameraRay(cs, differentialScale);
            SampledSpectrum L(0.f);
            std::optional<UnguidedMoment> unguided;
            if (estimatesPath)
                unguided.emplace();
            if (cr)
                L = Radiance(integrator, *cr, cs, lambda, sampler, counts.rays, unguided ? &*unguided : nullptr);
            if (!IsValidRadiance(L)) {
                ++counts.discarded;
                continue;
            }
            std::optional<VisibleSurface> visible;
            if (cr && scene.film.GBuffer()) {
                ++counts.rays.closest;
                visible = scene.FirstVisibleSurface(cr->ray, lambda);
            }
            scene.film.AddSample(p, L, lambda, cs.filterWeight, visible ? &*visible : nullptr);
            if (!moments)
                continue;
            const Float value = cs.filterWeight * MeanOutputRGB(scene.film, L, lambda);
            if (!unguided) {
                moments->Add(p, value);
                continue;
            }
            // Weighed by the wavelengths as the path left them.
            const SampledSpectrum cameraWeight = cr ? cr->weight : SampledSpectrum(0.f);
            const SampledSpectrum toValue = ValuePerRadiance(scene.film, cameraWeight, cs.filterWeight, lambda);
            moments->Add(p, value, float(unguided->SecondMoment(toValue)));
        }
    }
}

// Whether integrator is guidedpath or guidedvolpath: those estimate the path tracer's moments.
bool IsGuided(const TileIntegrator &integrator) {
    if (const auto *volpath = std::get_if<VolPathIntegrator>(&integrator))
        return volpath->Guided();
    return std::holds_alternative<GuidedPathIntegrator>(integrator);
}

// Splats came from one light path per camera sample, spread over the pixels.
Float SplatScale(const Bounds2i &pixels, int64_t cameraSamples) {
    return Float(double(pixels.Area()) / double(cameraSamples));
}

}  // namespace

RenderStatistics RenderTiles(Scene &scene, const TileIntegrator &integrator, SampleRange samples,
                             const RenderOptions &options, const char *title, SampleMoments *moments) {
    if (moments && moments->EstimatesPath() && !IsGuided(integrator))
        throw std::invalid_argument("RenderTiles: only guided integrators estimate the path tracer's moments");
    const Bounds2i pixels = scene.film.PixelBounds();
    const std::vector<Bounds2i> tiles = Tiles(pixels);
    // Every pixel of tile t has samples [samples.first, tileSamples[t]).
    std::vector<int> tileSamples(tiles.size(), samples.first);
    ProgressReporter progress(int64_t(pixels.Area()) * samples.Count(), title, options.quiet);
    tbb::enumerable_thread_specific<ThreadCounts> counts;

    int waveStart = samples.first, waveSize = 1;
    while (waveStart < samples.last) {
        const int waveEnd = std::min(samples.last, waveStart + waveSize);
        // The first wave ignores cancellation, so that every pixel has a sample.
        const bool cancellable = waveStart > samples.first;
        tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
            if (cancellable && options.Cancelled())
                return;
            std::visit([&](const auto &concrete) {
                RenderTile(scene, concrete, tiles[t], waveStart, waveEnd, counts.local(),
                           options.pixelStatistics, moments);
            }, integrator);
            tileSamples[t] = waveEnd;
            progress.Update(int64_t(tiles[t].Area()) * (waveEnd - waveStart));
        });
        waveStart = waveEnd;
        if (options.afterWave && !options.Cancelled()) {
            scene.film.SetSplatScale(SplatScale(pixels, int64_t(pixels.Area()) * (waveEnd - samples.first)));
            options.afterWave(waveEnd - samples.first);
        }
        const double elapsed = progress.ElapsedSeconds();
        const bool timeUp = options.timeLimitSeconds > 0 && elapsed >= options.timeLimitSeconds;
        if (options.Cancelled() || timeUp)
            break;
        waveSize = NextWaveSize(waveSize, waveStart - samples.first, elapsed, options.timeLimitSeconds);
    }
    progress.Done();

    RenderStatistics stats;
    stats.seconds = progress.ElapsedSeconds();
    const auto [fewest, most] = std::minmax_element(tileSamples.begin(), tileSamples.end());
    stats.samplesPerPixel = *fewest - samples.first;
    stats.maxSamplesPerPixel = *most - samples.first;
    stats.cancelled = stats.samplesPerPixel < samples.Count() && options.Cancelled();
    for (size_t t = 0; t < tiles.size(); ++t)
        stats.cameraSamples += int64_t(tiles[t].Area()) * (tileSamples[t] - samples.first);
    if (stats.cameraSamples > 0) {
        Float splatScale = SplatScale(pixels, stats.cameraSamples);
        scene.film.SetSplatScale(splatScale);
        if (const BDPTIntegrator *bdpt = std::get_if<BDPTIntegrator>(&integrator))
            bdpt->WriteStrategyImages(splatScale);
    }
    for (const ThreadCounts &c : counts) {
        stats.closestRays += c.rays.closest;
        stats.shadowRays += c.rays.shadow;
        stats.discardedSamples += c.discarded;
    }
    return stats;
}

}  // namespace pbrt
