// pbrt_ext: RGL .bsdf files made from an analytic BRDF, pbrt-v4's rough conductor (Trowbridge-Reitz
// normals, the conductor's Fresnel reflectance from eta and k): what the measured material's
// tests compare against, and scenes/measured.pbrt's data (cmd/make_bsdf writes it).
//
// The tables are those of the representation (bxdfs/measured.h) for this BRDF, with wo at
// theta_i (phi_i = 0; the file is isotropic):
//  - ndf: D(wm); sigma: the projected area cos theta_o (1 + Lambda(wo)), both over the angles'
//    unit-square coordinates;
//  - vndf: the visible normals' density D_wo(wm) = G1(wo) <wo . wm> D(wm) / cos theta_o, times
//    the Jacobian 2 pi^2 u_theta sin theta_m of those coordinates;
//  - spectra: R(u) = F(wo . wm) G(wo, wi) / G1(wo), so that R D / (4 sigma cos theta_i) is the
//    Torrance-Sparrow BRDF, tabulated at the nodes u of the sample space and placed at the wm
//    that the vndf table's own warp (PiecewiseLinear2D::Sample) takes each node to, as the
//    acquisition placed its measurements;
//  - luminance: R weighted by the CIE Y matching function over the file's wavelengths, the
//    density over u that makes sampling follow f cos theta_i.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/spectra/spectrum.h"

#include <string>
#include <vector>

namespace pbrt {

struct ConductorTableSpec {
    Float alpha = 0.3f;  // Trowbridge-Reitz alpha (isotropic)
    Spectrum eta = Spectrum(1.f), k = Spectrum(1.f);
    std::vector<float> wavelengths;  // nm, increasing
    int thetaCount = 16;             // theta_i values, uniform from 0 to 89 degrees
    int resolution = 32;             // nodes per side of each grid
};

// Throws std::runtime_error if the file cannot be written.
void WriteConductorBSDF(const std::string &path, const ConductorTableSpec &spec);

}  // namespace pbrt
