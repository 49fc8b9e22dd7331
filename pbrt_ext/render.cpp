#include "pbrt_ext/render.h"

#include "pbrt_ext/integrators.h"
#include "pbrt_ext/scene.h"
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
#include <vector>

namespace pbrt {

namespace {

constexpr int kTileSize = 16;

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

}  // namespace

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
    std::unique_ptr<tbb::global_control> threads;
    if (options.nThreads > 0)
        threads = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, options.nThreads);
    PathIntegrator integrator(scene, scene.integratorOptions);
    const Bounds2i pixels = scene.film.PixelBounds();
    const std::vector<Bounds2i> tiles = Tiles(pixels);
    const int spp = scene.sampler.SamplesPerPixel();
    const bool timed = options.timeLimitSeconds > 0;
    const int samplesPerPass = timed ? 1 : spp;
    ProgressReporter progress(int64_t(tiles.size()) * (spp / samplesPerPass), "Rendering",
                              options.quiet);
    tbb::enumerable_thread_specific<ThreadCounts> counts;

    int done = 0;
    while (done < spp && !(done > 0 && timed && progress.ElapsedSeconds() >= options.timeLimitSeconds)) {
        const int first = done, last = done + samplesPerPass;
        tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
            // Embree traverses fastest without denormals (its documentation's advice for every
            // rendering thread); set per tile since TBB owns the threads.
            _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
            _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
            Sampler sampler = scene.sampler;  // per tile: samplers carry per-pixel state
            ThreadCounts &local = counts.local();
            for (Point2i p : tiles[t])
                for (int i = first; i < last; ++i) {
                    sampler.StartPixelSample(p, i);
                    CameraSample cs = GetCameraSample(sampler, p, scene.film.GetFilter());
                    pstd::optional<CameraRay> cr = scene.camera.GenerateRay(cs);
                    SampledSpectrum L(0.f);
                    if (cr)
                        L = cr->weight * integrator.Li(cr->ray, sampler, local.rays);
                    if (!IsValidRadiance(L)) {
                        ++local.discarded;
                        continue;
                    }
                    scene.film.AddSample(p, L, cs.filterWeight);
                }
            progress.Update();
        });
        done = last;
    }
    progress.Done();

    RenderStatistics stats;
    stats.seconds = progress.ElapsedSeconds();
    stats.samplesPerPixel = done;
    stats.cameraSamples = int64_t(pixels.Area()) * done;
    for (const ThreadCounts &c : counts) {
        stats.closestRays += c.rays.closest;
        stats.shadowRays += c.rays.shadow;
        stats.discardedSamples += c.discarded;
    }
    return stats;
}

}  // namespace pbrt
