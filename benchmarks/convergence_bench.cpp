// The noise-to-time study (issues 5, 11 and 20): how fast each fabric sampler, path strategy,
// light sampler, sample generator and integrator removes noise from the scenes of
// scenes/convergence/ (the paper's Fig. 3 cylinder at three roughnesses under a sky and a small
// light, and at roughness 0.1 under the sky alone; a Cornell box with fabric boxes; a scene after
// Veach's MIS figure; a caustic on fabric).
//
// Each benchmark renders a scene once at n spp and compares it with the scene's reference image:
//   Convergence/<scene>/<fabric sampler>/<strategy>/spp:<n>   every fabric sampler and strategy,
//   LightSampler/<scene>/<bvh|power|uniform>/mis/spp:<n>      the light samplers (best, MIS),
//   Sampler/<scene>/<sampler>/mis/spp:<n>                     the sample generators (best, MIS),
//   Integrator/<scene>/<integrator>/mis/spp:<n>               path, bdpt, lightpath and sppm,
// recording the counters
//   seconds     the render's own time (scene loading excluded),
//   relMSE      mean over pixels and channels of (x - r)^2 / (r^2 + 1e-2),
//   efficiency  1 / (relMSE * seconds), the higher the better,
// plus spp and reference_spp. scripts/plot_convergence.py turns the JSON output
// (--benchmark_format=json or --benchmark_out=<file>) into plots and a table.
//
// A reference is rendered once at kReferenceSpp with MIS and the "best" fabric sampler and cached
// as <PBRT_EXT_BENCH_DIR, default build/bench>/reference/<scene>.spectral.exr (relative to the
// working folder); it is rendered again when missing or older than a scene file of its folder (the
// cylinders share an include). It uses another seed than the sweep, so that no sweep image shares
// its samples with the reference.
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/scene/sceneloader.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

using namespace pbrt;

