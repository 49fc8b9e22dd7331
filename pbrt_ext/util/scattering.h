// pbrt_ext: scattering geometry, Fresnel reflectance and the Trowbridge-Reitz microfacet
// distribution, with pbrt-v4's names and semantics (pbrt-v4 src/pbrt/util/scattering.h).
//
// References (Physically Based Rendering, 4th edition, "pbrt-v4"):
//   Section 9.3   specular reflection and Snell's law (Reflect, Refract), the Fresnel
//                 equations for dielectrics (FrDielectric) and conductors (FrComplex);
//   Section 9.6   the Trowbridge-Reitz (GGX) distribution, Smith masking-shadowing, and
//                 sampling of visible normals (Heitz, "Sampling the GGX Distribution of
//                 Visible Normals", JCGT 2018).
// Conventions: all directions live in the local shading frame (z = normal), point away
// from the surface and are normalized.
//
// Differs from pbrt-v4: pbrt-v4's scalar FrComplex takes a pstd::complex; here the scalar
// overload takes (eta, k) as two Floats so that the complex type can stay private.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace pbrt {

// Mirror wo about n; both point away from the surface.
PBRT_CPU_GPU inline Vector3f Reflect(Vector3f wo, Vector3f n) {
    return -wo + 2 * Dot(wo, n) * n;
}

// Refract wi through an interface with normal n and relative index eta (inside over
// outside, with n on the outside). If wi arrives from the inside (below n), the interface
// is flipped first, so *etap reports the relative index actually used. Returns false on
// total internal reflection, leaving *wt and *etap untouched.
PBRT_CPU_GPU inline bool Refract(Vector3f wi, Normal3f n, Float eta, Float *etap,
                                 Vector3f *wt) {
    Float cosTheta_i = Dot(n, wi);
    if (cosTheta_i < 0) {
        eta = 1 / eta;
        cosTheta_i = -cosTheta_i;
        n = -n;
    }
    Float sin2Theta_i = std::max<Float>(0, 1 - Sqr(cosTheta_i));
    Float sin2Theta_t = sin2Theta_i / Sqr(eta);
    if (sin2Theta_t >= 1)
        return false;
    Float cosTheta_t = SafeSqrt(1 - sin2Theta_t);
    *wt = -wi / eta + (cosTheta_i / eta - cosTheta_t) * Vector3f(n);
    if (etap)
        *etap = eta;
    return true;
}

// Unpolarized Fresnel reflectance of a dielectric interface. A negative cosTheta_i means
// the light arrives from inside, which swaps the two media.
PBRT_CPU_GPU inline Float FrDielectric(Float cosTheta_i, Float eta) {
    cosTheta_i = Clamp(cosTheta_i, -1, 1);
    if (cosTheta_i < 0) {
        eta = 1 / eta;
        cosTheta_i = -cosTheta_i;
    }
    Float sin2Theta_t = (1 - Sqr(cosTheta_i)) / Sqr(eta);
    if (sin2Theta_t >= 1)
        return 1;  // total internal reflection
    Float cosTheta_t = SafeSqrt(1 - sin2Theta_t);
    Float r_parl = (eta * cosTheta_i - cosTheta_t) / (eta * cosTheta_i + cosTheta_t);
    Float r_perp = (cosTheta_i - eta * cosTheta_t) / (cosTheta_i + eta * cosTheta_t);
    return (Sqr(r_parl) + Sqr(r_perp)) / 2;
}

namespace detail {

// Just the complex arithmetic the conductor Fresnel equations need: std::complex is not
// usable in device code, and pbrt-v4's pstd::complex is not part of this project's pstd.
struct FresnelComplex {
    Float re, im;

    // Implicit from Float, so that real operands mix in as they do with std::complex.
    PBRT_CPU_GPU FresnelComplex(Float re0, Float im0 = 0) : re(re0), im(im0) {}

    PBRT_CPU_GPU friend FresnelComplex operator+(FresnelComplex a, FresnelComplex b) {
        return {a.re + b.re, a.im + b.im};
    }
    PBRT_CPU_GPU friend FresnelComplex operator-(FresnelComplex a, FresnelComplex b) {
        return {a.re - b.re, a.im - b.im};
    }
    PBRT_CPU_GPU friend FresnelComplex operator*(FresnelComplex a, FresnelComplex b) {
        return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
    }
    PBRT_CPU_GPU friend FresnelComplex operator/(FresnelComplex a, FresnelComplex b) {
        Float scale = 1 / (b.re * b.re + b.im * b.im);
        return {scale * (a.re * b.re + a.im * b.im), scale * (a.im * b.re - a.re * b.im)};
    }
    // Squared magnitude, as std::norm.
    PBRT_CPU_GPU friend Float Norm(FresnelComplex z) { return z.re * z.re + z.im * z.im; }

