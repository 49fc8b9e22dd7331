// pbrt_ext: two BxDFs stacked with a scattering slab between them, pbrt-v4's LayeredBxDF
// (Physically Based Rendering, 4th edition, Section 14.3 "Scattering from Layered
// Materials", after Guo et al., "Position-Free Monte Carlo Simulation for Arbitrary Layered
// BSDFs", SIGGRAPH Asia 2018), with its two instances CoatedDiffuseBxDF (a dielectric coat
// over a Lambertian base) and CoatedConductorBxDF (a dielectric coat over a metal).
//
// Nothing here is closed-form: f(), Sample_f() and PDF() each follow random walks between
// the interfaces (z = thickness at the top, z = 0 at the bottom) through a homogeneous
// slab of unit extinction, the given single-scattering albedo and a Henyey-Greenstein phase
// function of asymmetry g. f() is an unbiased estimate of the BSDF (nSamples walks, with
// next-event estimation through the exit interface and MIS); Sample_f() returns the
// throughput and density of one whole walk, a density known only up to the walks that
// could have produced the same direction, hence pdfIsProportional; PDF() is an
// approximation fit for MIS weights, not a normalized density: the exact density of the
// top's reflection plus single-bounce estimates of the walks', mixed with a uniform
// density; the walks' term measures directions inside the coat per solid angle inside,
// which the coat's refraction compresses by about eta^2 (the whole integrates to 1 for an
// index-matched coat, to about 0.8 - 1.6 for eta = 1.5). Each walk draws its random numbers from an RNG seeded by
// hashing the arguments (f: wo and wi; Sample_f: wo, uc and u; PDF: wi and wo), so every
// call with the same arguments returns the same value.
// A twoSided layer looks the same from below: wo below the surface is mirrored to the top.
//
// Differs from pbrt-v4:
//  - Sample_f() reflects off the top or enters the layers in proportion to the light each
//    sends back (TopReflectionProbability()), and PDF() weighs the two parts by that same
//    choice. pbrt-v4 chooses by the top's Fresnel reflectance alone and its PDF() counts
//    the top's reflection as if always chosen; over a dark base (Veach's MIS plates) it
//    samples the highlight 5 % of the time for half of the energy, and its MIS weights
//    leave that highlight to those rare samples. The same image, with 4x less error on
//    those plates (docs/comparison.md);
//  - pbrt-v4 requires sampleFlags == All in Sample_f() and PDF(); here a restricted request
//    is honoured by rejecting walks that leave on a side it excludes (which keeps f / pdf
//    an unbiased estimate of the allowed part) and by a zero PDF() there;
//  - f()'s connections to wi through the exit interface's own lobe are MIS-weighted
//    against the presampled wis with the density wis has for the same inner direction,
//    exitInterface.PDF(wi, -w, adjoint mode); pbrt-v4 uses PDF(-w, wi, mode), the density
//    of the reverse move, so its two weights need not sum to one and its f() is biased
//    (LayeredExitMIS below; tests/bxdfs/layered_reference_test.cpp measures both against the
//    layer traced as explicit geometry);
//  - the seeds hash the arguments alone (pbrt-v4 also hashes its global --seed option);
//  - f()'s walk plays Russian roulette from its second event on, pbrt-v4's from its fifth:
//    a dark base's walk mostly ends after one reflection. Still unbiased, and a render
//    cannot tell the added variance from its own (Veach's MIS scene: 10 % less time, 0.5 %
//    more error).
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/bxdfs/conductor.h"
#include "pbrt_ext/bxdfs/dielectric.h"
#include "pbrt_ext/bxdfs/diffuse.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace pbrt {

// The density that f() weighs a connection through the exit interface's own lobe against,
// in its MIS with the presampled direction wis that reaches the same inner direction.
enum class LayeredExitMIS {
    // wis's own density for that inner direction, exitInterface.PDF(wi, -w, adjoint mode):
    // the two strategies' weights sum to one, so f() is unbiased.
    InnerDirection,
    // pbrt-v4's, exitInterface.PDF(-w, wi, mode): the density of the reverse move, which
    // measures wi, not the inner direction. The weights need not sum to one; for rough
    // coats f() comes out too bright (tests/bxdfs/layered_reference_test.cpp). Kept so that
    // pbrt-v4's images can be reproduced, and its bias measured.
    PbrtV4,
};

