// FabricMaterial: pbrt_ext's "fabric" material in pbrt-v4. It reads the same parameters, with the same
// defaults and errors, as pbrt_ext (docs/scene-format.md there):
//   spectrum/texture "reflectance" (0.5)   the lobe's color
//   float/texture    "roughness"   (0.5)   mapped to the lobe exponent n = ceil(1 + 29 (1 - r)²)
//   float "threadangle" (0), "threadelevation" (0)   degrees: about N from dpdu, then toward N
//   string "sampler" ("best"): uniform, cosine, paper, truncatedsinphi or best
//   string "normalization" ("paper"): paper or unitpeak
//   spectrum/texture "diffuse" (none)      a Lambertian base, weighted so the albedo stays ≤ 1
// and pbrt-v4's "displacement" and normal map. Its BxDF is always FabricDiffuseBxDF: with no diffuse
// base that is exactly FabricBxDF (bxdfs/fabricdiffuse.h).

// Before the guard: included first, this lets materials.h include this file where its dispatch
// needs FabricMaterial complete.
#include <pbrt/materials.h>

#ifndef PBRT_MATERIALS_FABRIC_H
#define PBRT_MATERIALS_FABRIC_H

#include <pbrt/pbrt.h>

#include <pbrt/bxdfs.h>
#include <pbrt/textures.h>

#include <string>

namespace pbrt {

class FabricMaterial {
  public:
    using BxDF = FabricDiffuseBxDF;
    using BSSRDF = void;

    static const char *Name() { return "FabricMaterial"; }

    FabricMaterial(SpectrumTexture reflectance, FloatTexture roughness, Vector3f thread,
                   FabricSampling sampling, FabricNormalization normalization,
                   SpectrumTexture diffuse, FloatTexture displacement, Image *normalMap)
        : reflectance(reflectance),
          roughness(roughness),
          thread(thread),
          sampling(sampling),
          normalization(normalization),
          diffuse(diffuse),
          displacement(displacement),
          normalMap(normalMap) {}

    static FabricMaterial *Create(const TextureParameterDictionary &parameters,
                                  Image *normalMap, const FileLoc *loc, Allocator alloc);

    template <typename TextureEvaluator>
    PBRT_CPU_GPU bool CanEvaluateTextures(TextureEvaluator texEval) const {
        return texEval.CanEvaluate({roughness}, {reflectance, diffuse});
    }

    template <typename TextureEvaluator>
    PBRT_CPU_GPU FabricDiffuseBxDF GetBxDF(TextureEvaluator texEval, MaterialEvalContext ctx,
                                           SampledWavelengths &lambda) const {
        SampledSpectrum color = Clamp(texEval(reflectance, ctx, lambda), 0, 1);
        FabricBxDF fabric(color, texEval(roughness, ctx), thread, sampling, normalization);
        SampledSpectrum base =
            diffuse ? Clamp(texEval(diffuse, ctx, lambda), 0, 1) : SampledSpectrum(0.f);
        return FabricDiffuseBxDF(fabric, base);
    }

    template <typename TextureEvaluator>
    PBRT_CPU_GPU void GetBSSRDF(TextureEvaluator texEval, MaterialEvalContext ctx,
                                SampledWavelengths &lambda, void *) const {}

    PBRT_CPU_GPU static constexpr bool HasSubsurfaceScattering() { return false; }

    PBRT_CPU_GPU FloatTexture GetDisplacement() const { return displacement; }
    PBRT_CPU_GPU const Image *GetNormalMap() const { return normalMap; }

    std::string ToString() const;

  private:
    SpectrumTexture reflectance;
    FloatTexture roughness;
    Vector3f thread;  // in the shading frame (FabricBxDF::ThreadDirection)
    FabricSampling sampling;
    FabricNormalization normalization;
    SpectrumTexture diffuse;  // nullptr: no base
    FloatTexture displacement;
    Image *normalMap;
};

}  // namespace pbrt

#endif  // PBRT_MATERIALS_FABRIC_H
