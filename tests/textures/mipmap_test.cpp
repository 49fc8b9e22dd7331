// Texture filtering: the pyramid pbrt-v4 builds (resized up to powers of two, halved by 2x2
// averages, each level in the file's texel format), its point, bilinear, trilinear and EWA
// lookups, the filtered checkerboard, and the filters driven by a camera's ray differentials
// over a plane seen at a grazing angle.
#include "pbrt_ext/cameras/cameras.h"
#include "pbrt_ext/interaction.h"
#include "pbrt_ext/textures/mipmap.h"
#include "pbrt_ext/textures/textures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace pbrt {
namespace {

// Uniform random texels in [0, 1), fixed seed.
Image RandomImage(Point2i res, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Float> u(0, 1);
    Image image(res);
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, u(rng));
    return image;
}

RGB Mean(const Image &image) {
    RGB sum;
    Point2i res = image.Resolution();
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) sum += image.GetChannels(Point2i(x, y));
    return sum / Float(res.x * res.y);
}

void ExpectRGBNear(RGB a, RGB b, Float tol, const std::string &what = "") {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], tol) << what << " channel " << c;
}

// A footprint whose widest extent selects level `level` of a pyramid of nLevels:
// width 2 max|d| = 2^(level - (nLevels - 1)).
Float HalfWidthForLevel(Float level, int nLevels) {
    return std::exp2(level - Float(nLevels - 1)) / 2;
}

TEST(ImagePyramid, LevelsHalveFromThePowerOfTwoAboveDownToOneTexel) {
    std::vector<Image> pyramid = Image::GeneratePyramid(RandomImage(Point2i(48, 20), 1), WrapMode::Repeat);
    std::vector<Point2i> expected = {{64, 32}, {32, 16}, {16, 8}, {8, 4}, {4, 2}, {2, 1}, {1, 1}};
    ASSERT_EQ(pyramid.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(pyramid[i].Resolution(), expected[i]) << i;
}

// Box filtering by 2x2 preserves the mean exactly: every level's mean is its parent's.
TEST(ImagePyramid, EachLevelsMeanEqualsItsParents) {
    for (Point2i res : {Point2i(64, 32), Point2i(48, 20), Point2i(1, 16)}) {
        std::vector<Image> pyramid = Image::GeneratePyramid(RandomImage(res, 2), WrapMode::Clamp);
        for (size_t i = 1; i < pyramid.size(); ++i)
            ExpectRGBNear(Mean(pyramid[i]), Mean(pyramid[i - 1]), 1e-5f, "level " + std::to_string(i));
    }
}

// Resampling up with normalized Lanczos weights keeps a constant image constant, whatever the
// wrap mode reads outside (black would darken the border, so it is not among them).
TEST(ImagePyramid, ResizingUpKeepsAConstantImage) {
    Image gray(Point2i(5, 3));
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x)
            for (int c = 0; c < 3; ++c) gray.SetChannel(Point2i(x, y), c, 0.25f);
    for (WrapMode wrap : {WrapMode::Clamp, WrapMode::Repeat}) {
        Image big = gray.FloatResizeUp(Point2i(8, 4), wrap);
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 8; ++x) ExpectRGBNear(big.GetChannels(Point2i(x, y)), RGB(0.25f, 0.25f, 0.25f), 1e-6f);
    }
}

// An 8-bit file's levels stay 8-bit (pbrt-v4 keeps the file's format), encoded with the file's
// encoding: each level's mean is its parent's to within half a code of rounding.
TEST(ImagePyramid, EightBitLevelsStayEightBit) {
    Image image = RandomImage(Point2i(32, 32), 3);
    std::string path = testing::TempDir() + "mipmap_test_random.png";
    image.Write(path);  // 8-bit sRGB
    for (ColorEncoding encoding : {ColorEncoding::Linear(), ColorEncoding::SRGB()}) {
        std::vector<Image> pyramid = Image::GeneratePyramid(Image::Read(path, encoding), WrapMode::Repeat);
        ASSERT_EQ(pyramid.size(), 6u);
        // The largest step of a code in linear values, over half of it.
        Float halfCode = encoding == ColorEncoding::Linear() ? 0.5f / 255 : 0.5f * (1 - SRGBToLinear(254.f / 255));
        for (size_t i = 0; i < pyramid.size(); ++i) {
            EXPECT_TRUE(pyramid[i].Is8Bit()) << i;
            if (i > 0) ExpectRGBNear(Mean(pyramid[i]), Mean(pyramid[i - 1]), halfCode, encoding.ToString());
        }
    }
    std::remove(path.c_str());
}

class MIPMapLookups : public testing::Test {
  protected:
    MIPMap Make(FilterFunction filter, Float maxAnisotropy = 8) {
        return MIPMap(RandomImage(Point2i(64, 64), 4), WrapMode::Repeat, {filter, maxAnisotropy});
    }
    const std::vector<Point2f> points = {{0.3f, 0.7f}, {0.51f, 0.12f}, {0.93f, 0.48f}, {0.05f, 0.99f}};
};

