// The scene options: camera, film, pixel filter, sampler, integrator (pbrt-v4's names and
// defaults; unsupported types map to the nearest supported one with a warning).
#include "pbrt_ext/scene/create.h"

#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace pbrt {

namespace {

// An entity whose type this renderer replaces: warn once, at its location.
void Substitute(const SceneEntity &entity, const char *what, const char *replacement) {
    WarningAt(entity.loc, "%s \"%s\" is not supported: rendering with %s instead", what,
              entity.name.c_str(), replacement);
}

Vector2f Radius(const ParameterDictionary &p, Float def) {
    return Vector2f(p.GetOneFloat("xradius", def), p.GetOneFloat("yradius", def));
}

// Film limits. Pixel coordinates are 32-bit floats, which past 2^24 cannot tell neighbouring
// pixels apart. The film counts its pixels in an int (Bounds2i::Area). Per rendered pixel it
// keeps four double sums, and writing adds the output image's three floats and, for 8-bit
// formats, three encoded bytes.
constexpr int kMaxResolution = 1 << 24;
constexpr uint64_t kFilmBytesPerPixel = 4 * sizeof(double) + 3 * sizeof(float) + 3;

// Where the resolution was written, for errors about the film's size.
FileLoc ResolutionLoc(const SceneEntity &e) {
    for (const char *name : {"xresolution", "yresolution"})
        if (const FileLoc *loc = e.parameters.Loc(name))
            return *loc;
    return e.loc;
}

void CheckResolution(const SceneEntity &e, Point2i resolution) {
    if (resolution.x <= 0 || resolution.y <= 0)
        throw ParseError(e.loc, "film resolution must be positive");
    for (int axis = 0; axis < 2; ++axis) {
        const char *name = axis == 0 ? "xresolution" : "yresolution";
        if (resolution[axis] > kMaxResolution)
            throw ParseError(*e.parameters.Loc(name),
                             fmt::format("{} {} is too large; expected at most {} (2^24: pixel "
                                         "coordinates are 32-bit floats)",
                                         name, resolution[axis], kMaxResolution));
    }
}

// Before the film allocates: the rendered pixels (those of pixelBounds inside the image; the
// film rejects any others) must be countable in an int and fit the memory budget.
// extraBytesPerPixel: the spectral film's bands' or the g-buffer's.
void CheckFilmSize(const SceneEntity &e, Point2i resolution, Bounds2i pixelBounds,
                   uint64_t extraBytesPerPixel) {
    Bounds2i rendered = Intersect(pixelBounds, Bounds2i(Point2i(0, 0), resolution));
    int64_t width = std::max(0, rendered.pMax.x - rendered.pMin.x),
            height = std::max(0, rendered.pMax.y - rendered.pMin.y);
    std::string what = fmt::format("the film's {} x {} pixels", width, height);
    if (width * height > std::numeric_limits<int>::max())
        throw ParseError(ResolutionLoc(e), fmt::format("{} are {} in all; expected at most {}",
                                                       what, width * height,
                                                       std::numeric_limits<int>::max()));
    CheckMemory(ResolutionLoc(e), what,
                SaturatingProduct({uint64_t(width * height), kFilmBytesPerPixel + extraBytesPerPixel}));
}

// The sampler constructors reject sample counts they cannot represent; the error goes where the
// count was set: the command line's --spp, else the first of `counts` the sampler was given.
template <typename Make>
Sampler MakeSampler(const SceneEntity &e, const RenderOverrides &overrides,
                    std::initializer_list<const char *> counts, Make make) {
    try {
        return make();
    } catch (const std::runtime_error &error) {
        FileLoc loc = e.loc;
        if (overrides.spp)
            loc = FileLoc{"--spp", 0, 0};
        else
            for (const char *name : counts)
                if (const FileLoc *written = e.parameters.Loc(name)) {
                    loc = *written;
                    break;
                }
        throw ParseError(loc, error.what());
    }
}

// What chose the film's pixel bounds: the command line's --pixelbounds or --cropwindow, else the
// file's "pixelbounds" or "cropwindow", else the Film directive.
FileLoc PixelBoundsLoc(const SceneEntity &e, const RenderOverrides &overrides) {
    if (overrides.pixelBounds)
        return FileLoc{"--pixelbounds", 0, 0};
    if (overrides.cropWindow)
        return FileLoc{"--cropwindow", 0, 0};
    for (const char *name : {"pixelbounds", "cropwindow"})
        if (const FileLoc *loc = e.parameters.Loc(name))
            return *loc;
    return e.loc;
}

// The film's own checks (a crop window that covers no pixel; pixel bounds empty or outside the
// image) throw std::runtime_error without a location: give them the location of the bounds.
template <typename Make>
auto WithPixelBoundsLoc(const SceneEntity &e, const RenderOverrides &overrides, Make make) {
    try {
        return make();
    } catch (const ParseError &) {
        throw;
    } catch (const std::runtime_error &error) {
        throw ParseError(PixelBoundsLoc(e, overrides), error.what());
    }
}

// The "randomization" of a low-discrepancy sampler, with pbrt-v4's defaults: permuted digits
// for Halton, whose prime bases have no fast Owen scramble, fast Owen for the Sobol' samplers.
// The "randomization" of a low-discrepancy sampler, with pbrt-v4's defaults: permuted digits
// for Halton, whose prime bases have no fast Owen scramble, fast Owen for the Sobol' samplers.
// A sampler named on the command line takes its default: the scene's was written for another.
RandomizeStrategy SamplerRandomization(const SceneEntity &e, const std::string &sampler, bool overridden) {
    const ParameterDictionary &p = e.parameters;
    bool halton = sampler == "halton";
    std::string fallback = halton ? "permutedigits" : "fastowen";
    std::string name = overridden ? fallback : p.GetOneString("randomization", fallback);
    if (name == "none") return RandomizeStrategy::None;
    if (name == "permutedigits") return RandomizeStrategy::PermuteDigits;
    if (name == "owen") return RandomizeStrategy::Owen;
    if (name == "fastowen" && !halton) return RandomizeStrategy::FastOwen;
    throw ParseError(*p.Loc("randomization"),
                     "unknown randomization \"" + name + "\" for the " + sampler +
                         " sampler: expected none, permutedigits" + (halton ? "" : ", fastowen") + " or owen");
}

}  // namespace

