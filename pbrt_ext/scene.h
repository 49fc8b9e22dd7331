// The render-ready scene and the builder that makes it (DESIGN.md: description -> builder -> scene).
//
// SceneBuilder is the one API through which scenes are made: the pbrt-v4 parser feeds it, and tests
// call it directly. It owns nothing Embree-specific in its interface; Build() creates the Embree
// aggregate, one area light per emissive primitive, and the light sampler the lights need.
#pragma once

#include "pbrt_ext/cameras/cameras.h"
#include "pbrt_ext/film/film.h"
#include "pbrt_ext/lights/lights.h"
#include "pbrt_ext/lights/lightsamplers.h"
#include "pbrt_ext/materials/materials.h"
#include "pbrt_ext/media/media.h"
#include "pbrt_ext/options.h"
#include "pbrt_ext/samplers/samplers.h"
#include "pbrt_ext/shapes/aggregate.h"
#include "pbrt_ext/shapes/shapes.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace pbrt {

// The light sampler a scene uses: "bvh" (default; pbrt-v4's but for its InfiniteLightChoice),
// "power" or "uniform". Probabilities are those at the receiving point ctx (only the BVH
// sampler's depend on it).
class LightSampler {
  public:
    using Variant = std::variant<BVHLightSampler, PowerLightSampler, UniformLightSampler>;
    template <typename T>
    LightSampler(T sampler) : sampler(std::move(sampler)) {}

    pstd::optional<SampledLight> Sample(const LightSampleContext &ctx, Float u) const {
        return std::visit([&](const auto &s) { return s.Sample(ctx, u); }, sampler);
    }
    Float PMF(const LightSampleContext &ctx, int lightIndex) const {
        return std::visit([&](const auto &s) { return s.PMF(ctx, lightIndex); }, sampler);
    }
    bool NeedsIncompletePDFs() const {
        return std::visit([](const auto &s) { return s.NeedsIncompletePDFs(); }, sampler);
    }

  private:
    Variant sampler;
};

// pbrt-v4's debugging switches (--force-diffuse, --disable-pixel-jitter,
// --disable-wavelength-jitter, --disable-texture-filtering, or the scene's Option directives).
struct RenderSwitches {
    bool forceDiffuse = false;      // every BSDF replaced by DiffuseEquivalent
    bool pixelJitter = true;        // false: pixel and lens centres, mid-shutter, filter weight 1
    bool wavelengthJitter = true;   // false: every sample carries the wavelengths of u = 0.5
    bool textureFiltering = true;   // false: no ray differentials, textures read at a point
};

// A diffuse BSDF with bsdf's directional albedo toward si.wo (pbrt-v4's --force-diffuse), which
// is estimated by a fixed 4 x 4 stratified quadrature, so that it needs no sampler dimensions.
BSDF DiffuseEquivalent(const BSDF &bsdf, const SurfaceInteraction &si);

