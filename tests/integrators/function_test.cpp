// pbrt-v4's function integrator: every test function integrates to 1; with independent samples
// the mean squared error of n-sample estimates is Var(f) / n, Var(f) = integral(f^2) - 1 by
// quadrature; the low-discrepancy samplers do better on the smooth function; the table has
// pbrt-v4's rows ("<n> <mse>", only at the counts a sampler is well distributed at, with
// skipbad); and "sobol", whose pixel samples are one sequence over the image, is refused.
#include "tests/support/scenefolder.h"

#include "pbrt_ext/integrators/function.h"
#include "pbrt_ext/scene.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace pbrt;

namespace {

constexpr TestFunction kFunctions[] = {TestFunction::Step, TestFunction::Diagonal,
                                       TestFunction::Disk, TestFunction::Checkerboard,
                                       TestFunction::RotatedCheckerboard, TestFunction::Gaussian};
const Point2i kResolution(32, 32);

// The integrals of f and f^2 over the unit square, by the midpoint rule on a 4000^2 grid (the
// discontinuities' cells are a 1e-3 fraction: the integrals are good to about 1e-3).
std::pair<double, double> Integrals(TestFunction f) {
    constexpr int n = 4000;
    double sum = 0, sum2 = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            double v = EvaluateTestFunction(f, Point2f((x + 0.5f) / n, (y + 0.5f) / n));
            sum += v;
            sum2 += v * v;
        }
    return {sum / (double(n) * n), sum2 / (double(n) * n)};
}

std::unique_ptr<Scene> FunctionScene(Sampler sampler, TestFunction f, bool skipBad = true) {
    SceneBuilder builder(PerspectiveCamera(Transform(), kResolution, DefaultScreenWindow(kResolution), 90),
                         RGBFilm(kResolution, Bounds2i(Point2i(0, 0), kResolution), BoxFilter(), "f.exr"),
                         std::move(sampler));
    IntegratorOptions o;
    o.type = IntegratorType::Function;
    o.function.function = f;
    o.function.skipBad = skipBad;
    builder.SetIntegrator(o);
    return builder.Build();
}

std::vector<std::pair<int, double>> Table(Sampler sampler, TestFunction f, bool skipBad = true) {
    auto scene = FunctionScene(std::move(sampler), f, skipBad);
    return FunctionErrorTable(*scene, RenderOptions{0, true});
}

TEST(FunctionIntegrator, EveryFunctionIntegratesToOne) {
    for (TestFunction f : kFunctions) EXPECT_NEAR(Integrals(f).first, 1, 2e-3) << int(f);
}

// 1024 pixels' squared errors at n = 64: their mean's relative standard error is about
// sqrt(2 / 1024) = 4.4 % (for these nearly two-valued functions a little more); 15 % is 3.4 of it.
TEST(FunctionIntegrator, IndependentSamplesHaveTheVarianceOverN) {
    for (TestFunction f : kFunctions) {
        double variance = Integrals(f).second - 1;
        auto table = Table(IndependentSampler(64, 5), f);
        ASSERT_EQ(table.size(), 64u);
        auto [n, mse] = table.back();
        EXPECT_NEAR(mse * n, variance, 0.15 * variance) << "function " << int(f);
    }
}

// On the smooth Gaussian, 64 low-discrepancy samples err far less than independent ones.
TEST(FunctionIntegrator, LowDiscrepancySamplersBeatIndependentOnASmoothFunction) {
    double independent = Table(IndependentSampler(64, 0), TestFunction::Gaussian).back().second;
    for (Sampler s : {Sampler(PaddedSobolSampler(64)), Sampler(ZSobolSampler(64, kResolution)),
                      Sampler(PMJ02BNSampler(64)), Sampler(HaltonSampler(36, kResolution))}) {
        double mse = Table(s, TestFunction::Gaussian).back().second;
        EXPECT_LT(mse, independent / 8) << s.Name();
    }
}

