// Rendering a scene: tiles over all cores (TBB) in waves of samples, a progress bar, final
// statistics (pbrt-v4's ImageTileIntegrator::Render).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace pbrt {

class Scene;

// Sample indices [first, last) of every pixel.
struct SampleRange {
    int first = 0, last = 0;
    int Count() const { return last - first; }
    friend bool operator==(const SampleRange &, const SampleRange &) = default;
};

// Per-pixel time and ray counts (film/pixelstatistics.h).
struct PixelStatistics;

struct RenderOptions {
    int nThreads = 0;  // 0: all cores
    bool quiet = false;
    // Stop starting new samples after this many seconds (0: no limit). The image then holds the
    // first k samples of every pixel, for the largest k finished in time (at least 1).
    double timeLimitSeconds = 0;
    // Read before each tile: once true, tiles not yet started are skipped and Render returns,
    // every pixel holding at least the first wave (one sample). A host sets it from anywhere, a
    // signal handler included; the library never installs one (cmd/interrupt.h does, for the
    // command line). nullptr: never cancelled.
    const std::atomic<bool> *cancel = nullptr;
    bool Cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
    // Only these sample indices of the scene's sampler (which keeps its samples per pixel, so
    // that each index gives the sample it gives in a full render); unset: all of them. A render
    // of a range is a slice that merges exactly with the others (filmslice.h). Must lie within
    // [0, samples per pixel) and not be empty (std::invalid_argument otherwise), and the
    // integrator's samples must be independent of each other: not sppm.
    std::optional<SampleRange> samples = std::nullopt;
    // Called by the tile integrators after each wave, with the samples every pixel has taken;
    // the film then holds their image, splats scaled. pbrt-v4's --write-partial-images,
    // --mse-reference-image and --display-server look at the image here. sppm, mlt and function
    // render no waves and never call it.
    std::function<void(int samplesPerPixel)> afterWave = nullptr;
    // Filled by the tile integrators when set (sized to the film's pixel bounds); sppm, mlt and
    // function leave it as it is.
    PixelStatistics *pixelStatistics = nullptr;
};

struct RenderStatistics {
    double seconds = 0;
    int64_t cameraSamples = 0;
    int64_t closestRays = 0, shadowRays = 0;
    int64_t discardedSamples = 0;  // radiance NaN or infinite: counted, never written
    // Taken by every pixel (fewer than asked when stopped early); of a sample range, those from
    // its first index on.
    int samplesPerPixel = 0;
    int maxSamplesPerPixel = 0;    // taken by some pixels: more only when cancelled mid-wave
    bool cancelled = false;        // RenderOptions::cancel stopped it before every sample was taken
    std::string integratorStatistics;  // what the integrator adds, a line each (guiding's tree)

    double CameraSamplesPerSecond() const { return cameraSamples / seconds; }
    double RaysPerSecond() const { return (closestRays + shadowRays) / seconds; }
    std::string ToString() const;
};

// The sample indices Render takes: options.samples, or all of the sampler's. Throws
// std::invalid_argument for a range outside the sampler's or under sppm.
SampleRange SamplesToRender(const Scene &scene, const RenderOptions &options);

// Renders every pixel of the scene's film; the film accumulates the result. Samples are taken in
// waves over the image, as pbrt-v4 does: sample indices [0, 1), [1, 3), [3, 7), ..., each wave
// twice the last up to 64 samples, so that every pixel soon has samples and a stop between waves
// (time limit) leaves every pixel with the same count. Each pixel takes its samples in index
// order, so the image is the same for any thread count, and stopped after k samples it is the
// image of a k-sample render.
RenderStatistics Render(Scene &scene, const RenderOptions &options);

}  // namespace pbrt
