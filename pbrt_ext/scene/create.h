// Renderer objects from scene-file entities (pbrt-v4's X::Create functions): each reads its
// entity's parameters with pbrt-v4's names and defaults, warns at the entity's location about
// what this renderer does not do, and leaves unread parameters to ReportUnused.
#pragma once

#include "pbrt_ext/options.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/scene/scenedescription.h"
#include "pbrt_ext/scene/spectra.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace pbrt {

// read(): an image or data file read for a parameter. Its error (std::runtime_error, naming the
// file) is rethrown located at the directive's parameter that named the file.
template <typename Read>
auto ReadFileAt(const FileLoc &loc, Read read) {
    try {
        return read();
    } catch (const ParseError &) {
        throw;  // located already (a memory check at the file)
    } catch (const std::runtime_error &error) {
        throw ParseError(loc, error.what());
    }
}

// A file named in the scene: relative paths are relative to the main scene file's folder (pbrt-v4).
inline std::string ResolvePath(const std::string &folder, const std::string &path) {
    std::filesystem::path p(path);
    return p.is_absolute() ? path : (std::filesystem::path(folder) / p).string();
}

// Scene options (create_options.cpp).
Filter CreateFilter(const SceneEntity &filter);
// exposureTime: the camera's shutter interval, which with the film's ISO sets pbrt-v4's imaging
// ratio.
RGBFilm CreateFilm(const SceneEntity &film, Float exposureTime, Filter filter,
                   const RenderOverrides &overrides);
// folder: the main scene file's, which relative lens and aperture files are in.
Camera CreateCamera(const CameraSceneEntity &camera, const RGBFilm &film, const std::string &folder);
// Keyframes of something that moves (a shape, an instance, the camera); a singular or
// projective keyframe is a ParseError at loc, its message after `what`.
AnimatedTransform CreateAnimatedTransform(const FileLoc &loc, const Transform &start,
                                          Float startTime, const Transform &end, Float endTime,
                                          const std::string &what = "");
// The camera's shutterclose - shutteropen (pbrt-v4's exposure time); throws ParseError unless
// positive.
Float ExposureTime(const CameraSceneEntity &camera);
Sampler CreateSampler(const SceneEntity &sampler, Point2i fullResolution,
                      const RenderOverrides &overrides);
// The integrator's options, and the light sampler's name ("power" or "uniform").
IntegratorOptions CreateIntegrator(const SceneEntity &integrator,
                                       const RenderOverrides &overrides,
                                       std::string *lightSampler);

// A spectrum parameter ("rgb", "blackbody", "spectrum": named, file, samples), with RGB read in
// sRGB as the use `type` asks (pbrt_ext/scene/spectra.h).
Spectrum GetSpectrum(const ParameterDictionary &parameters, const std::string &name,
                     Spectrum defaultValue, SpectrumType type, const std::string &folder);

// Material parameters that may be constants or named textures (create_textures.cpp). A named
// texture is created the first time a material refers to it, and only then: a texture nothing
// uses is never loaded.
class TextureResolver {
  public:
    // averageImages: every image texture is its image's average (--disable-image-textures).
    TextureResolver(const SceneDescription &scene, std::string folder, bool averageImages = false);
    ~TextureResolver();

    FloatTexture Float(const ParameterDictionary &parameters, const std::string &name,
                       pbrt::Float defaultValue);
    SpectrumTexture GetSpectrumTexture(const ParameterDictionary &parameters, const std::string &name,
                                       pbrt::Spectrum defaultValue, SpectrumType type);
    const std::string &Folder() const { return folder; }
    // Whether a texture made so far filters over the pixel's footprint (an image map or a
    // checkerboard): the scene then needs ray differentials.
    bool ReadsFootprint() const { return readsFootprint; }

  private:
    // The texture an entity describes; its named inputs through Float and GetSpectrumTexture.
    FloatTexture MakeFloat(const TransformedSceneEntity &entity);
    SpectrumTexture MakeSpectrum(const TransformedSceneEntity &entity, SpectrumType type);

    struct Cache;
    const SceneDescription &scene;
    std::string folder;
    std::unique_ptr<Cache> cache;
    bool readsFootprint = false;
    bool averageImages = false;
};

// Materials (create_materials.cpp). The material's type is the entity's name, or for a named
// material its "string type". std::nullopt for "interface" (no surface: shapes are invisible to
// shading). Unsupported types warn and become a stated stand-in. "mix" refers to other materials
// and is made by the scene loader's material resolver, not here.
std::optional<Material> CreateMaterial(const SceneEntity &material, const std::string &type,
                                       const RenderOverrides &overrides, TextureResolver &textures);
// The "fabric" material with the checks CreateMaterial applies (also how the fabric fuzz target
// builds exactly the BxDFs a scene file can ask for).
FabricMaterial CreateFabricMaterial(const ParameterDictionary &parameters, TextureResolver &textures,
                                    const RenderOverrides &overrides);

// Lights (create_lights.cpp): point, spot, distant, infinite; std::nullopt (with a warning) for
// types this renderer lacks.
std::optional<Light> CreateLight(const TransformedSceneEntity &light, const std::string &folder);
AreaLightDescription CreateAreaLight(const SceneEntity &areaLight, const std::string &folder);

// Media (create_media.cpp): a MakeNamedMedium entity, placed by its CTM.
Medium CreateMedium(const TransformedSceneEntity &medium, const std::string &folder);

// Shapes (create_shapes.cpp): adds the shape to the builder, or warns and skips types this
// renderer lacks. The alpha parameter (a float or a float texture) comes through `textures`,
// whose folder is also where meshes are looked for. A displaced mesh's "edgelength" is
// multiplied by displacementEdgeScale.
void AddShape(SceneBuilder &builder, const ShapeSceneEntity &shape, int material,
              std::optional<AreaLightDescription> emission, TextureResolver &textures,
              Float displacementEdgeScale);

}  // namespace pbrt