// Whichever of the two interfaces a walk is at: one pointer set, the other null.
template <typename TopBxDF, typename BottomBxDF>
class TopOrBottomBxDF {
  public:
    TopOrBottomBxDF() = default;
    PBRT_CPU_GPU TopOrBottomBxDF &operator=(const TopBxDF *t) {
        top = t;
        bottom = nullptr;
        return *this;
    }
    PBRT_CPU_GPU TopOrBottomBxDF &operator=(const BottomBxDF *b) {
        bottom = b;
        top = nullptr;
        return *this;
    }

    PBRT_CPU_GPU SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode mode) const {
        return top ? top->f(wo, wi, mode) : bottom->f(wo, wi, mode);
    }

    PBRT_CPU_GPU pstd::optional<BSDFSample> Sample_f(
        Vector3f wo, Float uc, Point2f u, TransportMode mode,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        return top ? top->Sample_f(wo, uc, u, mode, sampleFlags)
                   : bottom->Sample_f(wo, uc, u, mode, sampleFlags);
    }

    PBRT_CPU_GPU Float PDF(Vector3f wo, Vector3f wi, TransportMode mode,
                           BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        return top ? top->PDF(wo, wi, mode, sampleFlags) : bottom->PDF(wo, wi, mode, sampleFlags);
    }

    PBRT_CPU_GPU BxDFFlags Flags() const { return top ? top->Flags() : bottom->Flags(); }

  private:
    const TopBxDF *top = nullptr;
    const BottomBxDF *bottom = nullptr;
};

template <typename TopBxDF, typename BottomBxDF, bool twoSided>
class LayeredBxDF {
  public:
    LayeredBxDF() = default;
    // A zero thickness would make every transmittance 0 / 0; the smallest positive one
    // behaves as touching interfaces.
    PBRT_CPU_GPU LayeredBxDF(TopBxDF top0, BottomBxDF bottom0, Float thickness0,
                             const SampledSpectrum &albedo0, Float g0, int maxDepth0,
                             int nSamples0,
                             LayeredExitMIS exitMIS0 = LayeredExitMIS::InnerDirection)
        : top(top0), bottom(bottom0),
          thickness(std::max(thickness0, std::numeric_limits<Float>::min())), g(g0),
          albedo(albedo0), maxDepth(maxDepth0), nSamples(nSamples0), exitMIS(exitMIS0),
          innerReflectance(EstimateInnerReflectance()) {}

