// pbrt_ext: renders a pbrt-v4 scene file.
//
// Usage: pbrt_ext [options] scene.pbrt, or pbrt_ext merge OUT.exr SLICE.exr... (cmd/merge.h).
// Every option is documented by --help with its default; an unknown option is an error. Bad input (scene, meshes, images, options) is reported as
// "file:line:col: error: ..." with a non-zero exit, and no image is written. Ctrl-C during the
// render writes the image rendered so far and exits with status 130 (cmd/interrupt.h).
#include "pbrt_ext/cmd/interrupt.h"
#include "pbrt_ext/cmd/merge.h"
#include "pbrt_ext/film/filmslice.h"
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/options.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/log.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

struct CommandLine {
    std::string sceneFile;
    RenderOverrides overrides;
    // --samples: render a slice (filmslice.h), indices A:B or part k/K of the sampler's.
    std::string samples;
};

// "A:B" with 0 <= A < B, or "k/K" with 0 <= k < K: the k-th of K ranges as equal as spp
// allows. Throws CLI::ValidationError otherwise.
SampleRange ParseSampleRange(const std::string &text, int spp) {
    long a = 0, b = 0;
    char separator = 0, rest = 0;
    std::istringstream in(text);
    bool ok = (in >> a >> separator >> b) && !(in >> rest) && a >= 0 && a < b && b <= (1 << 30);
    if (ok && separator == ':')
        return {int(a), int(b)};
    if (ok && separator == '/' && b <= spp)
        return {int(a * spp / b), int((a + 1) * spp / b)};
    throw CLI::ValidationError("--samples", "\"" + text + "\": expected A:B with 0 <= A < B, or k/K with "
                               "0 <= k < K <= the samples per pixel (" + std::to_string(spp) + ")");
}

