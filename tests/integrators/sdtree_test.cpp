// The SD-tree of guided path tracing: the equal-area map inverts; a quadtree's samples follow the
// density it reports (chi-square, tests/support/chi2.h, alpha 0.01 with Sidak over the suite);
// its density integrates to 1 and its recorded energy is conserved by box filtering; refinement
// splits where energy is and leaves a uniform tree alone; the spatial tree splits leaves that
// record many samples; each leaf learns the BSDF fraction of least cross entropy with what its
// samples found (bsdffraction.h); a written tree reads back with the same densities and
// fractions, and a file that is not one, or is of another scene, is an error naming it.
#include "pbrt_ext/integrators/sdtree.h"

#include "tests/support/chi2.h"
#include "tests/support/scenefolder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

using namespace pbrt;

namespace {

constexpr int kChi2Tests = 2;

// A quadtree that learned energy along a band of directions and a bright spot, refined twice as
// training refines it, then recorded into again.
DTree Learned() {
    RNG rng(7);
    DTree tree;
    for (int pass = 0; pass < 3; ++pass) {
        for (int i = 0; i < 20000; ++i) {
            Point2f c(rng.Uniform<Float>(), rng.Uniform<Float>());
            double value = 0.05 + (std::abs(c.x - 0.7f) < 0.05f ? 10 : 0) +
                           (std::hypot(c.x - 0.2f, c.y - 0.3f) < 0.03f ? 200 : 0);
            Float s = tree.LeafSize(c) / 2;
            tree.RecordBox(Bounds2f(Point2f(std::max<Float>(0, c.x - s), std::max<Float>(0, c.y - s)),
                                    Point2f(std::min<Float>(1, c.x + s), std::min<Float>(1, c.y + s))),
                           value);
        }
        tree.Finalize();
        if (pass < 2)
            tree = tree.Refined(0.01, 20);
    }
    return tree;
}

TEST(EqualAreaMap, RoundTripsAndPreservesArea) {
    RNG rng(3);
    for (int i = 0; i < 10000; ++i) {
        Point2f c(rng.Uniform<Float>(), rng.Uniform<Float>());
        Vector3f w = DirectionFromCanonical(c);
        EXPECT_NEAR(Length(w), 1, 1e-5f);
        Point2f back = CanonicalFromDirection(w);
        EXPECT_NEAR(back.x, c.x, 2e-5f);
        EXPECT_NEAR(std::min(std::abs(back.y - c.y), 1 - std::abs(back.y - c.y)), 0, 2e-5f);
    }
    // Uniform in the square is uniform over the sphere: the density 1 / (4 pi).
    Chi2Options opts;
    opts.numTests = kChi2Tests;
    auto sample = [](Point2f u, Float) -> pstd::optional<Vector3f> { return DirectionFromCanonical(u); };
    Chi2Result r = Chi2TestSampler(sample, [](Vector3f) { return Inv4Pi; }, opts);
    EXPECT_TRUE(r.passed) << r.message;
}

TEST(DTree, SamplesFollowItsDensity) {
    DTree tree = Learned();
    ASSERT_GT(tree.NodeCount(), 20);
    Chi2Options opts;
    opts.numTests = kChi2Tests;
    auto sample = [&](Point2f u, Float) -> pstd::optional<Vector3f> {
        return DirectionFromCanonical(tree.Sample(u));
    };
    auto pdf = [&](Vector3f w) { return tree.PDF(CanonicalFromDirection(w)) * Inv4Pi; };
    Chi2Result r = Chi2TestSampler(sample, pdf, opts);
    EXPECT_TRUE(r.passed) << r.message;
}

// The density Sample gives with its point is the one PDF reports there.
TEST(DTree, SampleGivesTheDensityOfItsPoint) {
    DTree tree = Learned();
    RNG rng(5);
    for (int i = 0; i < 20000; ++i) {
        Float pdf = -1;
        Point2f c = tree.Sample(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()), &pdf);
        ASSERT_NEAR(pdf, tree.PDF(c), 1e-5f * tree.PDF(c)) << c.x << " " << c.y;
    }
}

// Uniform radiance L, recorded as Müller's records are (radiance over the density of its
// direction, here uniform), half of the records finding nothing: the tree learns L / 2 in
// every direction.
TEST(SDTree, LearnsTheRadianceItRecorded) {
    SDTree tree(Bounds3f(Point3f(0, 0, 0), Point3f(1, 1, 1)));
    RNG rng(13);
    const double L = 3;
    for (int i = 0; i < 4000; ++i) {
        Point3f p(rng.Uniform<Float>(), rng.Uniform<Float>(), rng.Uniform<Float>());
        Vector3f w = DirectionFromCanonical(Point2f(rng.Uniform<Float>(), rng.Uniform<Float>()));
        tree.Record(p, w, i % 2 ? L / Inv4Pi : 0, rng);
    }
    tree.Refine(0);
    const DTree &learned = tree.SamplingTree(Point3f(0.5f, 0.5f, 0.5f));
    EXPECT_NEAR(learned.MeanRadiance(), L / 2, 1e-4);
    for (Point2f c : {Point2f(0.1f, 0.2f), Point2f(0.9f, 0.5f)})
        EXPECT_NEAR(learned.Radiance(c), L / 2, 0.2 * L);  // the box filter's blur of the records
}

