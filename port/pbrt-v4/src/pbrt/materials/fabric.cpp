// FabricMaterial creation from scene-file parameters: pbrt_ext's "fabric" material
// (pbrt_ext/scene/create_materials.cpp there), with the same defaults and error messages.
#include <pbrt/materials/fabric.h>

#include <pbrt/paramdict.h>
#include <pbrt/util/error.h>
#include <pbrt/util/image.h>
#include <pbrt/util/print.h>

namespace pbrt {

namespace {

// Reads a "string" option by its names table; an unknown name is an error at the parameter.
template <typename Option, size_t N>
Option GetFabricOption(const TextureParameterDictionary &parameters, const char *parameter,
                       const char *what, const char *const (&names)[N], const char *def,
                       const FileLoc *materialLoc) {
    std::string name = parameters.GetOneString(parameter, def), error;
    pstd::optional<Option> option = FabricOptionFromName<Option>(what, names, name, &error);
    if (!option) {
        const FileLoc *loc = static_cast<const ParameterDictionary &>(parameters).loc(parameter);
        ErrorExit(loc ? loc : materialLoc, "%s", error);
    }
    return *option;
}

}  // namespace

FabricMaterial *FabricMaterial::Create(const TextureParameterDictionary &parameters,
                                       Image *normalMap, const FileLoc *loc, Allocator alloc) {
    SpectrumTexture reflectance =
        parameters.GetSpectrumTexture("reflectance", nullptr, SpectrumType::Albedo, alloc);
    if (!reflectance)
        reflectance = alloc.new_object<SpectrumConstantTexture>(
            alloc.new_object<ConstantSpectrum>(0.5f));
    FloatTexture roughness = parameters.GetFloatTexture("roughness", 0.5f, alloc);
    Vector3f thread = FabricBxDF::ThreadDirection(parameters.GetOneFloat("threadangle", 0),
                                                  parameters.GetOneFloat("threadelevation", 0));
    auto sampling = GetFabricOption<FabricSampling>(parameters, "sampler", "sampler",
                                                    kFabricSamplingNames, "best", loc);
    auto normalization = GetFabricOption<FabricNormalization>(
        parameters, "normalization", "normalization", kFabricNormalizationNames, "paper", loc);
    SpectrumTexture diffuse =
        parameters.GetSpectrumTextureOrNull("diffuse", SpectrumType::Albedo, alloc);
    FloatTexture displacement = parameters.GetFloatTextureOrNull("displacement", alloc);
    return alloc.new_object<FabricMaterial>(reflectance, roughness, thread, sampling,
                                            normalization, diffuse, displacement, normalMap);
}

std::string FabricMaterial::ToString() const {
    return StringPrintf("[ FabricMaterial reflectance: %s roughness: %s thread: %s sampling: %s "
                        "normalization: %s diffuse: %s displacement: %s normalMap: %s ]",
                        reflectance, roughness, thread, kFabricSamplingNames[int(sampling)],
                        kFabricNormalizationNames[int(normalization)], diffuse, displacement,
                        normalMap ? normalMap->ToString() : std::string("(nullptr)"));
}

}  // namespace pbrt
