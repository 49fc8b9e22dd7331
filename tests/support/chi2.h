// pbrt_ext tests: the one chi-square harness for direction samplers (BxDFs and warps).
//
// The idea follows pbrt-v4 (src/pbrt/bsdfs_test.cpp), Nori (src/chi2test.cpp) and
// Mitsuba 3 (chi2.py): draw many directions with the sampler, histogram them, integrate
// the claimed density over every histogram cell, and ask Pearson's test whether the
// counts could come from that density. Choices made here:
//   - Cells are equal in solid angle: uniform in (cos theta, phi) over the whole sphere,
//     so no cell is starved near the poles and a sampler may produce any direction.
//     The bins' pole is the +y axis, not the normal: around a pole the cells are long
//     thin wedges that see nothing of a lobe's radial shape, and the lobes tested most
//     (around the normal, at normal incidence) would fall into one ring of them. With
//     the pole on the horizon the normal sits on the bins' equator, where cells are
//     compact, and the horizon is still made of cell edges.
//   - A sampler may decline (empty optional). Expected counts are N * integral of the
//     pdf over the cell, with N the number of attempts, so sub-probability samplers are
//     tested as they are, and the pdf's integral over the sphere is checked against the
//     fraction accepted.
//   - Cell integrals are adaptive: 5x5 Gauss-Legendre on a piece against the sum over
//     its four quarters, splitting the worst piece until the cell's error is a small
//     fraction of its Poisson noise. This copes with narrow lobes, horizons that cut
//     cells, and integrable point singularities; nodes are interior, so a singular
//     point is never evaluated.
//   - Cells with an expected count below 5 are pooled; one sample in a cell whose
//     integral is exactly zero rejects outright.
//   - alpha = 0.01 with the Sidak correction for the number of tests in a suite; the
//     p-value comes from the regularized incomplete gamma function written below.
// Host-only test code: it may allocate and build strings.
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/spherequadrature.h"
#include "pbrt_ext/util/vecmath.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace pbrt {

// ---------------------------------------------------------------------------------------
// Quadrature shared by the statistical and property tests

// Unit direction from (cos theta, phi), in double for the quadrature and the binning.
inline Vector3f DirectionFromCosThetaPhi(double cosTheta, double phi) {
    double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    return Vector3f(Float(sinTheta * std::cos(phi)), Float(sinTheta * std::sin(phi)),
                    Float(cosTheta));
}

// Calls visit(w, weight) for the nodes of a product rule over the sphere, Gauss-Legendre in
// cos theta on each hemisphere separately (BxDFs are discontinuous at the horizon) and the
// midpoint rule in phi. Sum of visit's weights = 4 pi.
template <typename Visit>
void ForEachSphereQuadratureNode(int nCosTheta, int nPhi, Visit visit) {
    ForEachSphereNode(Frame::FromZ(Vector3f(0, 0, 1)), {0.0}, nCosTheta, nPhi, visit);
}

// ---------------------------------------------------------------------------------------
// Chi-square distribution

// Regularized upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a), for a > 0, x >= 0:
// the power series of P(a, x) below x = a + 1 (where it converges fast), the continued
// fraction of Q(a, x) above it (Lentz's method). Both need O(sqrt(a)) terms near x = a.
inline double RegularizedGammaQ(double a, double x) {
    if (x <= 0)
        return 1;
    double logPrefactor = a * std::log(x) - x - std::lgamma(a);
    constexpr double eps = 1e-15, tiny = 1e-300;
    if (x < a + 1) {
        double term = 1 / a, sum = term;
        for (int n = 1; n < 100000 && std::abs(term) > eps * std::abs(sum); ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return std::max(0.0, 1 - std::exp(logPrefactor) * sum);
    }
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int n = 1; n < 100000; ++n) {
        double an = -n * (n - a);
        b += 2;
        d = an * d + b;
        d = std::abs(d) < tiny ? tiny : d;
        c = b + an / c;
        c = std::abs(c) < tiny ? tiny : c;
        d = 1 / d;
        double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < eps)
            break;
    }
    return std::exp(logPrefactor) * h;
}