Filter CreateFilter(const SceneEntity &e) {
    const ParameterDictionary &p = e.parameters;
    Filter filter = GaussianFilter();
    if (e.name == "box") {
        filter = BoxFilter(Radius(p, 0.5f));
    } else if (e.name == "mitchell") {
        filter = MitchellFilter(Radius(p, 2), p.GetOneFloat("B", 1.f / 3), p.GetOneFloat("C", 1.f / 3));
    } else if (e.name == "triangle") {
        filter = TriangleFilter(Radius(p, 2));
    } else if (e.name == "gaussian" || e.name.empty()) {
        filter = GaussianFilter(Radius(p, 1.5f), p.GetOneFloat("sigma", 0.5f));
    } else if (e.name == "sinc" || e.name == "lanczos") {
        Substitute(e, "PixelFilter", "\"gaussian\"");
        return filter;  // its parameters belong to the filter we do not have
    } else {
        throw ParseError(e.loc, "unknown PixelFilter \"" + e.name +
                                    "\": expected box, gaussian, mitchell, triangle");
    }
    p.ReportUnused();
    return filter;
}

// pbrt-v4's PixelSensor::Create parameters: the sensor, ISO and white balance of the film, and
// the camera's exposure time.
PixelSensor CreateSensor(const SceneEntity &e, Float exposureTime) {
    const ParameterDictionary &p = e.parameters;
    std::string name = p.GetOneString("sensor", "cie1931");
    try {
        return PixelSensor::Create(name, p.GetOneFloat("iso", 100), p.GetOneFloat("whitebalance", 0),
                                   exposureTime, p.ColorSpace());
    } catch (const std::invalid_argument &error) {
        throw ParseError(p.Loc("sensor") ? *p.Loc("sensor") : e.loc, error.what());
    }
}

