// The scene description (BasicSceneBuilder): the graphics state each directive sees, the
// entities it records, pbrt-v4's defaults, and the exact text of every structural error.
#include "pbrt_ext/scene/scenedescription.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace pbrt {
namespace {

constexpr Float kTol = 1e-5f;

void ExpectNear(Point3f a, Point3f b) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], kTol) << "component " << i;
}

SceneDescription Describe(const std::string &text) { return DescribeSceneString(text, "s.pbrt"); }

// The ParseError text a scene produces, or "" when it describes fine.
std::string ErrorOf(const std::string &text) {
    try {
        Describe(text);
    } catch (const ParseError &e) {
        return e.what();
    }
    return "";
}

std::string BadFile(const std::string &name) {
    return std::string(PBRT_EXT_TEST_DATA_DIR) + "/bad/" + name;
}

std::string FileErrorOf(const std::string &path) {
    try {
        DescribeSceneFile(path);
    } catch (const ParseError &e) {
        return e.what();
    }
    return "";
}

// Counts the warnings issued while it lives, with their text kept off the test output.
class WarningCounter {
  public:
    WarningCounter() : start(Log().warnings), wasQuiet(Log().quiet) { Log().quiet = true; }
    ~WarningCounter() { Log().quiet = wasQuiet; }
    int Count() const { return Log().warnings - start; }

  private:
    int start;
    bool wasQuiet;
};

// The warnings describing text prints, one per line.
std::string WarningsOf(const std::string &text) {
    testing::internal::CaptureStderr();
    Describe(text);
    return testing::internal::GetCapturedStderr();
}

TEST(SceneDescription, DefaultsArePbrtV4s) {
    SceneDescription s = Describe("WorldBegin");
    EXPECT_EQ(s.camera.name, "perspective");
    EXPECT_EQ(s.film.name, "rgb");
    EXPECT_EQ(s.sampler.name, "zsobol");
    EXPECT_EQ(s.filter.name, "gaussian");
    EXPECT_EQ(s.integrator.name, "volpath");
    EXPECT_EQ(s.accelerator.name, "bvh");
    EXPECT_TRUE(s.camera.cameraFromWorld.t[0].IsIdentity());
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].name, "diffuse");
    EXPECT_TRUE(s.shapes.empty() && s.lights.empty() && s.instances.empty());
    EXPECT_TRUE(s.media.empty());
}

TEST(SceneDescription, OptionsKeepNameParametersAndLocation) {
    SceneDescription s = Describe(R"(
LookAt 0 0 -5  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [-1 1 -1 1]
Film "rgb" "integer xresolution" 64 "string filename" "out.exr"
Sampler "independent" "integer pixelsamples" 4
PixelFilter "box"
Integrator "path" "integer maxdepth" 3
Accelerator "kdtree"
WorldBegin)");
    EXPECT_EQ(s.camera.name, "orthographic");
    EXPECT_EQ(s.camera.loc.ToString(), "s.pbrt:3:1");
    EXPECT_EQ(s.camera.parameters.GetFloatArray("screenwindow").size(), 4u);
    EXPECT_EQ(s.film.parameters.GetOneInt("xresolution", 0), 64);
    EXPECT_EQ(s.film.parameters.GetOneString("filename", ""), "out.exr");
    EXPECT_EQ(s.sampler.name, "independent");
    EXPECT_EQ(s.sampler.parameters.GetOneInt("pixelsamples", 0), 4);
    EXPECT_EQ(s.filter.name, "box");
    EXPECT_EQ(s.integrator.parameters.GetOneInt("maxdepth", 0), 3);
    EXPECT_EQ(s.accelerator.name, "kdtree");
    EXPECT_EQ(s.integrator.loc.ToString(), "s.pbrt:7:1");
    // cameraFromWorld is the CTM at Camera: the eye maps to the camera-space origin.
    ExpectNear(s.camera.cameraFromWorld.t[0](Point3f(0, 0, -5)), Point3f(0, 0, 0));
    ExpectNear(s.camera.cameraFromWorld.t[0](Point3f(0, 0, 0)), Point3f(0, 0, 5));
}

