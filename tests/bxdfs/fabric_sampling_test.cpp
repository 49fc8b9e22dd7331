// FabricBxDF sampling: every sampler's directions follow the density PDF() reports (chi-square), the
// sample's f and pdf are f() and PDF(), and the density integrates to the fraction of samples produced.
#include "tests/support/chi2.h"
#include "tests/support/bxdf_properties.h"

#include "pbrt_ext/bxdfs/fabric.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace pbrt;

namespace {

struct SamplingCase {
    FabricSampling sampling;
    Float n;                 // exponent
    Float woPolar, woAzimuth;  // degrees; azimuth from dpdu (x)
    Float threadAngle, elevation;  // degrees
    const char *name = "";
};

const char *SamplerName(FabricSampling s) {
    constexpr const char *names[] = {"Uniform", "Cosine", "Paper", "TruncatedSinPhi", "Best"};
    return names[int(s)];
}

// Best in 63 configurations: every exponent of the issue, integer and not, with wo from the normal to
// 89° and threads along, across and elevated at 0, 30 and 60°.
std::vector<SamplingCase> BestCases() {
    struct Geometry {
        Float woPolar, woAzimuth, threadAngle, elevation;
    };
    const Geometry geometries[] = {{0, 0, 0, 0},    {45, 0, 0, 0},   {70, 90, 30, 0},
                                   {89, 10, 0, 0},  {30, 200, 0, 30}, {60, 45, 120, 30},
                                   {80, 300, 60, 60}};
    std::vector<SamplingCase> cases;
    for (Float n : {1.f, 2.f, 3.f, 5.f, 10.f, 20.f, 30.f, 2.5f, 7.3f})
        for (Geometry g : geometries)
            cases.push_back({FabricSampling::Best, n, g.woPolar, g.woAzimuth, g.threadAngle,
                             g.elevation});
    return cases;
}

// Every other sampler on 12 configurations spanning the same ranges.
std::vector<SamplingCase> OtherSamplerCases() {
    std::vector<SamplingCase> cases;
    for (FabricSampling s : {FabricSampling::Uniform, FabricSampling::Cosine, FabricSampling::Paper,
                             FabricSampling::TruncatedSinPhi})
        for (SamplingCase c : std::vector<SamplingCase>{{s, 1, 0, 0, 0, 0},
                                                        {s, 5, 45, 0, 0, 0},
                                                        {s, 30, 60, 30, 0, 0},
                                                        {s, 30, 85, 0, 0, 0},
                                                        {s, 2.5f, 20, 90, 45, 0},
                                                        {s, 10, 70, 180, 0, 0},
                                                        {s, 5, 40, 0, 0, 30},
                                                        {s, 20, 60, 270, 90, 30},
                                                        {s, 3, 75, 30, 0, 60},
                                                        {s, 30, 30, 150, 10, 60},
                                                        {s, 1.5f, 10, 0, 0, 45},
                                                        {s, 7.3f, 50, 100, 0, 75}})
            cases.push_back(c);
    return cases;
}

// One named, seeded case per hard configuration.
std::vector<SamplingCase> HardCases() {
    std::vector<SamplingCase> cases;
    for (FabricSampling s : {FabricSampling::Paper, FabricSampling::Best}) {
        cases.push_back({s, 30, 89.9f, 0, 0, 0, "GrazingAlongThread"});
        cases.push_back({s, 30, 89.9f, 90, 0, 0, "GrazingAcrossThread"});
        // With the thread at or near N the lobe's peak (θi = -θo) lies below the surface except for
        // grazing wo (velvet's rim): at wo = N only 1e-6 of the samples land above it, at 30° from
        // N 2e-4, too few for chi-square.
        cases.push_back({s, 10, 85, 0, 0, 90, "ThreadAlongNormal"});
        cases.push_back({s, 10, 80, 0, 0, 89, "ThreadNearlyAlongNormal"});
        cases.push_back({s, 300, 40, 20, 0, 0, "ExtremelySmooth"});
        cases.push_back({s, 0, 40, 20, 0, 0, "FlatLobe"});
        cases.push_back({s, 0.3f, 70, 20, 0, 30, "NearlyFlatLobe"});
        cases.push_back({s, 5, 60, 0, 0, 30, "OutgoingAlongThread"});
    }
    return cases;
}

std::vector<SamplingCase> AllCases() {
    std::vector<SamplingCase> all = BestCases();
    for (auto list : {OtherSamplerCases(), HardCases()})
        all.insert(all.end(), list.begin(), list.end());
    return all;
}

const int kSuiteSize = int(AllCases().size());  // for the Šidák correction

FabricBxDF Make(const SamplingCase &c) {
    return FabricBxDF(SampledSpectrum(0.8f), FabricExponent{c.n},
                      FabricBxDF::ThreadDirection(c.threadAngle, c.elevation), c.sampling);
}

Vector3f Outgoing(const SamplingCase &c) {
    Float theta = Radians(c.woPolar), phi = Radians(c.woAzimuth);
    return SphericalDirection(std::sin(theta), std::cos(theta), phi);
}

class FabricSampling_ : public testing::TestWithParam<SamplingCase> {};

std::string CaseName(const testing::TestParamInfo<SamplingCase> &info) {
    const SamplingCase &c = info.param;
    std::string name = std::string(SamplerName(c.sampling)) + "_" + std::to_string(info.index);
    return *c.name ? name + "_" + c.name : name;
}

}  // namespace

// Chi-square: 1e6 samples, 32 x 64 equal-solid-angle cells (tests/support/chi2.h), α = 0.01 over the whole
// suite (Šidák).
TEST_P(FabricSampling_, DirectionsFollowTheReportedDensity) {
    const SamplingCase &c = GetParam();
    Chi2Options opts;
    opts.numTests = kSuiteSize;
    opts.seed = 20170730;  // fixed
    Chi2Result r = Chi2TestBxDF(Make(c), Outgoing(c), opts);
    EXPECT_TRUE(r.passed) << r.message;
    // The density integrates to the fraction of attempts that produced a sample, never above 1.
    EXPECT_LE(r.integralPdf, 1 + 1e-3) << r.message;
}

// The sample's f and pdf are exactly what f() and PDF() return for its direction (1e-5 relative).
TEST_P(FabricSampling_, SampleAgreesWithEvaluation) {
    const SamplingCase &c = GetParam();
    PropertyResult r = CheckSampleMatchesEval(Make(c), Outgoing(c), BxDFCheckOptions{});
    EXPECT_TRUE(r.passed) << r.message;
}

INSTANTIATE_TEST_SUITE_P(Fabric, FabricSampling_, testing::ValuesIn(AllCases()), CaseName);