// P(X >= statistic) for X chi-square distributed with dof degrees of freedom.
inline double Chi2SurvivalProbability(double statistic, int dof) {
    return RegularizedGammaQ(0.5 * dof, 0.5 * statistic);
}

// Per-test level that keeps the suite-wide false rejection rate at alpha over numTests
// independent tests.
inline double SidakCorrectedLevel(double alpha, int numTests) {
    return -std::expm1(std::log1p(-alpha) / numTests);
}

// ---------------------------------------------------------------------------------------
// The harness

struct Chi2Options {
    // Bins uniform in y = cos theta_b in [-1, 1] and in the angle phi_b = atan2(z, x) in
    // [0, 2 pi) (above the surface for phi_b < pi; keep phiBins even so that the
    // horizon is made of cell edges). A smooth error adds about the same to the
    // statistic at any resolution while the statistic's noise grows with the number of
    // cells, so cells are no finer than lobes need.
    int cosThetaBins = 32;
    int phiBins = 64;
    int sampleCount = 1000000;
    double significance = 0.01;  // suite-wide, before the Sidak correction
    int numTests = 1;            // tests in the suite, for the Sidak correction
    double minExpectedCount = 5;  // cells expected below this are pooled
    uint64_t seed = 0;            // RNG sequence index
    // Cell integration refines until its error estimate is below this many standard
    // deviations of the cell's count (sqrt(expected)), or the refinements run out.
    double integrationTolerance = 0.02;
    int maxRefinements = 200;     // per cell; each costs 400 pdf evaluations
    int minIntegrationDepth = 0;  // start from 4^depth leaves: lobes far below cell size
    // Allowed |integral of pdf - accepted fraction| beyond 5 binomial sigmas.
    double integralTolerance = 1e-3;
};

struct Chi2Result {
    bool passed = false;
    double pValue = 0;
    double statistic = 0;
    int degreesOfFreedom = 0;
    double level = 0;             // Sidak-corrected significance actually used
    double integralPdf = 0;       // integral of the pdf over the sphere
    double acceptedFraction = 0;  // samples counted / attempts
    int64_t zeroPdfCellSamples = 0;   // samples in cells whose pdf integrates to zero
    int64_t invalidSamples = 0;       // non-finite or zero-length directions
    int64_t invalidPdfValues = 0;     // NaN, Inf or negative pdf at a quadrature node
    int64_t specularSkipped = 0;      // BxDF only: specular samples, not testable
    int64_t proportionalSamples = 0;  // BxDF only: pdfIsProportional samples counted
    std::string message;  // one summary line; the reasons and tables when it failed
};

namespace chi2detail {

constexpr double kPi = 3.14159265358979323846;

// The bins' spherical coordinates: polar axis +y, azimuth in the x-z plane from +x
// towards +z. Directions need not be normalized. A direction exactly on the horizon
// counts as above it, where samplers that produce one (z = 0 from a hemisphere warp)
// have their density.
inline void BinCoordinates(Vector3f w, double *cosTheta, double *phi) {
    double x = w.x, y = w.y, z = w.z, len = std::sqrt(x * x + y * y + z * z);
    *cosTheta = std::clamp(y / len, -1.0, 1.0);
    if (z == 0)
        *phi = x >= 0 ? 0 : std::nextafter(kPi, 0.0);
    else
        *phi = z > 0 ? std::atan2(z, x) : std::atan2(z, x) + 2 * kPi;
}

inline Vector3f DirectionFromBinCoordinates(double cosTheta, double phi) {
    double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    return Vector3f(Float(sinTheta * std::cos(phi)), Float(cosTheta),
                    Float(sinTheta * std::sin(phi)));
}

struct Table {
    Table(int cosBins, int phiBins)
        : nCos(cosBins), nPhi(phiBins), observed(size_t(cosBins) * phiBins, 0),
          expected(observed) {}
    int nCos, nPhi;
    std::vector<double> observed, expected;  // row-major, row 0 at cos theta_b = -1
    double CosTheta(int i) const { return -1 + 2.0 * i / nCos; }
    double Phi(int j) const { return 2 * kPi * j / nPhi; }
};

inline int CellIndex(const Table &t, Vector3f w) {
    double cosTheta, phi;
    BinCoordinates(w, &cosTheta, &phi);
    int i = std::clamp(int((cosTheta + 1) * 0.5 * t.nCos), 0, t.nCos - 1);
    int j = std::clamp(int(phi / (2 * kPi) * t.nPhi), 0, t.nPhi - 1);
    return i * t.nPhi + j;
}

inline bool IsValidDirection(Vector3f w) {
    double len2 = double(w.x) * w.x + double(w.y) * w.y + double(w.z) * w.z;
    return std::isfinite(len2) && len2 > 0;
}

struct Rect {
    double z0, z1, p0, p1;  // cos theta_b and phi_b ranges

