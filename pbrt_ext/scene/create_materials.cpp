// Materials from scene-file entities: pbrt-v4's parameters and defaults, and our "fabric".
#include "pbrt_ext/scene/create.h"

#include "pbrt_ext/media/scatteringpresets.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/error.h"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <mutex>

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
        m->reflectance = textures.GetSpectrumTexture(p, "reflectance", Spectrum(0.f), SpectrumType::Albedo);
        return;
    }
    m->eta = textures.GetSpectrumTexture(p, prefix + "eta", *GetNamedSpectrum("metal-Cu-eta"),
                                         SpectrumType::Unbounded);
    m->k = textures.GetSpectrumTexture(p, prefix + "k", *GetNamedSpectrum("metal-Cu-k"),
                                       SpectrumType::Unbounded);
}

// A dielectric's index: a float, or any spectrum (pbrt-v4: a named glass, samples, a file),
// which then disperses.
Spectrum GetEta(const ParameterDictionary &p, const std::string &name, Float def,
                const std::string &folder) {
    if (!p.HasParameter(name))
        return Spectrum(def);
    if (p.ParameterType(name) == "float")
        return Spectrum(p.GetOneFloat(name, def));
    return GetSpectrum(p, name, Spectrum(def), SpectrumType::Unbounded, folder);
}

LayerParameters GetLayer(const ParameterDictionary &p, TextureResolver &textures,
                         const RenderOverrides &overrides) {
    LayerParameters layer;
    layer.exitMIS = overrides.layeredExitMIS;
    layer.thickness = textures.Float(p, "thickness", 0.01f);
    layer.albedo = textures.GetSpectrumTexture(p, "albedo", Spectrum(0.f), SpectrumType::Albedo);
    layer.g = textures.Float(p, "g", 0);
    layer.maxDepth = p.GetOneInt("maxdepth", 10);
    layer.nSamples = p.GetOneInt("nsamples", 1);
    return layer;
}

}  // namespace

FabricMaterial CreateFabricMaterial(const ParameterDictionary &p, TextureResolver &textures,
                                    const RenderOverrides &overrides) {
    FabricMaterial m;
    m.reflectance = textures.GetSpectrumTexture(p, "reflectance", Spectrum(0.5f), SpectrumType::Albedo);
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
        m.diffuse = textures.GetSpectrumTexture(p, "diffuse", Spectrum(0.f), SpectrumType::Albedo);
    std::string error;
    pstd::optional<FabricNormalization> norm = FabricOptionFromName<FabricNormalization>(
        "normalization", kFabricNormalizationNames, normalization, &error);
    if (!norm)
        throw ParseError(*p.Loc("normalization"), error);
    m.normalization = *norm;
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
    m->SetNormalMap(ReadFileAt(*p.Loc("normalmap"), [&] {
        return ImageTextureCache::Get(ResolvePath(textures.Folder(), normalMap), ColorEncoding::Linear());
    }));
}

// pbrt-v4's measured material: "filename", an RGL .bsdf file relative to the scene's folder. A
// file is read once however many materials name it (while it stays unchanged on disk).
MeasuredMaterial CreateMeasuredMaterial(const SceneEntity &e, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty())
        throw ParseError(p.Loc("filename") ? *p.Loc("filename") : e.loc,
                         "the measured material needs \"string filename\", an RGL .bsdf file");
    const std::string path = ResolvePath(folder, filename);
    static std::mutex mutex;
    static std::map<std::string, std::shared_ptr<const MeasuredBxDFData>> loaded;
    std::error_code ec;
    std::string key = path + "|" + std::to_string(std::filesystem::file_size(path, ec)) + "|" +
                      std::to_string(std::filesystem::last_write_time(path, ec).time_since_epoch().count());
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = loaded.find(key); it != loaded.end()) return MeasuredMaterial{it->second};
    try {
        return MeasuredMaterial{loaded[key] = MeasuredBxDFData::Read(path)};
    } catch (const ParseError &) {
        throw;  // the memory check's, located at the file
    } catch (const std::runtime_error &error) {
        throw ParseError(*p.Loc("filename"), error.what());
    }
}

