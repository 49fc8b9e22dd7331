// The PNG, EXR and stb_image readers against OpenImageIO, which read these files before: the
// same size, channels and float values (but color not premultiplied by alpha), for every kind of
// PNG libpng expands (tests/data/png/make_pngs.py writes them from known samples), for an EXR
// with a data window off the origin, half and float channels, alpha and depth, and for TGA, BMP,
// JPEG and HDR files that OpenImageIO writes; hand-written TGA (run-length encoded) and 16-bit
// PSD files hold known samples (the PSD's read at 8 bits, as pbrt-v4 reads it).
#include "pbrt_ext/images/exrfile.h"
#include "pbrt_ext/images/imagecodec.h"
#include "pbrt_ext/images/imageheaders.h"
#include "pbrt_ext/images/pngfile.h"
#include "pbrt_ext/images/stbfile.h"

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

fs::path ScratchFile(const std::string &name) {
    return fs::temp_directory_path() / ("pbrt_ext_imagefiles_" + std::to_string(getpid()) + "_" + name);
}

void WriteBytes(const fs::path &path, const std::string &bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

TEST(ImageFileReaders, StbFormatsDecodeAsOpenImageIODecodesThem) {
    // 7 x 5 pixels whose 8-bit samples all differ.
    const int width = 7, height = 5;
    std::vector<uint8_t> rgb(size_t(width * height * 3));
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t((i * 37 + 11) % 256);
    for (const char *name : {"rgb.tga", "rgb.bmp", "rgb.jpg", "rgb.hdr"}) {
        fs::path path = ScratchFile(name);
        GetImageCodec().Write8Bit(path.string(), path.string(), width, height, rgb.data());
        ASSERT_TRUE(IsSTBImageExtension(path.extension().string())) << name;
        Decoded ours = Decode(*OpenSTBFile(path.string()));
        Decoded oiio = Decode(*GetImageCodec().Open(path.string()));
        fs::remove(path);
        EXPECT_EQ(ours.spec.width, width) << name;
        EXPECT_EQ(ours.spec.height, height) << name;
        ASSERT_EQ(ours.spec.nChannels, 3) << name;
        std::string ext = fs::path(name).extension().string();
        EXPECT_EQ(ours.spec.isFloat, ext == ".hdr") << name;
        ASSERT_EQ(ours.pixels.size(), oiio.pixels.size()) << name;
        for (size_t i = 0; i < ours.pixels.size(); ++i) {
            if (ext == ".jpg")  // lossy: two decoders' inverse transforms round differently
                ASSERT_NEAR(ours.pixels[i], oiio.pixels[i], 3.f / 255) << name << " sample " << i;
            else if (ext == ".hdr")  // the same shared-exponent samples, decoded to float
                ASSERT_NEAR(ours.pixels[i], oiio.pixels[i], 1e-6f * (1 + oiio.pixels[i])) << name << " sample " << i;
            else  // lossless: the samples written
                ASSERT_EQ(ours.pixels[i], float(rgb[i]) / 255) << name << " sample " << i;
        }
    }
}

TEST(ImageFileReaders, StbReadsRunLengthTgaAnd16BitPsd) {
    // A 4 x 1 true-color TGA (type 10, run-length encoded, 24 bits, top-left origin): one run of
    // three blue-green-red pixels (10, 20, 30), then one raw pixel (40, 50, 60).
    std::string tga = std::string("\0\0\x0a", 3) + std::string(9, '\0') +
                      std::string("\x04\0\x01\0\x18\x20", 6) + std::string("\x82\x1e\x14\x0a", 4) +
                      std::string("\x00\x3c\x32\x28", 4);
    fs::path tgaPath = ScratchFile("rle.tga");
    WriteBytes(tgaPath, tga);
    Decoded d = Decode(*OpenSTBFile(tgaPath.string()));
    fs::remove(tgaPath);
    ASSERT_EQ(d.spec.width, 4);
    ASSERT_EQ(d.spec.nChannels, 3);
    std::vector<float> expected;
    for (int v : {10, 20, 30, 10, 20, 30, 10, 20, 30, 40, 50, 60}) expected.push_back(float(v) / 255);
    EXPECT_EQ(d.pixels, expected);
    // A 2 x 1 RGB PSD with 16-bit samples (big-endian planes, uncompressed): red 1007 and
    // 65535, green 0 and 300, blue 20005 and 1.
    std::string psd = std::string("8BPS\0\x01", 6) + std::string(6, '\0') +
                      std::string("\0\x03\0\0\0\x01\0\0\0\x02\0\x10\0\x03", 14) +
                      std::string(12, '\0') +  // color mode data, resources, layers: none
                      std::string("\0\0", 2) +  // compression: raw
                      std::string("\x03\xef\xff\xff\0\0\x01\x2c\x4e\x25\0\x01", 12);
    fs::path psdPath = ScratchFile("rgb16.psd");
    WriteBytes(psdPath, psd);
    Decoded rgb16 = Decode(*OpenSTBFile(psdPath.string()));
    fs::remove(psdPath);
    ASSERT_EQ(rgb16.spec.nChannels, 4);  // stb_image gives every PSD an alpha channel, opaque
    EXPECT_FALSE(rgb16.spec.isFloat);
    // Each sample's high byte, as pbrt-v4 reads it (stbi_load).
    std::vector<float> samples16;
    for (int v : {1007, 0, 20005, 65535, 65535, 300, 1, 65535}) samples16.push_back(float(v >> 8) / 255);
    EXPECT_EQ(rgb16.pixels, samples16);
}

TEST(ImageFileReaders, StbRefusesImpossibleHeaders) {
    // An 18-byte TGA header that declares 60000 x 60000 pixels: no file of 18 bytes holds them,
    // and stb_image would allocate 10 GB to find out.
    fs::path path = ScratchFile("huge.tga");
    WriteBytes(path, std::string("\0\0\x02", 3) + std::string(9, '\0') + std::string("\x60\xea\x60\xea\x18\x20", 6));
    try {
        OpenSTBFile(path.string());
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error &e) {
        EXPECT_STREQ(e.what(), "the header declares 60000 x 60000 pixels, more than a file of 18 bytes can hold");
    }
    WriteBytes(path, "not an image");
    EXPECT_THROW(OpenSTBFile(path.string()), std::runtime_error);
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
