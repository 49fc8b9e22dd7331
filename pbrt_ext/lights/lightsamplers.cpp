#include "pbrt_ext/lights/lightsamplers.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace pbrt {

std::optional<std::string> LightSamplerNameError(const std::string &name) {
    if (name == "bvh" || name == "bvh-pbrt-v4" || name == "power" || name == "uniform")
        return std::nullopt;
    return "unknown light sampler \"" + name + "\": expected bvh, bvh-pbrt-v4, power or uniform";
}

pstd::optional<SampledLight> UniformLightSampler::Sample(Float u) const {
    if (lightCount == 0)
        return {};
    int lightIndex = std::min(int(u * lightCount), lightCount - 1);
    return SampledLight{lightIndex, Float(1) / lightCount};
}

Float UniformLightSampler::PMF(int lightIndex) const {
    if (lightIndex < 0 || lightIndex >= lightCount)
        return 0;
    return Float(1) / lightCount;
}

std::string UniformLightSampler::ToString() const {
    return "[ UniformLightSampler lightCount: " + std::to_string(lightCount) + " ]";
}

namespace {

std::vector<Float> LightPowers(pstd::span<const Light> lights) {
    // pbrt-v4's: the power at four visible wavelengths, weighted as the film weights them.
    SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
    std::vector<Float> power(lights.size());
    for (size_t i = 0; i < lights.size(); ++i)
        power[i] = std::max<Float>(SafeDiv(lights[i].Phi(lambda), lambda.PDF()).Average(), 0);
    if (std::all_of(power.begin(), power.end(), [](Float p) { return p == 0; }))
        std::fill(power.begin(), power.end(), Float(1));
    return power;
}

}  // namespace

PowerLightSampler::PowerLightSampler(pstd::span<const Light> lights) {
    if (!lights.empty())
        distribution = PiecewiseConstant1D(LightPowers(lights));
}

// A piece's density over [0, 1] is n times its probability.
pstd::optional<SampledLight> PowerLightSampler::Sample(Float u) const {
    if (distribution.size() == 0)
        return {};
    Float pdf;
    int lightIndex;
    distribution.Sample(u, &pdf, &lightIndex);
    return SampledLight{lightIndex, pdf / distribution.size()};
}

Float PowerLightSampler::PMF(int lightIndex) const {
    if (lightIndex < 0 || size_t(lightIndex) >= distribution.size())
        return 0;
    return distribution.func[lightIndex] / (distribution.Integral() * distribution.size());
}

std::string PowerLightSampler::ToString() const {
    return "[ PowerLightSampler lightCount: " + std::to_string(distribution.size()) + " ]";
}

namespace {

// The surface-area-orientation heuristic's cost of a node (pbrt-v4): power times the solid angle
// its emission can cover (M_Omega) times its surface area, stretched by how thin the parent box
// is along the split axis, so that splits across the long axis are preferred.
Float SplitCost(const LightBounds &b, const Bounds3f &parent, int dim) {
    Float thetaO = SafeACos(b.cosTheta_o), thetaE = SafeACos(b.cosTheta_e);
    Float thetaW = std::min(thetaO + thetaE, Pi);
    Float sinThetaO = SafeSqrt(1 - Sqr(b.cosTheta_o));
    Float mOmega = 2 * Pi * (1 - b.cosTheta_o) +
                   Pi / 2 * (2 * thetaW * sinThetaO - std::cos(thetaO - 2 * thetaW) -
                             2 * thetaO * sinThetaO + b.cosTheta_o);
    Vector3f d = parent.Diagonal();
    Float kr = std::max({d.x, d.y, d.z}) / d[dim];
    return b.phi * mOmega * kr * b.bounds.SurfaceArea();
}

}  // namespace

