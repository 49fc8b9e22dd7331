// Progressive multi-jittered (0,2) points with blue-noise selection, "pmj02bn" (Christensen,
// Kensler and Kilpatrick 2018, "Progressive Multi-Jittered Sample Sequences"): the point sets
// pbrt-v4's PMJ02BNSampler reads, generated at build time by cmd/sampletables_gen.
//
// Each prefix of 2^m points is a (0, m, 2)-net in base 2: every elementary interval of area
// 2^-m, of every shape 2^-a x 2^-(m-a), holds exactly one point. Point n is placed in a cell
// that is free in all m + 1 shapes (found by a search over the cell's x column and y bits,
// pruned shape by shape, as Pharr 2019 describes), jittered inside it; of a few such
// candidates, the one farthest from the points already placed is kept (best candidate), which
// gives the sequence its blue-noise spectrum.
#pragma once

#include "pbrt_ext/util/rng.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

namespace pbrt::pmj02bn {

// A point in 32-bit fixed point: x / 2^32, y / 2^32.
using FixedPoint2 = std::array<uint32_t, 2>;

class Generator {
  public:
    Generator(uint64_t seed, int candidates) : rng(seed), candidates(candidates) {}

    // The first 2^log2Count points of the sequence.
    std::vector<FixedPoint2> Generate(int log2Count) {
        if (log2Count < 0 || log2Count > 24) throw std::invalid_argument("pmj02bn: log2Count in [0, 24]");
        points.clear();
        points.push_back({rng.Uniform<uint32_t>(), rng.Uniform<uint32_t>()});
        for (uint32_t n = 1; n < (1u << log2Count); ++n) {
            if ((n & (n - 1)) == 0) StartLevel(std::countr_zero(n) + 1);
            Place(BestCandidate());
        }
        return points;
    }

  private:
    // Level m: the points n in [2^(m-1), 2^m) complete a net of 2^m points. Shape a has 2^a
    // columns and 2^(m-a) rows; a point's cell in it is (X >> (m-a), Y >> a), where X and Y
    // are the top m bits of its coordinates.
    void StartLevel(int level) {
        m = level;
        occupied.assign(size_t(m + 1), std::vector<uint8_t>(size_t(1) << m, 0));
        freeColumns.clear();
        columnSlot.assign(size_t(1) << m, 0);
        gridLog2 = (m - 1) / 2;  // squares of this side hold at least one of the 2^(m-1) points
        grid.assign(size_t(1) << (2 * gridLog2), {});
        for (uint32_t i = 0; i < points.size(); ++i) Mark(i);
        for (uint32_t x = 0; x < (1u << m); ++x)
            if (!occupied[size_t(m)][CellIndex(m, x, 0)]) {
                columnSlot[x] = uint32_t(freeColumns.size());
                freeColumns.push_back(x);
            }
    }

    void SwapColumns(size_t i, size_t j) {
        std::swap(freeColumns[i], freeColumns[j]);
        columnSlot[freeColumns[i]] = uint32_t(i);
        columnSlot[freeColumns[j]] = uint32_t(j);
    }

    size_t CellIndex(int a, uint32_t X, uint32_t Y) const {
        return (size_t(Y >> a) << a) | (X >> (m - a));
    }
    uint32_t Top(uint32_t v) const { return v >> (32 - m); }

    void Mark(uint32_t i) {
        uint32_t X = Top(points[i][0]), Y = Top(points[i][1]);
        for (int a = 0; a <= m; ++a) occupied[size_t(a)][CellIndex(a, X, Y)] = 1;
        grid[GridCell(points[i])].push_back(i);
    }
    // The grid column (k = 0) or row (k = 1) of p.
    int GridCoordinate(const FixedPoint2 &p, int k) const {
        return gridLog2 == 0 ? 0 : int(p[size_t(k)] >> (32 - gridLog2));
    }
    size_t GridCell(const FixedPoint2 &p) const {
        return (size_t(GridCoordinate(p, 1)) << gridLog2) | size_t(GridCoordinate(p, 0));
    }