// pbrt-v4's four ways to give a subsurface material's scattering, in its order: a measured
// "name" (reduced coefficients, so g is 0), "sigma_a" with "sigma_s", a diffuse "reflectance"
// with a mean free path "mfp" (1 by default), or else pbrt-v4's default (whole milk in mm^-1).
// What pbrt-v4 accepts but no material can be (a non-positive eta, a negative scale, |g| >= 1)
// is an error at the parameter.
SubsurfaceMaterial CreateSubsurfaceMaterial(const SceneEntity &e, TextureResolver &textures) {
    const ParameterDictionary &p = e.parameters;
    auto locOf = [&](const char *name) { return p.Loc(name) ? *p.Loc(name) : e.loc; };
    SubsurfaceMaterial m;
    Float g = p.GetOneFloat("g", 0);
    if (std::string name = p.GetOneString("name", ""); !name.empty()) {
        std::optional<std::pair<Spectrum, Spectrum>> measured = MeasuredScattering(name);
        if (!measured)
            throw ParseError(locOf("name"), "unknown subsurface \"name\" \"" + name +
                                                "\"; expected one of " + MeasuredScatteringNames());
        if (g != 0) WarningAt(locOf("g"), "subsurface: \"g\" is ignored with a named measurement");
        g = 0;
        m.sigma_a = SpectrumTexture(measured->first);
        m.sigma_s = SpectrumTexture(measured->second);
    } else if (p.HasParameter("sigma_a") || p.HasParameter("sigma_s")) {
        for (auto [given, other] : {std::pair{"sigma_a", "sigma_s"}, {"sigma_s", "sigma_a"}})
            if (p.HasParameter(given) && !p.HasParameter(other))
                throw ParseError(locOf(given), std::string("subsurface: \"") + given +
                                                   "\" without \"" + other + "\"");
        m.sigma_a = textures.GetSpectrumTexture(p, "sigma_a", Spectrum(0.f), SpectrumType::Unbounded);
        m.sigma_s = textures.GetSpectrumTexture(p, "sigma_s", Spectrum(0.f), SpectrumType::Unbounded);
    } else if (p.HasParameter("reflectance")) {
        m.reflectance = textures.GetSpectrumTexture(p, "reflectance", Spectrum(0.f), SpectrumType::Albedo);
        m.mfp = textures.GetSpectrumTexture(p, "mfp", Spectrum(1.f), SpectrumType::Unbounded);
    } else {
        const RGBColorSpace &srgb = RGBColorSpace::sRGB();
        m.sigma_a = SpectrumTexture(Spectrum(RGBUnboundedSpectrum(srgb, RGB(.0011f, .0024f, .014f))));
        m.sigma_s = SpectrumTexture(Spectrum(RGBUnboundedSpectrum(srgb, RGB(2.55f, 3.21f, 3.77f))));
    }
    m.scale = p.GetOneFloat("scale", 1);
    m.eta = p.GetOneFloat("eta", 1.33f);
    if (!(m.scale >= 0) || std::isinf(m.scale))
        throw ParseError(locOf("scale"), fmt::format("subsurface \"scale\" is {}; expected a finite value >= 0", m.scale));
    if (!(m.eta > 0) || std::isinf(m.eta))
        throw ParseError(locOf("eta"), fmt::format("subsurface \"eta\" is {}; expected a finite value > 0", m.eta));
    if (!(g > -1 && g < 1))
        throw ParseError(locOf("g"), fmt::format("subsurface \"g\" is {}; expected -1 < g < 1", g));
    Roughness roughness = GetRoughness(p, textures);
    m.uRoughness = roughness.u;
    m.vRoughness = roughness.v;
    m.remapRoughness = p.GetOneBool("remaproughness", true);
    m.table = std::make_shared<const BSSRDFTable>(g, m.eta);
    return m;
}

// pbrt-v4's precedence: sigma_a, else reflectance, else the melanins (eumelanin 1.3 when none
// of them is given); what is shadowed is read, and warned about, as pbrt-v4 does.
HairMaterial CreateHairMaterial(const SceneEntity &e, TextureResolver &textures) {
    const ParameterDictionary &p = e.parameters;
    auto optional = [&](const char *name, SpectrumType type) -> std::optional<SpectrumTexture> {
        if (!p.HasParameter(name))
            return {};
        return textures.GetSpectrumTexture(p, name, Spectrum(0.f), type);
    };
    HairMaterial m;
    m.sigma_a = optional("sigma_a", SpectrumType::Unbounded);
    std::optional<SpectrumTexture> reflectance = optional("reflectance", SpectrumType::Albedo);
    bool melanin = p.HasParameter("eumelanin") || p.HasParameter("pheomelanin");
    m.eumelanin = textures.Float(p, "eumelanin", m.sigma_a || reflectance || melanin ? 0 : 1.3f);
    m.pheomelanin = textures.Float(p, "pheomelanin", 0);
    if (m.sigma_a && (reflectance || melanin))
        WarningAt(e.loc, "hair: \"sigma_a\" is given; \"reflectance\" and the melanins are ignored");
    else if (reflectance && melanin)
        WarningAt(e.loc, "hair: \"reflectance\" is given; the melanins are ignored");
    if (!m.sigma_a)
        m.reflectance = reflectance;
    m.eta = textures.Float(p, "eta", 1.55f);
    m.beta_m = textures.Float(p, "beta_m", 0.3f);
    m.beta_n = textures.Float(p, "beta_n", 0.3f);
    m.alpha = textures.Float(p, "alpha", 2);
    return m;
}

}  // namespace

