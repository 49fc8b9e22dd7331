// Spectral transport as in pbrt-v4: the visible-wavelength density and its sampling, secondary
// wavelength termination, blackbody normalization, the named glass and gold spectra against their
// source data at given wavelengths, RGB spectra, and dispersion terminating only where eta varies.
#include "pbrt_ext/materials/materials.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pbrt {
namespace {

// The density integrates to 1 over [360, 830] nm (midpoint rule, 0.01 nm steps; 1e-4 covers the
// rule's error and the density's rounded constants).
TEST(SampledWavelengths, VisibleDensityIntegratesToOne) {
    double sum = 0;
    for (double l = 360.005; l < 830; l += 0.01) sum += VisibleWavelengthsPDF(Float(l)) * 0.01;
    EXPECT_NEAR(sum, 1, 1e-4);
    EXPECT_EQ(VisibleWavelengthsPDF(359.9f), 0);
    EXPECT_EQ(VisibleWavelengthsPDF(830.1f), 0);
}

// Sampling inverts the CDF: the fraction of samples below lambda equals the integral of the
// density up to it (8 quantiles, 2^16 stratified u; tolerance 2e-3 > the float rounding of the
// closed-form inverse).
TEST(SampledWavelengths, SamplingFollowsTheDensity) {
    constexpr int n = 1 << 16;
    for (double q : {400.0, 450.0, 500.0, 538.0, 560.0, 600.0, 650.0, 700.0}) {
        int below = 0;
        for (int i = 0; i < n; ++i) below += SampleVisibleWavelengths((i + 0.5f) / n) < q;
        double cdf = 0;
        for (double l = 360.005; l < q; l += 0.01) cdf += VisibleWavelengthsPDF(Float(l)) * 0.01;
        EXPECT_NEAR(double(below) / n, cdf, 2e-3) << q;
    }
}

TEST(SampledWavelengths, FourStratifiedSamplesWithTheirDensities) {
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.1f);
    for (int i = 0; i < NSpectrumSamples; ++i) {
        EXPECT_GE(lambda[i], Lambda_min);
        EXPECT_LE(lambda[i], Lambda_max);
        EXPECT_FLOAT_EQ(lambda.PDF()[i], VisibleWavelengthsPDF(lambda[i]));
        EXPECT_FLOAT_EQ(lambda[i], SampleVisibleWavelengths(0.1f + 0.25f * i));
    }
    EXPECT_FALSE(lambda.SecondaryTerminated());
}

// Terminating keeps the first wavelength with a quarter of its density (it now stands for all
// four), zeroes the others' density, and is idempotent.
TEST(SampledWavelengths, TerminateSecondary) {
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.3f);
    Float pdf0 = lambda.PDF()[0];
    lambda.TerminateSecondary();
    EXPECT_TRUE(lambda.SecondaryTerminated());
    EXPECT_FLOAT_EQ(lambda.PDF()[0], pdf0 / NSpectrumSamples);
    for (int i = 1; i < NSpectrumSamples; ++i) EXPECT_EQ(lambda.PDF()[i], 0);
    SampledWavelengths again = lambda;
    again.TerminateSecondary();
    EXPECT_EQ(again, lambda);
}

// Planck's law in double precision, independent of the library's.
double Planck(double lambdaNm, double T) {
    const double c = 299792458.0, h = 6.62607015e-34, kb = 1.380649e-23, l = lambdaNm * 1e-9;
    return 2 * h * c * c / (std::pow(l, 5) * (std::exp(h * c / (l * kb * T)) - 1));
}