    // Light can always come back out through the top, so the layer reflects; it transmits
    // only when both interfaces do. A scattering slab makes the whole thing diffuse.
    PBRT_CPU_GPU BxDFFlags Flags() const {
        BxDFFlags topFlags = top.Flags(), bottomFlags = bottom.Flags();
        BxDFFlags flags = BxDFFlags::Reflection;
        if (IsSpecular(topFlags))
            flags |= BxDFFlags::Specular;
        if (IsDiffuse(topFlags) || IsDiffuse(bottomFlags) || albedo)
            flags |= BxDFFlags::Diffuse;
        else if (IsGlossy(topFlags) || IsGlossy(bottomFlags))
            flags |= BxDFFlags::Glossy;
        if (IsTransmissive(topFlags) && IsTransmissive(bottomFlags))
            flags |= BxDFFlags::Transmission;
        return flags;
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

    PBRT_CPU_GPU SampledSpectrum rho(pstd::span<const Point2f> u1,
                                     pstd::span<const Float> uc,
                                     pstd::span<const Point2f> u2) const {
        return EstimateRho(*this, u1, uc, u2);
    }

    PBRT_CPU_GPU void Regularize() {
        top.Regularize();
        bottom.Regularize();
    }

    PBRT_CPU_GPU static constexpr const char *Name() { return "LayeredBxDF"; }

    // Host-only.
    std::string ToString() const { return Describe(Name()); }

  protected:
    // Host-only: the ToString() text under a given type name, for the named instances.
    std::string Describe(const char *name) const {
        char buf[128];
        std::snprintf(buf, sizeof(buf),
                      " thickness: %g g: %g maxDepth: %d nSamples: %d exitMIS: %s ]", thickness,
                      g, maxDepth, nSamples,
                      exitMIS == LayeredExitMIS::InnerDirection ? "inner" : "pbrt-v4");
        return std::string("[ ") + name + " top: " + top.ToString() +
               " bottom: " + bottom.ToString() + " albedo: " + albedo.ToString() + buf;
    }

  private:
    using Interface = TopOrBottomBxDF<TopBxDF, BottomBxDF>;

    // Transmittance of the slab (unit extinction) over a height difference dz along w.
    PBRT_CPU_GPU static Float Tr(Float dz, Vector3f w) {
        if (std::abs(dz) <= std::numeric_limits<Float>::min())
            return 1;
        return std::exp(-std::abs(dz / w.z));
    }

    // A sample a walk can continue from: it carries energy along a direction that leaves
    // the tangent plane.
    PBRT_CPU_GPU static bool Usable(const pstd::optional<BSDFSample> &bs) {
        return bs && bs->f && bs->pdf > 0 && bs->wi.z != 0;
    }

    // Walks that start from wi trace the adjoint quantity (pbrt-v4 writes !mode).
    PBRT_CPU_GPU static TransportMode Adjoint(TransportMode mode) {
        return mode == TransportMode::Radiance ? TransportMode::Importance
                                               : TransportMode::Radiance;
    }

    // The exit interface's f from the inner direction -w (w heads for the exit) out to
    // wi. When the presampled wis also reached that inner direction (wisCompetes), the
    // value is MIS-weighted against it: wPdf is the density w was drawn with, and wis
    // draws it with the exit's adjoint transmission density from wi (exitMIS).
    PBRT_CPU_GPU SampledSpectrum ExitLobe(const Interface &exitInterface, Vector3f w,
                                          Vector3f wi, TransportMode mode, bool wisCompetes,
                                          Float wPdf) const {
        SampledSpectrum fExit = exitInterface.f(-w, wi, mode);
        if (!fExit || !wisCompetes)
            return fExit;
        Float wisPdf =
            exitMIS == LayeredExitMIS::InnerDirection
                ? exitInterface.PDF(wi, -w, Adjoint(mode), BxDFReflTransFlags::Transmission)
                : exitInterface.PDF(-w, wi, mode, BxDFReflTransFlags::Transmission);
        return fExit * PowerHeuristic(1, wPdf, 1, wisPdf);
    }

    // Roughly how much of the light that enters through the top comes back out: the base's
    // (or the slab's) albedo A, of which the fraction that escapes the coat's internal
    // reflection Ri leaves after any number of bounces: A (1 - Ri) / (1 - A Ri), with Ri
    // about 1 - 1 / eta^2 for diffuse light inside a denser coat. Only sampling uses it.
    PBRT_CPU_GPU Float EstimateInnerReflectance() const {
        Float uc[1] = {0.5f};
        Point2f u[1] = {Point2f(0.5f, 0.5f)};
        Float A = std::max(bottom.rho(Vector3f(0, 0, 1), uc, u).Average(), albedo.Average());
        if (!(A < 1))
            return 1;
        Float Ri = std::max<Float>(0, 1 - 1 / Sqr(top.Eta()));
        return std::max<Float>(0, A) * (1 - Ri) / (1 - A * Ri);
    }

    // The probability that Sample_f() reflects off the top rather than entering the layers:
    // in proportion to the light each returns, the top's Fresnel reflectance against its
    // transmittance times innerReflectance. pbrt-v4 leaves the choice to the top's Fresnel
    // term alone, which over a dark base picks the highlight, most of what the surface
    // reflects, 4 % of the time at normal incidence. Never below that Fresnel term (the
    // estimate is at most 1), and kept below 1 so that the layers are always sampled.
    PBRT_CPU_GPU Float TopReflectionProbability(Vector3f wo) const {
        Float R = FrDielectric(AbsCosTheta(wo), top.Eta());
        Float returned = R + (1 - R) * innerReflectance;
        return returned > 0 ? std::min<Float>(R / returned, 0.9f) : 0;
    }

    // The Henyey-Greenstein phase function's value at (wo, wi), which is also the density
    // SampleHenyeyGreenstein() draws wi with.
    PBRT_CPU_GPU Float Phase(Vector3f wo, Vector3f wi) const {
        return HenyeyGreenstein(Dot(wo, wi), g);
    }

    TopBxDF top;
    BottomBxDF bottom;
    // pbrt-v4's material defaults.
    Float thickness = 0.01f, g = 0;
    SampledSpectrum albedo = SampledSpectrum(0.f);
    int maxDepth = 10, nSamples = 1;
    LayeredExitMIS exitMIS = LayeredExitMIS::InnerDirection;
    Float innerReflectance = 0;
};

// Random numbers for a walk, drawn in a fixed order (function arguments are evaluated in
// an unspecified one).
class LayeredWalkRNG {
  public:
    PBRT_CPU_GPU LayeredWalkRNG(uint64_t seqIndex, uint64_t offset) : rng(seqIndex, offset) {}
    PBRT_CPU_GPU Float Get1D() { return rng.Uniform<Float>(); }
    PBRT_CPU_GPU Point2f Get2D() {
        Float u0 = rng.Uniform<Float>();
        return Point2f(u0, rng.Uniform<Float>());
    }

