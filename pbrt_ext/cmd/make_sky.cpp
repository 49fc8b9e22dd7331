// make_sky: writes an analytic sky as a square equal-area octahedral EXR, the environment map
// format that LightSource "infinite" "string filename" reads (util/equalarea.h).
//
// The sky is a smooth gradient, bluish at the zenith and warmer toward the horizon, a dark ground
// below it, and a small bright sun disk with a soft glow around it. It is generated rather than
// downloaded so that the scenes in scenes/ need no external assets. Directions are in the light's
// space, +z up as pbrt-v4's infinite lights; the sun azimuth is measured from +x toward +y.
//
// Each pixel averages 4x4 directions inside it, so the sun disk, a few pixels wide at 256x256,
// is antialiased and its total power does not depend on where it falls on the pixel grid.
//
// With --no-sun, the gradient and the ground alone: a smooth environment, as the fabric paper's
// Fig. 3 comparison of BSDF samplers assumes (scenes/convergence/paper-fig3.toml).
//
// Usage: make_sky [--resolution N] [--sun-elevation deg] [--sun-azimuth deg] [--no-sun] out.exr
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/equalarea.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

using namespace pbrt;

namespace {

constexpr const char *kUsage =
    "usage: make_sky [--resolution N] [--sun-elevation deg] [--sun-azimuth deg] [--no-sun] out.exr\n"
    "  --resolution N       width and height of the square map, 4 to 4096 (default 256)\n"
    "  --sun-elevation deg  sun height above the horizon, -90 to 90 (default 35)\n"
    "  --sun-azimuth deg    sun direction about +z, from +x toward +y (default 30)\n"
    "  --no-sun             no sun disk and no glow: the sky's gradient alone\n"
    "  out.exr              the equal-area octahedral map to write (.exr)\n";

struct SkyOptions {
    int resolution = 256;
    Float sunElevation = 35, sunAzimuth = 30;  // degrees
    bool sun = true;
    std::string outFile;
};

// Radiances (linear RGB). The sky is about 1 near the horizon so that scenes need no exposure
// scale; the sun adds an irradiance of kSunIrradiance at normal incidence, a few times what the
// sky delivers, so that it casts visible shadows and highlights.
const RGB kZenith(0.30f, 0.50f, 1.00f);
const RGB kHorizon(1.00f, 0.88f, 0.72f);
const RGB kGround(0.06f, 0.055f, 0.05f);
const RGB kSunColor(1.00f, 0.93f, 0.82f);
constexpr Float kSunIrradiance = 4;
// Larger than the real sun's 0.27 degrees so that the disk covers several pixels at 256x256.
constexpr Float kSunRadiusDegrees = 2;
constexpr Float kGlowRadiance = 0.8f, kGlowWidthDegrees = 8;
// Below the horizon the sky fades into the ground over this range of z = sin(elevation) (about
// 17 degrees): gradual enough that a scene's floor edge shows no step at the horizon.
constexpr Float kHorizonBlend = 0.3f;
constexpr int kSubsamples = 4;  // per pixel and axis

[[noreturn]] void UsageError(const std::string &message) {
    std::fprintf(stderr, "make_sky: error: %s\n%s", message.c_str(), kUsage);
    std::exit(2);
}

// The whole of text as a finite number, or a usage error naming the flag.
double ParseNumber(const char *flag, const char *text) {
    errno = 0;
    char *end = nullptr;
    double value = std::strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || !std::isfinite(value))
        UsageError(std::string(flag) + ": expected a number, got \"" + text + "\"");
    return value;
}

