// Properties of pbrt_ext/util/scattering.h: Fresnel identities, reflection and refraction
// geometry, and the Trowbridge-Reitz distribution's normalization, sampling and
// regularization. Sampling uses fixed seeds, so every run sees the same numbers.

#include "pbrt_ext/util/scattering.h"

#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/spherequadrature.h"
#include "pbrt_ext/util/vecmath.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

using namespace pbrt;

namespace {

// Float evaluation of closed forms with values up to 1: about a hundred ulps of slack.
constexpr Float kFloatTolerance = 1e-5f;
// Geometry through sqrt and normalization: a little more.
constexpr Float kDirectionTolerance = 1e-5f;
// Quadrature over the sphere (Gauss-Legendre in cos(theta) about the normal): on this
// grid every integral below is within 3e-5 of its exact value, for every alpha in kAlphas.
constexpr int kQuadratureZ = 256, kQuadraturePhi = 256;
constexpr double kQuadratureTolerance = 1e-4;

const std::array<Float, 5> kEtas = {1.33f, 1.5f, 2.4f, 1 / 1.5f, 0.9f};
const std::array<Float, 9> kCosines = {1.f, 0.95f, 0.8f, 0.6f, 0.4f,
                                       0.2f, 0.1f, 0.01f, 0.f};

// Roughness settings for the distribution tests: isotropic from fairly smooth to very
// rough, plus anisotropic both ways.
struct Alphas {
    Float x, y;
};
const std::array<Alphas, 7> kAlphas = {{{0.05f, 0.05f},
                                        {0.1f, 0.1f},
                                        {0.3f, 0.3f},
                                        {0.7f, 0.7f},
                                        {1.f, 1.f},
                                        {0.15f, 0.6f},
                                        {0.8f, 0.2f}}};

// Draws the two coordinates in a fixed order (the order in which function arguments are
// evaluated is unspecified), so that results do not depend on the compiler.
Point2f Uniform2D(RNG &rng) {
    Float u0 = rng.Uniform<Float>();
    return Point2f(u0, rng.Uniform<Float>());
}

Vector3f DirectionFromAngles(Float theta, Float phi) {
    return SphericalDirection(std::sin(theta), std::cos(theta), phi);
}

// Integral of g over the upper hemisphere.
template <typename Integrand>
double IntegrateHemisphere(Integrand g) {
    auto upper = [&](Vector3f w) { return w.z > 0 ? double(g(w)) : 0.; };
    return IntegrateSphere(upper, Frame(), kQuadratureZ, kQuadraturePhi);
}

// Recovers (alpha_x, alpha_y) from Lambda along the x and y axes at 45 degrees, where
// Lambda = (sqrt(1 + alpha^2) - 1) / 2, so that tests observe the distribution only
// through its public interface.
Alphas RecoverAlphas(const TrowbridgeReitzDistribution &distrib) {
    auto alpha = [&](Vector3f w) { return std::sqrt(Sqr(2 * distrib.Lambda(w) + 1) - 1); };
    return {alpha(Normalize(Vector3f(1, 0, 1))), alpha(Normalize(Vector3f(0, 1, 1)))};
}

}  // namespace

// ---- Fresnel ---------------------------------------------------------------------------

TEST(FrDielectric, IndexMatchedInterfaceReflectsNothing) {
    for (Float cosTheta : kCosines) {
        if (cosTheta == 0)
            continue;  // 0/0 at exactly grazing; pbrt-v4 resolves it as total reflection
        EXPECT_NEAR(FrDielectric(cosTheta, 1), 0, kFloatTolerance) << cosTheta;
        EXPECT_NEAR(FrDielectric(-cosTheta, 1), 0, kFloatTolerance) << cosTheta;
    }
}

TEST(FrDielectric, NormalIncidenceMatchesClosedForm) {
    for (Float eta : kEtas) {
        Float expected = Sqr((eta - 1) / (eta + 1));
        EXPECT_NEAR(FrDielectric(1, eta), expected, kFloatTolerance) << eta;
        // Seen from the other side, the same interface reflects the same at normal incidence.
        EXPECT_NEAR(FrDielectric(-1, eta), expected, kFloatTolerance) << eta;
    }
}

TEST(FrDielectric, GrazingIncidenceReflectsEverything) {
    for (Float eta : kEtas)
        EXPECT_NEAR(FrDielectric(0, eta), 1, kFloatTolerance) << eta;
}