// Parses argv into the overrides; returns an exit code when the program should stop (help, or an
// error that CLI11 already printed), or -1 to go on.
int ParseCommandLine(int argc, char **argv, CommandLine *cmd) {
    CLI::App app("pbrt_ext: a compact pbrt-v4-style path tracer with the DreamWorks fabric BxDF",
                 "pbrt_ext");
    RenderOverrides &o = cmd->overrides;
    int spp = 0;
    std::string strategy, fabricSampler, layeredEstimator;
    std::vector<float> crop;
    std::vector<int> pixels, resolution;
    app.add_option("scene", cmd->sceneFile, "pbrt-v4 scene file")->required();
    app.add_option("--spp", spp, "samples per pixel (default: the scene's Sampler)");
    app.add_option("--nthreads", o.nThreads, "render threads (default: 0, all cores)");
    app.add_option("--seed", o.seed, "seed of the samplers (default: 0)");
    app.add_option("--outfile", o.outFile,
                   "output image, EXR or any OpenImageIO format by extension (default: the "
                   "scene's Film filename)");
    app.add_flag("--quiet", o.quiet, "no progress bar and no warnings (default: off)");
    app.add_flag("--stats", o.stats, "print render statistics at the end (default: off)");
    app.add_option("--resolution", resolution,
                   "x y: the film's resolution instead of its xresolution and yresolution "
                   "(default: the scene's)")
        ->expected(2)
        ->check(CLI::Range(1, 1 << 24));
    app.add_option("--samples", cmd->samples,
                   "A:B or k/K: render only sample indices A to B-1 of every pixel, or the k-th "
                   "of K equal parts (from 0), of the sampler's spp; the EXR keeps what "
                   "`pbrt_ext merge` needs to add slices up to the render of all their samples "
                   "(default: all samples)");
    app.add_option("--cropwindow", crop, "x0 x1 y0 y1: render only this part of the image, in "
                                         "[0, 1] (default: the scene's)")
        ->expected(4);
    app.add_option("--pixelbounds", pixels, "x0 x1 y0 y1: render only these pixels (default: "
                                            "the scene's; wins over --cropwindow)")
        ->expected(4);
    app.add_option("--strategy", strategy,
                   "mis, bsdf or light: how paths find light (default: mis)");
    app.add_option("--fabric-sampler", fabricSampler,
                   "uniform, cosine, paper, truncatedsinphi or best: the sampler of every fabric "
                   "material (default: each material's, best unless it says)");
    app.add_option("--layered-estimator", layeredEstimator,
                   "unbiased or pbrt-v4: the coated materials' BSDF estimator; pbrt-v4's weighs "
                   "one MIS connection with the wrong density and is biased bright for rough "
                   "coats (docs/comparison.md), kept to reproduce pbrt-v4's images (default: "
                   "unbiased)");
    app.add_option("--displacement-edge-scale", o.displacementEdgeScale,
                   "multiply the \"edgelength\" of every displaced mesh by this; a scene's Option "
                   "\"displacementedgescale\" wins over it, as in pbrt-v4 (default: 1)");
    app.add_option("--light-sampler", o.lightSampler,
                   "bvh, bvh-pbrt-v4, power or uniform: how next-event estimation picks a light; "
                   "bvh weighs distant and infinite lights against the others by what they can "
                   "give the point, bvh-pbrt-v4 picks them as often as all the others together, "
                   "as pbrt-v4 does (default: the integrator's \"lightsampler\", bvh unless it "
                   "says)")
        ->check([](const std::string &name) { return LightSamplerNameError(name).value_or(""); });
    app.add_option("--sampler", o.sampler,
                   "zsobol, halton, sobol, paddedsobol, stratified or independent: the sample "
                   "generator, with its default randomization (default: the scene's Sampler)")
        ->check([](const std::string &name) { return SamplerNameError(name).value_or(""); });
    app.add_option("--integrator", o.integrator,
                   "path, volpath, bdpt, lightpath, sppm, mlt, simplepath, simplevolpath, "
                   "randomwalk, ambientocclusion, function or guidedpath: the integrator, with the scene's "
                   "maxdepth and the others' defaults (default: the scene's Integrator)")
        ->check([](const std::string &name) { return IntegratorNameError(name).value_or(""); });
    app.add_option("--time-limit", o.timeLimitSeconds,
                   "stop after this many seconds with every pixel at the same sample count "
                   "(default: 0, no limit)");
    app.add_option("--guiding-save", o.guidingSave,
                   "guidedpath: write the trained SD-tree to this file (default: none)");
    app.add_option("--guiding-load", o.guidingLoad,
                   "guidedpath: render with the SD-tree of this file instead of training one, so that "
                   "sample slices (--samples) merge exactly (default: train)")
        ->check(CLI::ExistingFile);
    try {
        app.parse(argc, argv);
        if (spp != 0) {
            if (spp < 0)
                throw CLI::ValidationError("--spp", "must be positive");
            o.spp = spp;
        }
        if (!(o.displacementEdgeScale > 0) || !std::isfinite(o.displacementEdgeScale))
            throw CLI::ValidationError("--displacement-edge-scale", "must be positive and finite");
        if (resolution.size() == 2)
            o.resolution = Point2i(resolution[0], resolution[1]);
        if (crop.size() == 4)
            o.cropWindow = Bounds2f(Point2f(crop[0], crop[2]), Point2f(crop[1], crop[3]));
        if (pixels.size() == 4)
            o.pixelBounds = Bounds2i(Point2i(pixels[0], pixels[2]), Point2i(pixels[1], pixels[3]));
        if (!strategy.empty())
            o.strategy = ParsePathStrategy(strategy);
        if (!fabricSampler.empty())
            o.fabricSampler = ParseFabricSampling(fabricSampler);
        if (!layeredEstimator.empty())
            o.layeredExitMIS = ParseLayeredEstimator(layeredEstimator);
    } catch (const CLI::ParseError &e) {
        return app.exit(e);
    } catch (const std::invalid_argument &e) {
        std::fprintf(stderr, "pbrt_ext: error: %s\n", e.what());
        return 2;
    }
    return -1;
}

