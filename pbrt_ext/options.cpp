#include "pbrt_ext/options.h"

#include <stdexcept>
#include <utility>

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

namespace {

constexpr std::pair<const char *, IntegratorType> kIntegrators[] = {
    {"path", IntegratorType::Path},
    {"volpath", IntegratorType::VolPath},
    {"bdpt", IntegratorType::BDPT},
    {"lightpath", IntegratorType::LightPath},
    {"sppm", IntegratorType::SPPM},
    {"mlt", IntegratorType::MLT},
    {"simplepath", IntegratorType::SimplePath},
    {"simplevolpath", IntegratorType::SimpleVolPath},
    {"randomwalk", IntegratorType::RandomWalk},
    {"ambientocclusion", IntegratorType::AmbientOcclusion},
    {"function", IntegratorType::Function},
    {"guidedpath", IntegratorType::GuidedPath},
    {"guidedvolpath", IntegratorType::GuidedVolPath}};

constexpr std::pair<const char *, TestFunction> kTestFunctions[] = {
    {"step", TestFunction::Step},
    {"diagonal", TestFunction::Diagonal},
    {"disk", TestFunction::Disk},
    {"checkerboard", TestFunction::Checkerboard},
    {"rotatedcheckerboard", TestFunction::RotatedCheckerboard},
    {"gaussian", TestFunction::Gaussian}};

template <typename T, size_t N>
std::optional<T> FromName(const std::pair<const char *, T> (&names)[N], const std::string &name) {
    for (const auto &[known, value] : names)
        if (name == known)
            return value;
    return std::nullopt;
}

}  // namespace

std::optional<IntegratorType> IntegratorTypeFromName(const std::string &name) {
    return FromName(kIntegrators, name);
}

const char *IntegratorName(IntegratorType type) {
    for (const auto &[name, known] : kIntegrators)
        if (type == known)
            return name;
    return "?";
}

std::optional<TestFunction> TestFunctionFromName(const std::string &name) {
    return FromName(kTestFunctions, name);
}

std::optional<std::string> IntegratorNameError(const std::string &name) {
    if (IntegratorTypeFromName(name))
        return {};
    return "unknown Integrator \"" + name + "\": expected path, volpath, bdpt, lightpath, sppm, mlt, "
           "simplepath, simplevolpath, randomwalk, ambientocclusion, function, guidedpath or guidedvolpath";
}

}  // namespace pbrt
