// The ColorSpace directive, as pbrt-v4 has it: later "rgb" values are in the named space, the
// Film writes in the space in force at its directive, AttributeEnd restores the space, and an
// unknown name is an error at its line.
//
// The scene: a diffuse square facing the camera under a uniform sky of radiance 1 and nothing
// else, so every pixel on the square is the square's reflectance colour (one bounce, the
// cosine-weighted integral of the sky); the estimate's noise is the wavelengths' (4 a sample).
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/spectra/colorspace.h"

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
    return TestFolder(std::string("pbrt_ext_colorspacedirective_test_") +
                      testing::UnitTest::GetInstance()->current_test_info()->name());
}

// beforeFilm and material are written where their names say; the square at z = 5 fills the
// middle of the 16 x 16 image.
std::string WriteScene(const std::string &beforeFilm, const std::string &material,
                       const std::string &light = "LightSource \"infinite\" \"rgb L\" [1 1 1]") {
    std::filesystem::path scene = Folder() / "scene.pbrt";
    std::string out = (Folder() / "out.exr").string();
    std::ofstream(scene)
        << "LookAt 0 0 2  0 0 5  0 1 0\nCamera \"perspective\" \"float fov\" 60\n" << beforeFilm
        << "\nFilm \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16 \"string filename\" \""
        << out << "\"\nSampler \"independent\" \"integer pixelsamples\" 64\n"
        << "WorldBegin\n" << light << "\n" << material
        << "\nShape \"bilinearmesh\" \"point3 P\" [-1 -1 5  1 -1 5  -1 1 5  1 1 5]\n"
        << "  \"integer indices\" [0 1 2 3]\n";
    return scene.string();
}

struct Rendered {
    RGB middle;            // the mean over the middle 6 x 6 pixels
    std::string colorSpace;  // the EXR's "colorSpace" attribute
};

Rendered Render(const std::string &beforeFilm, const std::string &material,
                const std::string &light = "LightSource \"infinite\" \"rgb L\" [1 1 1]") {
    std::unique_ptr<Scene> scene = LoadScene(WriteScene(beforeFilm, material, light), RenderOverrides{});
    RenderOptions options;
    options.quiet = true;
    pbrt::Render(*scene, options);
    scene->film.WriteImage(ImageMetadata());
    EXRChannels exr = ReadEXRChannels((Folder() / "out.exr").string());
    Rendered r;
    const char *names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (int y = 5; y < 11; ++y)
            for (int x = 5; x < 11; ++x) sum += exr.channels.at(names[c])[size_t(y * 16 + x)];
        r.middle[c] = Float(sum / 36);
    }
    if (auto it = exr.stringAttributes.find("colorSpace"); it != exr.stringAttributes.end())
        r.colorSpace = it->second;
    return r;
}

// 2304 samples of 4 wavelengths each: over 8 seeds, the Rec. 2020 colour's sRGB channels scatter
// with standard deviations 1.4e-3, 2e-4 and 2.4e-3; 0.01 is more than 4 of them.
constexpr Float kTolerance = 0.01f;

void ExpectNear(const RGB &got, const RGB &expected, const char *what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], kTolerance) << what << " channel " << c;
}

// A Rec. 2020 reflectance, given as such, renders to an sRGB film as its sRGB equivalent, and
// not as the same numbers read as sRGB.
TEST(ColorSpaceDirective, RGBValuesAreInTheSpaceInForce) {
    const RGB rec2020(0.3f, 0.5f, 0.2f);
    const RGB expected =
        Mul<RGB>(ConvertRGBColorSpace(RGBColorSpace::Rec2020(), RGBColorSpace::sRGB()), rec2020);
    Rendered r = Render("", "ColorSpace \"rec2020\"\n"
                            "Material \"diffuse\" \"rgb reflectance\" [0.3 0.5 0.2]");
    ExpectNear(r.middle, expected, "rec2020 reflectance on an sRGB film");
    EXPECT_GT(std::abs(r.middle.r - rec2020.r), 0.05f) << "read as sRGB";
    EXPECT_EQ(r.colorSpace, "srgb");
}

