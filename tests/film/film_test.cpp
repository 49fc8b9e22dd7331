// The RGB film: pbrt-v4's crop rounding, weighted averages, the firefly clamp, lock-free tiles,
// and output files covering exactly the pixel bounds.
#include "pbrt_ext/film/film.h"

#include "pbrt_ext/cameras/cameras.h"
#include "pbrt_ext/samplers/samplers.h"

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

namespace pbrt {
namespace {

namespace fs = std::filesystem;

// Fixed wavelengths for the samples below: the film's arithmetic (weights, clamp, tiles) is
// checked on the sensor's RGB of one spectral sample, whose conversion is the same for every
// sample that carries these wavelengths.
const SampledWavelengths kLambda = SampledWavelengths::SampleVisible(0.3f);

// The RGB that one sample of radiance L at lambda records, as film.h documents it: the sensor's
// RGB, to XYZ, to the output colour space. Float rounding differs from the film's one combined
// matrix, hence the relative tolerance kMatrixRounding where it is compared.
RGB Recorded(const RGBFilm &film, const SampledSpectrum &L,
             const SampledWavelengths &lambda = kLambda) {
    RGB sensorRGB = film.Sensor().ToSensorRGB(L, lambda);
    return film.ColorSpace().ToRGB(Mul<XYZ>(film.Sensor().XYZFromSensorRGB, sensorRGB));
}
constexpr Float kMatrixRounding = 1e-5f;

void ExpectRGBNear(RGB a, RGB b, Float relTol, const std::string &what = "") {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(a[c], b[c], relTol * std::max<Float>(1, std::abs(b[c])))
            << what << " channel " << c << ": " << a.ToString() << " vs " << b.ToString();
}

TEST(Film, CropWindowRoundsLikePbrtV4) {
    Point2i res(10, 10);
    EXPECT_EQ(PixelBoundsFromCropWindow(res, Bounds2f(Point2f(0.25f, 0), Point2f(0.75f, 0.5f))),
              Bounds2i(Point2i(3, 0), Point2i(8, 5)));
    EXPECT_EQ(PixelBoundsFromCropWindow(res, Bounds2f(Point2f(0, 0), Point2f(1, 1))),
              Bounds2i(Point2i(0, 0), res));
    EXPECT_EQ(PixelBoundsFromCropWindow(res, Bounds2f(Point2f(-1, 0.5f), Point2f(2, 0.51f))),  // clamped
              Bounds2i(Point2i(0, 5), Point2i(10, 6)));
    EXPECT_THROW(PixelBoundsFromCropWindow(res, Bounds2f(Point2f(0.41f, 0), Point2f(0.45f, 1))),
                 std::runtime_error);
}

TEST(Film, RejectsBadBounds) {
    EXPECT_THROW(RGBFilm(Point2i(0, 4), Bounds2i(Point2i(0, 0), Point2i(1, 1)), BoxFilter(), "x.exr"),
                 std::runtime_error);
    EXPECT_THROW(RGBFilm(Point2i(4, 4), Bounds2i(Point2i(2, 2), Point2i(5, 3)), BoxFilter(), "x.exr"),
                 std::runtime_error);
}

TEST(Film, PixelIsTheWeightedAverage) {
    // The film records each sample's RGB (Recorded) and averages those: two samples of weights 1
    // and 3 give (a + 3 b) / 4.
    RGBFilm film(Point2i(8, 6), Bounds2i(Point2i(2, 1), Point2i(5, 4)), GaussianFilter(), "unused.exr");
    Point2i p(3, 2);
    SampledSpectrum a(1, 2, 3, 4), b(3, 2, 1, 0.5f);
    film.AddSample(p, a, kLambda, 1);
    film.AddSample(p, b, kLambda, 3);
    ExpectRGBNear(film.GetPixelRGB(p), (Recorded(film, a) + 3 * Recorded(film, b)) / 4,
                  kMatrixRounding);
    EXPECT_EQ(film.GetPixelRGB(Point2i(4, 3)), RGB(0, 0, 0));  // no samples: black
    // Negative (Mitchell) weights enter the ratio as they are: (2 * 4 - 1 * 1) / (2 - 1) = 7.
    film.AddSample(Point2i(2, 1), SampledSpectrum(4.f), kLambda, 2);
    film.AddSample(Point2i(2, 1), SampledSpectrum(1.f), kLambda, -1);
    ExpectRGBNear(film.GetPixelRGB(Point2i(2, 1)), Recorded(film, SampledSpectrum(7.f)),
                  kMatrixRounding);
}

TEST(Film, MaxComponentValueScalesKeepingHue) {
    // The limit applies to the sensor's RGB (pbrt-v4's RGBFilm::AddSample): a sample whose largest
    // sensor channel is 40 is scaled by 10 / 40, which scales its output RGB the same (the
    // conversion is linear), keeping its hue; one at 9 is unchanged.
    RGBFilm film(Point2i(2, 2), Bounds2i(Point2i(0, 0), Point2i(2, 2)), BoxFilter(), "unused.exr", 10);
    SampledSpectrum L(4, 2, 0.5f, 1);
    Float largest = film.Sensor().ToSensorRGB(L, kLambda).MaxComponentValue();
    ASSERT_GT(largest, 0);
    SampledSpectrum bright = L * (40 / largest), dim = L * (9 / largest);
    film.AddSample(Point2i(0, 0), bright, kLambda, 1);
    ExpectRGBNear(film.GetPixelRGB(Point2i(0, 0)), Recorded(film, bright) * (10.f / 40),
                  kMatrixRounding);
    film.AddSample(Point2i(1, 0), dim, kLambda, 1);  // below the limit: unchanged
    ExpectRGBNear(film.GetPixelRGB(Point2i(1, 0)), Recorded(film, dim), kMatrixRounding);
}

// A constant radiance reconstructs exactly, whatever the filter (its weights cancel in the
// ratio, even Mitchell's negative ones), through the real sampler -> filter -> film path. The
// wavelengths are held fixed, so that every sample records the same RGB.
TEST(Film, ConstantRadianceReconstructsExactly) {
    std::vector<Filter> filters = {BoxFilter(), GaussianFilter(), MitchellFilter(), TriangleFilter()};
    Point2i res(6, 5);
    for (const Filter &filter : filters) {
        RGBFilm film(res, Bounds2i(Point2i(0, 0), res), filter, "unused.exr");
        Sampler sampler = ZSobolSampler(16, res);
        for (Point2i p : film.PixelBounds())
            for (int i = 0; i < sampler.SamplesPerPixel(); ++i) {
                sampler.StartPixelSample(p, i);
                CameraSample cs = GetCameraSample(sampler, p, film.GetFilter());
                film.AddSample(p, SampledSpectrum(0.25f, 0.5f, 2, 1), kLambda, cs.filterWeight);
            }
        RGB expected = Recorded(film, SampledSpectrum(0.25f, 0.5f, 2, 1));
        for (Point2i p : film.PixelBounds())
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(film.GetPixelRGB(p)[c], expected[c],
                            1e-5f * std::max<Float>(1, std::abs(expected[c])))
                    << filter.ToString();
    }
}

// Threads writing disjoint tiles give the same film as one thread writing everything.
TEST(Film, DisjointTilesNeedNoLocks) {
    Point2i res(64, 48);
    Bounds2i all(Point2i(0, 0), res);
    auto render = [&](RGBFilm &film, Bounds2i tile) {
        Sampler sampler = IndependentSampler(8, 1);
        for (Point2i p : tile)
            for (int i = 0; i < 8; ++i) {
                sampler.StartPixelSample(p, i);
                SampledWavelengths lambda = film.SampleWavelengths(sampler.Get1D());
                Point2f u = sampler.Get2D();
                film.AddSample(p, SampledSpectrum(u.x, u.y, Float(p.x + p.y), 1 - u.x), lambda,
                               0.5f + u.x);
            }
    };
    RGBFilm serial(res, all, BoxFilter(), "unused.exr"), parallel(res, all, BoxFilter(), "unused.exr");
    render(serial, all);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back(render, std::ref(parallel), Bounds2i(Point2i(0, 12 * t), Point2i(64, 12 * (t + 1))));
    for (std::thread &t : threads) t.join();
    for (Point2i p : all) ASSERT_EQ(parallel.GetPixelRGB(p), serial.GetPixelRGB(p));
}

// Splats from many threads into one pixel all arrive: the sum is exact (each adds 1, which
// doubles sum without rounding). With sums per thread (the film's choice where they fit) and with
// one set of atomic sums.
class ConcurrentSplats : public testing::TestWithParam<bool> {};

TEST_P(ConcurrentSplats, ToOnePixelLoseNothing) {
    Point2i res(4, 4);
    RGBFilm film(res, Bounds2i(Point2i(0, 0), res), BoxFilter(), "unused.exr");
    film.EnableSplats(/*perThreadSums=*/GetParam());
    const SampledSpectrum L(1.f);
    const RGB one = film.Sensor().ToSensorRGB(L, kLambda);
    const int threads = 8, perThread = 100000;
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (int i = 0; i < perThread; ++i)
                film.AddSplat(Point2f(2.25f, 1.75f), L, kLambda);
        });
    for (std::thread &t : pool) t.join();
    // The splat scale of one splat per pixel leaves the total: the pixel holds all of them.
    film.SetSplatScale(1.0 / (double(threads) * perThread));
    RGBFilm reference(res, Bounds2i(Point2i(0, 0), res), BoxFilter(), "unused.exr");
    reference.EnableSplats();
    reference.AddSplat(Point2f(2.25f, 1.75f), L, kLambda);
    for (Point2i p : Bounds2i(Point2i(0, 0), res))
        EXPECT_EQ(film.GetPixelRGB(p), reference.GetPixelRGB(p)) << p.x << ", " << p.y;
    EXPECT_GT(reference.GetPixelRGB(Point2i(2, 1)).Average(), 0);
    EXPECT_GT(one.Average(), 0);
}

