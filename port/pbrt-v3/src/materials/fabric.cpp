// FabricMaterial (pbrt-v3): scene parameters to pbrt_ext's fabric BxDF, through FabricReflection.
#include "materials/fabric.h"

#include "error.h"
#include "interaction.h"
#include "materials/fabricreflection.h"
#include "memory.h"
#include "paramset.h"
#include "texture.h"

#include <cstdlib>
#include <string>

namespace pbrt {

void FabricMaterial::ComputeScatteringFunctions(SurfaceInteraction *si, MemoryArena &arena,
                                                TransportMode mode,
                                                bool allowMultipleLobes) const {
    if (bumpMap)
        Bump(bumpMap, si);
    si->bsdf = ARENA_ALLOC(arena, BSDF)(*si);
    pbrt_ext::FabricBxDF fabric(ToPbrtExt(reflectance->Evaluate(*si).Clamp(0, 1)),
                                roughness->Evaluate(*si), ToPbrtExt(thread),
                                pbrt_ext::FabricSampling(sampling),
                                pbrt_ext::FabricNormalization(normalization));
    Spectrum base = diffuse ? diffuse->Evaluate(*si).Clamp(0, 1) : Spectrum(0.f);
    si->bsdf->Add(ARENA_ALLOC(arena, FabricReflection)(
        pbrt_ext::FabricDiffuseBxDF(fabric, ToPbrtExt(base))));
}

namespace {

// A "string" option by pbrt_ext's names table; an unknown name is pbrt_ext's error, and the end.
template <typename Option, size_t N>
int FindFabricOption(const TextureParams &mp, const char *parameter, const char *what,
                     const char *const (&names)[N], const char *def) {
    std::string error;
    pstd::optional<Option> option =
        pbrt_ext::FabricOptionFromName<Option>(what, names, mp.FindString(parameter, def), &error);
    if (!option) {
        Error("%s", error.c_str());
        std::exit(1);
    }
    return int(*option);
}

}  // namespace

FabricMaterial *CreateFabricMaterial(const TextureParams &mp) {
    pbrt_ext::Vector3f thread = pbrt_ext::FabricBxDF::ThreadDirection(
        mp.FindFloat("threadangle", 0), mp.FindFloat("threadelevation", 0));
    int sampling = FindFabricOption<pbrt_ext::FabricSampling>(
        mp, "sampler", "sampler", pbrt_ext::kFabricSamplingNames, "best");
    int normalization = FindFabricOption<pbrt_ext::FabricNormalization>(
        mp, "normalization", "normalization", pbrt_ext::kFabricNormalizationNames, "paper");
    return new FabricMaterial(mp.GetSpectrumTexture("reflectance", Spectrum(0.5f)),
                              mp.GetFloatTexture("roughness", 0.5f),
                              mp.GetSpectrumTextureOrNull("diffuse"), FromPbrtExt(thread),
                              sampling, normalization, mp.GetFloatTextureOrNull("bumpmap"));
}

}  // namespace pbrt