// The spectral film's bands: "nbuckets" (16), "lambdamin" (360) and "lambdamax" (830) nm, as
// pbrt-v4 reads them.
struct SpectralBands {
    Float lambdaMin = Lambda_min, lambdaMax = Lambda_max;
    int count = 16;
};

// The spectral and g-buffer films write channels only EXR keeps, as in pbrt-v4.
void CheckEXROutput(const SceneEntity &e, const std::string &filename) {
    if (!IsEXRFilename(filename))
        throw ParseError(e.loc, "Film \"" + e.name + "\" writes EXR only, not \"" + filename + "\"");
}

SpectralBands ReadSpectralBands(const SceneEntity &e, const std::string &filename) {
    const ParameterDictionary &p = e.parameters;
    CheckEXROutput(e, filename);
    return {p.GetOneFloat("lambdamin", Lambda_min), p.GetOneFloat("lambdamax", Lambda_max),
            p.GetOneInt("nbuckets", 16)};
}

// The g-buffer film's "coordinatesystem": true for "camera" (the default), false for "world".
bool ReadGBufferSpace(const SceneEntity &e, const std::string &filename) {
    const ParameterDictionary &p = e.parameters;
    CheckEXROutput(e, filename);
    std::string space = p.GetOneString("coordinatesystem", "camera");
    if (space != "camera" && space != "world")
        throw ParseError(*p.Loc("coordinatesystem"), "unknown \"coordinatesystem\" \"" + space +
                                                         "\": expected camera or world");
    return space == "camera";
}

RGBFilm CreateFilm(const SceneEntity &e, Float exposureTime, Filter filter,
                   const RenderOverrides &overrides) {
    const ParameterDictionary &p = e.parameters;
    if (e.name == "image")
        throw ParseError(e.loc, "Film \"image\" is pbrt-v3's: this is a pbrt-v3 scene; upgrade it "
                                "with pbrt-v4's `pbrt --upgrade old.pbrt > new.pbrt`");
    if (!e.name.empty() && e.name != "rgb" && e.name != "spectral" && e.name != "gbuffer")
        throw ParseError(e.loc, "unknown Film \"" + e.name + "\": expected rgb, spectral or gbuffer");
    Point2i resolution(p.GetOneInt("xresolution", 1280), p.GetOneInt("yresolution", 720));
    if (overrides.resolution) resolution = *overrides.resolution;
    if (overrides.quick)  // as pbrt-v4's --quick
        resolution = Point2i(std::max(1, resolution.x / 4), std::max(1, resolution.y / 4));
    CheckResolution(e, resolution);
    std::string filename = p.GetOneString("filename", "pbrt.exr");
    if (!overrides.outFile.empty())
        filename = overrides.outFile;
    // pbrt-v4's pixelbounds and cropwindow, the command line winning over the file.
    Bounds2i pixelBounds(Point2i(0, 0), resolution);
    std::vector<Float> crop = p.GetFloatArray("cropwindow");
    std::vector<int> pb = p.GetIntArray("pixelbounds");
    if (overrides.pixelBounds) {
        pixelBounds = *overrides.pixelBounds;
    } else if (overrides.cropWindow) {
        pixelBounds = WithPixelBoundsLoc(e, overrides, [&] {
            return PixelBoundsFromCropWindow(resolution, *overrides.cropWindow);
        });
    } else if (pb.size() == 4) {
        pixelBounds = Bounds2i(Point2i(pb[0], pb[2]), Point2i(pb[1], pb[3]));
    } else if (crop.size() == 4) {
        pixelBounds = WithPixelBoundsLoc(e, overrides, [&] {
            return PixelBoundsFromCropWindow(
                resolution, Bounds2f(Point2f(crop[0], crop[2]), Point2f(crop[1], crop[3])));
        });
    }
    PixelSensor sensor = CreateSensor(e, exposureTime);
    Float diagonal = p.GetOneFloat("diagonal", 35);
    if (!(diagonal > 0))
        throw ParseError(*p.Loc("diagonal"), fmt::format("\"diagonal\" {} mm is not positive", diagonal));
    p.GetOneBool("savefp16", true);
    Float maxComponent = p.GetOneFloat("maxcomponentvalue", Infinity);
    std::optional<SpectralBands> bands;
    if (e.name == "spectral") bands = ReadSpectralBands(e, filename);
    std::optional<bool> gbufferInCameraSpace;
    if (e.name == "gbuffer") gbufferInCameraSpace = ReadGBufferSpace(e, filename);
    p.ReportUnused();
    CheckFilmSize(e, resolution, pixelBounds,
                  (bands ? 24 * uint64_t(std::max(0, bands->count)) : 0) +
                      (gbufferInCameraSpace ? GBufferChannels::BytesPerPixel() : 0));
    RGBFilm film = WithPixelBoundsLoc(e, overrides, [&] {
        return RGBFilm(resolution, pixelBounds, std::move(filter), filename, maxComponent, sensor,
                       &p.ColorSpace(), diagonal / 1000);
    });
    if (gbufferInCameraSpace) film.EnableGBuffer(*gbufferInCameraSpace);
    try {
        if (bands) film.EnableSpectralBuckets(bands->lambdaMin, bands->lambdaMax, bands->count);
    } catch (const std::invalid_argument &error) {
        throw ParseError(e.loc, std::string("Film \"spectral\": ") + error.what());
    }
    return film;
}

