// pbrt_ext: pbrt-v4's HairBxDF (Physically Based Rendering, 4th edition, Section 9.9), the
// scattering model of Chiang, Bitterli, Tappan and Burley, "A Practical and Controllable Hair
// and Fur Model for Production Path Tracing" (2016): a dielectric cylinder with an absorbing
// interior, whose light leaves after p = 0 (R), 1 (TT), 2 (TRT) or more internal paths, each with
// a longitudinal lobe Mp (roughness beta_m), an azimuthal lobe Np (beta_n, a trimmed logistic)
// and an attenuation Ap; cuticle scales tilt the lobes by alpha.
//
// The local frame is the curve's: x along the hair (dp/du), z the shading normal; h in [-1, 1]
// is where across the width the hair was hit (pbrt-v4: -1 + 2 v). Sample_f() picks p in
// proportion to the attenuations averaged over the wavelengths, then samples Mp and Np exactly,
// and returns the exact density of that procedure, which PDF() computes too; without absorption
// the two choices coincide and every sample's weight f cos / pdf is 1.
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <array>
#include <cmath>
#include <string>

namespace pbrt {

namespace hairdetail {

// The modified Bessel function of the first kind, order 0, by its series, summed until it
// converges (up to x = 12, where LogI0 turns asymptotic, that takes about 25 terms), and its
// logarithm, by Hankel's asymptotic series for larger x (five terms: below 1e-6 there).
// Sample_f() inverts the exact lobe, so Mp must be exact for the pdf to be the samples'
// density. pbrt-v4 is not quite: it stops the series at 10 terms (I0 up to 2 % short near
// x = 12) and halves the asymptotic 1/(8x) term, which leaves the narrow TT lobe 0.15 % short.
PBRT_CPU_GPU inline Float I0(Float x) {
    double sum = 1, term = 1, q = double(x) * x / 4;
    for (int i = 1; i < 60 && term > 1e-9 * sum; ++i) {
        term *= q / (double(i) * i);
        sum += term;
    }
    return Float(sum);
}

PBRT_CPU_GPU inline Float LogI0(Float x) {
    if (x <= 12)
        return std::log(I0(x));
    double r = 1 / double(x);
    double series = 1 + r * (1. / 8 + r * (9. / 128 + r * (75. / 1024 + r * (3675. / 32768))));
    return Float(x - 0.5 * std::log(2 * Pi * double(x)) + std::log(series));
}

// The longitudinal lobe at variance v; below v = 0.1 in log space, where I0 overflows (with
// 1 / sinh(1 / v) = 2 e^(-1/v), exact to e^(-20); pbrt-v4 rounds ln 2 to 0.6931).
PBRT_CPU_GPU inline Float Mp(Float cosTheta_i, Float cosTheta_o, Float sinTheta_i,
                             Float sinTheta_o, Float v) {
    Float a = cosTheta_i * cosTheta_o / v, b = sinTheta_i * sinTheta_o / v;
    if (v <= 0.1f)
        return std::exp(LogI0(a) - b - 1 / v + 0.69314718f + std::log(1 / (2 * v)));
    return std::exp(-b) * I0(a) / (std::sinh(1 / v) * 2 * v);
}

PBRT_CPU_GPU inline Float Logistic(Float x, Float s) {
    x = std::abs(x);
    return std::exp(-x / s) / (s * Sqr(1 + std::exp(-x / s)));
}

PBRT_CPU_GPU inline Float LogisticCDF(Float x, Float s) { return 1 / (1 + std::exp(-x / s)); }

PBRT_CPU_GPU inline Float TrimmedLogistic(Float x, Float s, Float a, Float b) {
    return Logistic(x, s) / (LogisticCDF(b, s) - LogisticCDF(a, s));
}

PBRT_CPU_GPU inline Float SampleTrimmedLogistic(Float u, Float s, Float a, Float b) {
    Float k = LogisticCDF(b, s) - LogisticCDF(a, s);
    Float x = -s * std::log(1 / (u * k + LogisticCDF(a, s)) - 1);
    return Clamp(x, a, b);
}

// The azimuth at which path p leaves.
PBRT_CPU_GPU inline Float Phi(int p, Float gamma_o, Float gamma_t) {
    return 2 * p * gamma_t - 2 * gamma_o + p * Pi;
}

PBRT_CPU_GPU inline Float Np(Float phi, int p, Float s, Float gamma_o, Float gamma_t) {
    Float dphi = phi - Phi(p, gamma_o, gamma_t);
    while (dphi > Pi)
        dphi -= 2 * Pi;
    while (dphi < -Pi)
        dphi += 2 * Pi;
    return TrimmedLogistic(dphi, s, -Pi, Pi);
}

}  // namespace hairdetail

class HairBxDF {
  public:
    static constexpr int pMax = 3;

