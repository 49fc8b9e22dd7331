// pbrt_ext: subsurface scattering, pbrt-v4's TabulatedBSSRDF (Physically Based Rendering, 3rd
// edition, Chapter 11 and Section 15.5; pbrt-v4's bssrdf.h).
//
// Light entering a translucent material at pi leaves it at po with the separable BSSRDF
//   S(po, wo, pi, wi) ~ (1 - Fr(wo)) Sp(|po - pi|) Sw(wi),
// where the spatial profile Sp = Sr(r) is that of a semi-infinite homogeneous slab of the
// material: photon beam diffusion (Habel et al. 2013), a multiple-scattering dipole integrated
// along the refracted beam plus the exact single-scattering term, tabulated once per material
// (its g and eta) over the single-scattering albedo rho and the optical radius r sigma_t, and
// interpolated with Catmull-Rom splines. Sw is NormalizedFresnelBxDF at the exit point.
//
// Sampling (SampleSp) picks a radius from the profile of the first wavelength and an axis of the
// frame at po (the normal with probability 1/2, each tangent with 1/4); the probe segment
// through the sphere of the profile's 99.9 % radius along that axis is intersected with the
// material's surface, and PDF_Sp combines the three axes' densities at the hit.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <optional>
#include <string>
#include <vector>

namespace pbrt {

// The radial profile Sr(r) of a semi-infinite slab by photon beam diffusion, its multiple- and
// single-scattering parts (pbrt-v4's BeamDiffusionMS and BeamDiffusionSS), each a 100-point
// quadrature along the refracted beam.
Float BeamDiffusionMS(Float sigma_s, Float sigma_a, Float g, Float eta, Float r);
Float BeamDiffusionSS(Float sigma_s, Float sigma_a, Float g, Float eta, Float r);

// The profile over 100 albedos (crowded towards 1, where skin and milk are) and 64 optical radii
// (0, then 2.5e-3 growing by 1.2 each), with each albedo's total (effective) reflectance rhoEff
// and the cumulative integrals of the profile over radius for sampling.
struct BSSRDFTable {
    std::vector<Float> rhoSamples, radiusSamples;
    std::vector<Float> profile;     // per rho, per radius: 2 pi r Sr(r)
    std::vector<Float> rhoEff;      // per rho: the profile's integral over radius
    std::vector<Float> profileCDF;  // per rho, per radius

    // The table of a material of Henyey-Greenstein asymmetry g and relative index eta.
    BSSRDFTable(Float g, Float eta);
    Float Profile(int rhoIndex, int radiusIndex) const {
        return profile[size_t(rhoIndex) * radiusSamples.size() + size_t(radiusIndex)];
    }
};

// The albedo rho with table.rhoEff(rho) = rhoEff at each wavelength, and from it and the mean
// free path mfp the coefficients (pbrt-v4's SubsurfaceFromDiffuse: sigma_s = rho / mfp,
// sigma_a = (1 - rho) / mfp).
void SubsurfaceFromDiffuse(const BSSRDFTable &table, const SampledSpectrum &rhoEff,
                           const SampledSpectrum &mfp, SampledSpectrum *sigma_a,
                           SampledSpectrum *sigma_s);

struct BSSRDFProbeSegment {
    Point3f p0, p1;
};

class TabulatedBSSRDF {
  public:
    TabulatedBSSRDF(Point3f po, Normal3f ns, Float eta, const SampledSpectrum &sigma_a,
                    const SampledSpectrum &sigma_s, const BSSRDFTable *table)
        : po(po), ns(ns), eta(eta), table(table) {
        sigma_t = sigma_a + sigma_s;
        for (int i = 0; i < NSpectrumSamples; ++i)
            rho[i] = sigma_t[i] != 0 ? sigma_s[i] / sigma_t[i] : 0;
    }

    SampledSpectrum Sp(Point3f pi) const { return Sr(Distance(po, pi)); }
    SampledSpectrum Sr(Float r) const;
    // A radius sampled from the first wavelength's profile; none if that wavelength is clear.
    std::optional<Float> SampleSr(Float u) const;
    // The density (per unit area of the plane) with which SampleSr's radius lands at distance r,
    // per wavelength.
    SampledSpectrum PDF_Sr(Float r) const;

    // A probe segment for the exit point (u1 picks the axis, u2 the radius and angle); none if
    // the sampled radius lies outside the profile's bounding sphere.
    std::optional<BSSRDFProbeSegment> SampleSp(Float u1, Point2f u2) const;
    // The density of SampleSp's probes meeting a surface at pi of normal ni (per unit area).
    SampledSpectrum PDF_Sp(Point3f pi, Normal3f ni) const;

    Float Eta() const { return eta; }
    std::string ToString() const;

  private:
    // The profile at optical radius rOptical for wavelength i and, if rhoEff is not null, the
    // total reflectance at that wavelength's albedo; false outside the table.
    bool Interpolate(int i, Float rOptical, Float *sr, Float *rhoEff) const;

    Point3f po;
    Normal3f ns;
    Float eta;
    SampledSpectrum sigma_t, rho;
    const BSSRDFTable *table;
};

}  // namespace pbrt
