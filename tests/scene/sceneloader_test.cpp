// Scene files to scenes: every scene we ship renders, only what is referenced is created, and bad
// input is reported where it was written.
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/error.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

using namespace pbrt;

namespace {

const std::filesystem::path kScenes = std::filesystem::path(PBRT_EXT_TEST_DATA_DIR) / "../../scenes";

// A scene file in a fresh temporary folder (paths inside are relative to it).
std::string WriteScene(const std::string &name, const std::string &text) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "pbrt_ext_loader_test";
    std::filesystem::create_directories(dir);
    std::filesystem::path file = dir / name;
    std::ofstream(file) << text;
    return file.string();
}

const char *kHeader = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 16 "integer yresolution" 16 "string filename" "out.exr"
Sampler "independent" "integer pixelsamples" 4
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
)";

std::string LoadError(const std::string &file) {
    try {
        LoadScene(file, RenderOverrides{});
    } catch (const ParseError &e) {
        return e.what();
    }
    return "no error";
}

// The BSDF of a scene's material at a hit, for some visible wavelengths. si is a copy: a bump
// or normal map perturbs its shading frame.
BSDF GetBSDF(const Material &m, SurfaceInteraction si) {
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    return m.GetBSDF(si, lambda);
}

RenderOverrides Quick() {
    RenderOverrides o;
    o.spp = 1;
    o.quiet = true;
    return o;
}

// The BSDF where a ray down the z axis meets a unit sphere of the given material, described.
std::string SphereBSDF(const std::string &fileName, const std::string &material,
                       const RenderOverrides &overrides = Quick()) {
    std::string file =
        WriteScene(fileName, std::string(kHeader) + material + "\nShape \"sphere\"\n");
    std::unique_ptr<Scene> scene = LoadScene(file, overrides);
    pstd::optional<ShapeIntersection> hit = scene->Intersect(Ray(Point3f(0, 0, 5), Vector3f(0, 0, -1)));
    if (!hit)
        return "no hit";
    return GetBSDF(scene->materials[0], hit->intr).ToString();
}

// A scene whose first line is `Sampler <sampler>`, lit by a uniform environment.
std::string WriteSamplerScene(const std::string &name, const std::string &sampler) {
    return WriteScene(name, "Sampler " + sampler + R"(
LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
)");
}

}  // namespace

class ShippedScene : public testing::TestWithParam<const char *> {};

TEST_P(ShippedScene, RendersWithoutNaN) {
    Log().quiet = true;
    std::unique_ptr<Scene> scene = LoadScene((kScenes / GetParam()).string(), Quick());
    RenderStatistics stats = Render(*scene, {0, true});
    EXPECT_EQ(stats.discardedSamples, 0);
    double sum = 0;
    for (Point2i p : scene->film.PixelBounds()) {
        RGB rgb = scene->film.GetPixelRGB(p);
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(rgb[c])) << p.x << ", " << p.y;
            sum += rgb[c];
        }
    }
    EXPECT_GT(sum, 0);  // the scene is lit and visible
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene,
                         testing::Values("cornell-box.pbrt", "fabric-furnace.pbrt",
                                         "fabric-cylinder.pbrt", "fabric-showcase.pbrt",
                                         "convergence/cylinder_r0.1.pbrt",
                                         "convergence/cylinder_r0.3.pbrt",
                                         "convergence/cylinder_r0.6.pbrt",
                                         "convergence/cornell_fabric.pbrt",
                                         "convergence/cornell_panel_light.pbrt",
                                         "media-cornell-fog.pbrt", "media-uniformgrid.pbrt",
                                         "media-rgbgrid.pbrt", "media-cloud.pbrt",
                                         "media-nanovdb-smoke.pbrt", "media-fabric-fog.pbrt",
                                         "subdivision.pbrt", "cylinders.pbrt",
                                         "motion-blur.pbrt", "fabric-woven.pbrt",
                                         "hair-fur.pbrt", "fabric-textured.pbrt",
                                         "procedural-textures.pbrt",
                                         "lights-images.pbrt", "portal-skylight.pbrt",
                                         "realistic-camera.pbrt", "spectral-film.pbrt",
                                         "gbuffer-film.pbrt", "displacement.pbrt",
                                         "colorspaces.pbrt", "measured.pbrt",
                                         "subsurface.pbrt", "bump-maps.pbrt",
                                         "cornell-box-simplepath.pbrt",
                                         "cornell-box-simplepath-uniform.pbrt",
                                         "cornell-box-randomwalk.pbrt",
                                         "cornell-box-ambientocclusion.pbrt",
                                         "cornell-box-mlt.pbrt", "caustic-fabric-mlt.pbrt",
                                         "media-cloud-simplevolpath.pbrt", "guiding-slit-fog.pbrt"));

