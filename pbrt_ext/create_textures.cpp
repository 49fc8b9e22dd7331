// Textures from scene-file entities, created on first reference (pbrt-v4's texture classes and
// parameters: constant, scale, mix, checkerboard, imagemap; others warn and become constant).
#include "pbrt_ext/create.h"

#include "pbrt_ext/util/error.h"

#include <filesystem>
#include <map>

namespace pbrt {

struct TextureResolver::Cache {
    std::map<std::string, FloatTexture> floats;
    std::map<std::string, SpectrumTexture> spectra;
};

TextureResolver::TextureResolver(const SceneDescription &scene, std::string folder)
    : scene(scene), folder(std::move(folder)), cache(std::make_unique<Cache>()) {}

TextureResolver::~TextureResolver() = default;

namespace {

UVMapping GetMapping(const TransformedSceneEntity &e) {
    const ParameterDictionary &p = e.parameters;
    std::string mapping = p.GetOneString("mapping", "uv");
    if (mapping != "uv")
        WarningAt(*p.Loc("mapping"), "texture mapping \"%s\" is not supported: using \"uv\"",
                  mapping.c_str());
    return UVMapping{p.GetOneFloat("uscale", 1), p.GetOneFloat("vscale", 1),
                     p.GetOneFloat("udelta", 0), p.GetOneFloat("vdelta", 0)};
}

// pbrt-v4's imagemap parameters, for both value types.
template <typename ImageTexture>
ImageTexture CreateImageTexture(const TransformedSceneEntity &e, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    ImageTexture t;
    t.mapping = GetMapping(e);
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty())
        throw ParseError(e.loc, "imagemap needs \"string filename\"");
    std::string path = ResolvePath(folder, filename);
    if (!std::filesystem::is_regular_file(path))
        throw ParseError(*p.Loc("filename"), "cannot open image \"" + filename + "\" (looked for " +
                                                 path + ")");
    std::string encodingName = p.GetOneString("encoding", "sRGB");
    std::optional<ColorEncoding> encoding = ColorEncoding::Get(encodingName);
    if (!encoding)
        throw ParseError(*p.Loc("encoding"), "unknown encoding \"" + encodingName +
                                                 "\": expected sRGB, linear or \"gamma g\"");
    std::string filterName = p.GetOneString("filter", "bilinear");
    std::optional<FilterFunction> filter = ParseFilterFunction(filterName);
    if (!filter)
        throw ParseError(*p.Loc("filter"), "unknown texture filter \"" + filterName +
                                               "\": expected point, bilinear, trilinear or ewa");
    Float maxAnisotropy = p.GetOneFloat("maxanisotropy", 8);
    if (!(maxAnisotropy >= 1))
        throw ParseError(*p.Loc("maxanisotropy"), "\"maxanisotropy\" must be at least 1");
    std::string wrap = p.GetOneString("wrap", "repeat");
    pstd::optional<WrapMode> wrapMode = ParseWrapMode(wrap);
    if (!wrapMode)
        throw ParseError(*p.Loc("wrap"), "unknown wrap mode \"" + wrap +
                                             "\": expected repeat, clamp, black or octahedralsphere");
    t.scale = p.GetOneFloat("scale", 1);
    t.invert = p.GetOneBool("invert", false);
    t.mipmap = ImageTextureCache::GetMIPMap(path, *encoding, *wrapMode,
                                            MIPMapFilterOptions{*filter, maxAnisotropy});
    return t;
}

}  // namespace

FloatTexture TextureResolver::Float(const ParameterDictionary &p, const std::string &name,
                                    pbrt::Float defaultValue) {
    if (!p.HasParameter(name) || p.ParameterType(name) != "texture")
        return FloatTexture(p.GetOneFloat(name, defaultValue));
    std::string texture = p.GetTexture(name);
    if (auto it = cache->floats.find(texture); it != cache->floats.end())
        return it->second;
    auto entity = scene.floatTextures.find(texture);
    if (entity == scene.floatTextures.end())
        throw ParseError(*p.Loc(name), "float texture \"" + texture + "\" is not defined");
    const TransformedSceneEntity &e = entity->second;
    const ParameterDictionary &tp = e.parameters;
    FloatTexture result;
    if (e.name == "constant") {
        result = FloatTexture(tp.GetOneFloat("value", 1));
    } else if (e.name == "scale") {
        result = FloatScaledTexture(Float(tp, "tex", 1), Float(tp, "scale", 1));
    } else if (e.name == "mix") {
        result = FloatMixTexture(Float(tp, "tex1", 0), Float(tp, "tex2", 1), Float(tp, "amount", 0.5f));
    } else if (e.name == "checkerboard") {
        result = FloatCheckerboardTexture(GetMapping(e), Float(tp, "tex1", 1), Float(tp, "tex2", 0));
        readsFootprint = true;
        tp.GetOneInt("dimension", 2);
    } else if (e.name == "imagemap") {
        result = CreateImageTexture<FloatImageTexture>(e, folder);
        readsFootprint = true;
    } else {
        WarningAt(e.loc, "texture \"%s\" is not supported: constant 0.5", e.name.c_str());
        return cache->floats.emplace(texture, FloatTexture(0.5f)).first->second;
    }
    tp.ReportUnused();
    return cache->floats.emplace(texture, std::move(result)).first->second;
}

SpectrumTexture TextureResolver::GetSpectrumTexture(const ParameterDictionary &p,
                                                    const std::string &name,
                                                    pbrt::Spectrum defaultValue, SpectrumType type) {
    if (!p.HasParameter(name) || p.ParameterType(name) != "texture")
        return SpectrumTexture(GetSpectrum(p, name, std::move(defaultValue), type, folder));
    std::string texture = p.GetTexture(name);
    if (auto it = cache->spectra.find(texture); it != cache->spectra.end())
        return it->second;
    auto entity = scene.spectrumTextures.find(texture);
    if (entity == scene.spectrumTextures.end())
        throw ParseError(*p.Loc(name), "spectrum texture \"" + texture + "\" is not defined");
    const TransformedSceneEntity &e = entity->second;
    const ParameterDictionary &tp = e.parameters;
    SpectrumTexture result;
    const pbrt::Spectrum one(1.f), zero(0.f);
    if (e.name == "constant") {
        result = SpectrumTexture(GetSpectrum(tp, "value", one, type, folder));
    } else if (e.name == "scale") {
        result = SpectrumScaledTexture(GetSpectrumTexture(tp, "tex", one, type), Float(tp, "scale", 1));
    } else if (e.name == "mix") {
        result = SpectrumMixTexture(GetSpectrumTexture(tp, "tex1", zero, type),
                                    GetSpectrumTexture(tp, "tex2", one, type), Float(tp, "amount", 0.5f));
    } else if (e.name == "checkerboard") {
        result = SpectrumCheckerboardTexture(GetMapping(e), GetSpectrumTexture(tp, "tex1", one, type),
                                             GetSpectrumTexture(tp, "tex2", zero, type));
        readsFootprint = true;
        tp.GetOneInt("dimension", 2);
    } else if (e.name == "imagemap") {
        SpectrumImageTexture t = CreateImageTexture<SpectrumImageTexture>(e, folder);
        t.type = type;
        result = std::move(t);
        readsFootprint = true;
    } else {
        WarningAt(e.loc, "texture \"%s\" is not supported: constant 0.5", e.name.c_str());
        return cache->spectra.emplace(texture, SpectrumTexture(pbrt::Spectrum(0.5f))).first->second;
    }
    tp.ReportUnused();
    return cache->spectra.emplace(texture, std::move(result)).first->second;
}

}  // namespace pbrt
