// Generated from pbrt_ext/bxdfs/fabric.h by scripts/port-pbrt-v4 --regenerate: edit that file, not this one.
// FabricBxDF: the DreamWorks fabric specular lobe, implemented exactly.
//
// Source: P. Deshmukh, F. Xie, E. Tabellion, "DreamWorks Fabric Shading Model: from Artist Friendly to
// Physically Plausible", SIGGRAPH 2017 Talks. The lobe is the paper's cylindrical cone
//     S(wo, wi) = (1 - |sin θh|)^n,   θh = (θo + θi) / 2,   sin θ = w·T,
// for a thread (fiber) direction T; f = color · S · normalization, reflection only.
//
// What we do differently from the paper, and why (derivations: docs/fabric.md):
//   - The paper samples θh = asin(1 - ξ^(n+1)); that is a typo for ξ^(1/(n+1)).
//   - The paper converts its pdf with the half-vector Jacobian 1/(4 wi·wh), which belongs to reflection
//     about a half vector. Our samplers build wi from θi = 2θh - θo and an azimuth about T, whose Jacobian
//     is dωi = 2 cos θi dθh dφ. Every sampler here reports the exact density of what it produces.
//   - The normalization 1/I_o(n) is evaluated for any real n by a series in double precision; the
//     paper's binomial closed form cancels catastrophically (useless in float beyond n ≈ 20).
//   - The lobe is evaluated without trig and without cancellation (1 - |sin θh| = cos²θh / (1 + |sin θh|)).
//   - Elevated threads (T out of the tangent plane) are sampled in the fiber frame with an azimuth
//     restricted to the directions above the surface, with its exact density.
//   - An optional unit-peak normalization reaches a directional albedo of exactly 1 at its peak.
//
// Conventions (pbrt-v4): directions in the local shading frame (z = shading normal, x = dpdu), f excludes
// the cosine, pdfs are per unit solid angle, both directions point away from the surface. The lobe is
// two-sided: with wo below the surface, both directions are mirrored through the tangent plane.
#pragma once

#include <pbrt/bxdfs/fabric_compat.h>
#include <pbrt/pbrt.h>
#include <pbrt/util/math.h>
#include <pbrt/util/pstd.h>
#include <pbrt/util/sampling.h>
#include <pbrt/util/spectrum.h>
#include <pbrt/util/vecmath.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>

