// Images: lossless EXR round trips with metadata, sRGB 8-bit files within quantization and kept
// as bytes, pbrt-v4's
// wrap modes and lookups, and errors that name the file and leave no partial output.
#include "pbrt_ext/images/image.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/log.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

namespace pbrt {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards.
class ImageFiles : public testing::Test {
  protected:
    void SetUp() override {
        dir = fs::temp_directory_path() /
              ("pbrt_image_test_" + std::to_string(::getpid()) + "_" +
               testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string Path(const std::string &name) const { return (dir / name).string(); }
    int FilesInDir() const { return int(std::distance(fs::directory_iterator(dir), fs::directory_iterator())); }

    fs::path dir;
};

// Values spanning what a render produces: tiny, above 1, exact zeros, fixed seed.
Image TestImage(Point2i res, Float maxValue, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Float> u(0, maxValue);
    Image image(res);
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, (x + y + c) % 7 ? u(rng) : 0);
    return image;
}

TEST(ImageColor, SRGBTransferFunctionsInvert) {
    for (int i = 0; i <= 1000; ++i) {
        Float v = i / 1000.f;
        EXPECT_NEAR(SRGBToLinear(LinearToSRGB(v)), v, 2e-6f);
    }
    EXPECT_NEAR(SRGBToLinear(0.5f), 0.21404f, 1e-4f);  // the standard's mid-gray
}

TEST_F(ImageFiles, ExrRoundTripIsExactWithMetadata) {
    Image image = TestImage(Point2i(17, 11), 20, 1);
    ImageMetadata md;
    md.samplesPerPixel = 64;
    md.renderTimeSeconds = 12.5;
    md.scene = "scenes/cornell.pbrt";
    md.extra["integrator"] = "path";
    std::string path = Path("out.exr");
    image.Write(path, md);

    Image back = Image::Read(path);
    ASSERT_EQ(back.Resolution(), image.Resolution());
    for (int y = 0; y < 11; ++y)
        for (int x = 0; x < 17; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(back.GetChannel(Point2i(x, y), c), image.GetChannel(Point2i(x, y), c));

    Imf::InputFile file(path.c_str());
    const Imf::Header &h = file.header();
    EXPECT_EQ(h.typedAttribute<Imf::IntAttribute>("samplesPerPixel").value(), 64);
    EXPECT_EQ(h.typedAttribute<Imf::DoubleAttribute>("renderTimeSeconds").value(), 12.5);
    EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("scene").value(), "scenes/cornell.pbrt");
    EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("integrator").value(), "path");
    EXPECT_EQ(h.channels().findChannel("R")->type, Imf::FLOAT);
    EXPECT_EQ(FilesInDir(), 1);  // no temporary left behind
}

// The colour space goes into the EXR as its standard chromaticities (what other tools read) and
// as a name.
TEST_F(ImageFiles, ExrRecordsTheColorSpace) {
    ImageMetadata md;
    md.colorSpace = &RGBColorSpace::sRGB();
    std::string path = Path("srgb.exr");
    TestImage(Point2i(4, 3), 1, 2).Write(path, md);
    Imf::InputFile file(path.c_str());
    const Imf::Header &h = file.header();
    EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("colorSpace").value(), "srgb");
    ASSERT_TRUE(Imf::hasChromaticities(h));
    const Imf::Chromaticities &c = Imf::chromaticities(h);
    const RGBColorSpace &cs = RGBColorSpace::sRGB();
    EXPECT_FLOAT_EQ(c.red.x, cs.r.x);
    EXPECT_FLOAT_EQ(c.green.y, cs.g.y);
    EXPECT_FLOAT_EQ(c.blue.x, cs.b.x);
    EXPECT_FLOAT_EQ(c.white.x, cs.w.x);
    EXPECT_FLOAT_EQ(c.white.y, cs.w.y);
    EXPECT_NEAR(c.white.x, 0.3127, 5e-4);  // D65
    EXPECT_NEAR(c.red.x, 0.64, 1e-6);      // Rec. 709 red

