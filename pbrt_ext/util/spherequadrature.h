// Deterministic integration over the unit sphere, for furnace tables and tests (host only).
//
// Gauss-Legendre in z = cos(polar angle) about a chosen axis, split at breakpoints, times the midpoint
// rule in azimuth. Choosing the axis along a lobe's axis of symmetry (a fabric thread) makes the sharp
// direction of the integrand the Gauss-Legendre one; kinks across the azimuth (a horizon) then
// converge as O(1/nPhi²).
#pragma once

#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"

#include <cmath>
#include <utility>
#include <vector>

namespace pbrt {

// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1] (Newton on P_n, double precision).
inline std::vector<std::pair<double, double>> GaussLegendre(int n) {
    std::vector<std::pair<double, double>> rule(n);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double x = std::cos(3.14159265358979323846 * (i + 0.75) / (n + 0.5)), dp = 0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1, p1 = x;  // P_0, P_1, then the recurrence up to P_n
            for (int k = 2; k <= n; ++k) {
                double pk = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = pk;
            }
            if (n == 1)
                p0 = 1;
            dp = n * (x * p1 - p0) / (x * x - 1);
            double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-15)
                break;
        }
        double w = 2 / ((1 - x * x) * dp * dp);
        rule[i] = {-x, w};
        rule[n - 1 - i] = {x, w};
    }
    return rule;
}

// Calls visit(w, weight) for the nodes of a product rule over the sphere: Gauss-Legendre with nZ
// nodes in z = Dot(w, frame.z) on each interval between the sorted breakpoints zBreaks (where the
// integrand has a kink, a jump or a sharp peak), times the midpoint rule with nPhi azimuths.
// The weights sum to 4π.
template <typename Visit>
void ForEachSphereNode(const Frame &frame, const std::vector<double> &zBreaks, int nZ, int nPhi,
                       Visit visit) {
    const double twoPi = 2 * 3.14159265358979323846;
    std::vector<double> edges{-1};
    for (double z : zBreaks)
        if (z > edges.back() && z < 1)
            edges.push_back(z);
    edges.push_back(1);
    auto rule = GaussLegendre(nZ);
    for (size_t k = 0; k + 1 < edges.size(); ++k) {
        double half = (edges[k + 1] - edges[k]) / 2, mid = (edges[k + 1] + edges[k]) / 2;
        for (auto [x, wx] : rule) {
            double z = mid + half * x, r = std::sqrt(std::max(0.0, 1 - z * z));
            for (int j = 0; j < nPhi; ++j) {
                double phi = twoPi * (j + 0.5) / nPhi;
                visit(frame.FromLocal(
                          Vector3f(Float(r * std::cos(phi)), Float(r * std::sin(phi)), Float(z))),
                      half * wx * twoPi / nPhi);
            }
        }
    }
}

// ∫_{S²} g(w) dω by ForEachSphereNode's rule.
template <typename Integrand>
double IntegrateSphere(Integrand g, const Frame &frame, const std::vector<double> &zBreaks, int nZ,
                       int nPhi) {
    double sum = 0;
    ForEachSphereNode(frame, zBreaks, nZ, nPhi,
                      [&](Vector3f w, double weight) { sum += weight * g(w); });
    return sum;
}

template <typename Integrand>
double IntegrateSphere(Integrand g, const Frame &frame, int nZ, int nPhi) {
    return IntegrateSphere(g, frame, {}, nZ, nPhi);
}

}  // namespace pbrt
