// The RGB film: pbrt-v4's crop rounding, weighted averages, the firefly clamp, lock-free tiles,
// and output files covering exactly the pixel bounds.
#include "pbrt_ext/film.h"

#include "pbrt_ext/cameras.h"
#include "pbrt_ext/samplers.h"

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

namespace pbrt {
namespace {

namespace fs = std::filesystem;

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
    RGBFilm film(Point2i(8, 6), Bounds2i(Point2i(2, 1), Point2i(5, 4)), GaussianFilter(), "unused.exr");
    Point2i p(3, 2);
    film.AddSample(p, SampledSpectrum(1, 2, 3), 1);
    film.AddSample(p, SampledSpectrum(3, 2, 1), 3);
    EXPECT_EQ(film.GetPixelRGB(p), SampledSpectrum(2.5f, 2, 1.5f));
    EXPECT_EQ(film.GetPixelRGB(Point2i(4, 3)), SampledSpectrum(0.f));  // no samples: black
    // Negative (Mitchell) weights enter the ratio as they are.
    film.AddSample(Point2i(2, 1), SampledSpectrum(4.f), 2);
    film.AddSample(Point2i(2, 1), SampledSpectrum(1.f), -1);
    EXPECT_EQ(film.GetPixelRGB(Point2i(2, 1)), SampledSpectrum(7.f));
}

TEST(Film, MaxComponentValueScalesKeepingHue) {
    RGBFilm film(Point2i(2, 2), Bounds2i(Point2i(0, 0), Point2i(2, 2)), BoxFilter(), "unused.exr", 10);
    film.AddSample(Point2i(0, 0), SampledSpectrum(40, 20, 5), 1);
    EXPECT_EQ(film.GetPixelRGB(Point2i(0, 0)), SampledSpectrum(10, 5, 1.25f));
    film.AddSample(Point2i(1, 0), SampledSpectrum(9, 1, 0), 1);  // below the limit: unchanged
    EXPECT_EQ(film.GetPixelRGB(Point2i(1, 0)), SampledSpectrum(9, 1, 0));
}

// A constant radiance reconstructs exactly, whatever the filter (its weights cancel in the
// ratio, even Mitchell's negative ones), through the real sampler -> filter -> film path.
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
                film.AddSample(p, SampledSpectrum(0.25f, 0.5f, 2), cs.filterWeight);
            }
        for (Point2i p : film.PixelBounds())
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(film.GetPixelRGB(p)[c], SampledSpectrum(0.25f, 0.5f, 2)[c], 1e-5f) << filter.ToString();
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
                Point2f u = sampler.Get2D();
                film.AddSample(p, SampledSpectrum(u.x, u.y, Float(p.x + p.y)), 0.5f + u.x);
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

TEST(Film, WritesOnlyThePixelBounds) {
    fs::path dir = fs::temp_directory_path() / ("pbrt_film_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Point2i res(10, 8);
    Bounds2i crop(Point2i(3, 2), Point2i(7, 5));
    for (std::string ext : {".exr", ".png"}) {
        std::string path = (dir / ("crop" + ext)).string();
        RGBFilm film(res, crop, BoxFilter(), path);
        for (Point2i p : crop) film.AddSample(p, SampledSpectrum(p.x / 10.f, p.y / 10.f, 0.5f), 1);
        ImageMetadata md;
        md.samplesPerPixel = 1;
        film.WriteImage(md);
        Image back = Image::Read(path);
        ASSERT_EQ(back.Resolution(), Point2i(4, 3)) << ext;
        Float tol = ext == ".exr" ? 0 : 0.01f;
        EXPECT_NEAR(back.GetChannel(Point2i(0, 0), 0), 0.3f, tol) << ext;
        EXPECT_NEAR(back.GetChannel(Point2i(3, 2), 1), 0.4f, tol) << ext;
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
