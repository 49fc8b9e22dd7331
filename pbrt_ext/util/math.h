// pbrt_ext: scalar math (pbrt-v4's util/math.h and the float helpers of util/float.h, reduced).
#pragma once

#include "pbrt_ext/pbrt.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace pbrt {

// Device code may not refer to a host variable by address, and std::min/std::max take their
// arguments by reference; so the device pass gives each constant its own device copy (as pbrt-v4's
// PBRT_CONST does), and constants can be used everywhere like literals.
#ifndef PBRT_CONST
#if defined(__CUDA_ARCH__)
#define PBRT_CONST static __device__ constexpr
#else
#define PBRT_CONST static constexpr
#endif
#endif

PBRT_CONST Float Pi = 3.14159265358979323846f;
PBRT_CONST Float InvPi = 0.31830988618379067154f;
PBRT_CONST Float Inv2Pi = 0.15915494309189533577f;
PBRT_CONST Float Inv4Pi = 0.07957747154594766788f;
PBRT_CONST Float PiOver2 = 1.57079632679489661923f;
PBRT_CONST Float PiOver4 = 0.78539816339744830961f;
PBRT_CONST Float Sqrt2 = 1.41421356237309504880f;
// The largest float below 1: keeps samples in [0, 1).
PBRT_CONST Float OneMinusEpsilon = 0x1.fffffep-1f;
PBRT_CONST Float Infinity = std::numeric_limits<Float>::infinity();

template <typename T>
PBRT_CPU_GPU constexpr T Sqr(T v) {
    return v * v;
}

template <typename T, typename U, typename V>
PBRT_CPU_GPU constexpr T Clamp(T val, U low, V high) {
    if (val < low) return T(low);
    if (val > high) return T(high);
    return val;
}

// Rounding can push an argument just outside the domain; these clamp it back instead of
// returning NaN (a NaN argument becomes 0 or the clamped bound, never NaN).
PBRT_CPU_GPU inline Float SafeSqrt(Float x) {
    return std::sqrt(std::max<Float>(0, x));
}

// The inverse error function on (-1, 1), from Giles's single-precision polynomials ("Approximating
// the erfinv function", GPU Computing Gems, 2011): erf(ErfInv(x)) is x to 2e-6 over (-1, 1)
// (tests/util/sampling_test.cpp).
PBRT_CPU_GPU inline Float ErfInv(Float x) {
    // +-1 would give infinities (SampleNormal's u = 0): the nearest finite values instead.
    x = Clamp(x, -OneMinusEpsilon, OneMinusEpsilon);
    Float w = -std::log((1 - x) * (1 + x)), p;
    if (w < 5) {
        w -= 2.5f;
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * w;
        p = -3.5233877e-06f + p * w;
        p = -4.39150654e-06f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.00125372503f + p * w;
        p = -0.00417768164f + p * w;
        p = 0.246640727f + p * w;
        p = 1.50140941f + p * w;
    } else {
        w = std::sqrt(w) - 3;
        p = -0.000200214257f;
        p = 0.000100950558f + p * w;
        p = 0.00134934322f + p * w;
        p = -0.00367342844f + p * w;
        p = 0.00573950773f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.00943887047f + p * w;
        p = 1.00167406f + p * w;
        p = 2.83297682f + p * w;
    }
    return p * x;
}
PBRT_CPU_GPU inline Float SafeASin(Float x) {
    return std::asin(Clamp(x, -1, 1));
}
PBRT_CPU_GPU inline Float SafeACos(Float x) {
    return std::acos(Clamp(x, -1, 1));
}

PBRT_CPU_GPU inline Float Lerp(Float x, Float a, Float b) {
    return (1 - x) * a + x * b;
}

// sin(x)/x, exact at 0 and to float precision near it (the Taylor series to x^2).
PBRT_CPU_GPU inline Float SinXOverX(Float x) {
    if (1 - x * x == 1) return 1;
    return std::sin(x) / x;
}
// The normalized sinc, sin(pi x)/(pi x).
PBRT_CPU_GPU inline Float Sinc(Float x) {
    return SinXOverX(Pi * x);
}
// A sinc windowed by a sinc of period tau (the Lanczos window), zero beyond radius.
PBRT_CPU_GPU inline Float WindowedSinc(Float x, Float radius, Float tau) {
    if (std::abs(x) > radius) return 0;
    return Sinc(x) * Sinc(x / tau);
}

// 0 below a, 1 above b, and the cubic 3t^2 - 2t^3 of t = (x - a) / (b - a) between.
PBRT_CPU_GPU inline Float SmoothStep(Float x, Float a, Float b) {
    if (a == b) return (x < a) ? 0 : 1;
    Float t = Clamp((x - a) / (b - a), 0, 1);
    return t * t * (3 - 2 * t);
}

PBRT_CPU_GPU constexpr Float Radians(Float deg) {
    return (Pi / 180) * deg;
}
PBRT_CPU_GPU constexpr Float Degrees(Float rad) {
    return (180 / Pi) * rad;
}

// v^n for a compile-time n, by repeated squaring unrolled at compile time.
template <int n, typename T>
PBRT_CPU_GPU constexpr T Pow(T v) {
    if constexpr (n < 0) {
        return T(1) / Pow<-n>(v);
    } else if constexpr (n == 0) {
        return T(1);
    } else if constexpr (n == 1) {
        return v;
    } else {
        T half = Pow<n / 2>(v);
        if constexpr (n % 2 == 1)
            return half * half * v;
        else
            return half * half;
    }
}

