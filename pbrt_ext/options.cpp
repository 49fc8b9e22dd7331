#include "pbrt_ext/options.h"

#include <stdexcept>

namespace pbrt {

std::string ToString(PathStrategy strategy) {
    switch (strategy) {
    case PathStrategy::MIS:
        return "mis";
    case PathStrategy::BSDF:
        return "bsdf";
    case PathStrategy::Light:
        return "light";
    }
    return "?";
}

PathStrategy ParsePathStrategy(const std::string &name) {
    for (PathStrategy s : {PathStrategy::MIS, PathStrategy::BSDF, PathStrategy::Light})
        if (ToString(s) == name)
            return s;
    throw std::invalid_argument("unknown strategy \"" + name + "\": expected mis, bsdf or light");
}

FabricSampling ParseFabricSampling(const std::string &name) {
    std::string error;
    pstd::optional<FabricSampling> sampling =
        FabricOptionFromName<FabricSampling>("sampler", kFabricSamplingNames, name, &error);
    if (!sampling)
        throw std::invalid_argument(error);
    return *sampling;
}

LayeredExitMIS ParseLayeredEstimator(const std::string &name) {
    if (name == "unbiased")
        return LayeredExitMIS::InnerDirection;
    if (name == "pbrt-v4")
        return LayeredExitMIS::PbrtV4;
    throw std::invalid_argument("unknown layered estimator \"" + name +
                                "\": \"unbiased\" or \"pbrt-v4\"");
}

const char *LayeredEstimatorName(LayeredExitMIS mis) {
    return mis == LayeredExitMIS::InnerDirection ? "unbiased" : "pbrt-v4";
}

std::optional<std::string> SamplerNameError(const std::string &name) {
    for (const char *known : {"zsobol", "halton", "sobol", "paddedsobol", "pmj02bn", "stratified", "independent"})
        if (name == known) return {};
    return "unknown Sampler \"" + name + "\": expected zsobol, halton, sobol, paddedsobol, pmj02bn, "
           "stratified or independent";
}

std::optional<std::string> IntegratorNameError(const std::string &name) {
    for (const char *known : {"path", "volpath", "bdpt", "lightpath", "sppm"})
        if (name == known) return {};
    return "unknown Integrator \"" + name + "\": expected path, volpath, bdpt, lightpath or sppm";
}

}  // namespace pbrt
