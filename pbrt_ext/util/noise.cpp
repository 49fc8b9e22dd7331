#include "pbrt_ext/util/noise.h"

#include "pbrt_ext/util/math.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace pbrt {

namespace {

// Ken Perlin's permutation of 0..255 (the reference implementation of "Improving Noise",
// SIGGRAPH 2002), the table pbrt-v4 hashes lattice points with; indexed up to 3 * 255 + 2
// through the wrap in Perm().
constexpr int kPermutation[256] = {
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225,
    140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148,
    247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122,
    60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54,
    65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169,
    200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64,
    52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212,
    207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213,
    119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9,
    129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104,
    218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241,
    81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157,
    184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93,
    222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180,
};

int Perm(int i) { return kPermutation[i & 255]; }

// pbrt-v4's 16 gradients: hash h picks u (dx for h < 8, 12 and 13, else dy) and v (dy for h < 4,
// 12 and 13, else dz), with signs from bits 0 and 1. As coefficients of (dx, dy, dz) each has
// exactly two nonzero, so the dot product adds the same two terms pbrt-v4 adds.
struct Gradient {
    Float x, y, z;
};
constexpr std::array<Gradient, 16> MakeGradients() {
    std::array<Gradient, 16> g{};
    for (int h = 0; h < 16; ++h) {
        Float su = (h & 1) ? -1 : 1, sv = (h & 2) ? -1 : 1;
        bool uIsX = h < 8 || h == 12 || h == 13, vIsY = h < 4 || h == 12 || h == 13;
        g[h] = {uIsX ? su : 0, (uIsX ? 0 : su) + (vIsY ? sv : 0), vIsY ? 0 : sv};
    }
    return g;
}
constexpr std::array<Gradient, 16> kGradients = MakeGradients();

Float Grad(int hash, Float dx, Float dy, Float dz) {
    const Gradient &g = kGradients[hash & 15];
    return g.x * dx + g.y * dy + g.z * dz;
}

// Perlin's quintic fade, 6t^5 - 15t^4 + 10t^3.
Float Fade(Float t) { return t * t * t * (t * (t * 6 - 15) + 10); }

}  // namespace

Float Noise(Float x, Float y, Float z) {
    // Coordinates reduced first, so that the lattice offsets below fit an int (pbrt-v4; fmod
    // changes nothing below 2^30, where it is skipped for speed).
    const Float range = Float(1 << 30);
    if (!(std::abs(x) < range && std::abs(y) < range && std::abs(z) < range)) {
        x = std::fmod(x, range);
        y = std::fmod(y, range);
        z = std::fmod(z, range);
    }
    int ix = int(std::floor(x)), iy = int(std::floor(y)), iz = int(std::floor(z));
    Float dx = x - ix, dy = y - iy, dz = z - iz;
    ix &= 255;
    iy &= 255;
    iz &= 255;
    // The lattice hash Perm(Perm(Perm(x) + y) + z) of the 8 corners, sharing its first levels.
    int x0 = Perm(ix), x1 = Perm(ix + 1);
    int x0y0 = Perm(x0 + iy), x0y1 = Perm(x0 + iy + 1), x1y0 = Perm(x1 + iy), x1y1 = Perm(x1 + iy + 1);
    Float w000 = Grad(Perm(x0y0 + iz), dx, dy, dz);
    Float w100 = Grad(Perm(x1y0 + iz), dx - 1, dy, dz);
    Float w010 = Grad(Perm(x0y1 + iz), dx, dy - 1, dz);
    Float w110 = Grad(Perm(x1y1 + iz), dx - 1, dy - 1, dz);
    Float w001 = Grad(Perm(x0y0 + iz + 1), dx, dy, dz - 1);
    Float w101 = Grad(Perm(x1y0 + iz + 1), dx - 1, dy, dz - 1);
    Float w011 = Grad(Perm(x0y1 + iz + 1), dx, dy - 1, dz - 1);
    Float w111 = Grad(Perm(x1y1 + iz + 1), dx - 1, dy - 1, dz - 1);
    Float wx = Fade(dx), wy = Fade(dy), wz = Fade(dz);
    Float y0 = Lerp(wy, Lerp(wx, w000, w100), Lerp(wx, w010, w110));
    Float y1 = Lerp(wy, Lerp(wx, w001, w101), Lerp(wx, w011, w111));
    return Lerp(wz, y0, y1);
}

Vector3f DNoise(Point3f p) {
    const Float delta = .01f;
    Float n = Noise(p);
    return Vector3f(Noise(p + Vector3f(delta, 0, 0)) - n, Noise(p + Vector3f(0, delta, 0)) - n,
                    Noise(p + Vector3f(0, 0, delta)) - n) /
           delta;
}

namespace {

// How many octaves of noise the footprint resolves: none finer than half its larger side, at
// most maxOctaves (pbrt-v4's band limit for FBm and Turbulence).
Float ResolvedOctaves(Vector3f dpdx, Vector3f dpdy, int maxOctaves) {
    Float len2 = std::max(LengthSquared(dpdx), LengthSquared(dpdy));
    return Clamp(-1 - std::log2(len2) / 2, 0, maxOctaves);
}

}  // namespace

Float FBm(Point3f p, Vector3f dpdx, Vector3f dpdy, Float omega, int maxOctaves) {
    Float n = ResolvedOctaves(dpdx, dpdy, maxOctaves);
    int nInt = int(std::floor(n));
    Float sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < nInt; ++i) {
        sum += o * Noise(lambda * p);
        lambda *= 1.99f;
        o *= omega;
    }
    // The partly resolved octave fades in.
    return sum + o * SmoothStep(n - Float(nInt), .3f, .7f) * Noise(lambda * p);
}

Float Turbulence(Point3f p, Vector3f dpdx, Vector3f dpdy, Float omega, int maxOctaves) {
    Float n = ResolvedOctaves(dpdx, dpdy, maxOctaves);
    int nInt = int(std::floor(n));
    Float sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < nInt; ++i) {
        sum += o * std::abs(Noise(lambda * p));
        lambda *= 1.99f;
        o *= omega;
    }
    // Unresolved octaves contribute their average |noise|, about 0.2; the partly resolved one
    // blends toward its value.
    sum += o * Lerp(SmoothStep(n - Float(nInt), .3f, .7f), 0.2f, std::abs(Noise(lambda * p)));
    for (int i = nInt; i < maxOctaves; ++i) {
        sum += o * 0.2f;
        o *= omega;
    }
    return sum;
}

}  // namespace pbrt
