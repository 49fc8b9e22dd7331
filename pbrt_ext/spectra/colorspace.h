// pbrt_ext: RGB colour spaces (pbrt-v4's util/colorspace.h, host side): sRGB, DCI-P3, Rec. 2020
// and ACES2065-1, as pbrt-v4 has them.
//
// A colour space is three primaries and a white, given as xy chromaticities, plus the spectrum of
// its illuminant, which fixes the white: w is the chromaticity of that spectrum, as pbrt-v4
// computes it, not a rounded published value. XYZFromRGB maps RGB (1, 1, 1) to the XYZ of the
// illuminant (Y = 1 for a luminance-1 illuminant, as all of pbrt-v4's are). An RGB reflectance in the space becomes a spectrum through the space's
// RGBToSpectrumTable, which was fitted under the same illuminant.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/spectra/rgbtospectrumtable.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/squarematrix.h"

#include <string>
#include <string_view>

namespace pbrt {

class RGBColorSpace {
  public:
    // Throws std::invalid_argument when the primaries are degenerate (collinear) or the
    // illuminant is black.
    RGBColorSpace(Chromaticity r, Chromaticity g, Chromaticity b, const Spectrum &illuminant,
                  const RGBToSpectrumTable *rgbToSpectrumTable);

    // The sigmoid polynomial of a reflectance rgb (components clamped to [0, 1]).
    RGBSigmoidPolynomial ToRGBCoeffs(RGB rgb) const;

    RGB ToRGB(XYZ xyz) const { return Mul<RGB>(RGBFromXYZ, xyz); }
    XYZ ToXYZ(RGB rgb) const { return Mul<XYZ>(XYZFromRGB, rgb); }
    // The Y row of XYZFromRGB: luminance = Dot(LuminanceVector(), rgb).
    RGB LuminanceVector() const { return RGB(XYZFromRGB[1][0], XYZFromRGB[1][1], XYZFromRGB[1][2]); }

    // Rec. ITU-R BT.709 primaries with pbrt-v4's "stdillum-D65" (luminance 1) as illuminant.
    static const RGBColorSpace &sRGB();
    // DCI-P3's primaries and Rec. ITU-R BT.2020's, both under "stdillum-D65" (pbrt-v4's DCI-P3
    // has D65 as white, not DCI's own); ACES2065-1 (AP0 primaries) under "illum-acesD60".
    static const RGBColorSpace &DCI_P3();
    static const RGBColorSpace &Rec2020();
    static const RGBColorSpace &ACES2065_1();
    // By pbrt-v4's names, case-insensitive: "srgb", "dci-p3", "rec2020", "aces2065-1"; null for
    // anything else.
    static const RGBColorSpace *GetNamed(std::string_view name);
    // The names GetNamed knows, quoted, for error messages.
    static std::string NamesList();
    // The named space whose primaries and white are the given ones, each coordinate within a
    // relative 1e-3 (pbrt-v4's Lookup, for an EXR's chromaticities); null if none is.
    static const RGBColorSpace *Lookup(Chromaticity r, Chromaticity g, Chromaticity b,
                                       Chromaticity w);

    bool operator==(const RGBColorSpace &cs) const;
    bool operator!=(const RGBColorSpace &cs) const { return !(*this == cs); }

    std::string ToString() const;
    // pbrt-v4's name of the space ("srgb", ...), "custom" for one built by hand.
    std::string_view Name() const;

    Chromaticity r, g, b, w;
    DenselySampledSpectrum illuminant;
    SquareMatrix<3> XYZFromRGB, RGBFromXYZ;

  private:
    const RGBToSpectrumTable *rgbToSpectrumTable;
};

// The matrix from linear RGB in `from` to linear RGB in `to` (identity when they are one space).
SquareMatrix<3> ConvertRGBColorSpace(const RGBColorSpace &from, const RGBColorSpace &to);

}  // namespace pbrt