INSTANTIATE_TEST_SUITE_P(Film, ConcurrentSplats, testing::Values(true, false),
                         [](const testing::TestParamInfo<bool> &param) {
                             return param.param ? "PerThreadSums" : "AtomicSums";
                         });

// A splat spreads over the pixels the filter covers by the filter's normalized weights: its
// total over the film is what a camera sample of the same radiance adds to its pixel.
TEST(Film, SplatSpreadsByTheNormalizedFilter) {
    // The wide Gaussian spans more pixels than AddSplat keeps its weights for on the stack.
    Point2i res(48, 48);
    Bounds2i all(Point2i(0, 0), res);
    for (Filter filter : {Filter(BoxFilter()), Filter(GaussianFilter()), Filter(MitchellFilter()),
                          Filter(TriangleFilter()), Filter(GaussianFilter(Vector2f(12, 10), 4))}) {
        RGBFilm splatted(res, all, filter, "unused.exr"), sampled(res, all, filter, "unused.exr");
        splatted.EnableSplats();
        const SampledSpectrum L(0.5f, 1.f, 2.f, 0.25f);
        splatted.AddSplat(Point2f(23.3f, 24.9f), L, kLambda);
        sampled.AddSample(Point2i(23, 24), L, kLambda, 1);
        double total = 0;
        int touched = 0;
        for (Point2i p : all) {
            total += splatted.GetPixelRGB(p).Average();
            touched += splatted.GetPixelRGB(p).Average() != 0;
        }
        EXPECT_NEAR(total, sampled.GetPixelRGB(Point2i(23, 24)).Average(),
                    0.02 * sampled.GetPixelRGB(Point2i(23, 24)).Average())
            << filter.ToString();
        EXPECT_LE(touched, (2 * filter.Radius().x + 1) * (2 * filter.Radius().y + 1)) << filter.ToString();
    }
}

