#include "pbrt_ext/spectra/colorspace.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pbrt {

namespace {

SquareMatrix<3> InvertOrThrow(const SquareMatrix<3> &m, const char *what) {
    pstd::optional<SquareMatrix<3>> inv = Inverse(m);
    if (!inv) throw std::invalid_argument(std::string("RGBColorSpace: ") + what);
    return *inv;
}

}  // namespace

RGBColorSpace::RGBColorSpace(Chromaticity r, Chromaticity g, Chromaticity b,
                             const Spectrum &illum, const RGBToSpectrumTable *rgbToSpectrumTable)
    : r(r), g(g), b(b), illuminant(DenselySample(illum)), rgbToSpectrumTable(rgbToSpectrumTable) {
    XYZ W = SpectrumToXYZ(illum);
    if (W.Y <= 0) throw std::invalid_argument("RGBColorSpace: the illuminant is black");
    w = W.xy();

    // Columns: the primaries' XYZ at Y = 1. Scaling column i by C[i] so that (1, 1, 1) maps to
    // W gives each primary the luminance that makes the three add up to the white.
    XYZ R = XYZ::FromxyY(r), G = XYZ::FromxyY(g), B = XYZ::FromxyY(b);
    SquareMatrix<3> primaries(R.X, G.X, B.X, R.Y, G.Y, B.Y, R.Z, G.Z, B.Z);
    XYZ C = InvertOrThrow(primaries, "the primaries are collinear") * W;
    XYZFromRGB = primaries * DiagonalMatrix(C.X, C.Y, C.Z);
    RGBFromXYZ = InvertOrThrow(XYZFromRGB, "the primaries are collinear");
}

RGBSigmoidPolynomial RGBColorSpace::ToRGBCoeffs(RGB rgb) const {
    return (*rgbToSpectrumTable)(RGB(std::max<Float>(rgb.r, 0), std::max<Float>(rgb.g, 0),
                                     std::max<Float>(rgb.b, 0)));
}

// The primaries are pbrt-v4's (spectra/colorspace.cpp), the same as cmd/rgb2spec_opt.h's kGamuts,
// which fitted each table under the same illuminant.
const RGBColorSpace &RGBColorSpace::sRGB() {
    static const RGBColorSpace cs({0.64f, 0.33f}, {0.3f, 0.6f}, {0.15f, 0.06f},
                                  GetNamedSpectrum("stdillum-D65").value(),
                                  &RGBToSpectrumTable::sRGB());
    return cs;
}

const RGBColorSpace &RGBColorSpace::DCI_P3() {
    static const RGBColorSpace cs({0.68f, 0.32f}, {0.265f, 0.69f}, {0.15f, 0.06f},
                                  GetNamedSpectrum("stdillum-D65").value(),
                                  &RGBToSpectrumTable::DCI_P3());
    return cs;
}

const RGBColorSpace &RGBColorSpace::Rec2020() {
    static const RGBColorSpace cs({0.708f, 0.292f}, {0.17f, 0.797f}, {0.131f, 0.046f},
                                  GetNamedSpectrum("stdillum-D65").value(),
                                  &RGBToSpectrumTable::Rec2020());
    return cs;
}

const RGBColorSpace &RGBColorSpace::ACES2065_1() {
    static const RGBColorSpace cs({0.7347f, 0.2653f}, {0.f, 1.f}, {0.0001f, -0.077f},
                                  GetNamedSpectrum("illum-acesD60").value(),
                                  &RGBToSpectrumTable::ACES2065_1());
    return cs;
}

namespace {

struct NamedColorSpace {
    std::string_view name;
    const RGBColorSpace &(*get)();
};
constexpr NamedColorSpace kNamedColorSpaces[] = {{"srgb", RGBColorSpace::sRGB},
                                                 {"dci-p3", RGBColorSpace::DCI_P3},
                                                 {"rec2020", RGBColorSpace::Rec2020},
                                                 {"aces2065-1", RGBColorSpace::ACES2065_1}};

}  // namespace

const RGBColorSpace *RGBColorSpace::GetNamed(std::string_view name) {
    std::string lower(name);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    for (const NamedColorSpace &n : kNamedColorSpaces)
        if (lower == n.name) return &n.get();
    return nullptr;
}

std::string_view RGBColorSpace::Name() const {
    for (const NamedColorSpace &n : kNamedColorSpaces)
        if (*this == n.get()) return n.name;
    return "custom";
}

std::string RGBColorSpace::NamesList() {
    std::string list;
    for (const NamedColorSpace &n : kNamedColorSpaces)
        list += (list.empty() ? "\"" : ", \"") + std::string(n.name) + "\"";
    return list;
}

const RGBColorSpace *RGBColorSpace::Lookup(Chromaticity r, Chromaticity g, Chromaticity b,
                                           Chromaticity w) {
    auto close = [](Float given, Float known) {
        return given == known || std::abs((given - known) / known) < 1e-3f;
    };
    auto same = [&](Chromaticity given, Chromaticity known) {
        return close(given.x, known.x) && close(given.y, known.y);
    };
    for (const NamedColorSpace &n : kNamedColorSpaces) {
        const RGBColorSpace &cs = n.get();
        if (same(r, cs.r) && same(g, cs.g) && same(b, cs.b) && same(w, cs.w))
            return &cs;
    }
    return nullptr;
}

bool RGBColorSpace::operator==(const RGBColorSpace &cs) const {
    auto same = [](Chromaticity a, Chromaticity b) { return a.x == b.x && a.y == b.y; };
    return same(r, cs.r) && same(g, cs.g) && same(b, cs.b) && same(w, cs.w) &&
           rgbToSpectrumTable == cs.rgbToSpectrumTable;
}

std::string RGBColorSpace::ToString() const {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "[ RGBColorSpace r: (%g, %g) g: (%g, %g) b: (%g, %g) w: (%g, %g) ]", r.x, r.y,
                  g.x, g.y, b.x, b.y, w.x, w.y);
    return buf;
}

SquareMatrix<3> ConvertRGBColorSpace(const RGBColorSpace &from, const RGBColorSpace &to) {
    if (from == to) return {};
    return to.RGBFromXYZ * from.XYZFromRGB;
}

}  // namespace pbrt
