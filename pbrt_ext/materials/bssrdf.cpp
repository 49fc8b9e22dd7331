#include "pbrt_ext/materials/bssrdf.h"

#include "pbrt_ext/util/catmullrom.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/scattering.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace pbrt {

Float BeamDiffusionMS(Float sigma_s, Float sigma_a, Float g, Float eta, Float r) {
    constexpr int nSamples = 100;
    // The reduced (similarity-scaled) coefficients, the diffusion coefficient with the
    // absorption correction of Grosjean, and the effective transport coefficient.
    Float sigmap_s = sigma_s * (1 - g), sigmap_t = sigma_a + sigmap_s, rhop = sigmap_s / sigmap_t;
    Float D_g = (2 * sigma_a + sigmap_s) / (3 * sigmap_t * sigmap_t);
    Float sigma_tr = SafeSqrt(sigma_a / D_g);
    // The extrapolated boundary's height and the exitance's fluence and flux weights, from the
    // boundary's Fresnel moments.
    Float fm1 = FresnelMoment1(eta), fm2 = FresnelMoment2(eta);
    Float ze = -2 * D_g * (1 + 3 * fm2) / (1 - 2 * fm1);
    Float cPhi = 0.25f * (1 - 2 * fm1), cE = 0.5f * (1 - 3 * fm2);
    Float Ed = 0;
    for (int i = 0; i < nSamples; ++i) {
        // A real source at depth zr along the beam and its mirror image at zv.
        Float zr = SampleExponential((i + 0.5f) / nSamples, sigmap_t), zv = -zr + 2 * ze;
        Float dr = std::sqrt(Sqr(r) + Sqr(zr)), dv = std::sqrt(Sqr(r) + Sqr(zv));
        Float phiD = Inv4Pi / D_g * (std::exp(-sigma_tr * dr) / dr - std::exp(-sigma_tr * dv) / dv);
        Float EDn = Inv4Pi * (zr * (1 + sigma_tr * dr) * std::exp(-sigma_tr * dr) / (dr * dr * dr) -
                              zv * (1 + sigma_tr * dv) * std::exp(-sigma_tr * dv) / (dv * dv * dv));
        Float E = phiD * cPhi + EDn * cE;
        // Habel et al.'s correction for sources close to the boundary.
        Float kappa = 1 - std::exp(-2 * sigmap_t * (dr + zr));
        Ed += kappa * rhop * rhop * E;
    }
    return Ed / nSamples;
}

Float BeamDiffusionSS(Float sigma_s, Float sigma_a, Float g, Float eta, Float r) {
    constexpr int nSamples = 100;
    Float sigma_t = sigma_a + sigma_s, rho = sigma_s / sigma_t;
    // Below tCrit along the beam, light from the scattering point meets the boundary beyond the
    // critical angle and cannot leave.
    Float tCrit = r * SafeSqrt(Sqr(eta) - 1);
    Float Ess = 0;
    for (int i = 0; i < nSamples; ++i) {
        Float ti = tCrit + SampleExponential((i + 0.5f) / nSamples, sigma_t);
        Float d = std::sqrt(Sqr(r) + Sqr(ti)), cosTheta_o = ti / d;
        Ess += rho * std::exp(-sigma_t * (d + tCrit)) / Sqr(d) * HenyeyGreenstein(cosTheta_o, g) *
               (1 - FrDielectric(-cosTheta_o, eta)) * std::abs(cosTheta_o);
    }
    return Ess / nSamples;
}

BSSRDFTable::BSSRDFTable(Float g, Float eta)
    : rhoSamples(100), radiusSamples(64), profile(100 * 64), rhoEff(100), profileCDF(100 * 64) {
    radiusSamples[0] = 0;
    radiusSamples[1] = 2.5e-3f;
    for (size_t i = 2; i < radiusSamples.size(); ++i)
        radiusSamples[i] = radiusSamples[i - 1] * 1.2f;
    const size_t nRho = rhoSamples.size(), nRadius = radiusSamples.size();
    for (size_t i = 0; i < nRho; ++i)
        rhoSamples[i] = (1 - std::exp(-8 * Float(i) / Float(nRho - 1))) / (1 - std::exp(-8.f));
    tbb::parallel_for(size_t(0), nRho, [&](size_t i) {
        for (size_t j = 0; j < nRadius; ++j) {
            Float rho = rhoSamples[i], r = radiusSamples[j];
            profile[i * nRadius + j] = 2 * Pi * r *
                                       (BeamDiffusionSS(rho, 1 - rho, g, eta, r) +
                                        BeamDiffusionMS(rho, 1 - rho, g, eta, r));
        }
        rhoEff[i] = IntegrateCatmullRom(radiusSamples,
                                        std::span<const Float>(&profile[i * nRadius], nRadius),
                                        std::span<Float>(&profileCDF[i * nRadius], nRadius));
    });
}

