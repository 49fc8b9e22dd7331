// Calls per second of f, PDF and Sample_f: FabricBxDF for every sampler at n = 1, 5, 30, against
// every other BxDF of pbrt_ext/bxdfs/bxdfs.h (the conductor and the diffuse BxDF being what a
// renderer would otherwise use for cloth).
//
// Each iteration evaluates one of kInputs precomputed random (wo, wi, u) inputs, so the branch mix is
// that of a renderer, not of one repeated direction. For a BxDF that transmits, every other wi lies
// below the surface, so that f and PDF also take their transmission paths. Counter "calls/s" is what
// the closing notes quote. Names are "<BxDF>/<call>[/<variant>]".
#include "pbrt_ext/bxdfs/bxdfs.h"
#include "pbrt_ext/util/rng.h"

#include <benchmark/benchmark.h>

#include <string>
#include <tuple>
#include <vector>

using namespace pbrt;

namespace {

constexpr int kInputs = 4096;

struct Input {
    Vector3f wo, wi;
    Float uc;
    Point2f u;
};

const std::vector<Input> &Inputs(bool transmissive) {
    static const auto make = [](bool flipEveryOther) {
        std::vector<Input> in(kInputs);
        RNG rng(42);
        auto u2 = [&] { return Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()); };
        for (size_t k = 0; k < in.size(); ++k) {
            in[k] = {SampleCosineHemisphere(u2()), SampleCosineHemisphere(u2()),
                     rng.Uniform<Float>(), u2()};
            if (flipEveryOther && k % 2)
                in[k].wi.z = -in[k].wi.z;
        }
        return in;
    };
    static const std::vector<Input> reflection = make(false), transmission = make(true);
    return transmissive ? transmission : reflection;
}

enum class Call { f, PDF, Sample_f };

template <typename BxDF>
void Run(benchmark::State &state, const BxDF &bxdf, Call call) {
    const std::vector<Input> &in = Inputs(IsTransmissive(bxdf.Flags()));
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

// Registers "<bxdf>/<call><variant>" for the three calls; make() builds the BxDF.
template <typename Make>
void RegisterCalls(const std::string &bxdf, const std::string &variant, Make make) {
    const std::pair<const char *, Call> calls[] = {
        {"f", Call::f}, {"PDF", Call::PDF}, {"Sample_f", Call::Sample_f}};
    for (const auto &c : calls)
        benchmark::RegisterBenchmark((bxdf + "/" + c.first + variant).c_str(),
                                     [=, call = c.second](benchmark::State &s) {
                                         Run(s, make(), call);
                                     });
}

FabricBxDF Fabric(FabricSampling sampling, Float n, Float elevationDegrees = 0) {
    return FabricBxDF(SampledSpectrum(0.8f), FabricExponent{n},
                      FabricBxDF::ThreadDirection(30, elevationDegrees), sampling);
}

TrowbridgeReitzDistribution Alpha(Float alpha) { return TrowbridgeReitzDistribution(alpha, alpha); }

ConductorBxDF Copper(Float alpha) {
    // Copper's eta and k at about 450, 550, 650 and 700 nm.
    return ConductorBxDF(Alpha(alpha), SampledSpectrum(1.22f, 0.95f, 0.27f, 0.21f),
                         SampledSpectrum(2.4f, 2.6f, 3.6f, 4.2f));
}

// A named BxDF factory: one row of the table below.
template <typename Make>
struct Named {
    const char *bxdf, *variant;
    Make make;
};
template <typename Make>
Named(const char *, const char *, Make) -> Named<Make>;

void RegisterAll() {
    const std::pair<const char *, FabricSampling> samplers[] = {
        {"uniform", FabricSampling::Uniform},
        {"cosine", FabricSampling::Cosine},
        {"paper", FabricSampling::Paper},
        {"truncatedsinphi", FabricSampling::TruncatedSinPhi},
        {"best", FabricSampling::Best}};
    for (const auto &[samplerName, sampling] : samplers)
        for (int n : {1, 5, 30})
            RegisterCalls("Fabric", std::string("/") + samplerName + "/n=" + std::to_string(n),
                          [s = sampling, n] { return Fabric(s, Float(n)); });

    // Layered BxDFs with pbrt-v4's material defaults (thickness 0.01, no slab albedo, maxdepth 10,
    // one sample) and a smooth coat of eta 1.5.
    const DielectricBxDF coat(1.5f, Alpha(0));
    const std::tuple others = {
        Named{"FabricElevated30", "/best/n=5", [] { return Fabric(FabricSampling::Best, 5, 30); }},
        Named{"FabricDiffuse", "/best/n=5",
              [] { return FabricDiffuseBxDF(Fabric(FabricSampling::Best, 5), SampledSpectrum(0.5f)); }},
        Named{"Diffuse", "", [] { return DiffuseBxDF(SampledSpectrum(0.5f)); }},
        Named{"Conductor", "/alpha=0.3", [] { return Copper(0.3f); }},
        Named{"Dielectric", "/smooth", [] { return DielectricBxDF(1.5f, Alpha(0)); }},
        Named{"Dielectric", "/alpha=0.3", [] { return DielectricBxDF(1.5f, Alpha(0.3f)); }},
        Named{"ThinDielectric", "", [] { return ThinDielectricBxDF(1.5f); }},
        Named{"DiffuseTransmission", "",
              [] { return DiffuseTransmissionBxDF(SampledSpectrum(0.25f), SampledSpectrum(0.5f)); }},
        Named{"CoatedDiffuse", "/smooth",
              [=] {
                  return CoatedDiffuseBxDF(coat, DiffuseBxDF(SampledSpectrum(0.5f)), 0.01f,
                                           SampledSpectrum(0.f), 0, 10, 1);
              }},
        Named{"CoatedConductor", "/smooth/alpha=0.3",
              [=] {
                  return CoatedConductorBxDF(coat, Copper(0.3f), 0.01f, SampledSpectrum(0.f), 0,
                                             10, 1);
              }}};
    std::apply([](const auto &...b) { (RegisterCalls(b.bxdf, b.variant, b.make), ...); },
               others);
}

const bool registered = (RegisterAll(), true);

}  // namespace
