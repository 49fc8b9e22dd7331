// Light samplers: which light next-event estimation asks (pbrt-v4's src/pbrt/lightsamplers.h:
// uniform, power and BVH). Lights are named by their index in the scene's light list; Sample
// returns the index and the discrete probability p of choosing it, and PMF(i) is that same
// probability, so an estimate divides by p and MIS weights use PMF. The BVH sampler's
// probabilities depend on the receiving point; the others ignore it.
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/lights/lightbounds.h"
#include "pbrt_ext/lights/lights.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/sampling.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pbrt {

// The samplers' names (the integrator's "lightsampler", --light-sampler): none for a known name,
// else the message every reader of a name reports.
std::optional<std::string> LightSamplerNameError(const std::string &name);

struct SampledLight {
    int lightIndex;
    Float p;
};

// Every light with probability 1/n.
class UniformLightSampler {
  public:
    explicit UniformLightSampler(pstd::span<const Light> lights) : lightCount(int(lights.size())) {}

    pstd::optional<SampledLight> Sample(Float u) const;
    Float PMF(int lightIndex) const;
    // pbrt-v4's context-aware overloads: this sampler ignores the receiving point.
    pstd::optional<SampledLight> Sample(const LightSampleContext &, Float u) const {
        return Sample(u);
    }
    Float PMF(const LightSampleContext &, int lightIndex) const { return PMF(lightIndex); }
    bool NeedsIncompletePDFs() const { return false; }
    std::string ToString() const;

  private:
    int lightCount;
};

// Lights with probability proportional to their power (the average of Phi's channels), as
// pbrt-v4; if no light has power, uniformly. Infinite and distant lights must have been
// preprocessed, since their power depends on the scene's extent.
class PowerLightSampler {
  public:
    explicit PowerLightSampler(pstd::span<const Light> lights);

    pstd::optional<SampledLight> Sample(Float u) const;
    Float PMF(int lightIndex) const;
    pstd::optional<SampledLight> Sample(const LightSampleContext &, Float u) const {
        return Sample(u);
    }
    Float PMF(const LightSampleContext &, int lightIndex) const { return PMF(lightIndex); }
    bool NeedsIncompletePDFs() const { return false; }
    std::string ToString() const;

  private:
    // Over [0, 1] with one piece per light: piece i has probability power_i / total.
    PiecewiseConstant1D distribution;
};

// How the BVH light sampler's first choice, between each light without bounds and the tree
// (as one), is made. pbrt-v4 makes them equally likely, so a weak distant light beside a bright
// area light takes half of the samples. By importance, each is weighed by what it can give the
// receiving point (UnboundedLightImportance, and the root's LightBounds::Importance): the same
// expectation, and on pbrt-v4's killeroo scenes (a dim distant light beside a bright disk) half
// the error (docs/benchmarks.md).
enum class InfiniteLightChoice { Importance, PbrtV4 };

// pbrt-v4's BVH light sampler (Conty Estevez and Kulla 2018, as pbrt-v4 builds it): the lights
// with bounds sit in a binary tree of LightBounds; sampling descends from the root, choosing each
// child with probability proportional to its importance at the receiving point, so that near,
// bright, facing lights are chosen more. Lights without bounds (distant, infinite) are chosen
// first, against the tree as a whole, as InfiniteLightChoice says; lights with no power are never
// chosen. Where a descent meets two children of importance 0 (no light below them can reach the
// point, though their parent's looser bounds allowed it) nothing is chosen, so the PMF sums to
// less than 1 there, as in pbrt-v4.
class BVHLightSampler {
  public:
    // allowIncompletePDF: the integrators' SampleLi will ask for it (MIS), which changes what
    // infinite lights can give (UnboundedLightImportance).
    explicit BVHLightSampler(pstd::span<const Light> lights,
                             InfiniteLightChoice infiniteChoice = InfiniteLightChoice::Importance,
                             bool allowIncompletePDF = false);

    pstd::optional<SampledLight> Sample(const LightSampleContext &ctx, Float u) const;
    Float PMF(const LightSampleContext &ctx, int lightIndex) const;
    // Whether built for MIS (allowIncompletePDF) with a light that is then never chosen though
    // complete densities would need it (a uniform sky): an integrator without MIS must not use
    // this sampler.
    bool NeedsIncompletePDFs() const { return needsIncompletePDFs; }
    std::string ToString() const;

  private:
    struct Node {
        Node(const LightBounds &bounds, int childOrLightIndex, bool isLeaf)
            : bounds(bounds), constants(bounds), childOrLightIndex(childOrLightIndex), isLeaf(isLeaf) {}
        Float Importance(const LightSampleContext &ctx) const {
            return bounds.Importance(ctx.p, ctx.n, constants);
        }

        LightBounds bounds;
        LightBounds::Constants constants;
        // A leaf's light index; an interior node's second child (its first is the next node).
        int childOrLightIndex;
        bool isLeaf;
    };
    struct BoundedLight {
        int lightIndex;
        LightBounds bounds;
    };

    // Builds the subtree of lights [begin, end) at depth, whose path from the root is bitTrail
    // (bit d: the second child at depth d); returns its bounds.
    LightBounds Build(std::vector<BoundedLight> &lights, size_t begin, size_t end,
                      uint64_t bitTrail, int depth);
    // The weights of the first choice at the receiving point: the i-th light without bounds's,
    // the tree's, and the sum of all of them.
    Float InfiniteWeight(size_t i, const LightSampleContext &ctx) const {
        return infiniteChoice == InfiniteLightChoice::PbrtV4
                   ? 1
                   : infiniteLights[i].importance.Importance(ctx.n);
    }
    Float TreeWeight(const LightSampleContext &ctx) const;
    Float WeightTotal(const LightSampleContext &ctx, Float treeWeight) const;
    // An interior node's two children (the next node, then the stored one) and their
    // importance at the receiving point: Sample and PMF descend by the same numbers.
    struct Children {
        int index[2];
        Float importance[2];
    };
    Children ChildrenAt(int nodeIndex, const LightSampleContext &ctx) const;
    // Whether the tree is one leaf that cannot reach the receiving point (interior nodes exclude
    // such lights through their children's importance).
    bool LoneLeafUnreachable(int nodeIndex, const LightSampleContext &ctx) const {
        return nodeIndex == 0 && nodes[0].Importance(ctx) == 0;
    }

    struct UnboundedLight {
        int lightIndex;
        UnboundedLightImportance importance;
    };
    std::vector<UnboundedLight> infiniteLights;
    InfiniteLightChoice infiniteChoice;
    bool needsIncompletePDFs = false;
    std::vector<Node> nodes;
    // By light index: the bit trail of a light in the tree, none for the others.
    std::vector<std::optional<uint64_t>> lightToBitTrail;
};

}  // namespace pbrt
