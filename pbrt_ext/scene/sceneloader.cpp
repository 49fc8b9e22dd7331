#include "pbrt_ext/scene/sceneloader.h"

#include "pbrt_ext/scene/create.h"
#include "pbrt_ext/scene/scenedescription.h"
#include "pbrt_ext/util/error.h"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace pbrt {

namespace {

// Materials are created when a shape first uses them, so that an unreferenced material (and
// the textures it names) is never loaded. Indices are the builder's; -1 is "interface".
class MaterialResolver {
  public:
    MaterialResolver(const SceneDescription &scene, SceneBuilder &builder,
                     const RenderOverrides &overrides, TextureResolver &textures)
        : scene(scene), builder(builder), overrides(overrides), textures(textures) {}

    int For(const ShapeSceneEntity &shape) {
        if (!shape.materialName.empty())
            return Named(shape.materialName, shape.loc);
        auto [it, inserted] = anonymous.try_emplace(shape.materialIndex, -1);
        if (inserted) {
            const SceneEntity &m = scene.materials[shape.materialIndex];
            it->second = Create(m, m.name, "Material \"" + m.name + "\"");
        }
        return it->second;
    }

  private:
    int Named(const std::string &name, const FileLoc &use) {
        auto [it, inserted] = named.try_emplace(name, -1);
        if (inserted) {
            auto found = scene.namedMaterials.find(name);
            if (found == scene.namedMaterials.end())
                throw ParseError(use, "named material \"" + name + "\" is not defined");
            const SceneEntity &m = found->second;
            std::string type = m.parameters.GetOneString("type", "");
            if (type.empty())
                throw ParseError(m.loc, "named material \"" + name + "\" needs a \"string type\"");
            it->second = Create(m, type, "MakeNamedMaterial \"" + name + "\" (\"" + type + "\")");
        }
        return it->second;
    }

    // A mix names two materials, which only this resolver can turn into indices.
    // what: the directive as the user wrote it, for Scene::materialDescriptions.
    int Create(const SceneEntity &m, const std::string &type, const std::string &what) {
        const std::string description = what + " at " + m.loc.ToString();
        if (type != "mix") {
            std::optional<Material> material = CreateMaterial(m, type, overrides, textures);
            return material ? builder.AddMaterial(std::move(*material), description) : -1;
        }
        const ParameterDictionary &p = m.parameters;
        std::vector<std::string> names = p.GetStringArray("materials");
        if (names.size() != 2)
            throw ParseError(p.Loc("materials") ? *p.Loc("materials") : m.loc,
                             "mix needs \"string materials\" with two named materials");
        MixMaterial mix{{Named(names[0], *p.Loc("materials")), Named(names[1], *p.Loc("materials"))},
                        textures.Float(p, "amount", 0.5f)};
        p.ReportUnused();
        return builder.AddMaterial(std::move(mix), description);
    }

    const SceneDescription &scene;
    SceneBuilder &builder;
    const RenderOverrides &overrides;
    TextureResolver &textures;
    std::map<int, int> anonymous;
    std::map<std::string, int> named;
};

// Media are created when the camera or a shape first names them: an unused MakeNamedMedium
// (and the grid or file it holds) is never loaded. The empty name is vacuum, -1.
class MediumResolver {
  public:
    MediumResolver(const SceneDescription &scene, SceneBuilder &builder, std::string folder)
        : scene(scene), builder(builder), folder(std::move(folder)) {}

    int For(const std::string &name) {
        if (name.empty())
            return -1;
        auto it = indices.find(name);
        if (it == indices.end())
            it = indices.emplace(name, builder.AddMedium(CreateMedium(scene.media.at(name), folder)))
                     .first;
        return it->second;
    }
    MediumInterface For(const ShapeSceneEntity &shape) {
        return MediumInterface(For(shape.insideMedium), For(shape.outsideMedium));
    }