    std::string plain = Path("plain.exr");
    TestImage(Point2i(4, 3), 1, 2).Write(plain, ImageMetadata{});
    Imf::InputFile none(plain.c_str());
    EXPECT_FALSE(Imf::hasChromaticities(none.header()));
}

// An EXR's chromaticities decide the colour space its RGB is read in, as pbrt-v4 matches them
// (each coordinate within a relative 1e-3): ours as we write them, a Rec. 2020 file written
// by another tool with the published primaries and D65 white, and sRGB, with a warning, for
// primaries no space we know has.
TEST_F(ImageFiles, ExrChromaticitiesGiveTheColorSpace) {
    for (const RGBColorSpace *cs : {&RGBColorSpace::sRGB(), &RGBColorSpace::DCI_P3(),
                                    &RGBColorSpace::Rec2020(), &RGBColorSpace::ACES2065_1()}) {
        ImageMetadata md;
        md.colorSpace = cs;
        std::string path = Path("space.exr");
        TestImage(Point2i(2, 2), 1, 3).Write(path, md);
        EXPECT_EQ(&Image::Read(path).ColorSpace(), cs) << cs->Name();
    }
    std::string plain = Path("plain.exr");
    TestImage(Point2i(2, 2), 1, 3).Write(plain, ImageMetadata{});
    EXPECT_EQ(&Image::Read(plain).ColorSpace(), &RGBColorSpace::sRGB());

    auto writeWith = [&](const std::string &name, Imf::Chromaticities c) {
        std::string path = Path(name);
        Imf::Header header(1, 1);
        Imf::addChromaticities(header, c);
        float rgb[3] = {0.25f, 0.5f, 0.75f};
        Imf::FrameBuffer fb;
        for (int i = 0; i < 3; ++i) {
            const char *channel[3] = {"R", "G", "B"};
            header.channels().insert(channel[i], Imf::Channel(Imf::FLOAT));
            fb.insert(channel[i], Imf::Slice(Imf::FLOAT, reinterpret_cast<char *>(&rgb[i]),
                                             sizeof(rgb), sizeof(rgb)));
        }
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(fb);
        out.writePixels(1);
        return path;
    };
    Imath::V2f d65(0.3127f, 0.3290f);
    std::string rec2020 = writeWith("rec2020.exr", Imf::Chromaticities({0.708f, 0.292f}, {0.170f, 0.797f},
                                                                      {0.131f, 0.046f}, d65));
    EXPECT_EQ(&Image::Read(rec2020).ColorSpace(), &RGBColorSpace::Rec2020());
    std::string adobe = writeWith("adobe.exr", Imf::Chromaticities({0.64f, 0.33f}, {0.21f, 0.71f},
                                                                  {0.15f, 0.06f}, d65));
    int warnings = Log().warnings;
    Log().quiet = true;
    Image image = Image::Read(adobe);
    Log().quiet = false;
    EXPECT_EQ(&image.ColorSpace(), &RGBColorSpace::sRGB());
    EXPECT_EQ(Log().warnings, warnings + 1);
    EXPECT_EQ(image.GetChannels(Point2i(0, 0)).g, 0.5f);
}

// The images made from one (a texture pyramid's resized, halved and re-encoded levels) stay in
// its colour space.
TEST_F(ImageFiles, PyramidLevelsKeepTheColorSpace) {
    ImageMetadata md;
    md.colorSpace = &RGBColorSpace::Rec2020();
    std::string path = Path("rec2020.exr");
    TestImage(Point2i(3, 5), 1, 4).Write(path, md);
    std::vector<Image> pyramid = Image::GeneratePyramid(Image::Read(path), WrapMode::Clamp);
    ASSERT_EQ(pyramid.size(), 4u);  // 4 x 8 up to 1 x 1
    for (const Image &level : pyramid)
        EXPECT_EQ(&level.ColorSpace(), &RGBColorSpace::Rec2020()) << level.Resolution().x;
}

