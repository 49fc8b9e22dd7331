// pbrt-v4's simplevolpath: media alone, by delta tracking with the hero wavelength. A medium that
// scatters without absorbing, in a uniform environment, leaves the environment as it was (a
// white furnace); a chromatic, absorbing medium gives the volumetric path tracer's image; and
// a scene whose surfaces scatter light is refused before rendering, as pbrt-v4 refuses it.
// Thresholds: 4 standard errors of each channel's mean difference (tests/support/imagestats.h).
#include "tests/support/imagestats.h"
#include "tests/support/scenes.h"

#include "pbrt_ext/render.h"

#include <gtest/gtest.h>
#include <gmock/gmock.h>

using namespace pbrt;
using namespace pbrt::testscenes;

namespace {

const Point2i kResolution(24, 24);

// A unit sphere of medium (or of nothing) bounded by an interface, under a uniform environment.
std::unique_ptr<Scene> SphereOfMedium(std::optional<Medium> medium, IntegratorType type, int spp) {
    SceneBuilder builder(LookingAt(Point3f(0, 0, 4), Point3f(0, 0, 0), 35, kResolution),
                         BoxFilteredFilm(kResolution), ZSobolSampler(spp, kResolution));
    if (medium)
        builder.SetMediumInterface(MediumInterface(builder.AddMedium(std::move(*medium)), -1));
    builder.AddSphere(UnitSphereAt(Point3f(0, 0, 0)), -1);
    builder.AddLight(UniformInfiniteLight(Spectrum(0.8f), 1));
    IntegratorOptions o;
    o.type = type;
    o.maxDepth = 1000;
    builder.SetIntegrator(o);
    auto scene = builder.Build();
    Render(*scene, {0, true});
    return scene;
}

void ExpectSameMeans(const RGBFilm &film, const RGBFilm &reference) {
    ChannelDifference d = MeanDifference(film, reference);
    for (int c = 0; c < 3; ++c)
        EXPECT_LT(d.Z(c), 4) << "channel " << c << ": mean difference " << d.mean[c] << " +- "
                             << d.standardError[c];
}

// Every path leaves the medium with its throughput unchanged (a phase function's sample weight
// is 1) and sees the environment: each pixel is the empty scene's, to rounding.
TEST(SimpleVolPath, AScatteringMediumInAFurnaceLeavesTheEnvironment) {
    for (Float g : {0.f, 0.7f}) {
        auto furnace = SphereOfMedium(HomogeneousMedium(Spectrum(0.f), Spectrum(3.f), 1, Spectrum(0.f), 0, g),
                                      IntegratorType::SimpleVolPath, 16);
        auto empty = SphereOfMedium(std::nullopt, IntegratorType::SimpleVolPath, 16);
        for (Point2i p : furnace->film.PixelBounds())
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(furnace->film.GetPixelRGB(p)[c], empty->film.GetPixelRGB(p)[c],
                            1e-5f * empty->film.GetPixelRGB(p)[c])
                    << "g " << g << ", pixel " << p.x << " " << p.y << ", channel " << c;
    }
}

TEST(SimpleVolPath, GivesTheVolumetricPathTracersImage) {
    auto chromatic = [] {
        return HomogeneousMedium(Spectrum(0.4f), Spectrum::PiecewiseLinear({360.f, 830.f}, {0.6f, 3.f}), 1,
                                 Spectrum(0.f), 0, 0.3f);
    };
    auto simple = SphereOfMedium(chromatic(), IntegratorType::SimpleVolPath, 256);
    auto reference = SphereOfMedium(chromatic(), IntegratorType::VolPath, 256);
    ExpectSameMeans(simple->film, reference->film);
}

// The test can fail: without the medium's absorption the image is brighter.
TEST(SimpleVolPath, TellsAnAbsorbingMediumFromAScatteringOne) {
    auto absorbing = SphereOfMedium(HomogeneousMedium(Spectrum(1.f), Spectrum(2.f), 1, Spectrum(0.f), 0, 0),
                                    IntegratorType::SimpleVolPath, 64);
    auto empty = SphereOfMedium(std::nullopt, IntegratorType::SimpleVolPath, 64);
    EXPECT_GT(MeanDifference(absorbing->film, empty->film).Z(1), 4);
}

TEST(SimpleVolPath, RefusesSurfacesThatScatter) {
    IntegratorOptions o;
    o.type = IntegratorType::SimpleVolPath;
    auto scene = CornellBox(Point2i(4, 4), 1, o);
    try {
        Render(*scene, {0, true});
        FAIL() << "rendered a scene with materials";
    } catch (const std::invalid_argument &e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("simplevolpath renders participating media alone"));
        EXPECT_THAT(e.what(), testing::HasSubstr("render it with volpath"));
    }
}

}  // namespace