SkyOptions ParseArguments(int argc, char **argv) {
    SkyOptions options;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::printf("%s", kUsage);
            std::exit(0);
        }
        if (arg == "--no-sun") {
            options.sun = false;
            continue;
        }
        if (arg.rfind("--", 0) != 0) {
            if (!options.outFile.empty())
                UsageError("more than one output file (\"" + options.outFile + "\", \"" + arg + "\")");
            options.outFile = arg;
            continue;
        }
        if (arg != "--resolution" && arg != "--sun-elevation" && arg != "--sun-azimuth")
            UsageError("unknown option \"" + arg + "\"");
        if (i + 1 == argc) UsageError(arg + ": missing value");
        double value = ParseNumber(arg.c_str(), argv[++i]);
        if (arg == "--resolution") {
            if (value != std::floor(value) || value < 4 || value > 4096)
                UsageError("--resolution: expected an integer from 4 to 4096, got " +
                           std::string(argv[i]));
            options.resolution = int(value);
        } else if (arg == "--sun-elevation") {
            if (value < -90 || value > 90)
                UsageError("--sun-elevation: expected degrees from -90 to 90, got " +
                           std::string(argv[i]));
            options.sunElevation = Float(value);
        } else {
            options.sunAzimuth = Float(value);
        }
    }
    if (options.outFile.empty()) UsageError("missing the output file");
    std::string ext = options.outFile.size() >= 4
                          ? options.outFile.substr(options.outFile.size() - 4)
                          : std::string();
    // Any other format would be 8-bit and clip the sun, which carries most of the energy.
    if (ext != ".exr" && ext != ".EXR")
        UsageError("the output must be an .exr file, got \"" + options.outFile + "\"");
    return options;
}

class Sky {
  public:
    explicit Sky(const SkyOptions &options)
        : sunDirection(SphericalDirection(std::cos(Radians(options.sunElevation)),
                                          std::sin(Radians(options.sunElevation)),
                                          Radians(options.sunAzimuth))),
          sun(options.sun), cosSunRadius(std::cos(Radians(kSunRadiusDegrees))),
          // Radiance that gives kSunIrradiance over the disk's solid angle 2 pi (1 - cos r).
          sunRadiance(kSunColor * (kSunIrradiance / (2 * Pi * (1 - cosSunRadius)))) {}

    RGB L(Vector3f w) const {
        RGB L = Background(w.z);
        if (!sun) return L;
        Float cosAngle = Dot(w, sunDirection);
        if (cosAngle >= cosSunRadius) L += sunRadiance;
        Float angle = Degrees(SafeACos(cosAngle));
        L += kSunColor * (kGlowRadiance * std::exp(-Sqr(angle / kGlowWidthDegrees) / 2));
        return L;
    }

  private:
    // Sky and ground as a function of the height z = sin(elevation) alone.
    static RGB Background(Float z) {
        if (z < 0) {
            Float t = Clamp(-z / kHorizonBlend, 0, 1);
            Float w = t * t * (3 - 2 * t);
            return (1 - w) * kHorizon + w * kGround;
        }
        // The warm band hugs the horizon: at 30 degrees of elevation it is down to 1/8.
        Float w = Pow<3>(1 - z);
        return (1 - w) * kZenith + w * kHorizon;
    }

    Vector3f sunDirection;
    bool sun;
    Float cosSunRadius;
    RGB sunRadiance;
};

Image RenderSky(const Sky &sky, int resolution) {
    Image image(Point2i(resolution, resolution));
    for (int y = 0; y < resolution; ++y)
        for (int x = 0; x < resolution; ++x) {
            RGB sum(0, 0, 0);
            for (int sy = 0; sy < kSubsamples; ++sy)
                for (int sx = 0; sx < kSubsamples; ++sx) {
                    // Pixel (x, y) covers [x, x+1] x [y, y+1] of the square, as the light's lookup.
                    Point2f uv((x + (sx + 0.5f) / kSubsamples) / resolution,
                               (y + (sy + 0.5f) / kSubsamples) / resolution);
                    sum += sky.L(EqualAreaSquareToSphere(uv));
                }
            sum /= Float(kSubsamples * kSubsamples);
            for (int c = 0; c < 3; ++c)
                image.SetChannel(Point2i(x, y), c, sum[c]);
        }
    return image;
}

}  // namespace

int main(int argc, char **argv) {
    SkyOptions options = ParseArguments(argc, argv);
    try {
        Image image = RenderSky(Sky(options), options.resolution);
        ImageMetadata metadata;
        char generator[128];
        std::snprintf(generator, sizeof(generator),
                      "make_sky --resolution %d --sun-elevation %g --sun-azimuth %g%s",
                      options.resolution, options.sunElevation, options.sunAzimuth,
                      options.sun ? "" : " --no-sun");
        metadata.extra["generator"] = generator;
        image.Write(options.outFile, metadata);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "make_sky: %s\n", e.what());
        return 1;
    }
    std::printf("wrote %s (%dx%d)\n", options.outFile.c_str(), options.resolution,
                options.resolution);
    return 0;
}
