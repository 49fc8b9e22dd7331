// The low-discrepancy building blocks: bit tricks, hashed permutations, scrambles, Sobol'
// generator matrices (against Boost.Random's own Sobol' engine) and radical inverses.
#include "pbrt_ext/util/lowdiscrepancy.h"
#include "pbrt_ext/util/rng.h"

#include <boost/random/sobol.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <vector>

namespace pbrt {
namespace {

TEST(LowDiscrepancy, BitHelpers) {
    EXPECT_EQ(ReverseBits32(1u), 0x80000000u);
    EXPECT_EQ(ReverseBits32(0x0000f00du), 0xb00f0000u);
    EXPECT_EQ(EncodeMorton2(3, 0), 5u);
    EXPECT_EQ(EncodeMorton2(0, 1), 2u);
    EXPECT_EQ(EncodeMorton2(0xffffffffu, 0), 0x5555555555555555ULL);
    // Sobol' dimension 1 in index order: 0, 1/2, 3/4, 1/4, 5/8 (m = 1, 3, 5, 15, ...).
    EXPECT_EQ(SobolBits(1, 1), 0x80000000u);
    EXPECT_EQ(SobolBits(2, 1), 0xc0000000u);
    EXPECT_EQ(SobolBits(3, 1), 0x40000000u);
    EXPECT_EQ(SobolBits(4, 1), 0xa0000000u);
    EXPECT_EQ(SobolBits(8, 1), 0xf0000000u);
    EXPECT_EQ(SobolBits(6, 0), 0x60000000u);  // van der Corput: 0.011b
}

TEST(SobolBits, DimensionOneTablesEqualTheColumnRecurrence) {
    // The byte tables against the matrix they tabulate: c_0 = 2^31, c_k = c_(k-1) ^ (c_(k-1) >> 1).
    auto direct = [](uint64_t a) {
        uint32_t v = 0, column = 0x80000000u;
        for (; a != 0; a >>= 1) {
            if (a & 1) v ^= column;
            column ^= column >> 1;
        }
        return v;
    };
    RNG rng(3);
    for (int i = 0; i < 100000; ++i) {
        uint64_t a = rng.Uniform<uint64_t>() >> (i % 64);
        ASSERT_EQ(SobolBits(a, 1), direct(a)) << a;
    }
    for (uint64_t a : {uint64_t(0), ~uint64_t(0), uint64_t(1) << 63, uint64_t(255) << 56})
        EXPECT_EQ(SobolBits(a, 1), direct(a)) << a;
}

TEST(LowDiscrepancy, PermutationElementIsAPermutation) {
    for (uint32_t l : {1u, 2u, 3u, 7u, 16u, 33u, 100u})
        for (uint32_t p : {0u, 1u, 0xdeadbeefu, 12345u}) {
            std::vector<int> seen(l, 0);
            for (uint32_t i = 0; i < l; ++i) ++seen[PermutationElement(i, l, p)];
            for (int c : seen) EXPECT_EQ(c, 1) << "l " << l << " p " << p;
        }
    // Different keys give different orders.
    std::vector<int> a, b;
    for (uint32_t i = 0; i < 16; ++i) {
        a.push_back(PermutationElement(i, 16, 1));
        b.push_back(PermutationElement(i, 16, 2));
    }
    EXPECT_NE(a, b);
}

TEST(LowDiscrepancy, ScramblesAreBijective) {
    // On the top 8 bits: distinct inputs stay distinct, for both Owen variants.
    for (uint32_t seed : {0u, 1u, 0x9e3779b9u}) {
        std::set<uint32_t> owen, fast;
        for (uint32_t v = 0; v < 256; ++v) {
            owen.insert(OwenScramble(v << 24, seed) >> 24);
            fast.insert(FastOwenScramble(v << 24, seed) >> 24);
        }
        EXPECT_EQ(owen.size(), 256u);
        EXPECT_EQ(fast.size(), 256u);
    }
}

// Boost's engine yields point n + 1 of the Gray-code order (Antonov and Saleev), component
// by component: the XOR of the columns of gray(n + 1)'s set bits, in 64-bit fixed point.
TEST(LowDiscrepancy, SobolMatricesMatchBoostRandomsEngine) {
    constexpr int kDimensions = 64;
    boost::random::sobol_engine<uint64_t, 64> engine(kDimensions);
    for (uint64_t n = 1; n <= 4096; ++n) {
        uint64_t gray = n ^ (n >> 1);
        for (int d = 0; d < kDimensions; ++d)
            ASSERT_EQ(SobolBitsFromMatrix(gray, SobolMatrix(d)), uint32_t(engine() >> 32))
                << "point " << n << " dimension " << d;
    }
}

TEST(LowDiscrepancy, SobolClosedFormsMatchTheirMatrices) {
    for (int d : {0, 1})
        for (uint64_t a : {1ull, 2ull, 3ull, 0x1234ull, 0xffffffffull, 0x100000000ull,
                           0x123456789abcdull, (1ull << 51) | 5})
            EXPECT_EQ(SobolBits(a, d), SobolBitsFromMatrix(a, SobolMatrix(d)))
                << "dimension " << d << " index " << a;
}

// Every one-dimensional projection of Sobol' points is a (0, 1)-sequence: the first 2^k
// points put one in each interval of length 2^-k. For the last dimensions too.
TEST(LowDiscrepancy, SobolDimensionsAreZeroOneSequences) {
    constexpr int k = 10;
    for (int d : {2, 3, 17, 500, kSobolDimensions - 1}) {
        std::vector<int> count(1 << k, 0);
        for (uint64_t a = 0; a < (1u << k); ++a)
            ++count[SobolBitsFromMatrix(a, SobolMatrix(d)) >> (32 - k)];
        for (int c : count) ASSERT_EQ(c, 1) << "dimension " << d;
    }
}

TEST(LowDiscrepancy, PrimesAndRadicalInverse) {
    EXPECT_EQ(kPrimes[0], 2);
    EXPECT_EQ(kPrimes[4], 11);
    EXPECT_EQ(kPrimes[kPrimeTableSize - 1], 7919);  // the 1000th prime
    EXPECT_FLOAT_EQ(RadicalInverse(0, 6), 0.375f);     // 110b -> 0.011b
    EXPECT_FLOAT_EQ(RadicalInverse(1, 5), 7.0f / 9);   // 12 in base 3 -> 0.21
    EXPECT_FLOAT_EQ(RadicalInverse(2, 7), 11.0f / 25);  // 12 in base 5 -> 0.21
    // InverseRadicalInverse undoes the digit reversal on b^n points.
    for (int base : {2, 3}) {
        int n = 5, points = int(std::pow(base, n));
        for (int i = 0; i < points; ++i) {
            uint64_t reversed = uint64_t(std::lround(RadicalInverse(base == 2 ? 0 : 1, uint64_t(i)) * points));
            EXPECT_EQ(InverseRadicalInverse(reversed, base, n), uint64_t(i));
        }
    }
}

// The multiplication that replaces the radical inverses' divisions must give the exact
// quotient for every prime and every 32-bit index: checked at the values where an inexact
// reciprocal would fail first (multiples of b and their neighbours, near 2^32), and at 4096
// random indices per prime (fixed seed).
TEST(LowDiscrepancy, DivideByPrimeIsExact) {
    std::mt19937 rng(7);
    for (int i = 0; i < kPrimeTableSize; ++i) {
        uint32_t b = uint32_t(kPrimes[size_t(i)]);
        uint32_t top = UINT32_MAX - UINT32_MAX % b;  // the largest multiple of b
        for (uint32_t a : {0u, 1u, b - 1, b, b + 1, top - 1, top, UINT32_MAX - 1, UINT32_MAX})
            ASSERT_EQ(DivideByPrime(a, i), a / b) << "a = " << a << ", b = " << b;
        for (int k = 0; k < 4096; ++k) {
            uint32_t a = uint32_t(rng());
            ASSERT_EQ(DivideByPrime(a, i), a / b) << "a = " << a << ", b = " << b;
        }
    }
    EXPECT_EQ(DivideByPrime(uint64_t(1) << 40, 1), (uint64_t(1) << 40) / 3);
}

TEST(LowDiscrepancy, HaltonDigitPermutationsAreSeededPermutations) {
    HaltonDigitPermutations perm(7), other(8);
    int differ = 0;
    for (int b : {0, 1, 5, HaltonDigitPermutations::kTabledBases - 1, HaltonDigitPermutations::kTabledBases,
                  kPrimeTableSize - 1}) {
        int base = kPrimes[b];
        EXPECT_EQ(kRadicalInverseDigits[size_t(b)], RadicalInverseDigits(base));  // compile time = run time
        for (int digitIndex = 0; digitIndex < RadicalInverseDigits(base); ++digitIndex) {
            std::vector<int> seen(base, 0);
            for (int digit = 0; digit < base; ++digit) {
                int permuted = perm.Permute(b, digitIndex, digit);
                ASSERT_EQ(permuted, perm.Compute(b, digitIndex, digit));  // the table is a cache
                ++seen[permuted];
                differ += permuted != other.Permute(b, digitIndex, digit);
            }
            for (int c : seen) ASSERT_EQ(c, 1) << "base " << base << " digit " << digitIndex;
        }
    }
    EXPECT_GT(differ, 0);
}

// The tabled bases' shortcut (the zero digits above an index's highest summed once) gives
// the digit-by-digit loop's value to the bit: at indices around every power of the base,
// where the number of digits changes, at random ones, and at 2^32 - 1.
TEST(LowDiscrepancy, ScrambledRadicalInverseShortcutIsExact) {
    HaltonDigitPermutations perm(5);
    RNG rng(9);
    for (int b = 0; b < HaltonDigitPermutations::kTabledBases; ++b) {
        uint64_t base = uint64_t(kPrimes[size_t(b)]);
        std::vector<uint32_t> indices = {0, 1, UINT32_MAX};
        for (uint64_t power = base; power <= UINT32_MAX; power *= base)
            for (uint64_t i : {power - 1, power, power + 1, 2 * power - 1})
                if (i <= UINT32_MAX) indices.push_back(uint32_t(i));
        for (int i = 0; i < 200; ++i) indices.push_back(rng.Uniform<uint32_t>() >> (i % 32));
        for (uint32_t a : indices) {
            Float digitByDigit = PermutedRadicalInverse<uint32_t>(
                a, b, [&](int digitIndex, int digit, uint64_t) { return perm.Permute(b, digitIndex, digit); });
            ASSERT_EQ(perm.RadicalInverse(b, a), digitByDigit) << "base " << base << " index " << a;
            ASSERT_EQ(ScrambledRadicalInverse(b, uint64_t(a), perm), digitByDigit);
        }
    }
}

// Scrambling permutes digits, so the first b^k indices still put one point in each interval
// of length b^-k, whichever the scramble.
TEST(LowDiscrepancy, ScrambledRadicalInversesStratify) {
    HaltonDigitPermutations perm(3);
    for (int b : {0, 1, 2, 3, 40}) {
        int base = kPrimes[b], strata = base;
        while (strata * base <= 4096) strata *= base;
        std::vector<int> permuted(strata, 0), owen(strata, 0);
        for (int i = 0; i < strata; ++i) {
            ++permuted[int(double(ScrambledRadicalInverse(b, uint64_t(i), perm)) * strata)];
            ++owen[int(double(OwenScrambledRadicalInverse(b, uint64_t(i), 0x5eed)) * strata)];
        }
        for (int i = 0; i < strata; ++i) {
            ASSERT_EQ(permuted[i], 1) << "base " << base;
            ASSERT_EQ(owen[i], 1) << "base " << base;
        }
    }
}

}  // namespace
}  // namespace pbrt
