// pbrt-v4's named spectra (src/pbrt/util/spectrum.cpp's GetNamedSpectrum), from cited data:
// optical glasses by their Sellmeier fits, metals' complex indices, the CIE standard
// illuminants, and camera sensor responses (pbrt_ext/sensordata.cpp).
#include "pbrt_ext/sensordata.h"
#include "pbrt_ext/spectrum.h"
#include "pbrt_ext/util/ciedata.h"

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pbrt {

namespace {

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
pstd::optional<Spectrum> NamedMetalSpectrum(std::string_view name) {
    for (const NamedMetal &m : kMetals)
        for (bool eta : {true, false}) {
            std::string full = "metal-" + std::string(m.name) + (eta ? "-eta" : "-k");
            if (name != full) continue;
            std::vector<Float> interleaved;
            for (const NKSample &s : m.samples) {
                interleaved.push_back(s.lambda);
                interleaved.push_back(eta ? s.n : s.k);
            }
            return Spectrum::PiecewiseLinear(interleaved, false);
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

// An illuminant tabulated at every nm and scaled to luminance 1, as pbrt-v4 normalizes its
// named illuminants.
template <typename F>
Spectrum UnitLuminanceIlluminant(F f) {
    std::vector<Float> interleaved;
    for (int lambda = int(Lambda_min); lambda <= int(Lambda_max); ++lambda) {
        interleaved.push_back(Float(lambda));
        interleaved.push_back(f(Float(lambda)));
    }
    return Spectrum::DenselySampled(Spectrum::PiecewiseLinear(interleaved, true));
}

}  // namespace

std::string NamedSpectrumNames() {
    std::string s;
    for (const SellmeierGlass &g : kGlasses) s += std::string(g.name) + ", ";
    for (const NamedMetal &m : kMetals)
        s += "metal-" + std::string(m.name) + "-eta, metal-" + std::string(m.name) + "-k, ";
    return s + "stdillum-A, stdillum-D65, " + SensorNames();
}

pstd::optional<Spectrum> GetNamedSpectrum(std::string_view name) {
    for (const SellmeierGlass &g : kGlasses)
        if (name == g.name) {
            auto ior = std::make_shared<DenselySampledSpectrum>();
            for (int lambda = ior->lambdaMin; lambda <= ior->lambdaMax; ++lambda)
                ior->values.push_back(SellmeierIOR(g, Float(lambda)));
            return Spectrum(std::shared_ptr<const DenselySampledSpectrum>(std::move(ior)));
        }
    if (pstd::optional<Spectrum> metal = NamedMetalSpectrum(name)) return metal;
    if (name == "stdillum-D65") {
        static const Spectrum d65 = UnitLuminanceIlluminant([](Float l) { return Float(CIEAt(l).d65); });
        return d65;
    }
    if (name == "stdillum-A") {
        static const Spectrum a = UnitLuminanceIlluminant(IlluminantA);
        return a;
    }
    return GetSensorResponse(name);
}

}  // namespace pbrt
