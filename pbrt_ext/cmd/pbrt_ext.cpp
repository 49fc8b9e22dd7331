// pbrt_ext: renders pbrt-v4 scene files, with pbrt-v4's command line (cmd/commandline.h).
//
// Usage: pbrt_ext [options] scene.pbrt..., or pbrt_ext merge OUT.exr SLICE.exr... (cmd/merge.h).
// Bad input (scene, meshes, images, options) is reported as "file:line:col: error: ..." and no
// image is written; the output file is checked before the render, so that a render is never lost
// to a name that can't be written. Ctrl-C during the render writes the image rendered so far
// (cmd/interrupt.h). Exit statuses: cmd/commandline.h.
#include "pbrt_ext/cmd/commandline.h"
#include "pbrt_ext/cmd/interrupt.h"
#include "pbrt_ext/cmd/merge.h"
#include "pbrt_ext/cmd/pixelmaterial.h"
#include "pbrt_ext/cmd/waveobservers.h"
#include "pbrt_ext/film/filmslice.h"
#include "pbrt_ext/film/pixelstatistics.h"
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/options.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/formatter.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/log.h"

#include <fmt/format.h>

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#ifndef PBRT_EXT_VERSION
#define PBRT_EXT_VERSION "unknown"
#endif

using namespace pbrt;