TEST_F(ImageFiles, ExrCropSetsDataAndDisplayWindows) {
    Image crop = TestImage(Point2i(4, 3), 1, 2);
    ImageMetadata md;
    md.fullResolution = Point2i(10, 8);
    md.pixelBounds = Bounds2i(Point2i(5, 2), Point2i(9, 5));
    std::string path = Path("crop.exr");
    crop.Write(path, md);
    Imf::InputFile file(path.c_str());
    EXPECT_EQ(file.header().displayWindow().max, Imath::V2i(9, 7));
    EXPECT_EQ(file.header().dataWindow().min, Imath::V2i(5, 2));
    EXPECT_EQ(file.header().dataWindow().max, Imath::V2i(8, 4));
    Image back = Image::Read(path);
    ASSERT_EQ(back.Resolution(), Point2i(4, 3));
    EXPECT_EQ(back.GetChannel(Point2i(3, 2), 1), crop.GetChannel(Point2i(3, 2), 1));

    md.pixelBounds = Bounds2i(Point2i(0, 0), Point2i(5, 3));  // does not match 4x3
    EXPECT_THROW(crop.Write(Path("bad.exr"), md), std::runtime_error);
}

TEST_F(ImageFiles, PngRoundTripWithinQuantization) {
    Image image = TestImage(Point2i(9, 5), 1.5f, 3);
    image.SetChannel(Point2i(0, 0), 0, -1);  // clamped to black
    std::string path = Path("out.png");
    image.Write(path);
    Image back = Image::Read(path);
    ASSERT_EQ(back.Resolution(), image.Resolution());
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 9; ++x)
            for (int c = 0; c < 3; ++c) {
                Float v = Clamp(image.GetChannel(Point2i(x, y), c), 0, 1);
                Float encoded = LinearToSRGB(v);
                // Half an 8-bit step in the encoded domain, mapped back through the curve.
                Float tol = SRGBToLinear(std::min(1.f, encoded + 0.5f / 255)) - v + 1e-6f;
                EXPECT_NEAR(back.GetChannel(Point2i(x, y), c), v, tol) << x << "," << y << "," << c;
            }
    EXPECT_EQ(back.GetChannel(Point2i(0, 0), 0), 0);
}

TEST_F(ImageFiles, EightBitFilesKeepTheirBytes) {
    // An 8-bit file is kept as bytes, decoded through a table: exactly the values the file's
    // samples (byte / 255 from the reader) give through the encoding; gray files and RGB files
    // whose channels are equal everywhere take one byte a pixel. 16-bit files stay float.
    const fs::path png = fs::path(PBRT_EXT_TEST_DATA_DIR) / "png";
    for (ColorEncoding encoding : {ColorEncoding::SRGB(), ColorEncoding::Linear(), ColorEncoding::Gamma(2.2f)}) {
        Image rgb = Image::Read((png / "rgb8.png").string(), encoding);
        ASSERT_TRUE(rgb.Is8Bit());
        // make_pngs.py's pixel (1, 1) is (40, 150, 225).
        RGB p = rgb.GetChannels(Point2i(1, 1));
        EXPECT_EQ(p.r, encoding.ToLinear(40.f / 255));
        EXPECT_EQ(p.g, encoding.ToLinear(150.f / 255));
        EXPECT_EQ(p.b, encoding.ToLinear(225.f / 255));
        EXPECT_EQ(rgb.GetChannel(Point2i(1, 1), 2), p.b);
    }
    Image gray = Image::Read((png / "gray8.png").string());
    ASSERT_TRUE(gray.Is8Bit());
    RGB g = gray.GetChannels(Point2i(1, 0));
    EXPECT_EQ(g.r, g.g);
    EXPECT_EQ(g.g, g.b);
    EXPECT_FALSE(Image::Read((png / "rgba16.png").string()).Is8Bit());

    // An RGB file of equal channels reads as the gray image it is; writing a pixel makes the
    // image float, and the other pixels keep their values.
    Image image(Point2i(3, 2));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, 0.1f * Float(x + 3 * y));
    image.Write(Path("gray.png"));
    Image back = Image::Read(Path("gray.png"));
    ASSERT_TRUE(back.Is8Bit());
    RGB before = back.GetChannels(Point2i(2, 1));
    EXPECT_EQ(before.r, before.b);
    EXPECT_NEAR(before.g, 0.5f, 0.01f);
    back.SetChannel(Point2i(0, 0), 1, 0.75f);
    EXPECT_FALSE(back.Is8Bit());
    EXPECT_EQ(back.GetChannel(Point2i(0, 0), 1), 0.75f);
    EXPECT_EQ(back.GetChannels(Point2i(2, 1)).g, before.g);
}