  private:
    RNG rng;
};

template <typename TopBxDF, typename BottomBxDF, bool twoSided>
PBRT_CPU_GPU SampledSpectrum LayeredBxDF<TopBxDF, BottomBxDF, twoSided>::f(
    Vector3f wo, Vector3f wi, TransportMode mode) const {
    if (twoSided && wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    bool enteredTop = twoSided || wo.z > 0;
    Interface enterInterface;
    if (enteredTop)
        enterInterface = &top;
    else
        enterInterface = &bottom;

    // Light toward wi leaves through the entrance interface if wi is on wo's side.
    bool exitsBottom = SameHemisphere(wo, wi) ^ enteredTop;
    Interface exitInterface, nonExitInterface;
    if (exitsBottom) {
        exitInterface = &bottom;
        nonExitInterface = &top;
    } else {
        exitInterface = &top;
        nonExitInterface = &bottom;
    }
    Float exitZ = exitsBottom ? 0 : thickness;
    bool exitSpecular = IsSpecular(exitInterface.Flags());

    // Reflection at the entrance needs no walk; it is counted once per walk so that the
    // division by nSamples below leaves it whole.
    SampledSpectrum f(0.f);
    if (SameHemisphere(wo, wi))
        f = Float(nSamples) * enterInterface.f(wo, wi, mode);

    LayeredWalkRNG r(Hash(wo), Hash(wi));
    for (int s = 0; s < nSamples; ++s) {
        // Into the slab from wo, and (the adjoint walk) from wi through the exit, which the
        // walk's vertices connect to by next-event estimation.
        Float uc = r.Get1D();
        pstd::optional<BSDFSample> wos = enterInterface.Sample_f(
            wo, uc, r.Get2D(), mode, BxDFReflTransFlags::Transmission);
        if (!Usable(wos))
            continue;
        uc = r.Get1D();
        pstd::optional<BSDFSample> wis = exitInterface.Sample_f(
            wi, uc, r.Get2D(), Adjoint(mode), BxDFReflTransFlags::Transmission);
        if (!Usable(wis))
            continue;

        SampledSpectrum beta = wos->f * AbsCosTheta(wos->wi) / wos->pdf;
        Float z = enteredTop ? thickness : 0;
        Vector3f w = wos->wi;
        for (int depth = 0; depth < maxDepth; ++depth) {
            // Russian roulette once the walk has lost most of its weight, from its second
            // event on (pbrt-v4: from its fifth). f()'s own variance is lost in a render's,
            // while the walk is much of its cost (docs/comparison.md measures both).
            if (depth > 0 && beta.MaxComponentValue() < 0.25f) {
                Float q = std::max<Float>(0, 1 - beta.MaxComponentValue());
                if (r.Get1D() < q)
                    break;
                beta /= 1 - q;
            }

            if (!albedo) {
                // Nothing scatters inside: straight on to the other interface.
                z = (z == thickness) ? 0 : thickness;
                beta *= Tr(thickness, w);
            } else {
                Float dz = SampleExponential(r.Get1D(), 1 / std::abs(w.z));
                Float zp = w.z > 0 ? (z + dz) : (z - dz);
                if (zp == z)
                    continue;
                if (0 < zp && zp < thickness) {
                    // A scattering event inside the slab: connect it to wi through the
                    // exit along the presampled wis (MIS against phase sampling) ...
                    Float phase = Phase(-w, -wis->wi);
                    Float wt = exitSpecular ? 1 : PowerHeuristic(1, wis->pdf, 1, phase);
                    f += beta * albedo * phase * wt * Tr(zp - exitZ, wis->wi) * wis->f / wis->pdf;

                    // ... then continue in a direction drawn from the phase function, whose
                    // weight p / pdf is one.
                    Float phasePdf;
                    Vector3f wp = SampleHenyeyGreenstein(-w, g, r.Get2D(), &phasePdf);
                    if (phasePdf == 0 || wp.z == 0)
                        continue;
                    beta *= albedo;
                    w = wp;
                    z = zp;

                    // If it heads for the exit, connect it to wi through the exit
                    // interface's own lobe (MIS against wis).
                    if (((z < exitZ && w.z > 0) || (z > exitZ && w.z < 0)) && !exitSpecular)
                        f += beta * Tr(zp - exitZ, w) *
                             ExitLobe(exitInterface, w, wi, mode, true, phasePdf);
                    continue;
                }
                z = Clamp(zp, 0, thickness);
            }

            if (z == exitZ) {
                // At the exit, transmission was accounted for by the connections above;
                // the walk goes on by reflection back into the slab.
                uc = r.Get1D();
                pstd::optional<BSDFSample> bs = exitInterface.Sample_f(
                    -w, uc, r.Get2D(), mode, BxDFReflTransFlags::Reflection);
                if (!Usable(bs))
                    break;
                beta *= bs->f * AbsCosTheta(bs->wi) / bs->pdf;
                w = bs->wi;
                continue;
            }

            // At the far interface: connect to wi along wis (MIS against this interface's
            // sampling), then reflect.
            bool nonExitSpecular = IsSpecular(nonExitInterface.Flags());
            if (!nonExitSpecular) {
                Float wt = 1;
                if (!exitSpecular)
                    wt = PowerHeuristic(1, wis->pdf, 1,
                                        nonExitInterface.PDF(-w, -wis->wi, mode,
                                                             BxDFReflTransFlags::Reflection));
                f += beta * nonExitInterface.f(-w, -wis->wi, mode) * AbsCosTheta(wis->wi) *
                     wt * Tr(thickness, wis->wi) * wis->f / wis->pdf;
            }
            uc = r.Get1D();
            pstd::optional<BSDFSample> bs = nonExitInterface.Sample_f(
                -w, uc, r.Get2D(), mode, BxDFReflTransFlags::Reflection);
            if (!Usable(bs))
                break;
            beta *= bs->f * AbsCosTheta(bs->wi) / bs->pdf;
            w = bs->wi;

            // The reflected direction may reach wi through the exit's lobe (MIS against
            // wis, which only a non-specular far interface could have used).
            if (!exitSpecular)
                f += beta * Tr(thickness, w) *
                     ExitLobe(exitInterface, w, wi, mode, !nonExitSpecular, bs->pdf);
        }
    }
    return f / Float(nSamples);
}

template <typename TopBxDF, typename BottomBxDF, bool twoSided>
PBRT_CPU_GPU pstd::optional<BSDFSample> LayeredBxDF<TopBxDF, BottomBxDF, twoSided>::Sample_f(
    Vector3f wo, Float uc, Point2f u, TransportMode mode,
    BxDFReflTransFlags sampleFlags) const {
    if (!sampleFlags)
        return {};
    bool flipWi = false;
    if (twoSided && wo.z < 0) {
        wo = -wo;
        flipWi = true;
    }
    // Rejection keeps f / pdf an unbiased estimate of the part the caller allows.
    auto finish = [&](BSDFSample bs) -> pstd::optional<BSDFSample> {
        if (flipWi)
            bs.wi = -bs.wi;
        BxDFReflTransFlags side = bs.IsReflection() ? BxDFReflTransFlags::Reflection
                                                    : BxDFReflTransFlags::Transmission;
        if (!(sampleFlags & side))
            return {};
        return bs;
    };

    bool enteredTop = twoSided || wo.z > 0;
    pstd::optional<BSDFSample> bs;
    if (!enteredTop) {
        bs = bottom.Sample_f(wo, uc, u, mode);
    } else {
        // Reflect or enter with TopReflectionProbability(); uc is reused for the top's own
        // sample once rescaled to [0, 1).
        Float pr = TopReflectionProbability(wo);
        bool reflect = uc < pr;
        Float ucTop = reflect ? uc / pr : (uc - pr) / (1 - pr);
        bs = top.Sample_f(wo, std::min(ucTop, OneMinusEpsilon), u, mode,
                          reflect ? BxDFReflTransFlags::Reflection
                                  : BxDFReflTransFlags::Transmission);
        if (bs)
            bs->pdf *= reflect ? pr : 1 - pr;
    }
    if (!Usable(bs))
        return {};
    if (bs->IsReflection()) {
        bs->pdfIsProportional = true;
        return finish(*bs);
    }

    // Follow the refracted direction through the slab until it leaves; f and pdf collect
    // the product of every event's value and density.
    Vector3f w = bs->wi;
    bool specularPath = bs->IsSpecular();
    LayeredWalkRNG r(Hash(wo), Hash(uc, u));
    SampledSpectrum f = bs->f * AbsCosTheta(bs->wi);
    Float pdf = bs->pdf;
    Float z = enteredTop ? thickness : 0;
    for (int depth = 0; depth < maxDepth; ++depth) {
        // Russian roulette scales the pdf: the caller's f / pdf stays unbiased.
        Float rrBeta = f.MaxComponentValue() / pdf;
        if (depth > 3 && rrBeta < 0.25f) {
            Float q = std::max<Float>(0, 1 - rrBeta);
            if (r.Get1D() < q)
                return {};
            pdf *= 1 - q;
        }
        if (w.z == 0)
            return {};

        if (albedo) {
            Float dz = SampleExponential(r.Get1D(), 1 / AbsCosTheta(w));
            Float zp = w.z > 0 ? (z + dz) : (z - dz);
            if (zp == z)
                return {};
            if (0 < zp && zp < thickness) {
                Float phasePdf;
                Vector3f wp = SampleHenyeyGreenstein(-w, g, r.Get2D(), &phasePdf);
                if (phasePdf == 0 || wp.z == 0)
                    return {};
                f *= albedo * phasePdf;
                pdf *= phasePdf;
                specularPath = false;
                w = wp;
                z = zp;
                continue;
            }
            z = Clamp(zp, 0, thickness);
        } else {
            z = (z == thickness) ? 0 : thickness;
            f *= Tr(thickness, w);
        }

        Interface interfaceBxDF;
        if (z == 0)
            interfaceBxDF = &bottom;
        else
            interfaceBxDF = &top;
        Float ucWalk = r.Get1D();
        bs = interfaceBxDF.Sample_f(-w, ucWalk, r.Get2D(), mode);
        if (!Usable(bs))
            return {};
        f *= bs->f;
        pdf *= bs->pdf;
        // f and pdf are products over the walk, of up to a glossy lobe's peak density per
        // event: a deep walk takes them past a float's range (inf / inf). Only their ratio
        // is used (pdfIsProportional), so both are rescaled to keep pdf near 1.
        if (pdf > 1e16f || pdf < 1e-16f) {
            f /= pdf;
            pdf = 1;
        }
        specularPath &= bs->IsSpecular();
        w = bs->wi;

        // Transmission through an interface leaves the layers.
        if (bs->IsTransmission()) {
            BxDFFlags flags =
                SameHemisphere(wo, w) ? BxDFFlags::Reflection : BxDFFlags::Transmission;
            flags |= specularPath ? BxDFFlags::Specular : BxDFFlags::Glossy;
            return finish(BSDFSample(f, w, pdf, flags, 1.f, true));
        }
        f *= AbsCosTheta(bs->wi);
    }
    return {};
}

template <typename TopBxDF, typename BottomBxDF, bool twoSided>
PBRT_CPU_GPU Float LayeredBxDF<TopBxDF, BottomBxDF, twoSided>::PDF(
    Vector3f wo, Vector3f wi, TransportMode mode, BxDFReflTransFlags sampleFlags) const {
    if (twoSided && wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    bool sameSide = SameHemisphere(wo, wi);
    if (!(sampleFlags &
          (sameSide ? BxDFReflTransFlags::Reflection : BxDFReflTransFlags::Transmission)))
        return 0;

    LayeredWalkRNG r(Hash(wi), Hash(wo));
    bool enteredTop = twoSided || wo.z > 0;
    // Reflection off the entrance has its exact density; the walks are estimated, and
    // weighted by how often Sample_f() enters.
    Float pdfSum = 0, enterProbability = 1;
    if (enteredTop) {
        Float pr = TopReflectionProbability(wo);
        enterProbability = 1 - pr;
        if (sameSide)
            pdfSum += nSamples * pr * top.PDF(wo, wi, mode, BxDFReflTransFlags::Reflection);
    } else if (sameSide) {
        pdfSum += nSamples * bottom.PDF(wo, wi, mode);
    }
    Float walkSum = 0;

    for (int s = 0; s < nSamples; ++s) {
        if (sameSide) {
            // Transmission in, reflection at the far interface, transmission out: the
            // densities of the two ends are estimated from sampled transmissions.
            Interface rInterface, tInterface;
            if (enteredTop) {
                rInterface = &bottom;
                tInterface = &top;
            } else {
                rInterface = &top;
                tInterface = &bottom;
            }
            Float uc = r.Get1D();
            pstd::optional<BSDFSample> wos = tInterface.Sample_f(
                wo, uc, r.Get2D(), mode, BxDFReflTransFlags::Transmission);
            uc = r.Get1D();
            pstd::optional<BSDFSample> wis = tInterface.Sample_f(
                wi, uc, r.Get2D(), Adjoint(mode), BxDFReflTransFlags::Transmission);
            if (!Usable(wos) || !Usable(wis))
                continue;
            if (!IsNonSpecular(tInterface.Flags())) {
                // Specular transmission fixes both inner directions.
                walkSum += rInterface.PDF(-wos->wi, -wis->wi, mode);
                continue;
            }
            uc = r.Get1D();
            pstd::optional<BSDFSample> rs =
                rInterface.Sample_f(-wos->wi, uc, r.Get2D(), mode);
            if (!Usable(rs))
                continue;
            if (!IsNonSpecular(rInterface.Flags())) {
                walkSum += tInterface.PDF(-rs->wi, wi, mode);
            } else {
                // Two estimates of the same density, combined by MIS.
                Float rPDF = rInterface.PDF(-wos->wi, -wis->wi, mode);
                walkSum += PowerHeuristic(1, wis->pdf, 1, rPDF) * rPDF;
                Float tPDF = tInterface.PDF(-rs->wi, wi, mode);
                walkSum += PowerHeuristic(1, rs->pdf, 1, tPDF) * tPDF;
            }
        } else {
            // Straight through both interfaces.
            Interface toInterface, tiInterface;
            if (enteredTop) {
                toInterface = &top;
                tiInterface = &bottom;
            } else {
                toInterface = &bottom;
                tiInterface = &top;
            }
            Float uc = r.Get1D();
            pstd::optional<BSDFSample> wos = toInterface.Sample_f(wo, uc, r.Get2D(), mode);
            if (!Usable(wos) || wos->IsReflection())
                continue;
            uc = r.Get1D();
            pstd::optional<BSDFSample> wis =
                tiInterface.Sample_f(wi, uc, r.Get2D(), Adjoint(mode));
            if (!Usable(wis) || wis->IsReflection())
                continue;
            if (IsSpecular(toInterface.Flags()))
                walkSum += tiInterface.PDF(-wos->wi, wi, mode);
            else if (IsSpecular(tiInterface.Flags()))
                walkSum += toInterface.PDF(wo, -wis->wi, mode);
            else
                walkSum += (toInterface.PDF(wo, -wis->wi, mode) +
                           tiInterface.PDF(-wos->wi, wi, mode)) / 2;
        }
    }
    // A little uniform density keeps the MIS weights of rare directions away from zero.
    return Lerp(0.9f, 1 / (4 * Pi), (pdfSum + enterProbability * walkSum) / nSamples);
}

// A dielectric coat over a Lambertian base (pbrt-v4's "coateddiffuse" material).
class CoatedDiffuseBxDF : public LayeredBxDF<DielectricBxDF, DiffuseBxDF, true> {
  public:
    using LayeredBxDF::LayeredBxDF;
    PBRT_CPU_GPU static constexpr const char *Name() { return "CoatedDiffuseBxDF"; }
    // Host-only.
    std::string ToString() const { return Describe(Name()); }
};

// A dielectric coat over a metal (pbrt-v4's "coatedconductor" material).
class CoatedConductorBxDF : public LayeredBxDF<DielectricBxDF, ConductorBxDF, true> {
  public:
    using LayeredBxDF::LayeredBxDF;
    PBRT_CPU_GPU static constexpr const char *Name() { return "CoatedConductorBxDF"; }
    // Host-only.
    std::string ToString() const { return Describe(Name()); }
};

}  // namespace pbrt
