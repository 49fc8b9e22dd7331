// Spectra to RGB: neutral spectra stay exactly neutral, luminance is normalized as pbrt-v4 does,
// the named glasses reproduce the SCHOTT catalog's n_d, the named metals are the tabulated data
// in data/spectra, .spd files read like inline samples, and bad input is an error at its location.
#include "pbrt_ext/spectra.h"

#include "pbrt_ext/paramdict.h"
#include "pbrt_ext/util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pbrt {
namespace {

namespace fs = std::filesystem;

const FileLoc kLoc{"scene.pbrt", 3, 7};

SpectrumParam Samples(std::vector<double> pairs) {
    return SpectrumParam{SpectrumParamKind::Samples, std::move(pairs), "", kLoc};
}
SpectrumParam Named(std::string name, SpectrumParamKind kind = SpectrumParamKind::Named) {
    return SpectrumParam{kind, {}, std::move(name), kLoc};
}
SpectrumParam BlackbodyParam(double T) {
    return SpectrumParam{SpectrumParamKind::Blackbody, {T}, "", kLoc};
}
SpectrumParam RGB(double r, double g, double b) {
    return SpectrumParam{SpectrumParamKind::RGB, {r, g, b}, "", kLoc};
}

void ExpectRGBNear(SampledSpectrum s, Float r, Float g, Float b, Float tol) {
    EXPECT_NEAR(s[0], r, tol);
    EXPECT_NEAR(s[1], g, tol);
    EXPECT_NEAR(s[2], b, tol);
}

// The exact text of the ParseError that f throws.
template <typename F>
std::string ErrorText(F f) {
    try {
        f();
    } catch (const ParseError &e) {
        return e.what();
    }
    return "<no error>";
}

Float Luminance(SampledSpectrum rgb) {  // linear sRGB's Y row
    return 0.2126729f * rgb[0] + 0.7151522f * rgb[1] + 0.0721750f * rgb[2];
}

TEST(SpectraNeutral, ConstantReflectanceAndUnboundedAreExactlyGray) {
    for (double c : {0.0, 0.25, 1.0})
        ExpectRGBNear(SpectrumToRGB(Samples({360, c, 830, c}), SpectrumKind::Reflectance, ""), c, c, c, 1e-6f);
    ExpectRGBNear(SpectrumToRGB(Samples({360, 2.5, 830, 2.5}), SpectrumKind::Unbounded, ""), 2.5f, 2.5f, 2.5f, 1e-5f);
}

TEST(SpectraNeutral, D65IlluminantIsWhiteWithUnitLuminance) {
    ExpectRGBNear(SpectrumToRGB(Named("stdillum-D65"), SpectrumKind::Illuminant, ""), 1, 1, 1, 1e-5f);
    EXPECT_NEAR(SpectrumToPhotometric(Named("stdillum-D65"), ""), 1, 1e-5f);
}

TEST(SpectraNeutral, RGBPassesThroughWithPhotometricOne) {
    ExpectRGBNear(SpectrumToRGB(RGB(0.2, 0.5, 0.9), SpectrumKind::Reflectance, ""), 0.2f, 0.5f, 0.9f, 0);
    ExpectRGBNear(SpectrumToRGB(RGB(3, 0, 7), SpectrumKind::Illuminant, ""), 3, 0, 7, 0);
    EXPECT_EQ(SpectrumToPhotometric(RGB(3, 0, 7), ""), 1);
}

TEST(SpectraIlluminant, EqualEnergyHasUnitLuminanceAndIsPinkInSRGB) {
    // Illuminant E is not sRGB's white: pbrt-v4's film records it reddish (no white balance).
    SampledSpectrum e = SpectrumToRGB(Samples({300, 1, 900, 1}), SpectrumKind::Illuminant, "");
    EXPECT_NEAR(Luminance(e), 1, 2e-3f);
    EXPECT_NEAR(SpectrumToPhotometric(Samples({300, 1, 900, 1}), ""), 1, 1e-4f);
    EXPECT_GT(e[0], e[1]);
    EXPECT_GT(e[1], e[2]);
}

TEST(SpectraIlluminant, PhotometricIsTheLuminanceOfTheRGB) {
    for (double T : {1800.0, 3200.0, 6500.0, 12000.0}) {
        SampledSpectrum rgb = SpectrumToRGB(BlackbodyParam(T), SpectrumKind::Illuminant, "");
        EXPECT_NEAR(Luminance(rgb), SpectrumToPhotometric(BlackbodyParam(T), ""), 3e-3f) << T;
    }
    SampledSpectrum a = SpectrumToRGB(Named("stdillum-A"), SpectrumKind::Illuminant, "");
    EXPECT_NEAR(Luminance(a), 1, 3e-3f);
    EXPECT_GT(a[0], a[1]);  // incandescent: warm
    EXPECT_GT(a[1], a[2]);
}

TEST(SpectraBlackbody, PlancksLawAndPeakNormalization) {
    // Radiance of the Sun's photosphere (5778 K) at 500 nm: 2hc^2 / (l^5 (e^{hc/lkT} - 1)).
    double h = 6.62606957e-34, c = 299792458., kb = 1.3806488e-23, l = 500e-9, T = 5778;
    double expected = 2 * h * c * c / (std::pow(l, 5) * (std::exp(h * c / (l * kb * T)) - 1));
    EXPECT_NEAR(Blackbody(500, 5778) / expected, 1, 1e-5);
    EXPECT_EQ(Blackbody(500, 0), 0);
    EXPECT_EQ(Blackbody(500, -10), 0);
    // Wien's displacement law places the peak; the normalized spectrum is at most 1 there.
    Float lambdaMax = Float(2.8977721e-3 / 5000 * 1e9);
    EXPECT_GT(Blackbody(lambdaMax, 5000), Blackbody(lambdaMax - 2, 5000));
    EXPECT_GT(Blackbody(lambdaMax, 5000), Blackbody(lambdaMax + 2, 5000));
    // A spectrum that peaks in the visible has a channel near its peak value 1.
    SampledSpectrum rgb = SpectrumToRGB(BlackbodyParam(5000), SpectrumKind::Illuminant, "");
    EXPECT_GT(rgb.MaxComponentValue(), 0.8f);
    EXPECT_LT(rgb.MaxComponentValue(), 1.2f);
}

TEST(SpectraBlackbody, HotterIsBluer) {
    Float previous = 0;
    for (double T : {2700.0, 4000.0, 6500.0, 10000.0, 20000.0}) {
        SampledSpectrum rgb = SpectrumToRGB(BlackbodyParam(T), SpectrumKind::Illuminant, "");
        Float blueOverRed = rgb[2] / rgb[0];
        EXPECT_GT(blueOverRed, previous) << T;
        previous = blueOverRed;
    }
    // Candle light is outside the sRGB gamut; the negative blue is clamped away.
    SampledSpectrum candle = SpectrumToRGB(BlackbodyParam(1500), SpectrumKind::Illuminant, "");
    EXPECT_GT(candle[0], candle[1]);
    EXPECT_GE(candle[2], 0);
    // Near 6504 K the Planckian locus passes close to D65: nearly neutral.
    SampledSpectrum d = SpectrumToRGB(BlackbodyParam(6504), SpectrumKind::Illuminant, "");
    d /= Luminance(d);
    ExpectRGBNear(d, 1, 1, 1, 0.06f);
}

TEST(SpectraGlass, SellmeierMatchesTheSchottCatalogRefractiveIndex) {
    // n_d at the helium d line (587.5618 nm), as the SCHOTT data sheets list it.
    struct { const char *name; double nd; } glasses[] = {
        {"glass-BK7", 1.51680}, {"glass-BAF10", 1.67003}, {"glass-FK51A", 1.48656},
        {"glass-LASF9", 1.85025}, {"glass-F5", 1.67271}, {"glass-F10", 1.72828},
        {"glass-F11", 1.78472}};
    for (const auto &g : glasses) {
        pstd::optional<Float> n = NamedGlassIOR(g.name, 587.5618f);
        ASSERT_TRUE(n.has_value()) << g.name;
        EXPECT_NEAR(*n, g.nd, 2e-5) << g.name;
        // Normal dispersion: blue refracts more.
        SampledSpectrum rgb = SpectrumToRGB(Named(g.name), SpectrumKind::Unbounded, "");
        EXPECT_LT(rgb[0], rgb[1]) << g.name;
        EXPECT_LT(rgb[1], rgb[2]) << g.name;
        EXPECT_NEAR(rgb[1], g.nd, 0.01) << g.name;
    }
    EXPECT_FALSE(NamedGlassIOR("glass-unobtainium", 550).has_value());
}

// Reads data/spectra/metal-<name>.nk into (lambda nm, value) pairs of column 1 (n) or 2 (k).
std::vector<double> ReadNK(const std::string &metal, int column) {
    std::ifstream in(std::string(PBRT_EXT_TEST_DATA_DIR) + "/../../data/spectra/metal-" + metal + ".nk");
    EXPECT_TRUE(in.good()) << metal;
    std::vector<double> pairs;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream row(line);
        double lambda, n, k;
        row >> lambda >> n >> k;
        pairs.push_back(lambda * 1000);
        pairs.push_back(column == 1 ? n : k);
    }
    return pairs;
}

