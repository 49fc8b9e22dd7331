// Textures: pbrt-v4's constant, scale, mix, checkerboard and image-map semantics; image maps
// honour uv mapping, t flip, filter, wrap, scale, invert and the file's encoding, and share one
// decoded image per (file, encoding).
#include "pbrt_ext/textures/textures.h"

#include "pbrt_ext/spectra/colorspace.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace pbrt {
namespace {

namespace fs = std::filesystem;

TextureEvalContext AtUV(Float u, Float v) {
    TextureEvalContext ctx;
    ctx.uv = Point2f(u, v);
    return ctx;
}

// The wavelengths spectrum textures are evaluated at: 400, 500, 600 and 700 nm.
const SampledWavelengths kLambda = SampledWavelengths::SampleUniform(0, 400, 800);

// A spectrum through the values v at kLambda's wavelengths, linear between them.
Spectrum At4(Float v0, Float v1, Float v2, Float v3) {
    return Spectrum::PiecewiseLinear({400, 500, 600, 700}, {v0, v1, v2, v3});
}

void ExpectSpectrumNear(SampledSpectrum s, SampledSpectrum expected, Float tol) {
    for (int i = 0; i < NSpectrumSamples; ++i)
        EXPECT_NEAR(s[i], expected[i], tol) << "at " << kLambda[i] << " nm";
}

// An image texel of the given RGB becomes the sRGB spectrum of the texture's type (pbrt-v4's
// SpectrumImageTexture): s must be that spectrum at kLambda.
void ExpectRGBNear(SampledSpectrum s, SpectrumType type, Float r, Float g, Float b, Float tol) {
    const RGBColorSpace &cs = RGBColorSpace::sRGB();
    RGB rgb(r, g, b);
    SampledSpectrum expected = type == SpectrumType::Albedo
                                   ? RGBAlbedoSpectrum(cs, rgb).Sample(kLambda)
                                   : RGBUnboundedSpectrum(cs, rgb).Sample(kLambda);
    ExpectSpectrumNear(s, expected, tol);
}

TEST(TextureCombine, ConstantAndScale) {
    EXPECT_EQ(FloatTexture(0.25f).Evaluate(AtUV(0, 0)), 0.25f);
    FloatTexture scaled = FloatScaledTexture(FloatTexture(3), FloatTexture(0.5f));
    EXPECT_EQ(scaled.Evaluate(AtUV(0, 0)), 1.5f);
    SpectrumTexture s =
        SpectrumScaledTexture(SpectrumTexture(At4(0.2f, 0.4f, 0.8f, 0.6f)), FloatTexture(0.5f));
    EXPECT_EQ(s.Evaluate(AtUV(0, 0), kLambda), SampledSpectrum(0.1f, 0.2f, 0.4f, 0.3f));
    // A zero scale gives exactly zero even for an infinite texture (it is not evaluated).
    FloatTexture zero = FloatScaledTexture(FloatTexture(Infinity), FloatTexture(0));
    EXPECT_EQ(zero.Evaluate(AtUV(0, 0)), 0);
}

TEST(TextureCombine, MixByAmountTexture) {
    // The amount is itself a texture: 0 on even checker squares, 1 on odd ones.
    FloatTexture amount = FloatCheckerboardTexture(UVMapping{}, FloatTexture(0.25f), FloatTexture(1));
    SpectrumTexture mix = SpectrumMixTexture(SpectrumTexture(At4(1, 0, 0, 0.5f)),
                                             SpectrumTexture(At4(0, 0, 1, 0.5f)), amount);
    ExpectSpectrumNear(mix.Evaluate(AtUV(0.5f, 0.5f), kLambda), SampledSpectrum(0.75f, 0, 0.25f, 0.5f),
                       1e-6f);
    ExpectSpectrumNear(mix.Evaluate(AtUV(1.5f, 0.5f), kLambda), SampledSpectrum(0, 0, 1, 0.5f), 0);
    // Weight 0 or 1 does not evaluate the other side (an Inf there would make NaN).
    FloatTexture pure = FloatMixTexture(FloatTexture(2), FloatTexture(Infinity), FloatTexture(0));
    EXPECT_EQ(pure.Evaluate(AtUV(0, 0)), 2);
}

TEST(TextureCombine, CheckerboardParityIncludingNegativeCoordinates) {
    FloatTexture board = FloatCheckerboardTexture(UVMapping{}, FloatTexture(1), FloatTexture(0));
    EXPECT_EQ(board.Evaluate(AtUV(0.5f, 0.5f)), 1);
    EXPECT_EQ(board.Evaluate(AtUV(1.5f, 0.5f)), 0);
    EXPECT_EQ(board.Evaluate(AtUV(1.5f, 1.5f)), 1);
    EXPECT_EQ(board.Evaluate(AtUV(-0.5f, 0.5f)), 0);   // square (-1, 0)
    EXPECT_EQ(board.Evaluate(AtUV(-0.5f, -0.5f)), 1);  // square (-1, -1)
}

TEST(TextureCombine, UVMappingScalesThenOffsets) {
    UVMapping m{4, 2, 0.5f, -1};
    TexCoord2D c = m.Map(AtUV(0.25f, 0.75f));
    EXPECT_EQ(c.st, Point2f(1.5f, 0.5f));
    // 4 checks across u in [0, 1): the square changes every quarter.
    FloatTexture board = FloatCheckerboardTexture(UVMapping{4, 4, 0, 0}, FloatTexture(1), FloatTexture(0));
    EXPECT_EQ(board.Evaluate(AtUV(0.1f, 0.1f)), 1);
    EXPECT_EQ(board.Evaluate(AtUV(0.3f, 0.1f)), 0);
}

TEST(TextureCombine, SharedChildrenMakeCopiesCheap) {
    FloatTexture child = FloatScaledTexture(FloatTexture(2), FloatTexture(3));
    FloatScaledTexture parent(child, FloatTexture(1));
    FloatScaledTexture copy = parent;
    EXPECT_EQ(copy.tex.get(), parent.tex.get());
    EXPECT_EQ(FloatTexture(copy).Evaluate(AtUV(0, 0)), 6);
}

TEST(ImageTextureOptions, ParseWrapModeAndColorEncoding) {
    EXPECT_EQ(*ParseWrapMode("repeat"), WrapMode::Repeat);
    EXPECT_EQ(*ParseWrapMode("clamp"), WrapMode::Clamp);
    EXPECT_EQ(*ParseWrapMode("black"), WrapMode::Black);
    EXPECT_EQ(*ParseWrapMode("octahedralsphere"), WrapMode::OctahedralSphere);
    EXPECT_FALSE(ParseWrapMode("mirror").has_value());

    EXPECT_EQ(*ColorEncoding::Get("linear"), ColorEncoding::Linear());
    EXPECT_EQ(*ColorEncoding::Get("sRGB"), ColorEncoding::SRGB());
    EXPECT_EQ(*ColorEncoding::Get("gamma 2.2"), ColorEncoding::Gamma(2.2f));
    EXPECT_EQ(ColorEncoding::Gamma(2.2f).ToString(), "gamma 2.2");
    for (const char *bad : {"srgb", "gamma", "gamma 0", "gamma -1", "gamma 2.2x", "gamma nan", ""})
        EXPECT_FALSE(ColorEncoding::Get(bad).has_value()) << bad;
    EXPECT_NEAR(ColorEncoding::Gamma(2).ToLinear(0.5f), 0.25f, 1e-7f);
    EXPECT_EQ(ColorEncoding::Linear().ToLinear(0.5f), 0.5f);
}

// Image files written per test, removed afterwards; the texture cache starts empty.
class ImageTextures : public testing::Test {
  protected:
    static constexpr SpectrumType U = SpectrumType::Unbounded, A = SpectrumType::Albedo;