  private:
    const SceneDescription &scene;
    SceneBuilder &builder;
    std::string folder;
    std::map<std::string, int> indices;
};

// An MSE reference image needs a file for the MSE lines, and the other way round. The command
// line gives both or neither, so an incomplete pair comes from an Option directive, whose location
// the error names.
void CheckMSEReferencePair(const SceneDescription &scene, const RenderOverrides &overrides) {
    if (overrides.mseReferenceImage.empty() == overrides.mseReferenceOut.empty()) return;
    const bool hasImage = !overrides.mseReferenceImage.empty();
    const char *given = hasImage ? "msereferenceimage" : "msereferenceout";
    const char *missing = hasImage ? "msereferenceout" : "msereferenceimage";
    const std::string message = fmt::format("\"{}\" needs \"{}\" too", given, missing);
    auto option = scene.options.find(given);
    if (option == scene.options.end()) throw std::invalid_argument(message);
    throw ParseError(option->second.loc, "option " + message);
}

// The command line's overrides with the scene's Option directives applied over them, as pbrt-v4
// applies them (the file wins). The scene description has checked each value's type.
RenderOverrides WithSceneOptions(const SceneDescription &scene, RenderOverrides overrides) {
    for (const auto &[name, option] : scene.options) {
        const std::string &value = option.value;
        if (name == "disablepixeljitter") overrides.disablePixelJitter = value == "true";
        else if (name == "disabletexturefiltering") overrides.disableTextureFiltering = value == "true";
        else if (name == "disablewavelengthjitter") overrides.disableWavelengthJitter = value == "true";
        else if (name == "forcediffuse") overrides.forceDiffuse = value == "true";
        else if (name == "seed") overrides.seed = std::stoi(value);
        else if (name == "wavefront" && value == "true") overrides.integrator = "volpath";
        else if (name == "displacementedgescale") {
            overrides.displacementEdgeScale = std::stof(value);
            if (!(overrides.displacementEdgeScale > 0))
                throw ParseError(option.loc, "option \"displacementedgescale\" is " + value +
                                                 "; expected a positive scale");
        } else if (name == "rendercoordsys") {
            if (value != "camera" && value != "cameraworld" && value != "world")
                throw ParseError(option.loc, "option \"rendercoordsys\" is \"" + value +
                                                 "\"; expected camera, cameraworld or world");
            // pbrt_ext renders in world space: the name changes only pbrt-v4's rounding.
        } else if (name == "msereferenceimage") {
            overrides.mseReferenceImage = value;
        } else if (name == "msereferenceout") {
            overrides.mseReferenceOut = value;
        } else if (name == "pixelstats") {
            overrides.pixelStats = value == "true";
        }
    }
    CheckMSEReferencePair(scene, overrides);
    return overrides;
}

// What turns a shape's names into the builder's indices, and the scale of its displacement's
// edge length.
struct Resolvers {
    MaterialResolver &materials;
    TextureResolver &textures;
    MediumResolver &media;
    Float displacementEdgeScale = 1;
};

// The keyframes of a moving shape or instance, at the scene's TransformTimes.
AnimatedTransform Motion(const SceneDescription &scene, const Transform &start,
                         const Transform &end, const FileLoc &loc) {
    return CreateAnimatedTransform(loc, start, scene.transformStartTime, end,
                                   scene.transformEndTime);
}

// A moving shape (pbrt-v4's AnimatedPrimitive), made in its object space as an object of its
// own: the object's name and the shape's motion, which places it.
struct MovingShape {
    std::string object;
    AnimatedTransform motion;
};

MovingShape AddMovingShapeObject(const SceneDescription &scene, int index, SceneBuilder &builder,
                                 Resolvers &r) {
    const ShapeSceneEntity &shape = scene.shapes[size_t(index)];
    MovingShape moving{fmt::format("<moving shape {}>", index),
                       Motion(scene, shape.worldFromObject, shape.worldFromObjectEnd, shape.loc)};
    ShapeSceneEntity still = shape;
    still.worldFromObject = still.worldFromObjectEnd = Transform();
    builder.SetMediumInterface(r.media.For(shape));
    builder.BeginObject(moving.object);
    AddShape(builder, still, r.materials.For(shape), {}, r.textures, r.displacementEdgeScale);
    builder.EndObject();
    return moving;
}

void AddShapes(const SceneDescription &scene, const std::vector<int> &indices,
               SceneBuilder &builder, Resolvers &r) {
    for (int i : indices) {
        const ShapeSceneEntity &shape = scene.shapes[i];
        if (shape.IsAnimated()) {
            MovingShape moving = AddMovingShapeObject(scene, i, builder, r);
            builder.AddObjectInstance(moving.object, moving.motion);
            continue;
        }
        builder.SetMediumInterface(r.media.For(shape));
        std::optional<AreaLightDescription> emission;
        if (shape.areaLight)
            emission = CreateAreaLight(*shape.areaLight, r.textures.Folder());
        AddShape(builder, shape, r.materials.For(shape), emission, r.textures,
                 r.displacementEdgeScale);
    }
}

// Keyframes of a moving shape inside an instance: the error between them falls as the square of
// the step, and 128 steps (Embree takes at most 129 time steps) keep the product within 1.5e-5
// of its size of pbrt-v4's for two 90-degree turns about different axes
// (tests/util/animatedtransform_test.cpp).
constexpr int kNestedMotionSteps = 128;

// Objects that some instance places, each defined once in the aggregate, then the instances.
// Embree instances one level deep, so a moving shape inside an object is an object of its own,
// which every instance of the outer object places with the product of the two motions.
void AddInstances(const SceneDescription &scene, SceneBuilder &builder, Resolvers &r) {
    std::set<std::string> used;
    for (const InstanceSceneEntity &instance : scene.instances)
        used.insert(instance.name);
    std::map<std::string, std::vector<MovingShape>> movingShapes;
    for (const std::string &name : used) {
        std::vector<int> still;
        for (int i : scene.instanceDefinitions.at(name).shapeIndices) {
            if (scene.shapes[size_t(i)].IsAnimated())
                movingShapes[name].push_back(AddMovingShapeObject(scene, i, builder, r));
            else
                still.push_back(i);
        }
        builder.BeginObject(name);
        AddShapes(scene, still, builder, r);
        builder.EndObject();
    }
    for (const InstanceSceneEntity &instance : scene.instances) {
        AnimatedTransform motion = Motion(scene, instance.worldFromInstance.t[0],
                                          instance.worldFromInstance.t[1], instance.loc);
        builder.AddObjectInstance(instance.name, motion);
        for (const MovingShape &moving : movingShapes[instance.name])
            builder.AddObjectInstance(moving.object,
                                      KeyframedTransform(motion, moving.motion, kNestedMotionSteps));
    }
}

// What an integrator needs of the camera, film and sampler; a ParseError where it lacks it.
void CheckIntegratorFits(const SceneDescription &scene, const IntegratorOptions &integrator,
                         const Camera &camera, const RGBFilm &film, const Sampler &sampler) {
    const std::string name = IntegratorName(integrator.type);
    const IntegratorType type = integrator.type;
    // Paths traced from the lights need the camera's importance, which pbrt-v4 gives the
    // perspective camera only.
    bool fromLights = type == IntegratorType::BDPT || type == IntegratorType::LightPath ||
                      type == IntegratorType::MLT;
    if (fromLights && !camera.CastOrNullptr<PerspectiveCamera>())
        throw ParseError(scene.integrator.loc, "Integrator \"" + name +
                                                   "\" needs a perspective camera, not \"" +
                                                   camera.Name() + "\"");
    // sppm adds each pixel's estimate as RGB: it has no wavelengths for the bands, nor camera
    // samples for the g-buffer; mlt's splats have no camera sample for it either.
    if ((type == IntegratorType::SPPM && (film.Buckets() || film.GBuffer())) ||
        (type == IntegratorType::MLT && film.GBuffer()) ||
        (IsGuided(type) && (film.Buckets() || film.GBuffer())))
        throw ParseError(scene.film.loc, "Film \"" + scene.film.name + "\" needs the radiance of "
                                         "camera samples, which " + name + " does not give: use "
                                         "Film \"rgb\"");
    if (type == IntegratorType::Function && sampler.Get<SobolSampler>())
        throw ParseError(scene.integrator.loc,
                         "the \"function\" integrator needs each pixel's own sample points: use "
                         "Sampler \"paddedsobol\", not \"sobol\" (one sequence over the image)");
}

}  // namespace