    void Place(const FixedPoint2 &p) {
        points.push_back(p);
        Mark(uint32_t(points.size() - 1));
        SwapColumns(columnSlot[Top(p[0])], freeColumns.size() - 1);
        freeColumns.pop_back();
    }

    FixedPoint2 BestCandidate() {
        FixedPoint2 best{};
        double bestDistance = -1;
        for (int c = 0; c < candidates; ++c) {
            FixedPoint2 p = RandomFreePoint();
            double d = NearestSquaredDistance(p);
            if (d > bestDistance) {
                bestDistance = d;
                best = p;
            }
        }
        return best;
    }

    // A uniformly jittered point in a random cell that is free in every shape: columns are
    // tried in random order, and each column's rows by a depth-first search over Y's bits.
    FixedPoint2 RandomFreePoint() {
        size_t tried = 0;
        for (size_t left = freeColumns.size(); left > 0; --left, ++tried) {
            size_t pick = tried + rng.Uniform<uint32_t>() % left;
            SwapColumns(tried, pick);
            uint32_t X = freeColumns[tried];
            if (std::optional<uint32_t> Y = FreeRow(X, 0, 0)) return Jitter(X, *Y);
        }
        throw std::runtime_error("pmj02bn: no free cell left for the next point");
    }

    // The rows below prefix `prefix` (its top j bits of Y) whose cells are free in the shapes
    // with j or more row bits; a random branch first.
    std::optional<uint32_t> FreeRow(uint32_t X, int j, uint32_t prefix) {
        if (j > 0 && occupied[size_t(m - j)][CellIndex(m - j, X, prefix << (m - j))]) return {};
        if (j == m) return prefix;
        uint32_t first = rng.Uniform<uint32_t>() & 1;
        for (uint32_t bit : {first, first ^ 1})
            if (std::optional<uint32_t> Y = FreeRow(X, j + 1, (prefix << 1) | bit)) return Y;
        return {};
    }

    FixedPoint2 Jitter(uint32_t X, uint32_t Y) {
        uint32_t low = ~0u >> m;  // m >= 1 here
        uint32_t jx = rng.Uniform<uint32_t>() & low, jy = rng.Uniform<uint32_t>() & low;
        return {(X << (32 - m)) | jx, (Y << (32 - m)) | jy};
    }

    // Toroidal, since the samplers tile the points over the image. Every grid cell holds a
    // point, so p's nearest neighbour is within sqrt(2) cells of it, and any point outside the
    // 5 x 5 cells around p's is at least 2 cells away.
    double NearestSquaredDistance(const FixedPoint2 &p) const {
        int side = 1 << gridLog2;
        int cx = GridCoordinate(p, 0), cy = GridCoordinate(p, 1);
        int lo = side >= 5 ? -2 : 0, hi = side >= 5 ? 2 : side - 1;  // a small grid: every cell once
        double best = 2;
        for (int dy = lo; dy <= hi; ++dy)
            for (int dx = lo; dx <= hi; ++dx) {
                size_t cell = (size_t((cy + dy + side) % side) << gridLog2) | size_t((cx + dx + side) % side);
                for (uint32_t i : grid[cell]) best = std::min(best, ToroidalSquaredDistance(p, points[i]));
            }
        return best;
    }
    static double ToroidalSquaredDistance(const FixedPoint2 &p, const FixedPoint2 &q) {
        double d2 = 0;
        for (int k = 0; k < 2; ++k) {
            uint32_t d = p[k] - q[k];  // modulo 2^32: the wrap-around is free
            double t = std::min(d, 0u - d) * 0x1p-32;
            d2 += t * t;
        }
        return d2;
    }

    RNG rng;
    int candidates;
    int m = 0, gridLog2 = 0;
    std::vector<FixedPoint2> points;
    std::vector<std::vector<uint8_t>> occupied;
    std::vector<uint32_t> freeColumns, columnSlot;  // the free x columns, and where each is
    std::vector<std::vector<uint32_t>> grid;
};

}  // namespace pbrt::pmj02bn