TEST(SceneDescription, WorldBeginResetsTheCTM) {
    SceneDescription s = Describe("Translate 1 2 3\nWorldBegin\nShape \"sphere\"");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_TRUE(s.shapes[0].worldFromObject.IsIdentity());
}

TEST(SceneDescription, TransformsComposeInFileOrder) {
    // pbrt-v4: each directive post-multiplies the CTM, so the last one applies first.
    SceneDescription s = Describe(R"(WorldBegin
Translate 1 0 0
Scale 2 2 2
Rotate 90 0 0 1
Shape "sphere")");
    ExpectNear(s.shapes[0].worldFromObject(Point3f(1, 0, 0)), Point3f(1, 2, 0));
}

TEST(SceneDescription, TransformMatricesAreWrittenByColumns) {
    SceneDescription s = Describe(R"(WorldBegin
Transform [1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1]
Shape "sphere"
ConcatTransform [2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1]
Shape "sphere"
Identity
Shape "sphere")");
    ExpectNear(s.shapes[0].worldFromObject(Point3f(0, 0, 0)), Point3f(5, 6, 7));
    ExpectNear(s.shapes[1].worldFromObject(Point3f(1, 1, 1)), Point3f(7, 8, 9));
    EXPECT_TRUE(s.shapes[2].worldFromObject.IsIdentity());
}

TEST(SceneDescription, AttributeBlocksSaveAndRestoreTheGraphicsState) {
    SceneDescription s = Describe(R"(WorldBegin
Material "conductor"
AttributeBegin
  Translate 0 0 1
  ReverseOrientation
  Material "dielectric"
  AreaLightSource "diffuse" "rgb L" [1 1 1]
  Shape "sphere"
AttributeEnd
Shape "disk")");
    ASSERT_EQ(s.shapes.size(), 2u);
    const ShapeSceneEntity &inside = s.shapes[0], &after = s.shapes[1];
    ExpectNear(inside.worldFromObject(Point3f(0, 0, 0)), Point3f(0, 0, 1));
    EXPECT_TRUE(inside.reverseOrientation);
    EXPECT_EQ(s.materials[inside.materialIndex].name, "dielectric");
    ASSERT_TRUE(inside.areaLight.has_value());
    EXPECT_EQ(inside.areaLight->name, "diffuse");
    EXPECT_EQ(inside.areaLight->loc.ToString(), "s.pbrt:7:3");
    EXPECT_TRUE(inside.areaLight->parameters.GetOneSpectrum("L").has_value());

    EXPECT_TRUE(after.worldFromObject.IsIdentity());
    EXPECT_FALSE(after.reverseOrientation);
    EXPECT_EQ(s.materials[after.materialIndex].name, "conductor");
    EXPECT_FALSE(after.areaLight.has_value());
    EXPECT_EQ(after.name, "disk");
    EXPECT_EQ(after.loc.ToString(), "s.pbrt:10:1");
}

TEST(SceneDescription, MaterialsAreIndexedOrNamedWhicheverCameLast) {
    SceneDescription s = Describe(R"(WorldBegin
Shape "sphere"
MakeNamedMaterial "gold" "string type" "conductor"
NamedMaterial "gold"
Shape "sphere"
Material "diffuse" "rgb reflectance" [0.1 0.2 0.3]
Shape "sphere"
NamedMaterial "gold"
Shape "sphere")");
    ASSERT_EQ(s.shapes.size(), 4u);
    EXPECT_EQ(s.shapes[0].materialIndex, 0);  // pbrt-v4's default diffuse
    EXPECT_EQ(s.shapes[1].materialIndex, -1);
    EXPECT_EQ(s.shapes[1].materialName, "gold");
    EXPECT_EQ(s.shapes[2].materialIndex, 1);
    EXPECT_EQ(s.shapes[2].materialName, "");
    EXPECT_EQ(s.shapes[3].materialName, "gold");
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[1].loc.ToString(), "s.pbrt:6:1");
    ASSERT_EQ(s.namedMaterials.count("gold"), 1u);
    EXPECT_EQ(s.namedMaterials.at("gold").name, "");
    EXPECT_EQ(s.namedMaterials.at("gold").parameters.GetOneString("type", ""), "conductor");
}