TEST(FrDielectric, NegativeCosineSwapsTheMedia) {
    for (Float eta : kEtas)
        for (Float cosTheta : kCosines)
            EXPECT_NEAR(FrDielectric(-cosTheta, eta), FrDielectric(cosTheta, 1 / eta),
                        kFloatTolerance)
                << eta << " " << cosTheta;
}

TEST(FrDielectric, TotalInternalReflectionBeyondTheCriticalAngle) {
    const Float eta = 1.5f;
    const Float cosCritical = std::sqrt(1 - Sqr(1 / eta));
    // From inside glass, every angle past the critical one reflects totally.
    EXPECT_EQ(FrDielectric(-0.9f * cosCritical, eta), 1);
    EXPECT_LT(FrDielectric(-(cosCritical + 0.1f), eta), 1);
}

TEST(FrComplex, WithoutAbsorptionEqualsFrDielectric) {
    for (Float eta : kEtas)
        for (Float cosTheta : kCosines)
            EXPECT_NEAR(FrComplex(cosTheta, eta, 0), FrDielectric(cosTheta, eta),
                        kFloatTolerance)
                << eta << " " << cosTheta;
}

TEST(FrComplex, NormalIncidenceMatchesClosedForm) {
    // Gold-like, copper-like and aluminium-like indices at visible wavelengths.
    const std::array<std::array<Float, 2>, 3> etaK = {
        {{0.18f, 3.4f}, {0.27f, 2.6f}, {1.3f, 7.5f}}};
    for (auto [eta, k] : etaK) {
        Float expected = (Sqr(eta - 1) + Sqr(k)) / (Sqr(eta + 1) + Sqr(k));
        EXPECT_NEAR(FrComplex(1, eta, k), expected, kFloatTolerance) << eta << " " << k;
        EXPECT_NEAR(FrComplex(0, eta, k), 1, kFloatTolerance) << eta << " " << k;
    }
}

TEST(FrComplex, SpectrumEvaluatesEachChannelOnItsOwn) {
    SampledSpectrum eta(0.2f, 1.1f, 1.5f, 0.7f), k(3.9f, 2.5f, 0.f, 1.2f);
    for (Float cosTheta : kCosines) {
        SampledSpectrum F = FrComplex(cosTheta, eta, k);
        for (int i = 0; i < NSpectrumSamples; ++i)
            EXPECT_EQ(F[i], FrComplex(cosTheta, eta[i], k[i])) << i;
    }
}

TEST(FrComplex, StaysInTheUnitInterval) {
    RNG rng(7);
    for (int i = 0; i < 10000; ++i) {
        Float cosTheta = 2 * rng.Uniform<Float>() - 1;
        Float eta = 0.01f + 4 * rng.Uniform<Float>(), k = 10 * rng.Uniform<Float>();
        Float F = FrComplex(cosTheta, eta, k);
        ASSERT_GE(F, 0) << cosTheta << " " << eta << " " << k;
        ASSERT_LE(F, 1 + kFloatTolerance) << cosTheta << " " << eta << " " << k;
    }
}

// ---- Reflection and refraction ---------------------------------------------------------

TEST(Reflect, MirrorsAboutTheNormal) {
    RNG rng(11);
    for (int i = 0; i < 1000; ++i) {
        Vector3f wo = SampleUniformSphere(Uniform2D(rng));
        Vector3f n = SampleUniformSphere(Uniform2D(rng));
        Vector3f wr = Reflect(wo, n);
        EXPECT_NEAR(Length(wr), 1, kDirectionTolerance);
        EXPECT_NEAR(Dot(wr, n), Dot(wo, n), kDirectionTolerance);
        // The half vector of wo and wr lies along n.
        EXPECT_NEAR(Length(Cross(wo + wr, n)), 0, kDirectionTolerance);
        Vector3f back = Reflect(wr, n);
        EXPECT_NEAR(Length(back - wo), 0, kDirectionTolerance);
    }
    Vector3f wr = Reflect(Vector3f(0.6f, 0, 0.8f), Vector3f(0, 0, 1));
    EXPECT_NEAR(wr.x, -0.6f, kFloatTolerance);
    EXPECT_NEAR(wr.z, 0.8f, kFloatTolerance);
}

