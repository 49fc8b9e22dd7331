// What pbrt_ext's fabric headers use that pbrt-v4 names differently or lacks (the port's only
// hand-written glue; see pbrt_ext's docs/porting.md). fabric.h and fabricdiffuse.h in this folder are
// generated from pbrt_ext/bxdfs/ by `scripts/port-pbrt-v4 --regenerate`, which maps their includes of
// pbrt_ext/base/bxdf.h here.
#ifndef PBRT_BXDFS_FABRIC_COMPAT_H
#define PBRT_BXDFS_FABRIC_COMPAT_H

#include <pbrt/pbrt.h>

#include <pbrt/base/bxdf.h>
#include <pbrt/util/math.h>
#include <pbrt/util/pstd.h>
#include <pbrt/util/spectrum.h>
#include <pbrt/util/vecmath.h>

namespace pbrt {

// v^n for an integer n by repeated squaring: exact for the paper's integer exponents, and faster
// than std::pow.
template <typename T>
PBRT_CPU_GPU constexpr T IntPow(T v, int n) {
    if (n < 0)
        return T(1) / IntPow(v, -n);
    T r = 1;
    for (; n > 0; n >>= 1, v *= v)
        if (n & 1)
            r *= v;
    return r;
}

// The BxDFs' rho members estimate by Monte Carlo from their own Sample_f; pbrt-v4's BxDF::rho
// (bxdfs.cpp) is that estimator, so they defer to it.
template <typename B>
SampledSpectrum EstimateRho(const B &bxdf, Vector3f wo, pstd::span<const Float> uc,
                            pstd::span<const Point2f> u2) {
    return BxDF(const_cast<B *>(&bxdf)).rho(wo, uc, u2);
}

template <typename B>
SampledSpectrum EstimateRho(const B &bxdf, pstd::span<const Point2f> u1,
                            pstd::span<const Float> uc, pstd::span<const Point2f> u2) {
    return BxDF(const_cast<B *>(&bxdf)).rho(u1, uc, u2);
}

}  // namespace pbrt

#endif  // PBRT_BXDFS_FABRIC_COMPAT_H