namespace pbrt {

// How Sample_f draws directions. All report their exact density.
enum class FabricSampling {
    Uniform,          // uniform hemisphere (baseline)
    Cosine,           // cosine hemisphere (baseline)
    Paper,            // the paper's θh sampling (typo fixed, independent sign), uniform azimuth about T
    TruncatedSinPhi,  // θh truncated to the visible range, azimuth ∝ cosine about N (FABRIC_MATH "S4")
    Best              // TruncatedSinPhi; for n <= 2 a one-sample 50/50 mixture with Cosine
};

// Scale of the lobe.
enum class FabricNormalization {
    Paper,    // 1 / I_o(n): the paper's; directional albedo ≤ 2/π for tangent threads
    UnitPeak  // the largest directional albedo over all wi is 1 (never above), for every n and elevation
};

// The names scene files give them ("string sampler", "string normalization"), in the enums' order.
inline constexpr const char *kFabricSamplingNames[] = {"uniform", "cosine", "paper", "truncatedsinphi",
                                                       "best"};
inline constexpr const char *kFabricNormalizationNames[] = {"paper", "unitpeak"};

// The option a scene file names, or nullopt and *error set to the message every renderer that reads
// "fabric" materials reports (pbrt_ext and the ports), e.g. `unknown fabric sampler "x": expected ...`.
template <typename Option, size_t N>
pstd::optional<Option> FabricOptionFromName(const char *what, const char *const (&names)[N],
                                            const std::string &name, std::string *error) {
    for (size_t i = 0; i < N; ++i)
        if (name == names[i])
            return Option(i);
    *error = std::string("unknown fabric ") + what + " \"" + name + "\": expected ";
    for (size_t i = 0; i < N; ++i)
        *error += std::string(names[i]) + (i + 2 < N ? ", " : (i + 1 < N ? " or " : ""));
    return {};
}

// ∫_0^{π/4} (1 - sin x)^n q(x) dx for q a polynomial in cos 2x given by its coefficients in
// u = 1 - sin x (cos 2x = -1 + 4u - 2u²). With u as variable the integrand is u^(n - 1/2) q(u) / √(2 - u);
// expanding 1/√(1 - u/2) = Σ γ_k u^k (γ_k = C(2k, k) / 8^k, ratio ≤ 1/2 on the range
// u ∈ [b, 1], b = 1 - 1/√2) integrates term by term. 40 terms reach 1e-13. bPowHalf = b^(n + 1/2).
PBRT_CPU_GPU constexpr double FabricFiberIntegral(double n, double bPowHalf, const double *q, int nq) {
    constexpr int nTerms = 40;
    constexpr double b = 0.292893218813452475599155637895;
    double gamma[5] = {1, 0, 0, 0, 0};  // γ_k .. γ_{k-4}, newest first
    double bPow = bPowHalf, sum = 0;
    for (int k = 0; k < nTerms; ++k) {
        if (k > 0) {
            for (int j = 4; j > 0; --j)
                gamma[j] = gamma[j - 1];
            gamma[0] = gamma[1] * (2 * k - 1) / (4 * k);
        }
        double d = 0;
        for (int j = 0; j < nq && j <= k; ++j)
            d += q[j] * gamma[j];
        sum += d * (1 - bPow) / (n + 0.5 + k);
        bPow *= b;
    }
    return sum * 0.70710678118654752440;
}

// The integrands' q: cos 2x (for I_o) and cos² 2x (for I_c), as coefficients in u.
PBRT_CONST double kFabricCos2x[] = {-1, 4, -2};
PBRT_CONST double kFabricCos2xSquared[] = {1, -8, 20, -16, 4};

// 1/I_o and 1/I_c for the integer exponents 0 ... 64, computed by the series at compile time: the
// paper's roughness mapping gives n in 1 ... 30, and a renderer makes a BxDF at every hit.
struct FabricNormalizationTable {
    static constexpr int size = 65;
    Float inverseIo[size], inverseIc[size];
};

PBRT_CPU_GPU constexpr FabricNormalizationTable MakeFabricNormalizationTable() {
    constexpr double sqrtB = 0.541196100146196984399723205366, fourPi = 4 * 3.14159265358979323846;
    FabricNormalizationTable table{};
    double bPowHalf = sqrtB;  // b^(n + 1/2)
    for (int n = 0; n < FabricNormalizationTable::size; ++n) {
        table.inverseIo[n] = Float(1 / (fourPi * FabricFiberIntegral(n, bPowHalf, kFabricCos2x, 3)));
        table.inverseIc[n] = Float(1 / (8 * FabricFiberIntegral(n, bPowHalf, kFabricCos2xSquared, 5)));
        bPowHalf *= 0.292893218813452475599155637895;
    }
    return table;
}

PBRT_CONST FabricNormalizationTable kFabricNormalizationTable = MakeFabricNormalizationTable();

// A lobe exponent given directly (continuous, any real n >= 0) instead of through roughness.
struct FabricExponent {
    Float n;
};

class FabricBxDF {
  public:
    FabricBxDF() = default;
    // Exponent from roughness with the paper's integer mapping n = ceil(1 + 29 (1 - r)²).
    PBRT_CPU_GPU FabricBxDF(SampledSpectrum color, Float roughness, Vector3f thread,
                            FabricSampling sampling = FabricSampling::Best,
                            FabricNormalization normalization = FabricNormalization::Paper)
        : FabricBxDF(color, FabricExponent{RoughnessToExponent(roughness)}, thread, sampling,
                     normalization) {}
    PBRT_CPU_GPU FabricBxDF(SampledSpectrum color, FabricExponent exponent, Vector3f thread,
                            FabricSampling sampling = FabricSampling::Best,
                            FabricNormalization normalization = FabricNormalization::Paper)
        : color(ClampZero(color)), sampling(sampling), normalization(normalization) {
        SetFiberFrame(thread);
        SetExponent(exponent.n);
    }

    // Roughness in [0, 1] (clamped; NaN counts as 0) to the lobe exponent: the paper's mapping, or its
    // continuous version without the ceil.
    PBRT_CPU_GPU static Float RoughnessToExponent(Float roughness, bool continuous = false) {
        Float r = roughness > 0 ? (roughness < 1 ? roughness : Float(1)) : Float(0);
        Float n = 1 + 29 * Sqr(1 - r);
        return continuous ? n : std::ceil(n);
    }

    // The thread direction in the local frame from artist parameters: an angle about N measured from
    // dpdu (x), then an elevation toward N, both in degrees.
    PBRT_CPU_GPU static Vector3f ThreadDirection(Float angleDegrees, Float elevationDegrees) {
        Float alpha = Radians(angleDegrees), beta = Radians(Clamp(elevationDegrees, -90, 90));
        return Vector3f(std::cos(beta) * std::cos(alpha), std::cos(beta) * std::sin(alpha),
                        std::sin(beta));
    }

    // 1 / I_o(n), I_o(n) = ∫_H² S(θi = 0, wo) dωo = 4π ∫_0^{π/4} (1 - sin x)^n cos 2x dx, any real n >= 0.
    PBRT_CPU_GPU static Float InverseIo(Float n);

    // 1 / I_c(n), I_c(n) = 8 ∫_0^{π/4} (1 - sin x)^n cos² 2x dx: the cosine-weighted integral of S at
    // θi = 0, where the directional albedo of a tangent thread peaks (docs/fabric.md).
    PBRT_CPU_GPU static Float InverseIc(Float n);