TEST(SceneDescription, NamedMaterialMayBeDefinedAfterItsUse) {
    SceneDescription s = Describe(R"(WorldBegin
NamedMaterial "late"
Shape "sphere"
MakeNamedMaterial "late" "string type" "diffuse")");
    EXPECT_EQ(s.shapes[0].materialName, "late");
}

TEST(SceneDescription, TexturesAreKeptByKindWithTheirClassAndPlacement) {
    SceneDescription s = Describe(R"(WorldBegin
Scale 2 2 2
Texture "checks" "spectrum" "checkerboard" "float uscale" 4
Texture "bump" "float" "imagemap" "string filename" "b.png"
Texture "checks" "float" "constant")");
    ASSERT_EQ(s.spectrumTextures.count("checks"), 1u);
    ASSERT_EQ(s.floatTextures.count("bump"), 1u);
    ASSERT_EQ(s.floatTextures.count("checks"), 1u);  // the kinds are separate namespaces
    const TransformedSceneEntity &checks = s.spectrumTextures.at("checks");
    EXPECT_EQ(checks.name, "checkerboard");
    EXPECT_EQ(checks.parameters.GetOneFloat("uscale", 1), 4);
    ExpectNear(checks.worldFromObject(Point3f(1, 1, 1)), Point3f(2, 2, 2));
    EXPECT_EQ(s.floatTextures.at("bump").loc.ToString(), "s.pbrt:4:1");
}

TEST(SceneDescription, LightsCarryTheirPlacement) {
    SceneDescription s = Describe(R"(WorldBegin
Translate 0 4 0
LightSource "point" "rgb I" [1 1 1]
AttributeBegin
  Rotate 90 1 0 0
  LightSource "distant"
AttributeEnd)");
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].name, "point");
    ExpectNear(s.lights[0].worldFromObject(Point3f(0, 0, 0)), Point3f(0, 4, 0));
    EXPECT_EQ(s.lights[1].name, "distant");
    EXPECT_EQ(s.lights[1].loc.ToString(), "s.pbrt:6:3");
}

TEST(SceneDescription, ObjectsListTheirShapesAndInstancesPlaceThem) {
    SceneDescription s = Describe(R"(WorldBegin
Shape "disk"
ObjectBegin "pair"
  Translate 1 0 0
  Shape "sphere"
  Shape "sphere"
ObjectEnd
Shape "disk"
Translate 0 0 3
ObjectInstance "pair"
ObjectInstance "later"
ObjectBegin "later"
ObjectEnd)");
    ASSERT_EQ(s.shapes.size(), 4u);
    EXPECT_EQ(s.shapes[0].insideObject, "");
    EXPECT_EQ(s.shapes[1].insideObject, "pair");
    EXPECT_EQ(s.shapes[2].insideObject, "pair");
    // ObjectEnd restores the CTM that ObjectBegin saw.
    EXPECT_TRUE(s.shapes[3].worldFromObject.IsIdentity());
    EXPECT_EQ(s.shapes[3].insideObject, "");
    const InstanceDefinitionSceneEntity &pair = s.instanceDefinitions.at("pair");
    EXPECT_EQ(pair.loc.ToString(), "s.pbrt:3:1");
    EXPECT_EQ(pair.shapeIndices, (std::vector<int>{1, 2}));
    EXPECT_TRUE(s.instanceDefinitions.at("later").shapeIndices.empty());
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_EQ(s.instances[0].name, "pair");
    EXPECT_EQ(s.instances[0].loc.ToString(), "s.pbrt:10:1");
    ExpectNear(s.instances[0].worldFromInstance.t[0](Point3f(0, 0, 0)), Point3f(0, 0, 3));
    ExpectNear(s.shapes[1].worldFromObject(Point3f(0, 0, 0)), Point3f(1, 0, 0));
}

