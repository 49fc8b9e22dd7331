// Throughput of FabricBxDF on adversarial inputs, and a count of what it must never return. Inputs are
// of the kinds tests/fabric_stress_test.cpp checks: grazing (tiny, zero and denormal z) directions,
// directions equal or within ulps of ±thread, unnormalized, denormal and huge vectors, exponents up to
// 1e4 and down to the smallest denormal, roughness outside [0, 1], zero and negative colors, threads
// along the normal, tangent, or of zero length, every sampler, both normalizations, regularized or not.
//
// They are generated once into a buffer (kConfigurations BxDFs, kCases calls of each kind, each on a
// random one of them), then at least kCalls calls (f + PDF + Sample_f per case) are timed over it.
// Counters: "calls/s"; "nonfinite" (NaN or Inf in f, PDF or a sample's f, pdf or wi) and "negative"
// (a negative f or pdf), both of which must be 0.
#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/util/rng.h"

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
constexpr FabricSampling kSamplers[] = {FabricSampling::Uniform, FabricSampling::Cosine,
                                        FabricSampling::Paper, FabricSampling::TruncatedSinPhi,
                                        FabricSampling::Best};

struct Case {
    uint32_t bxdf;
    Vector3f wo, wi;
    Float uc;
    Point2f u;
};

class Generator {
  public:
    Float U() { return rng.Uniform<Float>(); }
    uint32_t Pick(uint32_t n) { return rng.Uniform<uint32_t>() % n; }

    FabricBxDF BxDF() {
        SampledSpectrum color(U() < 0.1f ? 0.f : U() < 0.1f ? -U() : U());
        FabricSampling sampling = kSamplers[Pick(5)];
        FabricNormalization normalization =
            U() < 0.5f ? FabricNormalization::Paper : FabricNormalization::UnitPeak;
        Vector3f thread = Thread();
        FabricBxDF bxdf =
            U() < 0.5f ? FabricBxDF(color, -2 + 5 * U(), thread, sampling, normalization)
                       : FabricBxDF(color, FabricExponent{Exponent()}, thread, sampling,
                                    normalization);
        if (U() < 0.2f)
            bxdf.Regularize();
        return bxdf;
    }

    // Mostly a random unit vector; often grazing or (nearly) ±thread; often not of unit length.
    Vector3f Direction(Vector3f thread) {
        Vector3f w = SampleUniformSphere(Point2f(U(), U()));
        switch (Pick(8)) {
        case 0:
            w.z = std::ldexp(U() - 0.5f, -int(Pick(140)));
            break;
        case 1:
            w = U() < 0.5f ? thread : -thread;
            break;
        case 2:
            w = Normalize(thread + Vector3f(U() - 0.5f, U() - 0.5f, U() - 0.5f) * 1e-6f);
            break;
        default:
            break;
        }
        const Float scales[] = {1e-41f, 3e4f, 0.5f + U()};
        uint32_t s = Pick(10);
        return s < 3 ? w * scales[s] : w;
    }

  private:
    Vector3f Thread() {
        switch (Pick(6)) {
        case 0:
            return Vector3f(0, 0, U() < 0.5f ? 1 : -1);
        case 1:
            return Vector3f(1, 0, 1e-30f);
        case 2:
            return Vector3f(0, 0, 0);
        default:
            return SampleUniformSphere(Point2f(U(), U())) * (0.1f + 10 * U());
        }
    }

    Float Exponent() {
        const Float exponents[] = {1e4f * U(), 1e4f, std::numeric_limits<Float>::denorm_min(),
                                   40 * U()};
        return exponents[Pick(4)];
    }

    RNG rng{20171115};
};

struct Inputs {
    std::vector<FabricBxDF> bxdfs;
    std::vector<Case> cases;
};

const Inputs &AdversarialInputs() {
    static const Inputs inputs = [] {
        Inputs in;
        Generator g;
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