    // The factor that makes the peak directional albedo 1 for exponent n and thread elevation β.
    PBRT_CPU_GPU static Float UnitPeakNormalization(Float n, Float sinBeta, Float cosBeta) {
        return InverseIc(n) / UnitPeakElevationFactor(n, sinBeta, cosBeta);
    }

    PBRT_CPU_GPU BxDFFlags Flags() const {
        if (!color)
            return BxDFFlags::Unset;
        return n == 0 ? BxDFFlags::DiffuseReflection : BxDFFlags::GlossyReflection;
    }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode mode) const;
    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float uc, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const;
    PBRT_CPU_GPU Float PDF(Vector3f wo, Vector3f wi, TransportMode mode,
                           BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const;

    PBRT_CPU_GPU SampledSpectrum rho(Vector3f wo, pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, wo, uc, u2);
    }
    PBRT_CPU_GPU SampledSpectrum rho(pstd::span<const Point2f> u1, pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, u1, uc, u2);
    }

    // Widens a narrow lobe to tame paths that would otherwise be fireflies, by pbrt-v4's rule for
    // microfacet alpha (alpha < 0.3 becomes clamp(2 alpha, 0.1, 0.3)) applied to the lobe's angular
    // width alpha = 1 / (n + 1): E[1 - |sin θh|] scales as 1 / (n + 1). The exponent becomes continuous.
    PBRT_CPU_GPU void Regularize() {
        Float alpha = 1 / (n + 1);
        if (alpha < Float(0.3))
            SetExponent(1 / Clamp(2 * alpha, Float(0.1), Float(0.3)) - 1);
    }

    PBRT_CPU_GPU static constexpr const char *Name() { return "FabricBxDF"; }
    std::string ToString() const;

    PBRT_CPU_GPU Float Exponent() const { return n; }
    PBRT_CPU_GPU Float Normalization() const { return scale; }
    PBRT_CPU_GPU Vector3f Thread() const { return T; }
    PBRT_CPU_GPU SampledSpectrum Color() const { return color; }
    // An upper bound of the largest directional albedo per unit color, over all directions: 1 for
    // UnitPeak (up to rounding); I_c G / I_o for Paper, about 0.75 at most (conservative: G >= g).
    PBRT_CPU_GPU Float PeakAlbedo() const { return scale / UnitPeakNormalization(n, T.z, Np.z); }

  private:
    // Fiber coordinates of the pair (wo, wi): latitudes about T and the half angle θh.
    struct HalfAngle {
        Float sinThetaO, cosThetaO, sinThetaI, cosThetaI;
        Float sinThetaH, cosThetaH;
    };

    // Peak directional albedo of S/I_c at elevation β relative to β = 0, by a conservative table: 1 at
    // β = 0, up to 1.9 near β = 60°, toward 0 as β -> 90° (the lobe sinks below the horizon).
    PBRT_CPU_GPU static Float UnitPeakElevationFactor(Float n, Float sinBeta, Float cosBeta);

    PBRT_CPU_GPU void SetFiberFrame(Vector3f thread);
    PBRT_CPU_GPU void SetExponent(Float exponent);

    // Fiber latitude θ of a direction: sin θ = w·T, and cos θ = |w × T|, which keeps its digits near
    // the poles w = ±T where the samplers' density concentrates; √(1 - sin²θ) would not.
    PBRT_CPU_GPU Float SinLatitude(Vector3f w) const { return Clamp(Dot(w, T), -1, 1); }
    PBRT_CPU_GPU Float CosLatitude(Vector3f w) const { return Clamp(Length(Cross(w, T)), 0, 1); }
    PBRT_CPU_GPU HalfAngle Fiber(Vector3f wo, Vector3f wi) const;
    PBRT_CPU_GPU Float Lobe(const HalfAngle &h) const;

    // Densities of the lobe samplers, for directions above the surface.
    PBRT_CPU_GPU Float FiberLobePDF(const HalfAngle &h, Float S, Vector3f wi, bool truncated) const;
    // The density of the configured sampler at wi (both directions above the surface), given the
    // fiber coordinates h and lobe value S that f() also needs: Sample_f computes them once.
    PBRT_CPU_GPU Float SamplerPDF(const HalfAngle &h, Float S, Vector3f wi) const;
    PBRT_CPU_GPU pstd::optional<Vector3f> SampleFiberLobe(Vector3f wo, Float uc, Point2f u,
                                                          bool truncated) const;
    // The lobe is two-sided: below the surface, both directions are mirrored through it.
    PBRT_CPU_GPU static void MirrorToUpperSide(Vector3f &wo, Vector3f &wi) {
        if (wo.z < 0) {
            wo.z = -wo.z;
            wi.z = -wi.z;
        }
    }
    // By sign, not by the product wo.z * wi.z, which underflows to 0 for tiny (denormal) heights.
    PBRT_CPU_GPU static bool OnSameSide(Vector3f wo, Vector3f wi) {
        return (wo.z > 0 && wi.z > 0) || (wo.z < 0 && wi.z < 0);
    }
    PBRT_CPU_GPU bool UsesCosineMixture() const {
        return sampling == FabricSampling::Best && n <= 2;
    }

    SampledSpectrum color;
    Float n = 1, scale = 0;  // exponent; normalization (1/I_o or unit peak)
    int integerN = -1;       // n when it is a small integer (exact repeated squaring), else -1
    Vector3f T, B, Np;       // fiber frame: thread, N×T / |N×T|, T×B (Np·N = cos β >= 0)
    FabricSampling sampling = FabricSampling::Best;
    FabricNormalization normalization = FabricNormalization::Paper;
};

