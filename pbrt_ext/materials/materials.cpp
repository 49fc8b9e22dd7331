#include "pbrt_ext/materials/materials.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/scattering.h"

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

SampledSpectrum Reflectance(const SpectrumTexture &texture, const TextureEvalContext &ctx,
                            const SampledWavelengths &lambda) {
    return Clamp(texture.Evaluate(ctx, lambda), Float(0), Float(1));
}

// A dielectric's index at the first wavelength (pbrt-v4): one that varies with wavelength
// sends each wavelength its own way, so the others stop contributing.
Float SampledEta(const Spectrum &eta, SampledWavelengths &lambda) {
    Float sampled = eta(lambda[0]);
    if (!eta.IsConstant()) lambda.TerminateSecondary();
    return sampled == 0 ? 1 : sampled;
}

// A conductor's eta and k at lambda, from its reflectance where one is given.
void ConductorSpectra(const ConductorMaterial &m, const TextureEvalContext &ctx,
                      const SampledWavelengths &lambda, SampledSpectrum *eta, SampledSpectrum *k) {
    if (!m.reflectance) {
        *eta = m.eta.Evaluate(ctx, lambda);
        *k = m.k.Evaluate(ctx, lambda);
        return;
    }
    SampledSpectrum r = Clamp(m.reflectance->Evaluate(ctx, lambda), Float(0), Float(0.9999f));  // r = 1: k = inf
    *eta = SampledSpectrum(1.f);
    *k = 2 * Sqrt(r) / Sqrt(ClampZero(SampledSpectrum(1.f) - r));
}

}  // namespace

BxDF DiffuseMaterial::GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const {
    return DiffuseBxDF(Reflectance(reflectance, ctx, lambda));
}

BxDF ConductorMaterial::GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const {
    SampledSpectrum etas, ks;
    ConductorSpectra(*this, ctx, lambda, &etas, &ks);
    return ConductorBxDF(Microfacets(uRoughness, vRoughness, remapRoughness, ctx), etas, ks);
}

BxDF DielectricMaterial::GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const {
    return DielectricBxDF(SampledEta(eta, lambda),
                          Microfacets(uRoughness, vRoughness, remapRoughness, ctx));
}

BxDF ThinDielectricMaterial::GetBxDF(const TextureEvalContext &, SampledWavelengths &lambda) const {
    return ThinDielectricBxDF(SampledEta(eta, lambda));
}

BxDF DiffuseTransmissionMaterial::GetBxDF(const TextureEvalContext &ctx,
                                          SampledWavelengths &lambda) const {
    return DiffuseTransmissionBxDF(Reflectance(reflectance, ctx, lambda) * scale,
                                   Reflectance(transmittance, ctx, lambda) * scale);
}

BxDF CoatedDiffuseMaterial::GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const {
    SampledSpectrum r = Reflectance(reflectance, ctx, lambda);
    DielectricBxDF coat(SampledEta(eta, lambda),
                        Microfacets(uRoughness, vRoughness, remapRoughness, ctx));
    return CoatedDiffuseBxDF(coat, DiffuseBxDF(r), layer.thickness.Evaluate(ctx),
                             Reflectance(layer.albedo, ctx, lambda), layer.g.Evaluate(ctx),
                             layer.maxDepth, layer.nSamples, layer.exitMIS);
}

// pbrt-v4 gives the conductor under the coat its index relative to the coat's.
BxDF CoatedConductorMaterial::GetBxDF(const TextureEvalContext &ctx,
                                      SampledWavelengths &lambda) const {
    Float ieta = SampledEta(interfaceEta, lambda);
    DielectricBxDF coat(ieta, Microfacets(interfaceURoughness, interfaceVRoughness,
                                          remapRoughness, ctx));
    SampledSpectrum ce, ck;
    ConductorSpectra(conductor, ctx, lambda, &ce, &ck);
    ConductorBxDF base(Microfacets(conductor.uRoughness, conductor.vRoughness,
                                   conductor.remapRoughness, ctx),
                       ce / ieta, ck / ieta);
    return CoatedConductorBxDF(coat, base, layer.thickness.Evaluate(ctx),
                               Reflectance(layer.albedo, ctx, lambda), layer.g.Evaluate(ctx),
                               layer.maxDepth, layer.nSamples, layer.exitMIS);
}

