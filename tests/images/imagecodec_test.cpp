// OpenImageIO is a module loaded on first use (images/imagecodec.h): a render written as EXR or PNG
// (libpng and OpenEXR directly) never loads it, nor does one that reads a TGA texture (stb_image),
// which is what keeps start-up at pbrt-v4's (docs/benchmarks.md), and one written in another
// format (TGA) loads it and writes the file. The dynamic loader's own log (LD_DEBUG=libs) of the real
// command says which libraries a process loaded.
#include "pbrt_ext/images/image.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

using namespace pbrt;

namespace {

namespace fs = std::filesystem;

const std::string kFurnace = std::string(PBRT_EXT_TEST_DATA_DIR) + "/interrupt/furnace.pbrt";

struct CommandRun {
    int status = -1;
    std::string log;
};

// The command on the scene (the furnace) at 1 sample per pixel, with the loader's log in its
// output.
CommandRun RenderWithLoaderLog(const fs::path &outfile, const std::string &scene = kFurnace) {
    std::string command = "LD_DEBUG=libs " + std::string(PBRT_EXT_CLI) + " --spp 1 --quiet --outfile " +
                          outfile.string() + " " + scene + " 2>&1";
    CommandRun run;
    FILE *pipe = popen(command.c_str(), "r");
    if (!pipe) return run;
    std::array<char, 4096> buffer;
    while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) run.log.append(buffer.data(), n);
    int status = pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

fs::path ScratchDir() {
    fs::path dir = fs::temp_directory_path() / ("pbrt_ext_imagecodec_" + std::to_string(getpid()));
    fs::create_directories(dir);
    return dir;
}

TEST(ImageCodec, ExrAndPngNeverLoadOpenImageIO) {
    for (const char *name : {"furnace.exr", "furnace.png"}) {
        fs::path out = ScratchDir() / name;
        CommandRun run = RenderWithLoaderLog(out);
        ASSERT_EQ(run.status, 0) << run.log;
        ASSERT_NE(run.log.find("calling init"), std::string::npos) << "no loader log: " << run.log;
        EXPECT_EQ(run.log.find("libOpenImageIO"), std::string::npos) << name;
        EXPECT_EQ(run.log.find("libpbrt_ext_imagecodec"), std::string::npos) << name;
        // The furnace is 0.5 everywhere (the PNG holds it sRGB-encoded, within 8 bits and noise).
        EXPECT_NEAR(Image::Read(out.string()).GetChannels(Point2i(512, 512)).g, 0.5, 0.2) << name;
        fs::remove_all(out.parent_path());
    }
}

TEST(ImageCodec, TgaTexturesNeverLoadOpenImageIO) {
    // A 2 x 1 uncompressed TGA (BGR: a red and a blue pixel) on a diffuse sphere.
    fs::path dir = ScratchDir();
    std::string tga = std::string("\0\0\x02", 3) + std::string(9, '\0') +
                      std::string("\x02\0\x01\0\x18\x20\0\0\xff\xff\0\0", 12);
    std::ofstream(dir / "texture.tga", std::ios::binary).write(tga.data(), std::streamsize(tga.size()));
    std::ofstream(dir / "scene.pbrt")
        << "LookAt 0 0 5 0 0 0 0 1 0 Camera \"perspective\" \"float fov\" 10\n"
           "Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16\n"
           "WorldBegin\nLightSource \"infinite\" \"rgb L\" [1 1 1]\n"
           "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"texture.tga\"\n"
           "Material \"diffuse\" \"texture reflectance\" \"t\"\nShape \"sphere\"\n";
    CommandRun run = RenderWithLoaderLog(dir / "out.exr", (dir / "scene.pbrt").string());
    ASSERT_EQ(run.status, 0) << run.log;
    ASSERT_NE(run.log.find("calling init"), std::string::npos) << "no loader log: " << run.log;
    EXPECT_EQ(run.log.find("libOpenImageIO"), std::string::npos);
    EXPECT_EQ(run.log.find("libpbrt_ext_imagecodec"), std::string::npos);
    // Red on one side, blue on the other: the texture was read.
    Image image = Image::Read((dir / "out.exr").string());
    RGB left = image.GetChannels(Point2i(5, 8)), right = image.GetChannels(Point2i(10, 8));
    EXPECT_GT(left.r + right.r, 2 * (left.g + right.g));
    EXPECT_GT(left.b + right.b, 2 * (left.g + right.g));
    fs::remove_all(dir);
}

TEST(ImageCodec, OtherFormatsLoadTheModuleAndWrite) {
    fs::path out = ScratchDir() / "furnace.tga";
    CommandRun run = RenderWithLoaderLog(out);
    ASSERT_EQ(run.status, 0) << run.log;
    EXPECT_NE(run.log.find("libpbrt_ext_imagecodec"), std::string::npos);
    EXPECT_NE(run.log.find("libOpenImageIO"), std::string::npos);
    Image image = Image::Read(out.string());
    EXPECT_EQ(image.Resolution(), Point2i(1024, 1024));
    fs::remove_all(out.parent_path());
}

}  // namespace