// ---------------------------------------------------------------------------------------------------
// Implementation

// The unit-peak elevation factor G(x, β) >= g = (peak albedo at β) / (peak albedo at β = 0) of the
// unnormalized lobe, x = 1 / (n + 1); bilinear in (x, β) after dividing out the corner factor C below.
// Generated by docs/fabric/unit_peak_table.py, which verifies 0.9957 <= peak albedo <= 0.9997 on
// 4344 off-grid (n, β) with n up to 1e6 (docs/fabric/unit_peak.md).
PBRT_CONST int kUnitPeakNX = 14, kUnitPeakNBeta = 20;
PBRT_CONST Float kUnitPeakX[kUnitPeakNX] = {0, 0.0125, 0.03, 0.06, 0.1, 0.15, 0.2, 0.275, 0.35, 0.45, 0.55, 0.7, 0.85, 1};
PBRT_CONST Float kUnitPeakBeta[kUnitPeakNBeta] = {  // degrees
    0, 13, 24, 32, 38, 42, 45, 48, 51, 54, 58, 62, 66, 70, 74, 78, 82, 86, 88.5, 90};
PBRT_CONST Float kUnitPeakG[kUnitPeakNX][kUnitPeakNBeta] = {
    {1.203022, 1.244945, 1.30613, 1.374374, 1.447195, 1.512299, 1.575225, 1.667782, 1.755467, 1.826219, 1.885323, 1.904513, 1.882476, 1.81948, 1.717292, 1.579231, 1.40997, 1.215326, 1.082463, 1.000555},  // x = 0
    {1.202942, 1.244819, 1.305925, 1.374083, 1.446842, 1.51196, 1.575472, 1.669259, 1.756999, 1.827826, 1.887082, 1.906486, 1.884749, 1.822119, 1.720415, 1.583037, 1.414934, 1.22281, 1.094745, 1.02644},  // x = 0.0125
    {1.202743, 1.244488, 1.305342, 1.373265, 1.446036, 1.512032, 1.577024, 1.669643, 1.757318, 1.828154, 1.887634, 1.907512, 1.886558, 1.825041, 1.724856, 1.589515, 1.424191, 1.238347, 1.120648, 1.059844},  // x = 0.03
    {1.202201, 1.243555, 1.303805, 1.37146, 1.444725, 1.511452, 1.576283, 1.661529, 1.74872, 1.819124, 1.878696, 1.89944, 1.88027, 1.821478, 1.725133, 1.595285, 1.438807, 1.267336, 1.16406, 1.109409},  // x = 0.06
    {1.201221, 1.24187, 1.301042, 1.367839, 1.440157, 1.505044, 1.565592, 1.64036, 1.72274, 1.79136, 1.850037, 1.871674, 1.855352, 1.801626, 1.713024, 1.594349, 1.453291, 1.302624, 1.21267, 1.163829},  // x = 0.1
    {1.199665, 1.239114, 1.296236, 1.360537, 1.428884, 1.487971, 1.54131, 1.603864, 1.67672, 1.74092, 1.796505, 1.818377, 1.805958, 1.760149, 1.683785, 1.581866, 1.461774, 1.334355, 1.258022, 1.215615},  // x = 0.15
    {1.197844, 1.235854, 1.290146, 1.350303, 1.412658, 1.465229, 1.511595, 1.564539, 1.626436, 1.684292, 1.734853, 1.755829, 1.74693, 1.70922, 1.645453, 1.560178, 1.459787, 1.353898, 1.289465, 1.253017},  // x = 0.2
    {1.194602, 1.230168, 1.279588, 1.332666, 1.385873, 1.429295, 1.466609, 1.508528, 1.557077, 1.604754, 1.647032, 1.665707, 1.660767, 1.633292, 1.58564, 1.521501, 1.446172, 1.366164, 1.316705, 1.288206},  // x = 0.275
    {1.190853, 1.223729, 1.26796, 1.314062, 1.358889, 1.394689, 1.425019, 1.458536, 1.496677, 1.535244, 1.57004, 1.586326, 1.58424, 1.564809, 1.529946, 1.482431, 1.425898, 1.365899, 1.328435, 1.30658},  // x = 0.35
    {1.185317, 1.214683, 1.25239, 1.29013, 1.325737, 1.353464, 1.376538, 1.40166, 1.42972, 1.458818, 1.485675, 1.499344, 1.500078, 1.488728, 1.466691, 1.43589, 1.398748, 1.359051, 1.334, 1.31915},  // x = 0.45
    {1.17932, 1.205354, 1.237232, 1.26805, 1.296291, 1.317847, 1.335539, 1.354578, 1.375427, 1.397465, 1.418446, 1.43024, 1.433144, 1.427808, 1.415218, 1.396676, 1.373781, 1.348647, 1.332836, 1.323384},  // x = 0.55
    {1.170017, 1.191595, 1.216212, 1.238799, 1.258736, 1.273574, 1.285547, 1.298255, 1.311958, 1.326606, 1.341509, 1.35156, 1.356991, 1.358185, 1.355673, 1.350124, 1.342333, 1.333368, 1.327817, 1.324365},  // x = 0.7
    {1.160776, 1.178604, 1.197503, 1.213915, 1.227884, 1.238039, 1.246112, 1.25458, 1.263557, 1.273166, 1.284087, 1.29318, 1.300571, 1.306429, 1.31097, 1.314456, 1.317187, 1.319489, 1.321038, 1.321927},  // x = 0.85
    {1.151936, 1.166664, 1.18104, 1.192767, 1.202345, 1.20913, 1.214438, 1.219942, 1.225677, 1.231778, 1.239985, 1.248561, 1.257515, 1.266848, 1.276554, 1.28662, 1.297023, 1.307731, 1.314608, 1.318762},  // x = 1
};


