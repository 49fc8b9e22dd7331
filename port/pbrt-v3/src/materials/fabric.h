// FabricMaterial: pbrt_ext's "fabric" material in pbrt-v3, with the same parameters, defaults and
// errors as pbrt_ext (its docs/scene-format.md): "reflectance" (0.5), "roughness" (0.5),
// "threadangle" (0), "threadelevation" (0), "sampler" ("best"), "normalization" ("paper"),
// "diffuse" (none), and pbrt-v3's "bumpmap". Its BxDF is materials/fabricreflection.h.
// This header stays C++11 (core/api.cpp includes it); only fabric.cpp sees pbrt_ext's C++20 headers.
#ifndef PBRT_MATERIALS_FABRIC_H
#define PBRT_MATERIALS_FABRIC_H

#include "pbrt.h"
#include "geometry.h"
#include "material.h"

#include <memory>

namespace pbrt {

class FabricMaterial : public Material {
  public:
    // sampling and normalization are pbrt_ext::FabricSampling and FabricNormalization values.
    FabricMaterial(const std::shared_ptr<Texture<Spectrum>> &reflectance,
                   const std::shared_ptr<Texture<Float>> &roughness,
                   const std::shared_ptr<Texture<Spectrum>> &diffuse, const Vector3f &thread,
                   int sampling, int normalization,
                   const std::shared_ptr<Texture<Float>> &bumpMap)
        : reflectance(reflectance),
          roughness(roughness),
          diffuse(diffuse),
          thread(thread),
          sampling(sampling),
          normalization(normalization),
          bumpMap(bumpMap) {}

    void ComputeScatteringFunctions(SurfaceInteraction *si, MemoryArena &arena,
                                    TransportMode mode, bool allowMultipleLobes) const;

  private:
    std::shared_ptr<Texture<Spectrum>> reflectance;
    std::shared_ptr<Texture<Float>> roughness;
    std::shared_ptr<Texture<Spectrum>> diffuse;  // nullptr: no diffuse base
    Vector3f thread;                             // in the shading frame
    int sampling, normalization;
    std::shared_ptr<Texture<Float>> bumpMap;
};

FabricMaterial *CreateFabricMaterial(const TextureParams &mp);

}  // namespace pbrt

#endif  // PBRT_MATERIALS_FABRIC_H
