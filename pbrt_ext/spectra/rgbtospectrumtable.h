// pbrt_ext: RGB -> spectrum upsampling (pbrt-v4's RGBToSpectrumTable, util/color.h).
//
// Jakob and Hanika, "A Low-Dimensional Function Space for Efficient Spectral Upsampling",
// Computer Graphics Forum 38(2), 2019. A reflectance RGB in [0, 1]^3 becomes the sigmoid
// polynomial (color.h) whose colour under the colour space's illuminant is that RGB, by
// trilinear interpolation in a table of precomputed coefficients. The table is optimized at
// build time by cmd/rgb2spec_opt (see cmd/rgb2spec_opt.h for the fit) and compiled into the
// library, one per colour space of pbrt-v4's.
//
// Table layout, as pbrt-v4's: coeffs[maxc][zi][yi][xi] holds (c0, c1, c2) for the RGB whose
// largest component maxc is zNodes[zi] and whose next two components (cyclically) are
// xi / (res - 1) and yi / (res - 1) times it. Each of the three sub-tables covers the colours
// where its component is the largest; dividing the other two by it makes the grid uniform in
// hue and saturation, and the brightness nodes crowd towards black.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/math.h"

#include <cmath>
#include <string>

namespace pbrt {

class RGBToSpectrumTable {
  public:
    static constexpr int res = 64;
    using CoefficientArray = float[3][res][res][res][3];

    RGBToSpectrumTable(const float *zNodes, const CoefficientArray *coeffs)
        : zNodes(zNodes), coeffs(coeffs) {}

    // The tables built into the library: linear sRGB, DCI-P3 and Rec. 2020 under D65, and
    // ACES2065-1 under ACES's D60 (cmd/rgb2spec_opt.h's kGamuts).
    static const RGBToSpectrumTable &sRGB();
    static const RGBToSpectrumTable &DCI_P3();
    static const RGBToSpectrumTable &Rec2020();
    static const RGBToSpectrumTable &ACES2065_1();

    // The spectrum for a reflectance rgb in [0, 1]^3 (components outside are clamped to it, NaN
    // to 0). A grey r = g = b is exactly the constant spectrum r (+-infinite coefficients for 0
    // and 1); any other rgb interpolates the table.
    PBRT_CPU_GPU RGBSigmoidPolynomial operator()(RGB rgb) const {
        for (int c = 0; c < 3; ++c) rgb[c] = rgb[c] > 0 ? std::min<Float>(rgb[c], 1) : 0;

        if (rgb.r == rgb.g && rgb.g == rgb.b) {
            // s(c2) = 0.5 + c2 / (2 sqrt(1 + c2^2)) = v for this c2.
            Float v = rgb.r;
            if (v == 0) return RGBSigmoidPolynomial(0, 0, -Infinity);
            if (v == 1) return RGBSigmoidPolynomial(0, 0, Infinity);
            return RGBSigmoidPolynomial(0, 0, (v - Float(0.5)) / std::sqrt(v * (1 - v)));
        }

        // The largest component selects the sub-table (ties as pbrt-v4 breaks them); z > 0.
        int maxc = rgb.r > rgb.g ? (rgb.r > rgb.b ? 0 : 2) : (rgb.g > rgb.b ? 1 : 2);
        Float z = rgb[maxc];
        Float x = rgb[(maxc + 1) % 3] * (res - 1) / z;
        Float y = rgb[(maxc + 2) % 3] * (res - 1) / z;

        int xi = std::min(int(x), res - 2), yi = std::min(int(y), res - 2);
        int zi = ZInterval(z);
        Float dx = x - Float(xi), dy = y - Float(yi);
        Float dz = (z - zNodes[zi]) / (zNodes[zi + 1] - zNodes[zi]);

        Float c[3];
        for (int i = 0; i < 3; ++i) {
            auto co = [&](int ox, int oy, int oz) {
                return (*coeffs)[maxc][zi + oz][yi + oy][xi + ox][i];
            };
            c[i] = Lerp(dz,
                        Lerp(dy, Lerp(dx, co(0, 0, 0), co(1, 0, 0)),
                             Lerp(dx, co(0, 1, 0), co(1, 1, 0))),
                        Lerp(dy, Lerp(dx, co(0, 0, 1), co(1, 0, 1)),
                             Lerp(dx, co(0, 1, 1), co(1, 1, 1))));
        }
        return RGBSigmoidPolynomial(c[0], c[1], c[2]);
    }

    // The brightness of layer zi (for tests and tools).
    PBRT_CPU_GPU Float ZNode(int zi) const { return zNodes[zi]; }
    // The stored coefficients (c0, c1, c2) of a node, as a spectrum.
    PBRT_CPU_GPU RGBSigmoidPolynomial Node(int maxc, int zi, int yi, int xi) const {
        const float *c = (*coeffs)[maxc][zi][yi][xi];
        return RGBSigmoidPolynomial(c[0], c[1], c[2]);
    }

    std::string ToString() const { return "[ RGBToSpectrumTable res: " + std::to_string(res) + " ]"; }

  private:
    // The largest zi in [0, res - 2] with zNodes[zi] < z (zNodes[0] = 0 < z).
    PBRT_CPU_GPU int ZInterval(Float z) const {
        return detail::FindInterval(res, [&](int i) { return zNodes[i] < z; });
    }

    const float *zNodes;
    const CoefficientArray *coeffs;
};

}  // namespace pbrt
