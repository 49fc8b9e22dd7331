// pbrt_ext: the optimizer behind RGBToSpectrumTable (host only, double precision), shared by the
// build-time generator cmd/rgb2spec_opt.cpp and by the test that re-derives table cells.
//
// Jakob and Hanika, "A Low-Dimensional Function Space for Efficient Spectral Upsampling",
// Computer Graphics Forum 38(2), 2019: for each RGB, the sigmoid polynomial s(A t^2 + B t + C)
// (t the normalized wavelength) whose colour under the colour space's illuminant matches it,
// found by Gauss-Newton on the residual in CIELAB, where equal steps are roughly equally visible,
// so that the fit does not favour bright colours. Cells are solved in order of brightness along
// each column of the table, each one seeded with its neighbour's solution (the paper propagates
// solutions from cell to neighbouring cell; pbrt-v4's generator marches columns the same way):
// a colour close to a solved one has a solution close to it.
//
// What we do differently, and why:
//  - The observer and the illuminants are the renderer's tables over 360-830 nm (pbrt-v4's own
//    data: ciedata.h's D65, and "illum-acesD60" for ACES2065-1, the illuminant of pbrt-v4's
//    RGBColorSpace, where pbrt-v4's generator fits ACES under a D60 of its own), so the
//    renderer, the generator and the tests integrate against the same data. Integration is
//    Simpson's rule on 0.5 nm steps, aligned with the 1 nm matching functions (and the 5 nm
//    illuminants) so that every panel integrates a smooth function (the interpolated data has
//    kinks only at the samples).
//  - The RGB -> XYZ matrix is built from the space's primaries and the white that its tabulated
//    illuminant integrates to (as pbrt-v4's RGBColorSpace builds it), not the rounded standard
//    matrix, so that the constant spectrum c is exactly the grey (c, c, c).
//  - The Jacobian is analytic (pbrt-v4: central differences), a step that does not lower the
//    residual is halved (pbrt-v4 takes the full step), and the coefficients are not bounded to
//    200 (see kMaxCoefficient), so every sRGB cell converges (to 1e-6 in CIELAB). The wider
//    spaces hold colours that no reflectance has (ACES's green and blue lie outside the spectral
//    locus; saturated Rec. 2020 and DCI-P3 colours are brighter than any reflectance of their
//    chromaticity): those cells keep the closest fit the iterations reach, as in pbrt-v4.
//  - The layer z = 0 (black, which no finite coefficients reach) stores the solution of the
//    next layer, z = 1.7e-6: lookups below it keep their hue and stay within 2e-6 of black.
#pragma once

#include "pbrt_ext/spectra/namedspectradata.h"
#include "pbrt_ext/util/ciedata.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>
#include <cstddef>
#include <span>
#include <string_view>