// Every name pbrt-v4 accepts is its own integrator: none is substituted with a warning.
TEST(SceneLoader, EveryPbrtV4IntegratorLoadsWithoutAWarning) {
    for (const char *name : {"path", "volpath", "bdpt", "lightpath", "sppm", "mlt", "simplepath",
                             "simplevolpath", "randomwalk", "ambientocclusion", "function"}) {
        Log().quiet = true;
        int before = Log().warnings;
        std::unique_ptr<Scene> scene = LoadScene(
            WriteScene("integrator.pbrt", "Camera \"perspective\"\nIntegrator \"" + std::string(name) +
                                              "\"\nWorldBegin\nLightSource \"point\"\nShape \"sphere\"\n"),
            Quick());
        EXPECT_EQ(Log().warnings, before) << name;
        EXPECT_STREQ(IntegratorName(scene->integratorOptions.type), name);
    }
}

// Curves of each type with hair, a moving cylinder, a moving spherical camera, a bump map (ray
// differentials), tangents S and a subdivision surface, all in one scene (also a fuzz seed).
TEST(SceneLoader, GeometryFeaturesRenderTogether) {
    Log().quiet = true;
    std::unique_ptr<Scene> scene =
        LoadScene(std::string(PBRT_EXT_TEST_DATA_DIR) + "/scenes/geometry-features.pbrt", Quick());
    EXPECT_TRUE(scene->usesRayDifferentials);
    RenderStatistics stats = Render(*scene, {0, true});
    EXPECT_EQ(stats.discardedSamples, 0);
    double sum = 0;
    for (Point2i p : scene->film.PixelBounds())
        for (int c = 0; c < 3; ++c) {
            Float v = scene->film.GetPixelRGB(p)[c];
            ASSERT_TRUE(std::isfinite(v));
            sum += v;
        }
    EXPECT_GT(sum, 0);
}

TEST(SceneLoader, UnreferencedTexturesAndMaterialsAreNeverLoaded) {
    // The texture and the named material point at files that do not exist; nothing uses them.
    std::string file = WriteScene("unreferenced.pbrt", std::string(kHeader) + R"(
Texture "unused" "spectrum" "imagemap" "string filename" "no-such-image.png"
MakeNamedMaterial "unusedmat" "string type" "diffuse" "texture reflectance" "unused"
Material "diffuse"
Shape "sphere"
)");
    std::unique_ptr<Scene> scene = LoadScene(file, Quick());
    EXPECT_EQ(scene->materials.size(), 1u);
    Render(*scene, {1, true});
}

TEST(SceneLoader, ReferencedMissingTextureIsAnErrorAtItsUse) {
    std::string file = WriteScene("missing.pbrt", std::string(kHeader) + R"(
Material "diffuse" "texture reflectance" "nothing"
Shape "sphere"
)");
    EXPECT_EQ(LoadError(file), file + ":8:20: error: spectrum texture \"nothing\" is not defined");
}