// pbrt-v4 normalizes a blackbody to 1 at its peak (Wien's law), and the shape is Planck's. The
// tolerance, 1e-3 relative, covers the difference between the 2012 constants that pbrt-v4 (and we)
// use and the exact 2019 SI ones.
TEST(Blackbody, PeaksAtOneWithPlancksShape) {
    for (Float T : {1500.f, 2700.f, 5000.f, 6500.f, 10000.f}) {
        BlackbodySpectrum b(T);
        double peak = 2.8977721e-3 / T * 1e9;
        EXPECT_NEAR(b(Float(peak)), 1, 1e-5) << T;
        for (double l : {380.0, 450.0, 550.0, 650.0, 780.0}) {
            double expected = Planck(l, T) / Planck(peak, T);
            EXPECT_NEAR(b(Float(l)) / expected, 1, 1e-3) << T << " " << l;
            EXPECT_LE(b(Float(l)), 1 + 1e-6);
        }
        EXPECT_NEAR(Blackbody(550, T) / Planck(550, T), 1, 1e-3) << T;
    }
    EXPECT_EQ(Blackbody(550, 0), 0);
}

// SCHOTT's data sheet for N-BK7: n_F (486.13 nm) 1.52238, n_d (587.56 nm) 1.51680, n_C
// (656.27 nm) 1.51432, to the 5 decimals printed (tolerance 5e-5: 5e-6 of rounding plus the
// nearest-nm lookup of the 1 nm tabulation, at most 0.5 nm x 6e-5/nm).
TEST(NamedSpectra, GlassBK7AtTheFraunhoferLines) {
    pstd::optional<Spectrum> bk7 = GetNamedSpectrum("glass-BK7");
    ASSERT_TRUE(bk7.has_value());
    EXPECT_NEAR((*bk7)(486.13f), 1.52238, 5e-5);
    EXPECT_NEAR((*bk7)(587.56f), 1.51680, 5e-5);
    EXPECT_NEAR((*bk7)(656.27f), 1.51432, 5e-5);
    EXPECT_FALSE(bk7->IsConstant());
}

// RGB spectra: an albedo's values stay in [0, 1]; an unbounded spectrum scales with its RGB; an
// illuminant [1 1 1] is the colour space's illuminant; grey is flat.
TEST(RGBSpectra, AlbedoUnboundedIlluminant) {
    const RGBColorSpace &cs = RGBColorSpace::sRGB();
    RGBAlbedoSpectrum red(cs, RGB(0.9f, 0.1f, 0.05f));
    for (Float l = 360; l <= 830; l += 5) {
        EXPECT_GE(red(l), 0);
        EXPECT_LE(red(l), 1);
    }
    EXPECT_GT(red(650), red(450));
    RGBUnboundedSpectrum bright(cs, RGB(9, 1, 0.5f)), dim(cs, RGB(0.9f, 0.1f, 0.05f));
    for (Float l = 380; l <= 780; l += 20) EXPECT_NEAR(bright(l), 10 * dim(l), 1e-4f * bright(l) + 1e-6f) << l;
    RGBIlluminantSpectrum white(cs, RGB(1, 1, 1));
    for (Float l = 380; l <= 780; l += 20) EXPECT_NEAR(white(l), cs.illuminant(l), 1e-5f * cs.illuminant(l)) << l;
    RGBAlbedoSpectrum grey(cs, RGB(0.3f, 0.3f, 0.3f));
    for (Float l = 380; l <= 780; l += 20) EXPECT_NEAR(grey(l), 0.3f, 1e-6f);
}

// pbrt-v4's dielectric: a constant eta keeps all four wavelengths; a dispersive glass
// terminates the secondary ones and refracts by its index at the first.
TEST(Dispersion, OnlyAVaryingEtaTerminatesSecondaryWavelengths) {
    TextureEvalContext ctx;
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.4f);
    DielectricMaterial constant;
    constant.GetBxDF(ctx, lambda);
    EXPECT_FALSE(lambda.SecondaryTerminated());
    DielectricMaterial glass;
    glass.eta = *GetNamedSpectrum("glass-BK7");
    glass.GetBxDF(ctx, lambda);
    EXPECT_TRUE(lambda.SecondaryTerminated());
}

}  // namespace
}  // namespace pbrt
