#include "pbrt_ext/scene.h"

#include "pbrt_ext/util/log.h"

#include <array>
#include <stdexcept>

namespace pbrt {

SceneBuilder::SceneBuilder(Camera camera, RGBFilm film, Sampler sampler)
    : scene(new Scene{EmbreeAggregate(), {}, {}, {}, {}, LightSampler(UniformLightSampler({})),
                      std::move(camera), {}, false, false, {}, {}, std::move(film), std::move(sampler),
                      {}, {}, -1, {}}) {}

int SceneBuilder::AddMaterial(Material material, std::string description) {
    scene->materials.push_back(std::move(material));
    scene->materialDescriptions.push_back(std::move(description));
    return int(scene->materials.size()) - 1;
}

PrimitiveAttributes SceneBuilder::Attributes(int material,
                                             std::optional<FloatTexture> alpha) const {
    PrimitiveAttributes attributes{material, -1, nullptr, currentMediumInterface};
    if (alpha)
        attributes.alpha = std::make_shared<const FloatTexture>(std::move(*alpha));
    return attributes;
}

template <typename ShapeFor>
int SceneBuilder::AddAreaLights(const AreaLightDescription &emission, int count,
                                ShapeFor shapeFor) {
    int first = int(scene->lights.size());
    for (int i = 0; i < count; ++i) {
        Shape shape = shapeFor(i);
        Float scale = emission.scale;
        if (emission.power > 0) {
            Float k = Pi * shape.Area() * (emission.twoSided ? 2 : 1) *
                      (emission.image ? emission.image->meanLuminance : 1);
            scale *= k > 0 ? emission.power / k : 0;
        }
        scene->lights.push_back(
            DiffuseAreaLight(std::move(shape), emission.L, scale, emission.twoSided, emission.image));
        scene->lightMediumInterfaces.push_back(currentMediumInterface);
    }
    return first;
}

void SceneBuilder::AddTriangleMesh(std::shared_ptr<TriangleMesh> mesh, int material,
                                   std::optional<AreaLightDescription> emission,
                                   std::optional<FloatTexture> alpha) {
    emission = EmissionOutsideObjects(emission);
    PrimitiveAttributes attributes = Attributes(material, std::move(alpha));
    if (emission)
        attributes.areaLightBase =
            AddAreaLights(*emission, mesh->NumTriangles(),
                          [&](int i) { return Shape(Triangle(mesh.get(), i)); });
    scene->aggregate.AddTriangleMesh(std::move(mesh), attributes);
}

void SceneBuilder::AddBilinearPatchMesh(std::shared_ptr<BilinearPatchMesh> mesh, int material,
                                        std::optional<AreaLightDescription> emission,
                                        std::optional<FloatTexture> alpha) {
    emission = EmissionOutsideObjects(emission);
    PrimitiveAttributes attributes = Attributes(material, std::move(alpha));
    if (emission)
        attributes.areaLightBase =
            AddAreaLights(*emission, mesh->NumPatches(),
                          [&](int i) { return Shape(BilinearPatch(mesh.get(), i)); });
    scene->aggregate.AddBilinearPatchMesh(std::move(mesh), attributes);
}

void SceneBuilder::AddCurves(std::shared_ptr<CurveMesh> curves, int material,
                             std::optional<FloatTexture> alpha) {
    scene->aggregate.AddCurves(std::move(curves), Attributes(material, std::move(alpha)));
}

template <typename Quadric, typename AddToAggregate>
void SceneBuilder::AddQuadric(const Quadric &shape, int material,
                              std::optional<AreaLightDescription> emission,
                              std::optional<FloatTexture> alpha, AddToAggregate add) {
    emission = EmissionOutsideObjects(emission);
    PrimitiveAttributes attributes = Attributes(material, std::move(alpha));
    if (emission)
        attributes.areaLightBase = AddAreaLights(*emission, 1, [&](int) { return Shape(shape); });
    add(scene->aggregate, attributes);
}

void SceneBuilder::AddSphere(const Sphere &sphere, int material,
                             std::optional<AreaLightDescription> emission,
                             std::optional<FloatTexture> alpha) {
    AddQuadric(sphere, material, std::move(emission), std::move(alpha),
               [&](EmbreeAggregate &a, PrimitiveAttributes attrs) { a.AddSphere(sphere, attrs); });
}

void SceneBuilder::AddCylinder(const Cylinder &cylinder, int material,
                               std::optional<AreaLightDescription> emission,
                               std::optional<FloatTexture> alpha) {
    AddQuadric(cylinder, material, std::move(emission), std::move(alpha),
               [&](EmbreeAggregate &a, PrimitiveAttributes attrs) {
                   a.AddCylinder(cylinder, attrs);
               });
}

void SceneBuilder::AddDisk(const Disk &disk, int material,
                           std::optional<AreaLightDescription> emission,
                           std::optional<FloatTexture> alpha) {
    AddQuadric(disk, material, std::move(emission), std::move(alpha),
               [&](EmbreeAggregate &a, PrimitiveAttributes attrs) { a.AddDisk(disk, attrs); });
}

std::optional<AreaLightDescription> SceneBuilder::EmissionOutsideObjects(
    std::optional<AreaLightDescription> emission) const {
    if (emission && !currentObject.empty()) {
        Warning("object \"%s\": area lights inside objects are not supported; the shape is "
                "added without emission",
                currentObject.c_str());
        return {};
    }
    return emission;
}

void SceneBuilder::BeginObject(const std::string &name) {
    if (!currentObject.empty())
        throw std::invalid_argument("object \"" + name + "\" begins inside object \"" +
                                    currentObject + "\": objects cannot nest");
    if (objects.count(name))
        throw std::invalid_argument("object \"" + name + "\" is defined twice");
    objects[name] = scene->aggregate.BeginObject(name);
    currentObject = name;
}

void SceneBuilder::EndObject() {
    if (currentObject.empty())
        throw std::invalid_argument("object end without a matching object begin");
    scene->aggregate.EndObject();
    currentObject.clear();
}

void SceneBuilder::AddObjectInstance(const std::string &name,
                                     const KeyframedTransform &worldFromInstance) {
    auto it = objects.find(name);
    if (it == objects.end())
        throw std::invalid_argument("instance of undefined object \"" + name + "\"");
    scene->aggregate.AddInstance(it->second, worldFromInstance);
}

void SceneBuilder::AddLight(Light light, int medium) {
    CheckMedium(medium);
    scene->lights.push_back(std::move(light));
    scene->lightMediumInterfaces.push_back(MediumInterface(medium, medium));
}

int SceneBuilder::AddMedium(Medium medium) {
    scene->media.push_back(std::move(medium));
    return int(scene->media.size()) - 1;
}

void SceneBuilder::CheckMedium(int medium) const {
    if (medium < -1 || medium >= int(scene->media.size()))
        throw std::invalid_argument("medium " + std::to_string(medium) + " was not added");
}

void SceneBuilder::SetMediumInterface(MediumInterface mediumInterface) {
    CheckMedium(mediumInterface.inside);
    CheckMedium(mediumInterface.outside);
    currentMediumInterface = mediumInterface;
}

void SceneBuilder::SetCameraMedium(int medium) {
    CheckMedium(medium);
    scene->cameraMedium = medium;
}

void SceneBuilder::SetLightSampler(std::string name) {
    if (std::optional<std::string> error = LightSamplerNameError(name))
        throw std::invalid_argument(*error);
    lightSamplerName = std::move(name);
}

namespace {

// The 16 stratified sample pairs of the g-buffer's albedo estimate, made once.
struct AlbedoSamples {
    std::array<Float, 16> uc;
    std::array<Point2f, 16> u2;
};

const AlbedoSamples &GetAlbedoSamples() {
    static const AlbedoSamples samples = [] {
        AlbedoSamples s;
        for (int i = 0; i < 16; ++i) {
            s.uc[size_t(i)] = (i * 7 % 16 + 0.5f) / 16;
            s.u2[size_t(i)] = Point2f((i % 4 + 0.5f) / 4, (i / 4 + 0.5f) / 4);
        }
        return s;
    }();
    return samples;
}

}  // namespace

std::optional<VisibleSurface> Scene::FirstVisibleSurface(RayDifferential ray,
                                                         SampledWavelengths lambda) const {
    for (;;) {
        pstd::optional<ShapeIntersection> hit = Intersect(ray);
        if (!hit) return std::nullopt;
        SurfaceInteraction &si = hit->intr;
        ComputeDifferentials(si, ray);
        std::optional<BSDF> bsdf = GetBSDF(si, lambda);
        if (!bsdf) {  // an interface between media: what lies behind it is seen
            ray = si.SpawnRay(ray.d);
            continue;
        }
        // Camera space through the inverse the camera's transform keeps.
        Transform worldFromOutput;
        if (film.GBuffer()->CameraSpace()) worldFromOutput = camera.WorldFromCamera(si.time);
        VisibleSurface v;
        v.p = worldFromOutput.ApplyInverse(si.p);
        v.n = worldFromOutput.ApplyInverse(FaceForward(si.n, si.wo));
        v.ns = worldFromOutput.ApplyInverse(FaceForward(si.shading.n, si.wo));
        v.uv = si.uv;
        v.dpdx = worldFromOutput.ApplyInverse(si.dpdx);
        v.dpdy = worldFromOutput.ApplyInverse(si.dpdy);
        const AlbedoSamples &albedo = GetAlbedoSamples();
        v.albedo = bsdf->rho(si.wo, albedo.uc, albedo.u2);
        return v;
    }
}

BSDF DiffuseEquivalent(const BSDF &bsdf, const SurfaceInteraction &si) {
    constexpr int n = 4;
    std::array<Float, n * n> uc;
    std::array<Point2f, n * n> u2;
    for (int i = 0; i < n * n; ++i) {
        uc[i] = (i + 0.5f) / (n * n);
        u2[i] = Point2f((i % n + 0.5f) / n, (i / n + 0.5f) / n);
    }
    SampledSpectrum r = Clamp(bsdf.rho(si.wo, uc, u2), 0.f, 1.f);
    return BSDF(si.shading.n, si.shading.dpdu, DiffuseBxDF(r));
}

std::unique_ptr<Scene> SceneBuilder::Build() {
    scene->aggregate.Commit();
    scene->hasMotion = scene->camera.IsMoving() || scene->aggregate.HasMotion();
    // Without texture filtering, only bump maps read differentials (and step by pbrt-v4's
    // fallback); no material asks for them.
    for (const Material &m : scene->materials)
        scene->usesRayDifferentials |= m.UsesRayDifferentials() && scene->switches.textureFiltering;
    scene->usesRayDifferentials |= scene->film.GBuffer() != nullptr;  // its dzdx and dzdy
    if (scene->usesRayDifferentials)
        scene->cameraDifferentials =
            CameraDifferentials(scene->camera, scene->film.FullResolution());
    Bounds3f bounds = scene->aggregate.WorldBound();
    for (size_t i = 0; i < scene->lights.size(); ++i) {
        Light &light = scene->lights[i];
        light.Preprocess(bounds);
        if (light.Type() == LightType::Infinite)
            scene->infiniteLights.push_back(int(i));
    }
    // With one light there is nothing to select: the uniform sampler returns it with probability 1
    // without the power sampler's table search.
    if (lightSamplerName == "uniform" || scene->lights.size() <= 1)
        scene->lightSampler = UniformLightSampler(scene->lights);
    else if (lightSamplerName == "power")
        scene->lightSampler = PowerLightSampler(scene->lights);
    else {
        // Without MIS, lights must give complete densities. (volpath and sppm weigh with BSDF
        // sampling whatever the strategy; their infinite lights are then merely chosen more.)
        bool allowIncompletePDF = integratorOptions.strategy == PathStrategy::MIS;
        InfiniteLightChoice choice = lightSamplerName == "bvh-pbrt-v4" ? InfiniteLightChoice::PbrtV4
                                                                        : InfiniteLightChoice::Importance;
        scene->lightSampler = BVHLightSampler(scene->lights, choice, allowIncompletePDF);
    }
    scene->integratorOptions = integratorOptions;
    return std::move(scene);
}

}  // namespace pbrt
