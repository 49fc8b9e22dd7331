#include "pbrt_ext/materials/measuredwriter.h"

#include "pbrt_ext/util/ciedata.h"
#include "pbrt_ext/util/piecewiselinear2d.h"
#include "pbrt_ext/util/scattering.h"
#include "pbrt_ext/util/tensorfile.h"

#include <fmt/format.h>

#include <cmath>

namespace pbrt {

namespace {

// The direction of unit-square angle coordinates (measured.h's), kept off the horizon, where
// Lambda and tan theta are infinite while the tables' limits are finite.
Vector3f DirectionAt(Float uTheta, Float uPhi) {
    Float theta = std::min(Sqr(uTheta) * (Pi / 2), Pi / 2 - 1e-4f), phi = (2 * uPhi - 1) * Pi;
    return SphericalDirection(std::sin(theta), std::cos(theta), phi);
}

struct Slice {
    std::vector<float> vndf, luminance, spectra;  // spectra: per wavelength, then the grid
};

// The tables of one theta_i (see the header).
Slice TabulateSlice(const ConductorTableSpec &spec, const TrowbridgeReitzDistribution &distrib,
                    Float theta_o) {
    const int n = spec.resolution;
    const Vector3f wo(std::sin(theta_o), 0, std::cos(theta_o));
    auto node = [n](int i) { return Float(i) / Float(n - 1); };
    Slice s;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            Vector3f wm = DirectionAt(node(x), node(y));
            Float sinTheta_m = std::sqrt(Sqr(wm.x) + Sqr(wm.y));
            s.vndf.push_back(float(distrib.D(wo, wm) * 2 * Sqr(Pi) * node(x) * sinTheta_m));
        }
    const PiecewiseLinear2D<0> vndf(s.vndf.data(), n, n, {}, true);

    const size_t nLambda = spec.wavelengths.size();
    s.spectra.assign(nLambda * size_t(n) * size_t(n), 0.f);
    double ySum = 0;
    for (float lambda : spec.wavelengths) ySum += CIEAt(lambda).y;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            Point2f u_wm = vndf.Sample(Point2f(node(x), node(y)), {}).p;
            Vector3f wm = DirectionAt(u_wm[0], u_wm[1]);
            Vector3f wi = Reflect(wo, wm);
            double luminance = 0;
            for (size_t l = 0; l < nLambda && wi.z > 0; ++l) {
                Float lambda = spec.wavelengths[l];
                Float R = FrComplex(Dot(wo, wm), spec.eta(lambda), spec.k(lambda)) *
                          distrib.G(wo, wi) / distrib.G1(wo);
                s.spectra[(l * size_t(n) + size_t(y)) * size_t(n) + size_t(x)] = float(R);
                luminance += R * CIEAt(lambda).y / ySum;
            }
            s.luminance.push_back(float(luminance));
        }
    return s;
}

// A field over the unit square of a function of the direction there.
template <typename F>
std::vector<float> AngleGrid(int n, F f) {
    std::vector<float> v;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            v.push_back(float(f(DirectionAt(Float(x) / Float(n - 1), Float(y) / Float(n - 1)))));
    return v;
}

}  // namespace

void WriteConductorBSDF(const std::string &path, const ConductorTableSpec &spec) {
    const TrowbridgeReitzDistribution distrib(spec.alpha, spec.alpha);
    const uint64_t n = uint64_t(spec.resolution), nTheta = uint64_t(spec.thetaCount);
    const uint64_t nLambda = spec.wavelengths.size();
    std::vector<float> theta_i, vndf, luminance, spectra;
    for (int k = 0; k < spec.thetaCount; ++k) {
        // Uniform in theta, from 0 to 89 degrees: the BRDF changes fastest with theta_o towards
        // grazing, where Fresnel reflectance and shadowing change most.
        theta_i.push_back(Radians(89.f) * Float(k) / Float(spec.thetaCount - 1));
        Slice s = TabulateSlice(spec, distrib, theta_i.back());
        vndf.insert(vndf.end(), s.vndf.begin(), s.vndf.end());
        luminance.insert(luminance.end(), s.luminance.begin(), s.luminance.end());
        spectra.insert(spectra.end(), s.spectra.begin(), s.spectra.end());
    }
    std::string description =
        fmt::format("pbrt_ext WriteConductorBSDF: Trowbridge-Reitz alpha {} conductor", spec.alpha);
    TensorFields fields;
    fields["description"] =
        TensorField::FromBytes({description.size()}, {description.begin(), description.end()});
    fields["jacobian"] = TensorField::FromBytes({1}, {1});
    fields["phi_i"] = TensorField::FromFloats({1}, {0.f});
    fields["theta_i"] = TensorField::FromFloats({nTheta}, theta_i);
    fields["wavelengths"] = TensorField::FromFloats({nLambda}, spec.wavelengths);
    fields["ndf"] = TensorField::FromFloats(
        {n, n}, AngleGrid(spec.resolution, [&](Vector3f wm) { return distrib.D(wm); }));
    fields["sigma"] = TensorField::FromFloats({n, n}, AngleGrid(spec.resolution, [&](Vector3f wo) {
                                                  return CosTheta(wo) / distrib.G1(wo);
                                              }));
    fields["vndf"] = TensorField::FromFloats({1, nTheta, n, n}, vndf);
    fields["luminance"] = TensorField::FromFloats({1, nTheta, n, n}, luminance);
    fields["spectra"] = TensorField::FromFloats({1, nTheta, nLambda, n, n}, spectra);
    WriteTensorFile(path, fields);
}

}  // namespace pbrt