namespace pbrt::rgb2spec {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;  // row-major

// ---- Table layout (RGBToSpectrumTable's) -------------------------------------------------------

constexpr int kResolution = 64;
// The first layer solved in each column (z = 0.025), from the flat spectrum 1/2; the solution
// then spreads up and down the column, each layer seeded with its neighbour's (as in pbrt-v4).
constexpr int kStartLayer = kResolution / 5;

// The brightness (largest component) of layer k: smoothstep(smoothstep(k / (res - 1))), which
// crowds the layers towards black and towards full brightness, where the coefficients change
// fastest. Computed in double, rounded to float; the generated table stores these floats.
inline float ZNode(int k) {
    auto smoothstep = [](double x) { return x * x * (3 - 2 * x); };
    return float(smoothstep(smoothstep(k / double(kResolution - 1))));
}

// Offset of the coefficients of node (maxc, zi, yi, xi) in float[3][res][res][res][3].
constexpr size_t TableOffset(int maxc, int zi, int yi, int xi) {
    return 3 * (((size_t(maxc) * kResolution + zi) * kResolution + yi) * kResolution + xi);
}
constexpr size_t kTableFloats = TableOffset(3, 0, 0, 0);

// The RGB a node stands for: component maxc is the layer's brightness z, the next two (cyclically)
// are x and y times z, with x, y in [0, 1] on a uniform grid.
inline Vec3 NodeRGB(int maxc, int zi, int yi, int xi) {
    double z = ZNode(zi);
    Vec3 rgb;
    rgb[maxc] = z;
    rgb[(maxc + 1) % 3] = xi / double(kResolution - 1) * z;
    rgb[(maxc + 2) % 3] = yi / double(kResolution - 1) * z;
    return rgb;
}

// ---- The colour spaces ---------------------------------------------------------------------------

// pbrt-v4's four RGB colour spaces (spectra/colorspace.cpp): the primaries as CIE xy chromaticities
// (sRGB: ITU-R BT.709; DCI-P3: SMPTE RP 431-2 primaries with a D65 white, as pbrt-v4 has it;
// Rec. 2020: ITU-R BT.2020; ACES2065-1: SMPTE ST 2065-1's AP0, whose green and blue lie outside
// the spectral locus) and the illuminant that fixes the white.
struct Gamut {
    const char *name;    // pbrt-v4's ColorSpace name
    const char *symbol;  // in the generated table's C++ names
    std::array<double, 2> r, g, b;
    double (*illuminant)(double lambda);
};

// D65 as ciedata.h tabulates it (the data of pbrt-v4's "stdillum-D65").
inline double D65At(double lambda) { return CIEAt(Float(lambda)).d65; }
// pbrt-v4's "illum-acesD60", linearly interpolated between its samples (namedspectradata.cpp).
inline double ACESD60At(double lambda) {
    for (size_t i = 0; i < kNumNamedSpectrumTables; ++i) {
        const NamedSpectrumTable &table = kNamedSpectrumTables[i];
        if (table.name != "illum-acesD60") continue;
        std::span<const float> v = table.interleaved;
        for (size_t k = 0; k + 3 < v.size(); k += 2)
            if (lambda >= v[k] && lambda <= v[k + 2])
                return v[k + 1] + (lambda - v[k]) / (v[k + 2] - v[k]) * (v[k + 3] - v[k + 1]);
        return 0;
    }
    return 0;
}

inline constexpr Gamut kGamuts[] = {
    {"srgb", "sRGB", {0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, D65At},
    {"dci-p3", "DCI_P3", {0.68, 0.32}, {0.265, 0.690}, {0.15, 0.06}, D65At},
    {"rec2020", "Rec2020", {0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}, D65At},
    {"aces2065-1", "ACES2065_1", {0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.077}, ACESD60At},
};

// The entry of kGamuts named `name`; null for any other.
inline const Gamut *FindGamut(std::string_view name) {
    for (const Gamut &g : kGamuts)
        if (name == g.name) return &g;
    return nullptr;
}

// ---- The fit -----------------------------------------------------------------------------------

// The optimizer's wavelength variable t = (lambda - 360) / 470, in [0, 1] over the data; the
// polynomial is kept in t while solving, where its coefficients are of comparable size.
constexpr double kLambdaMin = 360, kLambdaRange = 470;
// A guard against runaway steps, not a constraint the solutions meet: the largest coefficient in
// the sRGB table is 3e4 (dark saturated blue). pbrt-v4 scales its coefficients back to 200, which
// here left 5 % of the cells unconverged (dark saturated colours, up to 1e-2 off in linear RGB,
// at colours of brightness 1e-3); every sRGB colour is reachable, only with steep spectra.
constexpr double kMaxCoefficient = 1e6;

// A * t^2 + B * t + C in t, as the polynomial in lambda (nm) that RGBSigmoidPolynomial
// evaluates: (c0, c1, c2) with c0 lambda^2 + c1 lambda + c2.
inline Vec3 ToNanometres(const Vec3 &abc) {
    double s = 1 / kLambdaRange, l0 = kLambdaMin;
    double A = abc[0], B = abc[1], C = abc[2];
    return {A * s * s, B * s - 2 * A * l0 * s * s, C - B * l0 * s + A * (l0 * s) * (l0 * s)};
}

struct SolveResult {
    Vec3 coeffs{};         // A, B, C in t
    double residual = 0;  // |Lab(fit) - Lab(target)|, CIELAB units (delta E 1976)
    int iterations = 0;
};

// The colour space and observer, precomputed: quadrature weights times the matching functions
// times the illuminant, and the RGB <-> XYZ matrices.
class SigmoidFit {
  public:
    // Linear sRGB (ITU-R BT.709 primaries), white = CIE D65.
    static const SigmoidFit &sRGB() { return ForGamut(kGamuts[0]); }
    // The fit for one of kGamuts, made once.
    static const SigmoidFit &ForGamut(const Gamut &gamut);

    // Primaries as CIE xy chromaticities; the white is the illuminant's.
    SigmoidFit(std::array<double, 2> r, std::array<double, 2> g, std::array<double, 2> b,
               double (*illuminant)(double lambda)) {
        constexpr double h = 0.5;  // two Simpson subintervals per 1 nm sample
        double norm = 0;
        for (int n = 0; n < kNodes; ++n) {
            double lambda = kLambdaMin + h * n;
            CIESample c = CIEAt(Float(lambda));
            double w = h / 3 * (n == 0 || n == kNodes - 1 ? 1 : (n % 2 == 1 ? 4 : 2));
            double I = illuminant(lambda);
            t[n] = (lambda - kLambdaMin) / kLambdaRange;
            weight[0][n] = w * c.x * I;
            weight[1][n] = w * c.y * I;
            weight[2][n] = w * c.z * I;
            norm += weight[1][n];
        }
        for (auto &row : weight)
            for (double &v : row) v /= norm;  // the perfect white has Y = 1
        for (int i = 0; i < 3; ++i)
            for (int n = 0; n < kNodes; ++n) white[i] += weight[i][n];

        // pbrt-v4's RGBColorSpace: columns are the primaries' XYZ at Y = 1, scaled so that
        // RGB (1, 1, 1) is the white.
        auto xyz = [](std::array<double, 2> xy) {
            return Vec3{xy[0] / xy[1], 1, (1 - xy[0] - xy[1]) / xy[1]};
        };
        Mat3 P;
        Vec3 pr = xyz(r), pg = xyz(g), pb = xyz(b);
        for (int i = 0; i < 3; ++i) P[i] = {pr[i], pg[i], pb[i]};
        Vec3 scale = Multiply(Inverse(P), white);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) rgbToXYZ[i][j] = P[i][j] * scale[j];
        xyzToRGB = Inverse(rgbToXYZ);
    }

    // XYZ of the reflectance s(A t^2 + B t + C) under the illuminant (white: Y = 1), and, if
    // asked, its derivatives d XYZ_i / d (A, B, C)_j.
    Vec3 XYZOf(const Vec3 &abc, Mat3 *jacobian = nullptr) const {
        Vec3 xyz{};
        Mat3 J{};
        for (int n = 0; n < kNodes; ++n) {
            double x = (abc[0] * t[n] + abc[1]) * t[n] + abc[2];
            double d = 1 + x * x, root = std::sqrt(d);
            double s = 0.5 + x / (2 * root);
            for (int i = 0; i < 3; ++i) xyz[i] += weight[i][n] * s;
            if (jacobian) {
                double ds = 0.5 / (d * root);  // s'(x)
                double dx[3] = {t[n] * t[n], t[n], 1};
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) J[i][j] += weight[i][n] * ds * dx[j];
            }
        }
        if (jacobian) *jacobian = J;
        return xyz;
    }

