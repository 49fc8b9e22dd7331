// Ambient occlusion against its closed form: a point on a plane under a ring (a disk with a hole)
// parallel to it at height h, inner radius ri and outer radius ro, centered above the point. The
// ring hides the cosine-weighted fraction sin^2(theta_o) - sin^2(theta_i) of the hemisphere,
// tan(theta) = r / h, so the point's occlusion value is 1 minus that. The camera looks down at the
// point through the hole with a 1-degree field of view (its pixels see points within 0.03 of it,
// where the fraction differs by under 1e-3). Thresholds: 4 standard errors of the pixel mean
// (1024 pixels, 64 samples each), plus the 1e-3.
#include "tests/support/imagestats.h"
#include "tests/support/scenes.h"

#include "pbrt_ext/render.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pbrt;
using namespace pbrt::testscenes;

namespace {

constexpr Float kHeight = 1, kInner = 0.5f, kOuter = 2;
const Point2i kResolution(32, 32);

std::unique_ptr<Scene> PlaneUnderRing(bool cosSample, Float maxDistance, bool withRing) {
    SceneBuilder builder(LookingAt(Point3f(0, 0, 3), Point3f(0, 0, 0), 1, kResolution),
                         BoxFilteredFilm(kResolution), ZSobolSampler(64, kResolution));
    int white = builder.AddMaterial(DiffuseMaterial{Spectrum(0.5f)});
    builder.AddTriangleMesh(Quad(Point3f(-10, -10, 0), Point3f(10, -10, 0), Point3f(10, 10, 0),
                                 Point3f(-10, 10, 0)),
                            white);
    if (withRing)
        builder.AddDisk(Disk(Transform(), false, kHeight, kOuter, kInner, 360), white);
    IntegratorOptions o;
    o.type = IntegratorType::AmbientOcclusion;
    o.ambientOcclusion = {cosSample, maxDistance};
    builder.SetIntegrator(o);
    auto scene = builder.Build();
    Render(*scene, {0, true});
    return scene;
}

double OpenFraction() {
    auto sin2 = [](Float r) { return double(r * r) / double(r * r + kHeight * kHeight); };
    return 1 - (sin2(kOuter) - sin2(kInner));
}

// The mean's tolerance: 4 standard errors of the per-pixel values about their mean, plus the
// closed form's variation over the pixels' points.
double Tolerance(const RGBFilm &film, int c) { return 4 * StandardErrorOfMean(film, c) + 1e-3; }

class AmbientOcclusion : public testing::TestWithParam<bool> {};

// An open hemisphere gives the film colour space's white: 1 in each channel.
TEST_P(AmbientOcclusion, AnOpenPlaneIsWhite) {
    auto open = PlaneUnderRing(GetParam(), Infinity, false);
    RGB mean = MeanRGB(open->film);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 1, 0.01) << "channel " << c;
}

TEST_P(AmbientOcclusion, ARingHidesItsCosineWeightedSolidAngle) {
    auto ring = PlaneUnderRing(GetParam(), Infinity, true);
    auto open = PlaneUnderRing(GetParam(), Infinity, false);
    RGB occluded = MeanRGB(ring->film), white = MeanRGB(open->film);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(occluded[c] / white[c], OpenFraction(), Tolerance(ring->film, c))
            << "channel " << c << ", cosine sampling " << GetParam();
}

// Beyond maxdistance nothing occludes.
TEST_P(AmbientOcclusion, OccludersBeyondMaxDistanceDoNotCount) {
    auto ring = PlaneUnderRing(GetParam(), 0.9f * kHeight, true);
    auto open = PlaneUnderRing(GetParam(), 0.9f * kHeight, false);
    RGB occluded = MeanRGB(ring->film), white = MeanRGB(open->film);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(occluded[c] / white[c], 1, 1e-6) << "channel " << c;
}

INSTANTIATE_TEST_SUITE_P(CosineAndUniform, AmbientOcclusion, testing::Bool());

}  // namespace
