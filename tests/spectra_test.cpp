// Spectra as a scene file writes them (CreateSpectrum): constant samples are exactly constant,
// "rgb" values become the sRGB spectra of their use and come back as that RGB through the
// observer, luminance is normalized as pbrt-v4 does, the named glasses reproduce the SCHOTT
// catalog's n_d, the named metals are the tabulated data in data/spectra, .spd files read like
// inline samples, and bad input is an error at its location.
//
// Before spectral transport these tests checked each spectrum's projection to linear sRGB. The
// renderer now carries the spectra themselves, so each check is on the spectrum's values at
// wavelengths, or on the colour the default film records for it (SpectrumToXYZ, then sRGB), which
// is the same projection the old tests made.
#include "pbrt_ext/spectra.h"

#include "pbrt_ext/materials.h"
#include "pbrt_ext/paramdict.h"
#include "pbrt_ext/util/colorspace.h"
#include "pbrt_ext/util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
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
SpectrumParam RGBParam(double r, double g, double b) {
    return SpectrumParam{SpectrumParamKind::RGB, {r, g, b}, "", kLoc};
}

Spectrum Create(const SpectrumParam &param, SpectrumType type, const std::string &baseDir = "") {
    return CreateSpectrum(param, type, RGBColorSpace::sRGB(), baseDir);
}

