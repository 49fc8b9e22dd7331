#include "pbrt_ext/render.h"

#include "pbrt_ext/integrators/function.h"
#include "pbrt_ext/integrators/guiding.h"
#include "pbrt_ext/integrators/imagetile.h"
#include "pbrt_ext/integrators/mlt.h"
#include "pbrt_ext/integrators/sppm.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/log.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>

namespace pbrt {

namespace {

TileIntegrator ChooseIntegrator(Scene &scene) {
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
    case IntegratorType::GuidedPath:
    case IntegratorType::GuidedVolPath:
        break;
    }
    return PathIntegrator(scene, o);
}

TileIntegrator MakeIntegrator(Scene &scene, const RenderOptions &options) {
    TileIntegrator integrator = ChooseIntegrator(scene);
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
    case IntegratorType::GuidedPath:
    case IntegratorType::GuidedVolPath:
        if (scene.integratorOptions.guiding.loadFile.empty())
            throw std::invalid_argument(std::string(IntegratorName(scene.integratorOptions.type)) +
                                        " renders a sample range only with a trained tree "
                                        "(--guiding-load): its training depends on the range");
        break;
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
    return buf + integratorStatistics;
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
    case IntegratorType::GuidedPath:
    case IntegratorType::GuidedVolPath:
        return RenderGuided(scene, samples, options);  // training iterations, then the image
    default:
        break;
    }
    return RenderTiles(scene, MakeIntegrator(scene, options), samples, options, "Rendering");
}

}  // namespace pbrt