TEST(SpectraMetal, NamedMetalsAreTheTabulatedData) {
    for (const char *metal : {"Ag", "Al", "Au", "Cu", "CuZn"})
        for (int column : {1, 2}) {
            std::string name = std::string("metal-") + metal + (column == 1 ? "-eta" : "-k");
            SampledSpectrum named = SpectrumToRGB(Named(name), SpectrumKind::Unbounded, "");
            SampledSpectrum data = SpectrumToRGB(Samples(ReadNK(metal, column)), SpectrumKind::Unbounded, "");
            ExpectRGBNear(named, data[0], data[1], data[2], 1e-4f);
        }
}

// Normal-incidence Fresnel reflectance of a conductor, per channel.
SampledSpectrum NormalReflectance(const std::string &metal) {
    SampledSpectrum eta = SpectrumToRGB(Named("metal-" + metal + "-eta"), SpectrumKind::Unbounded, "");
    SampledSpectrum k = SpectrumToRGB(Named("metal-" + metal + "-k"), SpectrumKind::Unbounded, "");
    SampledSpectrum r;
    for (int c = 0; c < 3; ++c)
        r[c] = (Sqr(eta[c] - 1) + Sqr(k[c])) / (Sqr(eta[c] + 1) + Sqr(k[c]));
    return r;
}

