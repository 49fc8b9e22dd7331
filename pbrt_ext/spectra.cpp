#include "pbrt_ext/spectra.h"

#include "pbrt_ext/paramdict.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <span>
#include <sstream>
#include <string_view>
#include <vector>

namespace pbrt {

namespace {

// ---- The observer and the white --------------------------------------------------------------

// CIE 1931 2-degree colour matching functions (xbar, ybar, zbar) and CIE standard illuminant D65
// (relative, 100 at 560 nm), 380-780 nm every 5 nm: the CIE data tables
// https://cie.co.at/datatable/cie-1931-colour-matching-functions-2-degree-observer and
// https://cie.co.at/datatable/cie-standard-illuminant-d65 (CIE 015:2018), transcribed from the
// copy in aschet/olfarve, py/olfarve.py.
struct CIESample {
    float x, y, z, d65;
};
constexpr float kCIELambdaMin = 380, kCIELambdaStep = 5;
constexpr CIESample kCIE[] = {
    {0.001368, 3.9e-05, 0.006450001, 49.9755},  // 380 nm
    {0.002236, 6.4e-05, 0.01054999, 52.3118},
    {0.004243, 0.00012, 0.02005001, 54.6482},
    {0.00765, 0.000217, 0.03621, 68.7015},
    {0.01431, 0.000396, 0.06785001, 82.7549},
    {0.02319, 0.00064, 0.1102, 87.1204},
    {0.04351, 0.00121, 0.2074, 91.486},
    {0.07763, 0.00218, 0.3713, 92.4589},
    {0.13438, 0.004, 0.6456, 93.4318},
    {0.21477, 0.0073, 1.03905, 90.057},
    {0.2839, 0.0116, 1.3856, 86.6823},  // 430 nm
    {0.3285, 0.01684, 1.62296, 95.7736},
    {0.34828, 0.023, 1.74706, 104.865},
    {0.34806, 0.0298, 1.7826, 110.936},
    {0.3362, 0.038, 1.77211, 117.008},
    {0.3187, 0.048, 1.7441, 117.41},
    {0.2908, 0.06, 1.6692, 117.812},
    {0.2511, 0.0739, 1.5281, 116.336},
    {0.19536, 0.09098, 1.28764, 114.861},
    {0.1421, 0.1126, 1.0419, 115.392},
    {0.09564, 0.13902, 0.8129501, 115.923},  // 480 nm
    {0.05795001, 0.1693, 0.6162, 112.367},
    {0.03201, 0.20802, 0.46518, 108.811},
    {0.0147, 0.2586, 0.3533, 109.082},
    {0.0049, 0.323, 0.272, 109.354},
    {0.0024, 0.4073, 0.2123, 108.578},
    {0.0093, 0.503, 0.1582, 107.802},
    {0.0291, 0.6082, 0.1117, 106.296},
    {0.06327, 0.71, 0.07824999, 104.79},
    {0.1096, 0.7932, 0.05725001, 106.239},
    {0.1655, 0.862, 0.04216, 107.689},  // 530 nm
    {0.2257499, 0.9148501, 0.02984, 106.047},
    {0.2904, 0.954, 0.0203, 104.405},
    {0.3597, 0.9803, 0.0134, 104.225},
    {0.4334499, 0.9949501, 0.008749999, 104.046},
    {0.5120501, 1, 0.005749999, 102.023},
    {0.5945, 0.995, 0.0039, 100},
    {0.6784, 0.9786, 0.002749999, 98.1671},
    {0.7621, 0.952, 0.0021, 96.3342},
    {0.8425, 0.9154, 0.0018, 96.0611},
    {0.9163, 0.87, 0.001650001, 95.788},  // 580 nm
    {0.9786, 0.8163, 0.0014, 92.2368},
    {1.0263, 0.757, 0.0011, 88.6856},
    {1.0567, 0.6949, 0.001, 89.3459},
    {1.0622, 0.631, 0.0008, 90.0062},
    {1.0456, 0.5668, 0.0006, 89.8026},
    {1.0026, 0.503, 0.00034, 89.5991},
    {0.9384, 0.4412, 0.00024, 88.6489},
    {0.8544499, 0.381, 0.00019, 87.6987},
    {0.7514, 0.321, 0.0001, 85.4936},
    {0.6424, 0.265, 4.999999e-05, 83.2886},  // 630 nm
    {0.5419, 0.217, 3e-05, 83.4939},
    {0.4479, 0.175, 2e-05, 83.6992},
    {0.3608, 0.1382, 1e-05, 81.863},
    {0.2835, 0.107, 0, 80.0268},
    {0.2187, 0.0816, 0, 80.1207},
    {0.1649, 0.061, 0, 80.2146},
    {0.1212, 0.04458, 0, 81.2462},
    {0.0874, 0.032, 0, 82.2778},
    {0.0636, 0.0232, 0, 80.281},
    {0.04677, 0.017, 0, 78.2842},  // 680 nm
    {0.0329, 0.01192, 0, 74.0027},
    {0.0227, 0.00821, 0, 69.7213},
    {0.01584, 0.005723, 0, 70.6652},
    {0.01135916, 0.004102, 0, 71.6091},
    {0.008110916, 0.002929, 0, 72.979},
    {0.005790346, 0.002091, 0, 74.349},
    {0.004109457, 0.001484, 0, 67.9765},
    {0.002899327, 0.001047, 0, 61.604},
    {0.00204919, 0.00074, 0, 65.7448},
    {0.001439971, 0.00052, 0, 69.8856},  // 730 nm
    {0.0009999493, 0.0003611, 0, 72.4863},
    {0.0006900786, 0.0002492, 0, 75.087},
    {0.0004760213, 0.0001719, 0, 69.3398},
    {0.0003323011, 0.00012, 0, 63.5927},
    {0.0002348261, 8.48e-05, 0, 55.0054},
    {0.0001661505, 6e-05, 0, 46.4182},
    {0.000117413, 4.24e-05, 0, 56.6118},
    {8.307527e-05, 3e-05, 0, 66.8054},
    {5.870652e-05, 2.12e-05, 0, 65.0941},
    {4.150994e-05, 1.499e-05, 0, 63.3828},  // 780 nm
};
constexpr int kCIESamples = int(std::size(kCIE));
static_assert(kCIESamples == 81);

// The table linearly interpolated at lambda; zero outside it.
CIESample CIEAt(Float lambda) {
    Float t = (lambda - kCIELambdaMin) / kCIELambdaStep;
    if (!(t >= 0) || t > kCIESamples - 1) return {0, 0, 0, 0};
    int i = std::min(int(t), kCIESamples - 2);
    Float f = t - i;
    const CIESample &a = kCIE[i], &b = kCIE[i + 1];
    return {Lerp(f, a.x, b.x), Lerp(f, a.y, b.y), Lerp(f, a.z, b.z), Lerp(f, a.d65, b.d65)};
}

struct XYZ {
    double x = 0, y = 0, z = 0;
};

using SpectrumFunction = std::function<Float(Float lambda)>;

// Integrates s (times D65 when underD65) against the matching functions at 1 nm steps over the
// table's range, normalized so that the light itself (D65, or a constant 1) has Y = 1.
XYZ Integrate(const SpectrumFunction &s, bool underD65) {
    XYZ xyz;
    double norm = 0;
    for (int lambda = 380; lambda <= 780; ++lambda) {
        CIESample c = CIEAt(Float(lambda));
        double light = underD65 ? c.d65 : 1;
        double v = s(Float(lambda)) * light;
        xyz.x += v * c.x;
        xyz.y += v * c.y;
        xyz.z += v * c.z;
        norm += light * c.y;
    }
    xyz.x /= norm;
    xyz.y /= norm;
    xyz.z /= norm;
    return xyz;
}

// XYZ to linear sRGB (IEC 61966-2-1 primaries, D65 white).
SampledSpectrum XYZToLinearSRGB(const XYZ &c) {
    return SampledSpectrum(Float(3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z),
                           Float(-0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z),
                           Float(0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z));
}

// The tabulated D65 through the rounded standard matrix lands a few 1e-4 off (1, 1, 1); dividing
// by it makes the white exact, so that white light and white surfaces stay neutral.
const SampledSpectrum &WhiteCorrection() {
    static const SampledSpectrum white =
        XYZToLinearSRGB(Integrate([](Float) { return Float(1); }, true));
    return white;
}

SampledSpectrum ToRGB(const SpectrumFunction &s, SpectrumKind kind) {
    bool underD65 = kind != SpectrumKind::Illuminant;
    SampledSpectrum rgb = XYZToLinearSRGB(Integrate(s, underD65)) / WhiteCorrection();
    if (kind == SpectrumKind::Reflectance) return Clamp(rgb, Float(0), Float(1));
    return ClampZero(rgb);
}

// ---- Tabulated and analytic spectra ----------------------------------------------------------

// pbrt-v4's PiecewiseLinearSpectrum: linear between samples, zero outside them.
Float PiecewiseLinear(std::span<const Float> lambdas, std::span<const Float> values, Float lambda) {
    if (lambdas.empty() || lambda < lambdas.front() || lambda > lambdas.back()) return 0;
    size_t i = std::upper_bound(lambdas.begin(), lambdas.end(), lambda) - lambdas.begin();
    if (i >= lambdas.size()) return values.back();
    Float t = (lambda - lambdas[i - 1]) / (lambdas[i] - lambdas[i - 1]);
    return Lerp(t, values[i - 1], values[i]);
}

struct Tabulated {
    std::vector<Float> lambdas, values;
    Float operator()(Float lambda) const { return PiecewiseLinear(lambdas, values, lambda); }
};

// (lambda, value) pairs with strictly increasing wavelengths; `what` names their origin.
Tabulated FromPairs(std::span<const double> pairs, const FileLoc &loc, const std::string &what) {
    if (pairs.empty() || pairs.size() % 2 != 0)
        throw ParseError(loc, what + " has " + std::to_string(pairs.size()) +
                                  " values, expected (wavelength, value) pairs");
    Tabulated t;
    for (size_t i = 0; i < pairs.size(); i += 2) {
        if (!t.lambdas.empty() && pairs[i] <= t.lambdas.back()) {
            std::ostringstream msg;
            msg << what << ": wavelength " << pairs[i] << " after " << t.lambdas.back()
                << ", expected increasing wavelengths";
            throw ParseError(loc, msg.str());
        }
        t.lambdas.push_back(Float(pairs[i]));
        t.values.push_back(Float(pairs[i + 1]));
    }
    return t;
}

// A .spd file: whitespace-separated numbers, '#' comments to the end of a line (pbrt-v4's
// ReadFloatFile), read as (lambda, value) pairs.
Tabulated ReadSpectrumFile(const SpectrumParam &param, const std::string &baseDir) {
    std::filesystem::path path(param.name);
    if (path.is_relative() && !baseDir.empty()) path = std::filesystem::path(baseDir) / path;
    std::string what = "spectrum file \"" + path.string() + "\"";
    std::optional<uint64_t> size = RegularFileSize(path.string(), nullptr);
    std::ifstream in;
    if (size) in.open(path);  // never a device or pipe, which may never end
    if (!in.is_open()) throw ParseError(param.loc, what + " cannot be read, expected a file of (wavelength, value) pairs");
    CheckMemory(param.loc, "parsing " + what, SaturatingProduct({*size, kParsedTextBytesPerByte}));
    std::vector<double> numbers;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        std::istringstream tokens(line.substr(0, line.find('#')));
        std::string token;
        while (tokens >> token) {
            char *end = nullptr;
            double v = std::strtod(token.c_str(), &end);
            if (*end != '\0' || !std::isfinite(v))
                throw ParseError(param.loc, what + " line " + std::to_string(lineNo) + ": \"" +
                                                token + "\" is not a number, expected (wavelength, value) pairs");
            numbers.push_back(v);
        }
    }
    return FromPairs(numbers, param.loc, what);
}

// pbrt-v4's BlackbodySpectrum: Planck's law scaled to peak 1 (at Wien's displacement).
Float NormalizedBlackbody(Float lambda, Float T) {
    Float lambdaMax = Float(2.8977721e-3 / T * 1e9);
    return Blackbody(lambda, T) / Blackbody(lambdaMax, T);
}

// ---- Named spectra ---------------------------------------------------------------------------

// Three-term Sellmeier coefficients (wavelength in micrometres) from the SCHOTT optical glass
// data sheets (SCHOTT AG, "Optical Glass - Data Sheets", 2015 catalog); pbrt-v4's glass-F5,
// -F10, -F11 are the dense flints SF5, SF10, SF11 (here N-SF5, N-SF10, N-SF11).
struct SellmeierGlass {
    std::string_view name;
    double B[3], C[3];
};
constexpr SellmeierGlass kGlasses[] = {
    {"glass-BK7", {1.03961212, 0.231792344, 1.01046945}, {0.00600069867, 0.0200179144, 103.560653}},
    {"glass-BAF10", {1.5851495, 0.143559385, 1.08521269}, {0.00926681282, 0.0424489805, 105.613573}},
    {"glass-FK51A", {0.971247817, 0.216901417, 0.904651666}, {0.00472301995, 0.0153575612, 168.68133}},
    {"glass-LASF9", {2.00029547, 0.298926886, 1.80691843}, {0.0121426017, 0.0538736236, 156.530829}},
    {"glass-F5", {1.52481889, 0.187085527, 1.42729015}, {0.011254756, 0.0588995392, 129.141675}},
    {"glass-F10", {1.62153902, 0.256287842, 1.64447552}, {0.0122241457, 0.0595736775, 147.468793}},
    {"glass-F11", {1.73759695, 0.313747346, 1.89878101}, {0.013188707, 0.0623068142, 155.23629}},
};

Float SellmeierIOR(const SellmeierGlass &g, Float lambda) {
    double l2 = Sqr(lambda * 1e-3), n2 = 1;
    for (int i = 0; i < 3; ++i) n2 += g.B[i] * l2 / (l2 - g.C[i]);
    return Float(std::sqrt(std::max(n2, 1.0)));
}

// Metal eta and k, tabulated from data/spectra/metal-*.nk (see the sources named there) by
// data/spectra/nk_to_table.py: wavelength (nm), n, k.
struct NKSample {
    float lambda, n, k;
};
// metal-Ag.nk
constexpr NKSample kAg[] = {
    {292.4, 1.39, 1.161},
    {300.9, 1.34, 0.964},
    {310.7, 1.13, 0.616},
    {320.4, 0.81, 0.392},
    {331.5, 0.17, 0.829},
    {342.5, 0.14, 1.142},
    {354.2, 0.1, 1.419},
    {367.9, 0.07, 1.657},
    {381.5, 0.05, 1.864},
    {397.4, 0.05, 2.07},
    {413.3, 0.05, 2.275},
    {430.5, 0.04, 2.462},
    {450.9, 0.04, 2.657},
    {471.4, 0.05, 2.869},
    {495.9, 0.05, 3.093},
    {520.9, 0.05, 3.324},
    {548.6, 0.06, 3.586},
    {582.1, 0.05, 3.858},
    {616.8, 0.06, 4.152},
    {659.5, 0.05, 4.483},
    {704.5, 0.04, 4.838},
    {756, 0.03, 5.242},
    {821.1, 0.04, 5.727},
    {892, 0.04, 6.312},
    {984, 0.04, 6.992},
};
// metal-Al.nk
constexpr NKSample kAl[] = {
    {247.97, 0.18137, 2.9029},
    {309.96, 0.28003, 3.7081},
    {326.28, 0.31474, 3.9165},
    {364.66, 0.39877, 4.3957},
    {413.28, 0.52135, 5.0008},
    {442.8, 0.6079, 5.3676},
    {476.87, 0.7278, 5.7781},
    {516.6, 0.8734, 6.2418},
    {563.57, 1.0728, 6.7839},
    {619.93, 1.366, 7.4052},
    {652.25, 1.5724, 7.7354},
    {688.81, 1.8301, 8.0601},
    {729.32, 2.1606, 8.3565},
    {774.91, 2.6154, 8.4914},
    {794.78, 2.7675, 8.3866},
    {815.69, 2.7668, 8.2573},
    {837.74, 2.6945, 8.1878},
    {885.61, 2.2802, 8.1134},
    {911.66, 1.9739, 8.3058},
};
// metal-Au.nk
constexpr NKSample kAu[] = {
    {292.4, 1.49, 1.878},
    {300.9, 1.53, 1.889},
    {310.7, 1.53, 1.893},
    {320.4, 1.54, 1.898},
    {331.5, 1.48, 1.883},
    {342.5, 1.48, 1.871},
    {354.2, 1.5, 1.866},
    {367.9, 1.48, 1.895},
    {381.5, 1.46, 1.933},
    {397.4, 1.47, 1.952},
    {413.3, 1.46, 1.958},
    {430.5, 1.45, 1.948},
    {450.9, 1.38, 1.914},
    {471.4, 1.31, 1.849},
    {495.9, 1.04, 1.833},
    {520.9, 0.62, 2.081},
    {548.6, 0.43, 2.455},
    {582.1, 0.29, 2.863},
    {616.8, 0.21, 3.272},
    {659.5, 0.14, 3.697},
    {704.5, 0.13, 4.103},
    {756, 0.14, 4.542},
    {821.1, 0.16, 5.083},
    {892, 0.17, 5.663},
    {984, 0.22, 6.35},
};
// metal-Cu.nk
constexpr NKSample kCu[] = {
    {292.4, 1.42, 1.633},
    {300.9, 1.4, 1.679},
    {310.7, 1.38, 1.729},
    {320.4, 1.38, 1.783},
    {331.5, 1.34, 1.821},
    {342.5, 1.36, 1.864},
    {354.2, 1.37, 1.916},
    {367.9, 1.36, 1.975},
    {381.5, 1.33, 2.045},
    {397.4, 1.32, 2.116},
    {413.3, 1.28, 2.207},
    {430.5, 1.25, 2.305},
    {450.9, 1.24, 2.397},
    {471.4, 1.25, 2.483},
    {495.9, 1.22, 2.564},
    {520.9, 1.18, 2.608},
    {548.6, 1.02, 2.577},
    {582.1, 0.7, 2.704},
    {616.8, 0.3, 3.205},
    {659.5, 0.22, 3.747},
    {704.5, 0.21, 4.205},
    {756, 0.24, 4.665},
    {821.1, 0.26, 5.18},
    {892, 0.3, 5.768},
    {984, 0.32, 6.421},
};
// metal-CuZn.nk
constexpr NKSample kCuZn[] = {
    {300, 1.388, 1.731},
    {310, 1.419, 1.764},
    {320, 1.446, 1.789},
    {330, 1.473, 1.807},
    {340, 1.494, 1.815},
    {350, 1.504, 1.815},
    {360, 1.503, 1.815},
    {370, 1.497, 1.818},
    {380, 1.487, 1.818},
    {390, 1.471, 1.813},
    {400, 1.445, 1.805},
    {410, 1.405, 1.794},
    {420, 1.35, 1.786},
    {430, 1.278, 1.784},
    {440, 1.191, 1.797},
    {450, 1.094, 1.829},
    {460, 0.994, 1.883},
    {470, 0.9, 1.957},
    {480, 0.816, 2.046},
    {490, 0.745, 2.145},
    {500, 0.686, 2.25},
    {510, 0.639, 2.358},
    {520, 0.602, 2.464},
    {530, 0.573, 2.568},
    {540, 0.549, 2.668},
    {550, 0.527, 2.765},
    {560, 0.505, 2.86},
    {570, 0.484, 2.958},
    {580, 0.468, 3.059},
    {590, 0.46, 3.159},
    {600, 0.45, 3.253},
    {610, 0.452, 3.345},
    {620, 0.449, 3.434},
    {630, 0.445, 3.522},
    {640, 0.444, 3.609},
    {650, 0.444, 3.695},
    {660, 0.445, 3.778},
    {670, 0.444, 3.86},
    {680, 0.444, 3.943},
    {690, 0.445, 4.025},
    {700, 0.446, 4.106},
    {710, 0.448, 4.186},
    {720, 0.45, 4.266},
    {730, 0.452, 4.346},
    {740, 0.455, 4.424},
    {750, 0.457, 4.501},
    {760, 0.458, 4.579},
    {770, 0.46, 4.657},
    {780, 0.464, 4.737},
    {790, 0.469, 4.814},
    {800, 0.473, 4.89},
    {810, 0.478, 4.965},
    {820, 0.481, 5.039},
    {830, 0.483, 5.115},
    {840, 0.486, 5.192},
    {850, 0.49, 5.269},
    {860, 0.494, 5.346},
    {870, 0.5, 5.423},
    {880, 0.507, 5.5},
    {890, 0.515, 5.575},
    {900, 0.523, 5.65},
};

struct NamedMetal {
    std::string_view name;
    std::span<const NKSample> samples;
};
const NamedMetal kMetals[] = {{"Ag", kAg}, {"Al", kAl}, {"Au", kAu}, {"Cu", kCu}, {"CuZn", kCuZn}};

// "metal-<name>-eta" or "metal-<name>-k" as a tabulated spectrum.
pstd::optional<Tabulated> NamedMetalSpectrum(std::string_view name) {
    for (const NamedMetal &m : kMetals)
        for (bool eta : {true, false}) {
            std::string full = "metal-" + std::string(m.name) + (eta ? "-eta" : "-k");
            if (name != full) continue;
            Tabulated t;
            for (const NKSample &s : m.samples) {
                t.lambdas.push_back(s.lambda);
                t.values.push_back(eta ? s.n : s.k);
            }
            return t;
        }
    return {};
}

// CIE standard illuminant A: Planck's law at 2856 K in the CIE's closed form (CIE 015:2018),
// 100 at 560 nm.
Float IlluminantA(Float lambda) {
    constexpr double c2 = 1.435e7, T = 2848;  // c2 in nm K; the CIE's T for the 1968 c2
    return Float(100 * std::pow(560.0 / lambda, 5) * std::expm1(c2 / (T * 560)) /
                 std::expm1(c2 / (T * lambda)));
}

std::string AvailableNames() {
    std::string s;
    for (const SellmeierGlass &g : kGlasses) s += std::string(g.name) + ", ";
    for (const NamedMetal &m : kMetals)
        s += "metal-" + std::string(m.name) + "-eta, metal-" + std::string(m.name) + "-k, ";
    return s + "stdillum-A, stdillum-D65";
}

// A named spectrum; illuminants are scaled to luminance 1 as pbrt-v4 scales its named ones.
pstd::optional<SpectrumFunction> NamedSpectrum(const std::string &name) {
    for (const SellmeierGlass &g : kGlasses)
        if (name == g.name) return SpectrumFunction([&g](Float l) { return SellmeierIOR(g, l); });
    if (pstd::optional<Tabulated> metal = NamedMetalSpectrum(name)) return SpectrumFunction(*metal);
    auto unitLuminance = [](SpectrumFunction s) -> SpectrumFunction {
        Float y = Float(Integrate(s, false).y);
        return [s, y](Float l) { return s(l) / y; };
    };
    if (name == "stdillum-D65") return unitLuminance([](Float l) { return Float(CIEAt(l).d65); });
    if (name == "stdillum-A") return unitLuminance(IlluminantA);
    return {};
}

// The spectrum a non-RGB parameter describes. A Named parameter that names no built-in
// spectrum is read as a file, as pbrt-v4 does for any string-valued spectrum.
SpectrumFunction Describe(const SpectrumParam &param, const std::string &baseDir) {
    switch (param.kind) {
    case SpectrumParamKind::Blackbody: {
        if (param.values.size() != 1 || !(param.values[0] > 0))
            throw ParseError(param.loc, "blackbody needs one temperature, expected a positive value in kelvin");
        Float T = Float(param.values[0]);
        return [T](Float l) { return NormalizedBlackbody(l, T); };
    }
    case SpectrumParamKind::Samples:
        return FromPairs(param.values, param.loc, "spectrum");
    case SpectrumParamKind::Named:
        if (pstd::optional<SpectrumFunction> s = NamedSpectrum(param.name)) return *s;
        if (!std::filesystem::path(param.name).has_extension())
            throw ParseError(param.loc, "unknown named spectrum \"" + param.name +
                                            "\", expected one of " + AvailableNames() +
                                            " or a spectrum file");
        return ReadSpectrumFile(param, baseDir);
    case SpectrumParamKind::File:
        return ReadSpectrumFile(param, baseDir);
    default:
        throw ParseError(param.loc, "not a spectral description");
    }
}

// pbrt-v4's checks on an "rgb" value: no negative component, none above 1 for a reflectance.
SampledSpectrum CheckedRGB(const SpectrumParam &param, SpectrumKind kind) {
    if (param.values.size() != 3)
        throw ParseError(param.loc, "rgb has " + std::to_string(param.values.size()) +
                                        " values, expected 3");
    SampledSpectrum rgb(Float(param.values[0]), Float(param.values[1]), Float(param.values[2]));
    std::ostringstream values;
    values << "(" << rgb[0] << ", " << rgb[1] << ", " << rgb[2] << ")";
    if (rgb.MinComponentValue() < 0)
        throw ParseError(param.loc, "rgb " + values.str() + " has a negative component, expected values >= 0");
    if (kind == SpectrumKind::Reflectance && rgb.MaxComponentValue() > 1)
        throw ParseError(param.loc, "rgb reflectance " + values.str() +
                                        " has a component > 1, expected values in [0, 1]");
    return rgb;
}

}  // namespace

Float Blackbody(Float lambda, Float T) {
    if (T <= 0) return 0;
    constexpr double c = 299792458., h = 6.62606957e-34, kb = 1.3806488e-23;
    double l = lambda * 1e-9;
    return Float((2 * h * c * c) / (std::pow(l, 5) * std::expm1((h * c) / (l * kb * T))));
}

pstd::optional<Float> NamedGlassIOR(const std::string &name, Float lambda) {
    for (const SellmeierGlass &g : kGlasses)
        if (name == g.name) return SellmeierIOR(g, lambda);
    return {};
}

SampledSpectrum SpectrumToRGB(const SpectrumParam &param, SpectrumKind kind,
                              const std::string &baseDir) {
    if (param.kind == SpectrumParamKind::RGB) return CheckedRGB(param, kind);
    return ToRGB(Describe(param, baseDir), kind);
}

Float SpectrumToPhotometric(const SpectrumParam &param, const std::string &baseDir) {
    if (param.kind == SpectrumParamKind::RGB) return 1;
    return Float(Integrate(Describe(param, baseDir), false).y);
}

}  // namespace pbrt