TEST(Refract, ObeysSnellsLawAndRoundTrips) {
    const Normal3f n(0, 0, 1);
    const Vector3f nv(0, 0, 1);
    for (Float eta : kEtas) {
        for (Float cosTheta_i : kCosines) {
            if (cosTheta_i == 0)
                continue;  // grazing incidence has no defined plane of incidence
            Vector3f wi = DirectionFromAngles(std::acos(cosTheta_i), 0.7f);
            Vector3f wt;
            Float etap = 0;
            bool refracted = Refract(wi, n, eta, &etap, &wt);
            Float sinTheta_i = SinTheta(wi);
            if (sinTheta_i / eta >= 1) {
                EXPECT_FALSE(refracted) << eta << " " << cosTheta_i;
                continue;
            }
            ASSERT_TRUE(refracted) << eta << " " << cosTheta_i;
            EXPECT_EQ(etap, eta);
            EXPECT_NEAR(Length(wt), 1, kDirectionTolerance);
            EXPECT_LT(wt.z, 0);
            EXPECT_NEAR(eta * SinTheta(wt), sinTheta_i, kDirectionTolerance);
            // Incident, normal and transmitted directions share one plane.
            EXPECT_NEAR(Dot(Cross(wi, nv), wt), 0, kDirectionTolerance);

            // Coming back from inside flips the interface and returns the original ray.
            Vector3f back;
            Float etapBack = 0;
            ASSERT_TRUE(Refract(wt, n, eta, &etapBack, &back));
            EXPECT_NEAR(etapBack, 1 / eta, kFloatTolerance);
            EXPECT_NEAR(Length(back - wi), 0, kDirectionTolerance) << eta << " " << cosTheta_i;
        }
    }
}

TEST(Refract, TotalInternalReflectionFromInside) {
    const Float eta = 1.5f;
    Vector3f wi = Normalize(Vector3f(0.9f, 0, -0.3f));  // inside, beyond the critical angle
    Vector3f wt(7, 7, 7);
    Float etap = -1;
    EXPECT_FALSE(Refract(wi, Normal3f(0, 0, 1), eta, &etap, &wt));
    EXPECT_EQ(wt.x, 7);  // outputs untouched on failure
    EXPECT_EQ(etap, -1);
    EXPECT_EQ(FrDielectric(CosTheta(wi), eta), 1);
}

// ---- Trowbridge-Reitz ------------------------------------------------------------------

TEST(TrowbridgeReitz, ProjectedNormalsIntegrateToOne) {
    for (Alphas a : kAlphas) {
        TrowbridgeReitzDistribution distrib(a.x, a.y);
        double integral =
            IntegrateHemisphere([&](Vector3f wm) { return distrib.D(wm) * CosTheta(wm); });
        EXPECT_NEAR(integral, 1, kQuadratureTolerance) << a.x << " " << a.y;
    }
}

TEST(TrowbridgeReitz, VisibleNormalPDFIntegratesToOne) {
    const std::array<Float, 5> thetas = {0.f, 0.5f, 1.f, 1.3f, Radians(85.f)};
    for (Alphas a : kAlphas) {
        TrowbridgeReitzDistribution distrib(a.x, a.y);
        for (Float theta : thetas) {
            for (Float side : {1.f, -1.f}) {
                Vector3f w = DirectionFromAngles(theta, 0.4f);
                w.z *= side;
                // For w below the surface the distribution is that of the mirrored -w.
                Vector3f wUp = side > 0 ? w : -w;
                double integral = IntegrateHemisphere([&](Vector3f wm) {
                    return Dot(wUp, wm) > 0 ? double(distrib.PDF(w, wm)) : 0.;
                });
                EXPECT_NEAR(integral, 1, kQuadratureTolerance)
                    << a.x << " " << a.y << " theta " << theta << " side " << side;
            }
        }
    }
}

TEST(TrowbridgeReitz, SmithMaskingIsConsistentWithD) {
    // The projected area of visible microfacets equals that of the macrosurface:
    // integral of G1(w) max(0, w.wm) D(wm) over wm = cos(theta_w).
    for (Alphas a : kAlphas) {
        TrowbridgeReitzDistribution distrib(a.x, a.y);
        Vector3f w = DirectionFromAngles(1.1f, 2.f);
        double integral = IntegrateHemisphere([&](Vector3f wm) {
            return distrib.G1(w) * std::max<Float>(0, Dot(w, wm)) * distrib.D(wm);
        });
        EXPECT_NEAR(integral, CosTheta(w), kQuadratureTolerance) << a.x << " " << a.y;
    }
}

