// What the command line overrides in a scene (pbrt-v4's PBRTOptions, reduced to this renderer).
#pragma once

#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/bxdfs/layered.h"
#include "pbrt_ext/integrators/path.h"
#include "pbrt_ext/util/bounds.h"

#include <optional>
#include <string>

namespace pbrt {

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
};

// "uniform", "cosine", "paper", "truncatedsinphi" or "best"; throws std::invalid_argument otherwise.
FabricSampling ParseFabricSampling(const std::string &name);

// --layered-estimator's names: "unbiased" (ours) or "pbrt-v4"; throws std::invalid_argument
// otherwise.
LayeredExitMIS ParseLayeredEstimator(const std::string &name);
const char *LayeredEstimatorName(LayeredExitMIS mis);

// Empty for a Sampler name pbrt_ext knows; otherwise the message naming the ones it does.
std::optional<std::string> SamplerNameError(const std::string &name);
// The same for an Integrator name pbrt_ext renders (path, volpath, bdpt, lightpath, sppm).
std::optional<std::string> IntegratorNameError(const std::string &name);

}  // namespace pbrt