TEST(SceneDescription, NamedCoordinateSystems) {
    SceneDescription s = Describe(R"(LookAt 0 0 -5  0 0 0  0 1 0
Camera "perspective"
WorldBegin
Translate 1 0 0
CoordinateSystem "mine"
CoordSysTransform "camera"
Shape "sphere"
CoordSysTransform "mine"
Shape "sphere"
CoordSysTransform "world"
Shape "sphere")");
    // "camera" is worldFromCamera: the camera-space origin is the eye.
    ExpectNear(s.shapes[0].worldFromObject(Point3f(0, 0, 0)), Point3f(0, 0, -5));
    ExpectNear(s.shapes[1].worldFromObject(Point3f(0, 0, 0)), Point3f(1, 0, 0));
    EXPECT_TRUE(s.shapes[2].worldFromObject.IsIdentity());
}

TEST(SceneDescription, AttributesAreDefaultsThatNeedNotBeUsed) {
    SceneDescription s = Describe(R"(WorldBegin
AttributeBegin
  Attribute "shape" "float radius" 2 "float zmax" 0.5
  Attribute "shape" "float radius" 3
  Shape "sphere"
  Shape "sphere" "float radius" 7
  Attribute "light" "float scale" 4
  LightSource "point"
  Attribute "material" "float roughness" 0.25
  Material "conductor"
  Attribute "texture" "float uscale" 8
  Texture "t" "float" "checkerboard"
AttributeEnd
Shape "sphere")");
    // A later Attribute replaces an earlier one of the same name; the shape's own wins.
    EXPECT_EQ(s.shapes[0].parameters.GetOneFloat("radius", 1), 3);
    EXPECT_EQ(s.shapes[1].parameters.GetOneFloat("radius", 1), 7);
    EXPECT_EQ(s.lights[0].parameters.GetOneFloat("scale", 1), 4);
    EXPECT_EQ(s.materials[1].parameters.GetOneFloat("roughness", 0), 0.25f);
    EXPECT_EQ(s.floatTextures.at("t").parameters.GetOneFloat("uscale", 1), 8);
    // Attributes end with their block.
    EXPECT_FALSE(s.shapes[2].parameters.HasParameter("radius"));
    // zmax was never read, yet it is no unused-parameter error: it was only a default.
    EXPECT_NO_THROW(s.shapes[0].parameters.ReportUnused());
    EXPECT_NO_THROW(s.shapes[1].parameters.ReportUnused());
}

TEST(SceneDescription, OwnParametersAreStillReportedUnused) {
    SceneDescription s = Describe("WorldBegin\nShape \"sphere\" \"float radiuss\" 2");
    try {
        s.shapes[0].parameters.ReportUnused();
        FAIL() << "expected an unused-parameter error";
    } catch (const ParseError &e) {
        EXPECT_EQ(std::string(e.what()), "s.pbrt:2:16: error: unused parameter \"float radiuss\"");
    }
}

TEST(SceneDescription, OptionsAreValidatedAndStored) {
    SceneDescription s = Describe(R"(Option "bool disablepixeljitter" true
Option "seed" 7
Option "string msereferenceimage" "ref.exr"
Option "disable_texture_filtering" "false"
WorldBegin
Option "float displacementedgescale" 0.5)");
    ASSERT_EQ(s.options.size(), 5u);
    EXPECT_EQ(s.options.at("disablepixeljitter").value, "true");
    EXPECT_EQ(s.options.at("disablepixeljitter").loc.ToString(), "s.pbrt:1:1");
    EXPECT_EQ(s.options.at("seed").value, "7");
    EXPECT_EQ(s.options.at("msereferenceimage").value, "ref.exr");
    EXPECT_EQ(s.options.at("disabletexturefiltering").value, "false");
    EXPECT_EQ(s.options.at("displacementedgescale").value, "0.5");
}

TEST(SceneDescription, OptionNamesIgnoreCaseDashesAndUnderscores) {
    SceneDescription s = Describe("Option \"Pixel-Stats\" true\nTransformTimes 0 1\nWorldBegin");
    ASSERT_EQ(s.options.count("pixelstats"), 1u);
    EXPECT_EQ(s.options.at("pixelstats").value, "true");
}

TEST(SceneDescription, FilesAreDescribedWithTheirPathInEachLocation) {
    std::filesystem::path file = std::filesystem::temp_directory_path() /
                                 ("pbrt_ext_scenedescription_test_" + std::to_string(::getpid()) +
                                  ".pbrt");
    std::ofstream(file) << "Camera \"orthographic\"\nWorldBegin\n  Shape \"sphere\"\n";
    SceneDescription s = DescribeSceneFile(file.string());
    std::filesystem::remove(file);
    EXPECT_EQ(s.camera.name, "orthographic");
    EXPECT_EQ(s.camera.loc.ToString(), file.string() + ":1:1");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].loc.ToString(), file.string() + ":3:3");
}