TEST(SceneLoader, FabricParametersReachTheMaterial) {
    std::string bsdf = SphereBSDF("fabric.pbrt", R"(
Material "fabric" "rgb reflectance" [0.9 0.2 0.1] "float roughness" 0.3 "float threadangle" 90
    "float threadelevation" 20 "string sampler" "paper" "string normalization" "unitpeak")");
    EXPECT_NE(bsdf.find("FabricBxDF"), std::string::npos) << bsdf;
    EXPECT_NE(bsdf.find("n: 16"), std::string::npos) << bsdf;  // ceil(1 + 29 * 0.49)
    EXPECT_NE(bsdf.find("normalization: unitpeak"), std::string::npos) << bsdf;
    EXPECT_NE(bsdf.find("sampling: paper"), std::string::npos) << bsdf;
}

// --sampler replaces the scene's Sampler, keeping its count; the scene's other parameters, written
// for its own sampler, are neither applied nor reported unused.
TEST(SceneLoader, CommandLineSamplerOverridesTheFile) {
    std::string file = WriteSamplerScene("sampler.pbrt", R"("halton" "integer pixelsamples" 9
    "string randomization" "owen")");
    RenderOverrides overrides;
    overrides.quiet = true;
    EXPECT_STREQ(LoadScene(file, overrides)->sampler.Name(), "halton");
    for (const char *name : {"independent", "stratified", "sobol", "paddedsobol", "zsobol", "pmj02bn"}) {
        overrides.sampler = name;
        std::unique_ptr<Scene> scene = LoadScene(file, overrides);
        EXPECT_STREQ(scene->sampler.Name(), name);
        EXPECT_EQ(scene->sampler.SamplesPerPixel(), std::string(name) == "zsobol" ? 16 : 9) << name;
    }
}

// Every sampler pbrt-v4 scenes ask for is rendered as asked: no substitution warning.
TEST(SceneLoader, PMJ02bnIsRenderedWithoutSubstitution) {
    std::string file = WriteSamplerScene("pmj02bn.pbrt", R"("pmj02bn" "integer pixelsamples" 64)");
    RenderOverrides overrides;
    overrides.quiet = true;
    int warnings = Log().warnings;
    std::unique_ptr<Scene> scene = LoadScene(file, overrides);
    EXPECT_EQ(Log().warnings, warnings);
    EXPECT_STREQ(scene->sampler.Name(), "pmj02bn");
    EXPECT_EQ(scene->sampler.SamplesPerPixel(), 64);
}

TEST(SceneLoader, CommandLineFabricSamplerOverridesTheFile) {
    RenderOverrides o = Quick();
    o.fabricSampler = FabricSampling::Uniform;
    std::string bsdf = SphereBSDF("fabric2.pbrt", R"(Material "fabric" "string sampler" "paper")", o);
    EXPECT_NE(bsdf.find("sampling: uniform"), std::string::npos) << bsdf;
}

// --layered-estimator reaches both coated materials; without it, their f() is ours.
TEST(SceneLoader, CommandLineLayeredEstimatorReachesCoatedMaterials) {
    RenderOverrides pbrtV4 = Quick();
    pbrtV4.layeredExitMIS = LayeredExitMIS::PbrtV4;
    for (const char *material : {R"(Material "coateddiffuse" "float roughness" 0.3)",
                                 R"(Material "coatedconductor" "float interface.roughness" 0.3)"}) {
        std::string bsdf = SphereBSDF("coated.pbrt", material);
        EXPECT_NE(bsdf.find("exitMIS: inner"), std::string::npos) << bsdf;
        bsdf = SphereBSDF("coated.pbrt", material, pbrtV4);
        EXPECT_NE(bsdf.find("exitMIS: pbrt-v4"), std::string::npos) << bsdf;
    }
}

