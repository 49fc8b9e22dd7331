// pbrt_ext tests: property checks for any BxDF, for the ones chi-square cannot make
// (STYLE.md example 12; pbrt-v4 src/pbrt/bsdfs_test.cpp, lajolla src/tests/materials.cpp).
//
// Every helper returns a result; the tests assert on it (EXPECT_TRUE(r.passed) <<
// r.message), so a helper never stops a test half-way and one failure message can list
// several offending directions. Directions are in the local shading frame (z = normal).
// Host-only test code.
#pragma once

#include "tests/support/chi2.h"

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace pbrt {

struct BxDFCheckOptions {
    int sampleCount = 4096;  // samples (or direction pairs) per check
    // Two values agree when |a - b| <= relTolerance * max(|a|, |b|) + absTolerance; the
    // absolute floor keeps float noise on tiny values from failing.
    Float relTolerance = 1e-5f;
    Float absTolerance = 1e-6f;
    uint64_t seed = 1;  // RNG sequence index
    TransportMode mode = TransportMode::Radiance;
    BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All;
    int maxReported = 5;  // failures spelled out in the message
};

struct PropertyResult {
    bool passed = true;
    int64_t checked = 0;   // cases looked at
    int64_t failures = 0;  // cases that failed
    std::string message;   // the first failures, one per line

    void Fail(const BxDFCheckOptions &opts, const std::string &what) {
        passed = false;
        if (failures++ < opts.maxReported)
            message += what + "\n";
    }
};

// The outgoing directions every BxDF is checked for: along the normal, ordinary and
// grazing angles at several azimuths (anisotropy), exactly tangent, and below the
// surface.
inline std::vector<Vector3f> PropertyTestDirections() {
    std::vector<Vector3f> dirs;
    for (double cosTheta : {1.0, 0.9, 0.5, 0.1, 1e-3, 0.0, -0.4, -0.95})
        for (double phi : {0.3, 1.9, 4.0}) {
            dirs.push_back(DirectionFromCosThetaPhi(cosTheta, phi));
            if (cosTheta == 1)
                break;  // phi is meaningless along the normal
        }
    return dirs;
}

namespace propertydetail {

inline bool Agree(double a, double b, const BxDFCheckOptions &opts) {
    return std::abs(a - b) <=
           opts.relTolerance * std::max(std::abs(a), std::abs(b)) + opts.absTolerance;
}

inline bool Agree(const SampledSpectrum &a, const SampledSpectrum &b,
                  const BxDFCheckOptions &opts) {
    for (int c = 0; c < NSpectrumSamples; ++c)
        if (!Agree(a[c], b[c], opts))
            return false;
    return true;
}

inline bool IsFiniteNonNegative(double v) { return std::isfinite(v) && v >= 0; }

inline bool IsFiniteNonNegative(const SampledSpectrum &s) {
    for (int c = 0; c < NSpectrumSamples; ++c)
        if (!IsFiniteNonNegative(s[c]))
            return false;
    return true;
}

inline std::string Str(Vector3f v) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "(%.7g, %.7g, %.7g)", v.x, v.y, v.z);
    return buf;
}

inline std::string Str(const SampledSpectrum &s) {
    std::string r = "[";
    char buf[32];
    for (int c = 0; c < NSpectrumSamples; ++c) {
        std::snprintf(buf, sizeof(buf), c ? ", %.7g" : "%.7g", s[c]);
        r += buf;
    }
    return r + "]";
}

inline std::string Str(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.7g", v);
    return buf;
}

inline Point2f NextPoint2f(RNG &rng) {
    Float u0 = rng.Uniform<Float>();  // its own statement: argument order is unspecified
    return Point2f(u0, rng.Uniform<Float>());
}

// The uniform numbers Sample_f gets, drawn in a fixed order.
struct SampleInputs {
    Float uc;
    Point2f u;
};

inline SampleInputs NextSampleInputs(RNG &rng) {
    Float uc = rng.Uniform<Float>();
    return {uc, NextPoint2f(rng)};
}

// Empty when f(wo, wi) == f(wi, wo), else a line saying how they differ.
template <typename BxDF>
std::string ReciprocityMismatch(const BxDF &bxdf, Vector3f wo, Vector3f wi,
                                const BxDFCheckOptions &opts) {
    SampledSpectrum forward = bxdf.f(wo, wi, opts.mode), backward = bxdf.f(wi, wo, opts.mode);
    if (Agree(forward, backward, opts))
        return {};
    return "wo = " + Str(wo) + ", wi = " + Str(wi) + ": f(wo, wi) " + Str(forward) +
           " vs f(wi, wo) " + Str(backward);
}

}  // namespace propertydetail

