#include "pbrt_ext/integrators/mlt.h"

#include "pbrt_ext/integrators/bdpt.h"
#include "pbrt_ext/integrators/bdptvertex.h"
#include "pbrt_ext/samplers/mltsampler.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/progressreporter.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace pbrt {

namespace {

// The primary sample vector's streams: each subpath and the connection read their own.
constexpr int kCameraStream = 0, kLightStream = 1, kConnectionStream = 2, kStreamCount = 3;
// How many mutations a chain makes between looks at the cancel flag and the clock.
constexpr int64_t kMutationsBetweenChecks = 256;
// The most memory the chains' own splat sums may take (24 bytes a pixel, per thread); past it,
// they splat into the film's sums, in the order the threads happen to run.
constexpr size_t kMaxOwnSplatBytes = size_t(1) << 30;

// A path's estimate, where it lands on the film, and its wavelengths. Chains sample paths in
// proportion to the estimate's Luminance (pbrt-v4's c(L)).
struct PathSample {
    SampledSpectrum L;
    Point2f pRaster;
    SampledWavelengths lambda;
};

// The bootstrap: luminances of paths from nBootstrap sample vectors at each depth, which give
// the normalization b and the chains' starting states.
struct Bootstrap {
    std::vector<double> cdf;  // running sums of the luminances, by rngIndex
    double b = 0;

    // The rngIndex (i (maxDepth + 1) + depth) of a start, in proportion to its luminance.
    int64_t Sample(Float u) const {
        auto it = std::upper_bound(cdf.begin(), cdf.end(), double(u) * cdf.back());
        return std::min<int64_t>(it - cdf.begin(), int64_t(cdf.size()) - 1);
    }
};

class MLT {
  public:
    MLT(Scene &scene, const RenderOptions &renderOptions)
        : scene(scene),
          renderOptions(renderOptions),
          options(scene.integratorOptions.mlt),
          maxDepth(scene.integratorOptions.maxDepth),
          sampleBounds(SampleBounds(scene)),
          bdpt(scene, scene.integratorOptions, sampleBounds.Area()),
          rayDifferentialScale(std::max<Float>(0.125f, 1 / std::sqrt(Float(options.mutationsPerPixel)))) {}

    RenderStatistics Render();

  private:
    static Bounds2f SampleBounds(const Scene &scene);
    // An MLTSampler, as the Sampler that bdpt's subpaths read.
    Sampler NewSampler(int64_t rngIndex) const {
        return MLTSampler(options.mutationsPerPixel, rngIndex, options.sigma,
                          options.largeStepProbability, kStreamCount, options.seed);
    }
    // The path of the given depth that the sampler's values make, by the strategy they choose.
    PathSample L(Sampler &sampler, int depth, RayCounts &rays) const;
    Bootstrap RunBootstrap(ProgressReporter &progress);
    // Runs one chain of the given length from a start the bootstrap chooses, splatting into sums
    // (the film's if null); returns the mutations made (fewer if stopped).
    int64_t RunChain(int64_t chain, const Bootstrap &bootstrap, int64_t mutations,
                     std::vector<double> *sums, ProgressReporter &progress, RayCounts &rays);
    // Runs chains [first, last) the same way.
    int64_t RunChains(int64_t first, int64_t last, const Bootstrap &bootstrap, int64_t totalMutations,
                      std::vector<double> *sums, ProgressReporter &progress, RayCounts &rays);
    void Splat(const PathSample &path, Float weight, std::vector<double> *sums) {
        if (sums)
            scene.film.AddSplat(path.pRaster, path.L * weight, path.lambda, *sums);
        else
            scene.film.AddSplat(path.pRaster, path.L * weight, path.lambda);
    }
    bool ShouldStop(const ProgressReporter &progress) const {
        return renderOptions.Cancelled() || (renderOptions.timeLimitSeconds > 0 &&
                             progress.ElapsedSeconds() >= renderOptions.timeLimitSeconds);
    }