BVHLightSampler::BVHLightSampler(pstd::span<const Light> lights, InfiniteLightChoice infiniteChoice,
                                 bool allowIncompletePDF)
    : infiniteChoice(infiniteChoice), lightToBitTrail(lights.size()) {
    std::vector<BoundedLight> bounded;
    for (size_t i = 0; i < lights.size(); ++i) {
        pstd::optional<LightBounds> b = lights[i].Bounds();
        if (!b) {
            UnboundedLightImportance importance = lights[i].Importance(allowIncompletePDF);
            infiniteLights.push_back({int(i), importance});
            needsIncompletePDFs |= infiniteChoice == InfiniteLightChoice::Importance &&
                                   importance.irradiance == 0 && lights[i].Importance(false).irradiance > 0;
        }
        else if (b->phi > 0)
            bounded.push_back({int(i), *b});
    }
    if (!bounded.empty())
        Build(bounded, 0, bounded.size(), 0, 0);
}

LightBounds BVHLightSampler::Build(std::vector<BoundedLight> &lights, size_t begin, size_t end,
                                   uint64_t bitTrail, int depth) {
    if (end - begin == 1) {
        nodes.emplace_back(lights[begin].bounds, lights[begin].lightIndex, true);
        lightToBitTrail[lights[begin].lightIndex] = bitTrail;
        return lights[begin].bounds;
    }
    Bounds3f bounds, centroidBounds;
    for (size_t i = begin; i < end; ++i) {
        bounds = Union(bounds, lights[i].bounds.bounds);
        centroidBounds = Union(centroidBounds, lights[i].bounds.Centroid());
    }

    // The cheapest split between 12 buckets of centroids along each axis.
    constexpr int nBuckets = 12;
    Float minCost = Infinity;
    int minDim = -1, minBucket = -1;
    auto bucketOf = [&](const BoundedLight &l, int dim) {
        Float t = (l.bounds.Centroid()[dim] - centroidBounds.pMin[dim]) /
                  (centroidBounds.pMax[dim] - centroidBounds.pMin[dim]);
        return std::clamp(int(t * nBuckets), 0, nBuckets - 1);
    };
    for (int dim = 0; dim < 3; ++dim) {
        if (!(centroidBounds.pMax[dim] > centroidBounds.pMin[dim]))
            continue;
        LightBounds buckets[nBuckets];
        for (size_t i = begin; i < end; ++i) {
            int b = bucketOf(lights[i], dim);
            buckets[b] = Union(buckets[b], lights[i].bounds);
        }
        for (int split = 0; split < nBuckets - 1; ++split) {
            LightBounds below, above;
            for (int b = 0; b <= split; ++b)
                below = Union(below, buckets[b]);
            for (int b = split + 1; b < nBuckets; ++b)
                above = Union(above, buckets[b]);
            Float cost = SplitCost(below, bounds, dim) + SplitCost(above, bounds, dim);
            if (cost > 0 && cost < minCost) {
                minCost = cost;
                minDim = dim;
                minBucket = split;
            }
        }
    }
    size_t mid = (begin + end) / 2;
    if (minDim >= 0) {
        auto it = std::partition(lights.begin() + begin, lights.begin() + end,
                                 [&](const BoundedLight &l) { return bucketOf(l, minDim) <= minBucket; });
        mid = size_t(it - lights.begin());
    }
    if (mid == begin || mid == end)
        mid = (begin + end) / 2;

    // Children in depth-first order: the first follows its parent, the second's index is stored.
    size_t nodeIndex = nodes.size();
    nodes.emplace_back(LightBounds(), 0, false);
    if (depth >= 64)
        throw std::runtime_error("BVHLightSampler: the light tree is deeper than 64 levels");
    LightBounds first = Build(lights, begin, mid, bitTrail, depth + 1);
    nodes[nodeIndex].childOrLightIndex = int(nodes.size());
    LightBounds second = Build(lights, mid, end, bitTrail | (uint64_t(1) << depth), depth + 1);
    nodes[nodeIndex] = Node(Union(first, second), nodes[nodeIndex].childOrLightIndex, false);
    return nodes[nodeIndex].bounds;
}

BVHLightSampler::Children BVHLightSampler::ChildrenAt(int nodeIndex,
                                                      const LightSampleContext &ctx) const {
    Children c{{nodeIndex + 1, nodes[nodeIndex].childOrLightIndex}, {}};
    for (int i = 0; i < 2; ++i)
        c.importance[i] = nodes[c.index[i]].Importance(ctx);
    return c;
}