    Rect Quarter(int k) const {
        double zm = 0.5 * (z0 + z1), pm = 0.5 * (p0 + p1);
        return {k & 1 ? zm : z0, k & 1 ? z1 : zm, k & 2 ? pm : p0, k & 2 ? p1 : pm};
    }
};

// Integrates a pdf over (cos theta_b, phi_b) rectangles, globally adaptively within a cell:
// a leaf's error estimate is |its Gauss-Legendre value - the sum over its quarters|, and
// the leaf with the largest one is split until the cell's total is small enough. Unlike
// recursion with a per-level budget this converges at a point singularity, where the
// error of the leaf holding the point only shrinks with its size. Counts invalid pdf
// values.
template <typename PdfFn>
class CellIntegrator {
  public:
    CellIntegrator(PdfFn &pdfFn, const Chi2Options &options)
        : pdf(pdfFn), opts(options), rule(GaussLegendre(kOrder)) {}

    double Integrate(const Rect &cell) {
        std::vector<Leaf> leaves;
        int splits = 1 << opts.minIntegrationDepth;
        double dz = (cell.z1 - cell.z0) / splits, dp = (cell.p1 - cell.p0) / splits;
        for (int i = 0; i < splits; ++i)
            for (int j = 0; j < splits; ++j) {
                Rect r{cell.z0 + i * dz, cell.z0 + (i + 1) * dz, cell.p0 + j * dp,
                       cell.p0 + (j + 1) * dp};
                leaves.push_back(MakeLeaf(r, Rule(r)));
            }
        double estimate = 0, error = 0;
        for (const Leaf &leaf : leaves)
            estimate += leaf.estimate, error += leaf.error;
        double n = opts.sampleCount;
        double tol = opts.integrationTolerance * std::sqrt(std::max(n * estimate, 1.0)) / n;

        auto byError = [](const Leaf &a, const Leaf &b) { return a.error < b.error; };
        std::make_heap(leaves.begin(), leaves.end(), byError);
        for (int k = 0; k < opts.maxRefinements && error > tol; ++k) {
            std::pop_heap(leaves.begin(), leaves.end(), byError);
            Leaf worst = leaves.back();
            leaves.pop_back();
            estimate -= worst.estimate;
            error -= worst.error;
            for (int q = 0; q < 4; ++q) {
                Leaf child = MakeLeaf(worst.rect.Quarter(q), worst.quarters[q]);
                estimate += child.estimate;
                error += child.error;
                leaves.push_back(child);
                std::push_heap(leaves.begin(), leaves.end(), byError);
            }
        }
        return estimate;
    }

    // A cell holding samples but no pdf at the nodes of the adaptive rule may hold a
    // sliver of density (a tilted horizon clipping a corner): look again on a fixed
    // fine grid before calling the samples impossible.
    double IntegrateFinely(const Rect &cell) {
        constexpr int splits = 32;
        double dz = (cell.z1 - cell.z0) / splits, dp = (cell.p1 - cell.p0) / splits, sum = 0;
        for (int i = 0; i < splits; ++i)
            for (int j = 0; j < splits; ++j)
                sum += Rule({cell.z0 + i * dz, cell.z0 + (i + 1) * dz, cell.p0 + j * dp,
                             cell.p0 + (j + 1) * dp});
        return sum;
    }

    int64_t invalidValues = 0;

  private:
    static constexpr int kOrder = 5;

