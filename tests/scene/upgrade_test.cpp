// pbrt-v4's --upgrade (scene/upgrade.h): pbrt-v3's directives come out as pbrt-v4 writes them,
// the shipped pbrt-v3 scene upgrades to a scene that loads, and a pbrt-v4 scene comes out as
// --format prints it.
#include "pbrt_ext/scene/formatter.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

using namespace pbrt;

namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(PBRT_EXT_TEST_DATA_DIR) / "../../scenes";

std::string Reformat(const SceneFile &file, bool upgrade) {
    std::ostringstream out;
    FormattingTarget target(out, std::nullopt, upgrade);
    ParseFiles(&target, {file});
    return out.str();
}

std::string Upgrade(const std::string &text) { return Reformat({"<v3>", text}, true); }

// The upgraded text holds `expected` (whitespace as --format writes it).
void ExpectHas(const std::string &upgraded, const std::string &expected) {
    EXPECT_NE(upgraded.find(expected), std::string::npos) << "no " << expected << " in\n" << upgraded;
}

TEST(Upgrade, CameraFilmSamplerIntegratorAsPbrtV4) {
    std::string v4 = Upgrade(R"(Film "image" "integer xresolution" 16 "float maxsampleluminance" 10 "float scale" 2
PixelFilter "gaussian" "float xwidth" 2 "float alpha" 2
Sampler "lowdiscrepancy" "integer pixelsamples" 4
Integrator "directlighting" "float rrthreshold" 0.5
Camera "environment"
WorldBegin
)");
    ExpectHas(v4, "Film \"rgb\"");
    ExpectHas(v4, "\"float maxcomponentvalue\" [ 10 ]");
    ExpectHas(v4, "\"float iso\" [ 200 ]");
    ExpectHas(v4, "\"float xradius\" [ 2 ]");
    ExpectHas(v4, "\"float sigma\" [ 0.5 ]");
    ExpectHas(v4, "Sampler \"paddedsobol\"");
    ExpectHas(v4, "Integrator \"path\"\n    \"integer maxdepth\" [ 1 ]");
    EXPECT_EQ(v4.find("rrthreshold"), std::string::npos);
    ExpectHas(v4, "Camera \"spherical\"\n    \"string mapping\" [ \"equirectangular\" ]");
}

TEST(Upgrade, LightsFoldTheirScales) {
    std::string v4 = Upgrade(R"(WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5] "rgb scale" [2 2 2] "integer samples" 4
LightSource "infinite" "string mapname" "sky.exr" "rgb L" [3 3 3]
AreaLightSource "area" "blackbody L" [5500 3] "integer nsamples" 2
)");
    ExpectHas(v4, "LightSource \"infinite\"\n    \"rgb L\" [ 0.5 0.5 0.5 ]\n    \"float scale\" [ 2 ]");
    ExpectHas(v4, "\"string filename\" [ \"sky.exr\" ]\n    \"float scale\" [ 3 ]");
    ExpectHas(v4, "AreaLightSource \"diffuse\"\n    \"blackbody L\" [ 5500 ]\n    \"float scale\" [ 3 ]");
    EXPECT_EQ(v4.find("samples"), std::string::npos);
    // A coloured scale has no float equivalent.
    EXPECT_THROW(Upgrade("WorldBegin\nLightSource \"point\" \"rgb scale\" [1 2 3]\n"), ParseError);
}

