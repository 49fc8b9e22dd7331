#include "pbrt_ext/materials.h"

#include "pbrt_ext/util/scattering.h"

namespace pbrt {

BxDF DiffuseMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    return DiffuseBxDF(Clamp(reflectance.Evaluate(ctx), Float(0), Float(1)));
}

BxDF ConductorMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    Float u = uRoughness.Evaluate(ctx), v = vRoughness.Evaluate(ctx);
    if (remapRoughness) {
        u = TrowbridgeReitzDistribution::RoughnessToAlpha(u);
        v = TrowbridgeReitzDistribution::RoughnessToAlpha(v);
    }
    return ConductorBxDF(TrowbridgeReitzDistribution(u, v), eta.Evaluate(ctx), k.Evaluate(ctx));
}

BxDF FabricMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    return FabricBxDF(Clamp(reflectance.Evaluate(ctx), Float(0), Float(1)), roughness.Evaluate(ctx),
                      FabricBxDF::ThreadDirection(threadAngle, threadElevation), sampling,
                      normalization);
}

}  // namespace pbrt