Float BVHLightSampler::TreeWeight(const LightSampleContext &ctx) const {
    if (nodes.empty())
        return 0;
    // Without lights outside the tree, its weight does not matter: it is chosen with
    // probability 1 (the root's importance over itself, to the last bit).
    if (infiniteChoice == InfiniteLightChoice::PbrtV4 || infiniteLights.empty())
        return 1;
    return nodes[0].Importance(ctx);
}

Float BVHLightSampler::WeightTotal(const LightSampleContext &ctx, Float treeWeight) const {
    Float total = treeWeight;
    for (size_t i = 0; i < infiniteLights.size(); ++i)
        total += InfiniteWeight(i, ctx);
    return total;
}

pstd::optional<SampledLight> BVHLightSampler::Sample(const LightSampleContext &ctx,
                                                     Float u) const {
    // The first choice, by the weights' running sum: a light without bounds, or the tree.
    Float treeWeight = TreeWeight(ctx), total = WeightTotal(ctx, treeWeight);
    if (!(total > 0))
        return {};
    Float uWeight = u * total;
    int lastWeighted = -1;
    for (size_t i = 0; i < infiniteLights.size(); ++i) {
        Float w = InfiniteWeight(i, ctx);
        if (uWeight < w)
            return SampledLight{infiniteLights[i].lightIndex, w / total};
        uWeight -= w;
        if (w > 0)
            lastWeighted = int(i);
    }
    // Rounding can carry uWeight past the last light's weight where the tree's is zero.
    if (treeWeight == 0)
        return SampledLight{infiniteLights[size_t(lastWeighted)].lightIndex,
                            InfiniteWeight(size_t(lastWeighted), ctx) / total};
    u = std::min(uWeight / treeWeight, OneMinusEpsilon);
    int nodeIndex = 0;
    Float pmf = treeWeight / total;
    while (!nodes[nodeIndex].isLeaf) {
        Children c = ChildrenAt(nodeIndex, ctx);
        Float sum = c.importance[0] + c.importance[1];
        if (sum == 0)
            return {};
        Float p0 = c.importance[0] / sum;
        int child = u < p0 ? 0 : 1;
        pmf *= c.importance[child] / sum;  // as PMF computes it, to the last bit
        u = std::min(child == 0 ? u / p0 : (u - p0) / (1 - p0), OneMinusEpsilon);
        nodeIndex = c.index[child];
    }
    if (LoneLeafUnreachable(nodeIndex, ctx))
        return {};
    return SampledLight{nodes[nodeIndex].childOrLightIndex, pmf};
}

Float BVHLightSampler::PMF(const LightSampleContext &ctx, int lightIndex) const {
    bool inTree = lightIndex >= 0 && size_t(lightIndex) < lightToBitTrail.size() &&
                  lightToBitTrail[lightIndex];
    Float treeWeight = TreeWeight(ctx), total = WeightTotal(ctx, treeWeight);
    if (!(total > 0))
        return 0;
    if (!inTree) {
        for (size_t i = 0; i < infiniteLights.size(); ++i)
            if (infiniteLights[i].lightIndex == lightIndex)
                return InfiniteWeight(i, ctx) / total;
        return 0;
    }
    if (treeWeight == 0)
        return 0;
    uint64_t bitTrail = *lightToBitTrail[lightIndex];
    int nodeIndex = 0;
    Float pmf = treeWeight / total;
    while (!nodes[nodeIndex].isLeaf) {
        Children c = ChildrenAt(nodeIndex, ctx);
        int child = int(bitTrail & 1);
        if (c.importance[child] == 0)
            return 0;
        pmf *= c.importance[child] / (c.importance[0] + c.importance[1]);
        nodeIndex = c.index[child];
        bitTrail >>= 1;
    }
    return LoneLeafUnreachable(nodeIndex, ctx) ? 0 : pmf;
}

std::string BVHLightSampler::ToString() const {
    return "[ BVHLightSampler nodes: " + std::to_string(nodes.size()) +
           " infiniteLights: " + std::to_string(infiniteLights.size()) + " ]";
}

}  // namespace pbrt