TEST_F(MIPMapLookups, TrilinearAtIntegerLevelsIsBilinearThereAndBlendsBetween) {
    MIPMap trilinear = Make(FilterFunction::Trilinear);
    int n = trilinear.Levels();
    ASSERT_EQ(n, 7);
    for (Point2f st : points)
        for (int level = 0; level < n - 1; ++level) {
            Float d = HalfWidthForLevel(Float(level), n);
            ExpectRGBNear(trilinear.Filter(st, Vector2f(d, 0), Vector2f(0, d / 2)), trilinear.Bilerp(level, st), 1e-6f);
            // Halfway up to the next level: the average of the two (also between levels 0 and 1).
            Float h = HalfWidthForLevel(level + 0.5f, n);
            RGB half = (trilinear.Bilerp(level, st) + trilinear.Bilerp(level + 1, st)) / 2;
            ExpectRGBNear(trilinear.Filter(st, Vector2f(0, h), Vector2f(h, 0)), half, 1e-5f);
        }
}

TEST_F(MIPMapLookups, BilinearAndPointReadTheLevelBelowTheFootprint) {
    MIPMap bilinear = Make(FilterFunction::Bilinear), point = Make(FilterFunction::Point);
    int n = bilinear.Levels();
    for (Point2f st : points) {
        Float d = HalfWidthForLevel(2.7f, n);
        ExpectRGBNear(bilinear.Filter(st, Vector2f(d, 0), Vector2f(0, d)), bilinear.Bilerp(2, st), 1e-6f);
        // Point: the texel of level 2 (16x16) containing st.
        Point2i texel(int(st[0] * 16), int(st[1] * 16));
        ExpectRGBNear(point.Filter(st, Vector2f(d, 0), Vector2f(0, d)), point.Texel(2, texel), 0);
        // No footprint reads the finest level.
        ExpectRGBNear(bilinear.Filter(st, Vector2f(0, 0), Vector2f(0, 0)), bilinear.Bilerp(0, st), 0);
    }
    // A footprint wider than the image reads the one texel on top: the image's mean.
    ExpectRGBNear(bilinear.Filter(points[0], Vector2f(2, 0), Vector2f(0, 2)), Mean(bilinear.Level(0)), 1e-5f);
}

// A circular footprint of radius r texels at level k: the weights are the truncated Gaussian
// exp(-2 q) - exp(-2) of q = d^2 / (r^2 + 1), d the distance from st to the texel's centre,
// over every texel with q < 1; summed here over the whole level, without EWA's bounding box.
RGB GaussianSum(const MIPMap &mipmap, int level, Point2f st, Float r) {
    Point2i res = mipmap.LevelResolution(level);
    Float sx = st[0] * res.x - 0.5f, sy = st[1] * res.y - 0.5f;
    RGB sum;
    double sumW = 0;
    for (int y = -res.y; y < 2 * res.y; ++y)
        for (int x = -res.x; x < 2 * res.x; ++x) {
            double q = (Sqr(x - sx) + Sqr(y - sy)) / (Sqr(r) + 1);
            if (q >= 1) continue;
            double w = std::exp(-2 * q) - std::exp(-2.0);
            sum += Float(w) * mipmap.Texel(level, Point2i(x, y));
            sumW += w;
        }
    return sum / Float(sumW);
}

TEST_F(MIPMapLookups, EWAWithACircularFootprintIsTheGaussianWeightedSum) {
    MIPMap ewa = Make(FilterFunction::EWA);
    int n = ewa.Levels();
    for (Point2f st : points)
        for (int level : {0, 2, 4}) {
            // The minor axis decides the level: radius 2^(level - (n-1)) in st, one texel of it.
            Float radius = std::exp2(Float(level - (n - 1)));
            RGB direct = GaussianSum(ewa, level, st, 1);
            ExpectRGBNear(ewa.Filter(st, Vector2f(radius, 0), Vector2f(0, radius)), direct, 1e-5f,
                          "level " + std::to_string(level));
            // Rotating the axes changes nothing for a circle.
            Float c = radius * std::cos(0.6f), s = radius * std::sin(0.6f);
            ExpectRGBNear(ewa.Filter(st, Vector2f(c, s), Vector2f(-s, c)), direct, 1e-5f);
        }
}

TEST_F(MIPMapLookups, EWALengthensTheMinorAxisToMaxAnisotropy) {
    MIPMap ewa = Make(FilterFunction::EWA, 8);
    Vector2f major(0.2f, 0.1f);
    Vector2f minorDir = Normalize(Vector2f(-0.1f, 0.2f));
    RGB thin = ewa.Filter(points[1], major, minorDir * 1e-4f);
    RGB clamped = ewa.Filter(points[1], major, minorDir * (Length(major) / 8));
    ExpectRGBNear(thin, clamped, 1e-6f);
}

// The 1D checks (+1 on even squares, -1 on odd ones) integrated numerically against a tent of
// radius r around x.
Float TentFilteredChecks(Float x, Float r) {
    constexpr int n = 20000;
    double sum = 0, sumW = 0;
    for (int i = 0; i < n; ++i) {
        double u = -r + 2 * r * (i + 0.5) / n, w = r - std::abs(u);
        sum += w * ((int(std::floor(x + u)) & 1) ? -1 : 1);
        sumW += w;
    }
    return Float(sum / sumW);
}

