// Renderer throughput: camera samples per second and rays per second of the path tracer on the
// Cornell box of tests/scenes.h (256 x 256, 64 spp, maxdepth 5, as the issue specifies), with
// diffuse boxes and with fabric boxes, for 1 ... all threads.
#include "scenes.h"

#include "pbrt_ext/render.h"

#include <benchmark/benchmark.h>

#include <thread>

using namespace pbrt;

namespace {

void RenderCornellBox(benchmark::State &state, Material boxes) {
    const int threads = int(state.range(0));
    RenderStatistics total;
    for (auto _ : state) {
        state.PauseTiming();
        auto scene = testscenes::CornellBox(Point2i(256, 256), 64, {5, false, PathStrategy::MIS},
                                            boxes);
        state.ResumeTiming();
        RenderStatistics stats = Render(*scene, {threads, true});
        total.seconds += stats.seconds;
        total.cameraSamples += stats.cameraSamples;
        total.closestRays += stats.closestRays;
        total.shadowRays += stats.shadowRays;
    }
    state.counters["camera_samples/s"] = total.CameraSamplesPerSecond();
    state.counters["rays/s"] = total.RaysPerSecond();
    state.counters["rays/sample"] = double(total.closestRays + total.shadowRays) /
                                    double(total.cameraSamples);
}

void ThreadCounts(benchmark::internal::Benchmark *b) {
    for (int t = 1; t <= int(std::thread::hardware_concurrency()); t *= 2)
        b->Arg(t);
    b->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
}

void CornellDiffuse(benchmark::State &state) {
    RenderCornellBox(state, DiffuseMaterial{SampledSpectrum(0.73f)});
}
void CornellFabric(benchmark::State &state) {
    FabricMaterial fabric;
    fabric.reflectance = SampledSpectrum(0.73f);
    fabric.roughness = 0.3f;
    RenderCornellBox(state, fabric);
}

}  // namespace

BENCHMARK(CornellDiffuse)->Apply(ThreadCounts);
BENCHMARK(CornellFabric)->Apply(ThreadCounts);
