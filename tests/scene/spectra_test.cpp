// Spectra as a scene file writes them (CreateSpectrum): constant samples are exactly constant,
// "rgb" values become the sRGB spectra of their use and come back as that RGB through the
// observer, luminance is normalized as pbrt-v4 does, the named glasses reproduce the SCHOTT
// catalog's n_d, every named spectrum is pbrt-v4's, .spd files read like
// inline samples, and bad input is an error at its location.
//
// Before spectral transport these tests checked each spectrum's projection to linear sRGB. The
// renderer now carries the spectra themselves, so each check is on the spectrum's values at
// wavelengths, or on the colour the default film records for it (SpectrumToXYZ, then sRGB), which
// is the same projection the old tests made.
#include "pbrt_ext/scene/spectra.h"

#include "pbrt_ext/materials/materials.h"
#include "pbrt_ext/scene/paramdict.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
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
// (tests/spectra/rgbtospectrum_test.cpp); an unbounded or illuminant RGB is fitted as rgb / (2 max rgb).
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
    // are pbrt-v4's tables (refractiveindex.info's, from the same Sellmeier fits) every 22 nm,
    // interpolated linearly, which is within 5e-5 of the fit at n_d (measured: 3.1e-5, BAF10).
    struct { const char *name; double nd; } glasses[] = {
        {"glass-BK7", 1.51680}, {"glass-BAF10", 1.67003}, {"glass-FK51A", 1.48656},
        {"glass-LASF9", 1.85025}, {"glass-F5", 1.67271}, {"glass-F10", 1.72828},
        {"glass-F11", 1.78472}};
    for (const auto &g : glasses) {
        Spectrum n = Create(Named(g.name), SpectrumType::Unbounded);
        EXPECT_FALSE(n.IsConstant()) << g.name;  // a dielectric of it disperses
        EXPECT_NEAR(n(587.5618f), g.nd, 5e-5) << g.name;
        // Normal dispersion: blue refracts more.
        EXPECT_GT(n(450), n(550)) << g.name;
        EXPECT_GT(n(550), n(650)) << g.name;
        EXPECT_NEAR(n(550), g.nd, 0.01) << g.name;
    }
    EXPECT_FALSE(GetNamedSpectrum("glass-unobtainium").has_value());
}