    struct Leaf {
        Rect rect;
        double quarters[4];  // the rule on each quarter, reused when the leaf is split
        double estimate, error;
    };

    Leaf MakeLeaf(const Rect &r, double whole) {
        Leaf leaf{r, {}, 0, 0};
        for (int q = 0; q < 4; ++q) {
            leaf.quarters[q] = Rule(r.Quarter(q));
            leaf.estimate += leaf.quarters[q];
        }
        leaf.error = std::abs(leaf.estimate - whole);
        return leaf;
    }

    // Tensor Gauss-Legendre rule; d(omega) = d(cos theta_b) d(phi_b).
    double Rule(const Rect &r) {
        double hz = 0.5 * (r.z1 - r.z0), hp = 0.5 * (r.p1 - r.p0), sum = 0;
        for (auto [xz, wz] : rule)
            for (auto [xp, wp] : rule) {
                double p = pdf(DirectionFromBinCoordinates(r.z0 + hz * (xz + 1),
                                                           r.p0 + hp * (xp + 1)));
                if (!std::isfinite(p) || p < 0) {
                    ++invalidValues;
                    continue;
                }
                sum += wz * wp * p;
            }
        return sum * hz * hp;
    }

    PdfFn &pdf;
    const Chi2Options &opts;
    std::vector<std::pair<double, double>> rule;
};

// Pearson's statistic with pooling of the cells expected below minExpected.
struct Pearson {
    double statistic = 0;
    int dof = 0;
};

inline Pearson PooledPearson(std::vector<std::pair<double, double>> cells,
                             double minExpected) {
    // (expected, observed), smallest expectation first, so that the pool fills from the
    // bottom and stops as soon as it is large enough.
    std::sort(cells.begin(), cells.end());
    Pearson result;
    double poolE = 0, poolO = 0;
    int categories = 0;
    for (auto [e, o] : cells) {
        if (e == 0 && o == 0)
            continue;
        if (e < minExpected || (poolE > 0 && poolE < minExpected)) {
            poolE += e;
            poolO += o;
        } else {
            result.statistic += (o - e) * (o - e) / e;
            ++categories;
        }
    }
    if (poolE > 0) {
        result.statistic += (poolO - poolE) * (poolO - poolE) / poolE;
        ++categories;
    }
    result.dof = categories - 1;
    return result;
}

// Sums t's rows and columns into at most rows x cols blocks and prints one table.
template <typename Value>
std::string BlockTable(const Table &t, const char *title, int rows, int cols,
                       Value value) {
    rows = std::min(rows, t.nCos);
    cols = std::min(cols, t.nPhi);
    std::string s = std::string(title) +
                    " (rows: y from +1 down to -1; columns: atan2(z, x) from 0 to 2 pi, "
                    "the left half above the surface)\n";
    char buf[32];
    for (int r = rows - 1; r >= 0; --r) {
        for (int c = 0; c < cols; ++c) {
            double o = 0, e = 0;
            for (int i = r * t.nCos / rows; i < (r + 1) * t.nCos / rows; ++i)
                for (int j = c * t.nPhi / cols; j < (c + 1) * t.nPhi / cols; ++j) {
                    o += t.observed[i * t.nPhi + j];
                    e += t.expected[i * t.nPhi + j];
                }
            std::snprintf(buf, sizeof(buf), " %7s", value(o, e).c_str());
            s += buf;
        }
        s += "\n";
    }
    return s;
}

// v with `digits` decimals, or in scientific notation when it is too wide for a table.
inline std::string Fixed(double v, int digits) {
    char buf[64];
    if (std::abs(v) < 1e7)
        std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
    else
        std::snprintf(buf, sizeof(buf), "%.1e", v);
    return buf;
}

// The cells that contribute most to the statistic, with their coordinates.
inline std::string WorstCells(const Table &t, int count) {
    std::vector<std::pair<double, int>> score;
    for (size_t k = 0; k < t.observed.size(); ++k) {
        double o = t.observed[k], e = t.expected[k];
        double s = e > 0 ? (o - e) * (o - e) / e : (o > 0 ? HUGE_VAL : 0);
        if (s > 0)
            score.push_back({s, int(k)});
    }
    count = std::min(count, int(score.size()));
    std::partial_sort(score.begin(), score.begin() + count, score.end(),
                      [](auto a, auto b) { return a.first > b.first; });
    std::string s = "worst cells (direction at the centre): observed vs expected\n";
    char buf[160];
    for (int k = 0; k < count; ++k) {
        int i = score[k].second / t.nPhi, j = score[k].second % t.nPhi;
        Vector3f c = DirectionFromBinCoordinates(0.5 * (t.CosTheta(i) + t.CosTheta(i + 1)),
                                                 0.5 * (t.Phi(j) + t.Phi(j + 1)));
        std::snprintf(buf, sizeof(buf), "  (%+.3f, %+.3f, %+.3f): %.0f vs %.2f\n", c.x, c.y,
                      c.z, t.observed[score[k].second], t.expected[score[k].second]);
        s += buf;
    }
    return s;
}

inline std::string DescribeTables(const Table &t) {
    constexpr int rows = 8, cols = 16;
    auto count = [](double v) { return Fixed(v, 0); };
    return BlockTable(t, "observed counts", rows, cols,
                      [&](double o, double) { return count(o); }) +
           BlockTable(t, "expected counts", rows, cols,
                      [&](double, double e) { return count(e); }) +
           BlockTable(t, "(observed - expected) / sqrt(expected)", rows, cols,
                      [](double o, double e) {
                          return e > 0 ? Fixed((o - e) / std::sqrt(e), 1)
                                       : std::string(o > 0 ? "inf" : "-");
                      }) +
           WorstCells(t, 8);
}

}  // namespace chi2detail

