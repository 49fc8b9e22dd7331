#include "pbrt_ext/cmd/commandline.h"

#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/util/text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>
#include <string_view>

namespace pbrt {

namespace {

// One option: its name, the placeholder of its value (none for a flag), its help and default,
// and what it does to the command line.
struct OptionSpec {
    enum class Group { PbrtV4, Ours, NotApplicable };
    const char *name;
    const char *value;  // nullptr: a flag
    Group group;
    const char *help;
    std::function<void(CommandLine &, const std::string &)> apply;
};

// Numbers, whole: "4" but not "4x" or "".
template <typename T>
T Number(const std::string &option, const std::string &text, const char *expected) {
    T value{};
    const char *end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end)
        throw CommandLineError(fmt::format("--{}: \"{}\" is not {}", option, text, expected));
    if constexpr (std::is_floating_point_v<T>)
        if (!std::isfinite(value))
            throw CommandLineError(fmt::format("--{}: \"{}\" is not finite", option, text));
    return value;
}

int Int(const std::string &option, const std::string &text, int min) {
    int v = Number<int>(option, text, "an integer");
    if (v < min)
        throw CommandLineError(fmt::format("--{}: {} is less than {}", option, v, min));
    return v;
}

double Real(const std::string &option, const std::string &text) {
    return Number<double>(option, text, "a number");
}

// "a,b,c": exactly n numbers.
template <typename T>
std::vector<T> List(const std::string &option, const std::string &text, size_t n,
                    const char *placeholder) {
    std::vector<T> values;
    std::string item;
    std::istringstream in(text);
    while (std::getline(in, item, ','))
        values.push_back(Number<T>(option, item, std::is_integral_v<T> ? "an integer" : "a number"));
    if (values.size() != n || text.empty() || text.back() == ',')
        throw CommandLineError(fmt::format("--{}: \"{}\": expected {} comma-separated values, {}",
                                           option, text, n, placeholder));
    return values;
}

// pbrt-v4's "--flag=true" / "--flag=false"; a bare flag is true.
bool FlagValue(const std::string &option, const std::string &text) {
    if (text.empty() || NormalizeOptionName(text) == "true") return true;
    if (NormalizeOptionName(text) == "false") return false;
    throw CommandLineError(fmt::format("--{}: \"{}\": expected true or false", option, text));
}

std::string Checked(const std::string &option, const std::string &value,
                    std::optional<std::string> (*nameError)(const std::string &)) {
    if (std::optional<std::string> error = nameError(value))
        throw CommandLineError("--" + option + ": " + *error);
    return value;
}

template <typename Parse>
auto Named(const std::string &option, const std::string &value, Parse parse) {
    try {
        return parse(value);
    } catch (const std::invalid_argument &e) {
        throw CommandLineError("--" + option + ": " + e.what());
    }
}

// An option pbrt-v4 has that this renderer can't follow, and why.
std::function<void(CommandLine &, const std::string &)> NotApplicable(const char *name,
                                                                      const char *why) {
    return [name, why](CommandLine &, const std::string &) {
        throw CommandLineError(fmt::format("--{} is not supported: {}", name, why));
    };
}

using G = OptionSpec::Group;

const std::vector<OptionSpec> &Options() {
    static const std::vector<OptionSpec> options = {
        // pbrt-v4's, in its --help's order.
        {"cropwindow", "x0,x1,y0,y1", G::PbrtV4,
         "render only this part of the image, in [0,1]^2 (default: the film's)",
         [](CommandLine &c, const std::string &v) {
             auto w = List<float>("cropwindow", v, 4, "x0,x1,y0,y1");
             c.overrides.cropWindow = Bounds2f(Point2f(w[0], w[2]), Point2f(w[1], w[3]));
         }},
        {"disable-image-textures", nullptr, G::PbrtV4,
         "every image texture returns its average value",
         [](CommandLine &c, const std::string &v) {
             c.overrides.disableImageTextures = FlagValue("disable-image-textures", v);
         }},
        {"disable-pixel-jitter", nullptr, G::PbrtV4,
         "sample pixels at their centres (and the lens centre, at the middle of the shutter)",
         [](CommandLine &c, const std::string &v) {
             c.overrides.disablePixelJitter = FlagValue("disable-pixel-jitter", v);
         }},
        {"disable-texture-filtering", nullptr, G::PbrtV4, "point-sample every texture",
         [](CommandLine &c, const std::string &v) {
             c.overrides.disableTextureFiltering = FlagValue("disable-texture-filtering", v);
         }},
        {"disable-wavelength-jitter", nullptr, G::PbrtV4,
         "every sample carries the same wavelengths",
         [](CommandLine &c, const std::string &v) {
             c.overrides.disableWavelengthJitter = FlagValue("disable-wavelength-jitter", v);
         }},
        {"displacement-edge-scale", "s", G::PbrtV4,
         "multiply every displaced mesh's \"edgelength\"; a scene's Option wins (default: 1)",
         [](CommandLine &c, const std::string &v) {
             double s = Real("displacement-edge-scale", v);
             if (!(s > 0))
                 throw CommandLineError("--displacement-edge-scale: must be positive");
             c.overrides.displacementEdgeScale = Float(s);
         }},
        {"display-server", "host:port", G::PbrtV4,
         "stream the image to tev at host:port after every wave (a warning if it is not there)",
         [](CommandLine &c, const std::string &v) { c.displayServer = v; }},
        {"force-diffuse", nullptr, G::PbrtV4,
         "every BSDF becomes a diffuse one with the same reflectance (rho)",
         [](CommandLine &c, const std::string &v) {
             c.overrides.forceDiffuse = FlagValue("force-diffuse", v);
         }},
        {"help", nullptr, G::PbrtV4, "print this text",
         [](CommandLine &c, const std::string &) { c.help = true; }},
        {"mse-reference-image", "file", G::PbrtV4,
         "with --mse-reference-out: the image each wave's MSE is measured against",
         [](CommandLine &c, const std::string &v) { c.overrides.mseReferenceImage = v; }},
        {"mse-reference-out", "file", G::PbrtV4,
         "write \"<samples per pixel> <MSE>\" after every wave to this file",
         [](CommandLine &c, const std::string &v) { c.overrides.mseReferenceOut = v; }},
        {"nthreads", "n", G::PbrtV4, "render threads (default: 0, every core)",
         [](CommandLine &c, const std::string &v) { c.overrides.nThreads = Int("nthreads", v, 0); }},
        {"outfile", "file", G::PbrtV4,
         "the image: .exr, .pfm, .png or any OpenImageIO format (default: the film's "
         "\"filename\")",
         [](CommandLine &c, const std::string &v) { c.overrides.outFile = v; }},
        {"pixel", "x,y", G::PbrtV4, "render only this pixel",
         [](CommandLine &c, const std::string &v) {
             auto p = List<int>("pixel", v, 2, "x,y");
             c.overrides.pixelBounds = Bounds2i(Point2i(p[0], p[1]), Point2i(p[0] + 1, p[1] + 1));
         }},
        {"pixelmaterial", "x,y", G::PbrtV4,
         "print what the ray through the pixel's centre hits, and the materials; no render",
         [](CommandLine &c, const std::string &v) {
             auto p = List<int>("pixelmaterial", v, 2, "x,y");
             c.pixelMaterial = Point2i(p[0], p[1]);
         }},
        {"pixelbounds", "x0,x1,y0,y1", G::PbrtV4,
         "render only these pixels; wins over --cropwindow (default: the film's)",
         [](CommandLine &c, const std::string &v) {
             auto p = List<int>("pixelbounds", v, 4, "x0,x1,y0,y1");
             c.overrides.pixelBounds = Bounds2i(Point2i(p[0], p[2]), Point2i(p[1], p[3]));
         }},
        {"pixelstats", nullptr, G::PbrtV4,
         "also write <outfile>-time.exr (milliseconds per pixel) and <outfile>-rays.exr (rays per "
         "pixel), for path, volpath, bdpt and the other tile integrators",
         [](CommandLine &c, const std::string &v) { c.overrides.pixelStats = FlagValue("pixelstats", v); }},
        {"quick", nullptr, G::PbrtV4,
         "a quarter of the resolution, 1 sample per pixel (mlt: 1/16 of its mutations and "
         "bootstrap)",
         [](CommandLine &c, const std::string &v) { c.overrides.quick = FlagValue("quick", v); }},
        {"quiet", nullptr, G::PbrtV4, "print errors only: no progress bar, no warnings",
         [](CommandLine &c, const std::string &v) { c.overrides.quiet = FlagValue("quiet", v); }},
        {"render-coord-sys", "name", G::PbrtV4,
         "camera, cameraworld or world; pbrt_ext renders in world space whatever the name (it "
         "changes only pbrt-v4's rounding)",
         [](CommandLine &, const std::string &v) {
             if (v != "camera" && v != "cameraworld" && v != "world")
                 throw CommandLineError("--render-coord-sys: \"" + v +
                                        "\": expected camera, cameraworld or world");
         }},
        {"seed", "n", G::PbrtV4, "the samplers' seed (default: 0)",
         [](CommandLine &c, const std::string &v) {
             c.overrides.seed = Int("seed", v, std::numeric_limits<int>::min());
         }},
        {"spp", "n", G::PbrtV4, "samples per pixel (default: the scene's Sampler's)",
         [](CommandLine &c, const std::string &v) { c.overrides.spp = Int("spp", v, 1); }},
        {"stats", nullptr, G::PbrtV4, "print render statistics at the end",
         [](CommandLine &c, const std::string &v) { c.overrides.stats = FlagValue("stats", v); }},
        {"wavefront", nullptr, G::PbrtV4,
         "render with volpath: the estimator pbrt-v4's wavefront integrator runs, in another "
         "order",
         [](CommandLine &c, const std::string &v) { c.wavefront = FlagValue("wavefront", v); }},
        {"write-partial-images", nullptr, G::PbrtV4, "write the image after every wave",
         [](CommandLine &c, const std::string &v) {
             c.writePartialImages = FlagValue("write-partial-images", v);
         }},
        {"format", nullptr, G::PbrtV4, "print the scene reformatted to standard output; no render",
         [](CommandLine &c, const std::string &v) {
             if (FlagValue("format", v)) c.reformat = CommandLine::Reformat::Format;
         }},
        {"toply", nullptr, G::PbrtV4,
         "as --format, with every triangle mesh written to mesh_NNNNN.ply in the current folder",
         [](CommandLine &c, const std::string &v) {
             if (FlagValue("toply", v)) c.reformat = CommandLine::Reformat::ToPLY;
         }},
        {"upgrade", nullptr, G::PbrtV4,
         "print a pbrt-v3 scene upgraded to pbrt-v4's format, with pbrt-v4's rules; no render",
         [](CommandLine &c, const std::string &v) {
             if (FlagValue("upgrade", v)) c.reformat = CommandLine::Reformat::Upgrade;
         }},
        {"log-file", "file", G::PbrtV4, "append messages to this file instead of standard error",
         [](CommandLine &c, const std::string &v) { c.logFile = v; }},
        {"log-level", "level", G::PbrtV4,
         "verbose, error or fatal: verbose adds what is loaded and rendered, fatal drops warnings "
         "(default: error)",
         [](CommandLine &c, const std::string &v) {
             if (v == "verbose") c.logLevel = LogLevel::Verbose;
             else if (v == "error") c.logLevel = LogLevel::Error;
             else if (v == "fatal") c.logLevel = LogLevel::Fatal;
             else throw CommandLineError("--log-level: \"" + v + "\": expected verbose, error or fatal");
         }},
        // Ours.
        {"version", nullptr, G::Ours, "print the version and exit",
         [](CommandLine &c, const std::string &) { c.version = true; }},
        {"resolution", "x,y", G::Ours, "the film's resolution (default: the scene's)",
         [](CommandLine &c, const std::string &v) {
             auto r = List<int>("resolution", v, 2, "x,y");
             if (r[0] < 1 || r[1] < 1 || r[0] > (1 << 24) || r[1] > (1 << 24))
                 throw CommandLineError("--resolution: \"" + v + "\": each in [1, 16777216]");
             c.overrides.resolution = Point2i(r[0], r[1]);
         }},
        {"samples", "A:B|k/K", G::Ours,
         "render sample indices A to B-1 of every pixel, or the k-th of K equal parts, as a slice "
         "that `pbrt_ext merge` adds up (default: all)",
         [](CommandLine &c, const std::string &v) { c.samples = v; }},
        {"time-limit", "seconds", G::Ours,
         "stop after this long, every pixel with the same sample count (default: 0, none)",
         [](CommandLine &c, const std::string &v) {
             double t = Real("time-limit", v);
             if (t < 0) throw CommandLineError("--time-limit: must not be negative");
             c.overrides.timeLimitSeconds = t;
         }},
        {"integrator", "name", G::Ours,
         "path, volpath, bdpt, lightpath, sppm, mlt, simplepath, simplevolpath, randomwalk, "
         "ambientocclusion, function, guidedpath or guidedvolpath, with the scene's maxdepth "
         "(default: the "
         "scene's)",
         [](CommandLine &c, const std::string &v) {
             c.overrides.integrator = Checked("integrator", v, IntegratorNameError);
         }},
        {"sampler", "name", G::Ours,
         "zsobol, halton, sobol, paddedsobol, pmj02bn, stratified or independent (default: the "
         "scene's)",
         [](CommandLine &c, const std::string &v) {
             c.overrides.sampler = Checked("sampler", v, SamplerNameError);
         }},
        {"light-sampler", "name", G::Ours,
         "bvh, bvh-pbrt-v4, power or uniform: how next-event estimation picks a light (default: "
         "the integrator's \"lightsampler\")",
         [](CommandLine &c, const std::string &v) {
             c.overrides.lightSampler = Checked("light-sampler", v, LightSamplerNameError);
         }},
        {"strategy", "name", G::Ours, "mis, bsdf or light: how paths find light (default: mis)",
         [](CommandLine &c, const std::string &v) {
             c.overrides.strategy = Named("strategy", v, ParsePathStrategy);
         }},
        {"fabric-sampler", "name", G::Ours,
         "uniform, cosine, paper, truncatedsinphi or best: every fabric material's sampler "
         "(default: each material's)",
         [](CommandLine &c, const std::string &v) {
             c.overrides.fabricSampler = Named("fabric-sampler", v, ParseFabricSampling);
         }},
        {"layered-estimator", "name", G::Ours,
         "unbiased or pbrt-v4 (biased bright for rough coats, for pbrt-v4's images) (default: "
         "unbiased)",
         [](CommandLine &c, const std::string &v) {
             c.overrides.layeredExitMIS = Named("layered-estimator", v, ParseLayeredEstimator);
         }},
        {"guiding-save", "file", G::Ours, "guidedpath, guidedvolpath: write the trained SD-tree to this file",
         [](CommandLine &c, const std::string &v) { c.overrides.guidingSave = v; }},
        {"guiding-load", "file", G::Ours,
         "guidedpath, guidedvolpath: render with this file's SD-tree instead of training one",
         [](CommandLine &c, const std::string &v) { c.overrides.guidingLoad = v; }},
        // pbrt-v4's that a CPU renderer has no use for.
        {"gpu", nullptr, G::NotApplicable, "", NotApplicable("gpu", "pbrt_ext renders on the CPU")},
        {"gpu-device", "index", G::NotApplicable, "",
         NotApplicable("gpu-device", "pbrt_ext renders on the CPU")},
        {"interactive", nullptr, G::NotApplicable, "",
         NotApplicable("interactive", "pbrt-v4 has it only on the GPU; pbrt_ext renders on the "
                                      "CPU")},
        {"fullscreen", nullptr, G::NotApplicable, "",
         NotApplicable("fullscreen", "it goes with --interactive, which pbrt_ext lacks")},
        {"debugstart", "values", G::NotApplicable, "",
         NotApplicable("debugstart", "pbrt_ext's error messages give no integrator state to "
                                     "start from; render the pixel with --pixel x,y")},
        {"log-utilization", nullptr, G::NotApplicable, "",
         NotApplicable("log-utilization", "pbrt_ext does not sample processor and memory use")},
    };
    return options;
}

// The values a list option takes: "x0,x1,y0,y1" is 4; 1 for the others.
size_t ListLength(const OptionSpec &o) {
    return o.value && std::string_view(o.value).find(',') != std::string_view::npos
               ? 1 + std::count(o.value, o.value + std::strlen(o.value), ',')
               : 1;
}

const OptionSpec *Find(const std::string &name) {
    for (const OptionSpec &o : Options())
        if (NormalizeOptionName(o.name) == NormalizeOptionName(name)) return &o;
    return nullptr;
}

size_t EditDistance(const std::string &a, const std::string &b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// "unknown option --sp; did you mean --spp?"
[[noreturn]] void Unknown(const std::string &arg, const std::string &name) {
    const OptionSpec *nearest = nullptr;
    size_t best = std::numeric_limits<size_t>::max();
    for (const OptionSpec &o : Options()) {
        std::string candidate = NormalizeOptionName(o.name);
        size_t d = EditDistance(NormalizeOptionName(name), candidate);
        if (candidate.rfind(NormalizeOptionName(name), 0) == 0) d = std::min<size_t>(d, 1);
        if (d < best) best = d, nearest = &o;
    }
    std::string message = "unknown option " + arg;
    if (nearest && best <= std::max<size_t>(2, name.size() / 3))
        message += fmt::format("; did you mean --{}?", nearest->name);
    throw CommandLineError(message + " (pbrt_ext --help lists them)");
}

}  // namespace

CommandLine ParseCommandLine(const std::vector<std::string> &args) {
    CommandLine c;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string &arg = args[i];
        if (arg.size() < 2 || arg[0] != '-' || (arg[1] >= '0' && arg[1] <= '9') || arg[1] == '.') {
            c.sceneFiles.push_back(arg);  // "-" is standard input
            continue;
        }
        if (arg == "-h") {
            c.help = true;
            continue;
        }
        std::string name = arg.substr(arg[1] == '-' ? 2 : 1), value;
        size_t equals = name.find('=');
        bool inlineValue = equals != std::string::npos;
        if (inlineValue) {
            value = name.substr(equals + 1);
            name.resize(equals);
        }
        const OptionSpec *option = Find(name);
        if (!option) Unknown(arg, name);
        if (option->value && !inlineValue) {
            if (i + 1 == args.size())
                throw CommandLineError(fmt::format("--{}: expected a value, {}", option->name,
                                                   option->value));
            value = args[++i];
            // A list written with spaces ("--resolution 64 48", which pbrt_ext took before it
            // took pbrt-v4's commas): its numbers become the comma list.
            if (value.find(',') == std::string::npos && IsNumberText(value))
                for (size_t more = ListLength(*option) - 1;
                     more > 0 && i + 1 < args.size() && IsNumberText(args[i + 1]); --more)
                    value += "," + args[++i];
        }
        option->apply(c, value);
    }
    if (c.wavefront && !c.overrides.integrator) c.overrides.integrator = "volpath";
    if (c.overrides.mseReferenceImage.empty() != c.overrides.mseReferenceOut.empty())
        throw CommandLineError("--mse-reference-image and --mse-reference-out go together");
    return c;
}

