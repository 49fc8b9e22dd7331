// pbrt-v4's g-buffer film: a plane facing the camera 3 units away gives P.z = 3 and N toward the
// camera in camera space, its world position in world space, flat depth slopes, its (u, v) and
// the diffuse albedo; pixels that see only the sky keep zeros; the RGB is the rgb film's bit for
// bit (the g-buffer takes no sample dimension); bad parameters are errors at the Film.
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/error.h"

#include "tests/support/scenefolder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace pbrt {
namespace {

// One folder per test: ctest runs the cases as parallel processes.
std::filesystem::path Folder() {
    return TestFolder(std::string("pbrt_ext_gbufferfilm_test_") +
                      testing::UnitTest::GetInstance()->current_test_info()->name());
}

// A 0.5-grey diffuse square at world z = 5 (x, y in [-1, 1], uv over it), seen from z = 2 down
// +z; 16x16 pixels at fov 60 see 3.46 units across, so the square fills the middle.
std::string WriteScene(const std::string &film, const std::string &rest = "") {
    std::filesystem::path scene = Folder() / "scene.pbrt";
    std::ofstream(scene) << "LookAt 0 0 2  0 0 5  0 1 0\nCamera \"perspective\" \"float fov\" 60\n"
                         << film << "\n" << rest << "\nSampler \"independent\" \"integer pixelsamples\" 32\n"
                         << "WorldBegin\nLightSource \"infinite\" \"rgb L\" [1 1 1]\n"
                         << "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
                         << "Shape \"bilinearmesh\" \"point3 P\" [-1 -1 5  1 -1 5  -1 1 5  1 1 5]\n"
                         << "  \"integer indices\" [0 1 2 3] \"point2 uv\" [0 0 1 0 0 1 1 1]\n";
    return scene.string();
}

EXRChannels RenderFilm(const std::string &film) {
    std::string out = (Folder() / "out.exr").string();
    std::unique_ptr<Scene> scene = LoadScene(WriteScene(film + " \"string filename\" \"" + out + "\""),
                                             RenderOverrides{});
    RenderOptions options;
    options.quiet = true;
    Render(*scene, options);
    scene->film.WriteImage(ImageMetadata());
    return ReadEXRChannels(out);
}

const char *kFilm = "Film \"gbuffer\" \"integer xresolution\" 16 \"integer yresolution\" 16";

TEST(GBufferFilm, APlaneFacingTheCameraInCameraSpace) {
    EXRChannels g = RenderFilm(kFilm);
    const auto &c = g.channels;
    for (const char *name : {"Albedo.R", "P.X", "dzdx", "N.Z", "Ns.Z", "u", "v", "Variance.G",
                             "RelativeVariance.B"})
        EXPECT_TRUE(c.count(name)) << name;
    size_t centre = 8 * 16 + 8, corner = 0;  // by the square's middle, and sky
    // The mean over the middle 6x6 pixels (32 samples each), centred on the square.
    auto middle = [&](const char *name) {
        double sum = 0;
        for (int y = 5; y < 11; ++y)
            for (int x = 5; x < 11; ++x) sum += c.at(name)[size_t(y * 16 + x)];
        return sum / 36;
    };
    EXPECT_NEAR(c.at("P.Z")[centre], 3, 1e-4f);
    EXPECT_NEAR(middle("P.X"), 0, 0.01);
    EXPECT_NEAR(middle("P.Y"), 0, 0.01);
    EXPECT_NEAR(c.at("N.Z")[centre], -1, 1e-5f);  // toward the camera
    EXPECT_NEAR(c.at("Ns.Z")[centre], -1, 1e-5f);
    EXPECT_NEAR(c.at("dzdx")[centre], 0, 1e-5f);
    EXPECT_NEAR(c.at("dzdy")[centre], 0, 1e-5f);
    EXPECT_NEAR(middle("u"), 0.5, 0.005);
    EXPECT_NEAR(middle("v"), 0.5, 0.005);
    // The grey's albedo through 4 wavelengths a sample: 1152 samples, within 0.02 (about 5
    // standard errors).
    for (const char *a : {"Albedo.R", "Albedo.G", "Albedo.B"}) EXPECT_NEAR(middle(a), 0.5, 0.02) << a;
    for (const char *sky : {"P.Z", "N.Z", "u", "Albedo.G"}) EXPECT_EQ(c.at(sky)[corner], 0) << sky;
    // Raster x to the right is camera +x, raster y down is camera -y; u and v follow the square.
    EXPECT_GT(c.at("P.X")[8 * 16 + 11], c.at("P.X")[centre]);
    EXPECT_LT(c.at("P.Y")[11 * 16 + 8], c.at("P.Y")[centre]);
    EXPECT_GE(c.at("Variance.R")[centre], 0);
}

TEST(GBufferFilm, WorldSpaceAndTheSameRGBAsTheRGBFilm) {
    EXRChannels world = RenderFilm(std::string(kFilm) + " \"string coordinatesystem\" \"world\"");
    EXPECT_NEAR(world.channels.at("P.Z")[8 * 16 + 8], 5, 1e-4f);
    EXRChannels rgb = RenderFilm("Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16");
    for (const char *name : {"R", "G", "B"}) EXPECT_EQ(world.channels.at(name), rgb.channels.at(name)) << name;
}

std::string LoadError(const std::string &film, const std::string &rest = "") {
    return LoadErrorAfterPath(WriteScene(film, rest));
}

TEST(GBufferFilm, BadParametersAreErrorsAtTheFilm) {
    EXPECT_THAT(LoadError("Film \"gbuffer\" \"string filename\" \"x.png\""),
                testing::StartsWith(":3:1: error: Film \"gbuffer\" writes EXR only, not \"x.png\""));
    EXPECT_THAT(LoadError("Film \"gbuffer\" \"string coordinatesystem\" \"screen\""),
                testing::StartsWith(":3:16: error: unknown \"coordinatesystem\" \"screen\": expected camera or world"));
    EXPECT_THAT(LoadError("Film \"gbuffer\"", "Integrator \"sppm\""),
                testing::HasSubstr("Film \"gbuffer\" needs the radiance of camera samples"));
    EXPECT_THAT(LoadError("Film \"hdr\""), testing::HasSubstr("unknown Film \"hdr\": expected rgb, spectral or gbuffer"));
}

}  // namespace
}  // namespace pbrt
