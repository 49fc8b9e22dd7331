// The estimators without MIS (pbrt-v4's simplepath in its four variants, and randomwalk) converge
// to the path tracer's image: on the Cornell box, at fixed seeds, each channel's mean difference
// from the path tracer's image is within 4 standard errors of 0 (the pixels taken as
// independent; a bias of 1 % would be 5 to 20 of them at these sample counts).
#include "tests/support/imagestats.h"
#include "tests/support/scenes.h"

#include "pbrt_ext/render.h"

#include <gtest/gtest.h>

using namespace pbrt;
using namespace pbrt::testscenes;

namespace {

constexpr double kMaxStandardErrors = 4;
const Point2i kResolution(32, 32);

std::unique_ptr<Scene> Rendered(IntegratorOptions options, int spp) {
    auto scene = CornellBox(kResolution, spp, options);
    Render(*scene, {0, true});
    return scene;
}

IntegratorOptions Options(IntegratorType type) {
    IntegratorOptions o;
    o.type = type;
    return o;
}

void ExpectSameMeans(const RGBFilm &film, const RGBFilm &reference, const std::string &what) {
    ChannelDifference d = MeanDifference(film, reference);
    for (int c = 0; c < 3; ++c)
        EXPECT_LT(d.Z(c), kMaxStandardErrors)
            << what << ", channel " << c << ": mean difference " << d.mean[c] << " +- "
            << d.standardError[c];
}

class SimplePath : public testing::TestWithParam<std::pair<bool, bool>> {};

TEST_P(SimplePath, ConvergesToThePathTracersImage) {
    auto [sampleLights, sampleBSDF] = GetParam();
    IntegratorOptions o = Options(IntegratorType::SimplePath);
    o.simplePath = {sampleLights, sampleBSDF};
    // Without light sampling the light is found only by chance: more samples.
    const int spp = sampleLights ? 256 : 2048;
    auto reference = Rendered(Options(IntegratorType::Path), 1024);
    auto simple = Rendered(o, spp);
    ExpectSameMeans(simple->film, reference->film, "samplelights " + std::to_string(sampleLights) +
                                                       " samplebsdf " + std::to_string(sampleBSDF));
}

INSTANTIATE_TEST_SUITE_P(EveryVariant, SimplePath,
                         testing::Values(std::pair(true, true), std::pair(true, false),
                                         std::pair(false, true), std::pair(false, false)));

TEST(RandomWalk, ConvergesToThePathTracersImage) {
    auto reference = Rendered(Options(IntegratorType::Path), 1024);
    auto walk = Rendered(Options(IntegratorType::RandomWalk), 4096);
    ExpectSameMeans(walk->film, reference->film, "randomwalk");
}

// The test can fail: a path tracer limited to one bounce is darker than the reference's five.
TEST(RandomWalk, TellsADifferentDepthApart) {
    IntegratorOptions shallow = Options(IntegratorType::RandomWalk);
    shallow.maxDepth = 1;
    auto reference = Rendered(Options(IntegratorType::Path), 1024);
    auto walk = Rendered(shallow, 4096);
    ChannelDifference d = MeanDifference(walk->film, reference->film);
    EXPECT_GT(d.Z(0), kMaxStandardErrors);
}

}  // namespace