// The Film's output is in the space in force at the Film directive, and its EXR says which.
TEST(ColorSpaceDirective, FilmWritesInTheSpaceAtItsDirective) {
    Rendered r = Render("ColorSpace \"rec2020\"",
                        "Material \"diffuse\" \"rgb reflectance\" [0.3 0.5 0.2]");
    ExpectNear(r.middle, RGB(0.3f, 0.5f, 0.2f), "rec2020 reflectance on a rec2020 film");
    EXPECT_EQ(r.colorSpace, "rec2020");
}

// ACES2065-1's white is ACES's D60, not D65: a grey under the space's own white light is grey on
// an ACES film (a D65 white or a D65 sky would tint it).
TEST(ColorSpaceDirective, GreyStaysGreyUnderACESWhite) {
    Rendered r = Render("ColorSpace \"aces2065-1\"",
                        "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]");
    ExpectNear(r.middle, RGB(0.5f, 0.5f, 0.5f), "grey on an ACES film");
    EXPECT_EQ(r.colorSpace, "aces2065-1");
}

// AttributeEnd restores the space that AttributeBegin saw, as pbrt-v4's graphics state does.
TEST(ColorSpaceDirective, AttributeEndRestoresTheSpace) {
    Rendered r = Render("", "AttributeBegin\nColorSpace \"aces2065-1\"\nAttributeEnd\n"
                            "Material \"diffuse\" \"rgb reflectance\" [0.3 0.5 0.2]");
    ExpectNear(r.middle, RGB(0.3f, 0.5f, 0.2f), "sRGB reflectance after the block");
}

// A 2 x 2 EXR of one colour, its chromaticities naming the given space.
std::string WriteUniformEXR(const std::string &name, RGB rgb, const RGBColorSpace &cs) {
    Image image(Point2i(2, 2));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, rgb[c]);
    ImageMetadata md;
    md.colorSpace = &cs;
    std::string path = (Folder() / name).string();
    image.Write(path, md);
    return path;
}

// An image texture's RGB is in the space its EXR's chromaticities name (pbrt-v4's MIPMap colour
// space), whatever the ColorSpace in force: here a Rec. 2020 texture in an sRGB scene.
TEST(ColorSpaceDirective, ImageTextureIsInItsFilesSpace) {
    const RGB rec2020(0.3f, 0.5f, 0.2f);
    std::string texture = WriteUniformEXR("rec2020.exr", rec2020, RGBColorSpace::Rec2020());
    Rendered r = Render("", "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"" + texture +
                                "\"\nMaterial \"diffuse\" \"texture reflectance\" \"t\"");
    ExpectNear(r.middle, Mul<RGB>(ConvertRGBColorSpace(RGBColorSpace::Rec2020(), RGBColorSpace::sRGB()), rec2020),
               "Rec. 2020 texture on an sRGB film");
}

// So is an environment map's: a uniform Rec. 2020 sky over a grey square renders as the grey
// times the sky's sRGB equivalent.
TEST(ColorSpaceDirective, EnvironmentMapIsInItsFilesSpace) {
    const RGB rec2020(0.3f, 0.5f, 0.2f);
    std::string sky = WriteUniformEXR("sky.exr", rec2020, RGBColorSpace::Rec2020());
    Rendered r = Render("", "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]",
                        "LightSource \"infinite\" \"string filename\" \"" + sky + "\"");
    RGB expected = Mul<RGB>(ConvertRGBColorSpace(RGBColorSpace::Rec2020(), RGBColorSpace::sRGB()), rec2020);
    ExpectNear(r.middle, RGB(0.5f * expected.r, 0.5f * expected.g, 0.5f * expected.b),
               "grey under a Rec. 2020 sky on an sRGB film");
}

TEST(ColorSpaceDirective, UnknownNameIsAnErrorAtItsLine) {
    std::string scene = WriteScene("", "ColorSpace \"adobergb\"");
    EXPECT_THAT(LoadErrorAfterPath(scene),
                testing::StartsWith(":8:1: error: unknown color space \"adobergb\"; expected one of "
                                    "\"srgb\", \"dci-p3\", \"rec2020\", \"aces2065-1\""));
}

}  // namespace
}  // namespace pbrt