    // Principal square root (non-negative real part): the branch on which FrComplex's
    // transmitted wave decays into the conductor instead of growing.
    PBRT_CPU_GPU friend FresnelComplex Sqrt(FresnelComplex z) {
        Float n = std::hypot(z.re, z.im);
        if (n == 0)
            return {0, 0};
        Float t1 = std::sqrt(Float(0.5) * (n + std::abs(z.re)));
        Float t2 = Float(0.5) * z.im / t1;
        if (z.re >= 0)
            return {t1, t2};
        return {std::abs(t2), std::copysign(t1, z.im)};
    }
};

}  // namespace detail

// Unpolarized Fresnel reflectance of a conductor with complex index eta + i k, seen from
// the dielectric side: the dielectric formulas continue analytically to complex eta.
// Light cannot arrive from inside a conductor, so cosTheta_i is clamped to [0, 1].
PBRT_CPU_GPU inline Float FrComplex(Float cosTheta_i, Float eta, Float k) {
    using Complex = detail::FresnelComplex;
    Complex etac(eta, k);
    cosTheta_i = Clamp(cosTheta_i, 0, 1);
    Float sin2Theta_i = 1 - Sqr(cosTheta_i);
    Complex sin2Theta_t = Complex(sin2Theta_i) / (etac * etac);
    Complex cosTheta_t = Sqrt(Complex(1) - sin2Theta_t);
    Complex r_parl = (etac * cosTheta_i - cosTheta_t) / (etac * cosTheta_i + cosTheta_t);
    Complex r_perp = (Complex(cosTheta_i) - etac * cosTheta_t) /
                     (Complex(cosTheta_i) + etac * cosTheta_t);
    return (Norm(r_parl) + Norm(r_perp)) / 2;
}

// Per channel: each RGB channel carries its own complex index.
PBRT_CPU_GPU inline SampledSpectrum FrComplex(Float cosTheta_i, SampledSpectrum eta,
                                              SampledSpectrum k) {
    SampledSpectrum result(0.f);
    for (int i = 0; i < NSpectrumSamples; ++i)
        result[i] = FrComplex(cosTheta_i, eta[i], k[i]);
    return result;
}

// The anisotropic Trowbridge-Reitz (GGX) microfacet distribution with the Smith
// height-correlated masking-shadowing function (pbrt-v4 Section 9.6). alpha_x and alpha_y
// are the roughness along the shading frame's x and y axes.
class TrowbridgeReitzDistribution {
  public:
    TrowbridgeReitzDistribution() = default;
    PBRT_CPU_GPU TrowbridgeReitzDistribution(Float ax, Float ay) : alpha_x(ax), alpha_y(ay) {
        // A rough distribution with one near-zero alpha would overflow the slope term in
        // D(), so its alphas get a floor; an effectively smooth one is left as given.
        // (Float(MinAlpha) passes a copy: device code cannot bind a reference to it.)
        if (!EffectivelySmooth()) {
            alpha_x = std::max(alpha_x, Float(MinAlpha));
            alpha_y = std::max(alpha_y, Float(MinAlpha));
        }
    }

    // Fraction of microfacet area (per unit macro area and solid angle) facing wm.
    PBRT_CPU_GPU Float D(Vector3f wm) const {
        Float tan2Theta = Tan2Theta(wm);
        if (IsInf(tan2Theta))
            return 0;
        Float cos4Theta = Sqr(Cos2Theta(wm));
        if (cos4Theta < 1e-16f)
            return 0;
        Float e = tan2Theta * InvAlpha2(wm);
        return 1 / (Pi * alpha_x * alpha_y * cos4Theta * Sqr(1 + e));
    }

    // Below this roughness, callers treat the surface as a perfect mirror: the lobe is
    // too narrow to sample or evaluate reliably in single precision.
    PBRT_CPU_GPU bool EffectivelySmooth() const {
        return std::max(alpha_x, alpha_y) < SmoothAlpha;
    }

    // Smith masking: fraction of the microfacets facing w that w can see.
    PBRT_CPU_GPU Float G1(Vector3f w) const { return 1 / (1 + Lambda(w)); }