Float ExposureTime(const CameraSceneEntity &e) {
    const ParameterDictionary &p = e.parameters;
    Float exposure = p.GetOneFloat("shutterclose", 1) - p.GetOneFloat("shutteropen", 0);
    if (!(exposure > 0))
        throw ParseError(p.Loc("shutterclose") ? *p.Loc("shutterclose") : e.loc,
                         fmt::format("the shutter interval {} is not positive; expected "
                                     "\"shutterclose\" after \"shutteropen\"", exposure));
    return exposure;
}

AnimatedTransform CreateAnimatedTransform(const FileLoc &loc, const Transform &start,
                                          Float startTime, const Transform &end, Float endTime,
                                          const std::string &what) {
    try {
        return AnimatedTransform(start, startTime, end, endTime);
    } catch (const std::invalid_argument &error) {
        throw ParseError(loc, what + error.what());
    }
}

Sampler CreateSampler(const SceneEntity &e, Point2i fullResolution,
                      const RenderOverrides &overrides) {
    const ParameterDictionary &p = e.parameters;
    int seed = p.GetOneInt("seed", overrides.seed);
    // --sampler replaces the scene's sampler; of the scene's parameters only the count carries
    // over, and the others are not reported unused.
    bool overridden = overrides.sampler.has_value();
    std::string name = overridden ? *overrides.sampler : e.name.empty() ? "zsobol" : e.name;
    int spp = overrides.spp.value_or(p.GetOneInt("pixelsamples", 16));
    if (overrides.quick) spp = 1;  // as pbrt-v4's --quick
    auto reportUnused = [&] {
        if (!overridden) p.ReportUnused();
    };
    if (name == "independent") {
        reportUnused();
        return MakeSampler(e, overrides, {"pixelsamples"}, [&] { return IndependentSampler(spp, seed); });
    }
    if (name == "stratified") {
        int xs = p.GetOneInt("xsamples", 4), ys = p.GetOneInt("ysamples", 4);
        bool jitter = p.GetOneBool("jitter", true);
        if (overrides.spp || overridden) {
            // pbrt-v4: the most square factorization of the requested count.
            int div = std::max(int(std::sqrt(double(spp))), 1);
            while (spp % div)
                --div;
            ys = spp / div;
            xs = spp / ys;
        }
        reportUnused();
        return MakeSampler(e, overrides, {"xsamples", "ysamples"},
                           [&] { return StratifiedSampler(xs, ys, jitter, seed); });
    }
    if (std::optional<std::string> error = SamplerNameError(name))
        throw ParseError(e.loc, *error);
    if (name == "pmj02bn") {
        reportUnused();
        return MakeSampler(e, overrides, {"pixelsamples"}, [&] { return PMJ02BNSampler(spp, seed); });
    }
    RandomizeStrategy randomize = SamplerRandomization(e, name, overridden);
    reportUnused();
    return MakeSampler(e, overrides, {"pixelsamples"}, [&]() -> Sampler {
        if (name == "halton") return HaltonSampler(spp, fullResolution, randomize, seed);
        if (name == "sobol") return SobolSampler(spp, fullResolution, randomize, seed);
        if (name == "paddedsobol") return PaddedSobolSampler(spp, randomize, seed);
        return ZSobolSampler(spp, fullResolution, randomize, seed);
    });
}