// pbrt-v4's checkerboard weighs tex2 by 1/2 - (filtered s checks)(filtered t checks)/2, each
// filtered by a tent of 1.5 times the footprint's extent on its axis.
TEST(FilteredCheckerboard, IsTheChecksIntegratedAgainstATent) {
    UVMapping mapping;
    for (auto [u, du] : {std::pair{0.3f, 0.4f}, {1.9f, 0.25f}, {-0.6f, 1.3f}, {5.01f, 0.05f}}) {
        TextureEvalContext ctx;
        ctx.uv = Point2f(u, 0.5f);  // t in the middle of an even square, no footprint in t
        ctx.dudx = du;
        ctx.dudy = du / 3;
        Float expected = 0.5f - TentFilteredChecks(u, 1.5f * du) / 2;
        EXPECT_NEAR(Checkerboard(mapping, ctx), expected, 1e-3f) << "u " << u;
    }
    // A footprint many checks wide averages to grey; none is the point value.
    TextureEvalContext wide;
    wide.uv = Point2f(0.3f, 0.2f);
    wide.dudx = wide.dvdy = 40;
    EXPECT_NEAR(Checkerboard(mapping, wide), 0.5f, 0.02f);
    TextureEvalContext none;
    none.uv = Point2f(1.3f, 0.2f);
    EXPECT_EQ(Checkerboard(mapping, none), 1);
}

// A checkerboard image on the plane y = -1 seen by a pinhole camera tilted down so that the
// top of the film grazes the plane at 5 degrees. uv = (x, z) / 4, 8-texel checks.
class GrazingPlane : public testing::Test {
  protected:
    static constexpr int kRes = 48;
    Camera camera = PerspectiveCamera(RotateX(25), Point2i(kRes, kRes), DefaultScreenWindow(Point2i(kRes, kRes)), 40);

    static Image CheckerImage() {
        Image image(Point2i(128, 128));
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x)
                for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, Float(((x / 8) + (y / 8)) & 1));
        return image;
    }
    static FloatImageTexture Texture(FilterFunction filter) {
        FloatImageTexture t;
        t.mipmap = std::make_shared<MIPMap>(CheckerImage(), WrapMode::Repeat, MIPMapFilterOptions{filter, 8});
        return t;
    }
    // The texture where the ray through pFilm meets the plane, with the footprint of its
    // differentials, or at the point alone.
    Float Lookup(const FloatImageTexture &texture, Point2f pFilm, bool footprint) const {
        CameraSample cs;
        cs.pFilm = pFilm;
        RayDifferential ray = camera.GenerateRayDifferential(cs)->ray;
        SurfaceInteraction si;
        si.p = ray(-1 / ray.d.y);
        si.n = si.shading.n = Normal3f(0, 1, 0);
        si.dpdu = Vector3f(4, 0, 0);
        si.dpdv = Vector3f(0, 0, 4);
        si.uv = Point2f(si.p.x / 4, si.p.z / 4);
        if (footprint) {
            EXPECT_TRUE(si.DifferentialsFrom(ray));
        }
        return texture.Evaluate(TextureEvalContext(si));
    }
};

// Against the pixel's true average (64x64 stratified point samples of the finest level), one
// jittered sample per pixel filtered by EWA errs less than one filtered bilinearly (isotropic,
// blurred along the footprint's short axis) or point sampled at the finest level (aliased).
TEST_F(GrazingPlane, EWAAtOneSampleIsCloserToThePixelAverageThanBilinear) {
    FloatImageTexture point = Texture(FilterFunction::Point), bilinear = Texture(FilterFunction::Bilinear),
                      ewa = Texture(FilterFunction::EWA);
    std::mt19937 rng(7);
    std::uniform_real_distribution<Float> jitter(0, 1);
    double errPoint = 0, errBilinear = 0, errEWA = 0;
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
            double reference = 0;
            for (int j = 0; j < 64; ++j)
                for (int i = 0; i < 64; ++i)
                    reference += Lookup(point, Point2f(x + (i + 0.5f) / 64, y + (j + 0.5f) / 64), false);
            reference /= 64 * 64;
            Point2f p(x + jitter(rng), y + jitter(rng));
            errPoint += Sqr(Lookup(point, p, false) - reference);
            errBilinear += Sqr(Lookup(bilinear, p, true) - reference);
            errEWA += Sqr(Lookup(ewa, p, true) - reference);
        }
    // Measured with seed 7: point 249, bilinear 71.6, EWA 57.1.
    EXPECT_LT(errEWA, errBilinear) << "point " << errPoint << " bilinear " << errBilinear << " ewa " << errEWA;
    EXPECT_LT(errEWA, 0.5 * errPoint) << "point " << errPoint << " bilinear " << errBilinear << " ewa " << errEWA;
}

}  // namespace
}  // namespace pbrt