TEST(SpectraMetal, MetalsHaveTheirColors) {
    SampledSpectrum au = NormalReflectance("Au"), cu = NormalReflectance("Cu");
    SampledSpectrum ag = NormalReflectance("Ag"), al = NormalReflectance("Al");
    EXPECT_GT(au[0], au[1]);  // gold and copper: red > green > blue
    EXPECT_GT(au[1], au[2]);
    EXPECT_GT(cu[0], cu[1]);
    EXPECT_GT(cu[1], cu[2]);
    EXPECT_GT(ag.MinComponentValue(), 0.85f);  // silver and aluminium: bright, nearly neutral
    EXPECT_GT(al.MinComponentValue(), 0.85f);
    EXPECT_LT(ag.MaxComponentValue() - ag.MinComponentValue(), 0.1f);
}

TEST(SpectraRange, ReflectanceIsClampedToTheUnitInterval) {
    // A narrow band outside the sRGB gamut: some channel would go negative unclamped.
    SampledSpectrum r = SpectrumToRGB(Samples({500, 0, 505, 1, 510, 0}), SpectrumKind::Reflectance, "");
    EXPECT_GE(r.MinComponentValue(), 0);
    EXPECT_LE(r.MaxComponentValue(), 1);
    SampledSpectrum u = SpectrumToRGB(Samples({500, 0, 505, 50, 510, 0}), SpectrumKind::Unbounded, "");
    EXPECT_GE(u.MinComponentValue(), 0);
}

TEST(SpectraRange, SamplesAreZeroOutsideTheirRange) {
    // pbrt-v4's PiecewiseLinearSpectrum: a spectrum given over 550-780 nm has no blue.
    SampledSpectrum r = SpectrumToRGB(Samples({600, 1, 780, 1}), SpectrumKind::Reflectance, "");
    EXPECT_LT(r[2], 0.02f);
    EXPECT_GT(r[0], 0.5f);
}

