// The SD-tree of Müller, Gross and Novák, "Practical Path Guiding for Efficient Light-Transport
// Simulation" (EGSR 2017), with the box filtering of Müller's "Practical Path Guiding in
// Production" (SIGGRAPH 2019 course): the radiance arriving in a scene, learned while rendering,
// as a binary tree over space whose leaves each hold a quadtree over the directions.
//
// Directions map to the unit square by a cylindrical equal-area map ((cos theta + 1) / 2,
// phi / 2 pi), so that a density per unit area of the square is 4 pi times one per solid angle.
// A quadtree (DTree) splits the square where energy arrived: each node's four quadrants hold
// the energy that came through them; sampling descends in proportion to it, so the density is
// piecewise constant over the leaves, and exactly the one PDF reports.
//
// Each spatial leaf holds two quadtrees: the one paths sample from (frozen during an iteration)
// and the one being recorded into (thread-safe sums). After an iteration, Refine makes the
// recorded energy the sampling tree, splits spatial leaves that received many records (more
// than c sqrt(2^k) after iteration k) and quadrants that hold more than a fraction of a
// leaf's energy, and starts a fresh recording tree of that shape. Each leaf also holds the
// fraction of directions sampled from the BSDF there, learned as it learns (bsdffraction.h).
#pragma once

#include "pbrt_ext/integrators/bsdffraction.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/atomicsum.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/vecmath.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace pbrt {

// The cylindrical equal-area map between directions and the unit square, and back.
Point2f CanonicalFromDirection(Vector3f w);
Vector3f DirectionFromCanonical(Point2f c);

// A piecewise-constant density over the unit square, as a quadtree of energies.
class DTree {
  public:
    DTree();  // one node: four empty quadrants, sampled uniformly

    // Adds value (in proportion to overlap) to the leaf quadrants that box covers; thread-safe.
    void RecordBox(const Bounds2f &box, double value);
    // After recording, from one thread: each node's sums become those of the leaves below it.
    void Finalize();

    // Sampling and density per unit area of the square, in proportion to the finalized
    // energies (uniform where a node has none). Sample gives the density of its point too, where
    // pdf is not null.
    Point2f Sample(Point2f u, Float *pdf = nullptr) const;
    Float PDF(Point2f c) const;
    double Energy() const;
    // The radiance learned along c, and its mean over the sphere: the energy is the sum of the
    // records' radiance over their density, weight the number of records (those of no radiance
    // too), so that energy / weight estimates the radiance integrated over the sphere.
    Float Radiance(Point2f c) const;
    Float MeanRadiance() const;
    void SetWeight(double records) { weight = records; }
    // The side of the leaf quadrant holding c.
    Float LeafSize(Point2f c) const;

    // The same shape, empty, with each quadrant that holds more than threshold of the energy
    // split (down to maxDepth levels) and each that holds less merged.
    DTree Refined(double threshold, int maxDepth) const;

    int NodeCount() const { return int(nodes.size()); }
    int Depth() const;

    void Write(std::ostream &out) const;
    // Throws std::runtime_error(what) for a malformed tree.
    static DTree Read(std::istream &in);

  private:
    struct Node {
        std::array<uint32_t, 4> child{};  // 0: the quadrant is a leaf
        std::array<AtomicSum, 4> sum;
        double Total() const {
            return sum[0].Load() + sum[1].Load() + sum[2].Load() + sum[3].Load();
        }
    };

    void RecordBox(uint32_t node, Point2f origin, Float size, const Bounds2f &box, double value);
    double FinalizeNode(uint32_t node);

    std::vector<Node> nodes;
    double weight = 0;
};

// The options of an SD-tree, with the papers' values by default but for c.
struct SDTreeOptions {
    // c: a leaf splits past c sqrt(2^k) records. Müller et al.'s 12000 left the trees of 320×240
    // renders coarse; 3000 (four times the leaves) gave, at 256 spp, 2.0× the efficiency in the
    // torchiere's room, 1.35× in veach-ajar, 1.06× and 1.10× in the slit room and under the
    // fabric, for 10-27 % more time per sample; 1000 was no better (docs/comparison.md).
    double spatialThreshold = 3000;
    double directionalThreshold = 0.01;
    int maxDirectionalDepth = 20;
    size_t maxBytes = size_t(256) << 20;  // no spatial split past this
    Float bsdfFraction = 0.5f;            // every leaf's at first
    bool learnBSDFFraction = true;        // or keep bsdfFraction everywhere
};

class SDTree {
  public:
    // Over a cube around the bounds (cubic cells split evenly).
    explicit SDTree(const Bounds3f &bounds, SDTreeOptions options = {});

    // The sampling tree of the leaf holding p.
    const DTree &SamplingTree(Point3f p) const { return leaves[LeafIndex(p, nullptr)]->sampling; }
    // What the leaf holding p guides with: its sampling tree and BSDF fraction, and the leaf's
    // index for RecordFraction.
    struct Guide {
        const DTree &directions;
        Float bsdfFraction;
        int leaf;
    };
    Guide SamplingGuide(Point3f p) const {
        int index = LeafIndex(p, nullptr);
        const Leaf &leaf = *leaves[size_t(index)];
        return Guide{leaf.sampling, leaf.bsdfFraction, index};
    }

    // Records value (the luminance of the radiance that arrived along w, over the density w was
    // sampled with) at p: stochastically box-filtered in space over a cell of the leaf's size
    // around p (rng), and in direction over the sampling tree's leaf quadrant around w.
    // Thread-safe.
    void Record(Point3f p, Vector3f w, double value, RNG &rng);
    // A guided sample at leaf (of SamplingGuide), for its BSDF fraction
    // (BSDFFractionLearner::Record). Thread-safe.
    void RecordFraction(int leaf, Float pdfBSDF, Float pdfGuide, double integrandOverPDF) {
        leaves[size_t(leaf)]->fraction.Record(pdfBSDF, pdfGuide, integrandOverPDF);
    }

    // After iteration k (0, 1, ...): see the header comment.
    void Refine(int iteration);

    struct Statistics {
        int spatialNodes = 0, leaves = 0, directionalNodes = 0, maxDirectionalDepth = 0;
        size_t bytes = 0;
    };
    Statistics Stats() const;
    const Bounds3f &Bounds() const { return bounds; }

    // A binary file with a magic number and version; Read throws std::runtime_error naming path
    // for a file that is not one, is truncated, or does not fit these bounds.
    void Write(const std::string &path) const;
    static SDTree Read(const std::string &path, const Bounds3f &sceneBounds, SDTreeOptions options = {});

  private:
    struct Leaf {
        DTree sampling, building;
        std::atomic<uint64_t> records{0};
        Float bsdfFraction = 0.5f;  // sampled with
        BSDFFractionLearner fraction;  // what this iteration found
    };
    struct Node {
        int axis = 0;                 // of the split: an inner node's, or a leaf's next
        std::array<int, 2> child{};   // inner node: node indices
        int leaf = -1;                // leaf node: index into leaves
    };

    SDTree() = default;
    int LeafIndex(Point3f p, Bounds3f *box) const;
    void SplitLeaves(uint64_t threshold);

    Bounds3f bounds;
    SDTreeOptions options;
    std::vector<Node> nodes;
    std::vector<std::unique_ptr<Leaf>> leaves;
};

}  // namespace pbrt