TEST(SceneLoaderErrors, BadFabricParametersAreReportedWhereWritten) {
    std::string file = WriteScene("badfabric.pbrt", std::string(kHeader) + R"(
Material "fabric" "string normalization" "energy"
Shape "sphere"
)");
    EXPECT_EQ(LoadError(file), file + ":8:19: error: unknown fabric normalization \"energy\": "
                                      "expected paper or unitpeak");
    std::string file2 = WriteScene("badsampler.pbrt", std::string(kHeader) + R"(
Material "fabric" "string sampler" "magic"
Shape "sphere"
)");
    EXPECT_EQ(LoadError(file2), file2 + ":8:19: error: unknown fabric sampler \"magic\": expected "
                                        "uniform, cosine, paper, truncatedsinphi or best");
}

// The film's sensor and the camera's shutter set the imaging ratio (pbrt-v4's PixelSensor): an
// unknown sensor, a negative white balance or an empty shutter interval is an error where written.
TEST(SceneLoaderErrors, BadSensorAndShutterAreReportedWhereWritten) {
    auto scene = [](const std::string &name, const std::string &camera, const std::string &film) {
        return WriteScene(name, "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" " + camera +
                                    "\nFilm \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8 " +
                                    film + "\nWorldBegin\n");
    };
    std::string sensor = scene("badsensor.pbrt", "", R"("string sensor" "canon_eos_999")");
    EXPECT_THAT(LoadError(sensor), testing::StartsWith(sensor + ":3:60: error: unknown sensor "
                                                                "\"canon_eos_999\"; expected one of: "
                                                                "cie1931, canon_eos_100d,"));
    std::string wb = scene("badwb.pbrt", "", R"("float whitebalance" -5)");
    EXPECT_EQ(LoadError(wb), wb + ":3:1: error: PixelSensor: \"whitebalance\" must be a "
                                  "temperature in K (or 0 for none), not -5.000000");
    std::string shutter = scene("badshutter.pbrt", R"("float shutteropen" 1 "float shutterclose" 0.5)", "");
    EXPECT_EQ(LoadError(shutter), shutter + ":2:44: error: the shutter interval -0.5 is not "
                                            "positive; expected \"shutterclose\" after "
                                            "\"shutteropen\"");
}

// Halton's prime bases have no fast Owen scramble (pbrt-v4 refuses it too); an unknown
// randomization is an error where written, naming the ones the sampler has.
TEST(SceneLoaderErrors, BadSamplerRandomizationIsReportedWhereWritten) {
    auto scene = WriteSamplerScene;
    std::string halton = scene("haltonfastowen.pbrt", R"("halton" "string randomization" "fastowen")");
    EXPECT_EQ(LoadError(halton), halton + ":1:18: error: unknown randomization \"fastowen\" for the halton "
                                          "sampler: expected none, permutedigits or owen");
    std::string sobol = scene("sobolbad.pbrt", R"("sobol" "string randomization" "scrambled")");
    EXPECT_EQ(LoadError(sobol), sobol + ":1:17: error: unknown randomization \"scrambled\" for the sobol "
                                        "sampler: expected none, permutedigits, fastowen or owen");
}

TEST(SceneLoaderErrors, UnusedAndUnknownAreErrors) {
    std::string file = WriteScene("unused.pbrt", std::string(kHeader) + R"(
Material "diffuse" "float roughnes" 0.2
Shape "sphere"
)");
    EXPECT_EQ(LoadError(file), file + ":8:20: error: unused parameter \"float roughnes\"");
    std::string file2 = WriteScene("unknown.pbrt", std::string(kHeader) + R"(
Shape "teapot"
)");
    EXPECT_EQ(LoadError(file2), file2 + ":8:1: error: unknown Shape \"teapot\": expected "
                                        "trianglemesh, plymesh, bilinearmesh, loopsubdiv, curve, sphere, disk or "
                                        "cylinder");
}

