// pbrt-v4's --format and --toply (scene/formatter.h): the printed scene is the same scene. Every
// shipped scene formats to a fixed point, and a formatted scene, meshes moved to PLY files or
// not, renders the image of the original bit for bit.
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/formatter.h"
#include "pbrt_ext/scene/sceneloader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace pbrt;

namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(PBRT_EXT_TEST_DATA_DIR) / "../../scenes";

std::string Format(const std::vector<SceneFile> &files, std::optional<std::string> plyFolder = {}) {
    std::ostringstream out;
    FormattingTarget target(out, std::move(plyFolder));
    ParseFiles(&target, files);
    return out.str();
}

// The image of a small render, every sample deterministic.
Image RenderImage(const std::vector<SceneFile> &files) {
    RenderOverrides o;
    o.quiet = true;
    o.spp = 2;
    o.resolution = Point2i(24, 18);
    std::unique_ptr<Scene> scene = LoadScene(files, o);
    Render(*scene, RenderOptions{1, true});
    return scene->film.GetImage();
}

void ExpectSameImage(const Image &a, const Image &b) {
    ASSERT_EQ(a.Resolution(), b.Resolution());
    for (int y = 0; y < a.Resolution().y; ++y)
        for (int x = 0; x < a.Resolution().x; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(a.GetChannel(Point2i(x, y), c), b.GetChannel(Point2i(x, y), c)) << x << ", " << y;
}

TEST(Format, EveryShippedSceneIsAFixedPoint) {
    int scenes = 0;
    for (const fs::directory_entry &e : fs::directory_iterator(kScenes)) {
        if (e.path().extension() != ".pbrt") continue;
        std::string once = Format({{e.path().string(), std::nullopt}});
        std::string twice = Format({{"<formatted>", once}});
        EXPECT_EQ(once, twice) << e.path();
        ++scenes;
    }
    EXPECT_GT(scenes, 30);
}

TEST(Format, AFormattedSceneRendersTheSameImage) {
    // The Cornell box's Include is inlined; nothing in it names a file.
    const std::string file = (kScenes / "cornell-box.pbrt").string();
    const std::string formatted = Format({{file, std::nullopt}});
    EXPECT_EQ(formatted.find("Include"), std::string::npos);
    ExpectSameImage(RenderImage({{file, std::nullopt}}), RenderImage({{"<formatted>", formatted}}));
}

TEST(Format, StringsKeepTheirEscapes) {
    const std::string scene = "Film \"rgb\" \"string filename\" \"a \\\"quoted\\\" \\\\ name.exr\"\nWorldBegin\n";
    const std::string formatted = Format({{"<scene>", scene}});
    EXPECT_NE(formatted.find("\"a \\\"quoted\\\" \\\\ name.exr\""), std::string::npos) << formatted;
}

TEST(ToPLY, MeshesMoveToPLYFilesAndRenderTheSame) {
    const fs::path dir = fs::temp_directory_path() / ("pbrt_ext_toply_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string scene = R"(LookAt 0 0 4  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Sampler "independent"
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Texture "checks" "spectrum" "checkerboard" "float uscale" 4 "float vscale" 4
Material "diffuse" "texture reflectance" "checks"
Shape "trianglemesh" "point3 P" [-1 -1 0  1 -1 0  1 1 0  -1 1 0.5] "integer indices" [0 1 2 0 2 3]
    "normal N" [0 0 1  0 0.1 1  0.1 0 1  0 0 1] "point2 uv" [0 0 1 0 1 1 0 1.25]
AttributeBegin
    Translate 0.3 0 -1
    Shape "trianglemesh" "point3 P" [-1 -1 0  1 -1 0  0 1 0]
AttributeEnd
)";
    const std::string formatted = Format({{"<scene>", scene}}, dir.string());
    EXPECT_EQ(formatted.find("trianglemesh"), std::string::npos) << formatted;
    EXPECT_NE(formatted.find("\"string filename\" [ \"mesh_00001.ply\" ]"), std::string::npos) << formatted;
    EXPECT_TRUE(fs::exists(dir / "mesh_00002.ply"));
    const fs::path file = dir / "scene.pbrt";
    std::ofstream(file) << formatted;
    ExpectSameImage(RenderImage({{"<scene>", scene}}), RenderImage({{file.string(), std::nullopt}}));
    fs::remove_all(dir);
}

}  // namespace