TEST(DTree, DensityIntegratesToOneAndEnergyIsConserved) {
    DTree tree;
    double recorded = 0;
    RNG rng(11);
    for (int i = 0; i < 1000; ++i) {
        Point2f c(rng.Uniform<Float>(), rng.Uniform<Float>());
        double value = rng.Uniform<Float>();
        tree.RecordBox(Bounds2f(Point2f(c.x * 0.9f, c.y * 0.9f), Point2f(c.x * 0.9f + 0.1f, c.y * 0.9f + 0.1f)),
                       value);
        recorded += value;
    }
    tree.Finalize();
    EXPECT_NEAR(tree.Energy(), recorded, 1e-6 * recorded);  // overlaps computed in float
    DTree learned = Learned();
    for (const DTree *t : {&tree, &learned}) {
        constexpr int n = 512;
        double integral = 0;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) integral += t->PDF(Point2f((x + 0.5f) / n, (y + 0.5f) / n));
        EXPECT_NEAR(integral / (n * n), 1, 1e-3);
    }
}

// An empty tree refines uniformly, until a quadrant's share of the area is under the threshold
// (1 + 4 + 16 + 64 nodes for 0.01); one that learned a spot, where the spot is.
TEST(DTree, RefinementSplitsWhereEnergyIs) {
    DTree uniform;
    uniform.Finalize();
    EXPECT_EQ(uniform.Refined(0.01, 20).NodeCount(), 85);
    EXPECT_LE(uniform.Refined(0.01, 3).Depth(), 3);
    DTree spot;
    for (int round = 0; round < 4; ++round) {
        spot.RecordBox(Bounds2f(Point2f(0.1f, 0.1f), Point2f(0.11f, 0.11f)), 1);
        spot.RecordBox(Bounds2f(Point2f(0, 0), Point2f(1, 1)), 0.05);
        spot.Finalize();
        if (round < 3)
            spot = spot.Refined(0.01, 20);
    }
    EXPECT_LT(spot.LeafSize(Point2f(0.105f, 0.105f)), 0.02f);
    EXPECT_GE(spot.LeafSize(Point2f(0.9f, 0.9f)), 0.125f);
    EXPECT_LT(spot.NodeCount(), 85);
}

SDTree Trained(int records) {
    SDTree tree(Bounds3f(Point3f(0, 0, 0), Point3f(1, 1, 1)));
    RNG rng(5);
    for (int i = 0; i < records; ++i) {
        Point3f p(rng.Uniform<Float>(), rng.Uniform<Float>(), rng.Uniform<Float>());
        tree.Record(p, Normalize(Vector3f(0.3f, p.x - 0.5f, 1)), 1 + p.y, rng);
    }
    tree.Refine(0);
    return tree;
}

TEST(SDTree, SplitsLeavesThatRecordedMany) {
    EXPECT_EQ(Trained(1000).Stats().leaves, 1);    // c sqrt(2^0) = 3000 records before a split
    SDTree::Statistics s = Trained(100000).Stats();
    EXPECT_GT(s.leaves, 4);
    EXPECT_EQ(s.spatialNodes, 2 * s.leaves - 1);
    EXPECT_GT(s.directionalNodes, 2 * s.leaves);
}

TEST(SDTree, WrittenTreeReadsBackTheSame) {
    SDTree tree = Trained(60000);
    std::string file = (TestFolder("pbrt_ext_sdtree_test") / "tree.sdt").string();
    tree.Write(file);
    SDTree read = SDTree::Read(file, Bounds3f(Point3f(0, 0, 0), Point3f(1, 1, 1)));
    EXPECT_EQ(read.Stats().leaves, tree.Stats().leaves);
    RNG rng(9);
    for (int i = 0; i < 1000; ++i) {
        Point3f p(rng.Uniform<Float>(), rng.Uniform<Float>(), rng.Uniform<Float>());
        Point2f c(rng.Uniform<Float>(), rng.Uniform<Float>());
        ASSERT_EQ(read.SamplingTree(p).PDF(c), tree.SamplingTree(p).PDF(c));
        ASSERT_EQ(read.SamplingTree(p).MeanRadiance(), tree.SamplingTree(p).MeanRadiance());
    }
}

