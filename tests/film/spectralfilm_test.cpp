// pbrt-v4's spectral film: bands of equal width, named as pbrt-v4 names its EXR channels, each
// the average of the radiance of the wavelengths that fell in it (camera samples) or its
// unbiased estimate (splats); wavelengths sampled uniformly over the range; a sky of constant
// spectral radiance renders every band of every pixel at that radiance; bad parameters are
// errors at the Film directive.
#include "pbrt_ext/film/film.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/ciedata.h"
#include "pbrt_ext/util/error.h"

#include "tests/support/scenefolder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace pbrt {
namespace {

RGBFilm SpectralFilm(int bands, Point2i res = Point2i(2, 1)) {
    RGBFilm film(res, Bounds2i(Point2i(0, 0), res), BoxFilter(), "unused.exr");
    film.EnableSpectralBuckets(400, 720, bands);
    return film;
}

TEST(SpectralBuckets, BandsAndTheirChannelNamesAreUniform) {
    SpectralBuckets buckets(Lambda_min, Lambda_max, 16, 1);
    EXPECT_EQ(buckets.ChannelName(0), "S0.374,688nm");  // pbrt-v4's name for 360-830 nm / 16
    EXPECT_EQ(buckets.ChannelName(15), "S0.815,312nm");
    EXPECT_EQ(buckets.BucketOf(360), 0);
    EXPECT_EQ(buckets.BucketOf(389.3f), 0);
    EXPECT_EQ(buckets.BucketOf(389.5f), 1);
    EXPECT_EQ(buckets.BucketOf(830), 15);
    EXPECT_THROW(SpectralBuckets(300, 830, 16, 1), std::invalid_argument);
    EXPECT_THROW(SpectralBuckets(500, 500, 16, 1), std::invalid_argument);
    EXPECT_THROW(SpectralBuckets(360, 830, 0, 1), std::invalid_argument);
}

TEST(SpectralBuckets, FilmSamplesWavelengthsUniformlyOverItsRange) {
    RGBFilm film = SpectralFilm(8);
    for (Float u : {0.f, 0.3f, 0.99f}) {
        SampledWavelengths lambda = film.SampleWavelengths(u);
        for (int i = 0; i < NSpectrumSamples; ++i) {
            EXPECT_GE(lambda[i], 400);
            EXPECT_LE(lambda[i], 720);
            EXPECT_FLOAT_EQ(lambda.PDF()[i], 1.f / 320);
        }
    }
}

// Camera samples average each band: a sample of radiance 2 in every wavelength and one of 4 give
// 3 x CIE_Y_integral in the bands they reached, with their filter weights 1 and 1; bands no
// wavelength fell in are black.
TEST(SpectralBuckets, CameraSamplesAverageEachBand) {
    RGBFilm film = SpectralFilm(8);
    SampledWavelengths lambda = film.SampleWavelengths(0.1f);  // 4 of the 8 bands
    film.AddSample(Point2i(0, 0), SampledSpectrum(2), lambda, 1);
    film.AddSample(Point2i(0, 0), SampledSpectrum(4), lambda, 1);
    const SpectralBuckets &b = *film.Buckets();
    int reached = 0;
    for (int band = 0; band < 8; ++band) {
        Float v = b.Value(0, band, 0);
        if (v == 0) continue;
        ++reached;
        EXPECT_NEAR(v, 3 * CIE_Y_integral, 1e-3f * CIE_Y_integral) << band;
    }
    EXPECT_EQ(reached, NSpectrumSamples);
    for (int band = 0; band < 8; ++band) EXPECT_EQ(b.Value(1, band, 0), 0);  // the other pixel
}

// Splats of a constant radiance L, each with its own wavelengths, estimate L x CIE_Y_integral in
// every band: 20000 splats (seed 5) at a pixel's centre through the box filter, scaled by
// 1 / 20000, within 3 % (about 6 standard errors).
TEST(SpectralBuckets, SplatsEstimateEachBandsAverage) {
    RGBFilm film = SpectralFilm(8);
    film.EnableSplats();
    std::mt19937 rng(5);
    std::uniform_real_distribution<Float> u(0, 1);
    const int n = 20000;
    for (int i = 0; i < n; ++i) film.AddSplat(Point2f(0.5f, 0.5f), SampledSpectrum(0.5f), film.SampleWavelengths(u(rng)));
    for (int band = 0; band < 8; ++band)
        EXPECT_NEAR(film.Buckets()->Value(0, band, 1.0 / n), 0.5f * CIE_Y_integral,
                    0.03f * 0.5f * CIE_Y_integral) << band;
}

std::filesystem::path Folder() { return TestFolder("pbrt_ext_spectralfilm_test"); }

std::string WriteScene(const std::string &film, const std::string &rest = "") {
    std::filesystem::path scene = Folder() / "scene.pbrt";
    std::ofstream(scene) << "Camera \"perspective\"\n" << film << "\n" << rest << "\nWorldBegin\n"
                         << "LightSource \"infinite\" \"spectrum L\" [360 1 830 1]\n";
    return scene.string();
}

// A sky of constant spectrum: pbrt-v4 normalizes the light to 1 nit (1 / CIE_Y_integral
// W/(m^2 sr nm)), and the bands carry CIE_Y_integral, so every band of every pixel is 1.
TEST(SpectralFilm, ConstantSkyGivesOneInEveryBand) {
    std::string out = (Folder() / "sky.exr").string();
    std::string scene = WriteScene("Film \"spectral\" \"integer xresolution\" 8 \"integer yresolution\" 6 "
                                   "\"integer nbuckets\" 5 \"string filename\" \"" + out + "\"",
                                   "Sampler \"independent\" \"integer pixelsamples\" 4");
    std::unique_ptr<Scene> loaded = LoadScene(scene, RenderOverrides{});
    RenderOptions options;
    options.quiet = true;
    Render(*loaded, options);
    const SpectralBuckets &b = *loaded->film.Buckets();
    ASSERT_EQ(b.Count(), 5);
    for (size_t p = 0; p < 48; ++p)
        for (int band = 0; band < 5; ++band) EXPECT_NEAR(b.Value(p, band, 1), 1, 1e-4f) << p << " " << band;
    loaded->film.WriteImage(ImageMetadata());
    EXRChannels file = ReadEXRChannels(out);
    EXPECT_EQ(file.channels.size(), 3u + 5u);
    EXPECT_EQ(file.stringAttributes["spectralLayoutVersion"], "1.0");
    EXPECT_NEAR(file.channels.at(b.ChannelName(2))[17], 1, 1e-4f);
    // A slice keeps the RGB sums only: no sample range of a spectral film.
    options.samples = SampleRange{0, 2};
    EXPECT_THROW(Render(*loaded, options), std::invalid_argument);
}

std::string LoadError(const std::string &film, const std::string &rest = "") {
    return LoadErrorAfterPath(WriteScene(film, rest));
}

TEST(SpectralFilm, BadParametersAreErrorsAtTheFilm) {
    EXPECT_THAT(LoadError("Film \"spectral\" \"string filename\" \"x.png\""),
                testing::StartsWith(":2:1: error: Film \"spectral\" writes EXR only, not \"x.png\""));
    EXPECT_THAT(LoadError("Film \"spectral\" \"float lambdamin\" 300"),
                testing::StartsWith(":2:1: error: Film \"spectral\": the wavelength range [300, 830] nm"));
    EXPECT_THAT(LoadError("Film \"spectral\" \"integer nbuckets\" 0"),
                testing::StartsWith(":2:1: error: Film \"spectral\": 0 spectral buckets"));
    EXPECT_THAT(LoadError("Film \"spectral\"", "Integrator \"sppm\""),
                testing::HasSubstr("camera samples, which sppm does not give"));
    EXPECT_THAT(LoadError("Film \"spectral\" \"integer xresolution\" 20000 \"integer yresolution\" "
                          "20000 \"integer nbuckets\" 1000"),
                testing::HasSubstr("error: the film's 20000 x 20000 pixels"));
}

}  // namespace
}  // namespace pbrt