// Tests a direction sampler against the density it claims.
//   sample(Point2f u, Float uc) -> pstd::optional<Vector3f>: a direction, or empty when
//     the sampler declines; u and uc are independent uniform numbers in [0, 1).
//   pdf(Vector3f w) -> Float: density per unit solid angle of the directions produced.
template <typename SampleFn, typename PdfFn>
Chi2Result Chi2TestSampler(SampleFn sample, PdfFn pdf, const Chi2Options &opts) {
    using namespace chi2detail;
    Chi2Result result;
    Table t(opts.cosThetaBins, opts.phiBins);
    size_t nCells = t.observed.size();
    const double n = opts.sampleCount;

    RNG rng(opts.seed);
    int64_t accepted = 0;
    for (int k = 0; k < opts.sampleCount; ++k) {
        // Separate statements: argument evaluation order is unspecified.
        Float uc = rng.Uniform<Float>();
        Float u0 = rng.Uniform<Float>();
        Point2f u(u0, rng.Uniform<Float>());
        pstd::optional<Vector3f> w = sample(u, uc);
        if (!w)
            continue;
        if (!IsValidDirection(*w)) {
            ++result.invalidSamples;
            continue;
        }
        ++accepted;
        t.observed[CellIndex(t, *w)] += 1;
    }
    result.acceptedFraction = accepted / n;

    CellIntegrator<PdfFn> integrator(pdf, opts);
    for (int i = 0; i < t.nCos; ++i)
        for (int j = 0; j < t.nPhi; ++j) {
            Rect cell{t.CosTheta(i), t.CosTheta(i + 1), t.Phi(j), t.Phi(j + 1)};
            double p = integrator.Integrate(cell);
            if (p == 0 && t.observed[i * t.nPhi + j] > 0)
                p = integrator.IntegrateFinely(cell);
            t.expected[i * t.nPhi + j] = n * p;
            result.integralPdf += p;
        }
    result.invalidPdfValues = integrator.invalidValues;

    std::vector<std::pair<double, double>> cells;
    cells.reserve(nCells);
    for (size_t k = 0; k < nCells; ++k) {
        if (t.expected[k] == 0)
            result.zeroPdfCellSamples += int64_t(t.observed[k]);
        else
            cells.push_back({t.expected[k], t.observed[k]});
    }
    // Declined samples get no category of their own: N (1 - integral) carries the whole
    // quadrature error of the integral (1e-5 of a float pdf is 10 counts here), which
    // would masquerade as a discrepancy. The integral check below covers them instead;
    // without that category the statistic's mean is between dof and dof + 1.
    Pearson pearson = PooledPearson(std::move(cells), opts.minExpectedCount);
    result.statistic = pearson.statistic;
    result.degreesOfFreedom = pearson.dof;
    result.pValue = pearson.dof > 0 ? Chi2SurvivalProbability(pearson.statistic, pearson.dof)
                                    : 0;
    result.level = SidakCorrectedLevel(opts.significance, opts.numTests);

    double binomialSigma = std::sqrt(
        std::max(result.integralPdf * (1 - result.integralPdf), 1 / n) / n);
    bool integralOk = std::abs(result.integralPdf - result.acceptedFraction) <=
                      5 * binomialSigma + opts.integralTolerance;

    std::string reasons;
    auto reject = [&](const std::string &why) { reasons += "  rejected: " + why + "\n"; };
    if (result.pValue < result.level)
        reject("p-value below the Sidak-corrected level");
    if (pearson.dof <= 0)
        reject("too few degrees of freedom");
    if (result.zeroPdfCellSamples > 0)
        reject(std::to_string(result.zeroPdfCellSamples) +
               " samples in cells where the pdf integrates to zero");
    if (result.invalidSamples > 0)
        reject(std::to_string(result.invalidSamples) +
               " non-finite or zero-length sampled directions");
    if (result.invalidPdfValues > 0)
        reject("pdf returned NaN, Inf or a negative value at " +
               std::to_string(result.invalidPdfValues) + " quadrature nodes");
    if (!integralOk)
        reject("the pdf's integral over the sphere does not match the accepted fraction");
    result.passed = reasons.empty();

    char summary[320];
    std::snprintf(summary, sizeof(summary),
                  "chi2 = %.2f, dof = %d, p-value = %.3g, level = %.3g, "
                  "integral of pdf = %.6f, accepted fraction = %.6f, samples = %d, "
                  "cells = %d x %d\n",
                  result.statistic, result.degreesOfFreedom, result.pValue, result.level,
                  result.integralPdf, result.acceptedFraction, opts.sampleCount, t.nCos,
                  t.nPhi);
    result.message = summary;
    if (!result.passed)
        result.message += reasons + DescribeTables(t);
    return result;
}