TEST(SceneDescription, MediaAreNamedPlacedAndAttachedToShapesAndCamera) {
    WarningCounter warnings;
    SceneDescription s = Describe(R"(MediumInterface "" "air"
Camera "perspective"
WorldBegin
Translate 1 2 3
Attribute "medium" "float scale" 2
MakeNamedMedium "fog" "string type" "homogeneous"
MakeNamedMedium "air" "string type" "homogeneous"
MediumInterface "fog" "air"
Shape "sphere")");
    EXPECT_EQ(warnings.Count(), 0);
    ASSERT_EQ(s.media.size(), 2u);
    const TransformedSceneEntity &fog = s.media.at("fog");
    EXPECT_EQ(fog.loc.ToString(), "s.pbrt:6:1");
    EXPECT_EQ(fog.parameters.GetOneFloat("scale", 1), 2);  // the Attribute's default
    EXPECT_EQ(fog.worldFromObject(Point3f(0, 0, 0)), Point3f(1, 2, 3));
    EXPECT_EQ(s.camera.medium, "air");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].insideMedium, "fog");
    EXPECT_EQ(s.shapes[0].outsideMedium, "air");
}

TEST(SceneDescription, UndefinedOrRedefinedMediaAreErrorsAtTheirUse) {
    EXPECT_EQ(ErrorOf(R"(WorldBegin
MediumInterface "smoke" ""
Shape "sphere")"),
              "s.pbrt:2:1: error: medium \"smoke\" is not defined; expected MakeNamedMedium "
              "\"smoke\" in the scene");
    EXPECT_EQ(ErrorOf(R"(WorldBegin
MakeNamedMedium "fog" "string type" "homogeneous"
MakeNamedMedium "fog" "string type" "homogeneous")"),
              "s.pbrt:3:1: error: named medium \"fog\" redefined; first defined at s.pbrt:2:1");
}

// ColorSpace is graphics state: the directives after it carry it (the Film included), and
// AttributeEnd restores the space AttributeBegin saw.
TEST(SceneDescription, ColorSpaceIsGraphicsState) {
    WarningCounter warnings;
    SceneDescription s = Describe(R"(ColorSpace "rec2020"
Film "rgb"
WorldBegin
Material "diffuse"
AttributeBegin
ColorSpace "ACES2065-1"
LightSource "point"
AttributeEnd
Shape "sphere")");
    EXPECT_EQ(warnings.Count(), 0);
    EXPECT_EQ(&s.film.parameters.ColorSpace(), &RGBColorSpace::Rec2020());
    EXPECT_EQ(&s.materials.back().parameters.ColorSpace(), &RGBColorSpace::Rec2020());
    EXPECT_EQ(&s.lights.back().parameters.ColorSpace(), &RGBColorSpace::ACES2065_1());
    EXPECT_EQ(&s.shapes.back().parameters.ColorSpace(), &RGBColorSpace::Rec2020());
    EXPECT_EQ(&Describe("WorldBegin\nMaterial \"diffuse\"").materials.back().parameters.ColorSpace(),
              &RGBColorSpace::sRGB());
    EXPECT_EQ(ErrorOf("ColorSpace \"prophoto\"\nWorldBegin"),
              "s.pbrt:1:1: error: unknown color space \"prophoto\"; expected one of \"srgb\", "
              "\"dci-p3\", \"rec2020\", \"aces2065-1\"");
}

