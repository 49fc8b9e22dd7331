// Materials from scene-file entities: pbrt-v4's parameters and defaults, and our "fabric".
#include "pbrt_ext/create.h"

#include "pbrt_ext/util/error.h"

namespace pbrt {

namespace {

// pbrt-v4's roughness parameters: "roughness", or "uroughness"/"vroughness" defaulting to it.
struct Roughness {
    FloatTexture u, v;
};

Roughness GetRoughness(const ParameterDictionary &p, TextureResolver &textures,
                       const std::string &prefix = "") {
    FloatTexture both = textures.Float(p, prefix + "roughness", 0);
    return {p.HasParameter(prefix + "uroughness") ? textures.Float(p, prefix + "uroughness", 0)
                                                  : both,
            p.HasParameter(prefix + "vroughness") ? textures.Float(p, prefix + "vroughness", 0)
                                                  : both};
}

// A conductor's eta and k: named or RGB spectra, or pbrt-v4's "reflectance" alternative
// (k = 2√r / √(1 - r), eta = 1). Copper by default, as pbrt-v4.
void GetConductorSpectra(const ParameterDictionary &p, TextureResolver &textures,
                         const std::string &prefix, ConductorMaterial *m) {
    if (p.HasParameter("reflectance")) {
        SampledSpectrum r = Clamp(textures.Spectrum(p, "reflectance", SampledSpectrum(0.f),
                                                    SpectrumKind::Reflectance)
                                      .Evaluate(TextureEvalContext()),
                                  Float(0), Float(0.9999f));
        m->eta = SampledSpectrum(1.f);
        m->k = 2 * Sqrt(r) / Sqrt(ClampZero(SampledSpectrum(1.f) - r));
        return;
    }
    SpectrumParam copperEta{SpectrumParamKind::Named, {}, "metal-Cu-eta", {}},
        copperK{SpectrumParamKind::Named, {}, "metal-Cu-k", {}};
    SampledSpectrum defaultEta = SpectrumToRGB(copperEta, SpectrumKind::Unbounded, textures.Folder());
    SampledSpectrum defaultK = SpectrumToRGB(copperK, SpectrumKind::Unbounded, textures.Folder());
    m->eta = textures.Spectrum(p, prefix + "eta", defaultEta, SpectrumKind::Unbounded);
    m->k = textures.Spectrum(p, prefix + "k", defaultK, SpectrumKind::Unbounded);
}

// A dielectric's index: a float, or a named glass at 550 nm (RGB rendering has no dispersion).
Float GetEta(const ParameterDictionary &p, const std::string &name, Float def) {
    if (!p.HasParameter(name))
        return def;
    if (p.ParameterType(name) == "float")
        return p.GetOneFloat(name, def);
    std::optional<SpectrumParam> s = p.GetOneSpectrum(name);
    if (s && s->kind == SpectrumParamKind::Named)
        if (pstd::optional<Float> eta = NamedGlassIOR(s->name, 550))
            return *eta;
    throw ParseError(*p.Loc(name), "\"" + name + "\" must be a float or a named glass spectrum");
}

LayerParameters GetLayer(const ParameterDictionary &p, TextureResolver &textures) {
    LayerParameters layer;
    layer.thickness = textures.Float(p, "thickness", 0.01f);
    layer.albedo = textures.Spectrum(p, "albedo", SampledSpectrum(0.f), SpectrumKind::Reflectance);
    layer.g = textures.Float(p, "g", 0);
    layer.maxDepth = p.GetOneInt("maxdepth", 10);
    layer.nSamples = p.GetOneInt("nsamples", 1);
    return layer;
}

}  // namespace

FabricMaterial CreateFabricMaterial(const ParameterDictionary &p, TextureResolver &textures,
                                    const RenderOverrides &overrides) {
    FabricMaterial m;
    m.reflectance = textures.Spectrum(p, "reflectance", SampledSpectrum(0.5f),
                                      SpectrumKind::Reflectance);
    m.roughness = textures.Float(p, "roughness", 0.5f);
    m.threadAngle = p.GetOneFloat("threadangle", 0);
    m.threadElevation = p.GetOneFloat("threadelevation", 0);
    std::string sampler = p.GetOneString("sampler", "best"),
                normalization = p.GetOneString("normalization", "paper");
    try {
        m.sampling = ParseFabricSampling(sampler);
    } catch (const std::invalid_argument &error) {
        throw ParseError(*p.Loc("sampler"), error.what());
    }
    if (overrides.fabricSampler)
        m.sampling = *overrides.fabricSampler;
    if (p.HasParameter("diffuse"))
        m.diffuse = textures.Spectrum(p, "diffuse", SampledSpectrum(0.f), SpectrumKind::Reflectance);
    if (normalization == "unitpeak")
        m.normalization = FabricNormalization::UnitPeak;
    else if (normalization != "paper")
        throw ParseError(*p.Loc("normalization"), "unknown fabric normalization \"" +
                                                      normalization + "\": expected paper or unitpeak");
    return m;
}

namespace {

// pbrt-v4's "texture displacement" (bump map; a float texture or value) and "string normalmap"
// (an image read with linear encoding, relative to the scene's folder).
void SetShadingPerturbation(const ParameterDictionary &p, TextureResolver &textures, Material *m) {
    if (p.HasParameter("displacement"))
        m->SetDisplacement(textures.Float(p, "displacement", 0));
    std::string normalMap = p.GetOneString("normalmap", "");
    if (normalMap.empty())
        return;
    if (p.HasParameter("displacement"))
        throw ParseError(*p.Loc("normalmap"), "a material takes \"displacement\" or \"normalmap\", "
                                              "not both");
    m->SetNormalMap(
        ImageTextureCache::Get(ResolvePath(textures.Folder(), normalMap), ColorEncoding::Linear()));
}

}  // namespace

std::optional<Material> CreateMaterial(const SceneEntity &e, const std::string &type,
                                       const RenderOverrides &overrides,
                                       TextureResolver &textures) {
    const ParameterDictionary &p = e.parameters;
    std::optional<Material> material;
    if (type == "diffuse" || type.empty()) {
        material = DiffuseMaterial{textures.Spectrum(p, "reflectance", SampledSpectrum(0.5f),
                                                     SpectrumKind::Reflectance)};
    } else if (type == "conductor") {
        ConductorMaterial m;
        GetConductorSpectra(p, textures, "", &m);
        Roughness r = GetRoughness(p, textures);
        m.uRoughness = r.u;
        m.vRoughness = r.v;
        m.remapRoughness = p.GetOneBool("remaproughness", true);
        material = m;
    } else if (type == "dielectric") {
        DielectricMaterial m;
        m.eta = GetEta(p, "eta", 1.5f);
        Roughness r = GetRoughness(p, textures);
        m.uRoughness = r.u;
        m.vRoughness = r.v;
        m.remapRoughness = p.GetOneBool("remaproughness", true);
        material = m;
    } else if (type == "thindielectric") {
        material = ThinDielectricMaterial{GetEta(p, "eta", 1.5f)};
    } else if (type == "diffusetransmission") {
        DiffuseTransmissionMaterial m;
        m.reflectance = textures.Spectrum(p, "reflectance", SampledSpectrum(0.25f),
                                          SpectrumKind::Reflectance);
        m.transmittance = textures.Spectrum(p, "transmittance", SampledSpectrum(0.25f),
                                            SpectrumKind::Reflectance);
        m.scale = p.GetOneFloat("scale", 1);
        material = m;
    } else if (type == "coateddiffuse") {
        CoatedDiffuseMaterial m;
        m.reflectance = textures.Spectrum(p, "reflectance", SampledSpectrum(0.5f),
                                          SpectrumKind::Reflectance);
        Roughness r = GetRoughness(p, textures);
        m.uRoughness = r.u;
        m.vRoughness = r.v;
        m.eta = GetEta(p, "eta", 1.5f);
        m.remapRoughness = p.GetOneBool("remaproughness", true);
        m.layer = GetLayer(p, textures);
        material = m;
    } else if (type == "coatedconductor") {
        CoatedConductorMaterial m;
        Roughness interface = GetRoughness(p, textures, "interface.");
        m.interfaceURoughness = interface.u;
        m.interfaceVRoughness = interface.v;
        m.interfaceEta = GetEta(p, "interface.eta", 1.5f);
        GetConductorSpectra(p, textures, "conductor.", &m.conductor);
        Roughness conductor = GetRoughness(p, textures, "conductor.");
        m.conductor.uRoughness = conductor.u;
        m.conductor.vRoughness = conductor.v;
        m.remapRoughness = m.conductor.remapRoughness = p.GetOneBool("remaproughness", true);
        m.layer = GetLayer(p, textures);
        material = m;
    } else if (type == "fabric") {
        material = CreateFabricMaterial(p, textures, overrides);
    } else if (type == "interface") {
        p.ReportUnused();
        return std::nullopt;
    } else if (type == "measured" || type == "hair" || type == "subsurface") {
        WarningAt(e.loc, "Material \"%s\" is not supported: rendered as diffuse 0.5",
                  type.c_str());
        return DiffuseMaterial{};
    } else {
        throw ParseError(e.loc, "unknown Material \"" + type + "\"");
    }
    SetShadingPerturbation(p, textures, &*material);
    p.ReportUnused();
    return material;
}

}  // namespace pbrt