    PBRT_CPU_GPU Float Lambda(Vector3f w) const {
        Float tan2Theta = Tan2Theta(w);
        if (IsInf(tan2Theta))
            return 0;
        return (std::sqrt(1 + Alpha2(w) * tan2Theta) - 1) / 2;
    }

    // Height-correlated masking-shadowing: a microfacet hidden from wo tends to be hidden
    // from wi too, which the product G1(wo) G1(wi) would ignore.
    PBRT_CPU_GPU Float G(Vector3f wo, Vector3f wi) const { return G(Lambda(wo), wi); }
    // The same, for a caller that already has Lambda(wo) (BxDFs whose Sample_f() needs both
    // G and the visible-normal density, which share it).
    PBRT_CPU_GPU Float G(Float lambda_o, Vector3f wi) const {
        return 1 / (1 + lambda_o + Lambda(wi));
    }

    // Distribution of normals visible from w; integrates to 1 over the wm facing w. As in
    // pbrt-v4 it uses |w . wm|, so it is also nonzero for back-facing wm, which
    // Sample_wm() never returns and the BxDFs never ask about.
    PBRT_CPU_GPU Float D(Vector3f w, Vector3f wm) const { return D(w, wm, D(wm)); }
    // The same, for a caller that already has D(wm).
    PBRT_CPU_GPU Float D(Vector3f w, Vector3f wm, Float Dwm) const {
        return D(w, Lambda(w), wm, Dwm);
    }
    // The same, for a caller that also has Lambda(w).
    PBRT_CPU_GPU Float D(Vector3f w, Float lambda_w, Vector3f wm, Float Dwm) const {
        return 1 / (1 + lambda_w) / AbsCosTheta(w) * Dwm * AbsDot(w, wm);
    }

    // Sample_wm() draws exactly the visible-normal distribution.
    PBRT_CPU_GPU Float PDF(Vector3f w, Vector3f wm) const { return D(w, wm); }
    PBRT_CPU_GPU Float PDF(Vector3f w, Vector3f wm, Float Dwm) const { return D(w, wm, Dwm); }
    PBRT_CPU_GPU Float PDF(Vector3f w, Float lambda_w, Vector3f wm, Float Dwm) const {
        return D(w, lambda_w, wm, Dwm);
    }

    // Samples a normal visible from w; it is always in the upper hemisphere (w below the
    // surface is mirrored first). Stretching by alpha turns the microsurface into a unit
    // hemisphere, whose visible normals are wh plus a point uniform on the spherical cap
    // z >= -wh.z (Dupuy and Benyoub, "Sound and Fast Sampling of Visible GGX Normals with
    // Spherical Caps", HPG 2023). pbrt-v4 warps a disk instead (Heitz 2018): the same
    // distribution from another map of u, with two more square roots and normalizations.
    PBRT_CPU_GPU Vector3f Sample_wm(Vector3f w, Point2f u) const {
        Vector3f wh = Normalize(Vector3f(alpha_x * w.x, alpha_y * w.y, w.z));
        if (wh.z < 0)
            wh = -wh;
        Float z = (1 - u[1]) * (1 + wh.z) - wh.z;
        Float sinTheta = SafeSqrt(1 - Sqr(z)), phi = 2 * Pi * u[0];
        Vector3f nh = Vector3f(sinTheta * std::cos(phi), sinTheta * std::sin(phi), z) + wh;
        // Unstretch; the floor keeps grazing normals strictly in the upper hemisphere.
        return Normalize(
            Vector3f(alpha_x * nh.x, alpha_y * nh.y, std::max<Float>(1e-6f, nh.z)));
    }

    // pbrt-v4's mapping from user-facing roughness to alpha.
    PBRT_CPU_GPU static Float RoughnessToAlpha(Float roughness) {
        return std::sqrt(roughness);
    }

    // Path regularization: widen near-specular lobes (double alpha, within [0.1, 0.3]) so
    // that light paths through them can be found by sampling; rougher ones are unchanged.
    PBRT_CPU_GPU void Regularize() {
        if (alpha_x < RegularizeMaxAlpha)
            alpha_x = Clamp(2 * alpha_x, RegularizeMinAlpha, RegularizeMaxAlpha);
        if (alpha_y < RegularizeMaxAlpha)
            alpha_y = Clamp(2 * alpha_y, RegularizeMinAlpha, RegularizeMaxAlpha);
    }

