#include "pbrt_ext/util/lowdiscrepancy.h"

// Joe and Kuo's primitive polynomials and initial direction numbers ("Constructing Sobol
// sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30, 2008), as
// Boost.Random carries them for its sobol engine: polynomial(d - 1) and minit(d - 1, k) are
// dimension d's.
#include <boost/random/sobol.hpp>

#include <bit>
#include <vector>

namespace pbrt {

namespace {

using SobolColumns = std::array<uint32_t, kSobolMatrixColumns>;

// Bratley and Fox's recurrence: with the primitive polynomial x^s + a_1 x^(s-1) + ... + 1 and
// the first s direction integers m_k given, m_k = m_(k-s) ^ (m_(k-s) << s) ^ XOR over the
// middle coefficients a_i of (m_(k-i) << i). Column k is m_k / 2^(k+1) in 32-bit fixed point.
SobolColumns ComputeSobolMatrix(int dimension) {
    SobolColumns columns{};
    if (dimension == 0) {
        for (int k = 0; k < kSobolMatrixColumns; ++k)
            columns[k] = k < 32 ? 0x80000000u >> k : 0;
        return columns;
    }
    using Tables = boost::random::default_sobol_table;
    unsigned polynomial = Tables::polynomial(std::size_t(dimension - 1));
    int degree = std::bit_width(polynomial) - 1;
    std::array<uint64_t, kSobolMatrixColumns> m{};
    for (int k = 0; k < kSobolMatrixColumns; ++k) {
        if (k < degree) {
            m[k] = Tables::minit(std::size_t(dimension - 1), std::size_t(k));
            continue;
        }
        m[k] = m[k - degree] ^ (m[k - degree] << degree);
        for (int i = 1; i < degree; ++i)
            if ((polynomial >> (degree - i)) & 1) m[k] ^= m[k - i] << i;
    }
    for (int k = 0; k < kSobolMatrixColumns; ++k)
        columns[k] = k <= 31 ? uint32_t(m[k] << (31 - k)) : uint32_t(m[k] >> (k - 31));
    return columns;
}

}  // namespace

const SobolColumns &SobolMatrix(int dimension) {
    static const std::vector<SobolColumns> matrices = [] {
        std::vector<SobolColumns> all(kSobolDimensions);
        for (int d = 0; d < kSobolDimensions; ++d)
            all[size_t(d)] = ComputeSobolMatrix(d);
        return all;
    }();
    return matrices[size_t(dimension)];
}

HaltonDigitPermutations::HaltonDigitPermutations(uint32_t seed) : seed(seed) {
    int size = 0;
    for (int b = 0; b < kTabledBases; ++b) {
        offsets[size_t(b)] = size;
        size += kRadicalInverseDigits[size_t(b)] * kPrimes[size_t(b)];
    }
    table.resize(size_t(size));
    for (int b = 0; b < kTabledBases; ++b)
        for (int digitIndex = 0; digitIndex < kRadicalInverseDigits[size_t(b)]; ++digitIndex)
            for (int digit = 0; digit < kPrimes[size_t(b)]; ++digit)
                table[size_t(offsets[size_t(b)] + digitIndex * kPrimes[size_t(b)] + digit)] =
                    uint16_t(Compute(b, digitIndex, digit));
    // Each base's tails, from position n (nothing left) down to 0, and b^-n by the very
    // multiplications PermutedRadicalInverse() makes.
    for (int b = 0; b < kTabledBases; ++b) {
        uint64_t base = uint64_t(kPrimes[size_t(b)]);
        int nDigits = kRadicalInverseDigits[size_t(b)];
        tailOffsets[size_t(b)] = int(tails.size());
        tails.resize(tails.size() + size_t(nDigits) + 1);
        Tail *tail = tails.data() + tailOffsets[size_t(b)];
        tail[nDigits] = {1, 0};
        for (int k = nDigits - 1; k >= 0; --k)
            tail[k] = {tail[k + 1].shift * base, tail[k + 1].zeros + uint64_t(Permute(b, k, 0)) * tail[k + 1].shift};
        double invBase = 1.0 / double(base), invBaseM = 1;
        for (int k = 0; k < nDigits; ++k) invBaseM *= invBase;
        invBasePowers[size_t(b)] = invBaseM;
    }
}

}  // namespace pbrt
