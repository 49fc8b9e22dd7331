#include "pbrt_ext/materials.h"

#include "pbrt_ext/options.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/scattering.h"

#include <stdexcept>

namespace pbrt {

namespace {

// TR microfacets from two roughness textures, optionally remapped (pbrt-v4's remaproughness).
TrowbridgeReitzDistribution Microfacets(const FloatTexture &uRoughness,
                                        const FloatTexture &vRoughness, bool remap,
                                        const TextureEvalContext &ctx) {
    Float u = uRoughness.Evaluate(ctx), v = vRoughness.Evaluate(ctx);
    if (remap) {
        u = TrowbridgeReitzDistribution::RoughnessToAlpha(u);
        v = TrowbridgeReitzDistribution::RoughnessToAlpha(v);
    }
    return TrowbridgeReitzDistribution(u, v);
}

SampledSpectrum Reflectance(const SpectrumTexture &texture, const TextureEvalContext &ctx) {
    return Clamp(texture.Evaluate(ctx), Float(0), Float(1));
}

}  // namespace

BxDF DiffuseMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    return DiffuseBxDF(Reflectance(reflectance, ctx));
}


BxDF ConductorMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    return ConductorBxDF(Microfacets(uRoughness, vRoughness, remapRoughness, ctx), eta.Evaluate(ctx),
                         k.Evaluate(ctx));
}

BxDF DielectricMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    return DielectricBxDF(eta, Microfacets(uRoughness, vRoughness, remapRoughness, ctx));
}

BxDF ThinDielectricMaterial::GetBxDF(const TextureEvalContext &) const {
    return ThinDielectricBxDF(eta);
}

BxDF DiffuseTransmissionMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    return DiffuseTransmissionBxDF(Reflectance(reflectance, ctx) * scale,
                                   Reflectance(transmittance, ctx) * scale);
}

BxDF CoatedDiffuseMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    return CoatedDiffuseBxDF(DielectricBxDF(eta, Microfacets(uRoughness, vRoughness,
                                                             remapRoughness, ctx)),
                             DiffuseBxDF(Reflectance(reflectance, ctx)),
                             layer.thickness.Evaluate(ctx), layer.albedo.Evaluate(ctx),
                             layer.g.Evaluate(ctx), layer.maxDepth, layer.nSamples);
}

BxDF CoatedConductorMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    DielectricBxDF coat(interfaceEta, Microfacets(interfaceURoughness, interfaceVRoughness,
                                                  remapRoughness, ctx));
    ConductorBxDF base(Microfacets(conductor.uRoughness, conductor.vRoughness,
                                   conductor.remapRoughness, ctx),
                       conductor.eta.Evaluate(ctx), conductor.k.Evaluate(ctx));
    return CoatedConductorBxDF(coat, base, layer.thickness.Evaluate(ctx), layer.albedo.Evaluate(ctx),
                               layer.g.Evaluate(ctx), layer.maxDepth, layer.nSamples);
}

BxDF FabricMaterial::GetBxDF(const TextureEvalContext &ctx) const {
    return FabricBxDF(Reflectance(reflectance, ctx), roughness.Evaluate(ctx),
                      FabricBxDF::ThreadDirection(threadAngle, threadElevation), sampling,
                      normalization);
}

int MixMaterial::Choose(const SurfaceInteraction &si) const {
    Float amt = amount.Evaluate(TextureEvalContext(si));
    if (amt <= 0)
        return materials[0];
    if (amt >= 1)
        return materials[1];
    Float u = Float(uint32_t(Hash(si.p, si.wo, materials[0], materials[1]))) * 0x1p-32f;
    return amt < u ? materials[0] : materials[1];
}

FabricSampling ParseFabricSampling(const std::string &name) {
    constexpr std::pair<const char *, FabricSampling> names[] = {
        {"uniform", FabricSampling::Uniform},
        {"cosine", FabricSampling::Cosine},
        {"paper", FabricSampling::Paper},
        {"truncatedsinphi", FabricSampling::TruncatedSinPhi},
        {"best", FabricSampling::Best}};
    for (auto [n, sampling] : names)
        if (name == n)
            return sampling;
    throw std::invalid_argument("unknown fabric sampler \"" + name +
                                "\": expected uniform, cosine, paper, truncatedsinphi or best");
}

}  // namespace pbrt