TEST(SceneDescription, ActiveTransformChoosesWhichEndMoves) {
    // killeroo-moving's pattern: each end of the CTM follows only the directives given to it.
    WarningCounter warnings;
    SceneDescription s = Describe(R"(TransformTimes 0.25 0.75
LookAt 0 0 0  0 0 1  0 1 0
ActiveTransform EndTime
Translate 0 0 -1
ActiveTransform All
Camera "perspective"
WorldBegin
ActiveTransform EndTime
Translate 5 0 0
ActiveTransform StartTime
Translate 0 1 0
ActiveTransform All
Translate 0 0 1
Shape "sphere"
AttributeBegin
  ActiveTransform StartTime
AttributeEnd
Shape "sphere"
ObjectBegin "still"
ObjectEnd
ActiveTransform EndTime
Translate 1 0 0
ObjectInstance "still")");
    EXPECT_EQ(warnings.Count(), 0);
    EXPECT_EQ(s.transformStartTime, 0.25f);
    EXPECT_EQ(s.transformEndTime, 0.75f);
    EXPECT_EQ(s.camera.transformStartTime, 0.25f);
    ExpectNear(s.camera.cameraFromWorld.t[1](Point3f(0, 0, 0)), Point3f(0, 0, -1));
    ASSERT_EQ(s.shapes.size(), 2u);
    ExpectNear(s.shapes[0].worldFromObject(Point3f(0, 0, 0)), Point3f(0, 1, 1));
    ExpectNear(s.shapes[0].worldFromObjectEnd(Point3f(0, 0, 0)), Point3f(5, 0, 1));
    EXPECT_TRUE(s.shapes[0].IsAnimated());
    // AttributeEnd restores which end is active along with the rest of the graphics state.
    EXPECT_TRUE(s.shapes[1].IsAnimated());
    ExpectNear(s.instances[0].worldFromInstance.t[1](Point3f(0, 0, 0)), Point3f(6, 0, 1));
    ExpectNear(s.instances[0].worldFromInstance.t[0](Point3f(0, 0, 0)), Point3f(0, 1, 1));
}

TEST(SceneDescription, WhatDoesNotMoveWarnsOncePerKind) {
    WarningCounter warnings;
    SceneDescription s = Describe(R"(WorldBegin
ActiveTransform EndTime
Translate 5 0 0
LightSource "point"
LightSource "point"
AreaLightSource "diffuse"
Shape "sphere"
ObjectBegin "o"
Shape "sphere"
ObjectEnd)");
    // Lights; the moving emitter; inside the object, the area light. A moving shape inside an
    // object moves (each instance places it with both motions).
    EXPECT_EQ(warnings.Count(), 3);
    ExpectNear(s.lights[0].worldFromObject(Point3f(0, 0, 0)), Point3f(0, 0, 0));
    EXPECT_FALSE(s.shapes[0].areaLight.has_value());
    EXPECT_TRUE(s.shapes[0].IsAnimated());
    EXPECT_TRUE(s.shapes[1].IsAnimated());
}

TEST(SceneDescription, AreaLightsInsideObjectsWarnOnce) {
    WarningCounter warnings;
    SceneDescription s = Describe(R"(WorldBegin
AreaLightSource "diffuse"
ObjectBegin "lamp"
Shape "sphere"
Shape "sphere"
ObjectEnd)");
    EXPECT_EQ(warnings.Count(), 1);
    EXPECT_TRUE(s.shapes[0].areaLight.has_value());  // kept: the description is the file's
}

TEST(SceneDescription, WarningsNameWhatIsIgnoredWhere) {
    EXPECT_EQ(WarningsOf("WorldBegin\nActiveTransform EndTime\nTranslate 1 0 0\n"
                         "LightSource \"point\""),
              "s.pbrt:4:1: warning: lights do not move over the shutter interval (as in pbrt-v4); "
              "the start transform is used\n");
    EXPECT_EQ(WarningsOf("WorldBegin\nAreaLightSource \"diffuse\"\nObjectBegin \"lamp\"\n"
                         " Shape \"sphere\"\nObjectEnd"),
              "s.pbrt:4:2: warning: area lights are not supported inside ObjectBegin; instances of "
              "object \"lamp\" will not emit\n");
}

// ---- Errors: exact text, located at the offending directive --------------------------------

struct ErrorCase {
    const char *scene, *error;
};