std::unique_ptr<Scene> LoadScene(const std::vector<SceneFile> &files,
                                 const RenderOverrides &commandLine) {
    SceneDescription scene = DescribeSceneFiles(files);
    // Relative paths (meshes, images, spectra) are relative to the first file's folder.
    const std::string folder = files.front().text
                                   ? std::filesystem::current_path().string()
                                   : std::filesystem::absolute(files.front().filename).parent_path().string();
    const RenderOverrides overrides = WithSceneOptions(scene, commandLine);

    RGBFilm film = CreateFilm(scene.film, ExposureTime(scene.camera), CreateFilter(scene.filter),
                              overrides);
    Camera camera = CreateCamera(scene.camera, film, folder);
    Sampler sampler = CreateSampler(scene.sampler, film.FullResolution(), overrides);
    std::string lightSampler;
    IntegratorOptions integrator = CreateIntegrator(scene.integrator, overrides, &lightSampler);
    CheckIntegratorFits(scene, integrator, camera, film, sampler);
    SceneBuilder builder(std::move(camera), std::move(film), std::move(sampler));
    builder.SetIntegrator(integrator);
    builder.SetOptions(overrides);
    builder.SetSwitches({overrides.forceDiffuse, !overrides.disablePixelJitter,
                         !overrides.disableWavelengthJitter, !overrides.disableTextureFiltering});
    builder.SetLightSampler(lightSampler);
    TextureResolver textures(scene, folder, overrides.disableImageTextures);
    MaterialResolver materials(scene, builder, overrides, textures);
    MediumResolver media(scene, builder, folder);
    Resolvers resolvers{materials, textures, media, overrides.displacementEdgeScale};
    builder.SetCameraMedium(media.For(scene.camera.medium));

    std::vector<int> worldShapes;
    for (size_t i = 0; i < scene.shapes.size(); ++i)
        if (scene.shapes[i].insideObject.empty())
            worldShapes.push_back(int(i));
    AddShapes(scene, worldShapes, builder, resolvers);
    AddInstances(scene, builder, resolvers);
    if (textures.ReadsFootprint() && !overrides.disableTextureFiltering)
        builder.RequireRayDifferentials();
    for (const LightSceneEntity &light : scene.lights)
        if (std::optional<Light> l = CreateLight(light, folder))
            builder.AddLight(std::move(*l), media.For(light.medium));
    return builder.Build();
}

std::unique_ptr<Scene> LoadScene(const std::string &filename, const RenderOverrides &overrides) {
    return LoadScene(std::vector<SceneFile>{{filename, std::nullopt}}, overrides);
}

}  // namespace pbrt
