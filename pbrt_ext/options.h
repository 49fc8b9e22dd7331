// What a render is asked to do: the integrator and its parameters, as the scene file or the command
// line gives them, and what the command line overrides in a scene (pbrt-v4's PBRTOptions, reduced
// to this renderer). Plain data, which the scene holds and the integrators read.
#pragma once

#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/bxdfs/layered.h"
#include "pbrt_ext/util/bounds.h"

#include <cstdint>
#include <optional>
#include <string>

namespace pbrt {

enum class PathStrategy {
    MIS,    // both estimators, weighted by the power heuristic (default)
    BSDF,   // BSDF sampling only: emitters count when paths hit them; delta lights are invisible
    Light,  // light sampling wherever it applies; emitters hit by BSDF sampling count only where
            // light sampling cannot reach them (seen directly or through a specular bounce)
};

std::string ToString(PathStrategy strategy);
// "mis", "bsdf" or "light"; throws std::invalid_argument naming the accepted values otherwise.
PathStrategy ParsePathStrategy(const std::string &name);

// pbrt-v4's integrators, by their scene-file names.
enum class IntegratorType {
    Path,      // "path": media ignored, as in pbrt-v4
    VolPath,   // "volpath" (pbrt-v4's default): media are rendered by the VolPathIntegrator. A
               // scene without media needs none of it and is rendered by the path tracer,
               // which estimates the same image.
    BDPT,           // "bdpt": bidirectional path tracing (integrators/bdpt.h)
    LightPath,      // "lightpath": paths traced from the lights only (integrators/lightpath.h)
    SPPM,           // "sppm": stochastic progressive photon mapping (integrators/sppm.h)
    MLT,            // "mlt": Metropolis light transport over bdpt's strategies (integrators/mlt.h)
    SimplePath,     // "simplepath": path tracing without MIS (integrators/simplepath.h)
    SimpleVolPath,  // "simplevolpath": media alone, without MIS (integrators/simplevolpath.h)
    RandomWalk,     // "randomwalk": uniform directions, no light sampling (integrators/randomwalk.h)
    AmbientOcclusion,  // "ambientocclusion" (integrators/ambientocclusion.h)
    Function,       // "function": sample generators on test functions (integrators/function.h)
    GuidedPath,     // "guidedpath": path tracing guided by a learned SD-tree (integrators/guidedpath.h)
    GuidedVolPath,  // "guidedvolpath": volpath guided by it (integrators/volpath.h); guidedpath
                    // where there are no media to render, as volpath is path there
};

// "path", "volpath", ...; none for a name pbrt-v4 does not have.
std::optional<IntegratorType> IntegratorTypeFromName(const std::string &name);
const char *IntegratorName(IntegratorType type);
// guidedpath and guidedvolpath: they learn an SD-tree (integrators/guiding.h).
inline bool IsGuided(IntegratorType type) {
    return type == IntegratorType::GuidedPath || type == IntegratorType::GuidedVolPath;
}

// The 2D test functions of the function integrator, each with integral 1 over [0, 1)^2.
enum class TestFunction { Step, Diagonal, Disk, Checkerboard, RotatedCheckerboard, Gaussian };

// "step", "diagonal", "disk", "checkerboard", "rotatedcheckerboard" or "gaussian"; none otherwise.
std::optional<TestFunction> TestFunctionFromName(const std::string &name);

// simplepath: next-event estimation with a uniformly chosen light, and BSDF sampling (else
// uniform directions).
struct SimplePathOptions {
    bool sampleLights = true, sampleBSDF = true;
};

// ambientocclusion: cosine-weighted directions (else uniform), and how far an occluder counts.
struct AmbientOcclusionOptions {
    bool cosSample = true;
    Float maxDistance = Infinity;
};

// mlt, with pbrt-v4's defaults; mutationsPerPixel is --spp when given.
struct MLTOptions {
    int64_t bootstrapSamples = 100000;
    int64_t chains = 1000;
    int mutationsPerPixel = 100;
    Float largeStepProbability = 0.3f, sigma = 0.01f;
    int seed = 0;  // of the bootstrap paths and the chains (--seed)
};

// function: the test function, the error table's file, whether rows are written only where the
// sampler's points are well distributed, the function's image (none if empty), and the seed of
// the per-pixel randomizations it makes itself.
struct FunctionOptions {
    TestFunction function = TestFunction::Step;
    std::string outputFile;
    bool skipBad = true;
    std::string imageFile;
    int seed = 0;
};

// guidedpath and guidedvolpath: the probability of sampling the BSDF (or phase function) rather
// than the learned distribution (where learned, each spatial leaf's starting value), the
// SD-tree's memory limit, and a tree to write after training or to read instead of training.
struct GuidingOptions {
    Float bsdfFraction = 0.5f;
    bool learnBSDFFraction = true;  // per spatial leaf (integrators/bsdffraction.h)
    // Render without guiding where a trial finds it less efficient than path tracing
    // (integrators/guiding.h).
    bool switchOff = true;
    size_t maxBytes = size_t(256) << 20;
    std::string saveFile, loadFile;
};

// The integrator a scene asks for and its parameters (pbrt-v4's Integrator directive).
struct IntegratorOptions {
    int maxDepth = 5;
    bool regularize = false;
    PathStrategy strategy = PathStrategy::MIS;
    IntegratorType type = IntegratorType::Path;
    // bdpt: also write each (s, t) strategy's image, unweighted (visualizeStrategies) or
    // weighted by MIS (visualizeWeights), beside the film's file (pbrt-v4's bdpt_dDD_sSS_tTT).
    bool visualizeStrategies = false, visualizeWeights = false;
    // sppm: photons per iteration (the film's pixel count if not positive), the visible
    // points' initial search radius, and the seed of the photons' Halton points.
    int64_t photonsPerIteration = -1;
    Float initialRadius = 1;
    int photonSeed = 0;
    // VolPathIntegrator only: weigh wavelengths by spectral MIS (pbrt-v4), or follow the hero
    // wavelength's probabilities alone (to measure what spectral MIS gains).
    bool spectralMIS = true;
    SimplePathOptions simplePath = {};
    AmbientOcclusionOptions ambientOcclusion = {};
    MLTOptions mlt = {};
    FunctionOptions function = {};
    GuidingOptions guiding = {};
};

struct RenderOverrides {
    std::optional<int> spp;                  // samples per pixel instead of the sampler's
    int nThreads = 0;                        // 0: all cores
    int seed = 0;                            // the samplers' seed (pbrt-v4's --seed)
    std::string outFile;                     // instead of the film's filename
    bool quiet = false;                      // no progress bar, no warnings
    bool stats = false;                      // print the render statistics
    std::optional<Point2i> resolution;       // instead of the film's x/yresolution
    std::optional<Bounds2f> cropWindow;      // instead of the film's
    std::optional<Bounds2i> pixelBounds;     // instead of the film's (wins over cropWindow)
    std::optional<PathStrategy> strategy;    // instead of the integrator's "mis"
    std::optional<FabricSampling> fabricSampler;  // for every fabric material
    // The coated materials' f() estimator: ours, or pbrt-v4's biased one for its images.
    LayeredExitMIS layeredExitMIS = LayeredExitMIS::InnerDirection;
    // Multiplies every displaced mesh's "edgelength" (pbrt-v4's --displacement-edge-scale; a
    // scene's Option "displacementedgescale" wins over it, as in pbrt-v4).
    Float displacementEdgeScale = 1;
    std::optional<std::string> lightSampler;  // a LightSamplerNameError name, instead of the integrator's
    std::optional<std::string> sampler;      // a Sampler name (SamplerNameError), instead of the scene's
    // An integrator name (IntegratorNameError) instead of the scene's, with the scene's
    // "maxdepth" and none of its other parameters.
    std::optional<std::string> integrator;
    double timeLimitSeconds = 0;             // 0: none
    std::string guidingSave, guidingLoad;    // the guided integrators' tree: written after training, or read
    // pbrt-v4's debugging switches, which a scene's Option directive can also set (and then wins):
    bool quick = false;                    // resolution / 4, 1 spp (mlt: mutations and bootstrap / 16)
    bool forceDiffuse = false;             // every BSDF: a diffuse one with its reflectance
    bool disablePixelJitter = false;       // pixel and lens centres, mid-shutter
    bool disableWavelengthJitter = false;  // the same wavelengths for every sample
    bool disableTextureFiltering = false;  // point-sampled textures (no ray differentials)
    bool disableImageTextures = false;     // each image texture: its average
    // What the command writes besides the image (a scene's Option directive can also ask):
    std::string mseReferenceImage, mseReferenceOut;  // a '<spp> <MSE>' line after every wave
    bool pixelStats = false;                          // <outfile>-time.exr and -rays.exr
};

// "uniform", "cosine", "paper", "truncatedsinphi" or "best"; throws std::invalid_argument otherwise.
FabricSampling ParseFabricSampling(const std::string &name);

// --layered-estimator's names: "unbiased" (ours) or "pbrt-v4"; throws std::invalid_argument
// otherwise.
LayeredExitMIS ParseLayeredEstimator(const std::string &name);
const char *LayeredEstimatorName(LayeredExitMIS mis);

// Empty for a Sampler name pbrt_ext knows; otherwise the message naming the ones it does.
std::optional<std::string> SamplerNameError(const std::string &name);
// The same for an Integrator name (pbrt-v4's eleven).
std::optional<std::string> IntegratorNameError(const std::string &name);

}  // namespace pbrt
