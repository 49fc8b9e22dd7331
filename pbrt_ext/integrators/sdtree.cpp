#include "pbrt_ext/integrators/sdtree.h"

#include "pbrt_ext/util/math.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <fstream>
#include <istream>
#include <ostream>
#include <stdexcept>

namespace pbrt {

Point2f CanonicalFromDirection(Vector3f w) {
    Float cosTheta = Clamp(w.z, -1, 1);
    Float phi = std::atan2(w.y, w.x);
    if (phi < 0)
        phi += 2 * Pi;
    return Point2f(std::min((cosTheta + 1) / 2, OneMinusEpsilon), std::min(phi * Inv2Pi, OneMinusEpsilon));
}

Vector3f DirectionFromCanonical(Point2f c) {
    Float cosTheta = 2 * c.x - 1, sinTheta = SafeSqrt(1 - Sqr(cosTheta));
    Float phi = 2 * Pi * c.y;
    return Vector3f(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
}

// ---- DTree --------------------------------------------------------------------------------

namespace {

// Quadrant q of a node covers [origin + (x, y) size / 2, ... + size / 2), x = q & 1, y = q >> 1.
Point2f QuadrantOrigin(Point2f origin, Float size, int q) {
    return Point2f(origin.x + (q & 1) * size / 2, origin.y + (q >> 1) * size / 2);
}

int QuadrantOf(Point2f c) { return (c.x >= 0.5f ? 1 : 0) | (c.y >= 0.5f ? 2 : 0); }

// c in quadrant q's own unit square.
Point2f IntoQuadrant(Point2f c, int q) {
    return Point2f(Clamp(2 * c.x - (q & 1), 0, OneMinusEpsilon), Clamp(2 * c.y - (q >> 1), 0, OneMinusEpsilon));
}

Float OverlapArea(const Bounds2f &a, const Bounds2f &b) {
    Float dx = std::min(a.pMax.x, b.pMax.x) - std::max(a.pMin.x, b.pMin.x);
    Float dy = std::min(a.pMax.y, b.pMax.y) - std::max(a.pMin.y, b.pMin.y);
    return dx > 0 && dy > 0 ? dx * dy : 0;
}

}  // namespace

DTree::DTree() : nodes(1) {}

void DTree::RecordBox(const Bounds2f &box, double value) {
    Float area = box.Area();
    if (!(area > 0) || !(value > 0) || !std::isfinite(value))
        return;
    RecordBox(0, Point2f(0, 0), 1, box, value / area);
}

void DTree::RecordBox(uint32_t node, Point2f origin, Float size, const Bounds2f &box, double density) {
    for (int q = 0; q < 4; ++q) {
        Point2f o = QuadrantOrigin(origin, size, q);
        Bounds2f quadrant(o, Point2f(o.x + size / 2, o.y + size / 2));
        Float overlap = OverlapArea(quadrant, box);
        if (overlap <= 0)
            continue;
        if (uint32_t child = nodes[node].child[size_t(q)])
            RecordBox(child, o, size / 2, box, density);
        else
            nodes[node].sum[size_t(q)].Add(density * overlap);
    }
}

void DTree::Finalize() { FinalizeNode(0); }

double DTree::FinalizeNode(uint32_t node) {
    for (int q = 0; q < 4; ++q)
        if (uint32_t child = nodes[node].child[size_t(q)]) {
            double sum = FinalizeNode(child);
            nodes[node].sum[size_t(q)].Store(sum);
        }
    return nodes[node].Total();
}

double DTree::Energy() const { return nodes[0].Total(); }

Float DTree::MeanRadiance() const { return weight > 0 ? Float(Energy() / weight * Inv4Pi) : 0; }

Float DTree::Radiance(Point2f c) const { return PDF(c) * MeanRadiance(); }

Point2f DTree::Sample(Point2f u, Float *pdf) const {
    // Each level picks the column by u.x and the row within it by u.y, both rescaled to the
    // part they chose (in double: 20 levels take 20 bits of each).
    // Rescaled values stay below 1, so that a side of zero weight is never chosen.
    constexpr double kBelowOne = 1 - 1e-12;
    double ux = u.x, uy = u.y, x = 0, y = 0, size = 1, density = 1;
    uint32_t node = 0;
    for (;;) {
        const Node &n = nodes[node];
        double s[4] = {n.sum[0].Load(), n.sum[1].Load(), n.sum[2].Load(), n.sum[3].Load()};
        if (!(s[0] + s[1] + s[2] + s[3] > 0))
            s[0] = s[1] = s[2] = s[3] = 1;
        double left = s[0] + s[2], right = s[1] + s[3];
        int col = ux * (left + right) < left ? 0 : 1;
        ux = col == 0 ? ux * (left + right) / left : (ux * (left + right) - left) / right;
        double top = s[col], bottom = s[col + 2];
        int row = top + bottom > 0 && uy * (top + bottom) < top ? 0 : 1;
        if (top + bottom > 0)
            uy = row == 0 ? uy * (top + bottom) / top : (uy * (top + bottom) - top) / bottom;
        int q = col | (row << 1);
        density *= 4 * s[q] / (left + right);
        size /= 2;
        x += col * size;
        y += row * size;
        ux = std::clamp(ux, 0.0, kBelowOne);
        uy = std::clamp(uy, 0.0, kBelowOne);
        if (!n.child[size_t(q)]) {
            if (pdf)
                *pdf = Float(density);
            return Point2f(std::min(Float(x + ux * size), OneMinusEpsilon),
                           std::min(Float(y + uy * size), OneMinusEpsilon));
        }
        node = n.child[size_t(q)];
    }
}

Float DTree::PDF(Point2f c) const {
    double pdf = 1;
    uint32_t node = 0;
    for (;;) {
        const Node &n = nodes[node];
        double total = n.Total();
        int q = QuadrantOf(c);
        if (total > 0)
            pdf *= 4 * n.sum[size_t(q)].Load() / total;
        if (!n.child[size_t(q)] || pdf == 0)
            return Float(pdf);
        c = IntoQuadrant(c, q);
        node = n.child[size_t(q)];
    }
}

Float DTree::LeafSize(Point2f c) const {
    Float size = 1;
    uint32_t node = 0;
    for (;;) {
        int q = QuadrantOf(c);
        size /= 2;
        uint32_t child = nodes[node].child[size_t(q)];
        if (!child)
            return size;
        c = IntoQuadrant(c, q);
        node = child;
    }
}

int DTree::Depth() const {
    std::vector<int> depth(nodes.size(), 1);
    int deepest = 1;
    for (size_t i = 0; i < nodes.size(); ++i)
        for (uint32_t child : nodes[i].child)
            if (child) {
                depth[child] = depth[i] + 1;
                deepest = std::max(deepest, depth[child]);
            }
    return deepest;
}

DTree DTree::Refined(double threshold, int maxDepth) const {
    DTree refined;
    const double total = Energy();
    // (node of this tree or -1 for none below a leaf, its energy fraction split evenly, the new
    // node, its depth): a quadrant with a fraction above the threshold gets a child.
    struct Item {
        int64_t old;
        double fraction;
        uint32_t node;
        int depth;
    };
    std::deque<Item> queue{{0, 1, 0, 1}};
    while (!queue.empty()) {
        Item it = queue.front();
        queue.pop_front();
        for (int q = 0; q < 4; ++q) {
            double fraction = it.old >= 0 && total > 0
                                  ? nodes[size_t(it.old)].sum[size_t(q)].Load() / total
                                  : it.fraction / 4;
            if (!(fraction > threshold) || it.depth >= maxDepth)
                continue;
            uint32_t child = uint32_t(refined.nodes.size());
            refined.nodes.emplace_back();
            refined.nodes[it.node].child[size_t(q)] = child;
            int64_t oldChild = it.old >= 0 && nodes[size_t(it.old)].child[size_t(q)]
                                   ? int64_t(nodes[size_t(it.old)].child[size_t(q)])
                                   : -1;
            queue.push_back({oldChild, fraction, child, it.depth + 1});
        }
    }
    return refined;
}

void DTree::Write(std::ostream &out) const {
    out.write(reinterpret_cast<const char *>(&weight), sizeof(weight));
    uint32_t count = uint32_t(nodes.size());
    out.write(reinterpret_cast<const char *>(&count), sizeof(count));
    for (const Node &n : nodes) {
        out.write(reinterpret_cast<const char *>(n.child.data()), sizeof(n.child));
        for (const AtomicSum &s : n.sum) {
            double v = s.Load();
            out.write(reinterpret_cast<const char *>(&v), sizeof(v));
        }
    }
}

DTree DTree::Read(std::istream &in) {
    DTree tree;
    if (!in.read(reinterpret_cast<char *>(&tree.weight), sizeof(tree.weight)) || !(tree.weight >= 0) ||
        !std::isfinite(tree.weight))
        throw std::runtime_error("a directional tree's record count is missing or invalid");
    uint32_t count = 0;
    if (!in.read(reinterpret_cast<char *>(&count), sizeof(count)) || count == 0 || count > (1u << 26))
        throw std::runtime_error("a directional tree's node count is missing or out of range");
    tree.nodes.resize(count);
    for (uint32_t i = 0; i < count; ++i) {
        Node &n = tree.nodes[i];
        if (!in.read(reinterpret_cast<char *>(n.child.data()), sizeof(n.child)))
            throw std::runtime_error("the file ends inside a directional tree");
        for (AtomicSum &s : n.sum) {
            double v;
            if (!in.read(reinterpret_cast<char *>(&v), sizeof(v)))
                throw std::runtime_error("the file ends inside a directional tree");
            if (!(v >= 0) || !std::isfinite(v))
                throw std::runtime_error("a directional tree holds a negative or non-finite energy");
            s.Store(v);
        }
        if (!std::isfinite(n.Total()))
            throw std::runtime_error("a directional tree's energies overflow");
        // Children come after their parents: no cycle, every node reached once.
        for (uint32_t child : n.child)
            if (child != 0 && (child <= i || child >= count))
                throw std::runtime_error("a directional tree's child index is out of order");
    }
    return tree;
}

// ---- SDTree -------------------------------------------------------------------------------

SDTree::SDTree(const Bounds3f &sceneBounds, SDTreeOptions options) : options(options) {
    // A cube around the scene, a little larger, so that every cell of a level has one shape.
    Point3f center = (sceneBounds.pMin + sceneBounds.pMax) / 2;
    Vector3f d = sceneBounds.Diagonal();
    Float half = 0.5f * 1.01f * std::max({d.x, d.y, d.z, Float(1e-3)});
    bounds = Bounds3f(center - Vector3f(half, half, half), center + Vector3f(half, half, half));
    nodes.push_back(Node{0, {0, 0}, 0});
    leaves.push_back(std::make_unique<Leaf>());
    leaves.back()->bsdfFraction = options.bsdfFraction;
}

int SDTree::LeafIndex(Point3f p, Bounds3f *box) const {
    Bounds3f b = bounds;
    int node = 0;
    while (nodes[size_t(node)].leaf < 0) {
        const Node &n = nodes[size_t(node)];
        Float mid = (b.pMin[n.axis] + b.pMax[n.axis]) / 2;
        int side = p[n.axis] >= mid ? 1 : 0;
        (side ? b.pMin : b.pMax)[n.axis] = mid;
        node = n.child[size_t(side)];
    }
    if (box)
        *box = b;
    return nodes[size_t(node)].leaf;
}

void SDTree::Record(Point3f p, Vector3f w, double value, RNG &rng) {
    // A record of no radiance carries no energy, but counts toward splitting its leaf: where paths
    // find nothing, the tree is refined as much as where they do.
    if (!(value >= 0) || !std::isfinite(value))
        return;
    // Stochastic box filtering in space: the record lands at a point jittered over a cell of
    // the leaf's size around p.
    Bounds3f box;
    LeafIndex(p, &box);
    Vector3f size = box.Diagonal();
    Point3f q;
    for (int i = 0; i < 3; ++i)
        q[i] = Clamp(p[i] + (rng.Uniform<Float>() - 0.5f) * size[i], bounds.pMin[i], bounds.pMax[i]);
    Leaf &leaf = *leaves[size_t(LeafIndex(q, nullptr))];
    leaf.records.fetch_add(1, std::memory_order_relaxed);
    if (value == 0)
        return;
    // Box filtering in direction over the recording tree's leaf quadrant around w.
    Point2f c = CanonicalFromDirection(w);
    Float s = leaf.building.LeafSize(c) / 2;
    Bounds2f footprint(Point2f(std::max<Float>(0, c.x - s), std::max<Float>(0, c.y - s)),
                       Point2f(std::min<Float>(1, c.x + s), std::min<Float>(1, c.y + s)));
    leaf.building.RecordBox(footprint, value);
}

void SDTree::SplitLeaves(uint64_t threshold) {
    size_t bytes = Stats().bytes;
    for (size_t node = 0; node < nodes.size() && bytes < options.maxBytes; ++node) {
        int leafIndex = nodes[node].leaf;
        if (leafIndex < 0 || leaves[size_t(leafIndex)]->records.load() <= threshold)
            continue;
        // Halved along the leaf's axis; its halves split along the next (cells stay at most
        // twice as long as wide).
        int axis = nodes[node].axis, next = (axis + 1) % 3;
        Leaf &leaf = *leaves[size_t(leafIndex)];
        uint64_t half = leaf.records.load() / 2;
        auto second = std::make_unique<Leaf>();
        second->sampling = leaf.sampling;
        second->building = leaf.building;
        second->records = half;
        second->bsdfFraction = leaf.bsdfFraction;
        leaf.records = half;
        bytes += size_t(second->sampling.NodeCount() + second->building.NodeCount()) * 48 + 2 * sizeof(Node) +
                 sizeof(Leaf);
        int a = int(nodes.size()), b = a + 1;
        nodes.push_back(Node{next, {0, 0}, leafIndex});
        nodes.push_back(Node{next, {0, 0}, int(leaves.size())});
        leaves.push_back(std::move(second));
        nodes[node] = Node{axis, {a, b}, -1};
    }
}

void SDTree::Refine(int iteration) {
    // What was recorded becomes what is sampled (a leaf that recorded nothing keeps its tree),
    // with the BSDF fraction its guided samples favoured (one that had too few keeps its own).
    for (auto &leaf : leaves) {
        leaf->building.Finalize();
        leaf->building.SetWeight(double(leaf->records.load()));
        if (leaf->building.Energy() > 0)
            leaf->sampling = leaf->building;
        if (options.learnBSDFFraction)
            leaf->bsdfFraction = leaf->fraction.Best(leaf->bsdfFraction);
        leaf->fraction.Reset();
    }
    SplitLeaves(uint64_t(options.spatialThreshold * std::sqrt(std::pow(2.0, iteration))));
    for (auto &leaf : leaves) {
        leaf->building = leaf->sampling.Refined(options.directionalThreshold, options.maxDirectionalDepth);
        leaf->records = 0;
    }
}

SDTree::Statistics SDTree::Stats() const {
    Statistics s;
    s.spatialNodes = int(nodes.size());
    s.leaves = int(leaves.size());
    for (const auto &leaf : leaves) {
        s.directionalNodes += leaf->sampling.NodeCount() + leaf->building.NodeCount();
        s.maxDirectionalDepth = std::max(s.maxDirectionalDepth, leaf->sampling.Depth());
    }
    // A quadtree node holds 4 children and 4 sums (48 bytes); a spatial node 16, a leaf 24.
    s.bytes = size_t(s.directionalNodes) * 48 + nodes.size() * sizeof(Node) + leaves.size() * sizeof(Leaf);
    return s;
}

namespace {

constexpr char kMagic[8] = {'P', 'B', 'X', 'S', 'D', 'T', 'R', '3'};

template <typename T>
void Put(std::ostream &out, const T &v) { out.write(reinterpret_cast<const char *>(&v), sizeof(v)); }

template <typename T>
T Get(std::istream &in, const char *what) {
    T v;
    if (!in.read(reinterpret_cast<char *>(&v), sizeof(v)))
        throw std::runtime_error(std::string("the file ends before ") + what);
    return v;
}

}  // namespace

void SDTree::Write(const std::string &path) const {
    std::ofstream out(path, std::ios::binary);
    out.write(kMagic, sizeof(kMagic));
    for (int i = 0; i < 3; ++i) Put(out, bounds.pMin[i]);
    for (int i = 0; i < 3; ++i) Put(out, bounds.pMax[i]);
    Put(out, uint32_t(nodes.size()));
    for (const Node &n : nodes) {
        Put(out, int32_t(n.axis));
        Put(out, int32_t(n.child[0]));
        Put(out, int32_t(n.child[1]));
        Put(out, int32_t(n.leaf));
    }
    Put(out, uint32_t(leaves.size()));
    for (const auto &leaf : leaves) {
        leaf->sampling.Write(out);
        Put(out, leaf->bsdfFraction);
    }
    if (!out.flush())
        throw std::runtime_error(path + ": error: cannot write the guiding tree");
}

SDTree SDTree::Read(const std::string &path, const Bounds3f &sceneBounds, SDTreeOptions options) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error(path + ": error: cannot open the guiding tree");
    try {
        char magic[sizeof(kMagic)];
        if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
            throw std::runtime_error("not a guiding tree written by --guiding-save");
        SDTree tree;
        tree.options = options;
        for (int i = 0; i < 3; ++i) tree.bounds.pMin[i] = Get<Float>(in, "the bounds");
        for (int i = 0; i < 3; ++i) tree.bounds.pMax[i] = Get<Float>(in, "the bounds");
        SDTree expected(sceneBounds, options);
        if (tree.bounds.pMin != expected.bounds.pMin || tree.bounds.pMax != expected.bounds.pMax)
            throw std::runtime_error("it was trained on another scene (its bounds differ)");
        uint32_t nodeCount = Get<uint32_t>(in, "the spatial tree");
        if (nodeCount == 0 || nodeCount > (1u << 26))
            throw std::runtime_error("its spatial node count is out of range");
        tree.nodes.resize(nodeCount);
        for (Node &n : tree.nodes) {
            n.axis = Get<int32_t>(in, "the spatial tree");
            n.child = {Get<int32_t>(in, "the spatial tree"), Get<int32_t>(in, "the spatial tree")};
            n.leaf = Get<int32_t>(in, "the spatial tree");
        }
        uint32_t leafCount = Get<uint32_t>(in, "the leaves");
        if (leafCount == 0 || leafCount > nodeCount)
            throw std::runtime_error("its leaf count is out of range");
        std::vector<int> reached(nodeCount, 0), leafUses(leafCount, 0);
        for (uint32_t i = 0; i < nodeCount; ++i) {
            const Node &n = tree.nodes[i];
            bool leaf = n.leaf >= 0;
            if ((leaf && (uint32_t(n.leaf) >= leafCount || leafUses[size_t(n.leaf)]++)) || n.axis < 0 ||
                n.axis > 2)
                throw std::runtime_error("a spatial node is malformed");
            if (!leaf)
                for (int child : n.child) {
                    if (child <= int(i) || uint32_t(child) >= nodeCount || reached[size_t(child)]++)
                        throw std::runtime_error("a spatial node's child index is out of order");
                }
        }
        if (std::count(leafUses.begin(), leafUses.end(), 1) != int(leafCount))
            throw std::runtime_error("a leaf belongs to no spatial node");
        for (uint32_t i = 0; i < leafCount; ++i) {
            auto leaf = std::make_unique<Leaf>();
            leaf->sampling = DTree::Read(in);
            leaf->bsdfFraction = Get<Float>(in, "a leaf's BSDF fraction");
            if (!(leaf->bsdfFraction > 0 && leaf->bsdfFraction <= 1))
                throw std::runtime_error("a leaf's BSDF fraction is outside (0, 1]");
            leaf->building = leaf->sampling.Refined(options.directionalThreshold, options.maxDirectionalDepth);
            tree.leaves.push_back(std::move(leaf));
        }
        return tree;
    } catch (const std::runtime_error &e) {
        throw std::runtime_error(path + ": error: " + e.what());
    }
}

}  // namespace pbrt
