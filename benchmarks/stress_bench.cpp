// Throughput of FabricBxDF on adversarial inputs, and a count of what it must never return. Inputs
// come from tests/support/fabric_adversarial.h, the generator of tests/bxdfs/fabric_stress_test.cpp.
//
// They are generated once into a buffer (kConfigurations BxDFs, kCases calls of each kind, each on a
// random one of them), then at least kCalls calls (f + PDF + Sample_f per case) are timed over it.
// Counters: "calls/s"; "nonfinite" (NaN or Inf in f, PDF or a sample's f, pdf or wi) and "negative"
// (a negative f or pdf), both of which must be 0.
#include "tests/support/fabric_adversarial.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using namespace pbrt;

namespace {

constexpr int kConfigurations = 4096;
constexpr int kCases = 1 << 18;
constexpr int64_t kCalls = 100'000'000;
struct Case {
    uint32_t bxdf;
    Vector3f wo, wi;
    Float uc;
    Point2f u;
};

struct Inputs {
    std::vector<FabricBxDF> bxdfs;
    std::vector<Case> cases;
};

const Inputs &AdversarialInputs() {
    static const Inputs inputs = [] {
        Inputs in;
        FabricAdversarialInputs g(20171115);
        for (int i = 0; i < kConfigurations; ++i)
            in.bxdfs.push_back(g.BxDF());
        for (int i = 0; i < kCases; ++i) {
            uint32_t b = g.Pick(kConfigurations);
            Vector3f thread = in.bxdfs[b].Thread();
            Vector3f wo = g.Direction(thread), wi = g.Direction(thread);
            in.cases.push_back({b, wo, wi, g.U(), Point2f(g.U(), g.U())});
        }
        return in;
    }();
    return inputs;
}

struct Tally {
    int64_t nonfinite = 0, negative = 0;

    void Add(Float v) {
        nonfinite += !std::isfinite(v);
        negative += v < 0;
    }
    void Add(const SampledSpectrum &s) {
        for (int c = 0; c < NSpectrumSamples; ++c)
            Add(s[c]);
    }
    void AddDirection(Vector3f w) {
        nonfinite += !(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z));
    }
};

void FabricStress(benchmark::State &state) {
    const Inputs &in = AdversarialInputs();
    const int64_t passes = (kCalls + 3 * kCases - 1) / (3 * kCases);
    Tally tally;
    for (auto _ : state)
        for (int64_t pass = 0; pass < passes; ++pass)
            for (const Case &c : in.cases) {
                const FabricBxDF &bxdf = in.bxdfs[c.bxdf];
                tally.Add(bxdf.f(c.wo, c.wi, TransportMode::Radiance));
                tally.Add(bxdf.PDF(c.wo, c.wi, TransportMode::Radiance));
                if (pstd::optional<BSDFSample> bs =
                        bxdf.Sample_f(c.wo, c.uc, c.u, TransportMode::Radiance)) {
                    tally.Add(bs->f);
                    tally.Add(bs->pdf);
                    tally.AddDirection(bs->wi);
                }
            }
    state.counters["calls/s"] = benchmark::Counter(double(state.iterations() * passes * 3 * kCases),
                                                   benchmark::Counter::kIsRate);
    state.counters["nonfinite"] = double(tally.nonfinite);
    state.counters["negative"] = double(tally.negative);
}

}  // namespace

BENCHMARK(FabricStress)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