// A float image texture reads an RGBA file's alpha where it is not 1 everywhere (pbrt-v4),
// decoded through the same encoding as the colour; other files keep their RGB.
TEST_F(ImageFiles, AlphaOfRGBAReadsAlphaWhereThereIsSome) {
    const fs::path png = fs::path(PBRT_EXT_TEST_DATA_DIR) / "png";
    // rgba16.png: 16-bit, alpha equal to green at (0, 0): 20000 / 65535.
    Image alpha = Image::Read((png / "rgba16.png").string(), ColorEncoding::Linear(), ImageChannels::AlphaOfRGBA);
    RGB a = alpha.GetChannels(Point2i(0, 0));
    EXPECT_NEAR(a.r, 20000.f / 65535, 1e-6f);
    EXPECT_EQ(a.r, a.g);
    EXPECT_EQ(a.g, a.b);
    // palette4_trns.png: 8-bit RGBA through a palette; texel (1, 0) has alpha 128 / 255, texel
    // (2, 0) alpha 0, texel (0, 0) alpha 1.
    Image trns = Image::Read((png / "palette4_trns.png").string(), ColorEncoding::SRGB(), ImageChannels::AlphaOfRGBA);
    EXPECT_NEAR(trns.GetChannels(Point2i(1, 0)).g, SRGBToLinear(128.f / 255), 1e-6f);
    EXPECT_EQ(trns.GetChannels(Point2i(2, 0)).b, 0);
    EXPECT_EQ(trns.GetChannels(Point2i(0, 0)).r, 1);
    // No alpha (rgb8.png) or no R, G, B (grayalpha8.png: Y and A): the colour, as Read gives it.
    for (const char *name : {"rgb8.png", "grayalpha8.png"}) {
        Image rgb = Image::Read((png / name).string());
        Image asAlpha = Image::Read((png / name).string(), ColorEncoding::SRGB(), ImageChannels::AlphaOfRGBA);
        for (int x = 0; x < rgb.Resolution().x; ++x)
            EXPECT_EQ(asAlpha.GetChannels(Point2i(x, 0)), rgb.GetChannels(Point2i(x, 0))) << name;
    }
}

TEST_F(ImageFiles, ReadErrorsNameTheFile) {
    std::string missing = Path("missing.exr");
    try {
        Image::Read(missing);
        FAIL() << "no exception";
    } catch (const std::runtime_error &e) {
        EXPECT_EQ(std::string(e.what()).rfind(missing + ": error: ", 0), 0u) << e.what();
    }
    std::ofstream(Path("garbage.png")) << "not a png";
    EXPECT_THROW(Image::Read(Path("garbage.png")), std::runtime_error);
}

TEST_F(ImageFiles, FailedWriteLeavesNoFileAndKeepsTheOldOne) {
    Image image = TestImage(Point2i(4, 4), 1, 4);
    EXPECT_THROW(image.Write(Path("out.unknownext")), std::runtime_error);
    EXPECT_THROW(image.Write(Path("no/such/dir/out.exr")), std::runtime_error);
    EXPECT_EQ(FilesInDir(), 0);

    std::string path = Path("keep.exr");
    image.Write(path);
    auto sizeBefore = fs::file_size(path);
    ImageMetadata bad;
    bad.extra["channels"] = "x";  // would clobber the EXR channel list
    EXPECT_THROW(Image(Point2i(8, 8)).Write(path, bad), std::runtime_error);
    EXPECT_EQ(fs::file_size(path), sizeBefore);
    EXPECT_EQ(Image::Read(path).Resolution(), Point2i(4, 4));
    EXPECT_EQ(FilesInDir(), 1);
    EXPECT_THROW(Image().Write(Path("empty.png")), std::runtime_error);
}

