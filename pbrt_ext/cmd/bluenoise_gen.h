// Blue-noise dither textures by void and cluster (Ulichney 1993): the textures pbrt-v4's
// PMJ02BNSampler offsets its points by, generated at build time by cmd/sampletables_gen.
//
// The texture is a ranking of its pixels: a pixel's rank is the order in which it joins a
// binary pattern that is kept as evenly spread as possible at every step, measured by a
// toroidal Gaussian "energy". So every threshold of the texture is a blue-noise pattern, and
// its values are uniformly distributed.
#pragma once

#include "pbrt_ext/util/rng.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace pbrt::bluenoise {

class VoidAndCluster {
  public:
    // resolution: a power of two, at least kTile; sigma: the Gaussian's, in pixels (Ulichney's 1.5).
    VoidAndCluster(int resolution, double sigma = 1.5)
        : res(resolution), radius(int(std::ceil(4 * sigma))) {
        if (res < kTile || (res & (res - 1)) != 0)
            throw std::invalid_argument("void and cluster: resolution must be a power of two >= 16");
        for (int d = -radius; d <= radius; ++d) weights.push_back(std::exp(-d * d / (2 * sigma * sigma)));
    }

    // The rank, in [0, resolution^2), of each pixel, row by row.
    std::vector<uint32_t> Ranks(uint64_t seed) {
        int n = res * res;
        std::vector<uint8_t> initial = InitialPattern(seed);
        int ones = int(std::count(initial.begin(), initial.end(), 1));
        std::vector<uint32_t> rank(size_t(n), 0);

        // Phase 1: the initial pattern's pixels, from the tightest cluster down.
        Reset(initial);
        for (int r = ones - 1; r >= 0; --r) {
            int p = TightestCluster();
            rank[size_t(p)] = uint32_t(r);
            Set(p, 0);
        }
        // Phases 2 and 3: the rest, each into the largest void. (Ulichney's phase 3 adds the
        // zero in the tightest cluster of zeros; on a torus the zeros' energy is a constant
        // minus the ones', so that is the same pixel.)
        Reset(initial);
        for (int r = ones; r < n; ++r) {
            int p = LargestVoid();
            rank[size_t(p)] = uint32_t(r);
            Set(p, 1);
        }
        return rank;
    }

  private:
    static constexpr int kTile = 16;  // the minimum search keeps one candidate per tile

    // A tenth of the pixels at random, then relaxed: the tightest cluster moves to the largest
    // void until that puts it back where it was.
    std::vector<uint8_t> InitialPattern(uint64_t seed) {
        RNG rng(seed);
        int n = res * res;
        std::vector<uint8_t> pattern(size_t(n), 0);
        for (int placed = 0; placed < n / 10;) {
            uint32_t p = rng.Uniform<uint32_t>() % uint32_t(n);
            if (!pattern[p]) {
                pattern[p] = 1;
                ++placed;
            }
        }
        Reset(pattern);
        for (;;) {
            int cluster = TightestCluster();
            Set(cluster, 0);
            int gap = LargestVoid();
            Set(gap, 1);
            if (gap == cluster) break;
        }
        return bits;
    }

    void Reset(const std::vector<uint8_t> &pattern) {
        tileBest.clear();
        bits.assign(pattern.size(), 0);
        energy.assign(pattern.size(), 0);
        for (int p = 0; p < res * res; ++p)
            if (pattern[size_t(p)]) Set(p, 1);
        int tiles = res / kTile;
        tileBest.assign(size_t(tiles * tiles), {});
        for (int t = 0; t < tiles * tiles; ++t) UpdateTile(t);
    }

    // Sets pixel p, adding or removing its Gaussian from the energy and refreshing the tiles
    // that the Gaussian touches.
    void Set(int p, uint8_t value) {
        if (bits[size_t(p)] == value) return;
        bits[size_t(p)] = value;
        double sign = value ? 1 : -1;
        int px = p % res, py = p / res;
        for (int dy = -radius; dy <= radius; ++dy) {
            int y = (py + dy + res) & (res - 1);
            for (int dx = -radius; dx <= radius; ++dx) {
                int x = (px + dx + res) & (res - 1);
                energy[size_t(y * res + x)] += sign * weights[size_t(dy + radius)] * weights[size_t(dx + radius)];
            }
        }
        if (tileBest.empty()) return;  // during Reset, which updates every tile afterwards
        int tiles = res / kTile;
        for (int ty : TilesSpanned(py))
            for (int tx : TilesSpanned(px))
                UpdateTile(ty * tiles + tx);
    }
    // The one or two tile coordinates that [c - radius, c + radius] covers, wrapped around.
    std::vector<int> TilesSpanned(int c) const {
        int first = ((c - radius + res) & (res - 1)) / kTile, last = ((c + radius) & (res - 1)) / kTile;
        if (first == last) return {first};
        return {first, last};
    }

    struct TileBest {
        int tightest = -1, largestVoid = -1;
    };
    void UpdateTile(int t) {
        int tiles = res / kTile, x0 = (t % tiles) * kTile, y0 = (t / tiles) * kTile;
        TileBest best;
        for (int y = y0; y < y0 + kTile; ++y)
            for (int x = x0; x < x0 + kTile; ++x) {
                int p = y * res + x;
                int &slot = bits[size_t(p)] ? best.tightest : best.largestVoid;
                bool better = bits[size_t(p)] ? energy[size_t(p)] > Energy(slot) : energy[size_t(p)] < Energy(slot);
                if (slot < 0 || better) slot = p;
            }
        tileBest[size_t(t)] = best;
    }
    double Energy(int p) const { return p < 0 ? 0 : energy[size_t(p)]; }

    int TightestCluster() const {
        int best = -1;
        for (const TileBest &t : tileBest)
            if (t.tightest >= 0 && (best < 0 || energy[size_t(t.tightest)] > energy[size_t(best)])) best = t.tightest;
        return best;
    }
    int LargestVoid() const {
        int best = -1;
        for (const TileBest &t : tileBest)
            if (t.largestVoid >= 0 && (best < 0 || energy[size_t(t.largestVoid)] < energy[size_t(best)]))
                best = t.largestVoid;
        return best;
    }

    int res, radius;
    std::vector<double> weights;
    std::vector<uint8_t> bits;
    std::vector<double> energy;
    std::vector<TileBest> tileBest;
};

}  // namespace pbrt::bluenoise
