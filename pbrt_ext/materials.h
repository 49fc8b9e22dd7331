// Materials: evaluate their textures at a hit and return a BxDF by value (pbrt-v4's
// src/pbrt/materials.h). The closed set is listed at the end; the builder creates only materials that
// some shape references.
#pragma once

#include "pbrt_ext/bsdf.h"
#include "pbrt_ext/bxdfs/bxdfs.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/textures.h"

#include <memory>
#include <optional>
#include <string>
#include <variant>

namespace pbrt {

struct DiffuseMaterial {
    SpectrumTexture reflectance = SampledSpectrum(0.5f);

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

// Roughness is TR alpha directly, or pbrt-v4's remapping from a perceptual roughness.
struct ConductorMaterial {
    SpectrumTexture eta = SampledSpectrum(0.2f, 0.92f, 1.1f);  // copper-like RGB default
    SpectrumTexture k = SampledSpectrum(3.9f, 2.45f, 2.14f);
    FloatTexture uRoughness = 0, vRoughness = 0;
    bool remapRoughness = true;

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

// Roughness as for ConductorMaterial; eta is a single index (RGB rendering has no dispersion).
struct DielectricMaterial {
    Float eta = 1.5f;
    FloatTexture uRoughness = 0, vRoughness = 0;
    bool remapRoughness = true;

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

struct ThinDielectricMaterial {
    Float eta = 1.5f;

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

struct DiffuseTransmissionMaterial {
    SpectrumTexture reflectance = SampledSpectrum(0.25f), transmittance = SampledSpectrum(0.25f);
    Float scale = 1;

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

// The parameters of pbrt-v4's layered materials: a medium of the given thickness, albedo and
// Henyey-Greenstein g between the interfaces, walked with at most maxDepth bounces, nSamples times.
struct LayerParameters {
    FloatTexture thickness = 0.01f;
    SpectrumTexture albedo = SampledSpectrum(0.f);
    FloatTexture g = 0;
    int maxDepth = 10, nSamples = 1;
};

struct CoatedDiffuseMaterial {
    SpectrumTexture reflectance = SampledSpectrum(0.5f);
    FloatTexture uRoughness = 0, vRoughness = 0;
    Float eta = 1.5f;
    bool remapRoughness = true;
    LayerParameters layer;

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

struct CoatedConductorMaterial {
    FloatTexture interfaceURoughness = 0, interfaceVRoughness = 0;
    Float interfaceEta = 1.5f;
    ConductorMaterial conductor;
    bool remapRoughness = true;
    LayerParameters layer;

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

// Our extension: the DreamWorks fabric lobe (pbrt_ext/bxdfs/fabric.h).
struct FabricMaterial {
    SpectrumTexture reflectance = SampledSpectrum(0.5f);
    FloatTexture roughness = 0.5f;
    Float threadAngle = 0, threadElevation = 0;  // degrees: about N from dpdu, then toward N
    FabricSampling sampling = FabricSampling::Best;
    FabricNormalization normalization = FabricNormalization::Paper;
    // An optional diffuse base lobe, weighted so that the total albedo stays at most 1
    // (pbrt_ext/bxdfs/fabricdiffuse.h).
    std::optional<SpectrumTexture> diffuse;

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

// pbrt-v4's stochastic mix of two materials: at each hit one of them is chosen, the second with
// probability `amount`, by a hash of the hit, so that the choice is the same for a given point and
// direction. The scene resolves a mix to the chosen material before asking for a BSDF.
struct MixMaterial {
    int materials[2];  // indices into the scene's materials (-1: an interface)
    FloatTexture amount = 0.5f;

    int Choose(const SurfaceInteraction &si) const;
    // Never reached: Scene::GetBSDF resolves mixes first (kept for the closed dispatch).
    BxDF GetBxDF(const TextureEvalContext &) const { return DiffuseBxDF(SampledSpectrum(0.f)); }
};

class Material {
  public:
    using Variant =
        std::variant<DiffuseMaterial, ConductorMaterial, DielectricMaterial, ThinDielectricMaterial,
                     DiffuseTransmissionMaterial, CoatedDiffuseMaterial, CoatedConductorMaterial,
                     FabricMaterial, MixMaterial>;
    template <typename T>
    Material(T material) : material(std::move(material)) {}

    // The BSDF at a hit, in the hit's shading frame, perturbed by the bump or normal map if any.
    BSDF GetBSDF(const SurfaceInteraction &si) const;

    const MixMaterial *AsMix() const { return std::get_if<MixMaterial>(&material); }

    // pbrt-v4's "texture displacement" (bump mapping) and "string normalmap" (a tangent-space
    // normal map read with linear encoding). Either perturbs the shading frame of every BSDF.
    void SetDisplacement(FloatTexture displacement) { this->displacement = std::move(displacement); }
    void SetNormalMap(std::shared_ptr<const Image> image) { normalMap = std::move(image); }

  private:
    Variant material;
    std::optional<FloatTexture> displacement;
    std::shared_ptr<const Image> normalMap;
};

}  // namespace pbrt