BxDF FabricMaterial::GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const {
    FabricBxDF fabric(Reflectance(reflectance, ctx, lambda), roughness.Evaluate(ctx),
                      FabricBxDF::ThreadDirection(threadAngle, threadElevation), sampling,
                      normalization);
    if (!diffuse)
        return fabric;
    return FabricDiffuseBxDF(fabric, Reflectance(*diffuse, ctx, lambda));
}

SampledSpectrum HairSigmaAFromConcentration(Float eumelanin, Float pheomelanin,
                                            const SampledWavelengths &lambda) {
    RGB eumelaninSigma_a(0.419f, 0.697f, 1.37f), pheomelaninSigma_a(0.187f, 0.4f, 1.05f);
    RGB sigma_a = eumelanin * eumelaninSigma_a + pheomelanin * pheomelaninSigma_a;
    return RGBUnboundedSpectrum(RGBColorSpace::sRGB(), sigma_a).Sample(lambda);
}

BxDF MeasuredMaterial::GetBxDF(const TextureEvalContext &, SampledWavelengths &lambda) const {
    return MeasuredBxDF(data.get(), lambda);
}

BxDF SubsurfaceMaterial::GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &) const {
    return DielectricBxDF(eta, Microfacets(uRoughness, vRoughness, remapRoughness, ctx));
}

TabulatedBSSRDF SubsurfaceMaterial::GetBSSRDF(const SurfaceInteraction &si,
                                              SampledWavelengths &lambda) const {
    TextureEvalContext ctx(si);
    SampledSpectrum sig_a, sig_s;
    if (sigma_a && sigma_s) {
        sig_a = ClampZero(scale * sigma_a->Evaluate(ctx, lambda));
        sig_s = ClampZero(scale * sigma_s->Evaluate(ctx, lambda));
    } else {
        SampledSpectrum mfree = ClampZero(scale * mfp.Evaluate(ctx, lambda));
        SampledSpectrum r = Reflectance(*reflectance, ctx, lambda);
        SubsurfaceFromDiffuse(*table, r, mfree, &sig_a, &sig_s);
    }
    return TabulatedBSSRDF(si.p, si.shading.n, eta, sig_a, sig_s, table.get());
}

BxDF HairMaterial::GetBxDF(const TextureEvalContext &ctx, SampledWavelengths &lambda) const {
    Float bm = std::max<Float>(1e-2f, beta_m.Evaluate(ctx));
    Float bn = std::max<Float>(1e-2f, beta_n.Evaluate(ctx));
    SampledSpectrum absorption;
    if (sigma_a)
        absorption = ClampZero(sigma_a->Evaluate(ctx, lambda));
    else if (reflectance)
        absorption = HairBxDF::SigmaAFromReflectance(Reflectance(*reflectance, ctx, lambda), bn);
    else
        absorption = HairSigmaAFromConcentration(std::max<Float>(0, eumelanin.Evaluate(ctx)),
                                                 std::max<Float>(0, pheomelanin.Evaluate(ctx)),
                                                 lambda);
    return HairBxDF(-1 + 2 * ctx.uv[1], eta.Evaluate(ctx), absorption, bm, bn,
                    alpha.Evaluate(ctx));
}