TEST(SceneDescriptionErrors, ExactMessages) {
    const ErrorCase cases[] = {
        {"WorldBegin\nCamera \"perspective\"",
         "s.pbrt:2:1: error: \"Camera\" is not allowed after WorldBegin; expected it before "
         "WorldBegin"},
        {"TransformTimes 1 0\nWorldBegin",
         "s.pbrt:1:1: error: TransformTimes 1 0: expected finite times with the end not before "
         "the start"},
        {"WorldBegin\nWorldBegin",
         "s.pbrt:2:1: error: \"WorldBegin\" is not allowed after WorldBegin; expected it before "
         "WorldBegin"},
        {"Film \"rgb\"\nShape \"sphere\"",
         "s.pbrt:2:1: error: \"Shape\" is not allowed before WorldBegin; expected it after "
         "WorldBegin"},
        {"AttributeBegin",
         "s.pbrt:1:1: error: \"AttributeBegin\" is not allowed before WorldBegin; expected it "
         "after WorldBegin"},
        {"WorldBegin\nAttributeBegin\nAttributeEnd\n  AttributeEnd",
         "s.pbrt:4:3: error: AttributeEnd without a matching AttributeBegin"},
        {"WorldBegin\nObjectEnd", "s.pbrt:2:1: error: ObjectEnd without a matching ObjectBegin"},
        {"WorldBegin\nObjectBegin \"a\"\nAttributeBegin\nObjectEnd",
         "s.pbrt:4:1: error: ObjectEnd inside the AttributeBegin at s.pbrt:3:1; expected "
         "AttributeEnd first"},
        {"WorldBegin\nAttributeBegin\nObjectBegin \"a\"\nAttributeEnd",
         "s.pbrt:4:1: error: AttributeEnd inside the ObjectBegin at s.pbrt:3:1; expected "
         "ObjectEnd first"},
        {"WorldBegin\nObjectBegin \"a\"\nObjectBegin \"b\"",
         "s.pbrt:3:1: error: ObjectBegin \"b\" inside ObjectBegin \"a\" at s.pbrt:2:1; expected "
         "ObjectEnd first (objects do not nest)"},
        {"WorldBegin\nObjectBegin \"a\"\nObjectEnd\nObjectBegin \"a\"",
         "s.pbrt:4:1: error: object \"a\" redefined; first defined at s.pbrt:2:1"},
        {"WorldBegin\nObjectBegin \"a\"\nObjectInstance \"b\"",
         "s.pbrt:3:1: error: ObjectInstance \"b\" inside ObjectBegin \"a\"; expected "
         "ObjectInstance outside object definitions"},
        {"WorldBegin\nObjectInstance \"ghost\"",
         "s.pbrt:2:1: error: object \"ghost\" is not defined; expected ObjectBegin \"ghost\" in "
         "the scene"},
        {"WorldBegin\nNamedMaterial \"m\"\n  Shape \"sphere\"",
         "s.pbrt:3:3: error: named material \"m\" is not defined; expected MakeNamedMaterial "
         "\"m\" in the scene"},
        {"WorldBegin\nMakeNamedMaterial \"m\"\nMakeNamedMaterial \"m\"",
         "s.pbrt:3:1: error: named material \"m\" redefined; first defined at s.pbrt:2:1"},
        {"WorldBegin\nTexture \"t\" \"float\" \"constant\"\nTexture \"t\" \"float\" \"scale\"",
         "s.pbrt:3:1: error: float texture \"t\" redefined; first defined at s.pbrt:2:1"},
        {"WorldBegin\nTexture \"t\" \"color\" \"constant\"",
         "s.pbrt:2:1: error: texture type \"color\" unknown; expected \"float\" or \"spectrum\""},
        {"WorldBegin\nCoordSysTransform \"nowhere\"",
         "s.pbrt:2:1: error: unknown coordinate system \"nowhere\"; expected \"camera\", "
         "\"world\" or a name given to CoordinateSystem before"},
        {"CoordSysTransform \"camera\"",
         "s.pbrt:1:1: error: unknown coordinate system \"camera\"; expected \"camera\", "
         "\"world\" or a name given to CoordinateSystem before"},
        {"WorldBegin\nAttribute \"camera\" \"float x\" 1",
         "s.pbrt:2:1: error: unknown Attribute target \"camera\"; expected \"shape\", \"light\", "
         "\"material\", \"medium\" or \"texture\""},
        {"Rotate 30 0 0 0",
         "s.pbrt:1:1: error: Rotate about the zero vector; expected a nonzero "
         "axis"},
        {"LookAt 1 2 3  1 2 3  0 1 0",
         "s.pbrt:1:1: error: LookAt: the eye and look-at points coincide"},
        {"Option \"fast\" true",
         "s.pbrt:1:1: error: unknown option \"fast\"; expected one of disablepixeljitter, "
         "disabletexturefiltering, disablewavelengthjitter, displacementedgescale, forcediffuse, "
         "msereferenceimage, msereferenceout, pixelstats, rendercoordsys, seed, wavefront"},
        {"Option \"disablepixeljitter\" 1",
         "s.pbrt:1:1: error: option \"disablepixeljitter\": bad value \"1\"; expected true or "
         "false"},
        {"Option \"seed\" 1.5",
         "s.pbrt:1:1: error: option \"seed\": bad value \"1.5\"; expected an integer"},
        {"Option \"float seed\" 1",
         "s.pbrt:1:1: error: option \"seed\" declared float; expected type integer"},
        {"Option \"seed\" 99999999999",
         "s.pbrt:1:1: error: option \"seed\": bad value \"99999999999\"; expected an integer"},
        {"Option \"displacementedgescale\" inf",
         "s.pbrt:1:1: error: option \"displacementedgescale\": bad value \"inf\"; expected a "
         "float"},
        {"Option \"displacementedgescale\" 0.5x",
         "s.pbrt:1:1: error: option \"displacementedgescale\": bad value \"0.5x\"; expected a "
         "float"},
        {"Option \"displacementedgescale\" \"half\"",
         "s.pbrt:1:1: error: option \"displacementedgescale\": bad value \"half\"; expected a "
         "float"},
        {"WorldBegin\nTransformTimes 0 1",
         "s.pbrt:2:1: error: \"TransformTimes\" is not allowed after WorldBegin; expected it "
         "before WorldBegin"},
        {"Film \"rgb\"",
         "s.pbrt: error: end of input before WorldBegin; expected WorldBegin and "
         "the scene"},
        {"WorldBegin\nAttributeBegin\n AttributeBegin\n AttributeEnd",
         "s.pbrt:2:1: error: AttributeBegin without a matching AttributeEnd"},
        {"WorldBegin\n ObjectBegin \"a\"",
         "s.pbrt:2:2: error: ObjectBegin without a matching ObjectEnd"},
    };
    for (const ErrorCase &c : cases) EXPECT_EQ(ErrorOf(c.scene), c.error) << c.scene;
}