    HairBxDF() = default;
    // alpha in degrees; beta_m, beta_n in [0, 1].
    PBRT_CPU_GPU HairBxDF(Float h, Float eta, const SampledSpectrum &sigma_a, Float beta_m,
                          Float beta_n, Float alpha)
        : h(h), eta(eta), sigma_a(sigma_a), beta_m(beta_m), beta_n(beta_n) {
        // The lobes' variances, from the roughnesses by Chiang et al.'s fits.
        v[0] = Sqr(0.726f * beta_m + 0.812f * Sqr(beta_m) + 3.7f * Pow20(beta_m));
        v[1] = .25f * v[0];
        v[2] = 4 * v[0];
        for (int p = 3; p <= pMax; ++p)
            v[p] = v[2];
        constexpr Float SqrtPiOver8 = 0.626657069f;
        s = SqrtPiOver8 * (0.265f * beta_n + 1.194f * Sqr(beta_n) + 5.372f * Pow22(beta_n));
        // sin and cos of 2^k alpha, which tilt the lobes of R, TT and TRT.
        sin2kAlpha[0] = std::sin(Radians(alpha));
        cos2kAlpha[0] = SafeSqrt(1 - Sqr(sin2kAlpha[0]));
        for (int i = 1; i < pMax; ++i) {
            sin2kAlpha[i] = 2 * cos2kAlpha[i - 1] * sin2kAlpha[i - 1];
            cos2kAlpha[i] = Sqr(cos2kAlpha[i - 1]) - Sqr(sin2kAlpha[i - 1]);
        }
    }

