// The cost of path guiding's SD-tree (pbrt_ext/integrators/sdtree.h): per path vertex, sampling
// a direction from a learned quadtree, its density, and a record (spatial jitter, directional box
// splat); per iteration, refining a tree of a million records, with its node counts and bytes.
// Counters: "calls/s" for the per-vertex operations; "nodes", "leaves" and "MB" for the tree.
#include "pbrt_ext/integrators/sdtree.h"
#include "pbrt_ext/util/rng.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

using namespace pbrt;

namespace {

// A record's position, direction and value: radiance arriving mostly from a bright window and a
// lamp, as in a room (a learned tree then has deep quadrants where they are).
struct Record {
    Point3f p;
    Vector3f w;
    double value;
};

std::vector<Record> Records(int n, uint64_t seed) {
    RNG rng(seed);
    std::vector<Record> records(static_cast<size_t>(n));
    for (Record &r : records) {
        r.p = Point3f(rng.Uniform<Float>(), rng.Uniform<Float>(), rng.Uniform<Float>());
        Float u = rng.Uniform<Float>();
        Vector3f toWindow = Normalize(Vector3f(1.2f, 0.5f, 0.8f) - Vector3f(r.p));
        Point2f jitter(rng.Uniform<Float>(), rng.Uniform<Float>());
        r.w = u < 0.5f ? Normalize(toWindow + 0.05f * DirectionFromCanonical(jitter))
                       : DirectionFromCanonical(jitter);
        r.value = u < 0.5f ? 20 : 0.1;
    }
    return records;
}

SDTree Learned(int records, int iterations) {
    SDTree tree(Bounds3f(Point3f(0, 0, 0), Point3f(1, 1, 1)));
    RNG rng(1);
    for (int k = 0; k < iterations; ++k) {
        for (const Record &r : Records(records, uint64_t(k)))
            tree.Record(r.p, r.w, r.value, rng);
        tree.Refine(k);
    }
    return tree;
}

void PerVertex(benchmark::State &state, int op) {
    static const SDTree tree = Learned(200000, 4);
    const std::vector<Record> in = Records(4096, 99);
    SDTree &recording = const_cast<SDTree &>(tree);
    RNG rng(2);
    size_t i = 0;
    for (auto _ : state) {
        const Record &r = in[i++ % in.size()];
        const DTree &guide = tree.SamplingTree(r.p);
        if (op == 0)
            benchmark::DoNotOptimize(guide.Sample(Point2f(Float(r.value * 0.01), r.w.x * 0.5f + 0.5f)));
        else if (op == 1)
            benchmark::DoNotOptimize(guide.PDF(CanonicalFromDirection(r.w)));
        else
            recording.Record(r.p, r.w, r.value, rng);
    }
    state.counters["calls/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_SampleDirection(benchmark::State &state) { PerVertex(state, 0); }
void BM_DirectionPDF(benchmark::State &state) { PerVertex(state, 1); }
void BM_Record(benchmark::State &state) { PerVertex(state, 2); }

// One iteration's refinement after a million records, over a tree that learned three before.
void BM_Refine(benchmark::State &state) {
    SDTree::Statistics stats;
    for (auto _ : state) {
        state.PauseTiming();
        SDTree tree = Learned(1000000, 3);
        RNG rng(4);
        for (const Record &r : Records(1000000, 3))
            tree.Record(r.p, r.w, r.value, rng);
        state.ResumeTiming();
        tree.Refine(3);
        stats = tree.Stats();
    }
    state.counters["nodes"] = stats.spatialNodes + stats.directionalNodes;
    state.counters["leaves"] = stats.leaves;
    state.counters["MB"] = double(stats.bytes) / (1 << 20);
}

}  // namespace

BENCHMARK(BM_SampleDirection);
BENCHMARK(BM_DirectionPDF);
BENCHMARK(BM_Record);
BENCHMARK(BM_Refine)->Unit(benchmark::kMillisecond)->Iterations(3);