namespace {

// The smallest positive parameter value.
constexpr Float kTiny = std::numeric_limits<Float>::min();

// An integrator's parameter that must lie in [min, max], read with its default; a ParseError at
// its location otherwise, naming the integrator.
template <typename T>
T GetInRange(const ParameterDictionary &p, IntegratorType type, const std::string &name, T def,
             T min, T max, const char *expected) {
    T value;
    if constexpr (std::is_integral_v<T>)
        value = T(p.GetOneInt(name, int(def)));
    else
        value = T(p.GetOneFloat(name, Float(def)));
    if (!(value >= min && value <= max))
        throw ParseError(*p.Loc(name), std::string(IntegratorName(type)) + " \"" + name +
                                           "\" must be " + expected);
    return value;
}

void ReadMLTParameters(const ParameterDictionary &p, const RenderOverrides &overrides, MLTOptions &mlt) {
    constexpr int kIntMax = std::numeric_limits<int>::max();
    constexpr IntegratorType kMLT = IntegratorType::MLT;
    mlt.bootstrapSamples = GetInRange(p, kMLT, "bootstrapsamples", 100000, 1, kIntMax, "at least 1");
    mlt.chains = GetInRange(p, kMLT, "chains", 1000, 1, kIntMax, "at least 1");
    mlt.mutationsPerPixel = GetInRange(p, kMLT, "mutationsperpixel", 100, 1, kIntMax, "at least 1");
    // --spp is the mutations per pixel, as in pbrt-v4.
    if (overrides.spp)
        mlt.mutationsPerPixel = *overrides.spp;
    if (overrides.quick) {  // as pbrt-v4's --quick
        mlt.mutationsPerPixel = std::max(1, mlt.mutationsPerPixel / 16);
        mlt.bootstrapSamples = std::max<int64_t>(1, mlt.bootstrapSamples / 16);
    }
    mlt.largeStepProbability = GetInRange<Float>(p, kMLT, "largestepprobability", 0.3f, 0, 1, "in [0, 1]");
    mlt.sigma = GetInRange<Float>(p, kMLT, "sigma", 0.01f, kTiny, Infinity, "positive");
    mlt.seed = overrides.seed;
}

void ReadFunctionParameters(const ParameterDictionary &p, const RenderOverrides &overrides,
                            FunctionOptions &function) {
    std::string name = p.GetOneString("function", "step");
    std::optional<TestFunction> f = TestFunctionFromName(name);
    if (!f)
        throw ParseError(*p.Loc("function"), "unknown function \"" + name + "\": expected step, "
                         "diagonal, disk, checkerboard, rotatedcheckerboard or gaussian");
    function.function = *f;
    // pbrt-v4's: the table goes to --outfile, else to <function>-mse.txt, unless "filename" says.
    function.outputFile =
        p.GetOneString("filename", overrides.outFile.empty() ? name + "-mse.txt" : overrides.outFile);
    function.skipBad = p.GetOneBool("skipbad", true);
    function.imageFile = p.GetOneString("imagefilename", "");
    function.seed = overrides.seed;
}

// The parameters each integrator reads besides maxdepth (pbrt-v4's X::Create).
void ReadParameters(const ParameterDictionary &p, const RenderOverrides &overrides,
                    IntegratorOptions &options, std::string *lightSampler) {
    switch (options.type) {
    case IntegratorType::SimplePath:
        options.simplePath.sampleLights = p.GetOneBool("samplelights", true);
        options.simplePath.sampleBSDF = p.GetOneBool("samplebsdf", true);
        return;
    case IntegratorType::AmbientOcclusion:
        options.ambientOcclusion.cosSample = p.GetOneBool("cossample", true);
        options.ambientOcclusion.maxDistance =
            GetInRange(p, options.type, "maxdistance", Infinity, kTiny, Infinity, "positive");
        return;
    case IntegratorType::MLT:
        ReadMLTParameters(p, overrides, options.mlt);
        options.regularize = p.GetOneBool("regularize", false);
        return;
    case IntegratorType::Function:
        ReadFunctionParameters(p, overrides, options.function);
        return;
    case IntegratorType::SimpleVolPath:
    case IntegratorType::RandomWalk:
        return;
    case IntegratorType::BDPT:
        options.visualizeStrategies = p.GetOneBool("visualizestrategies", false);
        options.visualizeWeights = p.GetOneBool("visualizeweights", false);
        break;
    case IntegratorType::SPPM:
        options.photonsPerIteration = p.GetOneInt("photonsperiteration", -1);
        options.initialRadius = GetInRange<Float>(p, options.type, "radius", 1, kTiny, Infinity, "positive");
        options.photonSeed = p.GetOneInt("seed", overrides.seed);
        break;
    case IntegratorType::GuidedPath:
    case IntegratorType::GuidedVolPath:
        options.guiding.bsdfFraction = GetInRange<Float>(p, options.type, "bsdffraction", 0.5f, kTiny, 1,
                                                         "in (0, 1]");
        options.guiding.learnBSDFFraction = p.GetOneBool("learnbsdffraction", true);
        options.guiding.switchOff = p.GetOneBool("switchoff", true);
        options.guiding.maxBytes = size_t(GetInRange(p, options.type, "guidingmemory", 256, 1, 1 << 20,
                                                     "at least 1 (MB)")) << 20;
        options.guiding.saveFile = overrides.guidingSave;
        options.guiding.loadFile = overrides.guidingLoad;
        break;
    case IntegratorType::Path:
    case IntegratorType::VolPath:
    case IntegratorType::LightPath:
        break;
    }
    options.regularize = p.GetOneBool("regularize", false);
    std::string sampler = p.GetOneString("lightsampler", "bvh");
    if (std::optional<std::string> error = LightSamplerNameError(sampler))
        throw ParseError(*p.Loc("lightsampler"), *error);
    *lightSampler = overrides.lightSampler.value_or(sampler);
}

}  // namespace