// Sample_f().pdf == PDF(wo, wi) and Sample_f().f == f(wo, wi) for opts.sampleCount
// samples. Specular and pdfIsProportional samples are skipped: for them the two are not
// meant to agree.
template <typename BxDF>
PropertyResult CheckSampleMatchesEval(const BxDF &bxdf, Vector3f wo,
                                      const BxDFCheckOptions &opts = {}) {
    using namespace propertydetail;
    PropertyResult result;
    RNG rng(opts.seed);
    for (int i = 0; i < opts.sampleCount; ++i) {
        auto [uc, u] = NextSampleInputs(rng);
        pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, uc, u, opts.mode, opts.sampleFlags);
        if (!bs || bs->IsSpecular() || bs->pdfIsProportional)
            continue;
        ++result.checked;
        Float pdf = bxdf.PDF(wo, bs->wi, opts.mode, opts.sampleFlags);
        SampledSpectrum f = bxdf.f(wo, bs->wi, opts.mode);
        if (!Agree(bs->pdf, pdf, opts) || !Agree(bs->f, f, opts))
            result.Fail(opts, "wo = " + Str(wo) + ", wi = " + Str(bs->wi) +
                                  ": Sample_f pdf " + Str(bs->pdf) + " vs PDF " + Str(pdf) +
                                  ", Sample_f f " + Str(bs->f) + " vs f " + Str(f));
    }
    return result;
}

// f(wo, wi) == f(wi, wo) for one pair.
template <typename BxDF>
PropertyResult CheckReciprocity(const BxDF &bxdf, Vector3f wo, Vector3f wi,
                                const BxDFCheckOptions &opts = {}) {
    PropertyResult result;
    result.checked = 1;
    if (std::string why = propertydetail::ReciprocityMismatch(bxdf, wo, wi, opts); !why.empty())
        result.Fail(opts, why);
    return result;
}

// Reciprocity of reflection for opts.sampleCount random pairs: wo uniform on the
// sphere, wi uniform on wo's hemisphere. (Transmission is not reciprocal in radiance
// units, so pairs across the surface are left to the caller's single-pair check.)
template <typename BxDF>
PropertyResult CheckReflectionReciprocity(const BxDF &bxdf,
                                          const BxDFCheckOptions &opts = {}) {
    using namespace propertydetail;
    PropertyResult result;
    RNG rng(opts.seed);
    for (int i = 0; i < opts.sampleCount; ++i) {
        Vector3f wo = SampleUniformSphere(NextPoint2f(rng));
        Vector3f wi = SampleUniformHemisphere(NextPoint2f(rng));
        if (wo.z < 0)
            wi = -wi;
        ++result.checked;
        if (std::string why = ReciprocityMismatch(bxdf, wo, wi, opts); !why.empty())
            result.Fail(opts, why);
    }
    return result;
}

// f, PDF and Sample_f never give NaN, Inf or negative values, and sampled directions are
// finite unit vectors: f and PDF at every node of a sphere quadrature, Sample_f for
// opts.sampleCount samples.
template <typename BxDF>
PropertyResult CheckFiniteNonNegative(const BxDF &bxdf, Vector3f wo,
                                      const BxDFCheckOptions &opts = {}) {
    using namespace propertydetail;
    PropertyResult result;
    ForEachSphereQuadratureNode(16, 32, [&](Vector3f wi, double) {
        ++result.checked;
        SampledSpectrum f = bxdf.f(wo, wi, opts.mode);
        Float pdf = bxdf.PDF(wo, wi, opts.mode, opts.sampleFlags);
        if (!IsFiniteNonNegative(f) || !IsFiniteNonNegative(pdf))
            result.Fail(opts, "wo = " + Str(wo) + ", wi = " + Str(wi) + ": f " + Str(f) +
                                  ", PDF " + Str(pdf));
    });
    RNG rng(opts.seed);
    for (int i = 0; i < opts.sampleCount; ++i) {
        auto [uc, u] = NextSampleInputs(rng);
        pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, uc, u, opts.mode, opts.sampleFlags);
        if (!bs)
            continue;
        ++result.checked;
        Vector3f wi = bs->wi;
        double len = std::sqrt(double(wi.x) * wi.x + double(wi.y) * wi.y + double(wi.z) * wi.z);
        bool ok = IsFiniteNonNegative(bs->f) && IsFiniteNonNegative(bs->pdf) &&
                  std::abs(len - 1) < 1e-3 && std::isfinite(bs->eta) && bs->eta > 0;
        if (!ok)
            result.Fail(opts, "wo = " + Str(wo) + ": Sample_f gave wi " + Str(wi) + ", f " +
                                  Str(bs->f) + ", pdf " + Str(bs->pdf) + ", eta " +
                                  Str(bs->eta));
    }
    return result;
}

// Mean and variance of the mean of n per-sample values (the values not added count as 0).
struct MeanEstimate {
    double sum = 0, sumSq = 0;
    void Add(double v) { sum += v, sumSq += v * v; }
    double Mean(int n) const { return sum / n; }
    double VarianceOfMean(int n) const {
        double m = Mean(n);
        return std::max(0.0, sumSq / n - m * m) / n;
    }
};

// Uniform random inputs for the rho() estimators: uc, u1 and u2 spans of one length.
struct RhoSamples {
    std::vector<Float> uc;
    std::vector<Point2f> u1, u2;
};

inline RhoSamples MakeRhoSamples(int count, uint64_t seed) {
    RhoSamples s{std::vector<Float>(count), std::vector<Point2f>(count),
                 std::vector<Point2f>(count)};
    RNG rng(seed);
    for (int i = 0; i < count; ++i) {
        s.uc[i] = rng.Uniform<Float>();
        s.u1[i] = Point2f(rng.Uniform<Float>(), rng.Uniform<Float>());
        s.u2[i] = Point2f(rng.Uniform<Float>(), rng.Uniform<Float>());
    }
    return s;
}

}  // namespace pbrt