TEST(Film, WritesOnlyThePixelBounds) {
    fs::path dir = fs::temp_directory_path() / ("pbrt_film_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Point2i res(10, 8);
    Bounds2i crop(Point2i(3, 2), Point2i(7, 5));
    for (std::string ext : {".exr", ".png"}) {
        std::string path = (dir / ("crop" + ext)).string();
        RGBFilm film(res, crop, BoxFilter(), path);
        // A different grey-ish value per pixel, (x + 10 y) / 100 times a spectrum whose RGB
        // has largest component 1, so that the PNG (in [0, 1]) keeps it too.
        SampledSpectrum L(1.f);
        RGB unit = Recorded(film, L);
        ASSERT_GT(unit.MinComponentValue(), 0) << unit.ToString();
        L /= unit.MaxComponentValue();
        for (Point2i p : crop) film.AddSample(p, L * ((p.x + 10 * p.y) / 100.f), kLambda, 1);
        ImageMetadata md;
        md.samplesPerPixel = 1;
        film.WriteImage(md);
        Image back = Image::Read(path);
        ASSERT_EQ(back.Resolution(), Point2i(4, 3)) << ext;
        Float tol = ext == ".exr" ? 0 : 0.01f;
        // Image pixel (0, 0) is film pixel (3, 2); the last, (3, 2), is film pixel (6, 4).
        for (Point2i q : Bounds2i(Point2i(0, 0), Point2i(4, 3)))
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(back.GetChannel(q, c), film.GetPixelRGB(crop.pMin + Vector2i(q))[c], tol)
                    << ext << " pixel " << q.x << ", " << q.y << " channel " << c;
        Float unitMax = unit.MaxComponentValue();
        EXPECT_NEAR(back.GetChannel(Point2i(0, 0), 0), 0.23f * unit[0] / unitMax, tol + 1e-6f) << ext;
        EXPECT_NEAR(back.GetChannel(Point2i(3, 2), 1), 0.46f * unit[1] / unitMax, tol + 1e-6f) << ext;
        if (ext == ".exr") {
            Imf::InputFile file(path.c_str());
            EXPECT_EQ(file.header().dataWindow().min, Imath::V2i(3, 2));
            EXPECT_EQ(file.header().displayWindow().max, Imath::V2i(9, 7));
        }
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pbrt
