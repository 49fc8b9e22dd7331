#include "pbrt_ext/render.h"

#include "pbrt_ext/integrators/ambientocclusion.h"
#include "pbrt_ext/integrators/bdpt.h"
#include "pbrt_ext/integrators/function.h"
#include "pbrt_ext/integrators/lightpath.h"
#include "pbrt_ext/integrators/mlt.h"
#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/integrators/randomwalk.h"
#include "pbrt_ext/integrators/simplepath.h"
#include "pbrt_ext/integrators/simplevolpath.h"
#include "pbrt_ext/integrators/sppm.h"
#include "pbrt_ext/integrators/volpath.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/log.h"
#include "pbrt_ext/util/progressreporter.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
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

bool Cancelled(const RenderOptions &options) {
    return options.cancel && options.cancel->load(std::memory_order_relaxed);
}

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

// Samples [first, last) of every pixel of the tile, each pixel's in index order.
template <typename Integrator>
void RenderTile(Scene &scene, const Integrator &integrator, const Bounds2i &tile, int first,
                int last, ThreadCounts &counts) {
    // Embree traverses fastest without denormals (its documentation's advice for every rendering
    // thread); set per tile since TBB owns the threads.
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    Sampler sampler = scene.sampler;  // per tile: samplers carry per-pixel state
    for (Point2i p : tile)
        for (int i = first; i < last; ++i) {
            sampler.StartPixelSample(p, i);
            // pbrt-v4's order: the wavelengths take the first dimension, then the camera sample.
            SampledWavelengths lambda = scene.film.SampleWavelengths(sampler.Get1D());
            CameraSample cs = GetCameraSample(sampler, p, scene.film.GetFilter(), scene.hasMotion);
            pstd::optional<CameraRayDifferential> cr =
                scene.GenerateCameraRay(cs, RayDifferentialScale(scene.sampler.SamplesPerPixel()));
            SampledSpectrum L(0.f);
            if (cr) {
                if constexpr (requires { integrator.Li(cr->ray, cs.pFilm, lambda, sampler, counts.rays); })
                    L = cr->weight * integrator.Li(cr->ray, cs.pFilm, lambda, sampler, counts.rays);
                else
                    L = cr->weight * integrator.Li(cr->ray, lambda, sampler, counts.rays);
            }
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
        }
}

// The integrators that estimate each camera sample by itself; sppm, mlt and function render
// in their own way (RenderSPPM, RenderMLT, RenderFunction).
using Integrator = std::variant<PathIntegrator, VolPathIntegrator, BDPTIntegrator, LightPathIntegrator,
                                SimplePathIntegrator, SimpleVolPathIntegrator, RandomWalkIntegrator,
                                AOIntegrator>;

Integrator ChooseIntegrator(Scene &scene) {
    const IntegratorOptions &o = scene.integratorOptions;
    switch (o.type) {
    case IntegratorType::BDPT:
        return BDPTIntegrator(scene, o);
    case IntegratorType::LightPath:
        return LightPathIntegrator(scene, o);
    case IntegratorType::SimplePath:
        return SimplePathIntegrator(scene, o);
    case IntegratorType::SimpleVolPath:
        return SimpleVolPathIntegrator(scene, o);
    case IntegratorType::RandomWalk:
        return RandomWalkIntegrator(scene, o);
    case IntegratorType::AmbientOcclusion:
        return AOIntegrator(scene, o);
    case IntegratorType::VolPath:
        // The volumetric path tracer only where there are media or subsurface materials to
        // render.
        if (!scene.media.empty() || scene.HasSubsurface())
            return VolPathIntegrator(scene, o);
        [[fallthrough]];
    case IntegratorType::Path:
    case IntegratorType::SPPM:
    case IntegratorType::MLT:
    case IntegratorType::Function:
        break;
    }
    return PathIntegrator(scene, o);
}

Integrator MakeIntegrator(Scene &scene, const RenderOptions &options) {
    Integrator integrator = ChooseIntegrator(scene);
    PathStrategy strategy = scene.integratorOptions.strategy;
    if (strategy != PathStrategy::MIS && !std::holds_alternative<PathIntegrator>(integrator) &&
        !options.quiet)
        Warning("--strategy %s applies to the path integrator; the others combine their "
                "estimators by MIS",
                ToString(strategy).c_str());
    return integrator;
}

}  // namespace

