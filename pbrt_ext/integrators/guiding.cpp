#include "pbrt_ext/integrators/guiding.h"

#include "pbrt_ext/integrators/imagetile.h"
#include "pbrt_ext/integrators/inversevariance.h"
#include "pbrt_ext/integrators/samplemoments.h"
#include "pbrt_ext/integrators/sdtree.h"
#include "pbrt_ext/integrators/trainingschedule.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/log.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>

namespace pbrt {

namespace {

SDTreeOptions TreeOptions(const GuidingOptions &guiding) {
    SDTreeOptions options;
    options.maxBytes = guiding.maxBytes;
    options.bsdfFraction = guiding.bsdfFraction;
    options.learnBSDFFraction = guiding.learnBSDFFraction;
    return options;
}

// The trial (guiding.h) comes after this many training iterations (1 + 2 samples per pixel), in
// place of the next iteration (4: half guided, half not). Earlier than after 1 + 2 + 4 (with 8),
// which cost the Cornell box's 64 spp a fifth of path's efficiency before switching off (0.79 of
// its time to equal error; 0.88 this early), and kept guiding in the same scenes (docs/comparison.md).
constexpr int kTrialAfterIterations = 2;
// How sure the trial must be that guiding is the less efficient before it switches guiding off:
// the difference of the two estimators' variance times cost, in standard errors
// (SampleMoments::Compare). Switching off where guiding would have paid costs its whole gain,
// keeping it where it does not costs a fraction, so an uncertain trial keeps guiding.
constexpr double kSwitchOffZ = 2;

// What the trial measured: each estimator's cost per sample (in path rays, a guided ray counted
// as rayCost), and how they compare (a: guided, b: unguided). guidedpath's compares with the path
// tracer's variance as the guided samples estimate it (unguidedmoment.h), which the unguided
// samples' own (unguidedOwnVariance) underestimates where rare paths carry the light.
struct Trial {
    SampleMoments::Comparison comparison;
    double unguidedOwnVariance = 0;
    double guidedCostPerSample = 0, unguidedCostPerSample = 0;
    double rayCost = 0;
    int samples = 0;
    // Guided samples' efficiency (1 / (variance × cost)) over unguided ones'.
    double Efficiency() const { return comparison.Efficiency(guidedCostPerSample, unguidedCostPerSample); }
    bool GuidingPays() const { return !(comparison.z > kSwitchOffZ); }
};

struct Training {
    RenderStatistics render;  // of the training iterations together
    int samples = 0, iterations = 0;
    double seconds = 0;
    std::optional<Trial> trial;  // none where there was none, or it was cancelled
    bool SwitchedOff() const { return trial && !trial->GuidingPays(); }
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

// Whether the scene renders by volpath, guided or not: guidedvolpath where there are media or
// subsurface materials (elsewhere it is guidedpath, as volpath is path there).
bool RendersVolumes(const Scene &scene) {
    return scene.integratorOptions.type == IntegratorType::GuidedVolPath &&
           (!scene.media.empty() || scene.HasSubsurface());
}

// The guided integrator that samples from tree, and records into it where record: guidedvolpath's
// where there are media or subsurface materials to render, guidedpath's otherwise (as volpath is
// path there).
TileIntegrator GuidedIntegrator(const Scene &scene, SDTree &tree, bool record) {
    const IntegratorOptions &options = scene.integratorOptions;
    if (RendersVolumes(scene))
        return VolPathIntegrator(scene, options, PathGuide(tree, record));
    return GuidedPathIntegrator(scene, options, tree, record);
}

// What guiding samples in place of: volpath where there are media or subsurface materials, path
// otherwise.
TileIntegrator UnguidedIntegrator(const Scene &scene) {
    const IntegratorOptions &options = scene.integratorOptions;
    if (RendersVolumes(scene))
        return VolPathIntegrator(scene, options);
    return PathIntegrator(scene, options);
}

double CostPerSample(const RenderStatistics &stats, double rayCost) {
    return rayCost * double(stats.closestRays + stats.shadowRays) / double(std::max<int64_t>(1, stats.cameraSamples));
}

// Whether the trial can take the path tracer's variance from the guided samples
// (unguidedmoment.h): where the path tracer weighs by MIS (volpath always does), on a film that
// does not clamp (a clamped sample's value is not linear in its radiance).
bool EstimatesPath(const Scene &scene) {
    return (RendersVolumes(scene) || scene.integratorOptions.strategy == PathStrategy::MIS) &&
           std::isinf(scene.film.MaxComponentValue());
}

// Renders samples with the tree frozen, their first half guided and the rest not, and compares the
// two (guiding.h); none once cancelled (then without the second half).
std::optional<Trial> RenderTrial(Scene &scene, SDTree &tree, SampleRange samples, double rayCost,
                                 const RenderOptions &options, RenderStatistics &render,
                                 InverseVarianceCombination &combination) {
    const Bounds2i pixels = scene.film.PixelBounds();
    SampleMoments guided(pixels, EstimatesPath(scene)), unguided(pixels);
    const int middle = samples.first + samples.Count() / 2;
    const RenderStatistics a = RenderTiles(scene, GuidedIntegrator(scene, tree, false),
                                           SampleRange{samples.first, middle}, options, "Trial", &guided);
    Add(render, a);
    combination.EndRender(guided);
    if (options.Cancelled())
        return std::nullopt;
    const RenderStatistics b = RenderTiles(scene, UnguidedIntegrator(scene), SampleRange{middle, samples.last},
                                           options, "Trial", &unguided);
    Add(render, b);
    combination.EndRender(unguided);
    Trial trial;
    trial.rayCost = rayCost;
    trial.guidedCostPerSample = CostPerSample(a, rayCost);
    trial.unguidedCostPerSample = CostPerSample(b, 1);
    const SampleMoments::Comparison direct =
        SampleMoments::Compare(guided, trial.guidedCostPerSample, unguided, trial.unguidedCostPerSample);
    trial.unguidedOwnVariance = direct.varianceB;
    trial.comparison = direct;
    if (guided.EstimatesPath()) {
        const SampleMoments::Comparison estimated =
            SampleMoments::CompareWithPath(guided, trial.guidedCostPerSample, trial.unguidedCostPerSample);
        // Not where a path the path tracer takes too seldom for a double made the estimate infinite.
        if (std::isfinite(estimated.varianceB))
            trial.comparison = estimated;
    }
    trial.samples = samples.Count();
    return trial;
}

// Training iterations from sample index first, and the trial in place of one (see the header
// comment); the tree learns, and each render ends in combination.
Training Train(Scene &scene, SDTree &tree, SampleRange samples, const RenderOptions &options,
               InverseVarianceCombination &combination) {
    Training training;
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    RenderOptions quiet = options;
    quiet.quiet = true;
    quiet.timeLimitSeconds = 0;
    double lastSeconds = 0;
    for (int k = 0;; ++k) {
        const int n = IterationSamples(k);
        if (!IterationFits(training.samples, samples.Count(), k) || options.Cancelled())
            break;
        // Under a time limit: only while the next iteration (twice the last) fits in half of it.
        if (options.timeLimitSeconds > 0 && elapsed() + 2 * lastSeconds > options.timeLimitSeconds / 2)
            break;
        const double before = elapsed();
        const int first = samples.first + training.samples;
        const SampleRange iteration{first, first + n};
        if (k == kTrialAfterIterations && scene.integratorOptions.guiding.switchOff) {
            const double rayCost = GuidedRayCost(training.samples + n, samples.Count(), k + 1);
            training.trial = RenderTrial(scene, tree, iteration, rayCost, quiet, training.render, combination);
        } else {
            SampleMoments moments(scene.film.PixelBounds());
            Add(training.render, RenderTiles(scene, GuidedIntegrator(scene, tree, true), iteration, quiet,
                                             "Training", &moments));
            combination.EndRender(moments);
            tree.Refine(k);
            ++training.iterations;
        }
        training.samples += n;
        if (training.SwitchedOff())
            break;
        lastSeconds = elapsed() - before;
    }
    training.seconds = elapsed();
    return training;
}

std::string TrialStatistics(const Trial &trial) {
    const SampleMoments::Comparison &c = trial.comparison;
    return fmt::format("guiding trial of {} samples per pixel: guided samples {:.2f} times as efficient as "
                       "unguided, z {:.1f} (guiding's excess of variance times cost, in standard errors); "
                       "relative variance {:.4g} and {:.4g} (unguided samples' own: {:.4g}), cost {:.1f} and "
                       "{:.1f} path rays (a guided ray counted as {:.2f} for the training and rendering to come); "
                       "guiding {}\n",
                       trial.samples, trial.Efficiency(), c.z, c.varianceA, c.varianceB, trial.unguidedOwnVariance,
                       trial.guidedCostPerSample,
                       trial.unguidedCostPerSample, trial.rayCost, trial.GuidingPays() ? "kept" : "switched off");
}

// The renders the image combines, each as samples per pixel and relative variance of one sample.
std::string CombinationStatistics(const InverseVarianceCombination &combination) {
    std::string renders;
    for (const InverseVarianceCombination::Weighed &w : combination.Renders())
        renders += fmt::format("{}{:.1f} spp {:.3g}", renders.empty() ? "" : ", ", w.samplesPerPixel,
                               w.relativeVariance);
    return fmt::format("guiding: renders combined by inverse variance (samples per pixel, relative variance of "
                       "one sample): {}\n", renders);
}

std::string TreeStatistics(const SDTree &tree, const Training &training, const InverseVarianceCombination *combination) {
    SDTree::Statistics s = tree.Stats();
    const std::string trial = training.trial ? TrialStatistics(*training.trial) : "";
    const std::string combined = combination ? CombinationStatistics(*combination) : "";
    return trial + combined + fmt::format("guiding: {} training iterations{}, {} samples per pixel, {:.3f} s\n"
                               "guiding tree: {} spatial nodes, {} leaves, {} directional nodes (depth up to {}), "
                               "{:.1f} MB\n",
                               training.iterations, training.trial ? " and the trial" : "", training.samples,
                               training.seconds, s.spatialNodes, s.leaves, s.directionalNodes,
                               s.maxDirectionalDepth, double(s.bytes) / (1 << 20));
}

}  // namespace

RenderStatistics RenderGuided(Scene &scene, SampleRange samples, const RenderOptions &options) {
    const GuidingOptions &guiding = scene.integratorOptions.guiding;
    const Bounds3f bounds = scene.aggregate.WorldBound();
    SDTree tree = guiding.loadFile.empty() ? SDTree(bounds, TreeOptions(guiding))
                                           : SDTree::Read(guiding.loadFile, bounds, TreeOptions(guiding));
    // With a tree read, one render: nothing to combine, and its slices merge exactly.
    std::optional<InverseVarianceCombination> combination;
    Training training;
    if (guiding.loadFile.empty())
        training = Train(scene, tree, samples, options, combination.emplace(scene.film));
    if (!guiding.saveFile.empty()) {
        tree.Write(guiding.saveFile);
        if (training.SwitchedOff() && !options.quiet)
            Warning("guiding was switched off by its trial (\"bool switchoff\" false keeps it on): %s holds the tree "
                    "of %d training iterations", guiding.saveFile.c_str(), training.iterations);
    }
    RenderOptions final = options;
    if (options.timeLimitSeconds > 0)
        final.timeLimitSeconds = std::max(1e-3, options.timeLimitSeconds - training.seconds);
    const SampleRange rest{samples.first + training.samples, samples.last};
    std::optional<SampleMoments> moments;
    if (combination)
        moments.emplace(scene.film.PixelBounds());
    RenderStatistics stats =
        RenderTiles(scene, training.SwitchedOff() ? UnguidedIntegrator(scene) : GuidedIntegrator(scene, tree, false),
                    rest, final, "Rendering", moments ? &*moments : nullptr);
    if (combination) {
        combination->EndRender(*moments);
        combination->Finish();
    }
    RenderStatistics total = training.render;
    Add(total, stats);
    total.seconds = training.seconds + stats.seconds;
    total.integratorStatistics = TreeStatistics(tree, training, combination ? &*combination : nullptr);
    return total;
}

}  // namespace pbrt
