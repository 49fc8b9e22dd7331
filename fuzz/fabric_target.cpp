// The fabric target: the fabric material's BxDF exactly as a scene file can ask for it (its
// parameters through CreateFabricMaterial, the scene loader's own checks), evaluated and sampled at
// one pair of directions, with the invariants every renderer that ports it relies on.
//
// Input layout (shorter inputs are ignored, bytes past the end unused):
//   byte 0      sampler name, byte 1 normalization name: indices into the lists below, each with
//               one unknown name so that the loader's rejection is exercised too;
//   byte 2      bit 0 Regularize(), bit 1 a diffuse base, bit 2 TransportMode::Importance,
//               bits 3-4 the BxDFReflTransFlags of Sample_f and PDF;
//   18 floats   (native byte order) roughness, threadangle, threadelevation, reflectance rgb,
//               diffuse rgb, wo xyz, wi xyz, uc, u0, u1.
// What a scene file cannot say is skipped: non-finite parameters (the parser refuses them) and
// parameters CreateFabricMaterial rejects. What pbrt's BxDF contract excludes is skipped or folded:
// directions must be unit vectors, so finite non-zero ones are normalized and others skipped;
// samples must lie in [0, 1), so finite ones are folded into it (the fractional part of |x|, the
// identity on [0, 1)) and others skipped.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"

#include "pbrt_ext/bxdfs/bxdfs.h"
#include "pbrt_ext/scene/create.h"

#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace pbrt::fuzz {

namespace {

constexpr const char *kSamplerNames[] = {"uniform", "cosine", "paper", "truncatedsinphi", "best",
                                         "unknown"};
constexpr const char *kNormalizationNames[] = {"paper", "unitpeak", "unknown"};
constexpr size_t kInputSize = 3 + 18 * sizeof(float);

// Sample_f promises f() and PDF() at the direction it made; FabricBxDF computes all three with the
// same expressions, and FabricDiffuseBxDF adds its two lobes in the same order, so they agree to
// rounding: a few float ulps (1e-7 each). 1e-5 leaves room for that and nothing more. Below
// kMinComparedPdf the values are denormal-range floats whose relative rounding error is unbounded;
// a sample there is never drawn in practice, and its weight is still checked to be finite.
constexpr Float kConsistencyTolerance = 1e-5f;
constexpr Float kMinComparedPdf = 1e-30f;
// f is symmetric by construction (FabricBxDF evaluates symmetric expressions in (wo, wi), the
// diffuse base is a constant): reciprocity must hold to the same rounding.
constexpr Float kReciprocityTolerance = 1e-5f;
// Sampled directions are built from an orthonormal frame and (sin, cos) pairs in float.
constexpr Float kUnitLengthTolerance = 1e-4f;

class Reader {
  public:
    explicit Reader(std::span<const uint8_t> data) : data(data) {}
    uint8_t Byte() { return data[pos++]; }
    Float Value() {
        float v;
        std::memcpy(&v, &data[pos], sizeof(v));
        pos += sizeof(v);
        return v;
    }

  private:
    std::span<const uint8_t> data;
    size_t pos = 0;
};

// A unit vector in double precision (no overflow for huge components, no loss for denormal ones);
// empty for non-finite or zero input.
std::optional<Vector3f> UnitDirection(Float x, Float y, Float z) {
    double len = std::sqrt(double(x) * x + double(y) * y + double(z) * z);
    if (!std::isfinite(len) || len == 0)
        return {};
    return Vector3f(Float(x / len), Float(y / len), Float(z / len));
}

std::optional<Float> UnitSample(Float x) {
    if (!std::isfinite(x))
        return {};
    Float a = std::abs(x);
    return a - std::floor(a);
}

ParsedParameter Parameter(std::string type, std::string name, std::vector<double> numbers,
                          std::vector<std::string> strings = {}) {
    ParsedParameter p;
    p.type = std::move(type);
    p.name = std::move(name);
    p.loc = {"input", 1, 1};
    p.numbers = std::move(numbers);
    p.strings = std::move(strings);
    return p;
}

// The first bytes of an input: what a scene file says about the material.
struct FabricParameters {
    uint8_t sampler, normalization, flags;
    Float values[9];
};

// The BxDF of a fabric material with the input's parameters; empty when a scene file could not
// ask for it.
std::optional<BxDF> MakeFabricBxDF(const FabricParameters &p) {
    for (Float v : p.values)
        if (!std::isfinite(v))
            return {};
    const Float *values = p.values;
    ParsedParameterVector params = {
        Parameter("string", "sampler", {}, {kSamplerNames[p.sampler % std::size(kSamplerNames)]}),
        Parameter("string", "normalization", {},
                  {kNormalizationNames[p.normalization % std::size(kNormalizationNames)]}),
        Parameter("float", "roughness", {values[0]}),
        Parameter("float", "threadangle", {values[1]}),
        Parameter("float", "threadelevation", {values[2]}),
        Parameter("rgb", "reflectance", {values[3], values[4], values[5]})};
    if (p.flags & 2)
        params.push_back(Parameter("rgb", "diffuse", {values[6], values[7], values[8]}));
    // No named textures and no spectrum files: the resolver needs neither a scene nor a folder.
    static const SceneDescription noScene;
    TextureResolver textures(noScene, "");
    try {
        FabricMaterial material =
            CreateFabricMaterial(ParameterDictionary(std::move(params)), textures, {});
        // Any visible wavelengths: the fabric's reflectances are the rgb's spectra there.
        SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
        BxDF bxdf = material.GetBxDF(TextureEvalContext(), lambda);
        if (p.flags & 1)
            bxdf.Regularize();
        return bxdf;
    } catch (const ParseError &) {
        return {};
    }
}

bool Valid(Float v) { return std::isfinite(v) && v >= 0; }
bool Valid(const SampledSpectrum &s) {
    for (int i = 0; i < NSpectrumSamples; ++i)
        if (!Valid(s[i]))
            return false;
    return true;
}

bool Close(Float a, Float b, Float tolerance) {
    return std::abs(a - b) <= tolerance * std::max(std::abs(a), std::abs(b));
}
bool Close(const SampledSpectrum &a, const SampledSpectrum &b, Float tolerance) {
    for (int i = 0; i < NSpectrumSamples; ++i)
        if (!Close(a[i], b[i], tolerance))
            return false;
    return true;
}

std::string Show(Vector3f v) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
    return buf;
}