    Scene &scene;
    const RenderOptions &renderOptions;
    const MLTOptions &options;
    int maxDepth;
    Bounds2f sampleBounds;  // before bdpt, which is made with its area
    BDPTIntegrator bdpt;
    Float rayDifferentialScale;
    tbb::enumerable_thread_specific<RayCounts> rayCounts;
};

// pbrt-v4's Film::SampleBounds: where camera samples may fall for the filter to reach a pixel.
Bounds2f MLT::SampleBounds(const Scene &scene) {
    Bounds2i pixels = scene.film.PixelBounds();
    Vector2f radius = scene.film.GetFilter().Radius();
    return Bounds2f(Point2f(Float(pixels.pMin.x) + 0.5f - radius.x, Float(pixels.pMin.y) + 0.5f - radius.y),
                    Point2f(Float(pixels.pMax.x) - 0.5f + radius.x, Float(pixels.pMax.y) - 0.5f + radius.y));
}

PathSample MLT::L(Sampler &sampler, int depth, RayCounts &rays) const {
    PathSample path{SampledSpectrum(0.f), Point2f(), SampledWavelengths()};
    if (scene.lights.empty())
        return path;
    MLTSampler &streams = *sampler.Get<MLTSampler>();
    streams.StartStream(kCameraStream);
    // A depth d path has d + 2 vertices and as many strategies (s light, t camera vertices),
    // but depth 0, an emitter seen directly, has only s = 0.
    int nStrategies = depth == 0 ? 1 : depth + 2;
    int s = depth == 0 ? 0 : std::min(int(sampler.Get1D() * Float(nStrategies)), nStrategies - 1);
    int t = depth + 2 - s;
    path.lambda = scene.SampleWavelengths(sampler.Get1D());
    path.pRaster = sampleBounds.Lerp(sampler.GetPixel2D());
    CameraSample cs;
    cs.pFilm = path.pRaster;
    cs.time = sampler.Get1D();
    cs.pLens = sampler.Get2D();
    pstd::optional<CameraRayDifferential> cr = scene.GenerateCameraRay(cs, rayDifferentialScale);
    if (!cr || !cr->weight)
        return path;
    // Per thread, reused at the longest size (a vertex is 464 bytes: resizing between the
    // strategies' lengths would construct some at every path).
    thread_local std::vector<BDPTVertex> cameraVertices, lightVertices;
    if (cameraVertices.size() < size_t(maxDepth + 2)) {
        cameraVertices.resize(size_t(maxDepth + 2));
        lightVertices.resize(size_t(maxDepth + 2));
    }
    if (bdpt.GenerateCameraSubpath(cr->ray, path.lambda, sampler, rays, cameraVertices.data(), t) != t)
        return path;
    streams.StartStream(kLightStream);
    if (bdpt.GenerateLightSubpath(path.lambda, sampler, cameraVertices[0].time, rays,
                                  lightVertices.data(), s) != s)
        return path;
    streams.StartStream(kConnectionStream);
    pstd::optional<Point2f> pRasterNew;
    Float misWeight = 0;
    path.L = bdpt.ConnectBDPT(path.lambda, lightVertices.data(), cameraVertices.data(), s, t, sampler,
                              rays, &pRasterNew, &misWeight) *
             Float(nStrategies);
    if (pRasterNew)
        path.pRaster = *pRasterNew;
    return path;
}

Bootstrap MLT::RunBootstrap(ProgressReporter &progress) {
    const int depths = maxDepth + 1;
    std::vector<double> weights(size_t(options.bootstrapSamples) * size_t(depths), 0);
    tbb::parallel_for(int64_t(0), int64_t(options.bootstrapSamples), [&](int64_t i) {
        RayCounts &rays = rayCounts.local();
        for (int depth = 0; depth < depths; ++depth) {
            int64_t rngIndex = i * depths + depth;
            Sampler sampler = NewSampler(rngIndex);
            PathSample path = L(sampler, depth, rays);
            weights[size_t(rngIndex)] = Luminance(path.L, path.lambda);
        }
        progress.Update(depths);
    });
    Bootstrap bootstrap;
    bootstrap.cdf.resize(weights.size());
    std::partial_sum(weights.begin(), weights.end(), bootstrap.cdf.begin());
    if (!(bootstrap.cdf.back() > 0))
        throw std::runtime_error("mlt: none of the " + std::to_string(weights.size()) +
                                 " bootstrap paths carries light (\"bootstrapsamples\" " +
                                 std::to_string(options.bootstrapSamples) +
                                 "): the image would be black, or its light is too rare to find");
    bootstrap.b = double(depths) * bootstrap.cdf.back() / double(weights.size());
    return bootstrap;
}

int64_t MLT::RunChain(int64_t chain, const Bootstrap &bootstrap, int64_t mutations,
                      std::vector<double> *sums, ProgressReporter &progress, RayCounts &rays) {
    RNG rng(uint64_t(chain), MixBits(uint64_t(options.seed)));
    const int64_t start = bootstrap.Sample(rng.Uniform<Float>());
    const int depth = int(start % (maxDepth + 1));
    Sampler sampler = NewSampler(start);
    MLTSampler &mlt = *sampler.Get<MLTSampler>();
    PathSample current = L(sampler, depth, rays);
    Float cCurrent = Luminance(current.L, current.lambda);
    // The current state's splat weight, summed over the mutations it stays through and
    // splatted once it is left: the same splats, in fewer film updates.
    Float currentWeight = 0;
    int64_t made = 0;
    for (; made < mutations; ++made) {
        if (made % kMutationsBetweenChecks == kMutationsBetweenChecks - 1) {
            progress.Update(kMutationsBetweenChecks);
            if (ShouldStop(progress))
                break;
        }
        mlt.StartIteration();
        PathSample proposed = L(sampler, depth, rays);
        Float cProposed = Luminance(proposed.L, proposed.lambda);
        // A chain starts on a path with light; a proposal without any is never accepted.
        Float accept = cCurrent > 0 ? std::min<Float>(1, cProposed / cCurrent) : 1;
        // Both states, each weighted by the probability of the chain being in it next.
        if (accept > 0)
            Splat(proposed, accept / cProposed, sums);
        if (accept < 1)
            currentWeight += (1 - accept) / cCurrent;
        if (rng.Uniform<Float>() < accept) {
            if (currentWeight > 0)
                Splat(current, currentWeight, sums);
            current = proposed;
            cCurrent = cProposed;
            currentWeight = 0;
            mlt.Accept();
        } else {
            mlt.Reject();
        }
    }
    if (currentWeight > 0)
        Splat(current, currentWeight, sums);
    return made;
}

int64_t MLT::RunChains(int64_t first, int64_t last, const Bootstrap &bootstrap, int64_t totalMutations,
                       std::vector<double> *sums, ProgressReporter &progress, RayCounts &rays) {
    const int64_t nChains = options.chains;
    int64_t made = 0;
    for (int64_t chain = first; chain < last && !ShouldStop(progress); ++chain) {
        const int64_t mutations = std::min((chain + 1) * totalMutations / nChains, totalMutations) -
                                  chain * totalMutations / nChains;
        made += RunChain(chain, bootstrap, mutations, sums, progress, rays);
    }
    return made;
}

RenderStatistics MLT::Render() {
    const int64_t sampleArea = int64_t(sampleBounds.Area());
    const int64_t totalMutations = sampleArea * int64_t(options.mutationsPerPixel);
    const int64_t bootstrapPaths = options.bootstrapSamples * int64_t(maxDepth + 1);
    ProgressReporter progress(bootstrapPaths + totalMutations, "Rendering", renderOptions.quiet);
    const Bootstrap bootstrap = RunBootstrap(progress);

    // An even split of the chains over the threads, each part splatting into sums of its own.
    const int64_t parts = std::min<int64_t>(options.chains, tbb::this_task_arena::max_concurrency());
    const bool ownSums = scene.film.SplatSumsBytes() * size_t(parts) <= kMaxOwnSplatBytes;
    std::vector<std::vector<double>> sums(ownSums ? size_t(parts) : 0);
    std::vector<int64_t> made(size_t(parts), 0);
    tbb::parallel_for(int64_t(0), parts, [&](int64_t part) {
        made[size_t(part)] = RunChains(part * options.chains / parts, (part + 1) * options.chains / parts,
                                       bootstrap, totalMutations, ownSums ? &sums[size_t(part)] : nullptr,
                                       progress, rayCounts.local());
    }, tbb::static_partitioner());
    for (const std::vector<double> &s : sums)
        scene.film.AddSplatSums(s);
    progress.Done();

    const int64_t mutations = std::accumulate(made.begin(), made.end(), int64_t(0));
    RenderStatistics stats;
    stats.seconds = progress.ElapsedSeconds();
    stats.cameraSamples = bootstrapPaths + mutations + options.chains;
    stats.samplesPerPixel = stats.maxSamplesPerPixel = int(mutations / std::max<int64_t>(1, sampleArea));
    stats.cancelled = mutations < totalMutations && renderOptions.Cancelled();
    // pbrt-v4's b / mutationsPerPixel, with the mutations made.
    scene.film.SetSplatScale(Float(bootstrap.b * double(sampleArea) / double(std::max<int64_t>(1, mutations))));
    for (const RayCounts &r : rayCounts) {
        stats.closestRays += r.closest;
        stats.shadowRays += r.shadow;
    }
    return stats;
}

}  // namespace

RenderStatistics RenderMLT(Scene &scene, const RenderOptions &options) {
    return MLT(scene, options).Render();
}

}  // namespace pbrt