PBRT_CPU_GPU inline Float FabricBxDF::InverseIo(Float n) {
    if (n == std::floor(n) && n >= 0 && n < FabricNormalizationTable::size)
        return kFabricNormalizationTable.inverseIo[int(n)];
    double bPowHalf = std::pow(0.292893218813452475599155637895, double(n) + 0.5);
    return Float(1 / (4 * 3.14159265358979323846 *
                      FabricFiberIntegral(n, bPowHalf, kFabricCos2x, 3)));
}

PBRT_CPU_GPU inline Float FabricBxDF::InverseIc(Float n) {
    if (n == std::floor(n) && n >= 0 && n < FabricNormalizationTable::size)
        return kFabricNormalizationTable.inverseIc[int(n)];
    double bPowHalf = std::pow(0.292893218813452475599155637895, double(n) + 0.5);
    return Float(1 / (8 * FabricFiberIntegral(n, bPowHalf, kFabricCos2xSquared, 5)));
}

PBRT_CPU_GPU inline void FabricBxDF::SetFiberFrame(Vector3f thread) {
    Float len = Length(thread);
    T = (len > 0 && IsFinite(len)) ? thread / len : Vector3f(1, 0, 0);
    // B = N×T; when T is (nearly) the normal any direction perpendicular to it serves.
    Vector3f nxt(-T.y, T.x, 0);
    Float nxtLen = Length(nxt);
    if (nxtLen > Float(1e-7)) {
        B = nxt / nxtLen;
    } else {
        T = Vector3f(0, 0, T.z > 0 ? 1 : -1);
        B = Vector3f(0, 1, 0);
    }
    Np = Cross(T, B);
    // S is invariant under T -> -T: keep the thread on the upper side so that sin β = T.z >= 0.
    if (T.z < 0) {
        T = -T;
        B = -B;
    }
}

PBRT_CPU_GPU inline void FabricBxDF::SetExponent(Float exponent) {
    // NaN or negative exponents mean a flat lobe; huge ones are capped where float S is a delta anyway.
    n = exponent > 0 ? (exponent < Float(1e6) ? exponent : Float(1e6)) : Float(0);
    integerN = (n == std::floor(n) && n <= 64) ? int(n) : -1;
    scale = normalization == FabricNormalization::Paper ? InverseIo(n)
                                                        : UnitPeakNormalization(n, T.z, Np.z);
}

PBRT_CPU_GPU inline FabricBxDF::HalfAngle FabricBxDF::Fiber(Vector3f wo, Vector3f wi) const {
    HalfAngle h;
    h.sinThetaO = SinLatitude(wo);
    h.sinThetaI = SinLatitude(wi);
    h.cosThetaO = CosLatitude(wo);
    h.cosThetaI = CosLatitude(wi);
    // Half-angle formulas with D = 2 √((1 + cos θo)(1 + cos θi)) >= 2; 1 - sin θo sin θi is formed
    // without cancellation when the two latitudes share a sign. Every expression is symmetric in
    // (o, i), and it is evaluated on the pair in a fixed order, so f is reciprocal to the last bit
    // even where the compiler fuses a * b + c into one rounding (pbrt-v4 builds with -march=native).
    bool inOrder = h.sinThetaO < h.sinThetaI ||
                   (h.sinThetaO == h.sinThetaI && h.cosThetaO <= h.cosThetaI);
    Float so = inOrder ? h.sinThetaO : h.sinThetaI, si = inOrder ? h.sinThetaI : h.sinThetaO;
    Float co = inOrder ? h.cosThetaO : h.cosThetaI, ci = inOrder ? h.cosThetaI : h.cosThetaO;
    Float D = 2 * std::sqrt((1 + co) * (1 + ci));
    Float sMax = std::max(std::abs(so), std::abs(si)), sMin = std::min(std::abs(so), std::abs(si));
    Float oneMinusSoSi = so * si > 0 ? (1 - sMax) + sMax * (1 - sMin) : 1 + sMax * sMin;
    h.sinThetaH = Clamp((so * (1 + ci) + si * (1 + co)) / D, -1, 1);
    h.cosThetaH = Clamp((co + ci + co * ci + oneMinusSoSi) / D, 0, 1);
    return h;
}

