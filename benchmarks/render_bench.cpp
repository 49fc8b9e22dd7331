// Renderer throughput: camera samples per second and rays per second of the path tracer on the
// Cornell box of tests/scenes.h (256 x 256, 64 spp, maxdepth 5, as the issue specifies), with
// diffuse boxes and with fabric boxes, for 1 ... all threads. With PBRT_EXT_BENCH_IMAGES set to a
// folder, each benchmark also writes the image it rendered there as PNG.
#include "scenes.h"

#include "pbrt_ext/render.h"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>
#include <thread>

using namespace pbrt;

namespace {

void RenderCornellBox(benchmark::State &state, Material boxes, const char *imageName) {
    const int threads = int(state.range(0));
    RenderStatistics total;
    std::unique_ptr<Scene> scene;
    for (auto _ : state) {
        state.PauseTiming();
        scene = testscenes::CornellBox(Point2i(256, 256), 64, {5, false, PathStrategy::MIS}, boxes);
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
    if (const char *folder = std::getenv("PBRT_EXT_BENCH_IMAGES")) {
        scene->film.GetImage().Write(std::string(folder) + "/" + imageName + "_" +
                                     std::to_string(threads) + "threads.png");
    }
}

void ThreadCounts(benchmark::internal::Benchmark *b) {
    for (int t = 1; t <= int(std::thread::hardware_concurrency()); t *= 2)
        b->Arg(t);
    b->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
}

void CornellDiffuse(benchmark::State &state) {
    RenderCornellBox(state, DiffuseMaterial{SampledSpectrum(0.73f)}, "cornell_diffuse");
}
void CornellFabric(benchmark::State &state) {
    FabricMaterial fabric;
    fabric.reflectance = SampledSpectrum(0.73f);
    fabric.roughness = 0.3f;
    RenderCornellBox(state, fabric, "cornell_fabric");
}

}  // namespace

BENCHMARK(CornellDiffuse)->Apply(ThreadCounts);
BENCHMARK(CornellFabric)->Apply(ThreadCounts);
