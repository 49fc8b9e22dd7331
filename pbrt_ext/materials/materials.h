// Materials: evaluate their textures at a hit and the path's wavelengths and return a BxDF by
// value (pbrt-v4's src/pbrt/materials.h). A dielectric whose index varies with wavelength
// terminates the path's secondary wavelengths, as in pbrt-v4: refraction then sends each
// wavelength its own way. The closed set is listed at the end; the builder creates only materials that
// some shape references.
#pragma once

#include "pbrt_ext/bxdfs/bxdfs.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/materials/bsdf.h"
#include "pbrt_ext/materials/bssrdf.h"
#include "pbrt_ext/textures/textures.h"

#include <memory>
#include <optional>
#include <string>
#include <variant>

namespace pbrt {

struct DiffuseMaterial {
    SpectrumTexture reflectance = Spectrum(0.5f);

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

// Roughness is TR alpha directly, or pbrt-v4's remapping from a perceptual roughness. Copper
// by default, as pbrt-v4. A reflectance, when given, replaces eta and k (pbrt-v4: k = 2 sqrt(r)
// / sqrt(1 - r), eta = 1).
struct ConductorMaterial {
    SpectrumTexture eta = *GetNamedSpectrum("metal-Cu-eta");
    SpectrumTexture k = *GetNamedSpectrum("metal-Cu-k");
    std::optional<SpectrumTexture> reflectance;
    FloatTexture uRoughness = 0, vRoughness = 0;
    bool remapRoughness = true;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

// Roughness as for ConductorMaterial; an eta that is not constant disperses.
struct DielectricMaterial {
    Spectrum eta = Spectrum(1.5f);
    FloatTexture uRoughness = 0, vRoughness = 0;
    bool remapRoughness = true;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

struct ThinDielectricMaterial {
    Spectrum eta = Spectrum(1.5f);

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

struct DiffuseTransmissionMaterial {
    SpectrumTexture reflectance = Spectrum(0.25f), transmittance = Spectrum(0.25f);
    Float scale = 1;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

// The parameters of pbrt-v4's layered materials: a medium of the given thickness, albedo and
// Henyey-Greenstein g between the interfaces, walked with at most maxDepth bounces, nSamples
// times; and which MIS weight f() gives the exit's connections (--layered-estimator).
struct LayerParameters {
    FloatTexture thickness = 0.01f;
    SpectrumTexture albedo = Spectrum(0.f);
    FloatTexture g = 0;
    int maxDepth = 10, nSamples = 1;
    LayeredExitMIS exitMIS = LayeredExitMIS::InnerDirection;
};

struct CoatedDiffuseMaterial {
    SpectrumTexture reflectance = Spectrum(0.5f);
    FloatTexture uRoughness = 0, vRoughness = 0;
    Spectrum eta = Spectrum(1.5f);
    bool remapRoughness = true;
    LayerParameters layer;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

struct CoatedConductorMaterial {
    FloatTexture interfaceURoughness = 0, interfaceVRoughness = 0;
    Spectrum interfaceEta = Spectrum(1.5f);
    ConductorMaterial conductor;
    bool remapRoughness = true;
    LayerParameters layer;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

// Our extension: the DreamWorks fabric lobe (pbrt_ext/bxdfs/fabric.h).
struct FabricMaterial {
    SpectrumTexture reflectance = Spectrum(0.5f);
    FloatTexture roughness = 0.5f;
    Float threadAngle = 0, threadElevation = 0;  // degrees: about N from dpdu, then toward N
    FabricSampling sampling = FabricSampling::Best;
    FabricNormalization normalization = FabricNormalization::Paper;
    // An optional diffuse base lobe, weighted so that the total albedo stays at most 1
    // (pbrt_ext/bxdfs/fabricdiffuse.h).
    std::optional<SpectrumTexture> diffuse;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

// pbrt-v4's hair (HairBxDF, Chiang et al. 2016), across the fiber at h = -1 + 2 v. The
// absorption inside the fiber comes from sigma_a, else from a reflectance (the colour after
// multiple scattering), else from melanin concentrations; eumelanin 1.3 (brown) when none is
// given. The roughnesses are kept at 0.01 or more, as pbrt-v4 keeps them.
struct HairMaterial {
    std::optional<SpectrumTexture> sigma_a, reflectance;
    FloatTexture eumelanin = 0, pheomelanin = 0;
    FloatTexture eta = 1.55f, beta_m = 0.3f, beta_n = 0.3f, alpha = 2;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

// The absorption coefficient (per unit of the fiber's diameter) that concentrations of
// eumelanin and pheomelanin give (pbrt-v4's constants, after d'Eon et al. 2011).
SampledSpectrum HairSigmaAFromConcentration(Float eumelanin, Float pheomelanin,
                                            const SampledWavelengths &lambda);

// pbrt-v4's MeasuredMaterial: an RGL .bsdf file (bxdfs/measured.h), shared by every material that
// names the same file.
struct MeasuredMaterial {
    std::shared_ptr<const MeasuredBxDFData> data;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
};

// pbrt-v4's SubsurfaceMaterial: a dielectric boundary (eta, roughness) over a translucent body
// whose BSSRDF (bssrdf.h) is given by sigma_a and sigma_s (per unit length, times scale), or by
// the diffuse reflectance it should have and a mean free path (inverted through the table).
// Its table depends on g and eta only and is made once, with the material.
struct SubsurfaceMaterial {
    Float scale = 1, eta = 1.33f;
    std::optional<SpectrumTexture> sigma_a, sigma_s;  // both, or neither
    std::optional<SpectrumTexture> reflectance;       // with mfp, when sigma_a and sigma_s are not given
    SpectrumTexture mfp = Spectrum(1.f);
    FloatTexture uRoughness = 0, vRoughness = 0;
    bool remapRoughness = true;
    std::shared_ptr<const BSSRDFTable> table;

