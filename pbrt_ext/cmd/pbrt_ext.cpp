// pbrt_ext: renders a pbrt-v4 scene file.
//
// Usage: pbrt_ext [options] scene.pbrt. Every option is documented by --help with its default; an
// unknown option is an error. Bad input (scene, meshes, images, options) is reported as
// "file:line:col: error: ..." with a non-zero exit, and no image is written. Ctrl-C during the
// render writes the image rendered so far and exits with status 130 (cmd/interrupt.h).
#include "pbrt_ext/cmd/interrupt.h"
#include "pbrt_ext/lightsamplers.h"
#include "pbrt_ext/options.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/sceneloader.h"
#include "pbrt_ext/util/log.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

struct CommandLine {
    std::string sceneFile;
    RenderOverrides overrides;
};

// Parses argv into the overrides; returns an exit code when the program should stop (help, or an
// error that CLI11 already printed), or -1 to go on.
int ParseCommandLine(int argc, char **argv, CommandLine *cmd) {
    CLI::App app("pbrt_ext: a compact pbrt-v4-style path tracer with the DreamWorks fabric BxDF",
                 "pbrt_ext");
    RenderOverrides &o = cmd->overrides;
    int spp = 0;
    std::string strategy, fabricSampler;
    std::vector<float> crop;
    std::vector<int> pixels;
    app.add_option("scene", cmd->sceneFile, "pbrt-v4 scene file")->required();
    app.add_option("--spp", spp, "samples per pixel (default: the scene's Sampler)");
    app.add_option("--nthreads", o.nThreads, "render threads (default: 0, all cores)");
    app.add_option("--seed", o.seed, "seed of the samplers (default: 0)");
    app.add_option("--outfile", o.outFile,
                   "output image, EXR or any OpenImageIO format by extension (default: the "
                   "scene's Film filename)");
    app.add_flag("--quiet", o.quiet, "no progress bar and no warnings (default: off)");
    app.add_flag("--stats", o.stats, "print render statistics at the end (default: off)");
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
    app.add_option("--light-sampler", o.lightSampler,
                   "bvh, power or uniform: how next-event estimation picks a light (default: "
                   "the integrator's \"lightsampler\", bvh unless it says)")
        ->check([](const std::string &name) { return LightSamplerNameError(name).value_or(""); });
    app.add_option("--sampler", o.sampler,
                   "zsobol, halton, sobol, paddedsobol, stratified or independent: the sample "
                   "generator, with its default randomization (default: the scene's Sampler)")
        ->check([](const std::string &name) { return SamplerNameError(name).value_or(""); });
    app.add_option("--integrator", o.integrator,
                   "path, volpath, bdpt, lightpath or sppm: the integrator, with the scene's "
                   "maxdepth and the others' defaults (default: the scene's Integrator)")
        ->check([](const std::string &name) { return IntegratorNameError(name).value_or(""); });
    app.add_option("--time-limit", o.timeLimitSeconds,
                   "stop after this many seconds with every pixel at the same sample count "
                   "(default: 0, no limit)");
    try {
        app.parse(argc, argv);
        if (spp != 0) {
            if (spp < 0)
                throw CLI::ValidationError("--spp", "must be positive");
            o.spp = spp;
        }
        if (crop.size() == 4)
            o.cropWindow = Bounds2f(Point2f(crop[0], crop[2]), Point2f(crop[1], crop[3]));
        if (pixels.size() == 4)
            o.pixelBounds = Bounds2i(Point2i(pixels[0], pixels[2]), Point2i(pixels[1], pixels[3]));
        if (!strategy.empty())
            o.strategy = ParsePathStrategy(strategy);
        if (!fabricSampler.empty())
            o.fabricSampler = ParseFabricSampling(fabricSampler);
    } catch (const CLI::ParseError &e) {
        return app.exit(e);
    } catch (const std::invalid_argument &e) {
        std::fprintf(stderr, "pbrt_ext: error: %s\n", e.what());
        return 2;
    }
    return -1;
}

// Renders the scene and writes its image: all of it, or, when Ctrl-C stopped the render, what
// was rendered, with kInterruptedExitStatus.
int RenderAndWriteImage(Scene &scene, const CommandLine &cmd) {
    const RenderOverrides &o = cmd.overrides;
    BeginInterruptibleRender();
    if (!o.quiet) {
        Vector2i size = scene.film.PixelBounds().Diagonal();
        std::fprintf(stderr,
                     "pbrt_ext: rendering %d x %d pixels at %d samples per pixel (Ctrl-C stops "
                     "and writes the image)\n",
                     size.x, size.y, scene.sampler.SamplesPerPixel());
    }
    RenderStatistics stats =
        Render(scene, {o.nThreads, o.quiet, o.timeLimitSeconds, &RenderInterrupt()});
    EndInterruptibleRender();

    ImageMetadata metadata;
    metadata.samplesPerPixel = stats.samplesPerPixel;
    metadata.renderTimeSeconds = stats.seconds;
    metadata.scene = cmd.sceneFile;
    metadata.interrupted = stats.cancelled;
    metadata.maxSamplesPerPixel = stats.maxSamplesPerPixel;
    scene.film.WriteImage(metadata);
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