// S = (1 - |sin θh|)^n with 1 - |sin θh| = cos²θh / (1 + |sin θh|): the direct difference loses every
// digit as |sin θh| -> 1. Small integer exponents (the paper's mapping) use exact repeated squaring.
PBRT_CPU_GPU inline Float FabricBxDF::Lobe(const HalfAngle &h) const {
    Float base = Sqr(h.cosThetaH) / (1 + std::abs(h.sinThetaH));
    return integerN >= 0 ? IntPow(base, integerN) : std::pow(base, n);
}

PBRT_CPU_GPU inline SampledSpectrum FabricBxDF::f(Vector3f wo, Vector3f wi, TransportMode) const {
    // S is symmetric in wo and wi, so both transport modes see the same f.
    if (!OnSameSide(wo, wi))
        return SampledSpectrum(0.f);
    MirrorToUpperSide(wo, wi);
    return color * (scale * Lobe(Fiber(wo, wi)));
}

// Truncation of the θh sampler (no sample below the fiber's latitude range): with positive θh,
// |sin θh| <= √((1 + sin θo)/2); with negative, |sin θh| <= √((1 - sin θo)/2). In t = 1 - |sin θh|,
// whose cdf is t^(n+1), each branch loses the mass a± = t±^(n+1) at its lower end.
struct FabricTruncation {
    Float aPlus, aMinus;
    PBRT_CPU_GPU Float Z() const { return 1 - (aPlus + aMinus) / 2; }
};

PBRT_CPU_GPU inline FabricTruncation FabricTruncate(Float sinThetaO, Float cosThetaO, Float n) {
    // 1 ± sin θo from cos²θo / (1 ∓ sin θo) where the direct sum cancels.
    Float so = sinThetaO, c2 = Sqr(cosThetaO);
    Float oneMinus = so > 0 ? c2 / (1 + so) : 1 - so;
    Float onePlus = so < 0 ? c2 / (1 - so) : 1 + so;
    // 1 - √x = (1 - x) / (1 + √x)
    Float tPlus = (oneMinus / 2) / (1 + std::sqrt(onePlus / 2));
    Float tMinus = (onePlus / 2) / (1 + std::sqrt(oneMinus / 2));
    return {std::pow(tPlus, n + 1), std::pow(tMinus, n + 1)};
}

// The azimuth about T of directions above the surface at latitude θi. With ψ = φ - π/2,
// wi·N = A + C cos ψ, A = sin θi sin β, C = cos θi cos β >= 0: visible for |ψ| < ψmax.
struct FabricArc {
    Float A, C, psiMax;

    PBRT_CPU_GPU FabricArc(Float sinThetaI, Float cosThetaI, Float sinBeta, Float cosBeta)
        : A(sinThetaI * sinBeta), C(cosThetaI * cosBeta) {
        if (A >= C)
            psiMax = Pi;
        else if (A <= -C)
            psiMax = 0;
        else
            psiMax = A == 0 ? PiOver2 : SafeACos(-A / C);
    }
    // ∫_{-ψmax}^{ψmax} (A + C cos ψ) dψ
    PBRT_CPU_GPU Float CosineIntegral() const {
        Float sinPsiMax = psiMax == Pi ? Float(0) : SafeSqrt(1 - Sqr(A / C));
        return 2 * (A * psiMax + C * sinPsiMax);
    }
    // ψ >= 0 with ∫_0^ψ (A + C cos) = target, by Newton's method safeguarded by bisection: the
    // integral is increasing and concave on [0, ψmax].
    PBRT_CPU_GPU Float InvertCosineIntegral(Float target) const {
        Float lo = 0, hi = psiMax, psi = 0;
        for (int i = 0; i < 40; ++i) {
            Float g = A * psi + C * std::sin(psi) - target;
            if (g > 0)
                hi = psi;
            else
                lo = psi;
            Float slope = A + C * std::cos(psi);
            Float next = slope > 0 ? psi - g / slope : (lo + hi) / 2;
            if (!(next >= lo && next <= hi))
                next = (lo + hi) / 2;
            if (std::abs(next - psi) <= Float(1e-7) * (1 + psi))
                return next;
            psi = next;
        }
        return psi;
    }
};