TEST(SceneLoaderErrors, MissingPlyIsReportedAtItsFilename) {
    std::string file = WriteScene("noply.pbrt", std::string(kHeader) + R"(
Shape "plymesh" "string filename" "absent.ply"
)");
    std::string error = LoadError(file);
    EXPECT_EQ(error.rfind(file + ":8:17: error: cannot open PLY file \"absent.ply\"", 0), 0u)
        << error;
}

TEST(SceneLoader, MixChoosesTheSecondMaterialWithProbabilityAmount) {
    // In a white furnace a diffuse sphere reflects its albedo; with a mix of red (a) and blue (b)
    // at amount 0.25, the red share of the sphere's pixels is 0.75. About 1e4 hashed choices:
    // a standard error of 0.0043; the threshold is 0.02 (4.6 of them).
    std::string file = WriteScene("mix.pbrt", R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 20
Film "rgb" "integer xresolution" 32 "integer yresolution" 32 "string filename" "out.exr"
Sampler "independent" "integer pixelsamples" 16
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
MakeNamedMaterial "a" "string type" "diffuse" "rgb reflectance" [0.8 0 0]
MakeNamedMaterial "b" "string type" "diffuse" "rgb reflectance" [0 0 0.8]
Material "mix" "string materials" ["a" "b"] "float amount" 0.25
Shape "sphere"
)");
    std::unique_ptr<Scene> scene = LoadScene(file, RenderOverrides{});
    Render(*scene, {0, true});
    double red = 0, blue = 0;
    for (Point2i p : scene->film.PixelBounds()) {
        RGB rgb = scene->film.GetPixelRGB(p);
        if (rgb[1] < 0.01f) {  // entirely on the sphere (the background is white)
            red += rgb[0];
            blue += rgb[2];
        }
    }
    ASSERT_GT(red + blue, 0);
    EXPECT_NEAR(red / (red + blue), 0.75, 0.02);
}

TEST(SceneLoader, PlyQuadsBecomePatchesCoveringTheirSquare) {
    // A quad written around its boundary must cover exactly its square (a patch with two
    // corners swapped would be a twisted hourglass that misses points near the edges' middles).
    std::string ply = WriteScene("quad.ply", "ply\nformat ascii 1.0\nelement vertex 4\n"
                                             "property float x\nproperty float y\nproperty float z\n"
                                             "element face 1\nproperty list uchar int vertex_indices\n"
                                             "end_header\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n4 0 1 2 3\n");
    std::string file = WriteScene("quad.pbrt", std::string(kHeader) +
                                                    "Shape \"plymesh\" \"string filename\" \"quad.ply\"\n");
    std::unique_ptr<Scene> scene = LoadScene(file, Quick());
    auto hits = [&](Float x, Float y) {
        return bool(scene->Intersect(Ray(Point3f(x, y, 1), Vector3f(0, 0, -1))));
    };
    for (auto [x, y] : {std::pair{0.9f, 0.1f}, {-0.9f, -0.1f}, {0.1f, 0.9f}, {-0.1f, -0.9f}, {0.f, 0.f}})
        EXPECT_TRUE(hits(x, y)) << x << ", " << y;
    for (auto [x, y] : {std::pair{1.1f, 0.f}, {0.f, -1.1f}})
        EXPECT_FALSE(hits(x, y)) << x << ", " << y;
}

TEST(SceneLoader, LoopSubdivBecomesItsLimitSurfaceInWorldSpace) {
    // The tetrahedron at alternate corners of [-1, 1]^3: a corner's limit point is a/5 at every
    // level (tests/shapes/loopsubdiv_test.cpp), here scaled by 2. Its normal is along the corner's axis.
    std::string file = WriteScene("loop.pbrt", std::string(kHeader) + R"(
Scale 2 2 2
Shape "loopsubdiv" "integer levels" 2 "integer indices" [0 1 2 0 3 1 0 2 3 1 3 2]
    "point3 P" [1 1 1  1 -1 -1  -1 1 -1  -1 -1 1]
)");
    std::unique_ptr<Scene> scene = LoadScene(file, Quick());
    Vector3f axis = Normalize(Vector3f(1, 1, 1));
    pstd::optional<ShapeIntersection> hit = scene->Intersect(Ray(Point3f(0, 0, 0), axis));
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->tHit, 2 * std::sqrt(3.f) / 5, 1e-5f);
    EXPECT_NEAR(AbsDot(Vector3f(hit->intr.shading.n), axis), 1, 1e-5f);
}