// Everything a render needs, immutable but for the film that accumulates it.
class Scene {
  public:
    pstd::optional<ShapeIntersection> Intersect(const Ray &ray, Float tMax = Infinity) const {
        return aggregate.Intersect(ray, tMax);
    }
    bool IntersectP(const Ray &ray, Float tMax = Infinity) const {
        return aggregate.IntersectP(ray, tMax);
    }
    // The footprint of a pixel at the hit (pbrt-v4's SurfaceInteraction::ComputeDifferentials):
    // from the ray's differentials, or, for a ray that has none, the camera's approximation.
    void ComputeDifferentials(SurfaceInteraction &si, const RayDifferential &ray) const {
        if (!usesRayDifferentials || si.DifferentialsFrom(ray))
            return;
        Vector3f dpdx, dpdy;
        cameraDifferentials.Approximate_dp_dxy(camera, si.p, si.n, si.time,
                                               sampler.SamplesPerPixel(), &dpdx, &dpdy);
        si.SetDifferentials(dpdx, dpdy);
    }
    // The camera ray of a sample, starting in the camera's medium, with its differentials
    // (scaled by differentialScale) only where some material reads the footprint: a scene
    // without that pays nothing for them.
    pstd::optional<CameraRayDifferential> GenerateCameraRay(const CameraSample &cs,
                                                            Float differentialScale) const {
        pstd::optional<CameraRayDifferential> cr;
        if (!usesRayDifferentials) {
            if (pstd::optional<CameraRay> r = camera.GenerateRay(cs))
                cr = CameraRayDifferential{RayDifferential(r->ray), r->weight};
        } else if ((cr = camera.GenerateRayDifferential(cs))) {
            cr->ray.ScaleDifferentials(differentialScale);
        }
        if (cr)
            cr->ray.medium = cameraMedium;
        return cr;
    }
    // The first surface with a material along a camera ray, in the g-buffer's space (camera or
    // world), with its albedo; none where the ray escapes. A second query of the camera ray,
    // made only for the g-buffer film.
    std::optional<VisibleSurface> FirstVisibleSurface(RayDifferential ray, SampledWavelengths lambda) const;
    // The BSDF at a hit, mixes resolved; none for an interface (a surface that only bounds media).
    // A bump or normal map replaces si's shading frame (Material::GetBSDF): call it once per hit.
    std::optional<BSDF> GetBSDF(SurfaceInteraction &si, SampledWavelengths &lambda) const {
        int index = ResolveMaterial(si);
        if (index < 0) return std::nullopt;
        if (!switches.forceDiffuse) return materials[index].GetBSDF(si, lambda);
        return DiffuseEquivalent(materials[index].GetBSDF(si, lambda), si);
    }
    // The BSSRDF under a hit's surface, mixes resolved as GetBSDF resolves them; none unless its
    // material is a subsurface one.
    std::optional<TabulatedBSSRDF> GetBSSRDF(const SurfaceInteraction &si, SampledWavelengths &lambda) const {
        int index = ResolveMaterial(si);
        if (index < 0) return std::nullopt;
        return materials[index].GetBSSRDF(si, lambda);
    }
    // Whether a material scatters under its surface (volpath then renders the scene).
    bool HasSubsurface() const {
        for (const Material &m : materials)
            if (m.HasSubsurface()) return true;
        return false;
    }
    // The material of a hit with mixes resolved (deterministically, per hit); -1 for none.
    int ResolveMaterial(const SurfaceInteraction &si) const {
        int index = si.materialIndex;
        while (index >= 0)
            if (const MixMaterial *mix = materials[index].AsMix())
                index = mix->Choose(si);
            else
                return index;
        return -1;
    }

    EmbreeAggregate aggregate;
    std::vector<Material> materials;
    std::vector<Light> lights;
    std::vector<int> infiniteLights;  // indices into lights: the ones escaping rays look up
    // Per light, the media around it: where rays leaving it start (an area light's shape's
    // interface; a point or infinite light is outside, in the medium in force at its directive).
    std::vector<MediumInterface> lightMediumInterfaces;
    LightSampler lightSampler;
    Camera camera;
    CameraDifferentials cameraDifferentials;
    // Whether some material reads a hit's footprint (a bump map, a filtered texture): only then
    // are the camera's ray differentials generated and every hit's footprint computed.
    bool usesRayDifferentials = false;
    // Whether the camera or some instance moves: only then does a camera sample draw a time.
    bool hasMotion = false;
    RenderSwitches switches;
    // The command line's options with the scene file's Option directives applied over them (the
    // file wins, as in pbrt-v4's Options): what the command writes besides the image.
    RenderOverrides options;
    // The wavelengths a camera sample carries, from its first dimension u.
    SampledWavelengths SampleWavelengths(Float u) const {
        return film.SampleWavelengths(switches.wavelengthJitter ? u : 0.5f);
    }
    RGBFilm film;
    Sampler sampler;
    IntegratorOptions integratorOptions;
    // Participating media, referred to by index from rays and surfaces; the camera's (-1:
    // vacuum) starts every camera ray.
    std::vector<Medium> media;
    int cameraMedium = -1;
    // Per material, what and where it is in the scene file, for the user (--pixelmaterial).
    std::vector<std::string> materialDescriptions;
};

// Emission of an area light attached to a shape (pbrt-v4's AreaLightSource "diffuse").
struct AreaLightDescription {
    Spectrum L = Spectrum(1.f);
    Float scale = 1;
    bool twoSided = false;
    // pbrt-v4's "power" (> 0: set): each shape's scale is multiplied by power / (pi area (2 if
    // two-sided) (the image's mean luminance, if any)), so that each emitting shape (each
    // triangle of a mesh, as in pbrt-v4) emits it.
    Float power = -1;
    // pbrt-v4's "filename": the emission is this image over the shape's uv instead of L.
    std::shared_ptr<const EmissionImage> image = nullptr;
};

class SceneBuilder {
  public:
    SceneBuilder(Camera camera, RGBFilm film, Sampler sampler);

    const Camera &GetCamera() const { return scene->camera; }
    // Materials are referenced by the index this returns.
    // description: what and where it is in the scene file ("Material \"diffuse\" at f:3:1").
    int AddMaterial(Material material, std::string description = {});