std::optional<Material> CreateMaterial(const SceneEntity &e, const std::string &type,
                                       const RenderOverrides &overrides,
                                       TextureResolver &textures) {
    const ParameterDictionary &p = e.parameters;
    std::optional<Material> material;
    if (type.empty() || type == "none") {
        // pbrt-v4 reads both as "interface", with the same warning.
        WarningAt(e.loc, "Material \"%s\" is deprecated; use \"interface\" instead", type.c_str());
        p.ReportUnused();
        return std::nullopt;
    }
    if (type == "diffuse") {
        material = DiffuseMaterial{textures.GetSpectrumTexture(p, "reflectance", Spectrum(0.5f), SpectrumType::Albedo)};
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
        m.eta = GetEta(p, "eta", 1.5f, textures.Folder());
        Roughness r = GetRoughness(p, textures);
        m.uRoughness = r.u;
        m.vRoughness = r.v;
        m.remapRoughness = p.GetOneBool("remaproughness", true);
        material = m;
    } else if (type == "thindielectric") {
        material = ThinDielectricMaterial{GetEta(p, "eta", 1.5f, textures.Folder())};
    } else if (type == "diffusetransmission") {
        DiffuseTransmissionMaterial m;
        m.reflectance = textures.GetSpectrumTexture(p, "reflectance", Spectrum(0.25f), SpectrumType::Albedo);
        m.transmittance = textures.GetSpectrumTexture(p, "transmittance", Spectrum(0.25f), SpectrumType::Albedo);
        m.scale = p.GetOneFloat("scale", 1);
        material = m;
    } else if (type == "coateddiffuse") {
        CoatedDiffuseMaterial m;
        m.reflectance = textures.GetSpectrumTexture(p, "reflectance", Spectrum(0.5f), SpectrumType::Albedo);
        Roughness r = GetRoughness(p, textures);
        m.uRoughness = r.u;
        m.vRoughness = r.v;
        m.eta = GetEta(p, "eta", 1.5f, textures.Folder());
        m.remapRoughness = p.GetOneBool("remaproughness", true);
        m.layer = GetLayer(p, textures, overrides);
        material = m;
    } else if (type == "coatedconductor") {
        CoatedConductorMaterial m;
        Roughness interface = GetRoughness(p, textures, "interface.");
        m.interfaceURoughness = interface.u;
        m.interfaceVRoughness = interface.v;
        m.interfaceEta = GetEta(p, "interface.eta", 1.5f, textures.Folder());
        GetConductorSpectra(p, textures, "conductor.", &m.conductor);
        Roughness conductor = GetRoughness(p, textures, "conductor.");
        m.conductor.uRoughness = conductor.u;
        m.conductor.vRoughness = conductor.v;
        m.remapRoughness = m.conductor.remapRoughness = p.GetOneBool("remaproughness", true);
        m.layer = GetLayer(p, textures, overrides);
        material = m;
    } else if (type == "fabric") {
        material = CreateFabricMaterial(p, textures, overrides);
    } else if (type == "interface") {
        p.ReportUnused();
        return std::nullopt;
    } else if (type == "hair") {
        material = CreateHairMaterial(e, textures);
    } else if (type == "measured") {
        material = CreateMeasuredMaterial(e, textures.Folder());
    } else if (type == "subsurface") {
        material = CreateSubsurfaceMaterial(e, textures);
    } else {
        throw ParseError(e.loc, "unknown Material \"" + type + "\"");
    }
    SetShadingPerturbation(p, textures, &*material);
    p.ReportUnused();
    return material;
}

}  // namespace pbrt