TEST(SceneLoader, FabricDiffuseBaseAddsTheEnergyBoundedBaseLobe) {
    std::string file = WriteScene("fabricdiffuse.pbrt", std::string(kHeader) + R"(
Material "fabric" "rgb reflectance" [0.5 0.5 0.5] "float roughness" 0.3 "rgb diffuse" [0.6 0.4 0.2]
Shape "sphere"
)");
    std::unique_ptr<Scene> scene = LoadScene(file, Quick());
    pstd::optional<ShapeIntersection> hit = scene->Intersect(Ray(Point3f(0, 0, 5), Vector3f(0, 0, -1)));
    ASSERT_TRUE(hit);
    std::string bsdf = GetBSDF(scene->materials[0], hit->intr).ToString();
    EXPECT_NE(bsdf.find("FabricDiffuseBxDF"), std::string::npos) << bsdf;
    Render(*scene, {1, true});
}

TEST(SceneLoaderErrors, MalformedCorpusGivesExactLocatedErrors) {
    // tests/data/bad/load_*.pbrt: errors the loader finds, each at the place it was written. Paths
    // in "(looked for ...)" depend on the checkout and are left out of the comparison.
    const std::pair<const char *, const char *> cases[] = {
        {"load_bad_fabric_normalization.pbrt",
         ":3:19: error: unknown fabric normalization \"energy\": expected paper or unitpeak"},
        {"load_missing_image.pbrt", ":3:35: error: cannot open image \"no-such-image.png\""},
        {"load_missing_environment.pbrt", ":3:24: error: cannot open image \"no-such-sky.exr\""},
        // The included file is named as resolved, which depends on the checkout's path.
        {"load_missing_include.pbrt", ":3:1: error: cannot open included file \""},
        {"load_missing_ply.pbrt", ":3:17: error: cannot open PLY file \"no-such-mesh.ply\""},
        {"load_undefined_texture.pbrt", ":3:20: error: spectrum texture \"undefined\" is not defined"},
        {"load_unused_parameter.pbrt", ":3:22: error: unused parameter \"float roughnes\""},
        // Participating media: each fault at the parameter that holds it.
        {"load_unknown_medium_type.pbrt",
         ":3:23: error: unknown medium type \"smoke\"; expected homogeneous, uniformgrid, "
         "rgbgrid, cloud or nanovdb"},
        {"load_unknown_medium_preset.pbrt",
         ":3:52: error: unknown medium preset \"Milk\"; expected one of \"Apple\", "},
        {"load_negative_sigma.pbrt",
         ":3:51: error: rgb (-1, 0.5, 0.5) has a negative component, expected values >= 0"},
        {"load_negative_medium_scale.pbrt",
         ":3:51: error: medium \"scale\" is -2; expected a finite value >= 0"},
        {"load_grid_size_mismatch.pbrt",
         ":4:5: error: grid medium has 5 \"density\" values; expected nx*ny*nz = 8"},
        // The NanoVDB reader's own message follows the resolved file name.
        {"load_missing_nvdb.pbrt", ":3:49: error: "},
        // Curves the bases cannot use; cylinders without area; subdivision control meshes.
        {"load_loopsubdiv_nonmanifold.pbrt",
         ":3:1: error: loopsubdiv: edge 0-1 is used twice in the same direction (triangles 0 "
         "and 1): the mesh must be a consistently oriented manifold"},
        {"load_spherical_mapping.pbrt",
         ":1:20: error: spherical camera \"mapping\" \"fisheye\" is unknown; expected "
         "equalarea or equirectangular"},
        {"load_curve_points.pbrt",
         ":3:1: error: curve: 5 control points; the degree 3 Bézier basis needs 4 + n * 3, n >= 0"},
        {"load_curve_type.pbrt",
         ":3:52: error: curve \"type\" \"tube\" is unknown; expected flat, cylinder or ribbon"},
        {"load_cylinder_radius.pbrt",
         ":3:18: error: cylinder \"radius\" is -1; expected a finite value > 0"},
        {"load_cylinder_heights.pbrt",
         ":3:1: error: cylinder \"zmin\" 1 and \"zmax\" 1: expected two different finite heights"},
        {"load_loopsubdiv_levels.pbrt",
         ":3:20: error: loopsubdiv \"levels\" is -1; expected 0 or more"},
        {"load_corrupt_nvdb.pbrt", ":3:49: error: "},
        // Texture filtering.
        {"load_texture_filter.pbrt",
         ":3:71: error: unknown texture filter \"lanczos\": expected point, bilinear, trilinear or ewa"},
        {"load_texture_maxanisotropy.pbrt", ":3:72: error: \"maxanisotropy\" must be at least 1"},
        {"load_texture_mapping.pbrt",
         ":3:39: error: unknown texture mapping \"cubic\": expected uv, spherical, cylindrical or planar"},
        {"load_texture_type.pbrt", ":3:1: error: unknown float texture \"marble\": expected constant, "},
        {"load_checkerboard_dimension.pbrt", ":3:39: error: checkerboard \"dimension\" is 4; expected 2 or 3"},
        // Lights made from images.
        {"load_goniometric_square.pbrt",
         ":3:27: error: goniometric image is 3 x 2; expected a square equal-area diagram"},
        {"load_projection_filename.pbrt", ":3:1: error: LightSource \"projection\" needs \"string filename\""},
        {"load_missing_emission_image.pbrt", ":3:64: error: cannot open image \"no-such.png\""},
        {"load_portal_rectangle.pbrt",
         ":3:40: error: portal is not a planar rectangle (its corners in order)"},
        // Paths traced from the lights need the camera's importance.
        {"load_bdpt_camera.pbrt",
         ":1:1: error: Integrator \"bdpt\" needs a perspective camera, not \"orthographic\""},
        {"load_sppm_radius.pbrt", ":1:19: error: sppm \"radius\" must be positive"},
        {"load_mlt_camera.pbrt", ":1:1: error: Integrator \"mlt\" needs a perspective camera, not \"orthographic\""},
        // Integrators: pbrt-v4's eleven names, and parameters out of range.
        {"load_integrator_unknown.pbrt",
         ":1:1: error: unknown Integrator \"whitted\": expected path, volpath, bdpt, lightpath, sppm, "
         "mlt, simplepath, simplevolpath, randomwalk, ambientocclusion, function, guidedpath or guidedvolpath"},
        {"load_ao_maxdistance.pbrt", ":1:31: error: ambientocclusion \"maxdistance\" must be positive"},
        {"load_maxdepth_negative.pbrt", ":1:19: error: path \"maxdepth\" must be at least 0"},
        {"load_function_unknown.pbrt",
         ":1:23: error: unknown function \"sine\": expected step, diagonal, disk, checkerboard, "
         "rotatedcheckerboard or gaussian"}};
    for (auto [name, expected] : cases) {
        std::string file = std::string(PBRT_EXT_TEST_DATA_DIR) + "/bad/" + name;
        std::string error = LoadError(file);
        EXPECT_EQ(error.substr(0, file.size() + std::strlen(expected)), file + expected) << error;
    }
    std::string dir = std::string(PBRT_EXT_TEST_DATA_DIR) + "/bad/";
    EXPECT_NE(LoadError(dir + "load_missing_nvdb.pbrt").find("no-such-volume.nvdb: cannot open the file: "),
              std::string::npos);
    EXPECT_NE(LoadError(dir + "load_corrupt_nvdb.pbrt")
                  .find("load_corrupt.nvdb: not a valid NanoVDB file: no NanoVDB magic number where a "
                        "segment starts"),
              std::string::npos);
}


