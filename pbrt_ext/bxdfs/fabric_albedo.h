// Directional albedo of a FabricBxDF by deterministic quadrature (host only): furnace tables and tests.
#pragma once

#include "pbrt_ext/bxdfs/albedo.h"
#include "pbrt_ext/bxdfs/fabric.h"
#include "pbrt_ext/util/spherequadrature.h"

#include <algorithm>
#include <vector>

namespace pbrt {

// a(wo) = ∫ f(wo, wi) cos θi dωi, integrated about the thread: the lobe is sharp only in the fiber
// latitude, with a cusp at sin θi = -sin θo and a width of ~1/(n+1) in sin θi, so Gauss-Legendre
// intervals are split there, geometrically spaced. ~1e-5 relative for n up to 1e3 at nPhi = 768.
inline double FabricDirectionalAlbedo(const FabricBxDF &bxdf, Vector3f wo, int nPhi = 768) {
    double cusp = -Dot(wo, bxdf.Thread()), width = 1 / (double(bxdf.Exponent()) + 1);
    std::vector<double> breaks{cusp};
    for (double d = width / 64; d < 2; d *= 2) {
        breaks.push_back(cusp - d);
        breaks.push_back(cusp + d);
    }
    std::sort(breaks.begin(), breaks.end());
    return DirectionalAlbedo(bxdf, wo, Frame::FromZ(bxdf.Thread()), breaks, 12, nPhi);
}

}  // namespace pbrt