// One evaluation and one sample at (wo, wi) with every invariant asserted.
class FabricCheck {
  public:
    FabricCheck(BxDF bxdf, Vector3f wo, Vector3f wi, TransportMode mode, BxDFReflTransFlags flags)
        : bxdf(std::move(bxdf)), wo(wo), wi(wi), mode(mode), flags(flags) {}

    void Evaluate() const {
        SampledSpectrum f = bxdf.f(wo, wi, mode), fReversed = bxdf.f(wi, wo, mode);
        Float pdf = bxdf.PDF(wo, wi, mode, flags);
        Require(Valid(f), "f(wo, wi) = " + f.ToString() + " is not finite and >= 0");
        Require(Valid(pdf), "PDF(wo, wi) = " + std::to_string(pdf) + " is not finite and >= 0");
        Require(Close(f, fReversed, kReciprocityTolerance),
                "not reciprocal: f(wo, wi) = " + f.ToString() + ", f(wi, wo) = " + fReversed.ToString());
    }

    void Sample(Float uc, Point2f u) const {
        pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, uc, u, mode, flags);
        if (!bs)
            return;
        std::string sample = " for the sample " + bs->ToString() + " at uc = " + std::to_string(uc) +
                             ", u = (" + std::to_string(u[0]) + ", " + std::to_string(u[1]) + ")";
        Require(std::isfinite(bs->pdf) && bs->pdf > 0, "pdf is not finite and > 0" + sample);
        Require(Valid(bs->f), "f is not finite and >= 0" + sample);
        Require(std::abs(Length(bs->wi) - 1) <= kUnitLengthTolerance, "wi is not a unit vector" + sample);
        Require((wo.z > 0 && bs->wi.z > 0) || (wo.z < 0 && bs->wi.z < 0),
                "a reflection-only BxDF sampled the other side" + sample);
        Require(std::isfinite((bs->f[0] + bs->f[1] + bs->f[2]) * std::abs(bs->wi.z) / bs->pdf),
                "the path weight f cos / pdf overflows" + sample);
        if (bs->pdf < kMinComparedPdf)
            return;
        SampledSpectrum f = bxdf.f(wo, bs->wi, mode);
        Float pdf = bxdf.PDF(wo, bs->wi, mode, flags);
        Require(Close(f, bs->f, kConsistencyTolerance), "f() = " + f.ToString() + " differs" + sample);
        Require(Close(pdf, bs->pdf, kConsistencyTolerance),
                "PDF() = " + std::to_string(pdf) + " differs" + sample);
    }

  private:
    void Require(bool ok, const std::string &what) const {
        if (!ok)
            ReportFinding("fabric", what + "\n  " + bxdf.ToString() + "\n  wo = " + Show(wo) +
                                        ", wi = " + Show(wi));
    }

    BxDF bxdf;
    Vector3f wo, wi;
    TransportMode mode;
    BxDFReflTransFlags flags;
};

}  // namespace

void FuzzFabric(std::span<const uint8_t> data) {
    if (data.size() < kInputSize)
        return;
    Reader in(data);
    FabricParameters p{in.Byte(), in.Byte(), in.Byte(), {}};
    Float w[6];
    for (Float &v : p.values)
        v = in.Value();
    for (Float &v : w)
        v = in.Value();
    std::optional<Vector3f> wo = UnitDirection(w[0], w[1], w[2]), wi = UnitDirection(w[3], w[4], w[5]);
    std::optional<Float> uc = UnitSample(in.Value()), u0 = UnitSample(in.Value()),
                         u1 = UnitSample(in.Value());
    if (!wo || !wi || !uc || !u0 || !u1)
        return;
    std::optional<BxDF> bxdf = MakeFabricBxDF(p);
    if (!bxdf)
        return;
    TransportMode mode = (p.flags & 4) ? TransportMode::Importance : TransportMode::Radiance;
    FabricCheck check(*bxdf, *wo, *wi, mode, BxDFReflTransFlags((p.flags >> 3) & 3));
    check.Evaluate();
    check.Sample(*uc, Point2f(*u0, *u1));
}

}  // namespace pbrt::fuzz