// Sobol' points are a net at every power of two, not only at the sampler's count: its rows
// before the last beat independent samples by 4x too (5x at 8 samples, more after; the padded
// sampler's own pixel samples, a random subset of its 64 until the last, do no better than
// independent ones there).
TEST(FunctionIntegrator, SobolPrefixesAreNets) {
    auto at = [](const std::vector<std::pair<int, double>> &table, int n) {
        for (auto [count, mse] : table)
            if (count == n) return mse;
        return -1.0;
    };
    auto independent = Table(IndependentSampler(64, 0), TestFunction::Gaussian);
    auto sobol = Table(PaddedSobolSampler(64), TestFunction::Gaussian);
    for (int n : {8, 16, 32}) EXPECT_LT(at(sobol, n), at(independent, n) / 4) << n << " samples";
}

std::vector<int> Counts(const std::vector<std::pair<int, double>> &table) {
    std::vector<int> n;
    for (auto [count, mse] : table) n.push_back(count);
    return n;
}

TEST(FunctionIntegrator, RowsAreAtTheCountsEachSamplerIsWellDistributedAt) {
    using testing::ElementsAre;
    EXPECT_THAT(Counts(Table(StratifiedSampler(4, 4, true), TestFunction::Disk)), ElementsAre(1, 4, 9, 16));
    EXPECT_THAT(Counts(Table(PaddedSobolSampler(16), TestFunction::Disk)), ElementsAre(1, 2, 4, 8, 16));
    EXPECT_THAT(Counts(Table(HaltonSampler(40, kResolution), TestFunction::Disk)), ElementsAre(1, 6, 36));
    EXPECT_EQ(Counts(Table(PaddedSobolSampler(16), TestFunction::Disk, false)).size(), 16u);
}

TEST(FunctionIntegrator, WritesPbrtV4sTable) {
    auto scene = FunctionScene(PaddedSobolSampler(8), TestFunction::Step);
    std::filesystem::path file = TestFolder("pbrt_ext_function_test") / "step-mse.txt";
    scene->integratorOptions.function.outputFile = file.string();
    RenderFunction(*scene, RenderOptions{0, true});
    std::ifstream in(file);
    std::string line;
    std::vector<int> counts;
    while (std::getline(in, line)) {
        std::istringstream row(line);
        int n;
        double mse;
        ASSERT_TRUE(row >> n >> mse) << line;
        EXPECT_TRUE((row >> std::ws).eof()) << line;
        EXPECT_GE(mse, 0);
        counts.push_back(n);
    }
    EXPECT_EQ(counts, (std::vector<int>{1, 2, 4, 8}));
}

TEST(FunctionIntegrator, TheShippedSceneLoadsAndRuns) {
    RenderOverrides quick;
    quick.spp = 16;
    auto scene = LoadScene(std::string(PBRT_EXT_TEST_DATA_DIR) + "/../../scenes/function-step.pbrt", quick);
    EXPECT_EQ(scene->integratorOptions.type, IntegratorType::Function);
    EXPECT_EQ(scene->integratorOptions.function.outputFile, "step-mse.txt");
    EXPECT_THAT(Counts(FunctionErrorTable(*scene, RenderOptions{0, true})), testing::ElementsAre(1, 2, 4, 8, 16));
}

TEST(FunctionIntegrator, RefusesTheGlobalSobolSequence) {
    std::filesystem::path file = TestFolder("pbrt_ext_function_test") / "sobol.pbrt";
    std::ofstream(file) << "Sampler \"sobol\"\nIntegrator \"function\"\nCamera \"perspective\"\nWorldBegin\n";
    EXPECT_THAT(LoadErrorAfterPath(file.string()),
                testing::StartsWith(":2:1: error: the \"function\" integrator needs each pixel's own "
                                    "sample points: use Sampler \"paddedsobol\""));
}

}  // namespace