SampleRange SamplesToRender(const Scene &scene, const RenderOptions &options) {
    const int spp = scene.integratorOptions.type == IntegratorType::MLT
                        ? scene.integratorOptions.mlt.mutationsPerPixel
                        : scene.sampler.SamplesPerPixel();
    if (!options.samples)
        return {0, spp};
    const SampleRange r = *options.samples;
    if (r.first < 0 || r.first >= r.last || r.last > spp)
        throw std::invalid_argument("the sample range " + std::to_string(r.first) + ":" +
                                    std::to_string(r.last) + " is empty or outside the sampler's 0:" +
                                    std::to_string(spp));
    switch (scene.integratorOptions.type) {
    case IntegratorType::SPPM:
        throw std::invalid_argument("sppm renders no sample range: each iteration narrows the "
                                    "radius the next one gathers photons in");
    case IntegratorType::MLT:
        throw std::invalid_argument("mlt renders no sample range: its Markov chains' splats are "
                                    "normalized by the bootstrap of the whole render");
    case IntegratorType::Function:
        throw std::invalid_argument("function renders no sample range: it writes an error table, "
                                    "not an image");
    default:
        break;
    }
    if (scene.film.Buckets() || scene.film.GBuffer())
        throw std::invalid_argument("the spectral and g-buffer films render no sample range: a "
                                    "slice keeps the RGB film's sums only");
    return r;
}

std::string RenderStatistics::ToString() const {
    char buf[512];
    std::snprintf(buf, sizeof(buf),
                  "render time %.3f s\ncamera samples %lld (%.3f M/s)\nrays %lld: %lld camera and "
                  "indirect, %lld shadow (%.3f M/s)\nsamples discarded for NaN/Inf radiance %lld\n",
                  seconds, (long long)cameraSamples, CameraSamplesPerSecond() / 1e6,
                  (long long)(closestRays + shadowRays), (long long)closestRays,
                  (long long)shadowRays, RaysPerSecond() / 1e6, (long long)discardedSamples);
    return buf;
}

RenderStatistics Render(Scene &scene, const RenderOptions &options) {
    const SampleRange samples = SamplesToRender(scene, options);
    std::unique_ptr<tbb::global_control> threads;
    if (options.nThreads > 0)
        threads = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, options.nThreads);
    switch (scene.integratorOptions.type) {
    case IntegratorType::SPPM:
        return RenderSPPM(scene, options);  // iterations of camera paths and photons
    case IntegratorType::MLT:
        return RenderMLT(scene, options);  // Markov chains
    case IntegratorType::Function:
        return RenderFunction(scene, options);  // an error table per sample count
    default:
        break;
    }
    const Integrator integrator = MakeIntegrator(scene, options);
    const Bounds2i pixels = scene.film.PixelBounds();
    const std::vector<Bounds2i> tiles = Tiles(pixels);
    // Every pixel of tile t has samples [samples.first, tileSamples[t]).
    std::vector<int> tileSamples(tiles.size(), samples.first);
    ProgressReporter progress(int64_t(pixels.Area()) * samples.Count(), "Rendering", options.quiet);
    tbb::enumerable_thread_specific<ThreadCounts> counts;

    int waveStart = samples.first, waveSize = 1;
    while (waveStart < samples.last) {
        const int waveEnd = std::min(samples.last, waveStart + waveSize);
        // The first wave ignores cancellation, so that every pixel has a sample.
        const bool cancellable = waveStart > samples.first;
        tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
            if (cancellable && Cancelled(options))
                return;
            std::visit([&](const auto &concrete) {
                RenderTile(scene, concrete, tiles[t], waveStart, waveEnd, counts.local());
            }, integrator);
            tileSamples[t] = waveEnd;
            progress.Update(int64_t(tiles[t].Area()) * (waveEnd - waveStart));
        });
        waveStart = waveEnd;
        const double elapsed = progress.ElapsedSeconds();
        const bool timeUp = options.timeLimitSeconds > 0 && elapsed >= options.timeLimitSeconds;
        if (Cancelled(options) || timeUp)
            break;
        waveSize = NextWaveSize(waveSize, waveStart - samples.first, elapsed, options.timeLimitSeconds);
    }
    progress.Done();

    RenderStatistics stats;
    stats.seconds = progress.ElapsedSeconds();
    const auto [fewest, most] = std::minmax_element(tileSamples.begin(), tileSamples.end());
    stats.samplesPerPixel = *fewest - samples.first;
    stats.maxSamplesPerPixel = *most - samples.first;
    stats.cancelled = stats.samplesPerPixel < samples.Count() && Cancelled(options);
    for (size_t t = 0; t < tiles.size(); ++t)
        stats.cameraSamples += int64_t(tiles[t].Area()) * (tileSamples[t] - samples.first);
    // Splats came from one light path per camera sample, spread over the pixels.
    if (stats.cameraSamples > 0) {
        Float splatScale = Float(double(pixels.Area()) / double(stats.cameraSamples));
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