    // Host-only.
    std::string ToString() const {
        char buf[96];
        std::snprintf(buf, sizeof(buf), "[ TrowbridgeReitzDistribution alpha_x: %g alpha_y: %g ]",
                      alpha_x, alpha_y);
        return buf;
    }

  private:
    // The squared roughness along w's azimuth, and 1 / the squared roughness along the
    // azimuth of wm's slope. An isotropic distribution needs no azimuth (cos^2 + sin^2 = 1),
    // which saves a square root and two divisions in every D() and Lambda().
    PBRT_CPU_GPU Float Alpha2(Vector3f w) const {
        if (alpha_x == alpha_y)
            return Sqr(alpha_x);
        return Sqr(CosPhi(w) * alpha_x) + Sqr(SinPhi(w) * alpha_y);
    }
    PBRT_CPU_GPU Float InvAlpha2(Vector3f wm) const {
        if (alpha_x == alpha_y)
            return 1 / Sqr(alpha_x);
        return Sqr(CosPhi(wm) / alpha_x) + Sqr(SinPhi(wm) / alpha_y);
    }

    static constexpr Float MinAlpha = 1e-4f, SmoothAlpha = 1e-3f;
    static constexpr Float RegularizeMinAlpha = 0.1f, RegularizeMaxAlpha = 0.3f;

    Float alpha_x = 0, alpha_y = 0;
};

// ---------------------------------------------------------------------------------------
// Scattering inside a layer (the medium between LayeredBxDF's interfaces; pbrt-v4 keeps
// these in util/scattering.h, util/sampling.h and media.h).

// The Henyey-Greenstein phase function. cosTheta is the cosine between wo and wi, which
// both point away from the scattering point, so forward scattering (g > 0) peaks at
// cosTheta = -1, as in pbrt-v4. Normalized over the sphere. g is clamped to [-0.99, 0.99],
// as pbrt-v4 clamps it: at |g| = 1 the function is a delta (and 0 here), beyond it negative.
PBRT_CPU_GPU inline Float ClampHenyeyGreensteinG(Float g) {
    return Clamp(g, -.99f, .99f);
}
PBRT_CPU_GPU inline Float HenyeyGreenstein(Float cosTheta, Float g) {
    g = ClampHenyeyGreensteinG(g);
    Float denom = 1 + Sqr(g) + 2 * g * cosTheta;
    return Inv4Pi * (1 - Sqr(g)) / (denom * SafeSqrt(denom));
}

// Samples wi exactly from HenyeyGreenstein(Dot(wo, wi), g) and sets *pdf to that density.
// The cosine mu between wi and the propagation direction -wo inverts the closed-form CDF;
// near g = 0 that inversion divides by g, so the isotropic case is sampled directly.
PBRT_CPU_GPU inline Vector3f SampleHenyeyGreenstein(Vector3f wo, Float g, Point2f u,
                                                    Float *pdf) {
    g = ClampHenyeyGreensteinG(g);
    Float mu;
    if (std::abs(g) < 1e-3f)
        mu = 1 - 2 * u[0];
    else
        mu = (1 + Sqr(g) - Sqr((1 - Sqr(g)) / (1 - g + 2 * g * u[0]))) / (2 * g);
    mu = Clamp(mu, -1, 1);
    Float cosTheta = -mu;  // relative to wo
    Float sinTheta = SafeSqrt(1 - Sqr(cosTheta));
    Vector3f wi =
        Frame::FromZ(wo).FromLocal(SphericalDirection(sinTheta, cosTheta, 2 * Pi * u[1]));
    if (pdf)
        *pdf = HenyeyGreenstein(cosTheta, g);
    return wi;
}

// Distance to the next collision in a medium with attenuation coefficient a: density
// a exp(-a x) on [0, inf).
PBRT_CPU_GPU inline Float SampleExponential(Float u, Float a) {
    return -std::log(1 - u) / a;
}
PBRT_CPU_GPU inline Float ExponentialPDF(Float x, Float a) {
    return a * std::exp(-a * x);
}
PBRT_CPU_GPU inline Float InvertExponentialSample(Float x, Float a) {
    return 1 - std::exp(-a * x);
}

// The first two moments of the dielectric Fresnel reflectance over the hemisphere, the integrals
// of Fr(cos, eta) cos^k for k = 1, 2 (d'Eon and Irving 2011's polynomial fits, as pbrt-v4 uses;
// host only: util/scattering.cpp).
Float FresnelMoment1(Float eta);
Float FresnelMoment2(Float eta);

}  // namespace pbrt