std::string CommandLineHelp() {
    std::string text =
        "usage: pbrt_ext [<options>] <scene.pbrt>...   (\"-\": the scene on standard input)\n"
        "       pbrt_ext merge <out.exr> <slice.exr>...  (adds --samples slices up; merge --help)\n"
        "\nOptions take \"--name value\", \"--name=value\" or \"-name value\"; lists are "
        "comma-separated;\nthe last of a repeated option wins. docs/cli.md has each one's pbrt-v4 "
        "equivalent.\n";
    const std::pair<G, const char *> groups[] = {{G::PbrtV4, "pbrt-v4's options"},
                                                 {G::Ours, "pbrt_ext's own options"}};
    for (const auto &[group, title] : groups) {
        text += fmt::format("\n{}:\n", title);
        for (const OptionSpec &o : Options()) {
            if (o.group != group) continue;
            std::string left = fmt::format("  --{}{}{}", o.name, o.value ? " <" : "",
                                           o.value ? std::string(o.value) + ">" : "");
            text += fmt::format("{:<34}{}\n", left, o.help);
        }
    }
    text += "\nNot supported: --gpu, --gpu-device, --interactive, --fullscreen (pbrt_ext renders on "
            "the CPU),\n--debugstart, --log-utilization.\n"
            "\nExit status: 0 success, 1 bad input or failed render, 2 bad command line, 130 "
            "interrupted (Ctrl-C;\nthe image rendered so far is written).\n";
    return text;
}

}  // namespace pbrt
