// The traversal limit (issue 24): how fast Embree alone traces a scene's own rays, beside how fast
// the renderer traces them while rendering. A path tracer cannot go faster than its traversal, so
// the ratio of the two says how much of a render's time is Embree's and how much is ours.
//
// For each scene, untimed: a render with a RayLog attached records every query the aggregate
// answers (closest-hit and shadow rays, in the order the render asked them). Then, timed on the same
// number of threads: a render without the log (the renderer's rays/s), and Embree tracing the
// recorded rays through EmbreeAggregate::Traverse, which skips building the interaction (Embree's
// rays/s, also split into closest-hit and shadow rays, and the camera's own rays, one per pixel).
//
// Scenes: the Cornell box of tests/support/scenes.h and scenes/*.pbrt below; PBRT_EXT_TRAVERSAL_SCENES may
// add pbrt files (a colon-separated list), e.g. the public scenes of docs/benchmarks.md.
#include "tests/support/scenes.h"

#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/shapes/raylog.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>
#include <pmmintrin.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

using namespace pbrt;

namespace {

// Makes the scene with the given samples per pixel, rendering on the given number of threads.
using MakeScene = std::function<std::unique_ptr<Scene>(int spp, int threads)>;

// Enough rays for a steady rate, few enough to keep (40 bytes each).
constexpr size_t kRayLogCapacity = size_t(1) << 22;

std::vector<LoggedRay> RecordRays(MakeScene make, int spp, int threads) {
    std::unique_ptr<Scene> scene = make(spp, threads);
    RayLog log(kRayLogCapacity);
    scene->aggregate.SetRayLog(&log);
    Render(*scene, {threads, true});
    scene->aggregate.SetRayLog(nullptr);
    return log.Rays();
}

// One ray through the centre of each pixel: the camera's most coherent rays.
std::vector<LoggedRay> CameraRays(const Scene &scene) {
    std::vector<LoggedRay> rays;
    for (Point2i p : scene.film.PixelBounds()) {
        CameraSample cs{Point2f(p.x + 0.5f, p.y + 0.5f), Point2f(0.5f, 0.5f)};
        if (pstd::optional<CameraRayDifferential> cr = scene.GenerateCameraRay(cs, 1))
            rays.push_back({cr->ray, Infinity, false});
    }
    return rays;
}

// Embree's rays per second over the rays, on the given number of threads: the rays in order,
// in blocks of consecutive rays, repeated for at least half a second.
double EmbreeRaysPerSecond(const Scene &scene, const std::vector<LoggedRay> &rays, int threads) {
    if (rays.empty())
        return 0;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    std::atomic<size_t> hits{0};
    size_t traced = 0;
    const auto start = std::chrono::steady_clock::now();
    double seconds = 0;
    while (seconds < 0.5) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](auto range) {
            _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
            _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
            size_t n = 0;
            for (size_t i = range.begin(); i != range.end(); ++i)
                n += scene.aggregate.Traverse(rays[i]);
            hits += n;
        });
        traced += rays.size();
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    benchmark::DoNotOptimize(hits.load());
    return double(traced) / seconds;
}

std::vector<LoggedRay> OfKind(const std::vector<LoggedRay> &rays, bool shadow) {
    std::vector<LoggedRay> kept;
    for (const LoggedRay &r : rays)
        if (r.shadow == shadow)
            kept.push_back(r);
    return kept;
}

// recordSpp keeps the log within its capacity; renderSpp makes the timed render last a while.
void MeasureLimit(benchmark::State &state, const MakeScene &make, int recordSpp, int renderSpp) {
    const int threads = int(state.range(0));
    for (auto _ : state) {
        try {
            std::vector<LoggedRay> rays = RecordRays(make, recordSpp, threads);
            std::unique_ptr<Scene> scene = make(renderSpp, threads);
            RenderStatistics stats = Render(*scene, {threads, true});
            const double embree = EmbreeRaysPerSecond(*scene, rays, threads);
            const std::vector<LoggedRay> shadowRays = OfKind(rays, true);
            state.counters["render_rays/s"] = stats.RaysPerSecond();
            state.counters["embree_rays/s"] = embree;
            state.counters["embree_closest/s"] = EmbreeRaysPerSecond(*scene, OfKind(rays, false), threads);
            state.counters["embree_shadow/s"] = EmbreeRaysPerSecond(*scene, shadowRays, threads);
            state.counters["embree_camera/s"] = EmbreeRaysPerSecond(*scene, CameraRays(*scene), threads);
            // The share of the render's time that Embree's traversal of its rays would take.
            state.counters["traversal_share"] = stats.RaysPerSecond() / embree;
            state.counters["shadow_fraction"] = double(shadowRays.size()) / double(rays.size());
        } catch (const std::exception &e) {
            state.SkipWithError(e.what());
            break;
        }
    }
}

MakeScene SceneFile(const std::string &path) {
    return [path](int spp, int threads) {
        RenderOverrides overrides;
        overrides.spp = spp;
        overrides.nThreads = threads;
        overrides.quiet = true;
        return LoadScene(path, overrides);
    };
}

void Register(const std::string &name, MakeScene make, int recordSpp, int renderSpp) {
    benchmark::internal::Benchmark *b = benchmark::RegisterBenchmark(
        name.c_str(), [=](benchmark::State &state) { MeasureLimit(state, make, recordSpp, renderSpp); });
    for (int t = 1; t <= int(std::thread::hardware_concurrency()); t *= 2)
        b->Arg(t);
    b->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
}

// Registered before main() runs, since the extra scenes come from the environment.
const bool registered = [] {
    Register("Limit/CornellDiffuse", [](int spp, int) {
        return testscenes::CornellBox(Point2i(256, 256), spp, {}, DiffuseMaterial{Spectrum(0.73f)});
    }, 4, 64);
    const std::string scenes = std::string(PBRT_EXT_SOURCE_DIR) + "/scenes/";
    Register("Limit/cornell-box.pbrt", SceneFile(scenes + "cornell-box.pbrt"), 2, 32);
    Register("Limit/fabric-showcase.pbrt", SceneFile(scenes + "fabric-showcase.pbrt"), 2, 16);
    if (const char *extra = std::getenv("PBRT_EXT_TRAVERSAL_SCENES")) {
        std::stringstream list(extra);
        for (std::string path; std::getline(list, path, ':');)
            if (!path.empty())
                Register("Limit/extra/" + std::filesystem::path(path).filename().string(), SceneFile(path), 1, 8);
    }
    return true;
}();

}  // namespace
