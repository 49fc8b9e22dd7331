// Start-up and memory: the wall time and peak resident memory of a whole `pbrt_ext` process
// rendering a scene at 1 sample per pixel, which is what a convergence sweep of many short renders
// pays each time: loading the program, parsing, building the BVH and light sampler, the film.
// With PBRT_EXT_PBRT_V4 set to pbrt-v4's executable, the same command of pbrt-v4 is measured
// beside it. Scenes: scenes/cornell-box.pbrt (256 x 256), and the scene file PBRT_EXT_LARGE_SCENE
// names, if set (a large public scene, e.g. pbrt-v4-scenes' crown; not ours to ship).
#include <benchmark/benchmark.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

extern char **environ;

namespace {

struct ProcessCost {
    double seconds = 0, peakRssMB = 0;
    bool ok = false;
};

// Runs argv to completion from the scene's folder (for its relative paths), its output discarded.
ProcessCost RunProcess(std::vector<std::string> argv, const std::string &scene) {
    std::vector<char *> args;
    for (std::string &a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    std::string dir = std::filesystem::path(scene).parent_path().string();
    posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
    ProcessCost cost;
    auto start = std::chrono::steady_clock::now();
    pid_t pid;
    if (posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ) == 0) {
        int status = 0;
        rusage usage{};
        if (wait4(pid, &status, 0, &usage) == pid) {
            cost.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            cost.peakRssMB = double(usage.ru_maxrss) / 1024;  // kilobytes on Linux
            cost.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
        }
    }
    posix_spawn_file_actions_destroy(&actions);
    return cost;
}

std::string Output() {
    return (std::filesystem::temp_directory_path() / "pbrt_ext_startup_bench.exr").string();
}

// Both renderers take the same arguments for these: 1 spp, all threads, quiet, EXR output.
std::vector<std::string> Command(const std::string &executable, const std::string &scene) {
    return {executable, "--spp", "1", "--quiet", "--outfile", Output(), scene};
}

void Measure(benchmark::State &state, const std::string &executable, const std::string &scene) {
    ProcessCost best;
    for (auto _ : state) {
        ProcessCost cost = RunProcess(Command(executable, scene), scene);
        if (!cost.ok) {
            state.SkipWithError(("failed: " + executable + " " + scene).c_str());
            return;
        }
        state.SetIterationTime(cost.seconds);
        if (!best.ok || cost.seconds < best.seconds) best.seconds = cost.seconds;
        best.peakRssMB = std::max(best.peakRssMB, cost.peakRssMB);
        best.ok = true;
    }
    state.counters["best_s"] = best.seconds;
    state.counters["peak_rss_MB"] = best.peakRssMB;
    std::filesystem::remove(Output());
}

void Register(const std::string &name, const std::string &scene) {
    auto add = [&](const std::string &renderer, const std::string &executable) {
        benchmark::RegisterBenchmark(("StartUp/" + name + "/" + renderer).c_str(),
                                     [=](benchmark::State &state) { Measure(state, executable, scene); })
            ->Iterations(3)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
    };
    add("pbrt_ext", PBRT_EXT_CLI);
    if (const char *v4 = std::getenv("PBRT_EXT_PBRT_V4")) add("pbrt-v4", v4);
}

const bool kRegistered = [] {
    Register("cornell-box", std::string(PBRT_EXT_SOURCE_DIR) + "/scenes/cornell-box.pbrt");
    if (const char *large = std::getenv("PBRT_EXT_LARGE_SCENE"))
        Register(std::filesystem::path(large).stem().string(), std::filesystem::absolute(large).string());
    return true;
}();

}  // namespace