// A simple check that Sample_wm() draws from PDF(): a histogram of samples on a coarse
// (theta, phi) grid of the upper hemisphere against the PDF integrated over each cell.
// The full chi-square test of the BxDFs lives with the BxDF tests.
namespace {

constexpr int kHistogramThetaBins = 16, kHistogramPhiBins = 16;

int HistogramCell(Vector3f wm) {
    int ti = std::min(int(SphericalTheta(wm) / (Pi / 2) * kHistogramThetaBins),
                      kHistogramThetaBins - 1);
    int pi = std::min(int(SphericalPhi(wm) / (2 * Pi) * kHistogramPhiBins),
                      kHistogramPhiBins - 1);
    return ti * kHistogramPhiBins + pi;
}

// Probability of each cell, by the midpoint rule on a finer grid; wm outside the normals
// visible from w (or from -w, for w below the surface) has probability zero.
std::vector<double> CellProbabilities(const TrowbridgeReitzDistribution &distrib, Vector3f w) {
    constexpr int kSubsteps = 16;
    const int nTheta = kHistogramThetaBins * kSubsteps, nPhi = kHistogramPhiBins * kSubsteps;
    const double dTheta = Pi / 2 / nTheta, dPhi = 2 * Pi / nPhi;
    Vector3f wUp = w.z < 0 ? -w : w;
    std::vector<double> p(kHistogramThetaBins * kHistogramPhiBins, 0);
    for (int i = 0; i < nTheta; ++i) {
        double theta = (i + 0.5) * dTheta;
        for (int j = 0; j < nPhi; ++j) {
            Vector3f wm = DirectionFromAngles(Float(theta), Float((j + 0.5) * dPhi));
            if (Dot(wUp, wm) > 0)
                p[HistogramCell(wm)] += distrib.PDF(w, wm) * std::sin(theta) * dTheta * dPhi;
        }
    }
    return p;
}

}  // namespace

TEST(TrowbridgeReitz, SampleWmMatchesPDF) {
    constexpr int kSamples = 1'000'000;
    // Allowed deviation of a cell count from its expectation, in standard deviations,
    // plus an absolute slack for the quadrature error of the expectation.
    constexpr double kMaxSigma = 5, kCountSlack = 1e-4 * kSamples;

    // Includes grazing and below-the-surface directions.
    const std::array<Float, 4> thetas = {0.2f, 1.f, 1.45f, Pi - 1.f};
    RNG rng(1234);
    for (Alphas a : {Alphas{0.3f, 0.3f}, Alphas{0.7f, 0.7f}, Alphas{0.15f, 0.6f}}) {
        TrowbridgeReitzDistribution distrib(a.x, a.y);
        for (Float theta : thetas) {
            Vector3f w = DirectionFromAngles(theta, 0.9f);
            Vector3f wUp = w.z < 0 ? -w : w;
            std::vector<double> observed(kHistogramThetaBins * kHistogramPhiBins, 0);
            for (int i = 0; i < kSamples; ++i) {
                Vector3f wm = distrib.Sample_wm(w, Uniform2D(rng));
                ASSERT_NEAR(Length(wm), 1, kDirectionTolerance);
                ASSERT_GT(wm.z, 0);
                ASSERT_GE(Dot(wUp, wm), -kDirectionTolerance);
                observed[HistogramCell(wm)] += 1;
            }
            std::vector<double> p = CellProbabilities(distrib, w);
            for (size_t cell = 0; cell < p.size(); ++cell) {
                double expected = p[cell] * kSamples;
                EXPECT_NEAR(observed[cell], expected,
                            kMaxSigma * std::sqrt(expected) + kCountSlack)
                    << "alpha " << a.x << " " << a.y << " theta_w " << theta << " cell "
                    << cell;
            }
        }
    }
}

TEST(TrowbridgeReitz, HeightCorrelatedGLiesBetweenProductAndMinimumOfG1) {
    TrowbridgeReitzDistribution distrib(0.4f, 0.25f);
    RNG rng(99);
    for (int i = 0; i < 1000; ++i) {
        Vector3f wo = SampleUniformHemisphere(Uniform2D(rng));
        Vector3f wi = SampleUniformHemisphere(Uniform2D(rng));
        Float G = distrib.G(wo, wi);
        // Strictly above the uncorrelated product wherever both directions are masked.
        if (distrib.Lambda(wo) > kFloatTolerance && distrib.Lambda(wi) > kFloatTolerance) {
            EXPECT_GT(G, distrib.G1(wo) * distrib.G1(wi));
        }
        EXPECT_LE(G, std::min(distrib.G1(wo), distrib.G1(wi)) + kFloatTolerance);
    }
    // Looking straight down, nothing is masked.
    EXPECT_EQ(distrib.G1(Vector3f(0, 0, 1)), 1);
}