class SpectrumFiles : public testing::Test {
  protected:
    void SetUp() override {
        dir = fs::temp_directory_path() /
              ("pbrt_spectra_test_" + std::to_string(::getpid()) + "_" +
               testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    void Write(const std::string &name, const std::string &text) { std::ofstream(dir / name) << text; }
    fs::path dir;
};

TEST_F(SpectrumFiles, SpdFileReadsLikeInlineSamplesRelativeToBaseDir) {
    Write("warm.spd", "# wavelength value\n400 0.1  # blue end\n550 0.5\n\n700 0.9\n");
    SampledSpectrum inlined = SpectrumToRGB(Samples({400, 0.1, 550, 0.5, 700, 0.9}), SpectrumKind::Reflectance, "");
    for (auto kind : {SpectrumParamKind::File, SpectrumParamKind::Named}) {
        SampledSpectrum file = SpectrumToRGB(Named("warm.spd", kind), SpectrumKind::Reflectance, dir.string());
        EXPECT_EQ(file, inlined);
    }
    SampledSpectrum absolute =
        SpectrumToRGB(Named((dir / "warm.spd").string(), SpectrumParamKind::File), SpectrumKind::Reflectance, "/nonexistent");
    EXPECT_EQ(absolute, inlined);
}

TEST_F(SpectrumFiles, BadFilesAreErrorsAtTheParameter) {
    Write("odd.spd", "400 0.1 500\n");
    Write("word.spd", "400 0.1\n500 half\n");
    Write("down.spd", "500 0.1 400 0.2\n");
    std::string d = dir.string();
    auto convert = [&](const char *name) {
        return ErrorText([&] { SpectrumToRGB(Named(name, SpectrumParamKind::File), SpectrumKind::Reflectance, d); });
    };
    EXPECT_EQ(convert("odd.spd"), "scene.pbrt:3:7: error: spectrum file \"" + d +
                                      "/odd.spd\" has 3 values, expected (wavelength, value) pairs");
    EXPECT_EQ(convert("word.spd"), "scene.pbrt:3:7: error: spectrum file \"" + d +
                                       "/word.spd\" line 2: \"half\" is not a number, expected (wavelength, value) pairs");
    EXPECT_EQ(convert("down.spd"), "scene.pbrt:3:7: error: spectrum file \"" + d +
                                       "/down.spd\": wavelength 400 after 500, expected increasing wavelengths");
    EXPECT_EQ(convert("missing.spd"), "scene.pbrt:3:7: error: spectrum file \"" + d +
                                          "/missing.spd\" cannot be read, expected a file of (wavelength, value) pairs");
}

TEST(SpectraErrors, ExactMessagesAtTheParameter) {
    auto convert = [](SpectrumParam p, SpectrumKind kind) {
        return ErrorText([&] { SpectrumToRGB(p, kind, ""); });
    };
    EXPECT_EQ(convert(Samples({400, 1, 500}), SpectrumKind::Reflectance),
              "scene.pbrt:3:7: error: spectrum has 3 values, expected (wavelength, value) pairs");
    EXPECT_EQ(convert(Samples({500, 1, 500, 1}), SpectrumKind::Reflectance),
              "scene.pbrt:3:7: error: spectrum: wavelength 500 after 500, expected increasing wavelengths");
    EXPECT_EQ(convert(RGB(0.5, -0.25, 0), SpectrumKind::Illuminant),
              "scene.pbrt:3:7: error: rgb (0.5, -0.25, 0) has a negative component, expected values >= 0");
    EXPECT_EQ(convert(RGB(0.5, 1.5, 0), SpectrumKind::Reflectance),
              "scene.pbrt:3:7: error: rgb reflectance (0.5, 1.5, 0) has a component > 1, expected values in [0, 1]");
    EXPECT_EQ(convert(RGB(0.5, 1.5, 0), SpectrumKind::Unbounded), "<no error>");
    EXPECT_EQ(convert(BlackbodyParam(0), SpectrumKind::Illuminant),
              "scene.pbrt:3:7: error: blackbody needs one temperature, expected a positive value in kelvin");
    EXPECT_EQ(convert(Named("metal-MgO-eta"), SpectrumKind::Unbounded),
              "scene.pbrt:3:7: error: unknown named spectrum \"metal-MgO-eta\", expected one of glass-BK7, "
              "glass-BAF10, glass-FK51A, glass-LASF9, glass-F5, glass-F10, glass-F11, metal-Ag-eta, "
              "metal-Ag-k, metal-Al-eta, metal-Al-k, metal-Au-eta, metal-Au-k, metal-Cu-eta, metal-Cu-k, "
              "metal-CuZn-eta, metal-CuZn-k, stdillum-A, stdillum-D65 or a spectrum file");
    EXPECT_EQ(ErrorText([] { SpectrumToPhotometric(BlackbodyParam(-5), ""); }),
              "scene.pbrt:3:7: error: blackbody needs one temperature, expected a positive value in kelvin");
}

}  // namespace
}  // namespace pbrt