// The samplers' density of wi: p(θh) · p(φ | θi) / (2 cos θi), since dωi = 2 cos θi dθh dφ.
PBRT_CPU_GPU inline Float FabricBxDF::FiberLobePDF(const HalfAngle &h, Float S, Vector3f wi,
                                                   bool truncated) const {
    if (h.cosThetaI == 0)
        return 0;  // wi = ±T exactly: a point of integrable infinite density
    Float Z = truncated ? FabricTruncate(h.sinThetaO, h.cosThetaO, n).Z() : Float(1);
    Float pThetaH = (n + 1) / (2 * Z) * S * h.cosThetaH;
    FabricArc arc(h.sinThetaI, h.cosThetaI, T.z, Np.z);
    if (arc.psiMax == 0)
        return 0;
    Float cosineIntegral = arc.CosineIntegral();
    if (truncated && !(cosineIntegral > 0))
        return 0;
    Float pPhi = truncated ? wi.z / cosineIntegral : 1 / (2 * arc.psiMax);
    return pThetaH * pPhi / (2 * h.cosThetaI);
}

PBRT_CPU_GPU inline pstd::optional<Vector3f> FabricBxDF::SampleFiberLobe(Vector3f wo, Float uc,
                                                                         Point2f u,
                                                                         bool truncated) const {
    // θh: choose the sign, then t = 1 - |sin θh| from its cdf t^(n+1) (restricted to [a, 1]).
    Float so = SinLatitude(wo), co = CosLatitude(wo);
    FabricTruncation trunc = truncated ? FabricTruncate(so, co, n) : FabricTruncation{0, 0};
    Float massPlus = 1 - trunc.aPlus, massMinus = 1 - trunc.aMinus;
    bool positive = uc * (massPlus + massMinus) < massPlus;
    Float a = positive ? trunc.aPlus : trunc.aMinus;
    Float v = Lerp(u[0], a, Float(1));
    if (!(v > 0))
        return {};
    // |sin θh| = 1 - v^(1/(n+1)), via expm1 to keep its digits when it is small (large n).
    Float absSinH = Clamp(-std::expm1(std::log(v) / (n + 1)), 0, 1);
    Float sinH = positive ? absSinH : -absSinH;
    Float cosH = SafeSqrt((1 - absSinH) * (1 + absSinH));
    // θi = 2θh - θo without trig.
    Float sin2H = 2 * sinH * cosH, cos2H = (cosH - sinH) * (cosH + sinH);
    Float sinI = Clamp(sin2H * co - cos2H * so, -1, 1);
    Float cosI = cos2H * co + sin2H * so;
    if (!(cosI > 0))
        return {};  // only the untruncated sampler gets here: a latitude beyond the pole
    // Azimuth about T, restricted to the arc above the surface.
    Float cosPhi, sinPhi;
    if (T.z == 0) {
        // Tangent thread: the arc is φ ∈ (0, π); closed forms for both azimuth densities.
        if (truncated) {
            cosPhi = 1 - 2 * u[1];
            sinPhi = 2 * SafeSqrt(u[1] * (1 - u[1]));
        } else {
            cosPhi = std::cos(Pi * u[1]);
            sinPhi = std::sin(Pi * u[1]);
        }
    } else {
        FabricArc arc(sinI, cosI, T.z, Np.z);
        if (arc.psiMax == 0)
            return {};
        Float w = 2 * u[1] - 1;  // its sign picks the side of the arc, |w| the position
        Float psi = truncated ? arc.InvertCosineIntegral(std::abs(w) * arc.CosineIntegral() / 2)
                              : std::abs(w) * arc.psiMax;
        psi = w < 0 ? -psi : psi;
        cosPhi = -std::sin(psi);
        sinPhi = std::cos(psi);
    }
    return sinI * T + cosI * (cosPhi * B + sinPhi * Np);
}

PBRT_CPU_GPU inline pstd::optional<BSDFSample> FabricBxDF::Sample_f(
    Vector3f wo, Float uc, Point2f u, TransportMode, BxDFReflTransFlags sampleFlags) const {
    if (!(sampleFlags & BxDFReflTransFlags::Reflection) || !(wo.z != 0))
        return {};
    bool flip = wo.z < 0;
    if (flip)
        wo.z = -wo.z;
    pstd::optional<Vector3f> wi;
    switch (sampling) {
    case FabricSampling::Uniform:
        wi = SampleUniformHemisphere(u);
        break;
    case FabricSampling::Cosine:
        wi = SampleCosineHemisphere(u);
        break;
    case FabricSampling::Paper:
        wi = SampleFiberLobe(wo, uc, u, false);
        break;
    case FabricSampling::TruncatedSinPhi:
    case FabricSampling::Best:
        if (UsesCosineMixture() && uc < Float(0.5))
            wi = SampleCosineHemisphere(u);
        else
            wi = SampleFiberLobe(wo, UsesCosineMixture() ? 2 * uc - 1 : uc, u, true);
        break;
    }
    if (!wi || !(wi->z > 0))
        return {};
    // f and pdf exactly as f() and PDF() compute them at this direction, sharing their work.
    HalfAngle h = Fiber(wo, *wi);
    Float S = Lobe(h), pdf = SamplerPDF(h, S, *wi);
    if (!(pdf > 0))
        return {};
    if (flip)
        wi->z = -wi->z;
    return BSDFSample(color * (scale * S), *wi, pdf, Flags());
}