// Media reach the surfaces that bound them, in the world and inside object instances, and the
// camera; a medium nothing names is never created; path and volpath are chosen as pbrt-v4 would.
TEST(SceneLoaderMedia, InterfacesInstancesAndTheCameraGetTheirMedia) {
    std::string file = WriteScene("media.pbrt", R"(LookAt 0 0 5  0 0 0  0 1 0
MakeNamedMedium "air" "string type" "homogeneous" "rgb sigma_s" [0.1 0.1 0.1]
MediumInterface "" "air"
Camera "perspective" "float fov" 30
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
MakeNamedMedium "unused" "string type" "nanovdb" "string filename" "no-such-file.nvdb"
MakeNamedMedium "ink" "string type" "homogeneous" "rgb sigma_a" [1 2 3]
ObjectBegin "drop"
  MediumInterface "ink" "air"
  Material "interface"
  Shape "sphere" "float radius" 0.5
ObjectEnd
AttributeBegin
  Translate 2 0 0
  ObjectInstance "drop"
AttributeEnd
)");
    Log().quiet = true;
    std::unique_ptr<Scene> scene = LoadScene(file, Quick());
    ASSERT_EQ(scene->media.size(), 2u);  // "unused" (a missing file) was never read
    EXPECT_EQ(scene->cameraMedium, 0);   // "air", made first for the camera
    EXPECT_EQ(scene->integratorOptions.type, IntegratorType::VolPath);  // pbrt-v4's default integrator
    pstd::optional<ShapeIntersection> hit =
        scene->Intersect(Ray(Point3f(2, 0, 5), Vector3f(0, 0, -1), 0));
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->intr.p.z, 0.5f, 1e-4f);
    EXPECT_EQ(hit->intr.mediumInterface, MediumInterface(1, 0));  // ink inside, air outside
    EXPECT_EQ(hit->intr.GetMedium(Vector3f(0, 0, -1)), 1);        // into the drop
    EXPECT_EQ(hit->intr.SpawnRay(Vector3f(0, 0, -1)).medium, 1);
    EXPECT_EQ(hit->intr.SpawnRay(Vector3f(0, 0, 1)).medium, 0);
}

