// Calls per second of f, PDF and Sample_f: FabricBxDF for every sampler at n = 1, 5, 30, against the
// DiffuseBxDF and ConductorBxDF (rough, TR) that a renderer would otherwise use.
//
// Each iteration evaluates one of kInputs precomputed random (wo, wi, u) inputs, so the branch mix is
// that of a renderer, not of one repeated direction. Counter "calls/s" is what the closing notes quote.
#include "pbrt_ext/bxdfs/conductor.h"
#include "pbrt_ext/bxdfs/diffuse.h"
#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/util/rng.h"

#include <benchmark/benchmark.h>

#include <vector>

using namespace pbrt;

namespace {

constexpr int kInputs = 4096;

struct Input {
    Vector3f wo, wi;
    Float uc;
    Point2f u;
};

const std::vector<Input> &Inputs() {
    static const std::vector<Input> inputs = [] {
        std::vector<Input> in(kInputs);
        RNG rng(42);
        auto u2 = [&] { return Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()); };
        for (Input &i : in)
            i = {SampleCosineHemisphere(u2()), SampleCosineHemisphere(u2()), rng.Uniform<Float>(),
                 u2()};
        return in;
    }();
    return inputs;
}

enum class Call { f, PDF, Sample_f };

template <typename BxDF>
void Run(benchmark::State &state, const BxDF &bxdf, Call call) {
    const std::vector<Input> &in = Inputs();
    size_t i = 0;
    for (auto _ : state) {
        const Input &x = in[i++ % kInputs];
        switch (call) {
        case Call::f:
            benchmark::DoNotOptimize(bxdf.f(x.wo, x.wi, TransportMode::Radiance));
            break;
        case Call::PDF:
            benchmark::DoNotOptimize(bxdf.PDF(x.wo, x.wi, TransportMode::Radiance));
            break;
        case Call::Sample_f:
            benchmark::DoNotOptimize(bxdf.Sample_f(x.wo, x.uc, x.u, TransportMode::Radiance));
            break;
        }
    }
    state.counters["calls/s"] = benchmark::Counter(double(state.iterations()),
                                                   benchmark::Counter::kIsRate);
}

FabricBxDF Fabric(FabricSampling sampling, Float n) {
    return FabricBxDF(SampledSpectrum(0.8f), FabricExponent{n}, FabricBxDF::ThreadDirection(30, 0),
                      sampling);
}

void RegisterAll() {
    struct Named {
        const char *name;
        Call call;
    };
    const Named calls[] = {{"f", Call::f}, {"PDF", Call::PDF}, {"Sample_f", Call::Sample_f}};
    const std::pair<const char *, FabricSampling> samplers[] = {
        {"uniform", FabricSampling::Uniform},
        {"cosine", FabricSampling::Cosine},
        {"paper", FabricSampling::Paper},
        {"truncatedsinphi", FabricSampling::TruncatedSinPhi},
        {"best", FabricSampling::Best}};
    for (Named c : calls) {
        for (auto [samplerName, sampling] : samplers)
            for (Float n : {1.f, 5.f, 30.f}) {
                std::string name = std::string("Fabric/") + c.name + "/" + samplerName +
                                   "/n=" + std::to_string(int(n));
                benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State &s) {
                    Run(s, Fabric(sampling, n), c.call);
                });
            }
        benchmark::RegisterBenchmark((std::string("FabricElevated30/") + c.name + "/best/n=5").c_str(),
                                     [=](benchmark::State &s) {
                                         Run(s,
                                             FabricBxDF(SampledSpectrum(0.8f), FabricExponent{5},
                                                        FabricBxDF::ThreadDirection(30, 30)),
                                             c.call);
                                     });
        benchmark::RegisterBenchmark((std::string("Diffuse/") + c.name).c_str(),
                                     [=](benchmark::State &s) {
                                         Run(s, DiffuseBxDF(SampledSpectrum(0.5f)), c.call);
                                     });
        benchmark::RegisterBenchmark(
            (std::string("Conductor/") + c.name + "/alpha=0.3").c_str(), [=](benchmark::State &s) {
                ConductorBxDF conductor(TrowbridgeReitzDistribution(0.3f, 0.3f),
                                        SampledSpectrum(0.2f, 0.9f, 1.1f),
                                        SampledSpectrum(3.9f, 2.4f, 2.2f));
                Run(s, conductor, c.call);
            });
    }
}

const bool registered = (RegisterAll(), true);

}  // namespace