TEST(SceneDescriptionErrors, BadFilesReportTheirLocation) {
    // The file's path starts each message; '@' stands for it inside one.
    const ErrorCase cases[] = {
        {"desc_unmatched_attributeend.pbrt",
         ":9:1: error: AttributeEnd without a matching AttributeBegin"},
        {"desc_undefined_named_material.pbrt",
         ":6:5: error: named material \"velvet\" is not defined; expected MakeNamedMaterial "
         "\"velvet\" in the scene"},
        {"desc_camera_in_world.pbrt",
         ":4:1: error: \"Camera\" is not allowed after WorldBegin; expected it before WorldBegin"},
        {"desc_nested_object.pbrt",
         ":5:3: error: ObjectBegin \"inner\" inside ObjectBegin \"outer\" at @:3:1; "
         "expected ObjectEnd first (objects do not nest)"},
        {"desc_missing_attributeend.pbrt",
         ":4:1: error: AttributeBegin without a matching AttributeEnd"},
        {"desc_no_worldbegin.pbrt",
         ": error: end of input before WorldBegin; expected WorldBegin and the scene"},
        {"desc_undefined_medium.pbrt",
         ":3:1: error: medium \"fog\" is not defined; expected MakeNamedMedium \"fog\" in the "
         "scene"},
    };
    for (const ErrorCase &c : cases) {
        std::string path = BadFile(c.scene), expected = path + c.error;
        if (size_t at = expected.find('@'); at != std::string::npos) expected.replace(at, 1, path);
        EXPECT_EQ(FileErrorOf(path), expected) << c.scene;
    }
}

}  // namespace
}  // namespace pbrt
