// Textures from scene-file entities, created on first reference (pbrt-v4's texture classes and
// parameters, their mappings in the CTM of the Texture directive). "ptex" warns and becomes a
// constant 0.5: Debian packages no Ptex library.
#include "pbrt_ext/scene/create.h"

#include "pbrt_ext/util/error.h"

#include <filesystem>
#include <map>
#include <type_traits>

namespace pbrt {

struct TextureResolver::Cache {
    std::map<std::string, FloatTexture> floats;
    std::map<std::string, SpectrumTexture> spectra;
};

TextureResolver::TextureResolver(const SceneDescription &scene, std::string folder,
                                 bool averageImages)
    : scene(scene), folder(std::move(folder)), cache(std::make_unique<Cache>()),
      averageImages(averageImages) {}

TextureResolver::~TextureResolver() = default;

namespace {

// Where a parameter was written, or the directive when it was not.
const FileLoc &LocOf(const TransformedSceneEntity &e, const std::string &name) {
    const FileLoc *loc = e.parameters.Loc(name);
    return loc ? *loc : e.loc;
}

TextureMapping2D GetMapping(const TransformedSceneEntity &e) {
    const ParameterDictionary &p = e.parameters;
    std::string mapping = p.GetOneString("mapping", "uv");
    if (mapping == "uv")
        return UVMapping{p.GetOneFloat("uscale", 1), p.GetOneFloat("vscale", 1),
                         p.GetOneFloat("udelta", 0), p.GetOneFloat("vdelta", 0)};
    if (mapping == "spherical") return SphericalMapping{e.worldFromObject};
    if (mapping == "cylindrical") return CylindricalMapping{e.worldFromObject};
    if (mapping == "planar")
        return PlanarMapping{e.worldFromObject, p.GetOneVector3f("v1", Vector3f(1, 0, 0)),
                             p.GetOneVector3f("v2", Vector3f(0, 1, 0)), p.GetOneFloat("udelta", 0),
                             p.GetOneFloat("vdelta", 0)};
    throw ParseError(LocOf(e, "mapping"), "unknown texture mapping \"" + mapping +
                                              "\": expected uv, spherical, cylindrical or planar");
}

// A checkerboard's mapping: 2D by default, texture space for "dimension" 3.
std::variant<TextureMapping2D, TextureMapping3D> GetCheckerboardMapping(const TransformedSceneEntity &e) {
    int dimension = e.parameters.GetOneInt("dimension", 2);
    if (dimension == 3) return TextureMapping3D{e.worldFromObject};
    if (dimension != 2)
        throw ParseError(LocOf(e, "dimension"), "checkerboard \"dimension\" is " +
                                                    std::to_string(dimension) + "; expected 2 or 3");
    return GetMapping(e);
}

// "octaves" of noise, at least 0 (pbrt-v4 sums none for fewer).
int GetOctaves(const TransformedSceneEntity &e) {
    int octaves = e.parameters.GetOneInt("octaves", 8);
    if (octaves < 0 || octaves > 64)
        throw ParseError(LocOf(e, "octaves"), "\"octaves\" is " + std::to_string(octaves) +
                                                  "; expected 0 to 64");
    return octaves;
}

// The unit vector "dir" in world space.
Vector3f GetDirection(const TransformedSceneEntity &e) {
    Vector3f dir = e.worldFromObject(e.parameters.GetOneVector3f("dir", Vector3f(0, 1, 0)));
    if (!(LengthSquared(dir) > 0) || !IsFinite(LengthSquared(dir)))
        throw ParseError(LocOf(e, "dir"), "directionmix \"dir\" must be a finite nonzero vector");
    return Normalize(dir);
}

[[noreturn]] void UnknownTexture(const TransformedSceneEntity &e, const char *kind, const char *expected) {
    throw ParseError(e.loc, std::string("unknown ") + kind + " texture \"" + e.name + "\": expected " + expected);
}

// pbrt-v4's imagemap parameters, for both value types.
template <typename ImageTexture>
ImageTexture CreateImageTexture(const TransformedSceneEntity &e, const std::string &folder,
                                bool averageOnly) {
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
    ImageChannels channels =
        std::is_same_v<ImageTexture, FloatImageTexture> ? ImageChannels::AlphaOfRGBA : ImageChannels::RGB;
    t.mipmap = ReadFileAt(LocOf(e, "filename"), [&] {
        return ImageTextureCache::GetMIPMap(
            path, *encoding, *wrapMode, MIPMapFilterOptions{*filter, maxAnisotropy, averageOnly},
            channels);
    });
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
    return cache->floats.emplace(texture, MakeFloat(entity->second)).first->second;
}

FloatTexture TextureResolver::MakeFloat(const TransformedSceneEntity &e) {
    const ParameterDictionary &tp = e.parameters;
    // The textures that read the pixel's footprint: the scene then needs ray differentials.
    bool filtered = e.name == "checkerboard" || e.name == "imagemap" || e.name == "fbm" ||
                    e.name == "wrinkled" || e.name == "windy";
    readsFootprint |= filtered;
    FloatTexture result;
    if (e.name == "constant") {
        result = FloatTexture(tp.GetOneFloat("value", 1));
    } else if (e.name == "scale") {
        result = FloatScaledTexture(Float(tp, "tex", 1), Float(tp, "scale", 1));
    } else if (e.name == "mix") {
        result = FloatMixTexture(Float(tp, "tex1", 0), Float(tp, "tex2", 1), Float(tp, "amount", 0.5f));
    } else if (e.name == "directionmix") {
        result = FloatDirectionMixTexture(Float(tp, "tex1", 0), Float(tp, "tex2", 1), GetDirection(e));
    } else if (e.name == "checkerboard") {
        result = FloatCheckerboardTexture(GetCheckerboardMapping(e), Float(tp, "tex1", 1), Float(tp, "tex2", 0));
    } else if (e.name == "dots") {
        // pbrt (v2 to v4) hands "inside" to the area around the dots and "outside" to the dots;
        // scenes are written for that.
        result = FloatDotsTexture(GetMapping(e), Float(tp, "inside", 1), Float(tp, "outside", 0));
    } else if (e.name == "bilerp") {
        result = FloatBilerpTexture{GetMapping(e), tp.GetOneFloat("v00", 0), tp.GetOneFloat("v01", 1),
                                    tp.GetOneFloat("v10", 0), tp.GetOneFloat("v11", 1)};
    } else if (e.name == "imagemap") {
        result = CreateImageTexture<FloatImageTexture>(e, folder, averageImages);
    } else if (e.name == "fbm") {
        result = FBmTexture{TextureMapping3D{e.worldFromObject}, GetOctaves(e), tp.GetOneFloat("roughness", .5f)};
    } else if (e.name == "wrinkled") {
        result = WrinkledTexture{TextureMapping3D{e.worldFromObject}, GetOctaves(e), tp.GetOneFloat("roughness", .5f)};
    } else if (e.name == "windy") {
        result = WindyTexture{TextureMapping3D{e.worldFromObject}};
    } else if (e.name == "ptex") {
        WarningAt(e.loc, "texture \"ptex\" is not supported (Debian packages no Ptex library): constant 0.5");
        return FloatTexture(0.5f);
    } else {
        UnknownTexture(e, "float", "constant, scale, mix, directionmix, checkerboard, dots, bilerp, "
                                   "imagemap, fbm, wrinkled, windy or ptex");
    }
    tp.ReportUnused();
    return result;
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
    return cache->spectra.emplace(texture, MakeSpectrum(entity->second, type)).first->second;
}

SpectrumTexture TextureResolver::MakeSpectrum(const TransformedSceneEntity &e, SpectrumType type) {
    const ParameterDictionary &tp = e.parameters;
    bool filtered = e.name == "checkerboard" || e.name == "imagemap" || e.name == "marble";
    readsFootprint |= filtered;
    const pbrt::Spectrum one(1.f), zero(0.f);
    auto spectrum = [&](const char *name, const pbrt::Spectrum &def) {
        return GetSpectrumTexture(tp, name, def, type);
    };
    SpectrumTexture result;
    if (e.name == "constant") {
        result = SpectrumTexture(GetSpectrum(tp, "value", one, type, folder));
    } else if (e.name == "scale") {
        result = SpectrumScaledTexture(spectrum("tex", one), Float(tp, "scale", 1));
    } else if (e.name == "mix") {
        result = SpectrumMixTexture(spectrum("tex1", zero), spectrum("tex2", one), Float(tp, "amount", 0.5f));
    } else if (e.name == "directionmix") {
        result = SpectrumDirectionMixTexture(spectrum("tex1", zero), spectrum("tex2", one), GetDirection(e));
    } else if (e.name == "checkerboard") {
        result = SpectrumCheckerboardTexture(GetCheckerboardMapping(e), spectrum("tex1", one), spectrum("tex2", zero));
    } else if (e.name == "dots") {
        result = SpectrumDotsTexture(GetMapping(e), spectrum("inside", one), spectrum("outside", zero));  // as above
    } else if (e.name == "bilerp") {
        result = SpectrumBilerpTexture{GetMapping(e), GetSpectrum(tp, "v00", zero, type, folder),
                                       GetSpectrum(tp, "v01", one, type, folder),
                                       GetSpectrum(tp, "v10", zero, type, folder),
                                       GetSpectrum(tp, "v11", one, type, folder)};
    } else if (e.name == "imagemap") {
        SpectrumImageTexture t = CreateImageTexture<SpectrumImageTexture>(e, folder, averageImages);
        t.type = type;
        result = std::move(t);
    } else if (e.name == "marble") {
        result = MarbleTexture{TextureMapping3D{e.worldFromObject}, GetOctaves(e), tp.GetOneFloat("roughness", .5f),
                               tp.GetOneFloat("scale", 1), tp.GetOneFloat("variation", .2f)};
    } else if (e.name == "ptex") {
        WarningAt(e.loc, "texture \"ptex\" is not supported (Debian packages no Ptex library): constant 0.5");
        return SpectrumTexture(pbrt::Spectrum(0.5f));
    } else {
        UnknownTexture(e, "spectrum", "constant, scale, mix, directionmix, checkerboard, dots, bilerp, "
                                      "imagemap, marble or ptex");
    }
    tp.ReportUnused();
    return result;
}

}  // namespace pbrt