TEST(SceneLoaderMedia, SurfacesThatBoundNoMediumKeepTheRaysMedium) {
    std::string file = WriteScene("keep.pbrt", std::string(kHeader) + R"(
Material "diffuse"
Shape "sphere" "float radius" 0.5
)");
    std::unique_ptr<Scene> scene = LoadScene(file, Quick());
    pstd::optional<ShapeIntersection> hit =
        scene->Intersect(Ray(Point3f(0, 0, 5), Vector3f(0, 0, -1), 3));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->intr.mediumInterface, MediumInterface(3));
    EXPECT_TRUE(scene->media.empty());
}

TEST(SceneLoaderLights, SpotLightReadsPbrtV4sConeDeltaAngle) {
    // pbrt-v4's SpotLight::Create reads "conedeltaangle"; "conedelta" is no parameter of it.
    auto spot = [](const std::string &delta) {
        return WriteScene("spot-" + delta + ".pbrt", std::string(kHeader) + R"(
LightSource "spot" "point3 from" [0 0 5] "point3 to" [0 0 0] "float coneangle" 20 "float )" +
                                                         delta + R"(" 4
Shape "sphere"
)");
    };
    EXPECT_NO_THROW(LoadScene(spot("conedeltaangle"), Quick()));
    std::string error = LoadError(spot("conedelta"));
    EXPECT_NE(error.find("unused parameter \"float conedelta\""), std::string::npos) << error;
}