// The fraction of the mixture alpha p_bsdf + (1 - alpha) p_guide whose cross entropy with the
// integrand is least, from samples of known densities and weights.
TEST(BSDFFractionLearner, ChoosesTheCandidateOfLeastCrossEntropy) {
    // Half the samples where only the BSDF has density, half where only the guide has, the first
    // weighing four times as much: -4 log(alpha) - log(1 - alpha) is least at alpha = 0.8.
    BSDFFractionLearner split;
    for (int i = 0; i < 40; ++i) {
        split.Record(2, 0, 4);
        split.Record(0, 2, 1);
    }
    EXPECT_FLOAT_EQ(split.Best(0.5f), 0.8f);
    // Where the integrand follows the BSDF, the most BSDF sampling a candidate has; where it
    // follows the guide, the least.
    BSDFFractionLearner bsdfWins, guideWins;
    for (int i = 0; i < 100; ++i) {
        bsdfWins.Record(1, 0.01f, 1);
        guideWins.Record(0.01f, 1, 1);
    }
    EXPECT_FLOAT_EQ(bsdfWins.Best(0.5f), 0.9f);
    EXPECT_FLOAT_EQ(guideWins.Best(0.5f), 0.1f);
    // Too few samples, samples that found nothing, or none since Reset: the fraction stays.
    BSDFFractionLearner few, dark;
    for (uint64_t i = 0; i + 1 < BSDFFractionLearner::kMinimumSamples; ++i) few.Record(1, 0.01f, 1);
    for (int i = 0; i < 100; ++i) dark.Record(1, 0.01f, 0);
    EXPECT_EQ(few.Best(0.3f), 0.3f);
    EXPECT_EQ(dark.Best(0.3f), 0.3f);
    bsdfWins.Reset();
    EXPECT_EQ(bsdfWins.Best(0.3f), 0.3f);
    // Samples that are not samples (no density, or a weight that is not finite) are ignored.
    BSDFFractionLearner bad;
    for (int i = 0; i < 100; ++i) {
        bad.Record(0, 0, 1);
        bad.Record(1, 0.01f, std::numeric_limits<double>::infinity());
        bad.Record(1, std::numeric_limits<Float>::quiet_NaN(), 1);
    }
    EXPECT_EQ(bad.Best(0.3f), 0.3f);
}

// Each leaf's fraction is learned from its own samples at Refine, kept where it learned nothing
// (or where learning is off), inherited by the halves of a split, and written with the tree.
TEST(SDTree, LearnsEachLeafsBSDFFractionAndWritesIt) {
    SDTree tree = Trained(60000);
    ASSERT_GT(tree.Stats().leaves, 1);
    const Point3f a(0.1f, 0.1f, 0.1f), b(0.9f, 0.9f, 0.9f);
    ASSERT_NE(tree.SamplingGuide(a).leaf, tree.SamplingGuide(b).leaf);
    EXPECT_EQ(tree.SamplingGuide(a).bsdfFraction, 0.5f);
    for (int i = 0; i < 100; ++i) tree.RecordFraction(tree.SamplingGuide(a).leaf, 0.01f, 1, 1);
    tree.Refine(1);
    EXPECT_FLOAT_EQ(tree.SamplingGuide(a).bsdfFraction, 0.1f);
    EXPECT_EQ(tree.SamplingGuide(b).bsdfFraction, 0.5f);
    std::string file = (TestFolder("pbrt_ext_sdtree_test") / "fractions.sdt").string();
    tree.Write(file);
    SDTree read = SDTree::Read(file, Bounds3f(Point3f(0, 0, 0), Point3f(1, 1, 1)));
    EXPECT_FLOAT_EQ(read.SamplingGuide(a).bsdfFraction, 0.1f);
    EXPECT_EQ(read.SamplingGuide(b).bsdfFraction, 0.5f);

    SDTreeOptions fixed;
    fixed.bsdfFraction = 0.7f;
    fixed.learnBSDFFraction = false;
    SDTree still(Bounds3f(Point3f(0, 0, 0), Point3f(1, 1, 1)), fixed);
    for (int i = 0; i < 100; ++i) still.RecordFraction(still.SamplingGuide(a).leaf, 0.01f, 1, 1);
    still.Refine(0);
    EXPECT_EQ(still.SamplingGuide(a).bsdfFraction, 0.7f);
}

TEST(SDTree, BadFilesAreErrorsNamingThem) {
    std::filesystem::path dir = TestFolder("pbrt_ext_sdtree_test");
    Bounds3f unit(Point3f(0, 0, 0), Point3f(1, 1, 1));
    std::string good = (dir / "good.sdt").string();
    Trained(20000).Write(good);
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto errorOf = [&](const std::string &name, const std::string &content, const Bounds3f &bounds) {
        std::string path = (dir / name).string();
        std::ofstream(path, std::ios::binary) << content;
        try {
            SDTree::Read(path, bounds);
        } catch (const std::runtime_error &e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_THAT(errorOf("text.sdt", "not a tree", unit), testing::HasSubstr("text.sdt: error: not a guiding tree"));
    EXPECT_THAT(errorOf("cut.sdt", bytes.substr(0, bytes.size() / 2), unit),
                testing::HasSubstr("cut.sdt: error: the file ends"));
    EXPECT_THAT(errorOf("other.sdt", bytes, Bounds3f(Point3f(0, 0, 0), Point3f(2, 1, 1))),
                testing::HasSubstr("other.sdt: error: it was trained on another scene"));
    std::string corrupt = bytes;
    for (size_t i = 40; i < corrupt.size(); i += 7) corrupt[i] = char(0xff);
    EXPECT_THAT(errorOf("corrupt.sdt", corrupt, unit), testing::HasSubstr("corrupt.sdt: error: "));
    EXPECT_THAT(errorOf("missing/none.sdt", "", unit), testing::HasSubstr("error"));
}

}  // namespace