namespace {

// "A:B" with 0 <= A < B, or "k/K" with 0 <= k < K: the k-th of K ranges as equal as spp
// allows. Throws CommandLineError otherwise.
SampleRange ParseSampleRange(const std::string &text, int spp) {
    long a = 0, b = 0;
    char separator = 0, rest = 0;
    std::istringstream in(text);
    bool ok = (in >> a >> separator >> b) && !(in >> rest) && a >= 0 && a < b && b <= (1 << 30);
    if (ok && separator == ':')
        return {int(a), int(b)};
    if (ok && separator == '/' && b <= spp)
        return {int(a * spp / b), int((a + 1) * spp / b)};
    throw CommandLineError("--samples: \"" + text + "\": expected A:B with 0 <= A < B, or k/K with "
                           "0 <= k < K <= the samples per pixel (" + std::to_string(spp) + ")");
}

void Fail(const std::string &message) { std::fprintf(stderr, "pbrt_ext: error: %s\n", message.c_str()); }

// The scene's files; standard input ("-", or no file when it is not a terminal) read once.
std::vector<SceneFile> SceneFiles(const CommandLine &cmd) {
    std::vector<std::string> names = cmd.sceneFiles;
    if (names.empty()) {
        if (::isatty(STDIN_FILENO))
            throw CommandLineError("no scene file: give one or more, or - for standard input "
                                   "(pbrt_ext --help)");
        names.push_back("-");
    }
    std::vector<SceneFile> files;
    bool stdinRead = false;
    for (const std::string &name : names) {
        if (name != "-") {
            files.push_back({name, std::nullopt});
            continue;
        }
        if (stdinRead) throw CommandLineError("\"-\" (standard input) is given twice");
        stdinRead = true;
        std::string text{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
        files.push_back({"<stdin>", std::move(text)});
    }
    return files;
}

// The files' text as it was loaded (a slice's identity), before a render that may take hours.
std::string SceneText(const std::vector<SceneFile> &files) {
    std::string text;
    for (const SceneFile &file : files) {
        if (file.text) {
            text += *file.text;
            continue;
        }
        std::ifstream in(file.filename, std::ios::binary);
        text.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    return text;
}

// The film's image; for --samples, a slice of the samples every pixel took (none when Ctrl-C
// left pixels with different counts: then the plain image, which no merge takes).
void WriteRender(const Scene &scene, const std::string &sceneName, std::optional<SampleRange> samples,
                 const SliceIdentity &identity, const RenderStatistics &stats, const std::string &stopped) {
    if (samples && stats.samplesPerPixel == stats.maxSamplesPerPixel) {
        const int first = samples->first;
        FilmSlice::FromFilm(scene.film, {first, first + stats.samplesPerPixel}, stats.seconds,
                            identity, sceneName)
            .Write(scene.film.GetFilename());
        return;
    }
    ImageMetadata metadata;
    metadata.samplesPerPixel = stats.samplesPerPixel;
    metadata.renderTimeSeconds = stats.seconds;
    metadata.scene = sceneName;
    metadata.interrupted = stats.cancelled;
    metadata.maxSamplesPerPixel = stats.maxSamplesPerPixel;
    if (!stopped.empty()) metadata.extra["stoppedEarly"] = stopped;
    scene.film.WriteImage(metadata);
}

// --pixelstats: <outfile>-time.exr and <outfile>-rays.exr, each value in R, G and B, placed in
// the full image as the film's own image is.
void WritePixelStatistics(const PixelStatistics &stats, const RGBFilm &film) {
    const std::string base = std::filesystem::path(film.GetFilename()).replace_extension().string();
    const Vector2i size = stats.pixels.Diagonal();
    ImageMetadata metadata;
    metadata.fullResolution = film.FullResolution();
    metadata.pixelBounds = stats.pixels;
    for (const auto &[name, values] : {std::pair{"-time.exr", &stats.milliseconds}, {"-rays.exr", &stats.rays}}) {
        Image image(Point2i(size.x, size.y));
        for (int y = 0; y < size.y; ++y)
            for (int x = 0; x < size.x; ++x)
                for (int c = 0; c < 3; ++c)
                    image.SetChannel(Point2i(x, y), c, Float((*values)[size_t(y) * size.x + x]));
        image.Write(base + name, metadata);
    }
}

// What stopped the render before all its samples, for the user and the EXR; empty if nothing.
std::string StoppedEarly(const RenderStatistics &stats, const RenderOptions &options, int asked) {
    if (stats.cancelled) return "interrupted";
    if (options.timeLimitSeconds > 0 && stats.samplesPerPixel < asked)
        return fmt::format("time limit of {:g} s", options.timeLimitSeconds);
    return "";
}

// Renders the scene and writes its image: all of it, or, when Ctrl-C stopped the render, what
// was rendered, with kInterruptedExitStatus.
int RenderAndWriteImage(Scene &scene, const CommandLine &cmd, const std::vector<SceneFile> &files) {
    const RenderOverrides &o = cmd.overrides;
    const std::string &outFile = scene.film.GetFilename();
    // The function integrator writes a table of errors there, not an image.
    const bool writesImage = scene.integratorOptions.type != IntegratorType::Function;
    if (std::optional<std::string> error = writesImage ? ImageWriteError(outFile) : OutputFolderError(outFile)) {
        Fail(*error + "; nothing rendered");
        return cmd.overrides.outFile.empty() ? kExitBadInput : kExitBadCommandLine;
    }
    if (!cmd.samples.empty() && !IsEXRFilename(outFile)) {
        Fail("--samples: the slice's sums need an EXR file, not \"" + outFile + "\"");
        return kExitBadCommandLine;
    }
    RenderOptions options{o.nThreads, o.quiet, o.timeLimitSeconds, &RenderInterrupt()};
    WaveObservers observers(cmd, scene);
    std::optional<PixelStatistics> pixelStatistics;
    if (scene.options.pixelStats) options.pixelStatistics = &pixelStatistics.emplace(scene.film.PixelBounds());
    if (observers.Any())
        options.afterWave = [&](int samplesPerPixel) { observers.AfterWave(samplesPerPixel); };
    SampleRange samples;
    try {
        if (!cmd.samples.empty())
            options.samples = ParseSampleRange(cmd.samples, scene.sampler.SamplesPerPixel());
        samples = SamplesToRender(scene, options);
    } catch (const CommandLineError &e) {
        Fail(e.what());
        return kExitBadCommandLine;
    } catch (const std::invalid_argument &e) {
        Fail(std::string("--samples: ") + e.what());
        return kExitBadCommandLine;
    }
    SliceIdentity identity;
    if (options.samples)
        identity = MakeSliceIdentity(SceneText(files), scene.sampler, scene.integratorOptions,
                                     scene.film, o);
    BeginInterruptibleRender();
    if (!o.quiet) {
        Vector2i size = scene.film.PixelBounds().Diagonal();
        std::fprintf(stderr,
                     "pbrt_ext: rendering %d x %d pixels at %d samples per pixel with %s (Ctrl-C "
                     "stops and writes the image)\n",
                     size.x, size.y, samples.Count(), IntegratorName(scene.integratorOptions.type));
    }
    RenderStatistics stats = Render(scene, options);
    EndInterruptibleRender();
    observers.AfterRender();
    // The function integrator has written its error table; the film holds nothing.
    if (scene.integratorOptions.type == IntegratorType::Function) {
        if (!o.quiet)
            std::fprintf(stderr, "pbrt_ext: wrote %s\n", scene.integratorOptions.function.outputFile.c_str());
        return kExitSuccess;
    }
    const std::string sceneName = files.size() == 1 ? files[0].filename : files[0].filename + " ...";
    const std::string stopped = StoppedEarly(stats, options, samples.Count());
    WriteRender(scene, sceneName, options.samples, identity, stats, stopped);
    if (pixelStatistics) WritePixelStatistics(*pixelStatistics, scene.film);
    if (o.stats)
        std::printf("%s", stats.ToString().c_str());
    std::string more;
    if (stats.maxSamplesPerPixel > stats.samplesPerPixel)
        more = " (" + std::to_string(stats.maxSamplesPerPixel) + " in part of the image)";
    if (!stopped.empty() || !o.quiet)
        std::fprintf(stderr, "pbrt_ext: %s%s: %d of %d samples per pixel%s in %.1f s\n",
                     stopped.empty() ? "wrote " : (stopped + ": wrote ").c_str(), outFile.c_str(),
                     stats.samplesPerPixel, samples.Count(), more.c_str(), stats.seconds);
    return stats.cancelled ? kInterruptedExitStatus : kExitSuccess;
}

// --log-level and --log-file: pbrt-v4's. The file takes everything printed on standard error.
bool SetUpLogging(const CommandLine &cmd) {
    if (!cmd.logFile.empty() && !std::freopen(cmd.logFile.c_str(), "a", stderr)) {
        Fail("--log-file: cannot open \"" + cmd.logFile + "\" for appending: " + std::strerror(errno));
        return false;
    }
    Log().quiet = cmd.overrides.quiet || cmd.logLevel == LogLevel::Fatal;
    return true;
}

void LogVerbose(const CommandLine &cmd, const Scene &scene) {
    if (cmd.logLevel != LogLevel::Verbose && cmd.logFile.empty()) return;
    Point2i res = scene.film.FullResolution();
    std::fprintf(stderr, "pbrt_ext: scene loaded: %d x %d film, %d samples per pixel, %s, maxdepth %d, "
                 "%zu lights, writes %s\n", res.x, res.y, scene.sampler.SamplesPerPixel(),
                 IntegratorName(scene.integratorOptions.type), scene.integratorOptions.maxDepth,
                 scene.lights.size(), scene.film.GetFilename().c_str());
}

int Main(const CommandLine &cmd) {
    if (cmd.help) {
        std::printf("%s", CommandLineHelp().c_str());
        return kExitSuccess;
    }
    if (cmd.version) {
        std::printf("pbrt_ext %s\n", PBRT_EXT_VERSION);
        return kExitSuccess;
    }
    // Before the scene loads, which may take long; its extension once the integrator is known.
    if (!cmd.overrides.outFile.empty())
        if (std::optional<std::string> error = OutputFolderError(cmd.overrides.outFile)) {
            Fail("--outfile: " + *error);
            return kExitBadCommandLine;
        }
    if (!SetUpLogging(cmd)) return kExitBadCommandLine;
    std::vector<SceneFile> files = SceneFiles(cmd);
    if (cmd.reformat != CommandLine::Reformat::None) {
        std::optional<std::string> plyFolder;
        if (cmd.reformat == CommandLine::Reformat::ToPLY) plyFolder = ".";
        FormattingTarget formatter(std::cout, plyFolder, cmd.reformat == CommandLine::Reformat::Upgrade);
        ParseFiles(&formatter, files);
        return kExitSuccess;
    }
    if (cmd.wavefront && !cmd.overrides.quiet)
        std::fprintf(stderr, "pbrt_ext: --wavefront: rendering with volpath, the estimator of "
                             "pbrt-v4's wavefront integrator (it runs the same paths in another order)\n");
    InstallInterruptHandler();
    std::unique_ptr<Scene> scene = LoadScene(files, cmd.overrides);
    LogVerbose(cmd, *scene);
    if (cmd.pixelMaterial) {
        try {
            PrintPixelMaterial(*scene, *cmd.pixelMaterial, std::cout);
        } catch (const std::runtime_error &e) {
            Fail(e.what());
            return kExitBadInput;
        }
        return kExitSuccess;
    }
    return RenderAndWriteImage(*scene, cmd, files);
}

}  // namespace

int main(int argc, char **argv) {
    if (argc >= 2 && std::strcmp(argv[1], "merge") == 0)
        return MergeMain(argc - 1, argv + 1);
    try {
        return Main(ParseCommandLine(std::vector<std::string>(argv + 1, argv + argc)));
    } catch (const CommandLineError &e) {
        Fail(e.what());
        return kExitBadCommandLine;
    } catch (const std::exception &e) {
        // ParseError's text is already "file:line:col: error: ..."; others say what failed.
        std::fprintf(stderr, "%s\n", e.what());
        return kExitBadInput;
    }
}
