// Materials: evaluate their textures at a hit and return a BxDF by value (pbrt-v4's
// src/pbrt/materials.h). The closed set is listed at the end; the builder creates only materials that
// some shape references.
#pragma once

#include "pbrt_ext/bsdf.h"
#include "pbrt_ext/bxdfs/bxdfs.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/textures.h"

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

// Our extension: the DreamWorks fabric lobe (pbrt_ext/bxdfs/fabric.h).
struct FabricMaterial {
    SpectrumTexture reflectance = SampledSpectrum(0.5f);
    FloatTexture roughness = 0.5f;
    Float threadAngle = 0, threadElevation = 0;  // degrees: about N from dpdu, then toward N
    FabricSampling sampling = FabricSampling::Best;
    FabricNormalization normalization = FabricNormalization::Paper;

    BxDF GetBxDF(const TextureEvalContext &ctx) const;
};

class Material {
  public:
    using Variant = std::variant<DiffuseMaterial, ConductorMaterial, FabricMaterial>;
    template <typename T>
    Material(T material) : material(std::move(material)) {}

    // The BSDF at a hit, in the hit's shading frame.
    BSDF GetBSDF(const SurfaceInteraction &si) const {
        TextureEvalContext ctx(si);
        BxDF bxdf = std::visit([&](const auto &m) { return m.GetBxDF(ctx); }, material);
        return BSDF(si.shading.n, si.shading.dpdu, std::move(bxdf));
    }

  private:
    Variant material;
};

}  // namespace pbrt
