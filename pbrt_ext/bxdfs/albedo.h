// The directional albedo of any BxDF by deterministic quadrature over the sphere
// (util/spherequadrature.h), for furnace tables and tests (host only).
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/util/spherequadrature.h"
#include "pbrt_ext/util/vecmath.h"

#include <cmath>
#include <vector>

namespace pbrt {

// Directional albedo ∫ f(wo, wi) |cos θi| dωi of one channel of a BxDF, by IntegrateSphere.
template <typename BxDF>
double DirectionalAlbedo(const BxDF &bxdf, Vector3f wo, const Frame &frame,
                         const std::vector<double> &zBreaks, int nZ, int nPhi, int channel = 0) {
    return IntegrateSphere(
        [&](Vector3f wi) {
            return double(bxdf.f(wo, wi, TransportMode::Radiance)[channel]) * std::abs(wi.z);
        },
        frame, zBreaks, nZ, nPhi);
}

}  // namespace pbrt