namespace {

namespace fs = std::filesystem;

constexpr const char *kScenes[] = {"cylinder_r0.1", "cylinder_r0.3", "cylinder_r0.6",
                                   "cylinder_env_r0.1", "cornell_fabric"};
constexpr const char *kFabricSamplers[] = {"uniform", "cosine", "paper", "best"};
// The scenes with several lights, and the scenes for the sample generators.
constexpr const char *kLightSamplerScenes[] = {"veach_mis", "cylinder_r0.1"};
constexpr const char *kLightSamplers[] = {"bvh", "power", "uniform"};
constexpr const char *kSamplerScenes[] = {"veach_mis", "cylinder_env_r0.1"};
constexpr const char *kSamplers[] = {"independent", "stratified", "halton", "sobol",
                                     "paddedsobol", "zsobol", "pmj02bn"};
constexpr const char *kStrategies[] = {"bsdf", "light", "mis"};
// The integrators, on a caustic that only paths from the light can sample.
constexpr const char *kIntegratorScenes[] = {"caustic_fabric"};
constexpr const char *kIntegrators[] = {"path", "bdpt", "lightpath", "sppm"};
constexpr int kSweepSpp[] = {4, 16, 64, 256};
// Its own noise adds about 1/16 of the best sweep image's error at 256 spp; the plot script
// subtracts that floor. Each reference takes about 30 s on 2 cores.
constexpr int kReferenceSpp = 4096;
constexpr int kReferenceSeed = 1;
// Keeps the relative error of near-black pixels finite without letting them dominate.
constexpr double kRelMSEEpsilon = 1e-2;

fs::path ScenePath(const std::string &scene) {
    return fs::path(PBRT_EXT_SOURCE_DIR) / "scenes" / "convergence" / (scene + ".pbrt");
}

fs::path ReferencePath(const std::string &scene) {
    const char *dir = std::getenv("PBRT_EXT_BENCH_DIR");
    // ".spectral": a reference cached by a build that rendered RGB, not spectra, is not reused.
    return fs::path(dir ? dir : "build/bench") / "reference" / (scene + ".spectral.exr");
}

std::unique_ptr<Scene> LoadQuietly(const std::string &scene, RenderOverrides overrides) {
    overrides.quiet = true;
    return LoadScene(ScenePath(scene).string(), overrides);
}

RenderStatistics RenderQuietly(Scene &scene) { return Render(scene, {0, true}); }

void WriteReference(const std::string &scene, const fs::path &cached) {
    RenderOverrides overrides;
    overrides.spp = kReferenceSpp;
    overrides.seed = kReferenceSeed;
    overrides.strategy = PathStrategy::MIS;
    overrides.fabricSampler = FabricSampling::Best;
    // An unbiased integrator that samples every path of the integrators' scenes.
    for (const char *integratorScene : kIntegratorScenes)
        if (scene == integratorScene)
            overrides.integrator = "bdpt";
    std::unique_ptr<Scene> reference = LoadQuietly(scene, overrides);
    RenderStatistics stats = RenderQuietly(*reference);
    fs::create_directories(cached.parent_path());
    ImageMetadata metadata;
    metadata.samplesPerPixel = kReferenceSpp;
    metadata.renderTimeSeconds = stats.seconds;
    metadata.scene = ScenePath(scene).string();
    reference->film.GetImage().Write(cached.string(), metadata);
}

// The newest scene file of the scene's folder and of scenes/include, which some include.
fs::file_time_type NewestSceneFile(const std::string &scene) {
    auto newest = fs::file_time_type::min();
    fs::path folder = ScenePath(scene).parent_path();
    for (const fs::path &dir : {folder, folder.parent_path() / "include"})
        for (const fs::directory_entry &entry : fs::directory_iterator(dir))
            if (entry.path().extension() == ".pbrt") newest = std::max(newest, entry.last_write_time());
    return newest;
}

// Read once per process; rendered first where the cache is missing or stale.
const Image &Reference(const std::string &scene) {
    static std::map<std::string, Image> references;
    if (auto it = references.find(scene); it != references.end()) return it->second;
    fs::path cached = ReferencePath(scene);
    if (!fs::exists(cached) ||
        fs::last_write_time(cached) < NewestSceneFile(scene))
        WriteReference(scene, cached);
    return references.emplace(scene, Image::Read(cached.string())).first->second;
}

double RelMSE(const Image &image, const Image &reference) {
    Point2i res = image.Resolution();
    if (res != reference.Resolution())
        throw std::runtime_error("the reference's resolution differs from the image's");
    double sum = 0;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
            for (int c = 0; c < Image::NChannels(); ++c) {
                double r = reference.GetChannel({x, y}, c);
                double d = image.GetChannel({x, y}, c) - r;
                sum += d * d / (r * r + kRelMSEEpsilon);
            }
    return sum / (double(res.x) * res.y * Image::NChannels());
}

// Renders the scene with these overrides (spp among them) and compares it with the reference.
void Convergence(benchmark::State &state, const std::string &scene, RenderOverrides overrides) {
    try {
        const Image &reference = Reference(scene);
        std::unique_ptr<Scene> rendered = LoadQuietly(scene, overrides);
        RenderStatistics stats;
        for (auto _ : state)
            stats = RenderQuietly(*rendered);
        double relMSE = RelMSE(rendered->film.GetImage(), reference);
        state.counters["seconds"] = stats.seconds;
        state.counters["relMSE"] = relMSE;
        state.counters["efficiency"] = 1 / (relMSE * stats.seconds);
        state.counters["spp"] = *overrides.spp;
        state.counters["reference_spp"] = kReferenceSpp;
    } catch (const std::exception &e) {
        state.SkipWithError(e.what());
    }
}

// <study>/<scene>/<choice>/<strategy>/spp:<n> for every sweep count.
void RegisterSweep(const std::string &study, const std::string &scene, const std::string &choice,
                   const std::string &strategy, RenderOverrides overrides) {
    overrides.strategy = ParsePathStrategy(strategy);
    for (int spp : kSweepSpp) {
        overrides.spp = spp;
        std::string name = study + "/" + scene + "/" + choice + "/" + strategy + "/spp:" + std::to_string(spp);
        benchmark::RegisterBenchmark(name.c_str(), Convergence, scene, overrides)
            ->Iterations(1)
            ->UseRealTime()
            ->Unit(benchmark::kSecond);
    }
}

// One override (choice, e.g. &RenderOverrides::lightSampler) set to each of choices in each scene,
// under MIS with the best fabric sampler.
template <size_t NScenes, size_t NChoices>
void RegisterChoiceSweeps(const char *study, const char *const (&scenes)[NScenes],
                          const char *const (&choices)[NChoices],
                          std::optional<std::string> RenderOverrides::*choice) {
    for (const char *scene : scenes)
        for (const char *value : choices) {
            RenderOverrides overrides;
            overrides.fabricSampler = FabricSampling::Best;
            overrides.*choice = value;
            RegisterSweep(study, scene, value, "mis", overrides);
        }
}

// Scenes outermost, so that each reference is rendered (or read) at its scene's first benchmark.
bool RegisterConvergence() {
    for (const char *scene : kScenes)
        for (const char *sampler : kFabricSamplers)
            for (const char *strategy : kStrategies) {
                RenderOverrides overrides;
                overrides.fabricSampler = ParseFabricSampling(sampler);
                RegisterSweep("Convergence", scene, sampler, strategy, overrides);
            }
    RegisterChoiceSweeps("LightSampler", kLightSamplerScenes, kLightSamplers, &RenderOverrides::lightSampler);
    RegisterChoiceSweeps("Sampler", kSamplerScenes, kSamplers, &RenderOverrides::sampler);
    RegisterChoiceSweeps("Integrator", kIntegratorScenes, kIntegrators, &RenderOverrides::integrator);
    return true;
}

const bool registered = RegisterConvergence();

}  // namespace
