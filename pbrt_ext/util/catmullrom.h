// pbrt_ext: Catmull-Rom splines over irregular nodes (pbrt-v4's CatmullRomWeights,
// IntegrateCatmullRom, InvertCatmullRom and SampleCatmullRom2D; Physically Based Rendering, 3rd
// edition, Section 8.6.1), which the tabulated BSSRDF interpolates, integrates and samples.
//
// Between nodes x_i and x_{i+1} the spline is the cubic Hermite interpolant of f_i and f_{i+1}
// whose end slopes are the finite differences over the neighbouring nodes (one-sided at the ends
// of the table), so it passes through every node and has a continuous first derivative.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/sampling.h"

#include <array>
#include <cmath>
#include <span>
#include <utility>

namespace pbrt {

namespace catmullrom {

// The slopes, scaled to the interval's width, at the ends of interval i of f over nodes.
template <typename Value>
std::pair<Float, Float> EndSlopes(std::span<const Float> nodes, Value f, int i) {
    const int n = int(nodes.size());
    Float x0 = nodes[size_t(i)], x1 = nodes[size_t(i) + 1], width = x1 - x0;
    Float f0 = f(i), f1 = f(i + 1);
    Float d0 = i > 0 ? width * (f1 - f(i - 1)) / (x1 - nodes[size_t(i) - 1]) : f1 - f0;
    Float d1 = i + 2 < n ? width * (f(i + 2) - f0) / (nodes[size_t(i) + 2] - x0) : f1 - f0;
    return {d0, d1};
}

// The t in [0, 1] where F(t) = 0, for F increasing with derivative f (Newton's steps, falling back
// to bisection whenever a step leaves the bracket).
template <typename Eval>
Float NewtonBisection(Eval eval) {
    Float lo = 0, hi = 1, t = 0.5f;
    for (int it = 0; it < 64; ++it) {
        auto [F, f] = eval(t);
        if (std::abs(F) < 1e-6f) break;
        (F < 0 ? lo : hi) = t;
        Float next = t - F / f;
        t = next > lo && next < hi ? next : (lo + hi) / 2;
        if (hi - lo < 1e-6f) break;
    }
    return t;
}

}  // namespace catmullrom

// The weights of the four nodes offset..offset+3 whose values, so weighted, interpolate at x (a
// weight of a node outside the table is 0); false if x is outside [nodes.front(), nodes.back()].
inline bool CatmullRomWeights(std::span<const Float> nodes, Float x, int *offset,
                              std::array<Float, 4> *weights) {
    if (!(x >= nodes.front() && x <= nodes.back())) return false;
    const int n = int(nodes.size());
    int i = detail::FindInterval(n, [&](int k) { return nodes[size_t(k)] <= x; });
    *offset = i - 1;
    Float x0 = nodes[size_t(i)], x1 = nodes[size_t(i) + 1];
    Float t = (x - x0) / (x1 - x0), t2 = t * t, t3 = t2 * t;
    std::array<Float, 4> &w = *weights;
    w = {0, 2 * t3 - 3 * t2 + 1, -2 * t3 + 3 * t2, 0};
    // The Hermite basis of the start slope (t^3 - 2t^2 + t) and the end slope (t^3 - t^2),
    // spread over the nodes that the finite differences take.
    Float s0 = t3 - 2 * t2 + t, s1 = t3 - t2;
    if (i > 0) {
        Float w0 = s0 * (x1 - x0) / (x1 - nodes[size_t(i) - 1]);
        w[0] = -w0;
        w[2] += w0;
    } else {
        w[1] -= s0;
        w[2] += s0;
    }
    if (i + 2 < n) {
        Float w3 = s1 * (x1 - x0) / (nodes[size_t(i) + 2] - x0);
        w[1] -= w3;
        w[3] = w3;
    } else {
        w[1] -= s1;
        w[2] += s1;
    }
    return true;
}

// The spline's integral over the whole table; cdf[i] receives it up to node i.
inline Float IntegrateCatmullRom(std::span<const Float> nodes, std::span<const Float> f,
                                 std::span<Float> cdf) {
    auto value = [&](int i) { return f[size_t(i)]; };
    Float sum = 0;
    cdf[0] = 0;
    for (size_t i = 0; i + 1 < nodes.size(); ++i) {
        auto [d0, d1] = catmullrom::EndSlopes(nodes, value, int(i));
        sum += (nodes[i + 1] - nodes[i]) * ((f[i] + f[i + 1]) / 2 + (d0 - d1) / 12);
        cdf[i + 1] = sum;
    }
    return sum;
}

// The x where the spline of increasing f equals u (the ends of the table outside its range).
inline Float InvertCatmullRom(std::span<const Float> nodes, std::span<const Float> f, Float u) {
    if (!(u > f.front())) return nodes.front();
    if (!(u < f.back())) return nodes.back();
    int i = detail::FindInterval(int(f.size()), [&](int k) { return f[size_t(k)] <= u; });
    auto value = [&](int k) { return f[size_t(k)]; };
    // Plain variables, not a structured binding: the lambda below captures them (clang 14).
    const std::pair<Float, Float> slopes = catmullrom::EndSlopes(nodes, value, i);
    const Float d0 = slopes.first, d1 = slopes.second;
    Float f0 = f[size_t(i)], f1 = f[size_t(i) + 1];
    Float t = catmullrom::NewtonBisection([&](Float s) {
        Float s2 = s * s, s3 = s2 * s;
        Float F = (2 * s3 - 3 * s2 + 1) * f0 + (-2 * s3 + 3 * s2) * f1 + (s3 - 2 * s2 + s) * d0 +
                  (s3 - s2) * d1;
        Float dF = (6 * s2 - 6 * s) * f0 + (-6 * s2 + 6 * s) * f1 + (3 * s2 - 4 * s + 1) * d0 +
                   (3 * s2 - 2 * s) * d1;
        return std::pair{F - u, dF};
    });
    return nodes[size_t(i)] + t * (nodes[size_t(i) + 1] - nodes[size_t(i)]);
}

// Samples x2 from the spline in the second variable of a table over nodes1 x nodes2, its first
// variable interpolated at alpha; values and cdf (IntegrateCatmullRom's, per row of nodes1) are
// row-major. Returns 0 if alpha is outside nodes1.
inline Float SampleCatmullRom2D(std::span<const Float> nodes1, std::span<const Float> nodes2,
                                std::span<const Float> values, std::span<const Float> cdf,
                                Float alpha, Float u) {
    int offset;
    std::array<Float, 4> weights;
    if (!CatmullRomWeights(nodes1, alpha, &offset, &weights)) return 0;
    auto interpolate = [&](std::span<const Float> table, int k) {
        Float v = 0;
        for (int j = 0; j < 4; ++j)
            if (weights[size_t(j)] != 0)
                v += table[size_t(offset + j) * nodes2.size() + size_t(k)] * weights[size_t(j)];
        return v;
    };
    const int n = int(nodes2.size());
    u *= interpolate(cdf, n - 1);
    int i = detail::FindInterval(n, [&](int k) { return interpolate(cdf, k) <= u; });
    Float x0 = nodes2[size_t(i)], x1 = nodes2[size_t(i) + 1], width = x1 - x0;
    Float f0 = interpolate(values, i), f1 = interpolate(values, i + 1);
    const std::pair<Float, Float> slopes = catmullrom::EndSlopes(
        nodes2, [&](int k) { return interpolate(values, k); }, i);
    const Float d0 = slopes.first, d1 = slopes.second;
    u = (u - interpolate(cdf, i)) / width;
    // The segment's integral from 0 to t and its derivative, the spline itself.
    Float t = catmullrom::NewtonBisection([&](Float s) {
        Float F = EvaluatePolynomial(s, 0, f0, 0.5f * d0, (1.f / 3.f) * (-2 * d0 - d1) + f1 - f0,
                                     0.25f * (d0 + d1) + 0.5f * (f0 - f1));
        Float dF =
            EvaluatePolynomial(s, f0, d0, -2 * d0 - d1 + 3 * (f1 - f0), d0 + d1 + 2 * (f0 - f1));
        return std::pair{F - u, dF};
    });
    return x0 + width * t;
}

}  // namespace pbrt
