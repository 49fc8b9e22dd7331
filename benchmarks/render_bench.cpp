// Renderer throughput: camera samples per second and rays per second of the path tracer for 1 ... all
// threads, on the Cornell box of tests/support/scenes.h (256 x 256, 64 spp, maxdepth 5, as the issue
// specifies) with diffuse and with fabric boxes, and on the fabric scenes of scenes/ loaded through
// LoadScene, at a sample count that keeps one single-threaded render near 5 s; and of bdpt and
// lightpath on the diffuse box and bdpt on scenes/caustic-fabric.pbrt, at 16 spp. Scene creation (and
// file loading) is not timed. With PBRT_EXT_BENCH_IMAGES set to a folder, each benchmark also writes
// the image it rendered there as PNG.
#include "tests/support/scenes.h"

#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <exception>
#include <string>
#include <thread>

using namespace pbrt;

namespace {

// Renders the scene makeScene() returns once per iteration with state.range(0) threads.
template <typename MakeScene>
void Measure(benchmark::State &state, MakeScene makeScene, const std::string &imageName) {
    const int threads = int(state.range(0));
    RenderStatistics total;
    std::unique_ptr<Scene> scene;
    for (auto _ : state) {
        state.PauseTiming();
        try {
            scene = makeScene(threads);
        } catch (const std::exception &e) {
            state.SkipWithError(e.what());
            break;
        }
        state.ResumeTiming();
        RenderStatistics stats = Render(*scene, {threads, true});
        total.seconds += stats.seconds;
        total.cameraSamples += stats.cameraSamples;
        total.closestRays += stats.closestRays;
        total.shadowRays += stats.shadowRays;
    }
    if (!scene)
        return;
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

void RenderCornellBox(benchmark::State &state, Material boxes, const char *imageName,
                      IntegratorType integrator = IntegratorType::Path, int spp = 64) {
    Measure(state, [&](int) {
        IntegratorOptions options;
        options.type = integrator;
        return testscenes::CornellBox(Point2i(256, 256), spp, options, boxes);
    }, imageName);
}

// scenes/<name>.pbrt with spp samples per pixel instead of the file's.
void RenderSceneFile(benchmark::State &state, const std::string &name, int spp) {
    Measure(state, [&](int threads) {
        RenderOverrides overrides;
        overrides.spp = spp;
        overrides.nThreads = threads;
        overrides.quiet = true;
        return LoadScene(std::string(PBRT_EXT_SOURCE_DIR) + "/scenes/" + name + ".pbrt", overrides);
    }, name);
}

void CornellDiffuse(benchmark::State &state) {
    RenderCornellBox(state, DiffuseMaterial{Spectrum(0.73f)}, "cornell_diffuse");
}
void CornellFabric(benchmark::State &state) {
    FabricMaterial fabric;
    fabric.reflectance = Spectrum(0.73f);
    fabric.roughness = 0.3f;
    RenderCornellBox(state, fabric, "cornell_fabric");
}
// The paths-from-the-lights integrators on the diffuse box, at 16 spp: a light subpath and
// every connection per camera sample.
void CornellBDPT(benchmark::State &state) {
    RenderCornellBox(state, DiffuseMaterial{Spectrum(0.73f)}, "cornell_bdpt", IntegratorType::BDPT, 16);
}
void CornellLightPath(benchmark::State &state) {
    RenderCornellBox(state, DiffuseMaterial{Spectrum(0.73f)}, "cornell_lightpath",
                     IntegratorType::LightPath, 16);
}
void FabricCylinder(benchmark::State &state) { RenderSceneFile(state, "fabric-cylinder", 32); }
void CausticFabric(benchmark::State &state) { RenderSceneFile(state, "caustic-fabric", 16); }
void FabricShowcase(benchmark::State &state) { RenderSceneFile(state, "fabric-showcase", 32); }

}  // namespace

BENCHMARK(CornellDiffuse)->Apply(ThreadCounts);
BENCHMARK(CornellFabric)->Apply(ThreadCounts);
BENCHMARK(FabricCylinder)->Apply(ThreadCounts);
BENCHMARK(FabricShowcase)->Apply(ThreadCounts);
BENCHMARK(CornellBDPT)->Apply(ThreadCounts);
BENCHMARK(CornellLightPath)->Apply(ThreadCounts);
BENCHMARK(CausticFabric)->Apply(ThreadCounts);
