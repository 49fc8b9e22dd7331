// Metropolis light transport (pbrt-v4's mlt) end to end. A diffuse sphere in a uniform
// environment (a furnace: radiance rho L on the sphere, L around it) has a closed form, and paths
// of nearly equal luminance, so the bootstrap normalizes within a fraction of a percent: the
// image mean must match within 1 %. On the Cornell box, where a few paths that see the light
// carry most of the luminance, the bootstrap's own noise decides the mean: with 200000 bootstrap
// samples, seeds 0 to 2 gave means within 4 % of the path tracer's (within 7 % with 20000): it
// must match within 5 % at seed 0. A render is a function of the seed and the threads; sample
// slices and bad parameters are refused with a message.
#include "tests/support/imagestats.h"
#include "tests/support/scenefolder.h"
#include "tests/support/scenes.h"

#include "pbrt_ext/render.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

using namespace pbrt;
using namespace pbrt::testscenes;

namespace {

constexpr Float kAlbedo = 0.5f;
const Point2i kResolution(32, 32);

IntegratorOptions MLT(int mutationsPerPixel, int seed = 0) {
    IntegratorOptions o;
    o.type = IntegratorType::MLT;
    o.maxDepth = 5;
    o.mlt.bootstrapSamples = 20000;
    o.mlt.chains = 256;
    o.mlt.mutationsPerPixel = mutationsPerPixel;
    o.mlt.seed = seed;
    return o;
}

std::unique_ptr<Scene> Furnace(IntegratorOptions options, int spp = 1) {
    SceneBuilder builder(LookingAt(Point3f(0, 0, 4), Point3f(0, 0, 0), 30, kResolution),
                         BoxFilteredFilm(kResolution), ZSobolSampler(spp, kResolution));
    builder.AddSphere(UnitSphereAt(Point3f(0, 0, 0)),
                      builder.AddMaterial(DiffuseMaterial{Spectrum(kAlbedo)}));
    builder.AddLight(UniformInfiniteLight(Spectrum(1.f), 1));
    builder.SetIntegrator(options);
    auto scene = builder.Build();
    Render(*scene, {0, true});
    return scene;
}

TEST(MLT, FurnaceMeanMatchesTheClosedForm) {
    auto reference = Furnace(PathTracer(5), 64);  // rho L and L, with little noise
    auto mlt = Furnace(MLT(64));
    RGB expected = MeanRGB(reference->film), got = MeanRGB(mlt->film);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 0.01 * expected[c]) << "channel " << c;
}

// The mean of the Cornell box rendered by mlt with these options, over the path tracer's, per
// channel.
RGB CornellBoxMeanRatio(IntegratorOptions options) {
    auto reference = CornellBox(kResolution, 1024, PathTracer(5));
    Render(*reference, {0, true});
    options.mlt.bootstrapSamples = 200000;
    auto mlt = CornellBox(kResolution, 1, options);
    Render(*mlt, {0, true});
    RGB expected = MeanRGB(reference->film), got = MeanRGB(mlt->film);
    return RGB(got[0] / expected[0], got[1] / expected[1], got[2] / expected[2]);
}

TEST(MLT, CornellBoxMeanMatchesThePathTracers) {
    RGB ratio = CornellBoxMeanRatio(MLT(256));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ratio[c], 1, 0.05) << "channel " << c;
}

// The test can fail: a depth limit of 1 loses a quarter of the box's light.
TEST(MLT, CornellBoxMeanTellsAShallowerDepthApart) {
    IntegratorOptions shallow = MLT(256);
    shallow.maxDepth = 1;
    EXPECT_LT(CornellBoxMeanRatio(shallow)[1], 0.9);
}

TEST(MLT, ARenderIsAFunctionOfTheSeedAndTheThreads) {
    auto a = Furnace(MLT(8, 1)), b = Furnace(MLT(8, 1)), c = Furnace(MLT(8, 2));
    int differ = 0;
    for (Point2i p : a->film.PixelBounds()) {
        RGB ra = a->film.GetPixelRGB(p), rb = b->film.GetPixelRGB(p), rc = c->film.GetPixelRGB(p);
        for (int ch = 0; ch < 3; ++ch) {
            ASSERT_EQ(ra[ch], rb[ch]) << "pixel " << p.x << " " << p.y;
            differ += ra[ch] != rc[ch];
        }
    }
    EXPECT_GT(differ, 0) << "another seed gave the same image";
}

TEST(MLT, RendersNoSampleRange) {
    auto scene = CornellBox(Point2i(4, 4), 1, MLT(4));
    RenderOptions options{0, true};
    options.samples = SampleRange{0, 2};
    EXPECT_THAT([&] { SamplesToRender(*scene, options); },
                testing::ThrowsMessage<std::invalid_argument>(testing::HasSubstr("mlt renders no sample range")));
}

std::string WriteScene(const std::string &integrator) {
    std::filesystem::path file = TestFolder("pbrt_ext_mlt_test") / "scene.pbrt";
    std::ofstream(file) << "Camera \"perspective\"\n" << integrator << "\nWorldBegin\n"
                        << "LightSource \"infinite\"\nShape \"sphere\"\n";
    return file.string();
}

TEST(MLT, BadParametersAreErrorsAtTheirLine) {
    EXPECT_THAT(LoadErrorAfterPath(WriteScene("Integrator \"mlt\" \"float sigma\" 0")),
                testing::StartsWith(":2:18: error: mlt \"sigma\" must be positive"));
    EXPECT_THAT(LoadErrorAfterPath(WriteScene("Integrator \"mlt\" \"float largestepprobability\" 1.5")),
                testing::StartsWith(":2:18: error: mlt \"largestepprobability\" must be in [0, 1]"));
    EXPECT_THAT(LoadErrorAfterPath(WriteScene("Integrator \"mlt\" \"integer chains\" 0")),
                testing::StartsWith(":2:18: error: mlt \"chains\" must be at least 1"));
    EXPECT_THAT(LoadErrorAfterPath(WriteScene("Integrator \"mlt\" \"integer bootstrapsamples\" -3")),
                testing::StartsWith(":2:18: error: mlt \"bootstrapsamples\" must be at least 1"));
}

TEST(MLT, SppSetsTheMutationsPerPixel) {
    RenderOverrides overrides;
    overrides.spp = 7;
    auto scene = LoadScene(WriteScene("Integrator \"mlt\" \"integer mutationsperpixel\" 100"), overrides);
    EXPECT_EQ(scene->integratorOptions.mlt.mutationsPerPixel, 7);
    EXPECT_EQ(SamplesToRender(*scene, {}).Count(), 7);
}

}  // namespace
