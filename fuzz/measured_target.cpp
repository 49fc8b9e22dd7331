// The measured target: an RGL .bsdf file (a tensor file, util/tensorfile.h) read by
// MeasuredBxDFData::Read, and, if it is read, the measured BxDF evaluated and sampled for a few
// directions and wavelengths: every f, pdf and sampled direction must be finite (f and pdf
// non-negative, directions of unit length in wo's hemisphere).
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/bxdfs/measured.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace pbrt::fuzz {

namespace {

bool FiniteNonNegative(const SampledSpectrum &s) {
    for (int i = 0; i < NSpectrumSamples; ++i)
        if (!std::isfinite(s[i]) || s[i] < 0) return false;
    return true;
}

void CheckBxDF(const MeasuredBxDFData &data) {
    const SampledWavelengths lambda = SampledWavelengths::SampleUniform(0.3f);
    const MeasuredBxDF bxdf(&data, lambda);
    const Vector3f directions[] = {Vector3f(0, 0, 1), Normalize(Vector3f(0.5f, 0.2f, 0.8f)),
                                   Normalize(Vector3f(-0.9f, 0.3f, 0.1f)),
                                   Normalize(Vector3f(0.3f, -0.4f, -0.7f))};
    for (Vector3f wo : directions) {
        for (Vector3f wi : directions) {
            SampledSpectrum f = bxdf.f(wo, wi, TransportMode::Radiance);
            Float pdf = bxdf.PDF(wo, wi, TransportMode::Radiance);
            if (!FiniteNonNegative(f) || !std::isfinite(pdf) || pdf < 0)
                ReportFinding("measured", fmt::format("f {} or PDF {} not finite and non-negative",
                                                      f.ToString(), pdf));
        }
        for (int i = 0; i < 16; ++i) {
            Point2f u((i % 4 + 0.5f) / 4, (i / 4 + 0.5f) / 4);
            pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, 0.5f, u, TransportMode::Radiance);
            if (!bs) continue;
            if (!FiniteNonNegative(bs->f) || !(bs->pdf > 0) || !std::isfinite(bs->pdf) ||
                std::abs(Length(bs->wi) - 1) > 1e-3f || !SameHemisphere(wo, bs->wi))
                ReportFinding("measured",
                              fmt::format("a sample that is not finite, of unit length and on wo's "
                                          "side: wo ({}, {}, {}) wi ({}, {}, {}) f {} pdf {}",
                                          wo.x, wo.y, wo.z, bs->wi.x, bs->wi.y, bs->wi.z,
                                          bs->f.ToString(), bs->pdf));
        }
    }
}

}  // namespace

void FuzzMeasured(std::span<const uint8_t> data) {
    std::string path = WriteScratchFile("measured", "brdf.bsdf", data);
    ExpectReadOrRejection("measured", [&] { CheckBxDF(*MeasuredBxDFData::Read(path)); });
}

}  // namespace pbrt::fuzz
