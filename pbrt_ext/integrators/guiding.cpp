#include "pbrt_ext/integrators/guiding.h"

#include "pbrt_ext/integrators/imagetile.h"
#include "pbrt_ext/integrators/sdtree.h"
#include "pbrt_ext/scene.h"

#include <fmt/format.h>

#include <chrono>

namespace pbrt {

namespace {

SDTreeOptions TreeOptions(const GuidingOptions &guiding) {
    SDTreeOptions options;
    options.maxBytes = guiding.maxBytes;
    options.bsdfFraction = guiding.bsdfFraction;
    options.learnBSDFFraction = guiding.learnBSDFFraction;
    return options;
}

struct Training {
    RenderStatistics render;  // of the training iterations together
    int samples = 0, iterations = 0;
    double seconds = 0;
};

// The statistics of two renders, one after the other, into one film.
void Add(RenderStatistics &total, const RenderStatistics &next) {
    total.cameraSamples += next.cameraSamples;
    total.closestRays += next.closestRays;
    total.shadowRays += next.shadowRays;
    total.discardedSamples += next.discardedSamples;
    total.samplesPerPixel += next.samplesPerPixel;
    total.maxSamplesPerPixel = total.samplesPerPixel - next.samplesPerPixel + next.maxSamplesPerPixel;
    total.cancelled |= next.cancelled;
}

// The guided integrator that samples from tree, and records into it where record: guidedvolpath's
// where there are media or subsurface materials to render, guidedpath's otherwise (as volpath is
// path there).
TileIntegrator GuidedIntegrator(const Scene &scene, SDTree &tree, bool record) {
    const IntegratorOptions &options = scene.integratorOptions;
    if (options.type == IntegratorType::GuidedVolPath && (!scene.media.empty() || scene.HasSubsurface()))
        return VolPathIntegrator(scene, options, PathGuide(tree, record));
    return GuidedPathIntegrator(scene, options, tree, record);
}

// Training iterations from sample index first (see the header comment); the tree learns.
Training Train(Scene &scene, SDTree &tree, SampleRange samples, const RenderOptions &options) {
    Training training;
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    RenderOptions quiet = options;
    quiet.quiet = true;
    quiet.timeLimitSeconds = 0;
    double lastSeconds = 0;
    for (int k = 0;; ++k) {
        const int n = 1 << k;
        if (2 * (training.samples + n) > samples.Count() || options.Cancelled())
            break;
        // Under a time limit: only while the next iteration (twice the last) fits in half of it.
        if (options.timeLimitSeconds > 0 && elapsed() + 2 * lastSeconds > options.timeLimitSeconds / 2)
            break;
        const double before = elapsed();
        const int first = samples.first + training.samples;
        Add(training.render,
            RenderTiles(scene, GuidedIntegrator(scene, tree, true),
                        SampleRange{first, first + n}, quiet, "Training"));
        tree.Refine(k);
        training.samples += n;
        ++training.iterations;
        lastSeconds = elapsed() - before;
    }
    training.seconds = elapsed();
    return training;
}

std::string TreeStatistics(const SDTree &tree, const Training &training) {
    SDTree::Statistics s = tree.Stats();
    return fmt::format("guiding: {} training iterations, {} samples per pixel, {:.3f} s\n"
                       "guiding tree: {} spatial nodes, {} leaves, {} directional nodes (depth up to {}), "
                       "{:.1f} MB\n",
                       training.iterations, training.samples, training.seconds, s.spatialNodes, s.leaves,
                       s.directionalNodes, s.maxDirectionalDepth, double(s.bytes) / (1 << 20));
}

}  // namespace

RenderStatistics RenderGuided(Scene &scene, SampleRange samples, const RenderOptions &options) {
    const GuidingOptions &guiding = scene.integratorOptions.guiding;
    const Bounds3f bounds = scene.aggregate.WorldBound();
    SDTree tree = guiding.loadFile.empty() ? SDTree(bounds, TreeOptions(guiding))
                                           : SDTree::Read(guiding.loadFile, bounds, TreeOptions(guiding));
    Training training;
    if (guiding.loadFile.empty())
        training = Train(scene, tree, samples, options);
    if (!guiding.saveFile.empty())
        tree.Write(guiding.saveFile);
    RenderOptions final = options;
    if (options.timeLimitSeconds > 0)
        final.timeLimitSeconds = std::max(1e-3, options.timeLimitSeconds - training.seconds);
    const SampleRange rest{samples.first + training.samples, samples.last};
    RenderStatistics stats = RenderTiles(scene, GuidedIntegrator(scene, tree, false), rest, final, "Rendering");
    RenderStatistics total = training.render;
    Add(total, stats);
    total.seconds = training.seconds + stats.seconds;
    total.integratorStatistics = TreeStatistics(tree, training);
    return total;
}

}  // namespace pbrt