void ExpectRGBNear(RGB s, Float r, Float g, Float b, Float tol) {
    EXPECT_NEAR(s[0], r, tol) << s.ToString();
    EXPECT_NEAR(s[1], g, tol) << s.ToString();
    EXPECT_NEAR(s[2], b, tol) << s.ToString();
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

Float Luminance(RGB rgb) {  // linear sRGB's Y row
    RGB y = RGBColorSpace::sRGB().LuminanceVector();
    return y.r * rgb.r + y.g * rgb.g + y.b * rgb.b;
}

// pbrt-v4's SpectrumToPhotometric in units of CIE_Y_integral: the luminance (Y) of an emission
// spectrum. pbrt-v4's lights divide their scale by SpectrumToPhotometric, which is the inner
// product with ybar (CIE_Y_integral for a spectrum of luminance 1): this ratio is the luminance
// the old RGB projection called photometric, 1 for the named illuminants.
Float Photometric(const Spectrum &s) { return SpectrumToPhotometric(s) / CIE_Y_integral; }

// The linear sRGB the default film records for an emission spectrum (its XYZ, Y = luminance).
RGB EmissionRGB(const Spectrum &s) { return RGBColorSpace::sRGB().ToRGB(SpectrumToXYZ(s)); }

// The linear sRGB of a reflectance r under sRGB's illuminant (D65), normalized so that a perfect
// reflector is white: sums at 1 nm over the rendered range, as SpectrumToXYZ sums.
RGB ReflectanceRGB(const std::function<double(Float)> &r) {
    const RGBColorSpace &cs = RGBColorSpace::sRGB();
    double x = 0, y = 0, z = 0, norm = 0;
    for (int lambda = int(Lambda_min); lambda <= int(Lambda_max); ++lambda) {
        Float l = Float(lambda);
        double light = cs.illuminant(l);
        x += light * r(l) * Spectra::X()(l);
        y += light * r(l) * Spectra::Y()(l);
        z += light * r(l) * Spectra::Z()(l);
        norm += light * Spectra::Y()(l);
    }
    return cs.ToRGB(XYZ(Float(x / norm), Float(y / norm), Float(z / norm)));
}
RGB ReflectanceRGB(const Spectrum &s) {
    return ReflectanceRGB([&](Float l) { return double(s(l)); });
}

// The RGB -> spectrum -> RGB round trip of the sigmoid table, per channel for an RGB in [0, 1]
// (tests/rgbtospectrum_test.cpp); an unbounded or illuminant RGB is fitted as rgb / (2 max rgb).
constexpr Float kRGBRoundTrip = 1e-3f;

TEST(SpectraNeutral, ConstantReflectanceAndUnboundedAreExactlyGray) {
    // A constant spectrum is that constant at every wavelength, whatever its use; seen under D65 a
    // constant reflectance is exactly the gray of its value (sRGB's white is D65's).
    for (double c : {0.0, 0.25, 1.0}) {
        Spectrum s = Create(Samples({360, c, 830, c}), SpectrumType::Albedo);
        for (Float lambda : {360.f, 412.5f, 550.f, 700.25f, 830.f})
            EXPECT_NEAR(s(lambda), c, 1e-6f) << lambda;
        ExpectRGBNear(ReflectanceRGB(s), c, c, c, 1e-6f);
    }
    Spectrum u = Create(Samples({360, 2.5, 830, 2.5}), SpectrumType::Unbounded);
    for (Float lambda : {360.f, 550.f, 830.f})
        EXPECT_NEAR(u(lambda), 2.5f, 1e-5f) << lambda;
    // An "rgb" gray is a constant spectrum too (the sigmoid of a constant polynomial).
    Spectrum gray = Create(RGBParam(0.25, 0.25, 0.25), SpectrumType::Albedo);
    for (Float lambda : {360.f, 550.f, 830.f})
        EXPECT_NEAR(gray(lambda), 0.25f, 1e-6f) << lambda;
}

TEST(SpectraNeutral, D65IlluminantIsWhiteWithUnitLuminance) {
    Spectrum d65 = Create(Named("stdillum-D65"), SpectrumType::Illuminant);
    ExpectRGBNear(EmissionRGB(d65), 1, 1, 1, 1e-5f);
    EXPECT_NEAR(Photometric(d65), 1, 1e-5f);
}

TEST(SpectraNeutral, RGBComesBackThroughTheObserverWithTheIlluminantsPhotometric) {
    // "rgb" values are no longer passed through: they become the sRGB spectrum of their use, whose
    // colour is the RGB again within the sigmoid table's round trip.
    Spectrum albedo = Create(RGBParam(0.2, 0.5, 0.9), SpectrumType::Albedo);
    ASSERT_NE(albedo.Get<RGBAlbedoSpectrum>(), nullptr);
    ExpectRGBNear(ReflectanceRGB(albedo), 0.2f, 0.5f, 0.9f, kRGBRoundTrip);
    Spectrum emission = Create(RGBParam(3, 0, 7), SpectrumType::Illuminant);
    ASSERT_NE(emission.Get<RGBIlluminantSpectrum>(), nullptr);
    ExpectRGBNear(EmissionRGB(emission), 3, 0, 7, kRGBRoundTrip * 2 * 7);
    // pbrt-v4 ignores the RGB in SpectrumToPhotometric: an "rgb" light's luminance is its
    // illuminant's, 1, so that "rgb L [1 1 1]" is D65 at 1 nit.
    EXPECT_NEAR(Photometric(emission), 1, 1e-5f);
    EXPECT_EQ(SpectrumToPhotometric(emission),
              SpectrumToPhotometric(Create(RGBParam(0.1, 0.1, 0.1), SpectrumType::Illuminant)));
    Spectrum unbounded = Create(RGBParam(0.5, 1.5, 0), SpectrumType::Unbounded);
    ASSERT_NE(unbounded.Get<RGBUnboundedSpectrum>(), nullptr);
    ExpectRGBNear(ReflectanceRGB(unbounded), 0.5f, 1.5f, 0, kRGBRoundTrip * 2 * 1.5f);
}

TEST(SpectraIlluminant, EqualEnergyHasUnitLuminanceAndIsPinkInSRGB) {
    // Illuminant E is not sRGB's white: pbrt-v4's film records it reddish (no white balance).
    Spectrum E = Create(Samples({300, 1, 900, 1}), SpectrumType::Illuminant);
    EXPECT_NEAR(Photometric(E), 1, 1e-4f);
    // As a light divides it by its photometric value: luminance 1.
    RGB e = EmissionRGB(E) / Photometric(E);
    EXPECT_NEAR(Luminance(e), 1, 2e-3f);
    EXPECT_GT(e[0], e[1]);
    EXPECT_GT(e[1], e[2]);
}

TEST(SpectraIlluminant, PhotometricIsTheLuminanceOfTheRGB) {
    for (double T : {1800.0, 3200.0, 6500.0, 12000.0}) {
        Spectrum bb = Create(BlackbodyParam(T), SpectrumType::Illuminant);
        EXPECT_NEAR(Luminance(EmissionRGB(bb)), Photometric(bb), 3e-3f) << T;
    }
    Spectrum A = Create(Named("stdillum-A"), SpectrumType::Illuminant);
    RGB a = EmissionRGB(A);
    EXPECT_NEAR(Luminance(a), 1, 3e-3f);
    EXPECT_NEAR(Photometric(A), 1, 1e-5f);
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
    // Wien's displacement law places the peak; the normalized spectrum is 1 there, less elsewhere.
    Float lambdaMax = Float(2.8977721e-3 / 5000 * 1e9);
    EXPECT_GT(Blackbody(lambdaMax, 5000), Blackbody(lambdaMax - 2, 5000));
    EXPECT_GT(Blackbody(lambdaMax, 5000), Blackbody(lambdaMax + 2, 5000));
    Spectrum bb = Create(BlackbodyParam(5000), SpectrumType::Illuminant);
    EXPECT_NEAR(bb(lambdaMax), 1, 1e-5f);
    for (Float lambda = Lambda_min; lambda <= Lambda_max; lambda += 5)
        EXPECT_LE(bb(lambda), 1 + 1e-5f) << lambda;
    // A spectrum that peaks in the visible has a channel near its peak value 1.
    RGB rgb = EmissionRGB(bb);
    EXPECT_GT(rgb.MaxComponentValue(), 0.8f);
    EXPECT_LT(rgb.MaxComponentValue(), 1.2f);
}

TEST(SpectraBlackbody, HotterIsBluer) {
    Float previous = 0;
    for (double T : {2700.0, 4000.0, 6500.0, 10000.0, 20000.0}) {
        RGB rgb = EmissionRGB(Create(BlackbodyParam(T), SpectrumType::Illuminant));
        Float blueOverRed = rgb[2] / rgb[0];
        EXPECT_GT(blueOverRed, previous) << T;
        previous = blueOverRed;
    }
    // Candle light is outside the sRGB gamut. The RGB projection clamped its negative blue; the
    // spectrum itself is what is rendered now, and it is never negative, falling toward blue.
    Spectrum candle = Create(BlackbodyParam(1500), SpectrumType::Illuminant);
    RGB c = EmissionRGB(candle);
    EXPECT_GT(c[0], c[1]);
    for (Float lambda = Lambda_min; lambda < Lambda_max; lambda += 5) {
        EXPECT_GE(candle(lambda), 0) << lambda;
        EXPECT_LT(candle(lambda), candle(lambda + 5)) << lambda;
    }
    // Near 6504 K the Planckian locus passes close to D65: nearly neutral.
    RGB d = EmissionRGB(Create(BlackbodyParam(6504), SpectrumType::Illuminant));
    d /= Luminance(d);
    ExpectRGBNear(d, 1, 1, 1, 0.06f);
}

TEST(SpectraGlass, SellmeierMatchesTheSchottCatalogRefractiveIndex) {
    // n_d at the helium d line (587.5618 nm), as the SCHOTT data sheets list it. The named glasses
    // are tabulated at every nm; linear interpolation between 587 and 588 nm is exact to 1e-7.
    struct { const char *name; double nd; } glasses[] = {
        {"glass-BK7", 1.51680}, {"glass-BAF10", 1.67003}, {"glass-FK51A", 1.48656},
        {"glass-LASF9", 1.85025}, {"glass-F5", 1.67271}, {"glass-F10", 1.72828},
        {"glass-F11", 1.78472}};
    for (const auto &g : glasses) {
        Spectrum n = Create(Named(g.name), SpectrumType::Unbounded);
        EXPECT_FALSE(n.IsConstant()) << g.name;  // a dielectric of it disperses
        EXPECT_NEAR(Lerp(0.5618f, n(587), n(588)), g.nd, 2e-5) << g.name;
        // Normal dispersion: blue refracts more.
        EXPECT_GT(n(450), n(550)) << g.name;
        EXPECT_GT(n(550), n(650)) << g.name;
        EXPECT_NEAR(n(550), g.nd, 0.01) << g.name;
    }
    EXPECT_FALSE(GetNamedSpectrum("glass-unobtainium").has_value());
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
    // At each of the file's wavelengths in the rendered range the named spectrum is the file's
    // value, and between them it is the same piecewise-linear function as the file's samples
    // given inline (checked at every nm).
    for (const char *metal : {"Ag", "Al", "Au", "Cu", "CuZn"})
        for (int column : {1, 2}) {
            std::string name = std::string("metal-") + metal + (column == 1 ? "-eta" : "-k");
            std::vector<double> pairs = ReadNK(metal, column);
            Spectrum named = Create(Named(name), SpectrumType::Unbounded);
            Spectrum data = Create(Samples(pairs), SpectrumType::Unbounded);
            int checked = 0;
            for (size_t i = 0; i < pairs.size(); i += 2)
                if (pairs[i] >= Lambda_min && pairs[i] <= Lambda_max) {
                    EXPECT_NEAR(named(Float(pairs[i])), pairs[i + 1], 1e-5 * pairs[i + 1])
                        << name << " at " << pairs[i] << " nm";
                    ++checked;
                }
            EXPECT_GE(checked, 10) << name;
            ASSERT_LE(pairs.front(), Lambda_min) << name;  // the data cover the rendered range
            ASSERT_GE(pairs[pairs.size() - 2], Lambda_max) << name;
            for (int lambda = int(Lambda_min); lambda <= int(Lambda_max); ++lambda)
                ASSERT_NEAR(named(Float(lambda)), data(Float(lambda)), 1e-5f * data(Float(lambda)))
                    << name << " at " << lambda << " nm";
        }
}

// Normal-incidence Fresnel reflectance of a named conductor, at lambda.
Float NormalReflectance(const std::string &metal, Float lambda) {
    Float eta = GetNamedSpectrum("metal-" + metal + "-eta").value()(lambda);
    Float k = GetNamedSpectrum("metal-" + metal + "-k").value()(lambda);
    return (Sqr(eta - 1) + Sqr(k)) / (Sqr(eta + 1) + Sqr(k));
}

TEST(SpectraMetal, MetalsHaveTheirColors) {
    // The colour of each metal's normal-incidence reflectance spectrum under D65.
    auto color = [](const char *metal) {
        return ReflectanceRGB([metal](Float l) { return double(NormalReflectance(metal, l)); });
    };
    RGB au = color("Au"), cu = color("Cu"), ag = color("Ag"), al = color("Al");
    EXPECT_GT(au[0], au[1]);  // gold and copper: red > green > blue
    EXPECT_GT(au[1], au[2]);
    EXPECT_GT(cu[0], cu[1]);
    EXPECT_GT(cu[1], cu[2]);
    EXPECT_GT(ag.MinComponentValue(), 0.85f);  // silver and aluminium: bright, nearly neutral
    EXPECT_GT(al.MinComponentValue(), 0.85f);
    EXPECT_LT(ag.MaxComponentValue() - ag.MinComponentValue(), 0.1f);
}

TEST(SpectraRange, ReflectanceIsClampedToTheUnitIntervalWhereItIsUsed) {
    // The RGB projection clamped a narrow band outside the sRGB gamut; spectrally there is no
    // gamut: the band is kept as given, in [0, 1], and nothing goes negative.
    Spectrum r = Create(Samples({500, 0, 505, 1, 510, 0}), SpectrumType::Albedo);
    EXPECT_EQ(r(505), 1);
    EXPECT_EQ(r(500), 0);
    EXPECT_EQ(r(450), 0);
    EXPECT_NEAR(r(502.5f), 0.5f, 1e-6f);
    for (Float lambda = Lambda_min; lambda <= Lambda_max; lambda += 0.5f) {
        EXPECT_GE(r(lambda), 0) << lambda;
        EXPECT_LE(r(lambda), 1) << lambda;
    }
    // Unbounded values are kept; a material clamps a reflectance to [0, 1] where it evaluates it
    // (pbrt-v4's Clamp in its materials), so a diffuse surface of this band reflects at most all.
    Spectrum u = Create(Samples({500, 0, 505, 50, 510, 0}), SpectrumType::Unbounded);
    EXPECT_EQ(u(505), 50);
    EXPECT_GE(u(502), 0);
    SampledWavelengths lambda = SampledWavelengths::SampleUniform(0, 505, 905);  // 505, 605, ...
    BxDF bxdf = DiffuseMaterial{u}.GetBxDF(TextureEvalContext(), lambda);
    Vector3f wo(0, 0, 1), wi = Normalize(Vector3f(0.3f, 0.2f, 1));
    SampledSpectrum R = Pi * bxdf.f(wo, wi, TransportMode::Radiance);
    EXPECT_NEAR(R[0], 1, 1e-6f);  // 50 at 505 nm, clamped
    EXPECT_EQ(R[1], 0);
}

TEST(SpectraRange, SamplesAreZeroOutsideTheirRange) {
    // pbrt-v4's PiecewiseLinearSpectrum: a spectrum given over 600-780 nm has no blue.
    Spectrum r = Create(Samples({600, 1, 780, 1}), SpectrumType::Albedo);
    EXPECT_EQ(r(450), 0);
    EXPECT_EQ(r(599), 0);
    EXPECT_EQ(r(781), 0);
    EXPECT_EQ(r(650), 1);
    RGB rgb = ReflectanceRGB(r);
    EXPECT_LT(rgb[2], 0.02f);
    EXPECT_GT(rgb[0], 0.5f);
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

// A file's spectrum is the inline samples' over their range. Outside it the two differ as they do
// in pbrt-v4: a file (PiecewiseLinearSpectrum::Read) holds its end values out to the rendered
// range, inline samples (a PiecewiseLinearSpectrum as given) are zero there.
void ExpectSameAsInline(const Spectrum &file, const Spectrum &inlined) {
    for (Float lambda = 400; lambda <= 700; lambda += 0.25f)
        ASSERT_EQ(file(lambda), inlined(lambda)) << lambda;
    for (Float lambda : {360.f, 399.f}) {
        EXPECT_EQ(file(lambda), inlined(400)) << lambda;
        EXPECT_EQ(inlined(lambda), 0) << lambda;
    }
    for (Float lambda : {701.f, 830.f}) {
        EXPECT_EQ(file(lambda), inlined(700)) << lambda;
        EXPECT_EQ(inlined(lambda), 0) << lambda;
    }
}

TEST_F(SpectrumFiles, SpdFileReadsLikeInlineSamplesRelativeToBaseDir) {
    Write("warm.spd", "# wavelength value\n400 0.1  # blue end\n550 0.5\n\n700 0.9\n");
    Spectrum inlined = Create(Samples({400, 0.1, 550, 0.5, 700, 0.9}), SpectrumType::Albedo);
    for (auto kind : {SpectrumParamKind::File, SpectrumParamKind::Named}) {
        Spectrum file = Create(Named("warm.spd", kind), SpectrumType::Albedo, dir.string());
        ExpectSameAsInline(file, inlined);
    }
    Spectrum absolute = Create(Named((dir / "warm.spd").string(), SpectrumParamKind::File),
                               SpectrumType::Albedo, "/nonexistent");
    ExpectSameAsInline(absolute, inlined);
}

TEST_F(SpectrumFiles, BadFilesAreErrorsAtTheParameter) {
    Write("odd.spd", "400 0.1 500\n");
    Write("word.spd", "400 0.1\n500 half\n");
    Write("down.spd", "500 0.1 400 0.2\n");
    std::string d = dir.string();
    auto convert = [&](const char *name) {
        return ErrorText(
            [&] { Create(Named(name, SpectrumParamKind::File), SpectrumType::Albedo, d); });
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
    auto convert = [](SpectrumParam p, SpectrumType type) {
        return ErrorText([&] { Create(p, type); });
    };
    EXPECT_EQ(convert(Samples({400, 1, 500}), SpectrumType::Albedo),
              "scene.pbrt:3:7: error: spectrum has 3 values, expected (wavelength, value) pairs");
    EXPECT_EQ(convert(Samples({500, 1, 500, 1}), SpectrumType::Albedo),
              "scene.pbrt:3:7: error: spectrum: wavelength 500 after 500, expected increasing wavelengths");
    EXPECT_EQ(convert(RGBParam(0.5, -0.25, 0), SpectrumType::Illuminant),
              "scene.pbrt:3:7: error: rgb (0.5, -0.25, 0) has a negative component, expected values >= 0");
    EXPECT_EQ(convert(RGBParam(0.5, 1.5, 0), SpectrumType::Albedo),
              "scene.pbrt:3:7: error: rgb reflectance (0.5, 1.5, 0) has a component > 1, expected values in [0, 1]");
    EXPECT_EQ(convert(RGBParam(0.5, 1.5, 0), SpectrumType::Unbounded), "<no error>");
    EXPECT_EQ(convert(BlackbodyParam(0), SpectrumType::Illuminant),
              "scene.pbrt:3:7: error: blackbody needs one temperature, expected a positive value in kelvin");
    // The named spectra are pbrt-v4's, now with its camera sensor responses (<camera>_r, _g, _b).
    std::string sensors;
    for (const char *camera :
         {"canon_eos_100d", "canon_eos_1dx_mkii", "canon_eos_200d", "canon_eos_200d_mkii",
          "canon_eos_5d", "canon_eos_5d_mkii", "canon_eos_5d_mkiii", "canon_eos_5d_mkiv",
          "canon_eos_5ds", "canon_eos_m", "hasselblad_l1d_20c", "nikon_d810", "nikon_d850",
          "sony_ilce_6400", "sony_ilce_7m3", "sony_ilce_7rm3", "sony_ilce_9"})
        for (const char *channel : {"_r", "_g", "_b"})
            sensors += std::string(", ") + camera + channel;
    EXPECT_EQ(convert(Named("metal-MgO-eta"), SpectrumType::Unbounded),
              "scene.pbrt:3:7: error: unknown named spectrum \"metal-MgO-eta\", expected one of glass-BK7, "
              "glass-BAF10, glass-FK51A, glass-LASF9, glass-F5, glass-F10, glass-F11, metal-Ag-eta, "
              "metal-Ag-k, metal-Al-eta, metal-Al-k, metal-Au-eta, metal-Au-k, metal-Cu-eta, metal-Cu-k, "
              "metal-CuZn-eta, metal-CuZn-k, stdillum-A, stdillum-D65" +
                  sensors + " or a spectrum file");
    EXPECT_EQ(convert(BlackbodyParam(-5), SpectrumType::Illuminant),
              "scene.pbrt:3:7: error: blackbody needs one temperature, expected a positive value in kelvin");
}

}  // namespace
}  // namespace pbrt