namespace {

struct ShadingFrame {
    Normal3f n;
    Vector3f dpdu, dpdv;
};

// pbrt-v4's BumpMap: the surface displaced along the shading normal by d(u, v), differentiated by
// forward differences, plus d times the turning of the normal itself (dn/du, dn/dv: large where a
// big displacement meets curved shading normals). The step is half the pixel's footprint in u
// and in v (from the ray differentials), or pbrt-v4's fallback of 0.0005 where it is zero.
ShadingFrame BumpMap(const FloatTexture &displacement, const SurfaceInteraction &si) {
    Float du = .5f * (std::abs(si.dudx) + std::abs(si.dudy));
    Float dv = .5f * (std::abs(si.dvdx) + std::abs(si.dvdy));
    if (du == 0)
        du = .0005f;
    if (dv == 0)
        dv = .0005f;
    TextureEvalContext ctx(si);
    Float d = displacement.Evaluate(ctx);
    TextureEvalContext shifted = ctx;
    shifted.p = si.p + du * si.shading.dpdu;
    shifted.uv = Point2f(si.uv[0] + du, si.uv[1]);
    Float dU = displacement.Evaluate(shifted);
    shifted.p = si.p + dv * si.shading.dpdv;
    shifted.uv = Point2f(si.uv[0], si.uv[1] + dv);
    Float dV = displacement.Evaluate(shifted);
    Vector3f n(si.shading.n);
    Vector3f dpdu = si.shading.dpdu + (dU - d) / du * n + d * Vector3f(si.shading.dndu);
    Vector3f dpdv = si.shading.dpdv + (dV - d) / dv * n + d * Vector3f(si.shading.dndv);
    Normal3f ns(Normalize(Cross(dpdu, dpdv)));
    if (!IsFinite(ns.x) || LengthSquared(Vector3f(ns)) == 0)
        return {si.shading.n, si.shading.dpdu, si.shading.dpdv};
    return {ns, dpdu, dpdv};
}

// pbrt-v4's NormalMap: the map's RGB in [0, 1] is a tangent-space normal 2 rgb - 1 in the frame
// (dpdu, n); t is flipped so that the file's top row is v = 1.
ShadingFrame NormalMap(const Image &image, const SurfaceInteraction &si) {
    Point2f st(si.uv[0], 1 - si.uv[1]);
    RGB rgb = image.Bilerp(st, WrapMode::Repeat);
    Vector3f local = Normalize(Vector3f(2 * rgb[0] - 1, 2 * rgb[1] - 1, 2 * rgb[2] - 1));
    Vector3f x = si.shading.dpdu - Dot(si.shading.dpdu, Vector3f(si.shading.n)) * Vector3f(si.shading.n);
    if (LengthSquared(x) == 0 || !IsFinite(local.x))
        return {si.shading.n, si.shading.dpdu, si.shading.dpdv};
    Frame frame = Frame::FromXZ(Normalize(x), Vector3f(si.shading.n));
    Normal3f ns(frame.FromLocal(local));
    Vector3f tangent = GramSchmidt(si.shading.dpdu, Vector3f(ns));
    if (LengthSquared(tangent) == 0)  // the map's normal lies along dpdu: the old normal is a tangent
        tangent = Vector3f(si.shading.n);
    Vector3f dpdu = Normalize(tangent) * Length(si.shading.dpdu);
    Vector3f dpdv = Normalize(Cross(Vector3f(ns), dpdu)) * Length(si.shading.dpdv);
    return {ns, dpdu, dpdv};
}

}  // namespace

BSDF Material::GetBSDF(SurfaceInteraction &si, SampledWavelengths &lambda) const {
    if (displacement || normalMap) {
        ShadingFrame frame = displacement ? BumpMap(*displacement, si) : NormalMap(*normalMap, si);
        si.SetShadingGeometry(frame.n, frame.dpdu, frame.dpdv, false);
    }
    TextureEvalContext ctx(si);
    BxDF bxdf = std::visit([&](const auto &m) { return m.GetBxDF(ctx, lambda); }, material);
    return BSDF(si.shading.n, si.shading.dpdu, std::move(bxdf));
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

}  // namespace pbrt