// Every named spectrum of pbrt-v4's (but the cameras', sensor_test) at ten wavelengths across the
// visible range, printed by pbrt-v4 itself (commit 5f7a6068, built from source: GetNamedSpectrum
// in a small program linked against its libpbrt_lib.a). The tables are pbrt-v4's own data, and
// illuminants are scaled to luminance 1 through the same CIE Y (util/cietables.h), so the values
// agree to float rounding.
struct NamedReference {
    const char *name;
    Float values[10];
};
constexpr Float kNamedLambdas[10] = {362.5f, 404.7f, 455.5f, 510, 546.1f, 587.6f, 632.8f, 700.3f, 781.1f, 829.5f};
const NamedReference kPbrtV4Named[] = {
    {"glass-BK7", {1.53678346f, 1.53028166f, 1.52483344f, 1.52079082f, 1.51873028f, 1.5168016f, 1.51509285f, 1.51305926f, 1.51116192f, 1.51021183f}},
    {"glass-BAF10", {1.70778501f, 1.69484854f, 1.68446362f, 1.67708766f, 1.67338347f, 1.669999f, 1.66706383f, 1.66366589f, 1.66059828f, 1.6591171f}},
    {"glass-FK51A", {1.50080013f, 1.49615967f, 1.49229121f, 1.48940539f, 1.48794138f, 1.4865582f, 1.48533428f, 1.48389077f, 1.48257852f, 1.48192358f}},
    {"glass-LASF9", {1.91997254f, 1.8984493f, 1.87771273f, 1.86339879f, 1.85646188f, 1.85026324f, 1.84483981f, 1.83877635f, 1.83348334f, 1.83098876f}},
    {"glass-F5", {1.72865498f, 1.71107101f, 1.69442737f, 1.68307889f, 1.6776036f, 1.67271793f, 1.66844225f, 1.6636492f, 1.65943718f, 1.65743482f}},
    {"glass-F10", {1.79057884f, 1.77580225f, 1.75498629f, 1.74097562f, 1.73422968f, 1.72827864f, 1.72310436f, 1.71733689f, 1.71223307f, 1.70988917f}},
    {"glass-F11", {1.87002158f, 1.84239125f, 1.81691444f, 1.79994905f, 1.79187429f, 1.78473711f, 1.77854919f, 1.77168894f, 1.76574719f, 1.76296103f}},
    {"metal-Ag-eta", {0.189600855f, 0.17272827f, 0.147130594f, 0.129961193f, 0.126282588f, 0.120655864f, 0.135152489f, 0.14252007f, 0.142891631f, 0.145715371f}},
    {"metal-Ag-k", {1.5788455f, 2.00751734f, 2.52398682f, 3.0097394f, 3.30765343f, 3.63832593f, 3.9858377f, 4.52545357f, 5.13928699f, 5.52274847f}},
    {"metal-Al-eta", {0.402403414f, 0.501730263f, 0.633500993f, 0.802834809f, 0.941964984f, 1.13572061f, 1.37292171f, 1.83933067f, 2.67215753f, 2.72350264f}},
    {"metal-Al-k", {4.40344191f, 4.91661167f, 5.535676f, 6.19860888f, 6.63813257f, 7.11940145f, 7.61774111f, 8.3151741f, 8.56280231f, 8.29968929f}},
    {"metal-Au-eta", {1.72074974f, 1.65021026f, 1.45974171f, 0.699721634f, 0.368803442f, 0.242451206f, 0.180833608f, 0.160511255f, 0.177332923f, 0.189043984f}},
    {"metal-Au-k", {1.85806739f, 1.95844567f, 1.85924172f, 2.01763487f, 2.65200162f, 2.96400762f, 3.06810212f, 3.96809506f, 4.92591763f, 5.41487503f}},
    {"metal-Cu-eta", {1.27472448f, 1.17681158f, 1.16235447f, 1.12723887f, 0.987340868f, 0.504284918f, 0.238628611f, 0.214898974f, 0.251038551f, 0.262062192f}},
    {"metal-Cu-k", {1.94251812f, 2.15178442f, 2.41732025f, 2.59537387f, 2.57918096f, 2.78228974f, 3.41678405f, 4.16076136f, 4.87084389f, 5.28326416f}},
    {"metal-CuZn-eta", {1.50150001f, 1.42619991f, 1.03900003f, 0.638999999f, 0.535580039f, 0.461920023f, 0.44472f, 0.446060002f, 0.464549959f, 0.482899994f}},
    {"metal-CuZn-k", {1.81575f, 1.79982996f, 1.85870004f, 2.35800004f, 2.72716975f, 3.13499975f, 3.54636002f, 4.10839987f, 4.74546957f, 5.11119986f}},
    {"metal-MgO-eta", {1.77271163f, 1.76102662f, 1.7515707f, 1.74432087f, 1.74077654f, 1.73750091f, 1.7346046f, 1.73136091f, 1.72871995f, 1.72871995f}},
    {"metal-MgO-k", {6.45152056e-07f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f}},
    {"metal-TiO2-eta", {3.8359766f, 3.33697104f, 3.14581633f, 3.01497698f, 2.96082401f, 2.91236782f, 2.87360191f, 2.82987761f, 2.79932809f, 2.78523684f}},
    {"metal-TiO2-k", {0.228526697f, 0.00866648834f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f}},
    {"stdillum-A", {0.0648277402f, 0.159066886f, 0.353035092f, 0.654263139f, 0.893124759f, 1.18821311f, 1.51367736f, 1.96532845f, 2.39834023f, 2.5890677f}},
    {"stdillum-D50", {0.256993532f, 0.551344395f, 0.938197434f, 1.01083386f, 1.06050634f, 0.949372709f, 0.899121881f, 0.810921431f, 0.704077244f, 0.66778183f}},
    {"stdillum-D65", {0.485397995f, 0.878334463f, 1.18768549f, 1.09012055f, 1.05355072f, 0.914048016f, 0.843397498f, 0.724960089f, 0.641967237f, 0.608442843f}},
    {"stdillum-F1", {0.136509985f, 1.3600508f, 0.871473908f, 0.863589883f, 1.85334206f, 1.10840285f, 0.47893849f, 0.0937320068f, 0.0313899964f, 0.0313899964f}},
    {"stdillum-F2", {0.0861459896f, 1.09179306f, 0.507823288f, 0.51468581f, 1.68402565f, 1.38435173f, 0.569089353f, 0.0798237771f, 0.0197113734f, 0.0197113734f}},
    {"stdillum-F3", {0.059869267f, 0.996796131f, 0.325265348f, 0.337312192f, 1.61577201f, 1.54191136f, 0.64363867f, 0.0790128559f, 0.0153323729f, 0.0153323729f}},
    {"stdillum-F4", {0.0416147374f, 0.952439308f, 0.20654051f, 0.219755024f, 1.52911794f, 1.68672585f, 0.740333796f, 0.0854927599f, 0.0138715794f, 0.0138715794f}},
    {"stdillum-F5", {0.13650091f, 1.31985676f, 0.835283339f, 0.82703495f, 1.86641634f, 1.09492743f, 0.436014712f, 0.0821341425f, 0.0291980561f, 0.0291980561f}},
    {"stdillum-F6", {0.0766644776f, 1.02939427f, 0.441879451f, 0.451955378f, 1.71676135f, 1.38492596f, 0.522194803f, 0.0660044849f, 0.0153328953f, 0.0153328953f}},
    {"stdillum-F7", {0.186861858f, 1.35597718f, 0.921900511f, 0.954747319f, 1.9545064f, 0.930426121f, 0.771505952f, 0.299198002f, 0.0591242611f, 0.0591242611f}},
    {"stdillum-F8", {0.0883210823f, 0.911343992f, 0.696203709f, 0.916057527f, 1.91394413f, 0.907940686f, 1.03486037f, 0.487371892f, 0.096350275f, 0.096350275f}},
    {"stdillum-F9", {0.0657017231f, 0.88970536f, 0.533716977f, 0.732939184f, 1.83947694f, 1.06597388f, 1.06763852f, 0.415512353f, 0.0817621425f, 0.0817621425f}},
    {"stdillum-F10", {0.080955863f, 0.840134144f, 0.774113059f, 0.171393037f, 4.73136711f, 0.978939652f, 0.518527091f, 0.0926831365f, 0.00656398945f, 0.00656398945f}},
    {"stdillum-F11", {0.0664308071f, 0.875764489f, 0.51684624f, 0.107311301f, 4.67129707f, 1.00043404f, 0.602696598f, 0.110595852f, 0.00657007983f, 0.00657007983f}},
    {"stdillum-F12", {0.0700803772f, 0.861596406f, 0.192283034f, 0.0671603605f, 4.19736004f, 1.07850814f, 0.736575425f, 0.132553503f, 0.00365001964f, 0.00365001964f}},
    {"illum-acesD60", {0.400835574f, 0.77028209f, 1.10322618f, 1.05907261f, 1.04942f, 0.928472459f, 0.879832864f, 0.77625221f, 0.681254447f, 0.645451903f}},
};