    void SetUp() override {
        dir = fs::temp_directory_path() /
              ("pbrt_textures_test_" + std::to_string(::getpid()) + "_" +
               testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
        ImageTextureCache::Clear();
    }
    void TearDown() override {
        ImageTextureCache::Clear();
        fs::remove_all(dir);
    }
    std::string Path(const std::string &name) const { return (dir / name).string(); }

    // A 2x2 linear EXR: top row red, green; bottom row blue, white.
    std::string WriteQuad() {
        Image image(Point2i(2, 2));
        RGB texels[4] = {RGB(1, 0, 0), RGB(0, 1, 0), RGB(0, 0, 1), RGB(1, 1, 1)};
        for (int i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(i % 2, i / 2), c, texels[i][c]);
        std::string path = Path("quad.exr");
        image.Write(path);
        return path;
    }

    SpectrumImageTexture Texture(const std::string &path, FilterFunction filter, WrapMode wrap) {
        SpectrumImageTexture t;
        t.mipmap = ImageTextureCache::GetMIPMap(path, ColorEncoding::SRGB(), wrap, {filter, 8});
        t.type = SpectrumType::Unbounded;
        return t;
    }

    fs::path dir;
};

TEST_F(ImageTextures, PointLookupFlipsTSoThatVZeroIsTheBottomRow) {
    SpectrumImageTexture t = Texture(WriteQuad(), FilterFunction::Point, WrapMode::Repeat);
    ExpectRGBNear(t.Evaluate(AtUV(0.25f, 0.25f), kLambda), U, 0, 0, 1, 0);  // bottom left: blue
    ExpectRGBNear(t.Evaluate(AtUV(0.75f, 0.25f), kLambda), U, 1, 1, 1, 0);  // bottom right: white
    ExpectRGBNear(t.Evaluate(AtUV(0.25f, 0.75f), kLambda), U, 1, 0, 0, 0);  // top left: red
    ExpectRGBNear(t.Evaluate(AtUV(0.75f, 0.75f), kLambda), U, 0, 1, 0, 0);
}

TEST_F(ImageTextures, WrapModesOutsideTheUnitSquare) {
    std::string path = WriteQuad();
    // u = -0.25 lies in the right column's repeat; clamp holds the left column; black is zero.
    auto point = [&](WrapMode wrap, Float u, Float v) {
        return Texture(path, FilterFunction::Point, wrap).Evaluate(AtUV(u, v), kLambda);
    };
    ExpectRGBNear(point(WrapMode::Repeat, -0.25f, 0.75f), U, 0, 1, 0, 0);
    ExpectRGBNear(point(WrapMode::Clamp, -0.25f, 0.75f), U, 1, 0, 0, 0);
    ExpectRGBNear(point(WrapMode::Black, -0.25f, 0.75f), U, 0, 0, 0, 0);
    ExpectRGBNear(point(WrapMode::Repeat, 1.25f, 1.75f), U, 1, 0, 0, 0);
}

TEST_F(ImageTextures, BilinearBlendsTexelCenters) {
    SpectrumImageTexture t = Texture(WriteQuad(), FilterFunction::Bilinear, WrapMode::Clamp);
    // The image center is equidistant from the four texels.
    ExpectRGBNear(t.Evaluate(AtUV(0.5f, 0.5f), kLambda), U, 0.5f, 0.5f, 0.5f, 1e-6f);
    // Halfway between the bottom texel centers.
    ExpectRGBNear(t.Evaluate(AtUV(0.5f, 0.25f), kLambda), U, 0.5f, 0.5f, 1, 1e-6f);
    // A texel center reproduces the texel.
    ExpectRGBNear(t.Evaluate(AtUV(0.25f, 0.75f), kLambda), U, 1, 0, 0, 1e-6f);
}

TEST_F(ImageTextures, ScaleInvertAndReflectanceClamp) {
    SpectrumImageTexture t = Texture(WriteQuad(), FilterFunction::Point, WrapMode::Repeat);
    t.scale = 3;
    ExpectRGBNear(t.Evaluate(AtUV(0.25f, 0.75f), kLambda), U, 3, 0, 0, 0);  // unbounded: as scaled
    t.type = SpectrumType::Albedo;
    ExpectRGBNear(t.Evaluate(AtUV(0.25f, 0.75f), kLambda), A, 1, 0, 0, 0);  // reflectance: at most 1
    t.scale = 0.5f;
    t.invert = true;
    ExpectRGBNear(t.Evaluate(AtUV(0.25f, 0.75f), kLambda), A, 0.5f, 1, 1, 0);  // 1 - 0.5 * red

    FloatImageTexture f;
    f.mipmap = t.mipmap;
    EXPECT_NEAR(f.Evaluate(AtUV(0.25f, 0.75f)), 1.f / 3, 1e-6f);  // channel average
    f.scale = 6;
    f.invert = true;
    EXPECT_EQ(f.Evaluate(AtUV(0.75f, 0.25f)), 0);  // 1 - 6 clamps to 0
}

TEST_F(ImageTextures, EightBitFilesHonourTheEncoding) {
    // Image::Write stores sRGB codes: this gray is code 128.
    Float code = 128.f / 255;
    Image gray(Point2i(1, 1));
    for (int c = 0; c < 3; ++c) gray.SetChannel(Point2i(0, 0), c, SRGBToLinear(code));
    std::string path = Path("gray.png");
    gray.Write(path);
    auto lookup = [&](ColorEncoding e) {
        return ImageTextureCache::Get(path, e)->GetChannels(Point2i(0, 0))[0];
    };
    EXPECT_NEAR(lookup(ColorEncoding::SRGB()), SRGBToLinear(code), 1e-6f);
    EXPECT_NEAR(lookup(ColorEncoding::Linear()), code, 1e-6f);
    EXPECT_NEAR(lookup(ColorEncoding::Gamma(2.2f)), std::pow(code, 2.2f), 1e-6f);
    // A float file is linear whatever the encoding says.
    std::string exr = Path("gray.exr");
    gray.Write(exr);
    EXPECT_EQ(ImageTextureCache::Get(exr, ColorEncoding::Gamma(2.2f))->GetChannels(Point2i(0, 0))[0], SRGBToLinear(code));
}

TEST_F(ImageTextures, CacheSharesOneImagePerFileAndEncoding) {
    std::string path = WriteQuad();
    auto a = ImageTextureCache::Get(path, ColorEncoding::SRGB());
    auto b = ImageTextureCache::Get(path, ColorEncoding::SRGB());
    auto c = ImageTextureCache::Get(path, ColorEncoding::Linear());
    EXPECT_EQ(a.get(), b.get());
    EXPECT_NE(a.get(), c.get());
    // Deleting the file does not matter once it is cached; after Clear() it must be read again.
    fs::remove(path);
    EXPECT_EQ(ImageTextureCache::Get(path, ColorEncoding::SRGB()).get(), a.get());
    ImageTextureCache::Clear();
    EXPECT_THROW(ImageTextureCache::Get(path, ColorEncoding::SRGB()), std::runtime_error);
}

}  // namespace
}  // namespace pbrt