PBRT_CPU_GPU inline Float FabricBxDF::SamplerPDF(const HalfAngle &h, Float S, Vector3f wi) const {
    Float pdf = 0;
    switch (sampling) {
    case FabricSampling::Uniform:
        pdf = UniformHemispherePDF();
        break;
    case FabricSampling::Cosine:
        pdf = CosineHemispherePDF(wi.z);
        break;
    case FabricSampling::Paper:
        pdf = FiberLobePDF(h, S, wi, false);
        break;
    case FabricSampling::TruncatedSinPhi:
    case FabricSampling::Best:
        pdf = FiberLobePDF(h, S, wi, true);
        if (UsesCosineMixture())
            pdf = (pdf + CosineHemispherePDF(wi.z)) / 2;
        break;
    }
    return IsFinite(pdf) ? pdf : Float(0);
}

PBRT_CPU_GPU inline Float FabricBxDF::PDF(Vector3f wo, Vector3f wi, TransportMode,
                                          BxDFReflTransFlags sampleFlags) const {
    if (!(sampleFlags & BxDFReflTransFlags::Reflection) || !OnSameSide(wo, wi))
        return 0;
    MirrorToUpperSide(wo, wi);
    HalfAngle h = Fiber(wo, wi);
    bool needsLobe = sampling != FabricSampling::Uniform && sampling != FabricSampling::Cosine;
    return SamplerPDF(h, needsLobe ? Lobe(h) : Float(0), wi);
}

// e^-z I0(z) for z >= 0 (Abramowitz & Stegun 9.8.1 and 9.8.2, relative error < 5e-7).
PBRT_CPU_GPU inline Float FabricScaledBesselI0(Float z) {
    if (z <= Float(3.75)) {
        Float t2 = Sqr(z / Float(3.75));
        return EvaluatePolynomial(t2, 1.f, 3.5156229f, 3.0899424f, 1.2067492f, 0.2659732f,
                                  0.0360768f, 0.0045813f) *
               std::exp(-z);
    }
    return EvaluatePolynomial(Float(3.75) / z, 0.39894228f, 0.01328592f, 0.00225319f,
                              -0.00157565f, 0.00916281f, -0.02057706f, 0.02635537f, -0.01647633f,
                              0.00392377f) /
           std::sqrt(z);
}

PBRT_CPU_GPU inline Float FabricBxDF::UnitPeakElevationFactor(Float n, Float sinBeta,
                                                              Float cosBeta) {
    if (sinBeta == 0)
        return 1;  // exact: a tangent thread peaks at I_c by construction (the table's margin aside)
    Float x = 1 / (n + 1);
    Float beta = Degrees(std::atan2(std::abs(sinBeta), cosBeta));
    // As n -> ∞ and β -> 90° together, g -> π x Φ(ε/x), Φ(t) = t + e^(-t/2) I0(t/2), ε = π/2 - β:
    // a shape no grid in (x, β) follows. The table holds G / C with C = M / (1 + M) -> 1 elsewhere.
    Float eps = std::atan2(cosBeta, std::abs(sinBeta));
    Float M = Pi * (eps + x * FabricScaledBesselI0(eps / (2 * x)));
    Float C = M / (1 + M);
    int i = 0, j = 0;
    while (i < kUnitPeakNX - 2 && x > kUnitPeakX[i + 1])
        ++i;
    while (j < kUnitPeakNBeta - 2 && beta > kUnitPeakBeta[j + 1])
        ++j;
    Float u = Clamp((x - kUnitPeakX[i]) / (kUnitPeakX[i + 1] - kUnitPeakX[i]), 0, 1);
    Float v = Clamp((beta - kUnitPeakBeta[j]) / (kUnitPeakBeta[j + 1] - kUnitPeakBeta[j]), 0, 1);
    Float G = Lerp(u, Lerp(v, kUnitPeakG[i][j], kUnitPeakG[i][j + 1]),
                   Lerp(v, kUnitPeakG[i + 1][j], kUnitPeakG[i + 1][j + 1]));
    return C * G;
}

inline std::string FabricBxDF::ToString() const {
    char buf[512];
    std::snprintf(buf, sizeof(buf),
                  "[ FabricBxDF color: [ %g, %g, %g ] n: %g normalization: %s scale: %g "
                  "thread: [ %g, %g, %g ] sampling: %s ]",
                  color[0], color[1], color[2], n,
                  kFabricNormalizationNames[int(normalization)], scale, T.x, T.y, T.z,
                  kFabricSamplingNames[int(sampling)]);
    return buf;
}

}  // namespace pbrt