TEST(SpectraNamed, EveryTableIsPbrtV4s) {
    for (const NamedReference &r : kPbrtV4Named) {
        pstd::optional<Spectrum> s = GetNamedSpectrum(r.name);
        ASSERT_TRUE(s.has_value()) << r.name;
        for (int i = 0; i < 10; ++i)
            EXPECT_NEAR((*s)(kNamedLambdas[i]), r.values[i], 2e-6f * r.values[i])
                << r.name << " at " << kNamedLambdas[i] << " nm";
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

// The table of whole-nm starting segments finds the segment the bisection finds: every value is
// the interpolation between the nodes around lambda, to the bit, for nodes at fractional and
// uneven wavelengths (as measured metal data has), at and between nodes and whole nm; a NaN
// wavelength is outside the range (0), not an index into the table.
TEST(SpectraRange, PiecewiseLinearLookupIsTheInterpolationBetweenItsNodes) {
    std::vector<Float> lambdas = {358.7f, 360.0f, 360.4f, 361.3f, 365.0f, 400.05f, 400.95f, 401.0f,
                                  520.5f, 700.0f, 829.99f, 831.2f};
    std::vector<Float> values(lambdas.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = Float(i % 3) + 0.1f * Float(i);
    Spectrum s = Spectrum::PiecewiseLinear(lambdas, values);
    std::vector<Float> probes(lambdas);
    for (Float lambda = 358.7f; lambda <= 831.2f; lambda += 0.05f) probes.push_back(lambda);
    for (Float lambda : probes) {
        size_t i = size_t(std::upper_bound(lambdas.begin(), lambdas.end(), lambda) - lambdas.begin()) - 1;
        Float expected = i + 1 == lambdas.size()
                             ? values.back()
                             : Lerp((lambda - lambdas[i]) / (lambdas[i + 1] - lambdas[i]), values[i], values[i + 1]);
        ASSERT_EQ(s(lambda), expected) << lambda;
    }
    EXPECT_EQ(s(std::numeric_limits<Float>::quiet_NaN()), 0);
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
    EXPECT_EQ(convert(Named("metal-Pt-eta"), SpectrumType::Unbounded),
              "scene.pbrt:3:7: error: unknown named spectrum \"metal-Pt-eta\", expected one of glass-BK7, "
              "glass-BAF10, glass-FK51A, glass-LASF9, glass-F5, glass-F10, glass-F11, metal-Ag-eta, "
              "metal-Ag-k, metal-Al-eta, metal-Al-k, metal-Au-eta, metal-Au-k, metal-Cu-eta, metal-Cu-k, "
              "metal-CuZn-eta, metal-CuZn-k, metal-MgO-eta, metal-MgO-k, metal-TiO2-eta, metal-TiO2-k, "
              "stdillum-A, stdillum-D50, stdillum-D65, stdillum-F1, stdillum-F2, stdillum-F3, "
              "stdillum-F4, stdillum-F5, stdillum-F6, stdillum-F7, stdillum-F8, stdillum-F9, "
              "stdillum-F10, stdillum-F11, stdillum-F12, illum-acesD60" +
                  sensors + " or a spectrum file");
    EXPECT_EQ(convert(BlackbodyParam(-5), SpectrumType::Illuminant),
              "scene.pbrt:3:7: error: blackbody needs one temperature, expected a positive value in kelvin");
}

}  // namespace
}  // namespace pbrt