std::string FileContents(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The film's image; for --samples, a slice of the samples every pixel took (none when Ctrl-C
// left pixels with different counts: then the plain image, which no merge takes).
void WriteRender(const Scene &scene, const CommandLine &cmd, std::optional<SampleRange> samples,
                 const SliceIdentity &identity, const RenderStatistics &stats) {
    if (samples && stats.samplesPerPixel == stats.maxSamplesPerPixel) {
        const int first = samples->first;
        FilmSlice::FromFilm(scene.film, {first, first + stats.samplesPerPixel}, stats.seconds,
                            identity, cmd.sceneFile)
            .Write(scene.film.GetFilename());
        return;
    }
    ImageMetadata metadata;
    metadata.samplesPerPixel = stats.samplesPerPixel;
    metadata.renderTimeSeconds = stats.seconds;
    metadata.scene = cmd.sceneFile;
    metadata.interrupted = stats.cancelled;
    metadata.maxSamplesPerPixel = stats.maxSamplesPerPixel;
    scene.film.WriteImage(metadata);
}

// Renders the scene and writes its image: all of it, or, when Ctrl-C stopped the render, what
// was rendered, with kInterruptedExitStatus.
int RenderAndWriteImage(Scene &scene, const CommandLine &cmd) {
    const RenderOverrides &o = cmd.overrides;
    if (!cmd.samples.empty() && !IsEXRFilename(scene.film.GetFilename())) {
        std::fprintf(stderr, "pbrt_ext: error: --samples: the slice's sums need an EXR file, not \"%s\"\n",
                     scene.film.GetFilename().c_str());
        return 2;
    }
    RenderOptions options{o.nThreads, o.quiet, o.timeLimitSeconds, &RenderInterrupt()};
    SampleRange samples;
    try {
        if (!cmd.samples.empty())
            options.samples = ParseSampleRange(cmd.samples, scene.sampler.SamplesPerPixel());
        samples = SamplesToRender(scene, options);
    } catch (const CLI::ValidationError &e) {
        std::fprintf(stderr, "pbrt_ext: error: %s\n", e.what());
        return 2;
    } catch (const std::invalid_argument &e) {
        std::fprintf(stderr, "pbrt_ext: error: --samples: %s\n", e.what());
        return 2;
    }
    // The scene file's text as it was loaded, before a render that may take hours.
    SliceIdentity identity;
    if (options.samples)
        identity = MakeSliceIdentity(FileContents(cmd.sceneFile), scene.sampler,
                                     scene.integratorOptions, scene.film, o);
    BeginInterruptibleRender();
    if (!o.quiet) {
        Vector2i size = scene.film.PixelBounds().Diagonal();
        std::fprintf(stderr,
                     "pbrt_ext: rendering %d x %d pixels at %d samples per pixel (Ctrl-C stops "
                     "and writes the image)\n",
                     size.x, size.y, samples.Count());
    }
    RenderStatistics stats = Render(scene, options);
    EndInterruptibleRender();
    // The function integrator has written its error table; the film holds nothing.
    if (scene.integratorOptions.type == IntegratorType::Function) {
        if (!o.quiet)
            std::fprintf(stderr, "pbrt_ext: wrote %s\n", scene.integratorOptions.function.outputFile.c_str());
        return 0;
    }
    WriteRender(scene, cmd, options.samples, identity, stats);
    if (o.stats)
        std::printf("%s", stats.ToString().c_str());
    if (!stats.cancelled)
        return 0;
    std::string more;
    if (stats.maxSamplesPerPixel > stats.samplesPerPixel)
        more = " (" + std::to_string(stats.maxSamplesPerPixel) + " in part of the image)";
    std::fprintf(stderr, "pbrt_ext: interrupted: %d samples per pixel%s written to %s\n",
                 stats.samplesPerPixel, more.c_str(), scene.film.GetFilename().c_str());
    return kInterruptedExitStatus;
}

}  // namespace

int main(int argc, char **argv) {
    if (argc >= 2 && std::strcmp(argv[1], "merge") == 0)
        return MergeMain(argc - 1, argv + 1);
    CommandLine cmd;
    if (int exitCode = ParseCommandLine(argc, argv, &cmd); exitCode >= 0)
        return exitCode;
    Log().quiet = cmd.overrides.quiet;
    InstallInterruptHandler();
    try {
        std::unique_ptr<Scene> scene = LoadScene(cmd.sceneFile, cmd.overrides);
        return RenderAndWriteImage(*scene, cmd);
    } catch (const std::exception &e) {
        // ParseError's text is already "file:line:col: error: ..."; others say what failed.
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
}