    // Shapes, each with a material (-1: an interface, invisible to shading), optional emission,
    // and an optional alpha texture that cuts the shape out where it is below 1 (pbrt-v4's
    // "alpha"; PrimitiveAttributes::alpha). The emission of a cut-out shape is not masked.
    void AddTriangleMesh(std::shared_ptr<TriangleMesh> mesh, int material,
                         std::optional<AreaLightDescription> emission = {},
                         std::optional<FloatTexture> alpha = {});
    void AddBilinearPatchMesh(std::shared_ptr<BilinearPatchMesh> mesh, int material,
                              std::optional<AreaLightDescription> emission = {},
                              std::optional<FloatTexture> alpha = {});
    void AddSphere(const Sphere &sphere, int material,
                   std::optional<AreaLightDescription> emission = {},
                   std::optional<FloatTexture> alpha = {});
    // Curves neither emit nor take alpha (pbrt-v4 cannot sample them as lights either).
    void AddCurves(std::shared_ptr<CurveMesh> curves, int material,
                   std::optional<FloatTexture> alpha = {});
    void AddCylinder(const Cylinder &cylinder, int material,
                     std::optional<AreaLightDescription> emission = {},
                     std::optional<FloatTexture> alpha = {});
    void AddDisk(const Disk &disk, int material, std::optional<AreaLightDescription> emission = {},
                 std::optional<FloatTexture> alpha = {});

    // Object instancing (pbrt-v4's ObjectBegin/ObjectEnd/ObjectInstance): shapes added between
    // BeginObject and EndObject form a named object, placed by each AddObjectInstance. Objects
    // cannot nest; emission inside an object is dropped with a warning (instances would share
    // one light). Unknown or repeated names throw std::invalid_argument.
    void BeginObject(const std::string &name);
    void EndObject();
    void AddObjectInstance(const std::string &name, const KeyframedTransform &worldFromInstance);
    void AddObjectInstance(const std::string &name, const AnimatedTransform &worldFromInstance) {
        AddObjectInstance(name, KeyframedTransform(worldFromInstance));
    }
    void AddObjectInstance(const std::string &name, const Transform &worldFromInstance) {
        AddObjectInstance(name, AnimatedTransform(worldFromInstance));
    }

    // Lights that are not attached to shapes: point, spot, distant, infinite; medium: the one
    // they are in (-1: vacuum).
    void AddLight(Light light, int medium = -1);

    // Participating media, referred to by the index AddMedium returns. Shapes added after
    // SetMediumInterface bound the media it names (pbrt-v4's MediumInterface directive); the
    // camera medium is where camera rays start.
    int AddMedium(Medium medium);
    void SetMediumInterface(MediumInterface mediumInterface);
    void SetCameraMedium(int medium);

    void SetIntegrator(IntegratorOptions options) { integratorOptions = options; }
    void SetSwitches(RenderSwitches switches) { scene->switches = switches; }
    void SetOptions(RenderOverrides options) { scene->options = std::move(options); }
    // "bvh" (default), "bvh-pbrt-v4" (InfiniteLightChoice::PbrtV4), "power" or "uniform".
    void SetLightSampler(std::string name);

    // Ray differentials are generated when a material's bump map asks for them (Build() sees
    // those) or a texture filters over the pixel's footprint (its creator says so here).
    void RequireRayDifferentials() { scene->usesRayDifferentials = true; }

    // The scene, ready to render. The builder is left empty.
    std::unique_ptr<Scene> Build();

  private:
    // Adds one DiffuseAreaLight per primitive of a shape; returns the index of the first.
    template <typename ShapeFor>
    int AddAreaLights(const AreaLightDescription &emission, int count, ShapeFor shapeFor);

    // The emission to attach to a shape being added, or none inside an object definition.
    std::optional<AreaLightDescription> EmissionOutsideObjects(
        std::optional<AreaLightDescription> emission) const;

    // A sphere, cylinder or disk: one primitive, one area light if it emits; `add` puts it into
    // the aggregate with its attributes.
    template <typename Quadric, typename AddToAggregate>
    void AddQuadric(const Quadric &shape, int material,
                    std::optional<AreaLightDescription> emission,
                    std::optional<FloatTexture> alpha, AddToAggregate add);
    // The attributes of a shape being added with this material and alpha texture.
    PrimitiveAttributes Attributes(int material, std::optional<FloatTexture> alpha) const;
    void CheckMedium(int medium) const;

    std::unique_ptr<Scene> scene;
    MediumInterface currentMediumInterface;
    std::map<std::string, int> objects;  // name -> the aggregate's object id
    std::string currentObject;           // empty outside ObjectBegin/End
    IntegratorOptions integratorOptions;
    std::string lightSamplerName = "bvh";
};

}  // namespace pbrt