IntegratorOptions CreateIntegrator(const SceneEntity &e, const RenderOverrides &overrides,
                                   std::string *lightSampler) {
    const ParameterDictionary &p = e.parameters;
    const std::string name = overrides.integrator.value_or(e.name.empty() ? "volpath" : e.name);
    std::optional<IntegratorType> type = IntegratorTypeFromName(name);
    if (!type)
        throw ParseError(e.loc, *IntegratorNameError(name));
    IntegratorOptions options;
    options.type = *type;
    // ambientocclusion and function have no depth (pbrt-v4 does not read it for them).
    if (options.type != IntegratorType::AmbientOcclusion && options.type != IntegratorType::Function)
        options.maxDepth = GetInRange(p, options.type, "maxdepth", 5, 0, std::numeric_limits<int>::max(),
                                      "at least 0");
    options.strategy = overrides.strategy.value_or(PathStrategy::MIS);
    options.photonSeed = overrides.seed;
    *lightSampler = overrides.lightSampler.value_or("bvh");
    // The command line's choice keeps only the scene's maxdepth: the other parameters are the
    // scene's integrator's, with its defaults.
    const bool overridden = overrides.integrator && *overrides.integrator != e.name;
    static const ParameterDictionary kNone;
    ReadParameters(overridden ? kNone : p, overrides, options, lightSampler);
    if (!overridden)
        p.ReportUnused();
    if (!IsGuided(options.type) && !(overrides.guidingSave + overrides.guidingLoad).empty())
        throw std::invalid_argument(std::string(overrides.guidingLoad.empty() ? "--guiding-save" : "--guiding-load") +
                                    ": the integrator is " + IntegratorName(options.type) +
                                    ", which learns no guiding tree (guidedpath and guidedvolpath do)");
    return options;
}

}  // namespace pbrt
