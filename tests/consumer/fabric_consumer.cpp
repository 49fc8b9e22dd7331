// A renderer with its own vector type uses the fabric BxDF through pbrt_ext::fabric: it converts
// its directions into the BxDF's local frame, samples, and evaluates. Exits 1 if the BxDF's
// sampled values disagree with its f() and PDF(), or if a white unit-peak fabric does not reflect
// all the light at its peak (2^16 samples; the mean within 4 standard errors of 1).
#include <pbrt_ext/bxdfs/fabric.h>

#include <cmath>
#include <cstdio>
#include <random>

struct MyVec {  // the host renderer's own type
    double x, y, z;
};

static pbrt::Vector3f ToLocal(MyVec v) {
    return pbrt::Vector3f(float(v.x), float(v.y), float(v.z));
}

int main() {
    using namespace pbrt;
    FabricBxDF fabric(SampledSpectrum(1.f), 0.4f, FabricBxDF::ThreadDirection(30, 0),
                      FabricSampling::Best, FabricNormalization::UnitPeak);
    Vector3f wo = ToLocal(MyVec{0, 0, 1});  // normal incidence: the peak for tangent threads
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u01(0.f, 0.99999994f);
    const int n = 1 << 16;
    double sum = 0, sumSquares = 0;
    for (int i = 0; i < n; ++i) {
        pstd::optional<BSDFSample> bs = fabric.Sample_f(wo, u01(rng), Point2f(u01(rng), u01(rng)),
                                                        TransportMode::Radiance);
        if (!bs)
            continue;
        float f = fabric.f(wo, bs->wi, TransportMode::Radiance)[0];
        float pdf = fabric.PDF(wo, bs->wi, TransportMode::Radiance);
        if (std::abs(f - bs->f[0]) > 1e-5f * f || std::abs(pdf - bs->pdf) > 1e-5f * pdf) {
            std::printf("fabric_consumer: Sample_f gave f %g pdf %g; f() %g, PDF() %g\n",
                        bs->f[0], bs->pdf, f, pdf);
            return 1;
        }
        double v = double(bs->f[0]) * bs->wi.z / bs->pdf;
        sum += v;
        sumSquares += v * v;
    }
    double mean = sum / n, error = std::sqrt((sumSquares / n - mean * mean) / n);
    std::printf("fabric_consumer: albedo at the peak %.5f +- %.5f (expected 1)\n", mean, error);
    return std::abs(mean - 1) <= 4 * error ? 0 : 1;
}