    // CIELAB relative to the white, and, if asked, d Lab / d XYZ.
    Vec3 Lab(const Vec3 &xyz, Mat3 *jacobian = nullptr) const {
        constexpr double delta = 6.0 / 29;
        Vec3 f, df;
        for (int i = 0; i < 3; ++i) {
            double u = xyz[i] / white[i];
            if (u > delta * delta * delta) {
                f[i] = std::cbrt(u);
                df[i] = 1 / (3 * f[i] * f[i] * white[i]);
            } else {
                f[i] = u / (3 * delta * delta) + 4.0 / 29;
                df[i] = 1 / (3 * delta * delta * white[i]);
            }
        }
        if (jacobian)
            *jacobian = Mat3{Vec3{0, 116 * df[1], 0}, Vec3{500 * df[0], -500 * df[1], 0},
                             Vec3{0, 200 * df[1], -200 * df[2]}};
        return {116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])};
    }

    // Gauss-Newton from `seed` towards the sigmoid polynomial whose colour is rgb.
    SolveResult Solve(const Vec3 &rgb, const Vec3 &seed) const {
        const Vec3 target = Lab(Multiply(rgbToXYZ, rgb));
        SolveResult best;
        best.coeffs = seed;
        Mat3 J;
        Vec3 r = Residual(target, best.coeffs, &J);
        best.residual = Norm(r);
        for (int it = 0; it < kMaxIterations && best.residual > kTolerance; ++it) {
            best.iterations = it + 1;
            Vec3 step;
            if (!SolveLinear(J, r, &step)) break;  // singular: flat sigmoid tails
            bool improved = false;
            for (int halvings = 0; halvings < kMaxHalvings && !improved; ++halvings) {
                Vec3 c;
                for (int j = 0; j < 3; ++j) c[j] = best.coeffs[j] + step[j];
                double largest = std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2])});
                if (largest > kMaxCoefficient)
                    for (double &v : c) v *= kMaxCoefficient / largest;
                Mat3 Jc;
                Vec3 rc = Residual(target, c, &Jc);
                if (double norm = Norm(rc); norm < best.residual) {
                    best.coeffs = c;
                    best.residual = norm;
                    r = rc;
                    J = Jc;
                    improved = true;
                }
                for (double &v : step) v *= 0.5;
            }
            if (!improved) break;  // at the coefficient bound, or at float-level precision
        }
        return best;
    }

    // Solves the column (maxc, yi, xi) of the table, writing the coefficients (in nm, as
    // RGBToSpectrumTable reads them) of every layer into table[TableOffset(maxc, zi, yi, xi)];
    // returns the largest residual (CIELAB) of the column.
    double SolveColumn(int maxc, int yi, int xi, float *table) const {
        double worst = 0;
        auto store = [&](int zi, const Vec3 &abc) {
            Vec3 c = ToNanometres(abc);
            for (int j = 0; j < 3; ++j) table[TableOffset(maxc, zi, yi, xi) + j] = float(c[j]);
        };
        Vec3 startCoeffs{};
        for (int up : {1, 0}) {
            Vec3 coeffs = startCoeffs;
            int first = up ? kStartLayer : kStartLayer - 1, end = up ? kResolution : 0;
            for (int zi = first; zi != end; zi += up ? 1 : -1) {
                SolveResult s = Solve(NodeRGB(maxc, zi, yi, xi), coeffs);
                coeffs = s.coeffs;
                if (zi == kStartLayer) startCoeffs = coeffs;
                worst = std::max(worst, s.residual);
                store(zi, coeffs);
                if (zi == 1) store(0, coeffs);
            }
        }
        return worst;
    }

    Mat3 rgbToXYZ, xyzToRGB;
    Vec3 white{};  // XYZ of the perfect reflector under the illuminant

    // Tolerance in CIELAB: 1e-6 delta E is 1e-8 in linear RGB near white, far below a float's
    // table entry.
    static constexpr double kTolerance = 1e-6;
    static constexpr int kMaxIterations = 50, kMaxHalvings = 12;

  private:
    static constexpr int kNodes = 941;  // 360-830 nm every 0.5 nm
    static_assert((kNodes - 1) * 0.5 == kLambdaRange);

    // Lab(target) - Lab(fit) and the derivative of Lab(fit) with respect to the coefficients.
    Vec3 Residual(const Vec3 &target, const Vec3 &abc, Mat3 *J) const {
        Mat3 dXYZ, dLab;
        Vec3 lab = Lab(XYZOf(abc, &dXYZ), &dLab);
        *J = Multiply(dLab, dXYZ);
        return {target[0] - lab[0], target[1] - lab[1], target[2] - lab[2]};
    }

    static double Norm(const Vec3 &v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

    static Vec3 Multiply(const Mat3 &m, const Vec3 &v) {
        Vec3 r{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r[i] += m[i][j] * v[j];
        return r;
    }
    static Mat3 Multiply(const Mat3 &a, const Mat3 &b) {
        Mat3 r{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k) r[i][j] += a[i][k] * b[k][j];
        return r;
    }
    static Mat3 Inverse(const Mat3 &m) {
        double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        Mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                // cofactor of m[j][i]
                int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
                r[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
            }
        return r;
    }
    // Gaussian elimination with partial pivoting; false when a pivot vanishes.
    static bool SolveLinear(Mat3 a, Vec3 b, Vec3 *x) {
        for (int col = 0; col < 3; ++col) {
            int pivot = col;
            for (int row = col + 1; row < 3; ++row)
                if (std::abs(a[row][col]) > std::abs(a[pivot][col])) pivot = row;
            if (!(std::abs(a[pivot][col]) > 1e-300)) return false;
            std::swap(a[col], a[pivot]);
            std::swap(b[col], b[pivot]);
            for (int row = col + 1; row < 3; ++row) {
                double f = a[row][col] / a[col][col];
                for (int k = col; k < 3; ++k) a[row][k] -= f * a[col][k];
                b[row] -= f * b[col];
            }
        }
        for (int row = 2; row >= 0; --row) {
            double v = b[row];
            for (int k = row + 1; k < 3; ++k) v -= a[row][k] * (*x)[k];
            (*x)[row] = v / a[row][row];
        }
        return std::isfinite((*x)[0]) && std::isfinite((*x)[1]) && std::isfinite((*x)[2]);
    }

    double t[kNodes];
    double weight[3][kNodes];  // quadrature weight * cmf * illuminant / normalization
};

inline const SigmoidFit &SigmoidFit::ForGamut(const Gamut &gamut) {
    static const std::vector<SigmoidFit> fits = [] {
        std::vector<SigmoidFit> v;
        for (const Gamut &g : kGamuts) v.emplace_back(g.r, g.g, g.b, g.illuminant);
        return v;
    }();
    return fits[size_t(&gamut - kGamuts)];
}

}  // namespace pbrt::rgb2spec
