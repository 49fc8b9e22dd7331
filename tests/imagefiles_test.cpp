// The PNG and EXR readers (libpng and OpenEXR directly) against OpenImageIO, which read these
// files before: the same size, channels and float values (but color not premultiplied by alpha), for every kind of PNG libpng expands
// (tests/data/png/make_pngs.py writes them from known samples) and for an EXR with a data window
// off the origin, half and float channels, alpha and depth.
#include "pbrt_ext/util/exrfile.h"
#include "pbrt_ext/util/imagecodec.h"
#include "pbrt_ext/util/imageheaders.h"
#include "pbrt_ext/util/pngfile.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace pbrt {
namespace {

namespace fs = std::filesystem;

const fs::path kPngDir = fs::path(PBRT_EXT_TEST_DATA_DIR) / "png";

struct Decoded {
    ImageFileSpec spec;
    std::vector<float> pixels;
};
Decoded Decode(ImageFileReader &reader) {
    Decoded d{reader.Spec(), {}};
    d.pixels.resize(size_t(d.spec.width) * size_t(d.spec.height) * size_t(d.spec.nChannels));
    reader.ReadPixels(d.pixels.data());
    return d;
}
// Channel name -> its values, so that files whose readers order channels differently compare.
std::map<std::string, std::vector<float>> ByName(const Decoded &d) {
    std::map<std::string, std::vector<float>> channels;
    for (int c = 0; c < d.spec.nChannels; ++c)
        for (size_t i = size_t(c); i < d.pixels.size(); i += size_t(d.spec.nChannels))
            channels[d.spec.channelNames[size_t(c)]].push_back(d.pixels[i]);
    return channels;
}

TEST(ImageFileReaders, PngFilesDecodeAsOpenImageIODecodesThem) {
    for (const char *name : {"rgb8.png", "rgba16.png", "gray8.png", "grayalpha8.png", "gray1.png",
                             "palette4_trns.png", "rgb8_interlaced.png"}) {
        std::string path = (kPngDir / name).string();
        ASSERT_EQ(ImageFileFormatOf(path), ImageFileFormat::PNG) << name;
        Decoded ours = Decode(*OpenPNGFile(path));
        Decoded oiio = Decode(*GetImageCodec().Open(path));
        EXPECT_EQ(ours.spec.width, oiio.spec.width) << name;
        EXPECT_EQ(ours.spec.height, oiio.spec.height) << name;
        ASSERT_EQ(ours.spec.nChannels, oiio.spec.nChannels) << name;
        EXPECT_FALSE(ours.spec.isFloat) << name;
        // OpenImageIO premultiplies color by alpha (rounding in the file's integer type); the
        // samples as stored are what pbrt-v4 reads and what we read now.
        int n = ours.spec.nChannels;
        bool alpha = n == 2 || n == 4;
        float quantum = name == std::string("rgba16.png") ? 1.f / 65535 : 1.f / 255;
        for (size_t i = 0; i < ours.pixels.size(); ++i) {
            bool color = !alpha || int(i % size_t(n)) != n - 1;
            float expected = ours.pixels[i] * (alpha && color ? ours.pixels[i - i % size_t(n) + size_t(n) - 1] : 1);
            ASSERT_NEAR(oiio.pixels[i], expected, (alpha && color) ? 1.01f * quantum : 1e-6f)
                << name << " sample " << i;
        }
    }
    // And the samples make_pngs.py wrote: rgb8's pixel (1, 1) is (40, 150, 225); rgba16's
    // pixel (1, 0) is (1007, 65535, 30000, 20005); the palette's (1, 0) is entry 1, green at
    // alpha 128.
    Decoded rgb = Decode(*OpenPNGFile((kPngDir / "rgb8.png").string()));
    EXPECT_EQ(rgb.pixels[(1 * 3 + 1) * 3 + 1], 150.f / 255);
    Decoded rgba = Decode(*OpenPNGFile((kPngDir / "rgba16.png").string()));
    EXPECT_EQ(rgba.pixels[1 * 4 + 0], 1007.f / 65535);
    EXPECT_EQ(rgba.pixels[1 * 4 + 3], 20005.f / 65535);
    Decoded palette = Decode(*OpenPNGFile((kPngDir / "palette4_trns.png").string()));
    EXPECT_EQ(palette.pixels[1 * 4 + 1], 1.f);
    EXPECT_EQ(palette.pixels[1 * 4 + 3], 128.f / 255);
}

TEST(ImageFileReaders, ExrDecodesAsOpenImageIODecodesIt) {
    std::string path = (fs::temp_directory_path() / ("pbrt_ext_imagefiles_" + std::to_string(getpid()) + ".exr")).string();
    const int width = 5, height = 3;
    Imath::Box2i dataWindow(Imath::V2i(2, -1), Imath::V2i(2 + width - 1, -1 + height - 1));
    Imf::Header header(Imath::Box2i(Imath::V2i(0, -4), Imath::V2i(9, 9)), dataWindow);
    std::vector<half> rgba(size_t(width * height * 4));
    std::vector<float> depth(size_t(width * height));
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = half(0.125f * float(i % 17) - 0.5f);
    for (size_t i = 0; i < depth.size(); ++i) depth[i] = 1e3f / float(i + 1);
    for (const char *c : {"R", "G", "B", "A"}) header.channels().insert(c, Imf::Channel(Imf::HALF));
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    {
        Imf::FrameBuffer fb;
        auto at = [&](auto *p, size_t stride) {
            return reinterpret_cast<char *>(p) - (dataWindow.min.x + dataWindow.min.y * width) * ptrdiff_t(stride);
        };
        const char *names[4] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c)
            fb.insert(names[c], Imf::Slice(Imf::HALF, at(rgba.data() + c, 4 * sizeof(half)), 4 * sizeof(half),
                                           4 * sizeof(half) * width));
        fb.insert("Z", Imf::Slice(Imf::FLOAT, at(depth.data(), sizeof(float)), sizeof(float), sizeof(float) * width));
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(fb);
        out.writePixels(height);
    }
    ASSERT_EQ(ImageFileFormatOf(path), ImageFileFormat::EXR);
    Decoded ours = Decode(*OpenEXRFile(path));
    Decoded oiio = Decode(*GetImageCodec().Open(path));
    EXPECT_EQ(ours.spec.width, width);
    EXPECT_EQ(ours.spec.height, height);
    EXPECT_TRUE(ours.spec.isFloat);
    EXPECT_EQ(ByName(ours), ByName(oiio));
    EXPECT_EQ(ByName(ours)["Z"], depth);
    fs::remove(path);
}

TEST(ImageFileReaders, MalformedFilesAreErrors) {
    std::string path = (fs::temp_directory_path() / ("pbrt_ext_imagefiles_bad_" + std::to_string(getpid()))).string();
    std::vector<char> png(fs::file_size(kPngDir / "rgb8.png"));
    std::ifstream(kPngDir / "rgb8.png", std::ios::binary).read(png.data(), std::streamsize(png.size()));
    png.resize(png.size() - 30);  // the image data cut off
    std::ofstream(path, std::ios::binary).write(png.data(), std::streamsize(png.size()));
    std::unique_ptr<ImageFileReader> reader = OpenPNGFile(path);
    std::vector<float> pixels(size_t(reader->Spec().width * reader->Spec().height * reader->Spec().nChannels));
    EXPECT_THROW(reader->ReadPixels(pixels.data()), std::runtime_error);
    std::ofstream(path, std::ios::binary) << "\x76\x2f\x31\x01 not an exr";
    EXPECT_THROW(OpenEXRFile(path), std::runtime_error);
    fs::remove(path);
}

}  // namespace
}  // namespace pbrt