TEST(ImageLookup, WrapModes) {
    Point2i res(4, 3);
    Point2i p(-1, 5);
    EXPECT_FALSE(RemapPixelCoords(&p, res, WrapMode::Black));
    p = Point2i(-1, 5);
    ASSERT_TRUE(RemapPixelCoords(&p, res, WrapMode::Clamp));
    EXPECT_EQ(p, Point2i(0, 2));
    p = Point2i(-1, 5);
    ASSERT_TRUE(RemapPixelCoords(&p, res, WrapMode::Repeat));
    EXPECT_EQ(p, Point2i(3, 2));
    p = Point2i(6, -1);
    ASSERT_TRUE(RemapPixelCoords(&p, res, WrapMode2D(WrapMode::Clamp, WrapMode::Repeat)));
    EXPECT_EQ(p, Point2i(3, 2));
}

TEST(ImageLookup, OctahedralWrapFoldsAcrossEdges) {
    Point2i res(8, 8);
    // Crossing the left edge mirrors x and flips y (pbrt-v4's convention).
    Point2i p(-1, 2);
    ASSERT_TRUE(RemapPixelCoords(&p, res, WrapMode::OctahedralSphere));
    EXPECT_EQ(p, Point2i(1, 5));
    p = Point2i(8, 0);
    RemapPixelCoords(&p, res, WrapMode::OctahedralSphere);
    EXPECT_EQ(p, Point2i(7, 7));
    p = Point2i(3, -1);
    RemapPixelCoords(&p, res, WrapMode::OctahedralSphere);
    EXPECT_EQ(p, Point2i(4, 1));
    p = Point2i(3, 8);
    RemapPixelCoords(&p, res, WrapMode::OctahedralSphere);
    EXPECT_EQ(p, Point2i(4, 7));
    p = Point2i(-1, -1);  // a corner stays inside a one-pixel image
    RemapPixelCoords(&p, Point2i(1, 1), WrapMode::OctahedralSphere);
    EXPECT_EQ(p, Point2i(0, 0));
}

TEST(ImageLookup, BilerpInterpolatesBetweenCenters) {
    Image image(Point2i(2, 1));
    image.SetChannel(Point2i(0, 0), 0, 1);
    image.SetChannel(Point2i(1, 0), 0, 3);
    image.SetChannel(Point2i(1, 0), 2, 5);
    EXPECT_FLOAT_EQ(image.BilerpChannel(Point2f(0.25f, 0.5f), 0), 1);  // pixel center
    EXPECT_FLOAT_EQ(image.BilerpChannel(Point2f(0.5f, 0.5f), 0), 2);   // halfway
    EXPECT_FLOAT_EQ(image.Bilerp(Point2f(0.75f, 0.5f))[2], 5);
    EXPECT_FLOAT_EQ(image.LookupNearestChannel(Point2f(0.6f, 0.1f), 0), 3);
    EXPECT_FLOAT_EQ(image.LookupNearest(Point2f(0.4f, 0.9f))[0], 1);
    EXPECT_FLOAT_EQ(image.BilerpChannel(Point2f(0.0f, 0.5f), 0, WrapMode::Black), 0.5f);
    std::vector<Float> d = image.GetSamplingDistribution();
    ASSERT_EQ(d.size(), 2u);
    EXPECT_FLOAT_EQ(d[0], 1.f / 3);
    EXPECT_FLOAT_EQ(d[1], 8.f / 3);
}

TEST(ImageLookup, NegativeResolutionThrows) {
    EXPECT_THROW(Image(Point2i(-1, 4)), std::runtime_error);
    EXPECT_TRUE(Image(Point2i(0, 4)).Empty());
}

}  // namespace
}  // namespace pbrt
