// Rendering a scene: tiles over all cores (TBB), a progress bar, final statistics (pbrt-v4's
// ImageTileIntegrator::Render, reduced to one pass over the pixels with all their samples).
#pragma once

#include <cstdint>
#include <string>

namespace pbrt {

class Scene;

struct RenderOptions {
    int nThreads = 0;  // 0: all cores
    bool quiet = false;
    // Stop starting new samples after this many seconds (0: no limit). The image then holds the
    // first k samples of every pixel, for the largest k finished in time (at least 1).
    double timeLimitSeconds = 0;
};

struct RenderStatistics {
    double seconds = 0;
    int64_t cameraSamples = 0;
    int64_t closestRays = 0, shadowRays = 0;
    int64_t discardedSamples = 0;  // radiance NaN or infinite: counted, never written
    int samplesPerPixel = 0;       // taken by every pixel (fewer than asked under a time limit)

    double CameraSamplesPerSecond() const { return cameraSamples / seconds; }
    double RaysPerSecond() const { return (closestRays + shadowRays) / seconds; }
    std::string ToString() const;
};

// Renders every pixel of the scene's film; the film accumulates the result. Samples are taken in
// passes over the image (one pass of all samples without a time limit, one sample index per pass
// with one), so that stopping between passes leaves every pixel with the same sample count.
RenderStatistics Render(Scene &scene, const RenderOptions &options);

}  // namespace pbrt