// v^n for a run-time n in O(log n) multiplications.
template <typename T>
PBRT_CPU_GPU constexpr T IntPow(T v, int n) {
    if (n < 0) return T(1) / IntPow(v, -n);
    T result(1);
    while (true) {
        if (n & 1) result *= v;
        n >>= 1;
        if (n == 0) return result;
        v *= v;  // only when another bit remains, so integer v cannot overflow needlessly
    }
}

template <typename T>
PBRT_CPU_GPU constexpr bool IsNaN(T v) {
    if constexpr (std::is_floating_point_v<T>)
        return std::isnan(v);
    else
        return false;
}
template <typename T>
PBRT_CPU_GPU constexpr bool IsInf(T v) {
    if constexpr (std::is_floating_point_v<T>)
        return std::isinf(v);
    else
        return false;
}
template <typename T>
PBRT_CPU_GPU constexpr bool IsFinite(T v) {
    if constexpr (std::is_floating_point_v<T>)
        return std::isfinite(v);
    else
        return true;
}

// Real power for material parameters: std::pow is NaN for a negative base and a fractional
// exponent; a non-positive (or NaN) base, or a NaN exponent, gives 0 instead.
PBRT_CPU_GPU inline Float SafePow(Float x, Float e) {
    if (!(x > 0) || IsNaN(e)) return 0;
    return std::pow(x, e);
}

// A fused multiply-add where the type has one, so the error analyses below hold.
template <typename T>
PBRT_CPU_GPU constexpr T FMA(T a, T b, T c) {
    if constexpr (std::is_floating_point_v<T>)
        return std::fma(a, b, c);
    else
        return a * b + c;
}

// a*b - c*d without catastrophic cancellation (Kahan): the second FMA recovers the rounding
// error of c*d exactly.
template <typename T>
PBRT_CPU_GPU constexpr T DifferenceOfProducts(T a, T b, T c, T d) {
    T cd = c * d;
    T differenceOfProducts = FMA(a, b, -cd);
    T error = FMA(-c, d, cd);
    return differenceOfProducts + error;
}
// a*b + c*d, compensated in the same way.
template <typename T>
PBRT_CPU_GPU constexpr T SumOfProducts(T a, T b, T c, T d) {
    T cd = c * d;
    T sumOfProducts = FMA(a, b, cd);
    T error = FMA(c, d, -cd);
    return sumOfProducts + error;
}

// c0 + t*(c1 + t*(c2 + ...)) by Horner's rule.
template <typename F, typename C>
PBRT_CPU_GPU constexpr F EvaluatePolynomial(F, C c) {
    return F(c);
}
template <typename F, typename C, typename... Cs>
PBRT_CPU_GPU constexpr F EvaluatePolynomial(F t, C c, Cs... cs) {
    return FMA(t, EvaluatePolynomial(t, cs...), F(c));
}

// Integers: the result lies in [0, b) for b > 0 (unlike %). Floating point: std::fmod.
template <typename T>
PBRT_CPU_GPU constexpr T Mod(T a, T b) {
    if constexpr (std::is_floating_point_v<T>) {
        return std::fmod(a, b);
    } else {
        T result = a - (a / b) * b;
        return (result < 0) ? result + b : result;
    }
}

// The adjacent representable floats, for conservative bounds; +/-0 are treated as one value.
PBRT_CPU_GPU inline float NextFloatUp(float v) {
    if (IsInf(v) && v > 0) return v;
    if (v == 0) v = 0.f;
    uint32_t bits = std::bit_cast<uint32_t>(v);
    bits = (v >= 0) ? bits + 1 : bits - 1;
    return std::bit_cast<float>(bits);
}
PBRT_CPU_GPU inline float NextFloatDown(float v) {
    if (IsInf(v) && v < 0) return v;
    if (v == 0) v = -0.f;
    uint32_t bits = std::bit_cast<uint32_t>(v);
    bits = (v > 0) ? bits - 1 : bits + 1;
    return std::bit_cast<float>(bits);
}

// The largest index i in [0, size - 2] with pred(i) true, for a predicate that is true
// up to some index and false after it (pbrt-v4's FindInterval): a bisection that clamps,
// so callers can index i and i + 1 even when u is outside the tabulated range.
// The bisection halves a count that does not depend on pred and moves its base by a
// conditional move, not a branch: it runs log2(size) steps for every u and mispredicts
// nothing, where a branch on a random u's comparison mispredicts half the time (the film's
// filter sampling searches twice per camera ray). Same index as pbrt-v4's bisection for any
// monotone predicate.
namespace detail {
template <typename Predicate>
PBRT_CPU_GPU inline int FindInterval(int size, const Predicate &pred) {
    // The first index in [1, size - 1) with pred false lies in [first, first + count].
    int first = 1, count = size - 2;
    while (count > 1) {
        int half = count >> 1;
        first = pred(first + half - 1) ? first + half : first;
        count -= half;
    }
    if (count == 1 && pred(first)) ++first;
    return Clamp(first - 1, 0, size - 2);
}

// FindInterval's index, walked to from a guess in [0, size - 2] near it (a guide table's
// entry): a step or two where the guess is close, the same index for any guess.
template <typename Predicate>
PBRT_CPU_GPU inline int FindIntervalFrom(int guess, int size, const Predicate &pred) {
    int i = guess;
    while (i > 0 && !pred(i)) --i;
    while (i < size - 2 && pred(i + 1)) ++i;
    return i;
}
}  // namespace detail

}  // namespace pbrt