    PBRT_CPU_GPU BxDFFlags Flags() const { return BxDFFlags::GlossyReflection; }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode /*mode*/) const {
        Geometry g = GeometryOf(wo);
        Float sinTheta_i = wi.x, cosTheta_i = SafeSqrt(1 - Sqr(sinTheta_i));
        Float phi = std::atan2(wi.z, wi.y) - g.phi_o;
        SampledSpectrum T = Exp(-sigma_a * (2 * g.cosGamma_t / g.cosTheta_t));
        SampledSpectrum fsum = SumLobes(g, sinTheta_i, cosTheta_i, phi, Ap(g.cosTheta_o, T));
        if (AbsCosTheta(wi) > 0)
            fsum /= AbsCosTheta(wi);
        return fsum;
    }

    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float uc, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection))
            return {};
        Geometry g = GeometryOf(wo);
        std::array<Float, pMax + 1> apPDF = ApPDF(g.cosTheta_o);
        // Choose the path by uc, then reuse what is left of uc for its azimuth.
        int p = 0;
        for (; p < pMax && uc >= apPDF[p]; ++p)
            uc -= apPDF[p];
        uc = apPDF[p] > 0 ? std::min(uc / apPDF[p], OneMinusEpsilon) : 0;
        auto [sinThetap_o, cosThetap_o] = TiltedTheta(p, g.sinTheta_o, g.cosTheta_o);
        // Mp about the tilted lobe, then Np about the path's exit azimuth.
        Float cosTheta =
            1 + v[p] * std::log(std::max<Float>(u[0], 1e-5f) + (1 - u[0]) * std::exp(-2 / v[p]));
        Float sinTheta = SafeSqrt(1 - Sqr(cosTheta));
        Float cosPhi = std::cos(2 * Pi * u[1]);
        Float sinTheta_i = -cosTheta * sinThetap_o + sinTheta * cosPhi * cosThetap_o;
        Float cosTheta_i = SafeSqrt(1 - Sqr(sinTheta_i));
        Float dphi = p < pMax ? hairdetail::Phi(p, g.gamma_o, g.gamma_t) +
                                    hairdetail::SampleTrimmedLogistic(uc, s, -Pi, Pi)
                              : 2 * Pi * uc;
        Float phi_i = g.phi_o + dphi;
        Vector3f wi(sinTheta_i, cosTheta_i * std::cos(phi_i), cosTheta_i * std::sin(phi_i));
        Float pdf = PDF(wo, wi, mode, sampleFlags);
        if (!(pdf > 0) || wi.z == 0)
            return {};
        return BSDFSample(f(wo, wi, mode), wi, pdf, Flags());
    }

    PBRT_CPU_GPU Float PDF(Vector3f wo, Vector3f wi, TransportMode /*mode*/,
                           BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection))
            return 0;
        Geometry g = GeometryOf(wo);
        Float sinTheta_i = wi.x, cosTheta_i = SafeSqrt(1 - Sqr(sinTheta_i));
        Float phi = std::atan2(wi.z, wi.y) - g.phi_o;
        return SumLobes(g, sinTheta_i, cosTheta_i, phi, ApPDF(g.cosTheta_o));
    }

    PBRT_CPU_GPU SampledSpectrum rho(Vector3f wo, pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, wo, uc, u2);
    }
    PBRT_CPU_GPU SampledSpectrum rho(pstd::span<const Point2f> u1, pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, u1, uc, u2);
    }

    // Nothing to widen: the lobes' roughnesses are the hair's own.
    PBRT_CPU_GPU void Regularize() {}

    PBRT_CPU_GPU static constexpr const char *Name() { return "HairBxDF"; }

    std::string ToString() const {
        return "[ HairBxDF h: " + std::to_string(h) + " eta: " + std::to_string(eta) +
               " beta_m: " + std::to_string(beta_m) + " beta_n: " + std::to_string(beta_n) +
               " sigma_a: " + sigma_a.ToString() + " ]";
    }

    // The absorption coefficient that gives, after multiple scattering, about the colour c
    // (Chiang et al.'s inverse fit in beta_n), per wavelength.
    PBRT_CPU_GPU static SampledSpectrum SigmaAFromReflectance(const SampledSpectrum &c,
                                                              Float beta_n) {
        SampledSpectrum sigma;
        for (int i = 0; i < NSpectrumSamples; ++i)
            sigma[i] = Sqr(std::log(c[i]) /
                           (5.969f - 0.215f * beta_n + 2.532f * Sqr(beta_n) -
                            10.73f * Pow3(beta_n) + 5.574f * Pow4(beta_n) +
                            0.245f * Pow5(beta_n)));
        return sigma;
    }

  private:
    // What every method needs of wo: its angles, and the refracted ray's.
    struct Geometry {
        Float sinTheta_o, cosTheta_o, phi_o, gamma_o, cosTheta_t, gamma_t, cosGamma_t;
    };
    PBRT_CPU_GPU Geometry GeometryOf(Vector3f wo) const {
        Geometry g;
        g.sinTheta_o = wo.x;
        g.cosTheta_o = SafeSqrt(1 - Sqr(g.sinTheta_o));
        g.phi_o = std::atan2(wo.z, wo.y);
        g.gamma_o = SafeASin(h);
        Float sinTheta_t = g.sinTheta_o / eta;
        g.cosTheta_t = SafeSqrt(1 - Sqr(sinTheta_t));
        // The refracted ray's azimuthal offset, through the modified index of refraction.
        Float etap = SafeSqrt(Sqr(eta) - Sqr(g.sinTheta_o)) / g.cosTheta_o;
        Float sinGamma_t = h / etap;
        g.cosGamma_t = SafeSqrt(1 - Sqr(sinGamma_t));
        g.gamma_t = SafeASin(sinGamma_t);
        return g;
    }

    // The lobes Mp Np weighted by path, the paths beyond pMax spread evenly around the fiber:
    // f (times |cos theta_i|) with the attenuations Ap, the pdf with the path probabilities.
    template <typename T>
    PBRT_CPU_GPU T SumLobes(const Geometry &g, Float sinTheta_i, Float cosTheta_i, Float phi,
                            const std::array<T, pMax + 1> &weight) const {
        T sum(0.f);
        for (int p = 0; p < pMax; ++p) {
            auto [sinThetap_o, cosThetap_o] = TiltedTheta(p, g.sinTheta_o, g.cosTheta_o);
            sum += hairdetail::Mp(cosTheta_i, cosThetap_o, sinTheta_i, sinThetap_o, v[p]) *
                   weight[p] * hairdetail::Np(phi, p, s, g.gamma_o, g.gamma_t);
        }
        return sum + hairdetail::Mp(cosTheta_i, g.cosTheta_o, sinTheta_i, g.sinTheta_o, v[pMax]) *
                         weight[pMax] / (2 * Pi);
    }

    // The lobe of path p leaves tilted by the scales: R by -2 alpha, TT by alpha, TRT by 4 alpha.
    PBRT_CPU_GPU std::array<Float, 2> TiltedTheta(int p, Float sinTheta_o, Float cosTheta_o) const {
        Float sin2, cos2, sign;
        switch (p) {
        case 0: sin2 = sin2kAlpha[1], cos2 = cos2kAlpha[1], sign = -1; break;
        case 1: sin2 = sin2kAlpha[0], cos2 = cos2kAlpha[0], sign = 1; break;
        case 2: sin2 = sin2kAlpha[2], cos2 = cos2kAlpha[2], sign = 1; break;
        default: return {sinTheta_o, cosTheta_o};
        }
        return {sinTheta_o * cos2 + sign * cosTheta_o * sin2,
                std::abs(cosTheta_o * cos2 - sign * sinTheta_o * sin2)};
    }

    // The fraction of light leaving after each path: Fresnel at the cuticle, T per crossing.
    PBRT_CPU_GPU std::array<SampledSpectrum, pMax + 1> Ap(Float cosTheta_o,
                                                         const SampledSpectrum &T) const {
        std::array<SampledSpectrum, pMax + 1> ap;
        Float cosGamma_o = SafeSqrt(1 - Sqr(h));
        Float f = FrDielectric(cosTheta_o * cosGamma_o, eta);
        ap[0] = SampledSpectrum(f);
        ap[1] = Sqr(1 - f) * T;
        for (int p = 2; p < pMax; ++p)
            ap[p] = ap[p - 1] * T * f;
        // All longer paths together, a geometric series (none where nothing gets through).
        for (int i = 0; i < NSpectrumSamples; ++i) {
            Float tf = T[i] * f;
            ap[pMax][i] = tf < 1 ? ap[pMax - 1][i] * tf / (1 - tf) : 0;
        }
        return ap;
    }

    // The probabilities of choosing each path: Ap averaged over the wavelengths, normalized.
    PBRT_CPU_GPU std::array<Float, pMax + 1> ApPDF(Float cosTheta_o) const {
        Float sinTheta_o = SafeSqrt(1 - Sqr(cosTheta_o));
        Float cosTheta_t = SafeSqrt(1 - Sqr(sinTheta_o / eta));
        Float etap = SafeSqrt(Sqr(eta) - Sqr(sinTheta_o)) / cosTheta_o;
        Float cosGamma_t = SafeSqrt(1 - Sqr(h / etap));
        SampledSpectrum T = Exp(-sigma_a * (2 * cosGamma_t / cosTheta_t));
        std::array<SampledSpectrum, pMax + 1> ap = Ap(cosTheta_o, T);
        std::array<Float, pMax + 1> pdf;
        Float sum = 0;
        for (int i = 0; i <= pMax; ++i)
            sum += pdf[i] = ap[i].Average();
        for (Float &x : pdf)
            x /= sum;
        return pdf;
    }

    static constexpr Float Pow3(Float x) { return x * x * x; }
    static constexpr Float Pow4(Float x) { return Sqr(Sqr(x)); }
    static constexpr Float Pow5(Float x) { return Pow4(x) * x; }
    static constexpr Float Pow20(Float x) { return Sqr(Pow5(Sqr(x))); }
    static constexpr Float Pow22(Float x) { return Pow20(x) * Sqr(x); }

    Float h = 0, eta = 1.55f;
    SampledSpectrum sigma_a;
    Float beta_m = 0.3f, beta_n = 0.3f;
    std::array<Float, pMax + 1> v;
    Float s;
    std::array<Float, pMax> sin2kAlpha, cos2kAlpha;
};

}  // namespace pbrt