TEST(TrowbridgeReitz, NeverNaNOrInfinite) {
    // Includes a degenerate alpha and grazing directions, where D's terms blow up.
    const std::array<Alphas, 3> alphas = {{{0.f, 0.5f}, {1e-4f, 1e-4f}, {0.5f, 0.5f}}};
    RNG rng(3);
    for (Alphas a : alphas) {
        TrowbridgeReitzDistribution distrib(a.x, a.y);
        for (int i = 0; i < 10000; ++i) {
            Vector3f w = SampleUniformSphere(Uniform2D(rng));
            Vector3f wm = SampleUniformHemisphere(Uniform2D(rng));
            if (i % 10 == 0)
                wm.z = 0;  // exactly grazing normal
            ASSERT_TRUE(IsFinite(distrib.D(wm))) << a.x << " " << a.y;
            ASSERT_TRUE(IsFinite(distrib.G1(w))) << a.x << " " << a.y;
            if (w.z != 0) {
                Vector3f s = distrib.Sample_wm(w, Uniform2D(rng));
                ASSERT_TRUE(IsFinite(s.x) && IsFinite(s.y) && IsFinite(s.z)) << a.x << " " << a.y;
                ASSERT_TRUE(IsFinite(distrib.PDF(w, s))) << a.x << " " << a.y;
            }
        }
    }
}

TEST(TrowbridgeReitz, RoughnessToAlphaIsSquareRoot) {
    for (Float r : {0.f, 0.01f, 0.25f, 1.f})
        EXPECT_NEAR(TrowbridgeReitzDistribution::RoughnessToAlpha(r), std::sqrt(r),
                    kFloatTolerance);
}

TEST(TrowbridgeReitz, EffectivelySmoothThreshold) {
    // pbrt-v4 treats alpha below 1e-3 in both directions as a mirror.
    constexpr Float kSmoothAlpha = 1e-3f;
    EXPECT_TRUE(TrowbridgeReitzDistribution(0, 0).EffectivelySmooth());
    EXPECT_TRUE(TrowbridgeReitzDistribution(0.9f * kSmoothAlpha, 0.5f * kSmoothAlpha)
                    .EffectivelySmooth());
    EXPECT_FALSE(TrowbridgeReitzDistribution(kSmoothAlpha, kSmoothAlpha).EffectivelySmooth());
    // One rough direction makes the whole distribution rough.
    EXPECT_FALSE(TrowbridgeReitzDistribution(0, 0.5f).EffectivelySmooth());
    EXPECT_FALSE(TrowbridgeReitzDistribution(0.5f, 0).EffectivelySmooth());
}

TEST(TrowbridgeReitz, RegularizeDoublesSmallAlphaWithinLimits) {
    struct Case {
        Float before, after;
    };
    // Doubling, clamped to [0.1, 0.3]; 0.3 and above are left alone.
    const std::array<Case, 9> cases = {{{0.f, 0.1f},
                                        {0.01f, 0.1f},
                                        {0.05f, 0.1f},
                                        {0.08f, 0.16f},
                                        {0.12f, 0.24f},
                                        {0.2f, 0.3f},
                                        {0.25f, 0.3f},
                                        {0.3f, 0.3f},
                                        {0.75f, 0.75f}}};
    constexpr Float kAlphaTolerance = 1e-4f;  // recovered through Lambda
    for (Case cx : cases) {
        for (Case cy : cases) {
            TrowbridgeReitzDistribution distrib(cx.before, cy.before);
            distrib.Regularize();
            Alphas a = RecoverAlphas(distrib);
            EXPECT_NEAR(a.x, cx.after, kAlphaTolerance) << cx.before << " " << cy.before;
            EXPECT_NEAR(a.y, cy.after, kAlphaTolerance) << cx.before << " " << cy.before;
            EXPECT_FALSE(distrib.EffectivelySmooth());
        }
    }
}

TEST(TrowbridgeReitz, ToStringNamesTheAlphas) {
    EXPECT_EQ(TrowbridgeReitzDistribution(0.25f, 0.5f).ToString(),
              "[ TrowbridgeReitzDistribution alpha_x: 0.25 alpha_y: 0.5 ]");
}
