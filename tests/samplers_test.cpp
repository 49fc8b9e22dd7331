// Samplers: values in [0, 1), a pure function of (pixel, sample, dimension, seed), and the
// distribution property each promises (strata visited once; Sobol' nets in every pixel).
#include "pbrt_ext/samplers.h"

#include "pbrt_ext/util/log.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

namespace pbrt {
namespace {

const Point2i kResolution(37, 23);

std::vector<Sampler> AllSamplers(int seed) {
    return {IndependentSampler(16, seed), StratifiedSampler(4, 4, true, seed),
            StratifiedSampler(3, 5, false, seed),
            ZSobolSampler(16, kResolution, RandomizeStrategy::FastOwen, seed),
            ZSobolSampler(8, kResolution, RandomizeStrategy::Owen, seed),
            ZSobolSampler(4, kResolution, RandomizeStrategy::None, seed),
            ZSobolSampler(32, kResolution, RandomizeStrategy::PermuteDigits, seed)};
}

// The values a path would consume: 1D, 2D, pixel 2D, interleaved.
std::vector<Float> Draw(Sampler &s, Point2i p, int index, int dimension = 0) {
    s.StartPixelSample(p, index, dimension);
    std::vector<Float> v;
    Point2f px = s.GetPixel2D();
    v.push_back(px.x);
    v.push_back(px.y);
    for (int i = 0; i < 6; ++i) {
        v.push_back(s.Get1D());
        Point2f u = s.Get2D();
        v.push_back(u.x);
        v.push_back(u.y);
    }
    return v;
}

TEST(Samplers, ValuesInHalfOpenUnitInterval) {
    for (Sampler s : AllSamplers(0))
        for (int y = 0; y < kResolution.y; y += 3)
            for (int x = 0; x < kResolution.x; x += 3)
                for (int i = 0; i < s.SamplesPerPixel(); ++i)
                    for (Float v : Draw(s, Point2i(x, y), i)) {
                        ASSERT_GE(v, 0) << s.ToString();
                        ASSERT_LT(v, 1) << s.ToString();
                    }
}

// Same values whatever was drawn before, and from a fresh copy: the premise of rendering the
// same image at any thread count.
TEST(Samplers, DeterministicPerPixelSampleAndDimension) {
    for (Sampler s : AllSamplers(7)) {
        Sampler fresh = s;
        std::vector<Float> a = Draw(s, Point2i(5, 9), 3);
        Draw(s, Point2i(20, 1), 0);
        Draw(s, Point2i(5, 9), 2);
        EXPECT_EQ(Draw(s, Point2i(5, 9), 3), a) << s.ToString();
        EXPECT_EQ(Draw(fresh, Point2i(5, 9), 3), a) << s.ToString();
        // Starting at dimension 2 continues the sequence after the pixel sample's two values.
        s.StartPixelSample(Point2i(5, 9), 3, 2);
        EXPECT_EQ(s.Get1D(), a[2]) << s.ToString();
    }
}

TEST(Samplers, SeedPixelAndIndexChangeTheValues) {
    std::vector<Sampler> s0 = AllSamplers(0), s1 = AllSamplers(1);
    for (size_t k = 0; k < s0.size(); ++k) {
        std::vector<Float> base = Draw(s0[k], Point2i(4, 4), 1);
        // Unscrambled Sobol' has nothing for the seed to change (as in pbrt-v4).
        if (s0[k].ToString().find("randomize: none") == std::string::npos) {
            EXPECT_NE(Draw(s1[k], Point2i(4, 4), 1), base) << s0[k].ToString();
        }
        EXPECT_NE(Draw(s0[k], Point2i(5, 4), 1), base) << s0[k].ToString();
        EXPECT_NE(Draw(s0[k], Point2i(4, 4), 2), base) << s0[k].ToString();
    }
}

// In every dimension, the pixel's samples hit each of the spp 1D strata exactly once.
TEST(Samplers, StratifiedAndZSobolStratify1D) {
    std::vector<Sampler> samplers = {StratifiedSampler(4, 2, true, 3), StratifiedSampler(5, 1, false, 3),
                                     ZSobolSampler(16, kResolution), ZSobolSampler(8, kResolution)};
    for (Sampler &s : samplers) {
        int spp = s.SamplesPerPixel();
        for (Point2i p : {Point2i(0, 0), Point2i(13, 7), Point2i(36, 22)})
            for (int dim = 0; dim < 8; ++dim) {
                std::vector<int> count(spp, 0);
                for (int i = 0; i < spp; ++i) {
                    s.StartPixelSample(p, i, dim);
                    ++count[int(s.Get1D() * spp)];
                }
                for (int c : count) EXPECT_EQ(c, 1) << s.ToString() << " dim " << dim;
            }
    }
}

TEST(Samplers, StratifiedCoversTheGridAndCentersWithoutJitter) {
    StratifiedSampler s(3, 5, false, 11);
    std::set<std::pair<int, int>> cells;
    for (int i = 0; i < 15; ++i) {
        s.StartPixelSample(Point2i(2, 3), i, 4);
        Point2f u = s.Get2D();
        EXPECT_NEAR(u.x * 3 - std::floor(u.x * 3), 0.5f, 1e-5f);
        EXPECT_NEAR(u.y * 5 - std::floor(u.y * 5), 0.5f, 1e-5f);
        cells.insert({int(u.x * 3), int(u.y * 5)});
    }
    EXPECT_EQ(cells.size(), 15u);
}

// Scrambled Sobol' points of one pixel form a (0, m, 2)-net: every elementary interval
// (2^-a by 2^-(m-a)) holds exactly one of the 2^m samples, for every pair of dimensions.
TEST(Samplers, ZSobolPixelSamplesFormNets) {
    for (RandomizeStrategy r : {RandomizeStrategy::None, RandomizeStrategy::PermuteDigits,
                                RandomizeStrategy::FastOwen, RandomizeStrategy::Owen})
        for (int log2spp : {0, 1, 2, 3, 4, 5, 6}) {
            ZSobolSampler s(1 << log2spp, kResolution, r, 5);
            for (Point2i p : {Point2i(0, 0), Point2i(9, 17), Point2i(36, 0)})
                for (int dim : {0, 2, 5}) {
                    std::vector<Point2f> pts;
                    for (int i = 0; i < s.SamplesPerPixel(); ++i) {
                        s.StartPixelSample(p, i, dim);
                        pts.push_back(s.Get2D());
                    }
                    for (int a = 0; a <= log2spp; ++a) {
                        int nx = 1 << a, ny = 1 << (log2spp - a);
                        std::vector<int> count(nx * ny, 0);
                        for (Point2f u : pts) ++count[int(u.y * ny) * nx + int(u.x * nx)];
                        for (int c : count)
                            ASSERT_EQ(c, 1) << s.ToString() << " spp " << (1 << log2spp) << " interval "
                                            << nx << "x" << ny;
                    }
                }
        }
}

// Neighbouring pixels get different subsets (no tiled repetition): their first samples differ.
TEST(Samplers, ZSobolDecorrelatesNeighbouringPixels) {
    ZSobolSampler s(4, kResolution);
    std::set<Float> firsts;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            s.StartPixelSample(Point2i(x, y), 0, 0);
            firsts.insert(s.GetPixel2D().x);
        }
    EXPECT_GE(firsts.size(), 14u);
}

TEST(Samplers, ZSobolRoundsSampleCountUpToPowerOfTwo) {
    Log().quiet = true;
    int before = Log().warnings;
    EXPECT_EQ(ZSobolSampler(12, kResolution).SamplesPerPixel(), 16);
    EXPECT_EQ(Log().warnings, before + 1);
    Log().quiet = false;
    EXPECT_EQ(ZSobolSampler(1, Point2i(1, 1)).SamplesPerPixel(), 1);
    EXPECT_THROW(ZSobolSampler(0, kResolution), std::runtime_error);
    EXPECT_THROW(StratifiedSampler(0, 3, true), std::runtime_error);
    EXPECT_THROW(IndependentSampler(-1), std::runtime_error);
}

TEST(Samplers, IndependentMomentsAreUniform) {
    IndependentSampler s(1024, 3);
    double sum = 0, sumSq = 0, sumProd = 0;
    int n = 0;
    for (int i = 0; i < 1024; ++i)
        for (Point2i p : {Point2i(0, 0), Point2i(1, 0), Point2i(0, 1)}) {
            s.StartPixelSample(p, i);
            for (int d = 0; d < 10; ++d) {
                Point2f u = s.Get2D();
                sum += u.x;
                sumSq += u.x * u.x;
                sumProd += (u.x - 0.5) * (u.y - 0.5);
                ++n;
            }
        }
    // Five standard errors: mean 1/2 (sd 0.289/sqrt n), E[x^2] = 1/3 (sd 0.298/sqrt n),
    // covariance 0 (sd 1/12/sqrt n).
    double sn = std::sqrt(double(n));
    EXPECT_NEAR(sum / n, 0.5, 5 * 0.289 / sn);
    EXPECT_NEAR(sumSq / n, 1.0 / 3, 5 * 0.298 / sn);
    EXPECT_NEAR(sumProd / n, 0, 5 * (1.0 / 12) / sn);
}

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

}  // namespace
}  // namespace pbrt