void SubsurfaceFromDiffuse(const BSSRDFTable &table, const SampledSpectrum &rhoEff,
                           const SampledSpectrum &mfp, SampledSpectrum *sigma_a,
                           SampledSpectrum *sigma_s) {
    for (int c = 0; c < NSpectrumSamples; ++c) {
        Float rho = InvertCatmullRom(table.rhoSamples, table.rhoEff, rhoEff[c]);
        (*sigma_s)[c] = rho / mfp[c];
        (*sigma_a)[c] = (1 - rho) / mfp[c];
    }
}

bool TabulatedBSSRDF::Interpolate(int i, Float rOptical, Float *sr, Float *rhoEff) const {
    int rhoOffset, radiusOffset;
    std::array<Float, 4> rhoWeights, radiusWeights;
    if (!CatmullRomWeights(table->rhoSamples, rho[i], &rhoOffset, &rhoWeights) ||
        !CatmullRomWeights(table->radiusSamples, rOptical, &radiusOffset, &radiusWeights))
        return false;
    *sr = 0;
    if (rhoEff) *rhoEff = 0;
    for (int j = 0; j < 4; ++j) {
        if (rhoWeights[size_t(j)] == 0) continue;
        if (rhoEff) *rhoEff += table->rhoEff[size_t(rhoOffset + j)] * rhoWeights[size_t(j)];
        for (int k = 0; k < 4; ++k)
            if (radiusWeights[size_t(k)] != 0)
                *sr += table->Profile(rhoOffset + j, radiusOffset + k) * rhoWeights[size_t(j)] *
                       radiusWeights[size_t(k)];
    }
    // The table holds 2 pi r Sr (the density over the radius); Sr is per unit area.
    if (rOptical != 0) *sr /= 2 * Pi * rOptical;
    return true;
}

SampledSpectrum TabulatedBSSRDF::Sr(Float r) const {
    SampledSpectrum result(0.f);
    for (int i = 0; i < NSpectrumSamples; ++i)
        if (Float sr; Interpolate(i, r * sigma_t[i], &sr, nullptr))
            result[i] = sr * Sqr(sigma_t[i]);  // from optical to rendering-space units
    return ClampZero(result);
}

std::optional<Float> TabulatedBSSRDF::SampleSr(Float u) const {
    if (sigma_t[0] == 0) return std::nullopt;
    return SampleCatmullRom2D(table->rhoSamples, table->radiusSamples, table->profile,
                              table->profileCDF, rho[0], u) /
           sigma_t[0];
}

SampledSpectrum TabulatedBSSRDF::PDF_Sr(Float r) const {
    SampledSpectrum pdf(0.f);
    for (int i = 0; i < NSpectrumSamples; ++i)
        if (Float sr, rhoEff; Interpolate(i, r * sigma_t[i], &sr, &rhoEff) && rhoEff > 0)
            pdf[i] = sr * Sqr(sigma_t[i]) / rhoEff;
    return ClampZero(pdf);
}

std::optional<BSSRDFProbeSegment> TabulatedBSSRDF::SampleSp(Float u1, Point2f u2) const {
    // The probe's axis: the normal with probability 1/2, else one of the two tangents.
    const Frame frame = Frame::FromZ(ns);
    Vector3f axis = frame.z, a = frame.x, b = frame.y;
    if (u1 < 0.25f) {
        axis = frame.x, a = frame.y, b = frame.z;
    } else if (u1 < 0.5f) {
        axis = frame.y, a = frame.z, b = frame.x;
    }
    std::optional<Float> r = SampleSr(u2[0]), rMax = SampleSr(0.999f);
    if (!r || !rMax || *r < 0 || *r >= *rMax) return std::nullopt;
    Float phi = 2 * Pi * u2[1];
    // The chord of the sphere of radius rMax around po at distance r from the axis through po.
    Float l = 2 * std::sqrt(Sqr(*rMax) - Sqr(*r));
    Point3f start = po + *r * (a * std::cos(phi) + b * std::sin(phi)) - l * axis / 2;
    return BSSRDFProbeSegment{start, start + l * axis};
}

SampledSpectrum TabulatedBSSRDF::PDF_Sp(Point3f pi, Normal3f ni) const {
    const Frame frame = Frame::FromZ(ns);
    Vector3f d = frame.ToLocal(pi - po), n = frame.ToLocal(Vector3f(ni));
    // The radius each axis's probe had, and how obliquely it met the surface there.
    const Float rProj[3] = {std::sqrt(Sqr(d.y) + Sqr(d.z)), std::sqrt(Sqr(d.z) + Sqr(d.x)),
                            std::sqrt(Sqr(d.x) + Sqr(d.y))};
    const Float axisProb[3] = {0.25f, 0.25f, 0.5f};
    SampledSpectrum pdf(0.f);
    for (int axis = 0; axis < 3; ++axis)
        pdf += PDF_Sr(rProj[axis]) * (std::abs(n[axis]) * axisProb[axis]);
    return pdf;
}

std::string TabulatedBSSRDF::ToString() const {
    return fmt::format("[ TabulatedBSSRDF eta: {} sigma_t: {} rho: {} ]", eta, sigma_t.ToString(),
                       rho.ToString());
}

}  // namespace pbrt
