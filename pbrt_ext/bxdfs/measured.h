// pbrt_ext: measured BRDFs in the RGL database's representation, pbrt-v4's MeasuredBxDF (Dupuy and
// Jakob, "An Adaptive Parameterization for Efficient Material Acquisition and Rendering",
// SIGGRAPH Asia 2018; Physically Based Rendering, 4th edition, Section 9.8).
//
// The BRDF is stored against wo (the tables' "incident" direction theta_i, phi_i) as
//   f(wo, wi) = R(u) D(wm) / (4 sigma(wo) cos theta_i),
// with wm the half vector, D the microfacet normal distribution (ndf), sigma(wo) its projected
// area (the integral of D(wm) <wo . wm>), and R the spectral reflectance tabulated not over wm
// but over u, the point of [0, 1]^2 that the visible-normal distribution's inverse warp (vndf)
// takes wm to: the acquisition placed its samples where the visible normals are dense. Angles
// enter the tables through u_theta = sqrt(2 theta / pi) and u_phi = (phi + pi) / (2 pi). An
// isotropic file (at most 2 phi_i values) is tabulated for wo at phi = 0 and is rotated to wo.
//
// Sampling warps the uniform sample by the luminance table (over u, for this wo), then by the
// visible-normal table to wm, and reflects wo about it; the pdf is the product of the two tables'
// densities over the Jacobian of u -> wm -> wi, 2 pi^2 u_theta sin theta_m times 4 (wo . wm), as
// pbrt-v4 computes it. Reflection only; two-sided as pbrt-v4 (wo below the surface is mirrored).
//
// Differs from pbrt-v4: Sample_f returns f() and PDF() of the direction it made, so that the
// three agree to the bit (pbrt-v4 returns the values along the warp, equal up to rounding); a
// sigma of 0 gives f = 0 rather than a division by zero, and so does a file whose (finite)
// values are large enough that f or the pdf overflows (fuzz finding, docs/fuzzing.md).
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/piecewiselinear2d.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace pbrt {

struct MeasuredBxDFData {
    std::string filename;
    std::vector<float> wavelengths;
    PiecewiseLinear2D<0> ndf, sigma;       // raw values over u_wm and u_wo
    PiecewiseLinear2D<2> vndf, luminance;  // densities; parameters phi_i, theta_i
    PiecewiseLinear2D<3> spectra;          // raw values; parameters phi_i, theta_i, lambda
    bool isotropic = true;

    // Reads an RGL .bsdf file (tensorfile.h), checking its fields' names, types, shapes and
    // values; throws std::runtime_error "<path>: error: <what>" for a file that is not one.
    static std::shared_ptr<const MeasuredBxDFData> Read(const std::string &path);
};

class MeasuredBxDF {
  public:
    MeasuredBxDF() = default;
    MeasuredBxDF(const MeasuredBxDFData *brdf, const SampledWavelengths &lambda)
        : brdf(brdf), lambda(lambda) {}

    BxDFFlags Flags() const { return BxDFFlags::GlossyReflection; }

    SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode /*mode*/) const {
        if (!SameHemisphere(wo, wi)) return SampledSpectrum(0.f);
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
        }
        Vector3f wm = wo + wi;
        if (LengthSquared(wm) == 0) return SampledSpectrum(0.f);
        wm = Normalize(wm);
        const Angles a = AnglesOf(wo, wm);
        Float sigma = brdf->sigma.Evaluate(a.u_wo, {});
        if (!(sigma > 0)) return SampledSpectrum(0.f);
        Point2f u = brdf->vndf.Invert(a.u_wm, {a.phi_o, a.theta_o}).p;
        SampledSpectrum value =
            Reflectance(u, a) * (brdf->ndf.Evaluate(a.u_wm, {}) / (4 * sigma * CosTheta(wi)));
        for (int i = 0; i < NSpectrumSamples; ++i)
            if (!std::isfinite(value[i]))
                value[i] = 0;  // a file's values that overflow (see above)
        return value;
    }

    pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float /*uc*/, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection) || wo.z == 0) return {};
        const bool flip = wo.z < 0;
        Vector3f w = flip ? -wo : wo;
        Float theta_o = SphericalTheta(w), phi_o = std::atan2(w.y, w.x);
        Point2f uLum = brdf->luminance.Sample(u, {phi_o, theta_o}).p;
        Point2f u_wm = brdf->vndf.Sample(uLum, {phi_o, theta_o}).p;
        Float theta_m = ThetaOf(u_wm[0]), phi_m = PhiOf(u_wm[1]) + (brdf->isotropic ? phi_o : 0);
        Vector3f wm = SphericalDirection(std::sin(theta_m), std::cos(theta_m), phi_m);
        Vector3f wi = Reflect(w, wm);
        if (wi.z <= 0) return {};
        if (flip) wi = -wi;
        Float pdf = PDF(wo, wi, mode, sampleFlags);
        if (!(pdf > 0)) return {};
        return BSDFSample(f(wo, wi, mode), wi, pdf, BxDFFlags::GlossyReflection);
    }

    Float PDF(Vector3f wo, Vector3f wi, TransportMode /*mode*/,
              BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        if (!(sampleFlags & BxDFReflTransFlags::Reflection) || !SameHemisphere(wo, wi)) return 0;
        if (wo.z < 0) {
            wo = -wo;
            wi = -wi;
        }
        Vector3f wm = wo + wi;
        if (LengthSquared(wm) == 0) return 0;
        wm = Normalize(wm);
        const Angles a = AnglesOf(wo, wm);
        PLSample inverse = brdf->vndf.Invert(a.u_wm, {a.phi_o, a.theta_o});
        Float lumPDF = brdf->luminance.Evaluate(inverse.p, {a.phi_o, a.theta_o});
        Float sinTheta_m = std::sqrt(Sqr(wm.x) + Sqr(wm.y));
        Float jacobian =
            4 * Dot(wo, wm) * std::max<Float>(2 * Sqr(Pi) * a.u_wm[0] * sinTheta_m, 1e-6f);
        Float pdf = inverse.pdf * lumPDF / jacobian;
        return std::isfinite(pdf) ? pdf : 0;
    }

    void Regularize() {}

    SampledSpectrum rho(Vector3f wo, pstd::span<const Float> uc,
                        pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, wo, uc, u2);
    }
    SampledSpectrum rho(pstd::span<const Point2f> u1, pstd::span<const Float> uc,
                        pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, u1, uc, u2);
    }

    static constexpr const char *Name() { return "MeasuredBxDF"; }
    std::string ToString() const { return "[ MeasuredBxDF filename: " + brdf->filename + " ]"; }

  private:
    // wo's angles and the table coordinates of wo and wm (wm's azimuth relative to wo's for an
    // isotropic file, wrapped into [0, 1)).
    struct Angles {
        Float theta_o, phi_o;
        Point2f u_wo, u_wm;
    };
    Angles AnglesOf(Vector3f wo, Vector3f wm) const {
        Angles a;
        a.theta_o = SphericalTheta(wo);
        a.phi_o = std::atan2(wo.y, wo.x);
        Float phi_m = std::atan2(wm.y, wm.x);
        a.u_wo = Point2f(UOfTheta(a.theta_o), UOfPhi(a.phi_o));
        Float v = UOfPhi(brdf->isotropic ? phi_m - a.phi_o : phi_m);
        a.u_wm = Point2f(UOfTheta(SphericalTheta(wm)), v - std::floor(v));
        return a;
    }
    SampledSpectrum Reflectance(Point2f u, const Angles &a) const {
        SampledSpectrum R;
        for (int i = 0; i < NSpectrumSamples; ++i)
            R[i] = std::max<Float>(0, brdf->spectra.Evaluate(u, {a.phi_o, a.theta_o, lambda[i]}));
        return R;
    }

    static Float UOfTheta(Float theta) { return std::sqrt(theta * (2 / Pi)); }
    static Float UOfPhi(Float phi) { return phi * (1 / (2 * Pi)) + 0.5f; }
    static Float ThetaOf(Float u) { return Sqr(u) * (Pi / 2); }
    static Float PhiOf(Float u) { return (2 * u - 1) * Pi; }

    const MeasuredBxDFData *brdf = nullptr;
    SampledWavelengths lambda;
};

}  // namespace pbrt
