// pbrt_ext: hashing of plain values, with pbrt-v4's names (src/pbrt/util/hash.h).
//
// Used where a computation must be a deterministic function of its inputs although it is
// random inside: the stochastic layered BxDF seeds its RNG from Hash(wo) and Hash(wi), so
// that f(wo, wi) gives the same value every time it is asked.
//
// MurmurHash64A is Austin Appleby's public-domain hash (github.com/aappleby/smhasher),
// written here from its published description.
#pragma once

#include "pbrt_ext/pbrt.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace pbrt {

// A 64-bit finalizer (xor-shift-multiply rounds, the constants of Stafford's "Mix13"):
// every input bit affects every output bit, so consecutive integers land far apart.
PBRT_CPU_GPU inline uint64_t MixBits(uint64_t v) {
    v ^= (v >> 31);
    v *= 0x7fb5d329728ea185ULL;
    v ^= (v >> 27);
    v *= 0x81dadef4bc2dd44dULL;
    v ^= (v >> 33);
    return v;
}

// The 64-bit MurmurHash2 variant: 8-byte blocks mixed into the state, then the tail bytes,
// then a final avalanche.
PBRT_CPU_GPU inline uint64_t MurmurHash64A(const unsigned char *key, size_t len,
                                           uint64_t seed) {
    constexpr uint64_t m = 0xc6a4a7935bd1e995ULL;
    constexpr int r = 47;
    uint64_t h = seed ^ (len * m);

    const unsigned char *end = key + 8 * (len / 8);
    for (; key != end; key += 8) {
        uint64_t k;
        std::memcpy(&k, key, sizeof(uint64_t));  // unaligned-safe load
        k *= m;
        k ^= k >> r;
        k *= m;
        h ^= k;
        h *= m;
    }

    size_t tail = len & 7;
    if (tail != 0) {
        for (size_t i = tail; i-- > 0;)
            h ^= uint64_t(key[i]) << (8 * i);
        h *= m;
    }

    h ^= h >> r;
    h *= m;
    h ^= h >> r;
    return h;
}

// Hash of the bytes of trivially copyable values, taken together in order.
template <typename... Args>
PBRT_CPU_GPU inline uint64_t Hash(Args... args) {
    static_assert((std::is_trivially_copyable_v<Args> && ...),
                  "Hash() reads the values' bytes");
    constexpr size_t size = (sizeof(Args) + ... + 0);
    // One spare byte keeps the array legal when Args is empty.
    unsigned char buf[size + 1];
    size_t offset = 0;
    ((std::memcpy(buf + offset, &args, sizeof(Args)), offset += sizeof(Args)), ...);
    return MurmurHash64A(buf, size, 0);
}

}  // namespace pbrt