    BxDF GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const;
    TabulatedBSSRDF GetBSSRDF(const SurfaceInteraction &si, SampledWavelengths &lambda) const;
};

// pbrt-v4's stochastic mix of two materials: at each hit one of them is chosen, the second with
// probability `amount`, by a hash of the hit, so that the choice is the same for a given point and
// direction. The scene resolves a mix to the chosen material before asking for a BSDF.
struct MixMaterial {
    int materials[2];  // indices into the scene's materials (-1: an interface)
    FloatTexture amount = 0.5f;

    int Choose(const SurfaceInteraction &si) const;
    // Never reached: Scene::GetBSDF resolves mixes first (kept for the closed dispatch).
    BxDF GetBxDF(const TextureEvalContext &, SampledWavelengths &) const {
        return DiffuseBxDF(SampledSpectrum(0.f));
    }
};

class Material {
  public:
    using Variant =
        std::variant<DiffuseMaterial, ConductorMaterial, DielectricMaterial, ThinDielectricMaterial,
                     DiffuseTransmissionMaterial, CoatedDiffuseMaterial, CoatedConductorMaterial,
                     FabricMaterial, HairMaterial, MeasuredMaterial, SubsurfaceMaterial, MixMaterial>;
    template <typename T>
    Material(T material) : material(std::move(material)) {}

    // The BSDF at a hit for the path's wavelengths, in the hit's shading frame. A bump or normal
    // map first perturbs that frame in si itself (pbrt-v4's SurfaceInteraction::GetBSDF), so
    // that the integrators' cosines |wi . si.shading.n| are the BSDF's own. Terminates lambda's
    // secondary wavelengths where it disperses.
    BSDF GetBSDF(SurfaceInteraction &si, SampledWavelengths &lambda) const;

    const MixMaterial *AsMix() const { return std::get_if<MixMaterial>(&material); }
    // The BSSRDF under the surface at a hit, for a subsurface material; none for the others.
    std::optional<TabulatedBSSRDF> GetBSSRDF(const SurfaceInteraction &si, SampledWavelengths &lambda) const {
        if (const auto *m = std::get_if<SubsurfaceMaterial>(&material)) return m->GetBSSRDF(si, lambda);
        return std::nullopt;
    }
    bool HasSubsurface() const { return std::holds_alternative<SubsurfaceMaterial>(material); }

    // pbrt-v4's "texture displacement" (bump mapping) and "string normalmap" (a tangent-space
    // normal map read with linear encoding). Either perturbs the shading frame of every BSDF.
    void SetDisplacement(FloatTexture displacement) { this->displacement = std::move(displacement); }
    // Whether GetBSDF reads the hit's ray differentials (pbrt-v4's bump map steps by them).
    bool UsesRayDifferentials() const { return displacement.has_value(); }
    void SetNormalMap(std::shared_ptr<const Image> image) { normalMap = std::move(image); }

  private:
    Variant material;
    std::optional<FloatTexture> displacement;
    std::shared_ptr<const Image> normalMap;
};

}  // namespace pbrt