// Tests bxdf.Sample_f against bxdf.PDF for one outgoing direction (local frame). Samples
// that are specular (a discrete probability, not a density) or have pdf 0 count as
// declined; their share shows as the gap between 1 and the accepted fraction, and the
// specular ones are reported. pdfIsProportional samples are counted and reported, but a
// chi-square test of such a BxDF is meaningless.
template <typename BxDF>
Chi2Result Chi2TestBxDF(const BxDF &bxdf, Vector3f wo, const Chi2Options &opts,
                        TransportMode mode = TransportMode::Radiance,
                        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) {
    int64_t specular = 0, proportional = 0;
    auto sample = [&](Point2f u, Float uc) -> pstd::optional<Vector3f> {
        pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, uc, u, mode, sampleFlags);
        if (!bs || bs->pdf == 0)
            return {};
        if (bs->IsSpecular()) {
            ++specular;
            return {};
        }
        proportional += bs->pdfIsProportional ? 1 : 0;
        return bs->wi;
    };
    auto pdf = [&](Vector3f wi) { return bxdf.PDF(wo, wi, mode, sampleFlags); };
    Chi2Result result = Chi2TestSampler(sample, pdf, opts);
    result.specularSkipped = specular;
    result.proportionalSamples = proportional;

    char context[160];
    std::snprintf(context, sizeof(context),
                  "wo = (%.6f, %.6f, %.6f), specular samples skipped = %lld, "
                  "pdfIsProportional samples = %lld\n",
                  wo.x, wo.y, wo.z, (long long)specular, (long long)proportional);
    std::string name;
    if constexpr (requires { bxdf.ToString(); })
        name = bxdf.ToString() + "\n";
    result.message = name + context + result.message;
    return result;
}

}  // namespace pbrt