TEST(Upgrade, MaterialsAsPbrtV4) {
    std::string v4 = Upgrade(R"(WorldBegin
Material "matte" "rgb Kd" [0.5 0.2 0.1] "float sigma" 10
Material "plastic" "rgb Kd" [0.4 0.4 0.4] "rgb Ks" [0 0 0] "float roughness" 0.1
Material "plastic" "rgb Kd" [0.4 0.4 0.4] "rgb Ks" [0.2 0.2 0.2]
Material "glass" "float index" 1.33 "rgb Kr" [1 1 1]
Material "mirror"
Material "uber" "rgb Kd" [0.3 0.3 0.3] "rgb Ks" [0 0 0] "texture bumpmap" "b"
MakeNamedMaterial "a" "string type" "metal"
MakeNamedMaterial "b" "string type" "translucent" "rgb Kd" [0.2 0.3 0.4]
MakeNamedMaterial "m" "string type" "mix" "string namedmaterial1" "a" "string namedmaterial2" "b" "rgb amount" [0.25 0.25 0.25]
Material ""
)");
    ExpectHas(v4, "Material \"diffuse\"\n    \"rgb reflectance\" [ 0.5 0.2 0.1 ]\n");
    EXPECT_EQ(v4.find("sigma"), std::string::npos);
    ExpectHas(v4, "Material \"diffuse\"\n    \"rgb reflectance\" [ 0.4 0.4 0.4 ]\n");  // Ks 0: no coat
    ExpectHas(v4, "Material \"coateddiffuse\"\n    \"rgb reflectance\" [ 0.4 0.4 0.4 ]\n");
    ExpectHas(v4, "Material \"dielectric\"\n    \"float eta\" [ 1.33 ]\n");
    ExpectHas(v4, "Material \"conductor\"\n    \"float roughness\" [ 0 ]\n    \"spectrum eta\" [ \"metal-Ag-eta\" ]");
    ExpectHas(v4, "\"texture displacement\" [ \"b\" ]");
    ExpectHas(v4, "\"string type\" [ \"conductor\" ]");
    ExpectHas(v4, "\"string type\" [ \"diffusetransmission\" ]\n    \"rgb transmittance\" [ 0.2 0.3 0.4 ]");
    // pbrt-v4's amount weighs the second material: the names swap.
    ExpectHas(v4, "\"float amount\" [ 0.25 ]\n    \"string materials\" [ \"b\" \"a\" ]");
    ExpectHas(v4, "Material \"interface\"");
    EXPECT_THROW(Upgrade("WorldBegin\nMaterial \"fourier\"\n"), ParseError);
}

TEST(Upgrade, TexturesAndShapesAsPbrtV4) {
    std::string v4 = Upgrade(R"(WorldBegin
Texture "t" "color" "imagemap" "string filename" "x.png" "bool trilinear" true "bool gamma" false
Texture "s" "color" "scale" "texture tex1" "t" "rgb tex2" [0.5 0.5 0.5]
Shape "trianglemesh" "point P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2] "float uv" [0 0 1 0 0 1]
    "bool discarddegenerateUVs" true
Shape "loopsubdiv" "integer nlevels" 2 "point P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 2]
)");
    ExpectHas(v4, "Texture \"t\" \"spectrum\" \"imagemap\"");
    ExpectHas(v4, "\"string filter\" [ \"trilinear\" ]\n    \"string encoding\" [ \"linear\" ]");
    ExpectHas(v4, "Texture \"s\" \"spectrum\" \"scale\"\n    \"texture tex\" [ \"t\" ]\n    \"float scale\" [ 0.5 ]");
    ExpectHas(v4, "\"point2 uv\" [ 0 0 1 0 0 1 ]");
    EXPECT_EQ(v4.find("discarddegenerateUVs"), std::string::npos);
    ExpectHas(v4, "\"integer levels\" [ 2 ]");
}

TEST(Upgrade, TheShippedPbrtV3SceneUpgradesToAScenePbrtExtLoads) {
    const std::string v3 = (kScenes / "pbrt-v3" / "fabric-spheres.pbrt").string();
    // As it is, it is refused with the hint to upgrade it.
    try {
        LoadScene(v3, RenderOverrides{});
        FAIL() << "a pbrt-v3 scene loaded";
    } catch (const ParseError &e) {
        EXPECT_NE(std::string(e.what()).find("--upgrade"), std::string::npos) << e.what();
    }
    const std::string v4 = Reformat({v3, std::nullopt}, true);
    RenderOverrides o;
    o.quiet = true;
    std::unique_ptr<Scene> scene = LoadScene(std::vector<SceneFile>{{"<upgraded>", v4}}, o);
    EXPECT_EQ(scene->film.FullResolution(), Point2i(320, 180));
    // The area light's sphere has the default diffuse, the floor its matte, then four fabrics.
    EXPECT_EQ(scene->materials.size(), 6u);
}

TEST(Upgrade, APbrtV4SceneComesOutAsFormatPrintsIt) {
    int scenes = 0;
    for (const fs::directory_entry &e : fs::directory_iterator(kScenes)) {
        if (e.path().extension() != ".pbrt") continue;
        SceneFile file{e.path().string(), std::nullopt};
        EXPECT_EQ(Reformat(file, true), Reformat(file, false)) << e.path();
        ++scenes;
    }
    EXPECT_GT(scenes, 30);
}

}  // namespace
